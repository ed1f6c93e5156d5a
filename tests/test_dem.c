/* The DEM loader (core/scene/dem.c): "dem:IMAGE?key=value&..." from a 16-bit PNG and a float
 * TIFF of the same heights (tests/data/dem, written by tests/tools/make_dem_scene.py), with
 * the glTF village placed on it, and its export to glTF read back; the G-buffer of the terrain
 * shades its upper side. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/image.h"
#include "cg/scene.h"
#include "test_support.h"

static const char *
data(const char *name)
{
    char relative[1024];
    snprintf(relative, sizeof relative, "dem/%s", name);
    return cg_test_data_path(relative);
}

static void
load(const char *source, cg_scene *s)
{
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(source, s, &err), &err);
}

static const cg_mesh *
find_mesh(const cg_scene *s, const char *name, int *index)
{
    for (int m = 0; m < s->mesh_count; m++)
        if (!strcmp(s->meshes[m].name, name)) {
            if (index)
                *index = m;
            return &s->meshes[m];
        }
    fail_msg("no mesh '%s'", name);
    return NULL;
}

/* The grid: 65 x 65 samples of the PNG (0..65535) at 15.625 m spacing make a 1 km square
 * terrain centred on the origin, y = sample x 0.002 + 10; the float TIFF of the same heights in
 * metres gives the same mesh; stride 2 keeps every other sample. */
static void
grid_from_png_and_tiff(void **state)
{
    (void)state;
    char source[1200];
    cg_scene png, tif;
    snprintf(source, sizeof source, "dem:%s?spacing=15.625&scale=0.002&offset=10", data("valley.png"));
    load(source, &png);
    snprintf(source, sizeof source, "dem:%s?spacing=15.625&offset=10", data("valley.tif"));
    load(source, &tif);
    const cg_mesh *a = find_mesh(&png, "terrain", NULL), *b = find_mesh(&tif, "terrain", NULL);
    assert_int_equal(a->vertex_count, 65 * 65);
    assert_int_equal(a->index_count, 64 * 64 * 6);
    assert_int_equal(b->vertex_count, a->vertex_count);
    assert_int_equal(a->kind, CG_MESH_HEIGHTFIELD);
    assert_int_equal(png.mesh_class[0].source, CG_KIND_SCENE);
    double worst = 0, lo = INFINITY, hi = -INFINITY;
    for (uint32_t v = 0; v < a->vertex_count; v++) {
        for (int k = 0; k < 3; k++)
            worst = fmax(worst, fabs(a->positions[3 * v + k] - b->positions[3 * v + k]));
        lo = fmin(lo, a->positions[3 * v + 1]), hi = fmax(hi, a->positions[3 * v + 1]);
        /* An integer sample times 0.002: a multiple of 0.002 above the offset. */
        double units = (a->positions[3 * v + 1] - 10.0) / 0.002;
        assert_float_equal(units, round(units), 2e-2);
    }
    printf("# PNG against TIFF: worst coordinate difference %.2e m; heights %.2f .. %.2f m\n", worst, lo, hi);
    assert_true(worst < 1e-4);
    assert_float_equal(a->positions[0], -500, 1e-4);
    assert_float_equal(a->positions[2], -500, 1e-4);
    assert_float_equal(a->positions[3 * (65 * 65 - 1)], 500, 1e-4);
    assert_true(hi - lo > 20);
    /* A sun and an overview camera come with it. */
    assert_int_equal(png.light_count, 1);
    assert_int_equal(png.lights[0].type, CG_LIGHT_DIRECTIONAL);
    assert_true(png.lights[0].direction[1] < 0);
    assert_int_equal(png.camera_count, 1);
    cg_scene_free(&tif);

    cg_scene half;
    snprintf(source, sizeof source, "dem:%s?spacing=15.625&scale=0.002&offset=10&stride=2", data("valley.png"));
    load(source, &half);
    const cg_mesh *c = find_mesh(&half, "terrain", NULL);
    assert_int_equal(c->vertex_count, 33 * 33);
    /* Vertex (i, j) of the strided grid is vertex (2i, 2j) of the full one. */
    for (int j = 0; j < 33; j += 8)
        for (int i = 0; i < 33; i += 8)
            for (int k = 0; k < 3; k++)
                assert_float_equal(c->positions[3 * (j * 33 + i) + k], a->positions[3 * (2 * j * 65 + 2 * i) + k], 1e-4);
    cg_scene_free(&half);
    cg_scene_free(&png);
}

/* The village on the terrain: each house (an instance, placed with place=instances) stands with
 * the bottom of its box on the lowest ground under it; the houses' kinds come from eq. 5
 * (complex: walls under a roof). The scene exported as glTF reads back with the same meshes,
 * kinds and triangles. */
static void
village_placed_and_exported(void **state)
{
    (void)state;
    char source[1200];
    snprintf(source, sizeof source, "dem:%s?spacing=15.625&scale=0.002&meshes=%s&place=instances", data("valley.png"),
             data("village.gltf"));
    cg_scene s;
    load(source, &s);
    int terrain = -1;
    find_mesh(&s, "terrain", &terrain);
    int houses = 0;
    for (int i = 0; i < s.instance_count; i++) {
        const cg_instance *inst = &s.instances[i];
        if (inst->mesh == terrain)
            continue;
        houses++;
        const cg_mesh *m = &s.meshes[inst->mesh];
        assert_int_equal(m->kind, CG_MESH_COMPLEX);
        assert_int_equal(s.mesh_class[inst->mesh].source, CG_KIND_CLASSIFIED);
        /* The house's lowest vertex in the world against the lowest terrain vertex under its box. */
        double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
        for (uint32_t v = 0; v < m->vertex_count; v++)
            for (int r = 0; r < 3; r++) {
                const float *p = m->positions + 3 * v;
                double w = inst->world[r] * p[0] + inst->world[4 + r] * p[1] + inst->world[8 + r] * p[2] +
                           inst->world[12 + r];
                lo[r] = fmin(lo[r], w), hi[r] = fmax(hi[r], w);
            }
        /* The lowest ground under the box: the terrain's vertices inside it and its surface at
         * the box's corners (the 65 x 65 grid, cells split from (i + 1, j) to (i, j + 1)). */
        const cg_mesh *t = &s.meshes[terrain];
        double ground = INFINITY;
        for (uint32_t v = 0; v < t->vertex_count; v++) {
            const float *p = t->positions + 3 * v;
            if (p[0] >= lo[0] && p[0] <= hi[0] && p[2] >= lo[2] && p[2] <= hi[2])
                ground = fmin(ground, p[1]);
        }
        for (int c = 0; c < 4; c++) {
            double fx = ((c & 1 ? hi[0] : lo[0]) + 500) / 15.625, fz = ((c & 2 ? hi[2] : lo[2]) + 500) / 15.625;
            int i = (int)fx, j = (int)fz;
            double u = fx - i, w = fz - j;
            const float *y = t->positions + 1;
            double h00 = y[3 * (j * 65 + i)], h10 = y[3 * (j * 65 + i + 1)], h01 = y[3 * ((j + 1) * 65 + i)],
                   h11 = y[3 * ((j + 1) * 65 + i + 1)];
            double h = u + w <= 1 ? h00 + u * (h10 - h00) + w * (h01 - h00)
                                  : h11 + (1 - u) * (h01 - h11) + (1 - w) * (h10 - h11);
            ground = fmin(ground, h);
        }
        printf("# house %d: bottom %.3f m, lowest ground under its box %.3f m\n", houses, lo[1], ground);
        assert_float_equal(lo[1], ground, 1e-3);
    }
    assert_int_equal(houses, 8);
    assert_int_equal(s.camera_count, 1);

    /* Exported and read back as glTF: kinds in the extras, the same triangles. */
    char out[1024];
    snprintf(out, sizeof out, "%s/dem.glb", cg_test_tmpdir());
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_export_gltf(&s, out, &err), &err);
    cg_scene back;
    load(out, &back);
    assert_int_equal(back.mesh_count, s.mesh_count);
    assert_int_equal(cg_scene_triangle_count(&back), cg_scene_triangle_count(&s));
    for (int m = 0; m < back.mesh_count; m++) {
        assert_int_equal(back.meshes[m].kind, s.meshes[m].kind);
        assert_int_equal(back.mesh_class[m].source, CG_KIND_EXTRAS);
    }
    cg_scene_free(&back);
    cg_scene_free(&s);
}

static void
bad_sources(void **state)
{
    (void)state;
    char source[1200];
    cg_scene s;
    cg_error err = { 0 };
    const char *bad[] = { "spacing=0", "spacing=abc", "stride=0", "stride=1.5", "place=floating", "colour=red",
                          "scale=1&scale=2", "sun_elevation=95", "albedo=2" };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        snprintf(source, sizeof source, "dem:%s?%s", data("valley.png"), bad[i]);
        assert_cg_status(cg_scene_load(source, &s, &err), &err, CG_ERR_SCENE_PARAM);
        assert_non_null(strstr(err.message, "valley.png"));
    }
    assert_cg_status(cg_scene_load("dem:/nonexistent/dem.png", &s, &err), &err, CG_ERR_FILE_NOT_FOUND);
    /* Not an image; a stride that leaves one sample. */
    snprintf(source, sizeof source, "dem:%s", data("village.gltf"));
    assert_cg_status(cg_scene_load(source, &s, &err), &err, CG_ERR_IMAGE_FORMAT);
    snprintf(source, sizeof source, "dem:%s?stride=100", data("valley.png"));
    assert_cg_status(cg_scene_load(source, &s, &err), &err, CG_ERR_SCENE_PARAM);
    /* The meshes file must load. */
    snprintf(source, sizeof source, "dem:%s?meshes=/nonexistent.gltf", data("valley.png"));
    cg_error_clear(&err);
    assert_false(cg_scene_load(source, &s, &err));
    assert_null(s.meshes);
}

/* A height field is seen from above: the G-buffer shades its upper side. At a crest's silhouette
 * the back-facing slope behind it can win the depth test at a pixel, and turned to the viewer its
 * normal pointed into the ground (this view at 320x180: 2 pixels, with n_y -0.84 to -0.96 on a
 * larger DEM), where a cone gather read the terrain's lit top from below (docs/hybrid.md). */
static void
height_field_normals_face_up(void **state)
{
    (void)state;
    char args[4096], out[1 << 14], normals[1024];
    snprintf(normals, sizeof normals, "%s/dem-normals.exr", cg_test_tmpdir());
    snprintf(args, sizeof args, "render 'dem:%s?spacing=15.625&scale=0.002' --graph direct.json --size 320x180 "
             "--dump gbuf.normal='%s' -o '%s/dem.png'", data("valley.png"), normals, cg_test_tmpdir());
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 0);
    cg_image img = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(cg_image_read(normals, &img, &err), &err);
    int covered = 0, down = 0;
    for (int i = 0; i < img.width * img.height; i++) {
        const float *n = &img.rgba[4 * i];
        if (n[3] <= 0.0f)
            continue;
        covered++;
        if (n[1] < -0.01f)
            down++;
    }
    cg_image_free(&img);
    assert_true(covered > 1000);
    if (down != 0)
        fail_msg("%d of %d covered pixels of the height field have a normal pointing down", down, covered);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(grid_from_png_and_tiff),
             cmocka_unit_test(village_placed_and_exported),
             cmocka_unit_test(bad_sources),
             cmocka_unit_test(height_field_normals_face_up))
