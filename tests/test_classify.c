/* Height-field classification (core/scene/classify.c): eq. 5 of the hybrid cone tracing paper
 * against the normal rule, on meshes built here with a known answer, and through the loaders.
 * The figures of docs/scenes.md are what this test prints. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/fs.h"
#include "cg/scene.h"
#include "test_support.h"

/* A mesh under construction: float positions, uint32 indices. */
typedef struct mesh_in {
    float *p;
    uint32_t *idx;
    uint32_t nv, ni, cap_v, cap_i;
} mesh_in;

static uint32_t
vertex(mesh_in *m, double x, double y, double z)
{
    if (m->nv == m->cap_v) {
        m->cap_v = m->cap_v ? 2 * m->cap_v : 1024;
        m->p = realloc(m->p, (size_t)m->cap_v * 3 * sizeof(float));
        assert_non_null(m->p);
    }
    m->p[3 * m->nv] = (float)x, m->p[3 * m->nv + 1] = (float)y, m->p[3 * m->nv + 2] = (float)z;
    return m->nv++;
}

static void
triangle(mesh_in *m, uint32_t a, uint32_t b, uint32_t c)
{
    if (m->ni + 3 > m->cap_i) {
        m->cap_i = m->cap_i ? 2 * m->cap_i : 3072;
        m->idx = realloc(m->idx, (size_t)m->cap_i * sizeof(uint32_t));
        assert_non_null(m->idx);
    }
    m->idx[m->ni++] = a, m->idx[m->ni++] = b, m->idx[m->ni++] = c;
}

/* A height field over [x0, x0 + size] x [z0, z0 + size], n x n cells, y = h(x, z) + lift,
 * counter-clockwise seen from above (up = true) or from below. Returns its first vertex. */
static uint32_t
grid(mesh_in *m, int n, double x0, double z0, double size, double lift, bool up)
{
    uint32_t first = m->nv;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = x0 + size * i / n, z = z0 + size * j / n;
            vertex(m, x, lift + 0.04 * size * sin(x / size * 6.0) * cos(z / size * 5.0), z);
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t v00 = first + (uint32_t)(j * (n + 1) + i), v10 = v00 + 1, v01 = v00 + (uint32_t)(n + 1),
                     v11 = v01 + 1;
            if (up) {
                triangle(m, v00, v01, v10);
                triangle(m, v10, v01, v11);
            } else {
                triangle(m, v00, v10, v01);
                triangle(m, v10, v11, v01);
            }
        }
    return first;
}

/* A scene holding mesh `m` once per transform (NULL: one instance at the identity). */
static void
scene_of(mesh_in *m, const float (*worlds)[16], int instances, cg_scene *s)
{
    memset(s, 0, sizeof *s);
    s->meshes = calloc(1, sizeof *s->meshes);
    s->instances = calloc((size_t)(instances ? instances : 1), sizeof *s->instances); /* zero: not moving */
    assert_non_null(s->meshes);
    assert_non_null(s->instances);
    s->mesh_count = 1;
    cg_mesh *mesh = &s->meshes[0];
    snprintf(mesh->name, sizeof mesh->name, "test");
    mesh->positions = m->p, mesh->indices = m->idx;
    mesh->vertex_count = m->nv, mesh->index_count = m->ni;
    mesh->normals = calloc((size_t)m->nv * 3 + 1, sizeof(float)); /* only for export: all +y */
    assert_non_null(mesh->normals);
    for (uint32_t v = 0; v < m->nv; v++) {
        mesh->normals[3 * v + 1] = 1;
        for (int k = 0; k < 3; k++) {
            mesh->bounds_min[k] = v ? fminf(mesh->bounds_min[k], m->p[3 * v + k]) : m->p[k];
            mesh->bounds_max[k] = v ? fmaxf(mesh->bounds_max[k], m->p[3 * v + k]) : m->p[k];
        }
    }
    s->materials = calloc(1, sizeof *s->materials);
    assert_non_null(s->materials);
    s->material_count = 1;
    snprintf(s->materials[0].name, sizeof s->materials[0].name, "default");
    s->materials[0].base_color[0] = s->materials[0].base_color[1] = s->materials[0].base_color[2] = 1;
    s->materials[0].base_color[3] = 1;
    s->materials[0].base_color_texture = s->materials[0].emissive_texture = -1;
    s->materials[0].emissive_strength = 1;
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    s->instance_count = instances ? instances : 1;
    for (int i = 0; i < s->instance_count; i++)
        memcpy(s->instances[i].world, worlds ? worlds[i] : identity, sizeof identity);
    memset(m, 0, sizeof *m);
}

static cg_mesh_class
classify(const cg_scene *s, cg_classify_rule rule, int resolution, cg_classify_points points, int threads)
{
    cg_classify_options o = { .rule = rule, .resolution = resolution, .points = points, .threads = threads };
    cg_mesh_class c;
    cg_error err = { 0 };
    assert_cg_ok(cg_mesh_classify(s, 0, &o, &c, &err), &err);
    return c;
}

static void
check(const char *what, const cg_scene *s, cg_mesh_kind eq5, cg_mesh_kind normals)
{
    cg_mesh_class a = classify(s, CG_CLASSIFY_EQ5, 0, CG_CLASSIFY_VERTICES, 0);
    cg_mesh_class b = classify(s, CG_CLASSIFY_NORMALS, 0, CG_CLASSIFY_VERTICES, 0);
    printf("# %-34s eq. 5 d = %.3e (max %.3e): %s; normals: %s\n", what, a.distance, a.max_distance,
           a.kind == CG_MESH_HEIGHTFIELD ? "heightfield" : "complex",
           b.kind == CG_MESH_HEIGHTFIELD ? "heightfield" : "complex");
    if (a.kind != eq5)
        fail_msg("%s: eq. 5 says %d (d = %g), expected %d", what, a.kind, a.distance, eq5);
    if (b.kind != normals)
        fail_msg("%s: the normal rule says %d, expected %d", what, b.kind, normals);
    assert_true(isnan(b.distance)); /* the normal rule computes no distance */
}

/* The test: a terrain with a vertical cliff face (a 5 m step across its middle, the
 * vertices doubled along it) and one with a vertical skirt along an edge: eq. 5 accepts both,
 * the normal rule rejects both for their vertical triangles. */
static void
cliff_and_skirt(void **state)
{
    (void)state;
    int n = 128;
    double size = 100;
    mesh_in m = { 0 };
    /* Two halves of one terrain, the far one 5 m lower, joined by a vertical wall. */
    uint32_t near = grid(&m, n, 0, 0, size, 5, true);
    uint32_t far = grid(&m, n, 0, size, size, 0, true);
    for (int i = 0; i < n; i++) {
        uint32_t top0 = near + (uint32_t)(n * (n + 1) + i), top1 = top0 + 1;
        uint32_t bot0 = far + (uint32_t)i, bot1 = bot0 + 1;
        triangle(&m, top0, bot0, top1);
        triangle(&m, top1, bot0, bot1);
    }
    cg_scene s;
    scene_of(&m, NULL, 1, &s);
    check("terrain with a 5 m cliff", &s, CG_MESH_HEIGHTFIELD, CG_MESH_COMPLEX);
    cg_scene_free(&s);

    /* A 96 x 96 cell terrain with a skirt 2 m down along its x = 0 edge. */
    n = 96;
    uint32_t top = grid(&m, n, 0, 0, size, 0, true);
    uint32_t skirt = m.nv;
    for (int j = 0; j <= n; j++)
        vertex(&m, 0, m.p[3 * (top + j * (n + 1)) + 1] - 2.0, size * j / n);
    for (int j = 0; j < n; j++) {
        uint32_t t0 = top + (uint32_t)(j * (n + 1)), t1 = t0 + (uint32_t)(n + 1);
        triangle(&m, t0, skirt + j, t1);
        triangle(&m, t1, skirt + j, skirt + j + 1);
    }
    scene_of(&m, NULL, 1, &s);
    check("terrain with a 2 m skirt", &s, CG_MESH_HEIGHTFIELD, CG_MESH_COMPLEX);
    cg_scene_free(&s);
}

/* The test: two up-facing layers 3 m apart in one 30 m mesh (a floor above a floor):
 * eq. 5 rejects it (half its vertices are a storey below the top), the normal rule accepts it. */
static void
two_layers(void **state)
{
    (void)state;
    mesh_in m = { 0 };
    grid(&m, 32, 0, 0, 30, 0, true);
    grid(&m, 32, 0, 0, 30, 3, true);
    cg_scene s;
    scene_of(&m, NULL, 1, &s);
    check("two layers 3 m apart", &s, CG_MESH_COMPLEX, CG_MESH_HEIGHTFIELD);
    cg_scene_free(&s);
}

/* Orientation plays no part in eq. 5: a terrain facing down is a height field; a closed box is not. */
static void
down_facing_and_box(void **state)
{
    (void)state;
    mesh_in m = { 0 };
    grid(&m, 64, 0, 0, 50, 0, false);
    cg_scene s;
    scene_of(&m, NULL, 1, &s);
    check("terrain facing down", &s, CG_MESH_HEIGHTFIELD, CG_MESH_COMPLEX);
    cg_scene_free(&s);

    /* A 10 m cube, each face a 16 x 16 grid (flat, outward facing). */
    for (int face = 0; face < 6; face++) {
        int axis = face / 2;
        double side = (face & 1) ? 10 : 0;
        uint32_t first = m.nv;
        for (int j = 0; j <= 16; j++)
            for (int i = 0; i <= 16; i++) {
                double c[3];
                c[axis] = side, c[(axis + 1) % 3] = 10.0 * i / 16, c[(axis + 2) % 3] = 10.0 * j / 16;
                vertex(&m, c[0], c[1], c[2]);
            }
        for (int j = 0; j < 16; j++)
            for (int i = 0; i < 16; i++) {
                uint32_t v = first + (uint32_t)(j * 17 + i);
                if (face & 1) {
                    triangle(&m, v, v + 1, v + 17);
                    triangle(&m, v + 1, v + 18, v + 17);
                } else {
                    triangle(&m, v, v + 17, v + 1);
                    triangle(&m, v + 1, v + 17, v + 18);
                }
            }
    }
    scene_of(&m, NULL, 1, &s);
    check("closed cube", &s, CG_MESH_COMPLEX, CG_MESH_COMPLEX);
    cg_scene_free(&s);
}

/* Eq. 5's distance between a mesh's vertices and the sampled grid's: on a perfect height field
 * it is not 0 but about 0.38 grid spacings (the mean distance to the nearest node of a square
 * lattice), i.e. about 0.27 / N of the diagonal: too coarse a resolution rejects every terrain.
 * d is the same with the mesh scaled by 1000 (D removes the units), with centroids about as
 * small, with 1 thread or 4, and the worst instance decides. */
static void
resolution_scale_points_instances(void **state)
{
    (void)state;
    mesh_in m = { 0 };
    grid(&m, 300, 0, 0, 100, 0, true);
    cg_scene s;
    scene_of(&m, NULL, 1, &s);
    const int resolutions[] = { 64, 256, 2048 };
    double d[3];
    for (int r = 0; r < 3; r++) {
        d[r] = classify(&s, CG_CLASSIFY_EQ5, resolutions[r], CG_CLASSIFY_VERTICES, 0).distance;
        printf("# resolution %4d: d = %.3e, d x N = %.3f\n", resolutions[r], d[r], d[r] * resolutions[r]);
        /* The lattice term alone, 0.27 / N, within a factor of 2 (the mesh's own vertices are a
         * lattice too, so some fall near the grid's). */
        assert_true(d[r] * resolutions[r] > 0.1 && d[r] * resolutions[r] < 0.6);
    }
    assert_true(d[0] > CG_EQ5_DEFAULT_THRESHOLD);
    assert_true(d[2] < CG_EQ5_DEFAULT_THRESHOLD);
    double one = classify(&s, CG_CLASSIFY_EQ5, 0, CG_CLASSIFY_VERTICES, 1).distance;
    double four = classify(&s, CG_CLASSIFY_EQ5, 0, CG_CLASSIFY_VERTICES, 4).distance;
    assert_float_equal(one, four, 1e-12 * one);
    double centroids = classify(&s, CG_CLASSIFY_EQ5, 0, CG_CLASSIFY_CENTROIDS, 0).distance;
    printf("# centroids: d = %.3e (vertices %.3e)\n", centroids, one);
    assert_true(centroids < CG_EQ5_DEFAULT_THRESHOLD);
    /* Scaled by 1000 and moved 100 km away. */
    for (uint32_t v = 0; v < s.meshes[0].vertex_count * 3; v++)
        s.meshes[0].positions[v] *= 1000;
    float far[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e5f, 2e4f, -1e5f, 1 };
    memcpy(s.instances[0].world, far, sizeof far);
    double scaled = classify(&s, CG_CLASSIFY_EQ5, 0, CG_CLASSIFY_VERTICES, 0).distance;
    printf("# scaled by 1000, 100 km away: d = %.3e\n", scaled);
    assert_float_equal(scaled, one, 1e-3 * one);
    /* A second instance standing on its edge (rotated 90 degrees about x): no longer a height
     * field (seen from above it is a 4 m strip of relief), and the mesh, whose kind all its
     * instances share, is complex. */
    s.instances = realloc(s.instances, 2 * sizeof *s.instances);
    assert_non_null(s.instances);
    s.instance_count = 2;
    s.instances[1] = s.instances[0];
    float standing[16] = { 1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1 };
    memcpy(s.instances[1].world, standing, sizeof standing);
    cg_mesh_class two = classify(&s, CG_CLASSIFY_EQ5, 0, CG_CLASSIFY_VERTICES, 0);
    assert_int_equal(two.instances, 2);
    assert_int_equal(two.kind, CG_MESH_COMPLEX);
    printf("# with a standing instance: d = %.3e\n", two.distance);
    assert_true(two.distance > 10 * CG_EQ5_DEFAULT_THRESHOLD);
    cg_scene_free(&s);
}

/* builtin:openworld: eq. 5 agrees with the kinds the scene sets, except for the roofs, which eq. 5
 * finds to be a height field (a gable roof has nothing below it within its mesh: its vertical
 * gable ends run from the eaves up to the ridge, all on the top surface); the scene keeps them
 * complex, as it built them. */
static void
openworld_kinds(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:openworld?triangles=20000", &s, &err), &err);
    for (int m = 0; m < s.mesh_count; m++) {
        assert_int_equal(s.mesh_class[m].source, CG_KIND_SCENE);
        cg_mesh_class c;
        assert_cg_ok(cg_mesh_classify(&s, m, NULL, &c, &err), &err);
        printf("# openworld '%s': d = %.3e\n", s.meshes[m].name, c.distance);
        cg_mesh_kind expected = strcmp(s.meshes[m].name, "roofs") ? s.meshes[m].kind : CG_MESH_HEIGHTFIELD;
        if (c.kind != expected)
            fail_msg("'%s': eq. 5 gives %d (d = %g), expected %d", s.meshes[m].name, c.kind, c.distance, expected);
    }
    cg_scene_free(&s);
}

/* Through a file: a glTF mesh without extras is classified at loading (the source's keys choose
 * the rule and its parameters), one with "conegraph_kind" keeps its kind; bad keys are refused. */
static void
through_the_loader(void **state)
{
    (void)state;
    /* A 2x2 cell terrain facing down: eq. 5 says heightfield, normals complex. */
    mesh_in m = { 0 };
    grid(&m, 2, 0, 0, 2, 0, false);
    cg_scene hand;
    scene_of(&m, NULL, 1, &hand);
    const char *path = cg_test_tmpdir();
    char file[512];
    snprintf(file, sizeof file, "%s/down.gltf", path);
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_export_gltf(&hand, file, &err), &err); /* writes conegraph_kind: complex */
    cg_scene_free(&hand);

    /* The exported file carries its kind in the extras: kept whatever the rule. */
    cg_scene s;
    assert_cg_ok(cg_scene_load(file, &s, &err), &err);
    assert_int_equal(s.mesh_class[0].source, CG_KIND_EXTRAS);
    assert_int_equal(s.meshes[0].kind, CG_MESH_COMPLEX);
    cg_scene_free(&s);

    /* The same mesh without extras: classified. */
    char *text;
    size_t size;
    assert_cg_ok(cg_read_file(file, &text, &size, &err), &err);
    char *extra = strstr(text, "\"conegraph_kind\"");
    assert_non_null(extra);
    memcpy(extra, "\"conegraph_note\"", strlen("\"conegraph_note\""));
    snprintf(file, sizeof file, "%s/plain.gltf", path);
    FILE *f = fopen(file, "wb");
    assert_non_null(f);
    fwrite(text, 1, size, f);
    fclose(f);
    free(text);
    assert_cg_ok(cg_scene_load(file, &s, &err), &err);
    assert_int_equal(s.mesh_class[0].source, CG_KIND_CLASSIFIED);
    assert_int_equal(s.meshes[0].kind, CG_MESH_HEIGHTFIELD);
    assert_true(s.mesh_class[0].distance < CG_EQ5_DEFAULT_THRESHOLD);
    cg_scene_free(&s);
    char source[600];
    snprintf(source, sizeof source, "%s?classify=normals", file);
    assert_cg_ok(cg_scene_load(source, &s, &err), &err);
    assert_int_equal(s.meshes[0].kind, CG_MESH_COMPLEX);
    assert_int_equal(s.classify.rule, CG_CLASSIFY_NORMALS);
    cg_scene_free(&s);
    /* A threshold below the lattice term of a 2-sample grid rejects it. */
    snprintf(source, sizeof source, "%s?eq5_resolution=2&eq5_threshold=1e-9&eq5_points=centroids", file);
    assert_cg_ok(cg_scene_load(source, &s, &err), &err);
    assert_int_equal(s.meshes[0].kind, CG_MESH_COMPLEX);
    cg_scene_free(&s);
    const char *bad[] = { "?classify=maybe", "?eq5_resolution=1", "?eq5_threshold=-1", "?eq5_points=all",
                          "?eq5_threshold=0.1&eq5_threshold=0.2", "?colour=red" };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        snprintf(source, sizeof source, "%s%s", file, bad[i]);
        assert_cg_status(cg_scene_load(source, &s, &err), &err, CG_ERR_SCENE_PARAM);
    }
    /* Built-in scenes take the keys too (their kinds are their own). */
    assert_cg_ok(cg_scene_load("builtin:cornell?eq5_threshold=0.01", &s, &err), &err);
    assert_float_equal(s.classify.threshold, 0.01, 0);
    cg_scene_free(&s);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(cliff_and_skirt),
             cmocka_unit_test(two_layers),
             cmocka_unit_test(down_facing_and_box),
             cmocka_unit_test(resolution_scale_points_instances),
             cmocka_unit_test(openworld_kinds),
             cmocka_unit_test(through_the_loader))
