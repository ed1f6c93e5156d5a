/* Built-in scenes: sizes follow the parameter, seeds are deterministic, openworld has what the
 * hybrid method needs (a height field, complex meshes, space under a structure), cornell and
 * furnace have their lights and closed, inward-facing boxes; bad names and parameters fail
 * with their named errors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <dirent.h>
#include <unistd.h>

#include "cg/scene.h"
#include "test_support.h"

static double
now_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static const cg_mesh *
find_mesh(const cg_scene *s, const char *name)
{
    for (int i = 0; i < s->mesh_count; i++)
        if (!strcmp(s->meshes[i].name, name))
            return &s->meshes[i];
    return NULL;
}

static void
world_point(const cg_scene *s, int instance, uint32_t vertex, double out[3])
{
    const cg_instance *in = &s->instances[instance];
    const float *p = s->meshes[in->mesh].positions + 3 * (size_t)vertex;
    for (int r = 0; r < 3; r++)
        out[r] = in->world[r] * p[0] + in->world[4 + r] * p[1] + in->world[8 + r] * p[2] + in->world[12 + r];
}

static void
triangle_normal(const double a[3], const double b[3], const double c[3], double n[3])
{
    double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] /= l;
}

static void
check_count(const char *source, long target)
{
    cg_scene s;
    cg_error err = { 0 };
    double t0 = now_seconds();
    assert_cg_ok(cg_scene_load(source, &s, &err), &err);
    double t = now_seconds() - t0;
    size_t n = cg_scene_triangle_count(&s);
    printf("# %s: %zu triangles in %.3f s\n", source, n, t);
    assert_true(fabs((double)n - (double)target) <= 0.01 * (double)target);
    cg_scene_free(&s);
}

static void
openworld_triangles_follow_parameter(void **state)
{
    (void)state;
    check_count("builtin:openworld?triangles=10000", 10000);
    check_count("builtin:openworld", 200000);
    check_count("builtin:openworld?triangles=200000&seed=9", 200000);
    check_count("builtin:openworld?triangles=2000000", 2000000);
}

static bool
same_scene(const cg_scene *a, const cg_scene *b)
{
    if (a->mesh_count != b->mesh_count || a->instance_count != b->instance_count ||
        a->material_count != b->material_count || a->light_count != b->light_count ||
        a->camera_count != b->camera_count)
        return false;
    for (int i = 0; i < a->mesh_count; i++) {
        const cg_mesh *x = &a->meshes[i], *y = &b->meshes[i];
        if (x->vertex_count != y->vertex_count || x->index_count != y->index_count ||
            memcmp(x->positions, y->positions, 12 * (size_t)x->vertex_count) ||
            memcmp(x->normals, y->normals, 12 * (size_t)x->vertex_count) ||
            memcmp(x->indices, y->indices, 4 * (size_t)x->index_count) || x->kind != y->kind ||
            x->material != y->material)
            return false;
    }
    return !memcmp(a->instances, b->instances, sizeof *a->instances * (size_t)a->instance_count) &&
           !memcmp(a->materials, b->materials, sizeof *a->materials * (size_t)a->material_count) &&
           !memcmp(a->lights, b->lights, sizeof *a->lights * (size_t)a->light_count) &&
           !memcmp(a->cameras, b->cameras, sizeof *a->cameras * (size_t)a->camera_count);
}

static void
same_seed_same_scene(void **state)
{
    (void)state;
    cg_scene a, b, c;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:openworld?triangles=30000&seed=7", &a, &err), &err);
    assert_cg_ok(cg_scene_load("builtin:openworld?seed=7&triangles=30000", &b, &err), &err);
    assert_cg_ok(cg_scene_load("builtin:openworld?triangles=30000&seed=8", &c, &err), &err);
    assert_true(same_scene(&a, &b));
    assert_false(same_scene(&a, &c));
    cg_scene_free(&a);
    cg_scene_free(&b);
    cg_scene_free(&c);
}

/* Height of the terrain's triangles under (x, z), by brute force; NAN when none covers it. */
static double
terrain_height_at(const cg_scene *s, int terrain_instance, double x, double z)
{
    const cg_mesh *m = &s->meshes[s->instances[terrain_instance].mesh];
    for (uint32_t t = 0; t < m->index_count; t += 3) {
        double p[3][3];
        for (int v = 0; v < 3; v++)
            world_point(s, terrain_instance, m->indices[t + v], p[v]);
        double d = (p[1][2] - p[2][2]) * (p[0][0] - p[2][0]) + (p[2][0] - p[1][0]) * (p[0][2] - p[2][2]);
        double l0 = ((p[1][2] - p[2][2]) * (x - p[2][0]) + (p[2][0] - p[1][0]) * (z - p[2][2])) / d;
        double l1 = ((p[2][2] - p[0][2]) * (x - p[2][0]) + (p[0][0] - p[2][0]) * (z - p[2][2])) / d;
        double l2 = 1 - l0 - l1;
        if (l0 >= -1e-9 && l1 >= -1e-9 && l2 >= -1e-9)
            return l0 * p[0][1] + l1 * p[1][1] + l2 * p[2][1];
    }
    return NAN;
}

static void
openworld_has_heightfield_complex_and_space_under(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:openworld?triangles=10000&seed=3", &s, &err), &err);
    int terrain = -1, complex_meshes = 0;
    for (int i = 0; i < s.instance_count; i++) {
        const cg_mesh *m = &s.meshes[s.instances[i].mesh];
        if (m->kind == CG_MESH_HEIGHTFIELD) {
            assert_int_equal(terrain, -1);
            terrain = i;
            /* The height-field rule: every triangle faces up. */
            for (uint32_t t = 0; t < m->index_count; t += 3) {
                double p[3][3], n[3];
                for (int v = 0; v < 3; v++)
                    world_point(&s, i, m->indices[t + v], p[v]);
                triangle_normal(p[0], p[1], p[2], n);
                assert_true(n[1] > 1e-3);
            }
            assert_true(m->index_count / 3 > cg_scene_triangle_count(&s) * 9 / 10);
        } else {
            complex_meshes++;
        }
    }
    assert_true(terrain >= 0);
    assert_true(complex_meshes >= 3);
    /* Something stands over open air: a downward-facing triangle of a complex mesh at
     * least 3 m above the terrain under it (the bridge deck, the arch's intrados). */
    int over_air = 0;
    for (int i = 0; i < s.instance_count; i++) {
        const cg_mesh *m = &s.meshes[s.instances[i].mesh];
        if (m->kind != CG_MESH_COMPLEX)
            continue;
        for (uint32_t t = 0; t < m->index_count; t += 3) {
            double p[3][3], n[3];
            for (int v = 0; v < 3; v++)
                world_point(&s, i, m->indices[t + v], p[v]);
            triangle_normal(p[0], p[1], p[2], n);
            if (n[1] > -0.5)
                continue;
            double cx = (p[0][0] + p[1][0] + p[2][0]) / 3, cy = (p[0][1] + p[1][1] + p[2][1]) / 3;
            double cz = (p[0][2] + p[1][2] + p[2][2]) / 3;
            double h = terrain_height_at(&s, terrain, cx, cz);
            if (cy - h > 3)
                over_air++;
        }
    }
    printf("# %d downward-facing triangles stand more than 3 m above the terrain\n", over_air);
    assert_true(over_air >= 2);
    /* Buildings, in several colours: albedos that differ per channel bleed colour. */
    int coloured = 0;
    for (int i = 0; i < s.material_count; i++) {
        const float *c = s.materials[i].base_color;
        if (fabsf(c[0] - c[1]) > 0.3f || fabsf(c[1] - c[2]) > 0.3f)
            coloured++;
    }
    assert_true(coloured >= 3);
    /* A sun of a few W/m^2 from above, and a camera; extent a few hundred metres. */
    assert_int_equal(s.light_count, 1);
    assert_int_equal(s.lights[0].type, CG_LIGHT_DIRECTIONAL);
    assert_true(s.lights[0].intensity >= 1 && s.lights[0].intensity <= 10);
    assert_true(s.lights[0].direction[1] < -0.3f);
    assert_int_equal(s.camera_count, 1);
    assert_int_equal(s.cameras[0].type, CG_CAMERA_PERSPECTIVE);
    assert_true(s.bounds_max[0] - s.bounds_min[0] >= 200 && s.bounds_max[0] - s.bounds_min[0] <= 1000);
    cg_scene_free(&s);
}

static void
cornell_box(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:cornell", &s, &err), &err);
    assert_int_equal(s.light_count, 1);
    const cg_light *l = &s.lights[0];
    assert_int_equal(l->type, CG_LIGHT_SPOT);
    assert_true(l->direction[1] < -0.99f);
    assert_true(l->position[1] > 0.9f && l->position[1] < 1.0f);
    assert_true(l->outer_cone_angle < 1.5f); /* one perspective shadow map covers it */
    assert_int_equal(s.camera_count, 1);
    const cg_mesh *left = find_mesh(&s, "left_wall"), *right = find_mesh(&s, "right_wall");
    assert_non_null(left);
    assert_non_null(right);
    const float *red = s.materials[left->material].base_color;
    const float *green = s.materials[right->material].base_color;
    assert_true(red[0] > 2 * red[1] && green[1] > 2 * green[0]);
    /* Walls face into the box: the left wall's normal is +x, the right's -x. */
    assert_true(left->normals[0] > 0.99f && right->normals[0] < -0.99f);
    assert_true(fabsf(s.bounds_max[1] - s.bounds_min[1] - 1) < 1e-5f);
    assert_int_equal(cg_scene_triangle_count(&s), 10 + 2 * 12);
    cg_scene_free(&s);
}

/* builtin:cornell?scale=S&light_scale=K is the default box with every length times S and the
 * spot's intensity times K S^2 (E = I / d^2 unchanged at every scale, times K). */
static void
cornell_scales(void **state)
{
    (void)state;
    cg_scene unit, s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:cornell", &unit, &err), &err);
    static const struct { const char *source; double scale, light; } cases[] = {
        { "builtin:cornell?scale=1e-6", 1e-6, 1 },
        { "builtin:cornell?scale=1e6&light_scale=1e5", 1e6, 1e5 },
        { "builtin:cornell?light_scale=1e-6", 1, 1e-6 },
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double k = cases[c].scale;
        assert_cg_ok(cg_scene_load(cases[c].source, &s, &err), &err);
        for (int i = 0; i < 3; i++) {
            assert_float_equal(s.bounds_min[i], unit.bounds_min[i] * k, 1e-6 * k);
            assert_float_equal(s.bounds_max[i], unit.bounds_max[i] * k, 1e-6 * k);
            assert_float_equal(s.lights[0].position[i], unit.lights[0].position[i] * k, 1e-6 * k);
            assert_float_equal(s.cameras[0].world[12 + i], unit.cameras[0].world[12 + i] * k, 1e-6 * k);
        }
        double intensity = unit.lights[0].intensity * cases[c].light * k * k;
        assert_float_equal(s.lights[0].intensity, intensity, 1e-6 * intensity);
        assert_float_equal(s.cameras[0].znear, unit.cameras[0].znear * k, 1e-6 * k);
        assert_float_equal(s.cameras[0].zfar, unit.cameras[0].zfar * k, 1e-6 * k);
        assert_int_equal(cg_scene_triangle_count(&s), cg_scene_triangle_count(&unit));
        cg_scene_free(&s);
    }
    cg_scene_free(&unit);
}

static void
check_furnace(const char *source, double scale, float albedo, float radiance, bool heightfield)
{
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(source, &s, &err), &err);
    for (int k = 0; k < 3; k++) {
        assert_true(fabs(s.bounds_min[k] + scale / 2) <= 1e-6 * scale);
        assert_true(fabs(s.bounds_max[k] - scale / 2) <= 1e-6 * scale);
    }
    assert_int_equal(s.light_count, 0);
    assert_int_equal(s.camera_count, 1);
    /* The camera is inside, its near plane well inside the walls. */
    for (int k = 0; k < 3; k++)
        assert_true(fabsf(s.cameras[0].world[12 + k]) < scale / 4);
    assert_true(s.cameras[0].znear < scale / 4);
    size_t triangles = 0, heightfield_triangles = 0;
    for (int i = 0; i < s.instance_count; i++) {
        const cg_mesh *m = &s.meshes[s.instances[i].mesh];
        if (m->kind == CG_MESH_HEIGHTFIELD) {
            /* The floor, y = -S/2, facing up. */
            heightfield_triangles += m->index_count / 3;
            assert_true(fabs(m->bounds_min[1] + scale / 2) <= 1e-6 * scale);
            assert_true(fabs(m->bounds_max[1] + scale / 2) <= 1e-6 * scale);
        }
        const cg_material *mat = &s.materials[m->material];
        for (int c = 0; c < 3; c++) {
            assert_float_equal(mat->base_color[c], albedo, 0);
            assert_float_equal(mat->emissive[c] * mat->emissive_strength, radiance, radiance * 1e-6);
        }
        assert_int_equal(mat->emissive_texture, -1);
        assert_int_equal(mat->base_color_texture, -1);
        /* Every face points to the centre. */
        for (uint32_t t = 0; t < m->index_count; t += 3) {
            double p[3][3], n[3];
            for (int v = 0; v < 3; v++)
                world_point(&s, i, m->indices[t + v], p[v]);
            triangle_normal(p[0], p[1], p[2], n);
            double c[3] = { (p[0][0] + p[1][0] + p[2][0]) / 3, (p[0][1] + p[1][1] + p[2][1]) / 3,
                            (p[0][2] + p[1][2] + p[2][2]) / 3 };
            assert_true(n[0] * c[0] + n[1] * c[1] + n[2] * c[2] < -0.4 * scale);
            const float *sn = m->normals + 3 * (size_t)m->indices[t];
            assert_true(sn[0] * n[0] + sn[1] * n[1] + sn[2] * n[2] > 0.999);
        }
        triangles += m->index_count / 3;
    }
    /* Closed: the six faces of the cube, two triangles each, cover its whole surface. */
    assert_int_equal(triangles, 12);
    assert_int_equal(heightfield_triangles, heightfield ? 2 : 0);
    cg_scene_free(&s);
}

static void
furnace_scales(void **state)
{
    (void)state;
    check_furnace("builtin:furnace", 1, 0.5f, 1, false);
    check_furnace("builtin:furnace?scale=1e-3&albedo=0.8&radiance=2", 1e-3, 0.8f, 2, false);
    check_furnace("builtin:furnace?scale=1e4&albedo=1&radiance=0.25", 1e4, 1, 0.25f, false);
    check_furnace("builtin:furnace?heightfield=0", 1, 0.5f, 1, false);
    check_furnace("builtin:furnace?heightfield=1&scale=1e4&albedo=0.5&radiance=2", 1e4, 0.5f, 2, true);
}

/* The cosine between the sun's travel direction and the normal of the first triangle of mesh `m`
 * (world space): negative where the sun lights the side the normal points to. */
static double
sun_against_normal(const cg_scene *s, int instance)
{
    const cg_mesh *m = &s->meshes[s->instances[instance].mesh];
    double p[3][3], n[3];
    for (int v = 0; v < 3; v++)
        world_point(s, instance, m->indices[v], p[v]);
    triangle_normal(p[0], p[1], p[2], n);
    const float *d = s->lights[0].direction;
    return d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
}

/* The unit scenes of the GI tests: their sun lights what their truths assume, and turning a scene
 * (yaw, tilt) turns everything together, so that the physics stays the same. */
static void
unit_scenes(void **state)
{
    (void)state;
    static const char *const names[] = { "plates", "wallfloor", "thinwall", "boxplane", "terrain" };
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        char plain[64], turned[96];
        snprintf(plain, sizeof plain, "builtin:%s", names[i]);
        snprintf(turned, sizeof turned, "builtin:%s?yaw=30&tilt=20", names[i]);
        cg_scene a, b;
        cg_error err = { 0 };
        assert_cg_ok(cg_scene_load(plain, &a, &err), &err);
        assert_cg_ok(cg_scene_load(turned, &b, &err), &err);
        assert_int_equal(a.light_count, 1);
        assert_int_equal(a.lights[0].type, CG_LIGHT_DIRECTIONAL);
        assert_int_equal(a.camera_count, 1);
        assert_int_equal(cg_scene_triangle_count(&a), cg_scene_triangle_count(&b));
        assert_int_equal(a.instance_count, b.instance_count);
        for (int k = 0; k < a.instance_count; k++)
            assert_float_equal(sun_against_normal(&a, k), sun_against_normal(&b, k), 1e-5);
        /* The turned scene is not axis-aligned any more: its bounds grew. */
        double va = 1, vb = 1;
        for (int k = 0; k < 3; k++) {
            va *= a.bounds_max[k] - a.bounds_min[k] + 1e-3;
            vb *= b.bounds_max[k] - b.bounds_min[k] + 1e-3;
        }
        assert_true(vb > va);
        cg_scene_free(&a);
        cg_scene_free(&b);
    }
    cg_scene s;
    cg_error err = { 0 };
    /* plates: the source (the second half of the mesh, normal -y) is lit from below, the
     * receiver's top (normal +y) is not. */
    assert_cg_ok(cg_scene_load("builtin:plates?h=0.5", &s, &err), &err);
    const cg_mesh *plates = &s.meshes[s.instances[0].mesh];
    assert_true(plates->normals[1] > 0.99f && plates->normals[3 * (plates->vertex_count - 1) + 1] < -0.99f);
    assert_true(s.lights[0].direction[1] > 0.3f);
    cg_scene_free(&s);
    /* wallfloor with an emitting wall and no sun: lit by the wall alone. */
    assert_cg_ok(cg_scene_load("builtin:wallfloor?E=0&emit=2", &s, &err), &err);
    assert_int_equal(s.light_count, 0);
    const cg_mesh *wall = find_mesh(&s, "wall"), *floor_ = find_mesh(&s, "floor");
    assert_non_null(wall);
    assert_non_null(floor_);
    assert_float_equal(s.materials[wall->material].emissive_strength, 2.0, 1e-6);
    assert_float_equal(s.materials[floor_->material].emissive_strength *
                       s.materials[floor_->material].emissive[0], 0.0, 0.0);
    cg_scene_free(&s);
    /* terrain: A = 0 is flat. */
    assert_cg_ok(cg_scene_load("builtin:terrain?A=0&n=8", &s, &err), &err);
    assert_float_equal(s.bounds_max[1] - s.bounds_min[1], 0.0, 0.0);
    assert_int_equal(cg_scene_triangle_count(&s), 2 * 8 * 8);
    cg_scene_free(&s);
}

/* Height range and the buildings' extent along x and their triangles of an openworld. */
typedef struct world_shape {
    float lo[3], hi[3];
    double town_x0, town_x1;
    size_t building_triangles;
} world_shape;

static world_shape
load_world(const char *source)
{
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(source, &s, &err), &err);
    world_shape w = { .town_x0 = INFINITY, .town_x1 = -INFINITY };
    memcpy(w.lo, s.bounds_min, sizeof w.lo);
    memcpy(w.hi, s.bounds_max, sizeof w.hi);
    for (int m = 0; m < s.mesh_count; m++) {
        if (strncmp(s.meshes[m].name, "buildings_", 10))
            continue;
        w.building_triangles += s.meshes[m].index_count / 3;
        for (uint32_t v = 0; v < s.meshes[m].vertex_count; v++) {
            double x = s.meshes[m].positions[3 * v];
            w.town_x0 = fmin(w.town_x0, x);
            w.town_x1 = fmax(w.town_x1, x);
        }
    }
    printf("# %s: bounds [%g %g %g] .. [%g %g %g], buildings x %g .. %g, %zu wall triangles\n", source,
           w.lo[0], w.lo[1], w.lo[2], w.hi[0], w.hi[1], w.hi[2], w.town_x0, w.town_x1, w.building_triangles);
    cg_scene_free(&s);
    return w;
}

/* size scales the world: the terrain's extent exactly, its height range about as sqrt(size / 400),
 * the town spread over the map with more buildings, not bigger ones; the default is today's world
 * (its numbers as before the parameter existed) and size=400 is the default. */
static void
openworld_size_scales_world(void **state)
{
    (void)state;
    world_shape d = load_world("builtin:openworld");
    const float lo[3] = { -200, -25.8873f, -200 }, hi[3] = { 200, 29.8561f, 200 };
    for (int a = 0; a < 3; a++) {
        assert_float_equal(d.lo[a], lo[a], 1e-3);
        assert_float_equal(d.hi[a], hi[a], 1e-3);
    }
    assert_int_equal(d.building_triangles, 800);
    world_shape same = load_world("builtin:openworld?size=400");
    assert_memory_equal(&same, &d, sizeof d);
    const double sizes[] = { 100, 1000, 4000 };
    for (int i = 0; i < 3; i++) {
        char source[64];
        snprintf(source, sizeof source, "builtin:openworld?size=%g", sizes[i]);
        world_shape w = load_world(source);
        double k = sizes[i] / 400;
        assert_float_equal(w.lo[0], -sizes[i] / 2, 1e-3);
        assert_float_equal(w.hi[0], sizes[i] / 2, 1e-3);
        assert_float_equal(w.lo[2], -sizes[i] / 2, 1e-3);
        assert_float_equal(w.hi[2], sizes[i] / 2, 1e-3);
        double relief = (w.hi[1] - w.lo[1]) / (d.hi[1] - d.lo[1]) / sqrt(k);
        assert_true(relief > 0.5 && relief < 1.5);
        /* A larger town, not larger buildings: k^2 times the buildings within half, over 80% of the
         * scaled width the default's cover; a smaller world has fewer. */
        if (k > 1) {
            assert_true(w.town_x1 - w.town_x0 > 0.8 * k * (d.town_x1 - d.town_x0));
            assert_true(w.building_triangles > 0.5 * k * k * (double)d.building_triangles);
        } else {
            assert_true(w.building_triangles < d.building_triangles);
        }
    }
    check_count("builtin:openworld?size=4000", 200000);
    check_count("builtin:openworld?size=16000&triangles=2000000", 2000000);
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_status(cg_scene_load("builtin:openworld?size=99", &s, &err), &err, CG_ERR_SCENE_PARAM);
    assert_non_null(strstr(err.message, "size=99"));
}

static void
bad_names_and_parameters(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_status(cg_scene_load("builtin:nowhere", &s, &err), &err, CG_ERR_SCENE_UNKNOWN);
    for (const char *const *n = cg_scene_builtin_names(); *n; n++) {
        assert_non_null(strstr(err.message, *n));
        assert_non_null(cg_scene_builtin_doc(*n));
    }
    assert_null(cg_scene_builtin_doc("nowhere"));
    const char *bad[] = {
        "builtin:openworld?triangles=0",     "builtin:openworld?triangles=abc",
        "builtin:openworld?triangles=1e5",   "builtin:openworld?seed=-1",
        "builtin:openworld?colour=red",      "builtin:openworld?triangles",
        "builtin:openworld?seed=1&seed=2",   "builtin:openworld?triangles=99999999999",
        "builtin:openworld?&",               "builtin:cornell?size=2",
        "builtin:cornell?scale=0",           "builtin:cornell?light_scale=-1",
        "builtin:furnace?albedo=1.5",        "builtin:furnace?scale=0",
        "builtin:furnace?radiance=nan",      "builtin:furnace?scale=-1",
        "builtin:furnace?heightfield=2",     "builtin:furnace?heightfield=0.5",
        "builtin:plates?h=0",                "builtin:wallfloor?gamma=90",
        "builtin:thinwall?back=2",           "builtin:thinwall?view=2",
        "builtin:boxplane?L=1",              "builtin:terrain?n=1",
        "builtin:terrain?tilt=91",           "builtin:plates?albedo=1.1",
        "builtin:openworld?size=0",          "builtin:openworld?size=64001",
        "builtin:openworld?size=-400",       "builtin:openworld?size=nan",
        "builtin:openworld?size=1km",
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        cg_error_clear(&err);
        if (cg_scene_load(bad[i], &s, &err))
            fail_msg("%s loaded", bad[i]);
        if (err.status != CG_ERR_SCENE_PARAM)
            fail_msg("%s: %s (%s), expected CG_ERR_SCENE_PARAM", bad[i], cg_status_name(err.status),
                     err.message);
        assert_int_equal(s.mesh_count, 0);
        assert_null(s.meshes);
    }
}

static void
assert_close(double a, double b, double tol, const char *what, const char *source)
{
    if (!(fabs(a - b) <= tol))
        fail_msg("%s: %s: %.9g after the round trip, %.9g before", source, what, b, a);
}

/* Export to `file` in the test directory, load it back, compare what renderers depend on. */
static void
check_round_trip(const char *source, const char *file)
{
    cg_scene a, b;
    cg_error err = { 0 };
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", cg_test_tmpdir(), file);
    assert_cg_ok(cg_scene_load(source, &a, &err), &err);
    assert_cg_ok(cg_scene_export_gltf(&a, path, &err), &err);
    assert_cg_ok(cg_scene_load(path, &b, &err), &err);
    double scale = a.bounds_max[0] - a.bounds_min[0];
    assert_int_equal(cg_scene_triangle_count(&a), cg_scene_triangle_count(&b));
    assert_int_equal(a.mesh_count, b.mesh_count);
    assert_int_equal(a.instance_count, b.instance_count);
    for (int i = 0; i < a.mesh_count; i++) {
        assert_string_equal(a.meshes[i].name, b.meshes[i].name);
        assert_int_equal(a.meshes[i].kind, b.meshes[i].kind);
        assert_int_equal(a.meshes[i].index_count, b.meshes[i].index_count);
        assert_int_equal(a.meshes[i].material, b.meshes[i].material);
        assert_memory_equal(a.meshes[i].positions, b.meshes[i].positions, 12 * (size_t)a.meshes[i].vertex_count);
    }
    assert_int_equal(a.material_count, b.material_count);
    for (int i = 0; i < a.material_count; i++)
        for (int k = 0; k < 3; k++) {
            const cg_material *x = &a.materials[i], *y = &b.materials[i];
            assert_close(x->base_color[k], y->base_color[k], 1e-7, "base colour", source);
            assert_close(x->emissive[k] * x->emissive_strength, y->emissive[k] * y->emissive_strength,
                         1e-6 * fmax(1, x->emissive_strength), "emitted radiance", source);
        }
    assert_int_equal(a.light_count, b.light_count);
    for (int i = 0; i < a.light_count; i++) {
        const cg_light *x = &a.lights[i], *y = &b.lights[i];
        assert_string_equal(x->name, y->name);
        assert_int_equal(x->type, y->type);
        assert_close(x->intensity, y->intensity, 0, "intensity", source);
        assert_close(x->outer_cone_angle, y->outer_cone_angle, 0, "outer cone", source);
        assert_close(x->inner_cone_angle, y->inner_cone_angle, 0, "inner cone", source);
        for (int k = 0; k < 3; k++) {
            assert_close(x->color[k], y->color[k], 0, "colour", source);
            assert_close(x->position[k], y->position[k], 1e-6 * scale, "position", source);
            if (x->type != CG_LIGHT_POINT)
                assert_close(x->direction[k], y->direction[k], 1e-6, "direction", source);
        }
    }
    assert_int_equal(a.camera_count, b.camera_count);
    for (int i = 0; i < a.camera_count; i++) {
        const cg_camera *x = &a.cameras[i], *y = &b.cameras[i];
        assert_string_equal(x->name, y->name);
        assert_int_equal(x->type, y->type);
        assert_close(x->yfov, y->yfov, 0, "yfov", source);
        assert_close(x->aspect, y->aspect, 0, "aspect", source);
        assert_close(x->znear, y->znear, 0, "znear", source);
        assert_close(x->zfar, y->zfar, 0, "zfar", source);
        for (int k = 0; k < 16; k++) /* exact, but -0 may come back as 0 */
            assert_close(x->world[k], y->world[k], 0, "camera matrix", source);
    }
    for (int k = 0; k < 3; k++) {
        assert_close(a.bounds_min[k], b.bounds_min[k], 0, "bounds", source);
        assert_close(a.bounds_max[k], b.bounds_max[k], 0, "bounds", source);
    }
    cg_scene_free(&a);
    cg_scene_free(&b);
}

static void
export_then_load_back(void **state)
{
    (void)state;
    check_round_trip("builtin:openworld?triangles=10000&seed=4", "openworld.gltf");
    check_round_trip("builtin:openworld?triangles=10000&seed=4", "openworld.glb");
    check_round_trip("builtin:cornell", "cornell.gltf");
    check_round_trip("builtin:cornell", "cornell.glb");
    check_round_trip("builtin:furnace?scale=1e4&radiance=5&albedo=0.9", "furnace.gltf");
}

static bool
tmpdir_has_temp_files(void)
{
    DIR *d = opendir(cg_test_tmpdir());
    assert_non_null(d);
    bool found = false;
    for (struct dirent *e; (e = readdir(d));)
        found = found || strstr(e->d_name, ".tmp-") != NULL;
    closedir(d);
    return found;
}

static void
export_failures_leave_nothing(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load("builtin:cornell", &s, &err), &err);
    char path[4200];
    snprintf(path, sizeof path, "%s/no/such/dir/out.gltf", cg_test_tmpdir());
    assert_cg_status(cg_scene_export_gltf(&s, path, &err), &err, CG_ERR_IO);
    assert_non_null(strstr(err.message, "out.gltf"));
    snprintf(path, sizeof path, "%s/out.obj", cg_test_tmpdir());
    assert_cg_status(cg_scene_export_gltf(&s, path, &err), &err, CG_ERR_USAGE);
    assert_int_not_equal(access(path, F_OK), 0);
    assert_false(tmpdir_has_temp_files());
    cg_scene_free(&s);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(openworld_triangles_follow_parameter),
             cmocka_unit_test(same_seed_same_scene),
             cmocka_unit_test(openworld_has_heightfield_complex_and_space_under),
             cmocka_unit_test(openworld_size_scales_world),
             cmocka_unit_test(cornell_box),
             cmocka_unit_test(cornell_scales),
             cmocka_unit_test(furnace_scales),
             cmocka_unit_test(unit_scenes),
             cmocka_unit_test(bad_names_and_parameters),
             cmocka_unit_test(export_then_load_back),
             cmocka_unit_test(export_failures_leave_nothing))
