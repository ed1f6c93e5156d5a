/* Correctness under animation (issue: dynamic scenes at the cost of what changed): the cache
 * must never show stale light or geometry. `conegraph render` plays builtin:openworld with
 * motion=all (every complex object moving) and motion=sun (the sun turning) through
 * hybrid.json for several frames; the last frame must equal a fresh render at the same time
 * (relMSE below 1e-3, the bound) and a run with every cache off (terrain.cache=false,
 * the paper's rebuild) on the same frames.
 *
 * Measured, and asserted: the images and the 2D lightmaps are equal bit for bit. They can be:
 * the only cache is heightmap_raster's kept geometry, which is rasterized by the same draw
 * whenever it is rebuilt, and its relight evaluates the lit raster's very formula
 * (common/surface_light.glsl) on the very attribute values; everything else (voxelize
 * included) is recomputed every frame, deterministically on llvmpipe. A cache that one day
 * approximates must keep the relMSE bound and may relax the bit-for-bit one, saying why.
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
#define COMMON "--graph hybrid.json --size 96x54"

static char out[1 << 16];

static void
render(const char *motion, const char *options, const char *name, char image[512], char lightmap[512])
{
    snprintf(image, 512, "%s/%s-%s.exr", cg_test_tmpdir(), motion, name);
    snprintf(lightmap, 512, "%s/%s-%s-lightmap.exr", cg_test_tmpdir(), motion, name);
    char args[2048];
    snprintf(args, sizeof args, "render '" SCENE "%s' " COMMON " %s --dump terrainmip.lightmap='%s' -o '%s'",
             motion, options, lightmap, image);
    int code = cg_test_run_conegraph(args, true, out, sizeof out);
    if (code != 0)
        fail_msg("%s exited %d:\n%s", args, code, out);
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
 * 10), with heightmap_raster's words: rasterized in the first frame, kept in the others. */
static void
check_costs(const char *path)
{
    char *text = NULL;
    cg_error err = {0};
    assert_cg_ok(cg_read_file(path, &text, NULL, &err), &err);
    assert_memory_equal(text, "frame,time,pass,type,ms,rebuilt\n", 32);
    int rows = 0, terrain = 0;
    for (char *line = strtok(strchr(text, '\n') + 1, "\n"); line; line = strtok(NULL, "\n")) {
        rows++;
        int frame = atoi(line);
        if (strstr(line, ",terrain,heightmap_raster,")) {
            terrain++;
            assert_non_null(strstr(line, frame == 0 ? "\"geometry rasterized (first frame);" : "\"geometry kept;"));
        }
    }
    assert_int_equal(rows, 5 * 10);
    assert_int_equal(terrain, 5);
    free(text);
}

static void
check_motion(const char *motion)
{
    char animated[512], animated_map[512], fresh[512], fresh_map[512], rebuilt[512], rebuilt_map[512];
    char costs[512], options[1024];
    snprintf(costs, sizeof costs, "%s/%s-costs.csv", cg_test_tmpdir(), motion);
    snprintf(options, sizeof options, "--frames 5 --fps 4 --time 0.5 --pass-costs '%s'", costs);
    render(motion, options, "animated", animated, animated_map);
    /* The last frame's report says the 2D geometry was kept and only the light recomputed. */
    assert_non_null(strstr(out, "rebuilt: geometry kept; light 262144 texels relit (1 geometry build since prepare)"));
    check_costs(costs);
    render(motion, "--frames 1 --time 1.5", "fresh", fresh, fresh_map);
    render(motion, "--frames 5 --fps 4 --time 0.5 --set terrain.cache=false", "rebuilt", rebuilt, rebuilt_map);
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

int
main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_object_moving),
        cmocka_unit_test(test_sun_turning),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
