/* Correctness under animation (issue: dynamic scenes at the cost of what changed): the caches
 * must never show stale light or geometry. `conegraph render` plays builtin:openworld with
 * motion=all (every complex object moving) and motion=sun (the sun turning) for several frames,
 * through hybrid.json (heightmap_raster's kept 2D geometry) and vct.json (voxelize's kept surface
 * volumes); the last frame must equal a fresh render at the same time (relMSE below 1e-3, the
 * issue's bound) and a run with the cache off (terrain.cache=false, vox.cache=false: the papers'
 * rebuild) on the same frames.
 *
 * Measured, and asserted: the images (and hybrid.json's 2D lightmaps) are equal bit for bit. They
 * can be: a kept geometry is built by the same draw whenever it is rebuilt, from the same
 * instances (the cache rebuilds whenever one of them differs by value), and deterministically on
 * llvmpipe; heightmap_raster's relight evaluates the lit raster's very formula
 * (common/surface_light.glsl) on the very attribute values, and voxel_light lights the kept
 * volumes every frame as it lights fresh ones. voxelize's partial re-voxelization (only the voxels
 * the moved instances covered and cover, from every instance reaching them) sums integers, whose
 * order does not matter, so its geometry volumes equal a whole voxelization's bit for bit too: with
 * one building moving (it dips through the terrain, so the voxels it leaves are shared with the
 * terrain, whose part must stay) the four volumes of the last frame are compared too.
 *
 * Also asserted from `render --pass-costs`: what the cached passes report rebuilding per frame
 * (heightmap_raster: the geometry in the first frame only under every motion, as the terrain never
 * moves; voxelize: in the first frame only with the sun turning, in part in every later frame
 * with one building or every complex object moving).
 *
 * The frames are at t = 0.5 + k / 4 (exact in binary), so the fresh render's --time 1.5 is
 * the same time as the animated run's fifth frame, to the bit.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/fs.h"
#include "cg/image.h"
#include "cg/metrics.h"
#include "test_support.h"

#define SCENE "builtin:openworld?triangles=20000&period=4&motion="
/* The graphs' volumes at 64^3 (128^3 as shipped): the caches' exactness does not depend on the
 * voxels' count, and a frame of voxel_light at 64^3 costs an eighth (a 5-frame render of
 * motion=all through vct.json: 3.7 s at 128^3, 1.5 s at 64^3). */
#define SIZE "--size 96x54 --set vox.resolution=64"

static char out[1 << 16];

static const char *const volumes[4] = {"albedo", "coverage", "normal", "emission"};

/* Renders through `graph`; `lightmap` (NULL: none) gets hybrid.json's 2D lightmap, `geometry`
 * (NULL: none) vct.json's four geometry volumes (vox.albedo, coverage, normal, emission). */
static void
render_dumps(const char *graph, const char *motion, const char *options, const char *name, char image[512],
             char lightmap[512], char geometry[4][512])
{
    snprintf(image, 512, "%s/%s-%s-%s.exr", cg_test_tmpdir(), graph, motion, name);
    char dump[3000] = "";
    if (lightmap) {
        snprintf(lightmap, 512, "%s/%s-%s-%s-lightmap.exr", cg_test_tmpdir(), graph, motion, name);
        snprintf(dump, sizeof dump, "--dump terrainmip.lightmap='%s'", lightmap);
    }
    for (int v = 0; geometry && v < 4; v++) {
        snprintf(geometry[v], 512, "%s/%s-%s-%s-%s.exr", cg_test_tmpdir(), graph, motion, name, volumes[v]);
        size_t used = strlen(dump);
        snprintf(dump + used, sizeof dump - used, " --dump vox.%s='%s'", volumes[v], geometry[v]);
    }
    char args[5000];
    snprintf(args, sizeof args, "render '" SCENE "%s' --graph %s " SIZE " --verbose %s %s -o '%s'", motion, graph, options,
             dump, image);
    int code = cg_test_run_conegraph(args, true, out, sizeof out);
    if (code != 0)
        fail_msg("%s exited %d:\n%s", args, code, out);
}

static void
render(const char *graph, const char *motion, const char *options, const char *name, char image[512],
       char lightmap[512])
{
    render_dumps(graph, motion, options, name, image, lightmap, NULL);
}

/* relMSE of `test` against `ref`; *max_difference gets the largest |difference| of a channel. */
static double
compare(const char *test, const char *ref, double *max_difference)
{
    cg_image a = {0}, b = {0};
    cg_error err = {0};
    assert_cg_ok(cg_image_read(test, &a, &err), &err);
    assert_cg_ok(cg_image_read(ref, &b, &err), &err);
    assert_int_equal(a.width, b.width);
    assert_int_equal(a.height, b.height);
    *max_difference = 0.0;
    for (size_t i = 0; i < (size_t)a.width * (size_t)a.height * 4; i++) {
        double d = fabs((double)a.rgba[i] - (double)b.rgba[i]);
        *max_difference = fmax(*max_difference, isnan(d) ? INFINITY : d);
    }
    cg_metrics m;
    assert_cg_ok(cg_metrics_compute(&a, &b, &m, &err), &err);
    cg_image_free(&a);
    cg_image_free(&b);
    return m.rel_mse;
}

/* render --pass-costs: a header, then per frame a row per live pass (hybrid.json on openworld:
 * 10), with heightmap_raster's words: rasterized in the first frame, kept in the others, and the
 * gather's texture reads: a count, of pixels; none for the terrain's raster, which counts none. */
static void
check_costs(const char *path)
{
    char *text = NULL;
    cg_error err = {0};
    assert_cg_ok(cg_read_file(path, &text, NULL, &err), &err);
    const char *header = "frame,time,pass,type,ms,reads,items,item,rebuilt\n";
    assert_memory_equal(text, header, strlen(header));
    int rows = 0, terrain = 0, gathers = 0;
    for (char *line = strtok(strchr(text, '\n') + 1, "\n"); line; line = strtok(NULL, "\n")) {
        rows++;
        int frame = atoi(line);
        if (strstr(line, ",terrain,heightmap_raster,")) {
            terrain++;
            assert_non_null(strstr(line, frame == 0 ? "\"geometry rasterized (first frame);" : "\"geometry kept;"));
            assert_non_null(strstr(line, ",,,\""));     /* no reads counted */
        }
        const char *gather = strstr(line, ",gather,hybrid_gather,");
        if (gather) {
            gathers++;
            double ms = 0.0, reads = 0.0, items = 0.0;
            char item[16] = "";
            assert_int_equal(sscanf(gather + strlen(",gather,hybrid_gather,"), "%lf,%lf,%lf,%15[a-z],", &ms, &reads,
                                    &items, item), 4);
            assert_true(reads > items && items > 0.0);
            assert_string_equal(item, "pixel");
        }
    }
    assert_int_equal(rows, 5 * 10);
    assert_int_equal(terrain, 5);
    assert_int_equal(gathers, 5);
    free(text);
}

static void
check_motion(const char *motion)
{
    char animated[512], animated_map[512], fresh[512], fresh_map[512], rebuilt[512], rebuilt_map[512];
    char costs[512], options[1024];
    snprintf(costs, sizeof costs, "%s/hybrid-%s-costs.csv", cg_test_tmpdir(), motion);
    snprintf(options, sizeof options, "--frames 5 --fps 4 --time 0.5 --pass-costs '%s'", costs);
    render("hybrid.json", motion, options, "animated", animated, animated_map);
    /* The last frame's report says the 2D geometry was kept and only the light recomputed, for
     * what moved: the buildings, which cast shadows on the terrain, or the sun. */
    char relit[160];
    snprintf(relit, sizeof relit, "rebuilt: geometry kept; light 262144 texels relit (%s; 1 geometry build since prepare)",
             strcmp(motion, "sun") == 0 ? "lights changed" : "an instance changed");
    assert_non_null(strstr(out, relit));
    check_costs(costs);
    render("hybrid.json", motion, "--frames 1 --time 1.5", "fresh", fresh, fresh_map);
    render("hybrid.json", motion, "--frames 5 --fps 4 --time 0.5 --set terrain.cache=false", "rebuilt", rebuilt,
           rebuilt_map);
    assert_non_null(strstr(out, "rebuilt: geometry and light rasterized (cache=false)"));

    double d_fresh = 0, d_rebuilt = 0, d_map_fresh = 0, d_map_rebuilt = 0;
    double e_fresh = compare(animated, fresh, &d_fresh);
    double e_rebuilt = compare(animated, rebuilt, &d_rebuilt);
    compare(animated_map, fresh_map, &d_map_fresh);
    compare(animated_map, rebuilt_map, &d_map_rebuilt);
    printf("# motion=%s, frame 5 at t = 1.5 s: against a fresh render relMSE %g (max |difference| %g, "
           "2D lightmap %g); against cache=false relMSE %g (max %g, 2D lightmap %g)\n",
           motion, e_fresh, d_fresh, d_map_fresh, e_rebuilt, d_rebuilt, d_map_rebuilt);
    assert_true(e_fresh < 1e-3);
    assert_true(e_rebuilt < 1e-3);
    assert_true(d_fresh == 0.0 && d_rebuilt == 0.0);
    assert_true(d_map_fresh == 0.0 && d_map_rebuilt == 0.0);
}

/* vct.json's voxelize (vox) in the costs of `path`, 5 frames: the geometry voxelized in the first
 * frame, then each later frame's report beginning with `later`. */
static void
check_voxelize_costs(const char *path, const char *later)
{
    char *text = NULL;
    cg_error err = {0};
    assert_cg_ok(cg_read_file(path, &text, NULL, &err), &err);
    int vox = 0;
    for (char *line = strtok(strchr(text, '\n') + 1, "\n"); line; line = strtok(NULL, "\n")) {
        if (!strstr(line, ",vox,voxelize,"))
            continue;
        int frame = atoi(line);
        vox++;
        const char *want = frame == 0 ? "\"geometry voxelized (first frame; 1 geometry build since prepare)\"" : later;
        if (!strstr(line, want))
            fail_msg("frame %d of %s: want %s in\n%s", frame, path, want, line);
    }
    assert_int_equal(vox, 5);
    free(text);
}

/* What voxelize reports after the first frame: the geometry kept with the sun turning, voxelized
 * again in part when buildings move (only the voxels they covered and cover). */
#define VOX_KEPT "\"geometry kept (1 geometry build since prepare)\""
#define VOX_PARTIAL "\"geometry re-voxelized in part (a voxelized instance changed: "

/* vct.json: the last of 5 frames against a fresh render and against vox.cache=false. */
static void
check_vct_motion(const char *motion)
{
    char animated[512], fresh[512], rebuilt[512], costs[512], options[1024];
    snprintf(costs, sizeof costs, "%s/vct-%s-costs.csv", cg_test_tmpdir(), motion);
    snprintf(options, sizeof options, "--frames 5 --fps 4 --time 0.5 --pass-costs '%s'", costs);
    render("vct.json", motion, options, "animated", animated, NULL);
    /* The sun turning leaves the geometry as it is; every complex object moving voxelizes again the
     * voxels they cover. */
    check_voxelize_costs(costs, strcmp(motion, "sun") != 0 ? VOX_PARTIAL : VOX_KEPT);
    render("vct.json", motion, "--frames 1 --time 1.5", "fresh", fresh, NULL);
    render("vct.json", motion, "--frames 5 --fps 4 --time 0.5 --set vox.cache=false", "rebuilt", rebuilt, NULL);
    assert_non_null(strstr(out, "rebuilt: geometry voxelized (cache=false)"));

    double d_fresh = 0, d_rebuilt = 0;
    double e_fresh = compare(animated, fresh, &d_fresh);
    double e_rebuilt = compare(animated, rebuilt, &d_rebuilt);
    printf("# vct.json, motion=%s, frame 5 at t = 1.5 s: against a fresh render relMSE %g (max |difference| %g); "
           "against vox.cache=false relMSE %g (max %g)\n",
           motion, e_fresh, d_fresh, e_rebuilt, d_rebuilt);
    assert_true(e_fresh < 1e-3);
    assert_true(e_rebuilt < 1e-3);
    assert_true(d_fresh == 0.0 && d_rebuilt == 0.0);
}

static void
test_every_object_moving(void **state)
{
    (void)state;
    check_motion("all");
}

static void
test_sun_turning(void **state)
{
    (void)state;
    check_motion("sun");
}

static void
test_vct_every_object_moving(void **state)
{
    (void)state;
    check_vct_motion("all");
}

static void
test_vct_sun_turning(void **state)
{
    (void)state;
    check_vct_motion("sun");
}

/* Largest |difference| of a channel between two dumped volumes (or images). */
static double
max_difference(const char *test, const char *ref)
{
    double d = 0.0;
    compare(test, ref, &d);
    return d;
}

/* One building moving: voxelize re-voxelizes in part every frame after the first (the building
 * dips through the terrain: the voxels it leaves keep the terrain's part), and its four geometry
 * volumes and the image of the last frame equal a fresh render at the same time and a run with
 * vox.cache=false (the whole volume voxelized every frame), bit for bit. */
static void
test_vct_one_moving(void **state)
{
    (void)state;
    char animated[512], fresh[512], rebuilt[512], costs[512], options[1024];
    char g_animated[4][512], g_fresh[4][512], g_rebuilt[4][512];
    snprintf(costs, sizeof costs, "%s/vct-one-costs.csv", cg_test_tmpdir());
    snprintf(options, sizeof options, "--frames 5 --fps 4 --time 0.5 --pass-costs '%s'", costs);
    render_dumps("vct.json", "one", options, "animated", animated, NULL, g_animated);
    check_voxelize_costs(costs, VOX_PARTIAL "1 region,");
    render_dumps("vct.json", "one", "--frames 1 --time 1.5", "fresh", fresh, NULL, g_fresh);
    render_dumps("vct.json", "one", "--frames 5 --fps 4 --time 0.5 --set vox.cache=false", "rebuilt", rebuilt, NULL,
                 g_rebuilt);
    assert_non_null(strstr(out, "rebuilt: geometry voxelized (cache=false)"));
    for (int v = 0; v < 4; v++) {
        double d_fresh = max_difference(g_animated[v], g_fresh[v]);
        double d_rebuilt = max_difference(g_animated[v], g_rebuilt[v]);
        printf("# vct.json, motion=one, frame 5: vox.%s against a fresh render max |difference| %g, against "
               "vox.cache=false %g\n", volumes[v], d_fresh, d_rebuilt);
        assert_true(d_fresh == 0.0 && d_rebuilt == 0.0);
    }
    double d_fresh = max_difference(animated, fresh), d_rebuilt = max_difference(animated, rebuilt);
    printf("# vct.json, motion=one, frame 5 image: against a fresh render max |difference| %g, against "
           "vox.cache=false %g\n", d_fresh, d_rebuilt);
    assert_true(d_fresh == 0.0 && d_rebuilt == 0.0);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_every_object_moving),
             cmocka_unit_test(test_sun_turning),
             cmocka_unit_test(test_vct_every_object_moving),
             cmocka_unit_test(test_vct_sun_turning),
             cmocka_unit_test(test_vct_one_moving))
