/* voxelize alone on a software context: coverage of quads and sliver triangles at many
 * orientations against the exact triangle/voxel overlap (tests/passes/tribox_ref.h), the
 * holes plain rasterization would leave, the radiance a lit surface's voxels hold, and
 * order-independent averaging. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gl.h"
#include "cg/scene.h"
#include "test_support.h"
#include "tribox_ref.h"
#include "vct_fixture.h"

#define RES 32

static const char graph_template[] =
    "{ \"version\": 1, \"passes\": { \"vox\": { \"type\": \"voxelize\", \"params\": {"
    " \"resolution\": %d, \"region\": \"explicit\", \"padding\": 0, \"conservative\": %s, \"format\": \"%s\","
    " \"min_x\": 0, \"min_y\": 0, \"min_z\": 0, \"max_x\": 1, \"max_y\": 1, \"max_z\": 1 } } },"
    " \"outputs\": [ \"vox.radiance\" ] }";

/* The surface model through the compute-shader voxelizer (voxelizer=compute): the same voxels. */
static const char compute_template[] =
    "{ \"version\": 1, \"passes\": { \"vox\": { \"type\": \"voxelize\", \"params\": {"
    " \"model\": \"surface\", \"voxelizer\": \"compute\", \"cache\": false,"
    " \"resolution\": %d, \"region\": \"explicit\", \"padding\": 0,"
    " \"min_x\": 0, \"min_y\": 0, \"min_z\": 0, \"max_x\": 1, \"max_y\": 1, \"max_z\": 1 } } },"
    " \"outputs\": [ \"vox.albedo\" ] }";

/* Deterministic rotations: a small LCG, no global state. */
static double
next_uniform(uint64_t *seed)
{
    *seed = *seed * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*seed >> 11) / 9007199254740992.0;
}

static void
random_rotation(uint64_t *seed, double m[3][3])
{
    /* Arvo 1992: uniform random rotation from three uniforms. */
    double t = 2 * M_PI * next_uniform(seed), p = 2 * M_PI * next_uniform(seed), z = next_uniform(seed);
    double r = sqrt(z), v[3] = {cos(p) * r, sin(p) * r, sqrt(1 - z)};
    double R[3][3] = {{cos(t), sin(t), 0}, {-sin(t), cos(t), 0}, {0, 0, 1}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            /* M = (2 v v^T - I) R */
            m[i][j] = 0;
            for (int k = 0; k < 3; k++)
                m[i][j] += (2 * v[i] * v[k] - (i == k)) * R[k][j];
        }
}

static void
rotate_about_centre(const double m[3][3], const double p[3], double out[3])
{
    for (int i = 0; i < 3; i++) {
        out[i] = 0.5;
        for (int k = 0; k < 3; k++)
            out[i] += m[i][k] * (p[k] - 0.5);
    }
}

typedef struct coverage {
    int missing;    /* voxels the triangles cut but left empty */
    int extra;      /* occupied voxels the triangles do not touch */
    int expected;
} coverage;

static coverage
check_coverage(const vf_scene *s, const float *vox)
{
    coverage c = {0, 0, 0};
    for (int z = 0; z < RES; z++)
        for (int y = 0; y < RES; y++)
            for (int x = 0; x < RES; x++) {
                double centre[3] = {x + 0.5, y + 0.5, z + 0.5};
                bool strict = false, loose = false;
                for (uint32_t t = 0; t < s->mesh.vertex_count; t += 3) {
                    double v[3][3];
                    for (int i = 0; i < 3; i++)
                        for (int k = 0; k < 3; k++)
                            v[i][k] = s->positions[3 * (t + i) + k] * RES;
                    strict = strict || tribox_overlap_ref(centre, 0.5 - 1e-3, v[0], v[1], v[2]);
                    loose = loose || tribox_overlap_ref(centre, 0.5 + 1e-3, v[0], v[1], v[2]);
                }
                bool occupied = vox[4 * ((size_t)(z * RES + y) * RES + x) + 3] > 0.5f;
                c.expected += strict;
                c.missing += strict && !occupied;
                c.extra += occupied && !loose;
            }
    return c;
}

/* `shape` 0: a sliver 0.6 long and 0.002 wide (a 16th of a voxel); 1: a 0.5 x 0.4 quad. */
static void
build_shape(vf_scene *s, int shape, const double m[3][3])
{
    vf_scene_init(s, 1.0f, 1.0f);
    double a[3], b[3], c[3], d[3];
    if (shape == 0) {
        const double p[3][3] = {{0.2, 0.5, 0.5}, {0.8, 0.5, 0.5}, {0.2, 0.502, 0.5}};
        rotate_about_centre(m, p[0], a);
        rotate_about_centre(m, p[1], b);
        rotate_about_centre(m, p[2], c);
        vf_add_triangle(s, a, b, c);
    } else {
        const double p[4][3] = {{0.25, 0.3, 0.5}, {0.75, 0.3, 0.5}, {0.75, 0.7, 0.5}, {0.25, 0.7, 0.5}};
        rotate_about_centre(m, p[0], a);
        rotate_about_centre(m, p[1], b);
        rotate_about_centre(m, p[2], c);
        rotate_about_centre(m, p[3], d);
        vf_add_triangle(s, a, b, c);
        vf_add_triangle(s, a, c, d);
    }
    vf_finish(s);
}

static int
run_orientations(cg_context *ctx, bool conservative, bool compute, int shape, int count, coverage *total)
{
    char json[1024];
    if (compute)
        snprintf(json, sizeof json, compute_template, RES);
    else
        snprintf(json, sizeof json, graph_template, RES, conservative ? "true" : "false", "rgba16f");
    vf_scene *s = calloc(1, sizeof *s);
    assert_non_null(s);
    double identity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    build_shape(s, shape, identity);
    vf_runner r;
    vf_start(&r, &s->scene, 32, 32, json, NULL);
    uint64_t seed = 12345u + (uint64_t)shape;
    int worst = 0;
    *total = (coverage){0, 0, 0};
    for (int i = 0; i < count; i++) {
        double m[3][3];
        random_rotation(&seed, m);
        build_shape(s, shape, i == 0 ? identity : m);
        vf_frame(&r);
        int size = 0;
        /* Opacity (radiance) or albedo alpha (surface): 1 where a surface is. */
        float *vox = vf_read_volume(&r, compute ? "vox.albedo" : "vox.radiance", 0, &size);
        assert_int_equal(size, RES);
        coverage c = check_coverage(s, vox);
        free(vox);
        total->missing += c.missing;
        total->extra += c.extra;
        total->expected += c.expected;
        if (c.missing > worst)
            worst = c.missing;
    }
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    free(s);
    return worst;
}

/* Conservative mode: exactly the voxels each triangle touches, at every orientation, through the
 * geometry-shader voxelizer and the compute-shader one (model surface, voxelizer=compute). */
static void
test_coverage_exact(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    for (int compute = 0; compute < 2; compute++)
        for (int shape = 0; shape < 2; shape++) {
            coverage total;
            run_orientations(ctx, true, compute, shape, 40, &total);
            fprintf(stderr, "# %s, %s, 40 orientations: %d voxels expected, %d missing, %d extra\n",
                    compute ? "compute voxelizer" : "conservative", shape == 0 ? "sliver" : "quad", total.expected,
                    total.missing, total.extra);
            assert_int_equal(total.missing, 0);
            assert_int_equal(total.extra, 0);
            assert_true(total.expected > 40 * 10);
        }
}

/* Plain rasterization (conservative = false) loses voxels: the measurement behind the
 * default, printed for docs/vct.md; it must find holes for the sliver, or the test above
 * proves nothing about dilation. */
static void
test_plain_rasterization_leaves_holes(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    for (int shape = 0; shape < 2; shape++) {
        coverage total;
        run_orientations(ctx, false, false, shape, 40, &total);
        fprintf(stderr, "# plain rasterization, %s, 40 orientations: %d voxels expected, %d missing (%.1f%%), %d extra\n",
                shape == 0 ? "sliver" : "quad", total.expected, total.missing,
                100.0 * total.missing / total.expected, total.extra);
        if (shape == 0)
            assert_true(total.missing > total.expected / 4);
        assert_int_equal(total.extra, 0);
    }
}

/* A white-ish quad facing a directional light of irradiance E = 3 k W/m^2 and emitting 0.05 k:
 * every voxel it occupies holds albedo E / pi + emission (DESIGN.md units), within the
 * fixed-point and half-float rounding (RGBA8: as a fraction of the published scale), at any
 * brightness k; voxels away from it stay empty and black. */
static void
check_lit_surface(cg_context *ctx, const char *format, double k)
{
    bool rgba8 = strcmp(format, "rgba8") == 0;
    const float albedo = 0.6f, emission = (float)(0.05 * k), irradiance = (float)(3.0 * k);
    vf_scene *s = calloc(1, sizeof *s);
    assert_non_null(s);
    vf_scene_init(s, albedo, emission);
    /* y = 0.51: not on a voxel face, so one layer of voxels. */
    const double a[3] = {0.2, 0.51, 0.2}, b[3] = {0.8, 0.51, 0.2}, c[3] = {0.8, 0.51, 0.8}, d[3] = {0.2, 0.51, 0.8};
    vf_add_triangle(s, a, c, b);
    vf_add_triangle(s, a, d, c);
    cg_light *sun = &s->lights[s->scene.light_count++];
    sun->type = CG_LIGHT_DIRECTIONAL;
    sun->color[0] = sun->color[1] = sun->color[2] = 1.0f;
    sun->intensity = irradiance;
    sun->direction[1] = -1.0f;
    vf_finish(s);
    char json[1024];
    snprintf(json, sizeof json, graph_template, RES, "true", format);
    vf_runner r;
    vf_start(&r, &s->scene, 32, 32, json, NULL);
    vf_frame(&r);
    int size = 0;
    float *vox = vf_read_volume(&r, "vox.radiance", 0, &size);
    const double radiance = albedo * irradiance / M_PI + emission;
    /* The region block (common/volume.glsl): origin, voxel size, resolution, levels, scale. */
    float block[8];
    glGetNamedBufferSubData(fg_graph_texture(r.graph, "vox.region"), 0, sizeof block, block);
    assert_float_equal(block[0], 0.0, 1e-7);
    assert_float_equal(block[3], 1.0 / RES, 1e-7);
    assert_float_equal(block[4], RES, 0.0);
    assert_float_equal(block[5], 6, 0.0);
    /* RGBA8 holds radiance over the volume's maximum; RGBA16F radiance over the scene's radiance
     * bound / 32768 (sdk/radiance.h): the brightest emission plus the brightest albedo (material 0,
     * white) lit by the sun. Each publishes its scale. */
    if (rgba8) {
        assert_float_equal(block[6], radiance, 1e-5 * radiance);
    } else {
        double bound = emission + 1.0 * irradiance / M_PI;
        assert_float_equal(block[6], bound / 32768.0, 1e-6 * bound / 32768.0);
    }
    const double expected = rgba8 ? 1.0 : radiance / block[6];
    const double tolerance = rgba8 ? 0.5 / 255.0 : 2e-3 * expected;
    int occupied = 0;
    for (int z = 0; z < RES; z++)
        for (int y = 0; y < RES; y++)
            for (int x = 0; x < RES; x++) {
                const float *v = &vox[4 * ((size_t)(z * RES + y) * RES + x)];
                if (v[3] > 0.5f) {
                    occupied++;
                    assert_int_equal(y, 16);
                    for (int k = 0; k < 3; k++)
                        if (fabs(v[k] - expected) > tolerance)
                            fail_msg("voxel (%d,%d,%d): radiance %g, expected %g", x, y, z, v[k], expected);
                } else {
                    assert_true(v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f);
                }
            }
    /* x, z from 0.2*32 = 6.4 to 25.6: voxels 6..25, 20 x 20. */
    assert_int_equal(occupied, 20 * 20);
    /* Cleared and rebuilt every frame, averaged in integers: the next frame gives the same bits. */
    vf_frame(&r);
    float *again = vf_read_volume(&r, "vox.radiance", 0, &size);
    assert_memory_equal(again, vox, sizeof(float) * 4 * RES * RES * RES);
    free(again);
    free(vox);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    free(s);
}

static void
test_lit_surface_radiance(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    /* From starlight to 1e9 W/m^2: half floats hold 6.1e-5 to 65504 at full precision. */
    static const double brightness[] = {1e-7, 1.0, 1e9};
    for (int i = 0; i < 3; i++) {
        check_lit_surface(ctx, "rgba16f", brightness[i]);
        check_lit_surface(ctx, "rgba8", brightness[i]);
    }
}

/* The `meshes` filter (the hybrid method voxelizes complex meshes only): over one region,
 * the terrain's voxels and the buildings' voxels together are exactly the voxels of all
 * meshes; a filter no mesh passes culls the pass. */
static float *
occupancy(cg_context *ctx, const cg_scene *scene, const char *meshes, bool *culled)
{
    char json[512];
    snprintf(json, sizeof json,
             "{ \"version\": 1, \"passes\": { \"vox\": { \"type\": \"voxelize\", \"params\": {"
             " \"resolution\": %d, \"meshes\": \"%s\", \"region\": \"scene\" } } },"
             " \"outputs\": [ \"vox.radiance\" ] }", RES, meshes);
    vf_runner r;
    vf_start(&r, scene, 32, 32, json, NULL);
    *culled = fg_pass_is_culled(fg_graph_find_pass(r.graph, "vox"));
    float *vox = NULL;
    if (!*culled) {
        vf_frame(&r);
        int size = 0;
        vox = vf_read_volume(&r, "vox.radiance", 0, &size);
    }
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    assert_false(*culled);
    return vox;
}

static void
test_mesh_filter(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_error err = {0};
    cg_scene scene = cg_test_load_scene("builtin:openworld?triangles=5000");
    bool culled = false;
    float *all = occupancy(ctx, &scene, "all", &culled);
    float *terrain = occupancy(ctx, &scene, "heightfield", &culled);
    float *complex = occupancy(ctx, &scene, "complex", &culled);
    int n_all = 0, n_terrain = 0, n_complex = 0;
    for (int i = 0; i < RES * RES * RES; i++) {
        bool a = all[4 * i + 3] > 0.5f, t = terrain[4 * i + 3] > 0.5f, c = complex[4 * i + 3] > 0.5f;
        n_all += a, n_terrain += t, n_complex += c;
        if (a != (t || c))
            fail_msg("voxel %d: all %d, heightfield %d, complex %d", i, a, t, c);
    }
    fprintf(stderr, "# openworld 5000 triangles at %d^3: %d voxels, %d terrain, %d complex\n", RES, n_all,
            n_terrain, n_complex);
    assert_true(n_terrain > 0 && n_complex > 0 && n_complex < n_all && n_terrain < n_all);
    free(all);
    free(terrain);
    free(complex);
    cg_scene_free(&scene);

    /* builtin:cornell has no height field: voxelize and the gather are culled, the frame runs. */
    assert_cg_ok(cg_scene_load("builtin:cornell", &scene, &err), &err);
    const char *const heightfield_only[] = {"vox.meshes=heightfield", NULL};
    vf_runner r;
    vf_start_file(&r, &scene, 32, 32, "vct.json", heightfield_only);
    vf_frame(&r);
    assert_true(fg_pass_is_culled(fg_graph_find_pass(r.graph, "vox")));
    assert_true(fg_pass_is_culled(fg_graph_find_pass(r.graph, "gather")));
    assert_false(fg_pass_is_culled(fg_graph_find_pass(r.graph, "final")));
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    cg_scene_free(&scene);
}

/* voxelize's `slices`: the volume voxelized a slice of z at a time, the accumulation holding one.
 * The sums are integers and each slice receives every fragment that falls in it, so the geometry
 * volumes equal a whole voxelization's bit for bit: slices that do not divide the depth (3: 22,
 * 22 and 20 voxels), one voxel each (64), and the compute voxelizer. */
static void
test_slices_equal_whole(void **state)
{
    static const char *const names[5] = {"vox.albedo", "vox.coverage", "vox.normal", "vox.emission", "vox.specular"};
    cg_context *ctx = cg_test_gl_context(state);
    cg_scene scene = cg_test_load_scene("builtin:openworld?triangles=5000");
    static const char *const cases[][4] = {
        {"vox.resolution=64", "vox.slices=1", NULL, NULL},
        {"vox.resolution=64", "vox.slices=3", NULL, NULL},
        {"vox.resolution=64", "vox.slices=64", NULL, NULL},
        {"vox.resolution=64", "vox.slices=1", "vox.voxelizer=compute", NULL},
        {"vox.resolution=64", "vox.slices=3", "vox.voxelizer=compute", NULL},
    };
    const int expected_depth[] = {64, 22, 1, 64, 22};
    float *whole[2][5] = {{NULL}};
    for (int c = 0; c < 5; c++) {
        vf_runner r;
        vf_start_file(&r, &scene, 16, 16, "vct.json", cases[c]);
        vf_frame(&r);
        const fg_resource_info *accumulation = fg_graph_find_resource(r.graph, "vox.accumulation");
        assert_non_null(accumulation);
        int w = accumulation->desc.width, h = accumulation->desc.height, d = accumulation->desc.depth;
        /* 3 x 2 x 3 slabs of one slice (common/blocks.h). */
        assert_int_equal(w, 3 * 64);
        assert_int_equal(h, 2 * 64);
        assert_int_equal(d, 3 * expected_depth[c]);
        int compute = c >= 3, equal = 0;
        for (int i = 0; i < 5; i++) {
            int size = 0;
            float *v = vf_read_volume(&r, names[i], 0, &size);
            assert_int_equal(size, 64);
            if (!whole[compute][i]) {
                whole[compute][i] = v;
                continue;
            }
            if (memcmp(v, whole[compute][i], sizeof(float) * 4 * 64 * 64 * 64))
                fail_msg("%s, %s: %s differs from the whole voxelization's", cases[c][1],
                         compute ? "compute" : "geometry", names[i]);
            equal++;
            free(v);
        }
        fprintf(stderr, "# %s %s: accumulation %dx%dx%d, %d of 5 volumes equal to slices=1's\n", cases[c][1],
                compute ? "compute" : "geometry", w, h, d, equal);
        assert_no_gl_errors(ctx);
        vf_stop(&r);
    }
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 5; i++)
            free(whole[k][i]);
    cg_scene_free(&scene);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_coverage_exact),
             cmocka_unit_test(test_plain_rasterization_leaves_holes),
             cmocka_unit_test(test_lit_surface_radiance),
             cmocka_unit_test(test_mesh_filter),
             cmocka_unit_test(test_slices_equal_whole))
