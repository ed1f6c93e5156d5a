/* The radiance range: builtin:cornell and builtin:furnace (its floor a height field) lit from
 * 1e-6 to 1e9 W/m^2 through every graph of graphs/ (and the furnace through the hybrid graph
 * with a half-float 2D lightmap) give the image lit at 1 W/m^2 times the light's ratio: relMSE below 1e-3 after
 * dividing by it, no NaN or Inf, nothing stuck at the half-float maximum. A scene lit 1e5 times
 * brighter is 1e5 times brighter to rounding: relMSE below 1e-9, mean luminance within 1e-4 and
 * every pixel within 2e-3 (the voxels' fixed-point sums round dim fragments to whole units; the
 * raster and traced parts agree to 3e-7). Irradiance here is the spot's at the Cornell floor's
 * centre (2.1 W/m^2 x light_scale) and pi L in the furnace of emitted radiance L. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sweep_fixture.h"
#include "test_support.h"

#define WIDTH 48
#define HEIGHT 27
#define MAX_REL_MSE 1e-3

/* Five levels keep the test quick (CI runs it under the sanitizers too): the two ends, the unit,
 * 1e5 (the "exactly 1e5 times brighter"), and 1e-3, where half floats would be denormal. */
static const double irradiances[] = {1e-6, 1e-3, 1.0, 1e5, 1e9};
#define LEVEL_COUNT ((int)(sizeof irradiances / sizeof irradiances[0]))
#define UNIT_LEVEL 2
#define BRIGHT_LEVEL 3      /* 1e5 x the unit level: "exactly" 1e5 times brighter */
#define BRIGHT_REL_MSE 1e-9
#define BRIGHT_LUMINANCE 1e-4
#define BRIGHT_PIXEL 2e-3

typedef struct lit_scene {
    const char *format;         /* the scene with its light's parameter as %.17g */
    double irradiance_per_unit; /* W/m^2 for the parameter 1 */
} lit_scene;

#define CORNELL 0
#define FURNACE 1
static const lit_scene scenes[] = {
    [CORNELL] = {"builtin:cornell?light_scale=%.17g", 2.0 / (0.97 * 0.97)},
    [FURNACE] = {"builtin:furnace?heightfield=1&radiance=%.17g", M_PI},
};

static const char *const reference_overrides[] = {"trace.spp=16", NULL};
static const char *const half_lightmap[] = {"terrain.format=rgba16f", NULL};

/* The largest |a / k - b| / max(|b|, floor) over the RGB values of the pixels, floor = 1e-3 of the
 * image's largest value (so that black pixels compare absolutely). */
static double
max_relative_difference(const cg_image *a, const cg_image *b, double k)
{
    double top = 0.0, worst = 0.0;
    size_t n = (size_t)a->width * (size_t)a->height * 4;
    for (size_t i = 0; i < n; i++)
        if (i % 4 != 3)
            top = fmax(top, fabs(b->rgba[i]));
    for (size_t i = 0; i < n; i++)
        if (i % 4 != 3)
            worst = fmax(worst, fabs(a->rgba[i] / k - b->rgba[i]) / fmax(fabs(b->rgba[i]), 1e-3 * top));
    return worst;
}

static size_t
half_float_maxima(const cg_image *img)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)img->width * (size_t)img->height * 4; i++)
        n += i % 4 != 3 && img->rgba[i] == 65504.0f;
    return n;
}

/* The graph on scenes first..last. */
static int
check_configuration(const char *graph, const char *label, const char *const *overrides, int first, int last)
{
    int failures = 0;
    for (int sc = first; sc <= last; sc++) {
        cg_image images[LEVEL_COUNT] = {0};
        double parameters[LEVEL_COUNT];
        for (int i = 0; i < LEVEL_COUNT; i++) {
            char source[128];
            parameters[i] = irradiances[i] / scenes[sc].irradiance_per_unit;
            snprintf(source, sizeof source, scenes[sc].format, parameters[i]);
            if (sf_level_runs(i, LEVEL_COUNT, UNIT_LEVEL))
                images[i] = sf_render(source, graph, overrides, WIDTH, HEIGHT);
        }
        for (int i = 0; i < LEVEL_COUNT; i++) {
            if (!sf_level_runs(i, LEVEL_COUNT, UNIT_LEVEL))
                continue;
            double ratio = parameters[i] / parameters[UNIT_LEVEL];
            size_t bad = sf_nonfinite(&images[i]), stuck = half_float_maxima(&images[i]);
            cg_metrics m = sf_compare(&images[i], &images[UNIT_LEVEL], ratio);
            double worst = max_relative_difference(&images[i], &images[UNIT_LEVEL], ratio);
            print_message("# %-32.32s E = %-6g %-22s relMSE %.3g, max relative difference %.3g, mean luminance "
                          "ratio %.6f%s%s\n", scenes[sc].format, irradiances[i], label, m.rel_mse, worst,
                          m.mean_luminance_ratio, bad ? ", NOT FINITE" : "", stuck ? ", AT 65504" : "");
            if (bad || stuck || !(m.rel_mse < MAX_REL_MSE)) {
                print_error("%s at E = %g with %s: %zu non-finite values, %zu at 65504, relMSE %g (limit %g)\n",
                            scenes[sc].format, irradiances[i], label, bad, stuck, m.rel_mse, MAX_REL_MSE);
                failures++;
            }
            if (i == BRIGHT_LEVEL && !(m.rel_mse < BRIGHT_REL_MSE && fabs(m.mean_luminance_ratio - 1.0) < BRIGHT_LUMINANCE &&
                                       worst < BRIGHT_PIXEL)) {
                print_error("%s 1e5 times brighter with %s: relMSE %g (limit %g), mean luminance ratio %.7f (limit 1 +- "
                            "%g), worst pixel %g (limit %g)\n", scenes[sc].format, label, m.rel_mse, BRIGHT_REL_MSE,
                            m.mean_luminance_ratio, BRIGHT_LUMINANCE, worst, BRIGHT_PIXEL);
                failures++;
            }
        }
        for (int i = 0; i < LEVEL_COUNT; i++)
            cg_image_free(&images[i]);
    }
    return failures;
}

static void
test_every_graph_over_the_range(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    static char graphs[CG_TEST_MAX_GRAPHS][256];
    int graph_count = cg_test_list_graphs(graphs);
    assert_true(graph_count > 0);
    int failures = 0;
    for (int g = 0; g < graph_count; g++)
        failures += check_configuration(graphs[g], graphs[g], strcmp(graphs[g], "reference") ? NULL : reference_overrides,
                                        CORNELL, FURNACE);
    /* The furnace alone has a height field (Cornell's hybrid graph culls its 2D branch). */
    failures += check_configuration("hybrid", "hybrid, rgba16f terrain", half_lightmap, FURNACE, FURNACE);
    assert_no_gl_errors(ctx);
    assert_int_equal(failures, 0);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_every_graph_over_the_range))
