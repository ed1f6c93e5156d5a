/* heightmap_raster's cache (cache=true): the kept geometry is rasterized again exactly when a
 * height-field instance changed, the light is recomputed exactly when something it reads changed,
 * and a cached frame equals a frame rebuilt from nothing (cache=false) bit for bit:
 *   - a static frame: geometry and light kept (no dispatch), the map as cache=false's;
 *   - a static terrain under a turning sun: geometry kept, relit ("lights changed"), the map
 *     equals cache=false's;
 *   - a complex quad over the terrain (a shadow caster) moved by hand: relit ("an instance
 *     changed"), its shadow moved as in cache=false's;
 *   - the terrain turned by hand (its world matrix changed, its revision not bumped, its bounds
 *     the same): the geometry is rasterized again and equals a fresh cache=false map;
 *   - the GPU scene uploaded again: rasterized again (its meshes may have changed in place).
 * Frames after the first run fg_graph_execute directly, not vf_frame, which uploads the scene
 * again every frame. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gl.h"
#include "hybrid_fixture.h"
#include "test_support.h"

static double
bumpy(double x, double z, const void *user)
{
    (void)user;
    return 1.0 + 0.4 * x - 0.25 * z + 0.3 * sin(1.7 * x) * cos(1.1 * z);
}

static const char graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"shadow\": { \"type\": \"shadow_map\", \"params\": { \"resolution\": 256 } },"
    " \"hm\": { \"type\": \"heightmap_raster\", \"params\": { \"resolution\": 64, \"format\": \"%s\", \"cache\": %s },"
    "   \"inputs\": { \"shadow\": \"shadow.depth\", \"shadow_matrix\": \"shadow.matrix\" } } },"
    " \"outputs\": [ \"hm.lightmap\" ] }";

static void
make_scene(hf_scene *s)
{
    hf_init(s);
    hf_material(s, 1, 0.6f, 0.05f);
    hf_grid(s, 24, -4.0, -4.0, 8.0, bumpy, NULL);
    /* A complex plate at 3.5 m, above the terrain's middle, casting a shadow on it. */
    const double corner[3] = {-1.0, 3.5, -1.0}, e1[3] = {0.0, 0.0, 2.0}, e2[3] = {2.0, 0.0, 0.0};
    hf_quad(s, corner, e1, e2);
    const double sun[3] = {0.4, -1.0, 0.3};
    hf_sun(s, sun, 3.0f);
    hf_finish(s);
}

static void
start(vf_runner *r, hf_scene *s, const char *format, bool cache)
{
    vf_run_format(r, &s->scene, 16, 16, graph, format, cache ? "true" : "false");
}

/* Texels of level 0 that differ between the two runners' lightmaps. */
static int
differing_texels(const vf_runner *a, const vf_runner *b)
{
    int wa = 0, ha = 0, wb = 0, hb = 0;
    float *ma = hf_read_2d(a, "hm.lightmap", 0, &wa, &ha);
    float *mb = hf_read_2d(b, "hm.lightmap", 0, &wb, &hb);
    assert_int_equal(wa, wb);
    assert_int_equal(ha, hb);
    int differ = 0;
    for (int i = 0; i < wa * ha; i++)
        differ += memcmp(&ma[4 * i], &mb[4 * i], 4 * sizeof(float)) != 0;
    free(ma);
    free(mb);
    return differ;
}

static void
check_format(const char *format)
{
    hf_scene cached_scene, fresh_scene;
    make_scene(&cached_scene);
    make_scene(&fresh_scene);
    vf_runner cached, fresh;
    start(&cached, &cached_scene, format, true);
    assert_non_null(strstr(vf_rebuilt(&cached, "hm"), "geometry rasterized (first frame)"));
    start(&fresh, &fresh_scene, format, false);
    assert_string_equal(vf_rebuilt(&fresh, "hm"), "geometry and light rasterized (cache=false)");
    assert_int_equal(differing_texels(&cached, &fresh), 0);

    /* Nothing changed: nothing relit, the map kept. */
    vf_next_frame(&cached);
    vf_next_frame(&fresh);
    assert_non_null(strstr(vf_rebuilt(&cached, "hm"), "geometry kept; light kept"));
    assert_int_equal(differing_texels(&cached, &fresh), 0);

    /* The sun turns: the geometry is kept, the light follows. */
    for (int k = 1; k <= 3; k++) {
        hf_turn_sun(&cached, &cached_scene, 40.0);
        hf_turn_sun(&fresh, &fresh_scene, 40.0);
        vf_next_frame(&cached);
        vf_next_frame(&fresh);
        assert_non_null(strstr(vf_rebuilt(&cached, "hm"), "geometry kept; light"));
        assert_non_null(strstr(vf_rebuilt(&cached, "hm"), "relit (lights changed"));
        assert_int_equal(differing_texels(&cached, &fresh), 0);
    }

    /* The plate moves 1.5 m by hand (no revision bumped): its shadow on the terrain moves. */
    int w = 0, h = 0;
    float *before = hf_read_2d(&cached, "hm.lightmap", 0, &w, &h);
    for (int k = 0; k < 2; k++) {
        hf_scene *sc = k == 0 ? &cached_scene : &fresh_scene;
        sc->instances[1].world[12] += 1.5f;
    }
    vf_next_frame(&cached);
    vf_next_frame(&fresh);
    assert_non_null(strstr(vf_rebuilt(&cached, "hm"), "relit (an instance changed"));
    assert_int_equal(differing_texels(&cached, &fresh), 0);
    float *after = hf_read_2d(&cached, "hm.lightmap", 0, &w, &h);
    int moved = 0;
    for (int i = 0; i < w * h; i++)
        moved += memcmp(&before[4 * i], &after[4 * i], 4 * sizeof(float)) != 0;
    printf("# heightmap_raster %s: the caster moved, %d of %d texels changed\n", format, moved, w * h);
    assert_true(moved > 0);
    free(before);
    free(after);

    /* The terrain turns half a turn about +y by hand: same bounds, other heights under each
     * texel, no revision bumped. */
    static const float half_turn[16] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1};
    memcpy(cached_scene.instances[0].world, half_turn, sizeof half_turn);
    memcpy(fresh_scene.instances[0].world, half_turn, sizeof half_turn);
    vf_next_frame(&cached);
    vf_next_frame(&fresh);
    assert_non_null(strstr(vf_rebuilt(&cached, "hm"), "geometry rasterized (a height-field instance changed)"));
    assert_int_equal(differing_texels(&cached, &fresh), 0);
    vf_next_frame(&cached);
    assert_non_null(strstr(vf_rebuilt(&cached, "hm"), "geometry kept"));

    /* The scene uploaded again: rasterized again. */
    vf_frame(&cached);
    assert_non_null(strstr(vf_rebuilt(&cached, "hm"), "geometry rasterized (scene uploaded again)"));
    printf("# heightmap_raster %s: cache=true equals cache=false bit for bit over 9 frames "
           "(static, sun turning, a caster moved and the terrain turned by hand, scene re-uploaded)\n", format);
    vf_stop(&cached);
    vf_stop(&fresh);
    hf_free(&cached_scene);
    hf_free(&fresh_scene);
}

static void
test_cache_follows_changes(void **state)
{
    (void)state;
    check_format("rgba32f");
    check_format("rgba16f");
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_cache_follows_changes))
