/* voxelize's partial re-voxelization (model=surface, cache=true): when some instances move, only
 * the voxels they covered before and cover now are voxelized again, from every instance that
 * reaches them, and the four geometry volumes must equal a whole voxelization (cache=false) of
 * the same scene bit for bit, frame after frame:
 *   - a wall standing on a terrain of 20000 triangles (chunked by the pass: more than its
 *     16384-triangle threshold) moves along it: the voxels it shared with the terrain must keep
 *     the terrain's part, and those it leaves must hold the terrain alone;
 *   - the wall turns by hand (its world matrix changed, no revision bumped);
 *   - the wall moves out of the volume (its new box is empty: only its old one is cleared and
 *     voxelized again), and back in;
 *   - nothing changes: the volumes are kept;
 *   - the terrain itself is stretched: the changed region is most of the volume, so the pass
 *     voxelizes the whole volume instead, and says so.
 * Through both voxelizers (geometry shader, compute shader). The pass's report says which it did. Frames after the first run fg_graph_execute directly, as
 * the apps do (vf_frame uploads the scene again, which voxelizes everything). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gl.h"
#include "hybrid_fixture.h"
#include "test_support.h"

#define RES 32

static const char graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"vox\": { \"type\": \"voxelize\", \"params\": { \"model\": \"surface\", \"resolution\": 32, \"cache\": %s,"
    "   \"voxelizer\": \"%s\","
    "   \"region\": \"explicit\", \"padding\": 0, \"min_x\": -4, \"min_y\": -4, \"min_z\": -4,"
    "   \"max_x\": 4, \"max_y\": 4, \"max_z\": 4 } } },"
    " \"outputs\": [ \"vox.albedo\", \"vox.coverage\", \"vox.normal\", \"vox.emission\", \"vox.specular\" ] }";

static const char *const volumes[5] = {"vox.albedo", "vox.coverage", "vox.normal", "vox.emission", "vox.specular"};

/* hf_town: a terrain of 100 x 100 quads over the volume's floor, a wall standing on it and a
 * roof-like quad elsewhere that never moves; the wall a rough metal, so that the specular volume's
 * sums move with it too. */
static void
make_scene(hf_scene *s)
{
    hf_town(s, 100, 0.5f);
    hf_finish(s);
    s->materials[2].metallic = 1.0f;
    s->materials[2].roughness = 0.5f;
    s->materials[2].specular = 1.0f;
    s->materials[2].ior = 1.5f;
}

static void
start(vf_runner *r, hf_scene *s, bool cache, const char *voxelizer)
{
    vf_run_format(r, &s->scene, 16, 16, graph, cache ? "true" : "false", voxelizer);
}

/* Voxels of the five volumes that differ between the two runners (any channel, bit for bit). */
static int
differing_voxels(const vf_runner *a, const vf_runner *b)
{
    int differ = 0;
    for (int v = 0; v < 5; v++) {
        int na = 0, nb = 0;
        float *va = vf_read_volume(a, volumes[v], 0, &na);
        float *vb = vf_read_volume(b, volumes[v], 0, &nb);
        assert_int_equal(na, RES);
        assert_int_equal(nb, RES);
        for (int i = 0; i < RES * RES * RES; i++)
            differ += memcmp(&va[4 * i], &vb[4 * i], 4 * sizeof(float)) != 0;
        free(va);
        free(vb);
    }
    return differ;
}

/* Occupied voxels (albedo alpha 1). */
static float *
occupancy(const vf_runner *r)
{
    int n = 0;
    return vf_read_volume(r, "vox.albedo", 0, &n);
}

/* The same world matrix change in both scenes' instance `i`. */
static void
set_world(hf_scene *a, hf_scene *b, int i, const float world[16])
{
    memcpy(a->instances[i].world, world, sizeof a->instances[i].world);
    memcpy(b->instances[i].world, world, sizeof b->instances[i].world);
}

static const float *
translation(float x, float y, float z)
{
    static float m[16];
    const float t[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1};
    memcpy(m, t, sizeof m);
    return m;
}

/* One frame of both runners; the cached one must report `want` and equal the whole rebuild. */
static void
step(vf_runner *cached, vf_runner *whole, const char *want, const char *what)
{
    vf_next_frame(cached);
    vf_next_frame(whole);
    if (!strstr(vf_rebuilt(cached, "vox"), want))
        fail_msg("%s: want '%s' in the report, got '%s'", what, want, vf_rebuilt(cached, "vox"));
    assert_string_equal(vf_rebuilt(whole, "vox"), "geometry voxelized (cache=false)");
    int differ = differing_voxels(cached, whole);
    printf("# %s: %s; %d voxels differ from cache=false\n", what, vf_rebuilt(cached, "vox"), differ);
    assert_int_equal(differ, 0);
}

static void
check_voxelizer(const char *voxelizer)
{
    printf("# voxelizer=%s\n", voxelizer);
    hf_scene cached_scene, whole_scene;
    make_scene(&cached_scene);
    make_scene(&whole_scene);
    vf_runner cached, whole;
    start(&cached, &cached_scene, true, voxelizer);
    start(&whole, &whole_scene, false, voxelizer);
    assert_non_null(strstr(vf_rebuilt(&cached, "vox"), "geometry voxelized (first frame"));
    assert_int_equal(differing_voxels(&cached, &whole), 0);
    float *before = occupancy(&cached);

    /* The wall slides along the terrain by about two voxels. */
    set_world(&cached_scene, &whole_scene, 1, translation(0.45f, 0.1f, 0.6f));
    step(&cached, &whole, "geometry re-voxelized in part (a voxelized instance changed: 1 region,", "wall moved");
    /* Voxels the wall occupied that still hold something: the terrain's, which its clearing must
     * not have erased (the comparison above checks their values; this checks that there are). */
    float *after = occupancy(&cached);
    int shared = 0, terrain_only = 0;
    for (int i = 0; i < RES * RES * RES; i++) {
        int z = i / (RES * RES), x = i % RES;
        /* the wall's old footprint: x in [-1, 0.3] m, z in [0.2, 0.6] m (4 voxels a metre from -4) */
        bool under_wall = x >= 12 && x <= 17 && z >= 16 && z <= 18;
        if (under_wall && before[4 * i + 3] == 1.0f) {
            shared++;
            terrain_only += after[4 * i + 3] == 1.0f;
        }
    }
    printf("# voxels under the wall's old place: %d occupied before, %d still occupied after it moved\n", shared,
           terrain_only);
    assert_true(terrain_only > 0);
    free(before);
    free(after);

    /* Turned by hand about the vertical (a quarter turn) and moved: no revision bumped. */
    static const float turned[16] = {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, -0.3f, 0.05f, 0.4f, 1};
    set_world(&cached_scene, &whole_scene, 1, turned);
    step(&cached, &whole, "geometry re-voxelized in part (a voxelized instance changed: 1 region,", "wall turned");

    /* Out of the volume, then back in. */
    set_world(&cached_scene, &whole_scene, 1, translation(20.0f, 0.0f, 0.0f));
    step(&cached, &whole, "geometry re-voxelized in part (a voxelized instance changed: 1 region,",
         "wall moved out of the volume");
    set_world(&cached_scene, &whole_scene, 1, translation(-0.2f, 0.0f, -0.1f));
    step(&cached, &whole, "geometry re-voxelized in part (a voxelized instance changed: 1 region,",
         "wall moved back in");

    /* Both quads move, apart: two regions. */
    set_world(&cached_scene, &whole_scene, 1, translation(0.3f, 0.0f, 0.0f));
    set_world(&cached_scene, &whole_scene, 2, translation(-0.2f, -0.1f, 0.3f));
    step(&cached, &whole, "geometry re-voxelized in part (a voxelized instance changed: 2 regions,",
         "wall and roof moved");

    step(&cached, &whole, "geometry kept (builds: 1 whole, 5 partial)", "nothing moved");

    /* The terrain is stretched fourfold in height: its box, before and after, is more than half the
     * volume, over the partial limit. */
    static const float stretched[16] = {1, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    set_world(&cached_scene, &whole_scene, 0, stretched);
    step(&cached, &whole, "geometry voxelized (a voxelized instance changed; changed regions",
         "terrain stretched");
    assert_non_null(strstr(vf_rebuilt(&cached, "vox"), "builds: 2 whole, 5 partial"));

    vf_stop(&cached);
    vf_stop(&whole);
    hf_free(&cached_scene);
    hf_free(&whole_scene);
}

static void
test_partial_equals_whole(void **state)
{
    (void)state;
    check_voxelizer("geometry");
    check_voxelizer("compute");
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_partial_equals_whole))
