/* End to end: builtin:cornell through graphs/direct.json at 64x64, as `conegraph render`
 * runs it, gives a sane image: finite, non-negative, lit where the box is, with the
 * tonemapped output consistent with the linear one. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/builtin.h"
#include "cg/camera.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/graphfile.h"
#include "cg/scene.h"
#include "test_support.h"

#define SIZE 64

static void
test_cornell_direct(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_error err = { 0 };
    cg_scene scene;
    assert_cg_ok(cg_scene_load("builtin:cornell", &scene, &err), &err);
    int camera;
    assert_cg_ok(cg_camera_select(&scene, NULL, &camera, &err), &err);
    fg_frame frame = { .scene = &scene, .width = SIZE, .height = SIZE };
    cg_view_from_scene(&scene, camera, SIZE, SIZE, &frame.view);

    fg_registry *registry = fg_registry_create();
    assert_cg_ok(cg_builtin_passes_register(registry, &err), &err);
    fg_graph *graph = fg_graph_create(registry);
    assert_cg_ok(fg_graph_load_file(graph, cg_test_graph_path("direct.json"), &err), &err);
    /* The command-line override path, as `--set shadow.resolution=512` would take it. */
    assert_cg_ok(fg_graph_apply_override(graph, "shadow.resolution=512", &err), &err);

    cg_gpu_scene gpu;
    assert_cg_ok(cg_gpu_scene_upload(&scene, &gpu, &err), &err);
    frame.gpu_scene = &gpu;
    fg_compile_options options = { 0 };
    assert_cg_ok(fg_graph_compile(graph, &frame, &options, &err), &err);
    assert_cg_ok(fg_graph_prepare(graph, &err), &err);
    for (int f = 0; f < 2; f++) {
        frame.index = (uint64_t)f;
        assert_cg_ok(fg_graph_execute(graph, &frame, FG_TIMING_SYNC, &err), &err);
    }
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    /* The box is lit by a light a shadow map can serve: the shadow pass must be live. */
    for (int i = 0; i < fg_graph_pass_count(graph); i++)
        if (!strcmp(fg_pass_type_of(fg_graph_pass_at(graph, i))->name, "shadow_map"))
            assert_false(fg_pass_is_culled(fg_graph_pass_at(graph, i)));

    int w, h;
    float *hdr = cg_test_read_texture(fg_graph_texture(graph, "final.hdr"), 0, &w, &h, NULL);
    float *ldr = cg_test_read_texture(fg_graph_texture(graph, "final.ldr"), 0, NULL, NULL, NULL);
    assert_int_equal(w, SIZE);
    assert_int_equal(h, SIZE);
    int lit = 0;
    double sum = 0.0;
    for (int i = 0; i < SIZE * SIZE; i++) {
        double l = 0.0;
        for (int c = 0; c < 3; c++) {
            float v = hdr[4 * i + c];
            if (!isfinite(v) || v < 0.0f)
                fail_msg("pixel %d channel %d is %g", i, c, v);
            l += v;
            /* Tonemapping is monotonic and maps 0 to 0. */
            if (v == 0.0f)
                assert_float_equal(ldr[4 * i + c], 0.0, 0.0);
        }
        sum += l;
        lit += l > 1e-4;
    }
    /* The camera looks into the box lit by a spot from the ceiling: the ceiling and the
     * boxes' shadows are dark; the floor, the walls and the boxes' tops are lit. */
    if (lit < SIZE * SIZE / 3)
        fail_msg("%d of %d pixels lit", lit, SIZE * SIZE);
    assert_true(sum / (SIZE * SIZE) > 1e-3);
    free(hdr);
    free(ldr);
    fg_graph_destroy(graph);
    cg_gpu_scene_destroy(&gpu);
    fg_registry_destroy(registry);
    cg_scene_free(&scene);
    assert_no_gl_errors(ctx);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_cornell_direct))
