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
#include "vct_fixture.h"

#define SIZE 64

static void
test_cornell_direct(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_scene scene = cg_test_load_scene("builtin:cornell");
    /* The command-line override path, as `--set shadow.resolution=512` would take it. */
    static const char *const overrides[] = { "shadow.resolution=512", NULL };
    vf_runner r;
    vf_start_file(&r, &scene, SIZE, SIZE, "direct.json", overrides);
    vf_frame(&r);
    vf_next_frame(&r);
    fg_graph *graph = r.graph;
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
    vf_stop(&r);
    cg_scene_free(&scene);
    assert_no_gl_errors(ctx);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_cornell_direct))
