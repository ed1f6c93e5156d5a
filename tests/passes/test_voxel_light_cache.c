/* voxel_light's cache (cache=true, the default): the light volumes are relit exactly when
 * something they read changed, and a relit frame equals a frame lit from nothing (cache=false)
 * bit for bit. On a small town (terrain, wall, roof) under a sun, with and without a uniform sky:
 *   - a static frame dispatches nothing and writes nothing: a marker cleared into the radiance
 *     volume before it is still there after it;
 *   - the sun turns: relit; under the sky the first gather, G(V_0), which reads no punctual light,
 *     is kept from the last relight, and the volumes still equal cache=false's;
 *   - the wall moves (its world matrix, by hand): relit with the gather; equal;
 *   - the sky changes: relit; equal;
 *   - a graph with bounces = 2 never keeps a gather (its last one reads the lights): equal;
 *   - with bounce_spacing 2 (the representatives' sort kept with the list of voxels): the same.
 * Frames after the first run fg_graph_execute directly (vf_next_frame), as the apps animate. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gl.h"
#include "hybrid_fixture.h"
#include "test_support.h"

static const char graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"shadow\": { \"type\": \"shadow_map\", \"params\": { \"resolution\": 256 } },"
    " \"vox\": { \"type\": \"voxelize\", \"params\": { \"model\": \"surface\", \"resolution\": 32 } },"
    " \"light\": { \"type\": \"voxel_light\", \"params\": { \"bounces\": %d, \"bounce_cones\": 6, \"cache\": %s,"
    "   \"bounce_spacing\": %d },"
    "   \"inputs\": { \"albedo\": \"vox.albedo\", \"coverage\": \"vox.coverage\", \"normal\": \"vox.normal\","
    "     \"emission\": \"vox.emission\", \"region\": \"vox.region\","
    "     \"shadow\": \"shadow.depth\", \"shadow_matrix\": \"shadow.matrix\" } } },"
    " \"outputs\": [ \"light.radiance\", \"light.sides\", \"light.normals\" ] }";

static const char *const volumes[3] = {"light.radiance", "light.sides", "light.normals"};

static void
make_scene(hf_scene *s, float sky)
{
    hf_town(s, 6, 0.0f);
    const double sun[3] = {0.4, -1.0, 0.3};
    hf_sun(s, sun, 3.0f);
    hf_finish(s);
    if (sky > 0.0f) {
        cg_error err = {0};
        cg_sky uniform = {.type = CG_SKY_UNIFORM, .radiance = {sky, sky, sky}};
        assert_cg_ok(cg_scene_set_sky(&s->scene, &uniform, &err), &err);
    }
}

static void
start(vf_runner *r, hf_scene *s, int bounces, bool cache, int spacing)
{
    vf_run_format(r, &s->scene, 16, 16, graph, bounces, cache ? "true" : "false", spacing);
}

static void
assert_rebuilt(const vf_runner *r, const char *expected)
{
    if (!strstr(vf_rebuilt(r, "light"), expected))
        fail_msg("voxel_light reported \"%s\", expected \"%s\" in it", vf_rebuilt(r, "light"), expected);
}

/* Voxels of levels 0 and 1 of the three volumes that differ between the two runners. */
static int
differing_voxels(const vf_runner *a, const vf_runner *b)
{
    int differ = 0;
    for (int v = 0; v < 3; v++)
        for (int level = 0; level < 2; level++) {
            int na = 0, nb = 0;
            float *va = vf_read_volume(a, volumes[v], level, &na);
            float *vb = vf_read_volume(b, volumes[v], level, &nb);
            assert_int_equal(na, nb);
            for (size_t i = 0; i < (size_t)na * na * na; i++)
                differ += memcmp(&va[4 * i], &vb[4 * i], 4 * sizeof(float)) != 0;
            free(va);
            free(vb);
        }
    return differ;
}

/* Level 0 of the radiance cleared to a value no relight writes; true when all of it still holds it. */
static const float marker[4] = {7.0f, -3.0f, 5.0f, 11.0f};

static void
mark(const vf_runner *r)
{
    glClearTexImage(fg_graph_texture(r->graph, "light.radiance"), 0, GL_RGBA, GL_FLOAT, marker);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

static bool
still_marked(const vf_runner *r)
{
    int n = 0;
    float *v = vf_read_volume(r, "light.radiance", 0, &n);
    bool marked = true;
    for (size_t i = 0; i < (size_t)n * n * n && marked; i++)
        marked = !memcmp(&v[4 * i], marker, sizeof marker);
    free(v);
    return marked;
}

static void
both_next(vf_runner *a, vf_runner *b)
{
    vf_next_frame(a);
    vf_next_frame(b);
}

static void
check(float sky, int bounces, int spacing)
{
    hf_scene cached_scene, fresh_scene;
    make_scene(&cached_scene, sky);
    make_scene(&fresh_scene, sky);
    vf_runner cached, fresh;
    start(&cached, &cached_scene, bounces, true, spacing);
    start(&fresh, &fresh_scene, bounces, false, spacing);
    assert_rebuilt(&cached, "volumes relit (first frame)");
    assert_rebuilt(&fresh, "volumes relit (cache=false)");
    assert_rebuilt(&cached, sky > 0.0f ? (bounces == 1 ? "1 gather of" : "2 gathers of") : "dispatches");
    assert_int_equal(differing_voxels(&cached, &fresh), 0);

    /* A static frame: nothing dispatched, nothing written (the marker stays). */
    mark(&cached);
    vf_next_frame(&cached);
    assert_rebuilt(&cached, "volumes kept (0 dispatches");
    assert_true(still_marked(&cached));

    /* The sun turns: relit (over the marker), the first gather kept under the sky with one bounce. */
    hf_turn_sun(&cached, &cached_scene, 35.0);
    hf_turn_sun(&fresh, &fresh_scene, 35.0);
    both_next(&cached, &fresh);
    assert_rebuilt(&cached, "volumes relit (lights changed");
    if (sky > 0.0f && bounces == 1)
        assert_rebuilt(&cached, "first gather kept");
    else
        assert_null(strstr(vf_rebuilt(&cached, "light"), "first gather kept"));
    assert_false(still_marked(&cached));
    assert_int_equal(differing_voxels(&cached, &fresh), 0);
    vf_next_frame(&cached);
    assert_rebuilt(&cached, "volumes kept (0 dispatches");

    /* The wall moves by hand (no revision bumped): relit with its gathers. */
    cached_scene.instances[1].world[12] += 0.35f;
    fresh_scene.instances[1].world[12] += 0.35f;
    both_next(&cached, &fresh);
    assert_rebuilt(&cached, "volumes relit (an instance changed");
    assert_null(strstr(vf_rebuilt(&cached, "light"), "first gather kept"));
    assert_int_equal(differing_voxels(&cached, &fresh), 0);

    /* The sky changes (or appears): relit. */
    cg_error err = {0};
    cg_sky brighter = {.type = CG_SKY_UNIFORM, .radiance = {sky + 0.3f, sky + 0.2f, sky + 0.1f}};
    assert_cg_ok(cg_scene_set_sky(&cached_scene.scene, &brighter, &err), &err);
    assert_cg_ok(cg_scene_set_sky(&fresh_scene.scene, &brighter, &err), &err);
    both_next(&cached, &fresh);
    assert_rebuilt(&cached, "volumes relit (sky changed");
    assert_int_equal(differing_voxels(&cached, &fresh), 0);
    vf_next_frame(&cached);
    assert_rebuilt(&cached, "volumes kept (0 dispatches; 4 relights since prepare)");

    printf("# voxel_light sky %.2f bounces %d bounce_spacing %d: cache=true equals cache=false bit for bit over "
           "8 frames (static, sun turning, wall moved by hand, sky changed)\n", sky, bounces, spacing);
    vf_stop(&cached);
    vf_stop(&fresh);
    hf_free(&cached_scene);
    hf_free(&fresh_scene);
}

static void
test_relights_what_changed(void **state)
{
    (void)state;
    check(0.4f, 1, 1);  /* the sky's gather, kept while the sun turns */
    check(0.0f, 1, 1);  /* no sky, no emitter: no gather */
    check(0.4f, 2, 1);  /* two gathers, none kept */
    check(0.4f, 1, 2);  /* spaced: the sorted voxels kept with the list while only the lights change */
    check(0.4f, 2, 2);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_relights_what_changed))
