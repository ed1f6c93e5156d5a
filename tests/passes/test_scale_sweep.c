/* The scale sweep: builtin:furnace (its floor a height field) and builtin:cornell
 * scaled from 1e-6 m to 1e6 m, lights scaled to give the same irradiance, through every graph of
 * graphs/ (the path-traced reference with few samples and a fixed seed) give the image of scale 1:
 * relMSE below 1e-3, no NaN or Inf. An epsilon, bias, clamp or near plane in metres rather than
 * relative to the scene (or to the quantity it guards) shows here as a scale whose image drifts. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sweep_fixture.h"
#include "test_support.h"

#define WIDTH 48
#define HEIGHT 27
#define MAX_REL_MSE 1e-3

static const double scales[] = {1e-6, 1e-3, 1.0, 1e3, 1e6};
#define SCALE_COUNT ((int)(sizeof scales / sizeof scales[0]))
#define UNIT_SCALE 2

/* The reference with 16 samples per pixel: its fixed seed gives every scale the same random
 * numbers, so the images differ only where rounding moves a ray. */
static const char *const reference_overrides[] = {"trace.spp=16", NULL};

/* The furnace with its floor a height field: the VCT graphs voxelize it with the walls, the
 * hybrid graphs trace it through their 2D lightmap and HSAT. */
static const char *const scenes[] = {
    "builtin:furnace?heightfield=1&scale=%g",
    "builtin:cornell?scale=%g",
};

/* builtin:openworld has no scale parameter: scaled after loading, through the graphs that reach
 * what the box scenes lack (an orthographic shadow map for the sun, real terrain in the 2D
 * lightmap and HSAT, the 3D lightmap of its buildings); few triangles, to stay quick. */
static const char *const openworld = "builtin:openworld?triangles=5000";
/* The graphs for scenes scaled or moved after loading: direct light, VCT, hybrid. */
static const char *const placement_graphs[] = {"direct", "vct", "hybrid"};

static void
test_openworld_at_every_scale(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    int failures = 0;
    for (size_t g = 0; g < sizeof placement_graphs / sizeof placement_graphs[0]; g++) {
        cg_image images[SCALE_COUNT] = {0};
        for (int i = 0; i < SCALE_COUNT; i++)
            if (sf_level_runs(i, SCALE_COUNT, UNIT_SCALE))
                images[i] = sf_render_placed(openworld, scales[i], 0.0, placement_graphs[g], NULL, WIDTH, HEIGHT);
        for (int i = 0; i < SCALE_COUNT; i++) {
            if (!sf_level_runs(i, SCALE_COUNT, UNIT_SCALE))
                continue;
            size_t bad = sf_nonfinite(&images[i]);
            cg_metrics m = sf_compare(&images[i], &images[UNIT_SCALE], 1.0);
            print_message("# %s x %-8g %-13s relMSE %.3g, max |difference| %.3g, mean luminance %.6g (ratio %.6f)%s\n",
                          openworld, scales[i], placement_graphs[g], m.rel_mse, m.max_error, m.mean_luminance_test,
                          m.mean_luminance_ratio, bad ? ", NOT FINITE" : "");
            if (bad || !(m.rel_mse < MAX_REL_MSE)) {
                print_error("%s scaled by %g with %s.json: %zu non-finite values, relMSE %g against scale 1 (limit %g)\n",
                            openworld, scales[i], placement_graphs[g], bad, m.rel_mse, MAX_REL_MSE);
                failures++;
            }
        }
        for (int i = 0; i < SCALE_COUNT; i++)
            cg_image_free(&images[i]);
    }
    assert_no_gl_errors(ctx);
    assert_int_equal(failures, 0);
}

/* Scale-free is not translation-free: positions are fp32 world coordinates, whose rounding grows
 * with the distance from the origin, not with the scene. The 1 m Cornell box 100 and 1000 m away
 * along each axis (1e3 box sizes) must still give the image at the origin; beyond that the fp32
 * G-buffer positions, 2^-24 of the distance, near the shadow bias (docs/architecture.md). Before
 * the shadow map's depth pass applied its view and projection apart, the box at 60-100 m was
 * shadowed everywhere. */
static const double offsets[] = {1e2, 1e3};

static void
test_cornell_away_from_the_origin(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    int failures = 0;
    for (size_t g = 0; g < sizeof placement_graphs / sizeof placement_graphs[0]; g++) {
        cg_image at_origin = sf_render("builtin:cornell", placement_graphs[g], NULL, WIDTH, HEIGHT);
        for (size_t i = 0; i < sizeof offsets / sizeof offsets[0]; i++) {
            cg_image moved = sf_render_placed("builtin:cornell", 1.0, offsets[i], placement_graphs[g], NULL, WIDTH, HEIGHT);
            size_t bad = sf_nonfinite(&moved);
            cg_metrics m = sf_compare(&moved, &at_origin, 1.0);
            print_message("# builtin:cornell moved %g m along each axis, %-7s relMSE %.3g, max |difference| %.3g, "
                          "mean luminance ratio %.6f%s\n", offsets[i], placement_graphs[g], m.rel_mse, m.max_error,
                          m.mean_luminance_ratio, bad ? ", NOT FINITE" : "");
            if (bad || !(m.rel_mse < MAX_REL_MSE)) {
                print_error("builtin:cornell moved %g m with %s.json: %zu non-finite values, relMSE %g (limit %g)\n",
                            offsets[i], placement_graphs[g], bad, m.rel_mse, MAX_REL_MSE);
                failures++;
            }
            cg_image_free(&moved);
        }
        cg_image_free(&at_origin);
    }
    assert_no_gl_errors(ctx);
    assert_int_equal(failures, 0);
}

static void
test_every_graph_at_every_scale(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    static char graphs[CG_TEST_MAX_GRAPHS][256];
    int graph_count = cg_test_list_graphs(graphs);
    assert_true(graph_count > 0);
    int failures = 0;
    for (size_t sc = 0; sc < sizeof scenes / sizeof scenes[0]; sc++)
        for (int g = 0; g < graph_count; g++) {
            cg_image images[SCALE_COUNT] = {0};
            for (int i = 0; i < SCALE_COUNT; i++) {
                if (!sf_level_runs(i, SCALE_COUNT, UNIT_SCALE))
                    continue;
                char source[128];
                snprintf(source, sizeof source, scenes[sc], scales[i]);
                images[i] = sf_render(source, graphs[g], strcmp(graphs[g], "reference") ? NULL : reference_overrides,
                                      WIDTH, HEIGHT);
            }
            for (int i = 0; i < SCALE_COUNT; i++) {
                if (!sf_level_runs(i, SCALE_COUNT, UNIT_SCALE))
                    continue;
                char source[128];
                snprintf(source, sizeof source, scenes[sc], scales[i]);
                size_t bad = sf_nonfinite(&images[i]);
                cg_metrics m = sf_compare(&images[i], &images[UNIT_SCALE], 1.0);
                print_message("# %-44s %-13s relMSE %.3g, max |difference| %.3g, mean luminance %.6g (ratio %.6f)%s\n",
                              source, graphs[g], m.rel_mse, m.max_error, m.mean_luminance_test,
                              m.mean_luminance_ratio, bad ? ", NOT FINITE" : "");
                if (bad || !(m.rel_mse < MAX_REL_MSE)) {
                    print_error("%s with %s.json: %zu non-finite values, relMSE %g against scale 1 (limit %g)\n",
                                source, graphs[g], bad, m.rel_mse, MAX_REL_MSE);
                    failures++;
                }
            }
            for (int i = 0; i < SCALE_COUNT; i++)
                cg_image_free(&images[i]);
        }
    assert_no_gl_errors(ctx);
    assert_int_equal(failures, 0);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_every_graph_at_every_scale),
             cmocka_unit_test(test_openworld_at_every_scale),
             cmocka_unit_test(test_cornell_away_from_the_origin))
