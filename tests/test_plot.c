/* The bench plots (apps/conegraph/bench/plot.c): markers land in the right order on linear and
 * log axes, unusable points are skipped, rings and lines are drawn. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../apps/conegraph/bench/plot.h"
#include "test_support.h"

static float
srgb_to_linear(float v)
{
    return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

/* Centroid of the pixels of exactly colour c (sRGB); returns the count. */
static int
centroid(const cg_image *img, const float c[3], double *cx, double *cy)
{
    int n = 0;
    double sx = 0, sy = 0;
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++) {
            const float *p = &img->rgba[4 * (y * img->width + x)];
            if (fabsf(p[0] - srgb_to_linear(c[0])) < 1e-6f && fabsf(p[1] - srgb_to_linear(c[1])) < 1e-6f &&
                fabsf(p[2] - srgb_to_linear(c[2])) < 1e-6f) {
                n++;
                sx += x;
                sy += y;
            }
        }
    if (n) {
        *cx = sx / n;
        *cy = sy / n;
    }
    return n;
}

static void
markers_follow_the_data(void **state)
{
    (void)state;
    for (int log_axes = 0; log_axes < 2; log_axes++) {
        const double x1[] = { 1.0 }, y1[] = { 100.0 };        /* left, high */
        const double x2[] = { 50.0, -1.0 }, y2[] = { 0.5, NAN }; /* right, low; then unusable */
        plot_series series[2] = {
            { .color = { 1, 0, 0 }, .x = x1, .y = y1, .count = 1 },
            { .color = { 0, 0, 1 }, .x = x2, .y = y2, .count = 2 },
        };
        plot_desc plot = { .title = "test", .xlabel = "x", .ylabel = "y", .logx = log_axes, .logy = log_axes,
                           .series = series, .series_count = 2, .width = 400, .height = 300 };
        cg_image img = { 0 };
        cg_error err = { 0 };
        assert_cg_ok(plot_render(&plot, &img, &err), &err);
        assert_int_equal(img.width, 400);
        double rx, ry, bx, by;
        assert_int_equal(centroid(&img, series[0].color, &rx, &ry), 49); /* one 7x7 marker */
        assert_int_equal(centroid(&img, series[1].color, &bx, &by), 49); /* the NaN point is skipped */
        assert_true(rx < bx);   /* smaller x is further left */
        assert_true(ry < by);   /* larger y is higher up (smaller row) */
        cg_image_free(&img);
    }
}

static void
rings_and_lines_are_drawn(void **state)
{
    (void)state;
    const double x[] = { 3, 1, 2 }, y[] = { 1, 3, 2 };
    plot_series series[1] = { { .name = "front", .color = { 0, 0.5f, 0 }, .x = x, .y = y, .count = 3,
                                .line = true, .ring = true } };
    plot_desc plot = { .series = series, .series_count = 1 };
    cg_image img = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(plot_render(&plot, &img, &err), &err);
    assert_int_equal(img.width, 960);
    double cx, cy;
    /* Three rings, two line segments and the legend's ring: well over a few hundred pixels. */
    assert_true(centroid(&img, series[0].color, &cx, &cy) > 300);
    cg_image_free(&img);
}

/* The dark grey (label) pixels of four points, the first two 1% of the y axis apart, with
 * these labels; *cx: their mean column. */
static int
label_pixels(const char *const labels[4], double *cx)
{
    static const float label_grey[3] = { 0.25f, 0.25f, 0.25f };
    const double x[] = { 2.0, 2.0, 8.0, 8.0 }, y[] = { 5.0, 5.1, 0.0, 10.0 };
    plot_series series[1] = { { .color = { 0, 0, 1 }, .x = x, .y = y, .count = 4, .labels = labels } };
    plot_desc plot = { .series = series, .series_count = 1, .width = 400, .height = 300 };
    cg_image img = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(plot_render(&plot, &img, &err), &err);
    double cy;
    int n = centroid(&img, label_grey, cx, &cy);
    cg_image_free(&img);
    return n;
}

/* Each marker shape covers its own set of pixels (a square: 7x7 in the colour); a label is
 * drawn beside its point in dark grey, and a second label that would cover the first goes
 * elsewhere. */
static void
markers_and_labels(void **state)
{
    (void)state;
    enum { W = 200, H = 150 };
    static const float red[3] = { 1, 0, 0 };
    static bool masks[PLOT_MARKER_COUNT][W * H];
    for (int m = 0; m < PLOT_MARKER_COUNT; m++) {
        const double x[] = { 1.0 }, y[] = { 1.0 };
        const plot_marker markers[] = { (plot_marker)m };
        plot_series series[1] = { { .color = { 1, 0, 0 }, .x = x, .y = y, .count = 1, .markers = markers } };
        plot_desc plot = { .series = series, .series_count = 1, .width = W, .height = H };
        cg_image img = { 0 };
        cg_error err = { 0 };
        assert_cg_ok(plot_render(&plot, &img, &err), &err);
        double cx, cy;
        int count = centroid(&img, red, &cx, &cy);
        assert_true(count > 0);
        if (m == PLOT_SQUARE)
            assert_int_equal(count, 49);
        for (int i = 0; i < W * H; i++)
            masks[m][i] = fabsf(img.rgba[4 * i] - 1.0f) < 1e-6f && img.rgba[4 * i + 1] == 0.0f;
        cg_image_free(&img);
    }
    for (int a = 0; a < PLOT_MARKER_COUNT; a++)
        for (int b = a + 1; b < PLOT_MARKER_COUNT; b++)
            assert_true(memcmp(masks[a], masks[b], sizeof masks[a]) != 0);

    /* Two points close together, both labelled: each label is drawn whole, clear of the other. */
    static const char *const both[] = { "A=1", "A=2", "", "" }, *first[] = { "A=1", "", "", "" },
                             *second[] = { "", "A=2", "", "" };
    double cx;
    int n1 = label_pixels(first, &cx);
    assert_true(n1 > 0);
    assert_true(cx < 200);  /* beside its point at x = 2 of 0..10: in the left half */
    int n2 = label_pixels(second, &cx);
    assert_true(n2 > 0);
    assert_int_equal(label_pixels(both, &cx), n1 + n2);
}

/* The dark grey (label) pixels of a plot of `count` points at one spot, each labelled. */
static int
crowded_label_pixels(int count)
{
    static const float label_grey[3] = { 0.25f, 0.25f, 0.25f };
    double x[16], y[16];
    const char *labels[16];
    static const char *const names[16] = { "first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth",
                                           "ninth", "tenth", "eleventh", "twelfth", "a", "b", "c", "d" };
    for (int i = 0; i < count; i++) {
        x[i] = 5.0;
        y[i] = 5.0 + 0.01 * i;
        labels[i] = names[i];
    }
    const double corners_x[] = { 0.0, 10.0 }, corners_y[] = { 0.0, 10.0 };
    plot_series series[2] = { { .color = { 0, 0, 1 }, .x = x, .y = y, .count = count, .labels = labels },
                              { .color = { 0, 1, 0 }, .x = corners_x, .y = corners_y, .count = 2 } };
    plot_desc plot = { .series = series, .series_count = 2, .width = 400, .height = 300 };
    cg_image img = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(plot_render(&plot, &img, &err), &err);
    double cx, cy;
    int n = centroid(&img, label_grey, &cx, &cy);
    cg_image_free(&img);
    return n;
}

/* Twelve points on one spot: every one gets its label (moved farther out where the near places
 * are taken), so the labels' pixels are about the sum of each label drawn alone. */
static void
every_point_is_labelled(void **state)
{
    (void)state;
    int alone = 0;
    for (int k = 0; k < 12; k++) {
        /* Label k alone: the first k + 1 points, labels counted from a plot of only k + 1, less
         * the plot of k. */
        alone += crowded_label_pixels(k + 1) - (k ? crowded_label_pixels(k) : 0);
    }
    int together = crowded_label_pixels(12);
    if (together < alone * 9 / 10)
        fail_msg("twelve labels on one spot draw %d pixels, alone they would draw %d", together, alone);
}

/* Lower case is drawn as lower case: "axis" and "AXIS" as titles differ. */
static void
lower_case_has_its_own_glyphs(void **state)
{
    (void)state;
    const double x[] = { 1.0 }, y[] = { 1.0 };
    plot_series series[1] = { { .color = { 1, 0, 0 }, .x = x, .y = y, .count = 1 } };
    cg_image a = { 0 }, b = { 0 };
    cg_error err = { 0 };
    plot_desc plot = { .title = "axis", .series = series, .series_count = 1, .width = 200, .height = 150 };
    assert_cg_ok(plot_render(&plot, &a, &err), &err);
    plot.title = "AXIS";
    assert_cg_ok(plot_render(&plot, &b, &err), &err);
    /* The title's band, the top 30 rows. */
    assert_true(memcmp(a.rgba, b.rgba, sizeof(float) * 4 * 200 * 30) != 0);
    cg_image_free(&a);
    cg_image_free(&b);
}

/* A named series gets one legend entry (its marker once more); a series without a name none. */
static void
legend_beside_the_plot(void **state)
{
    (void)state;
    const double x[] = { 1.0, 2.0 }, y[] = { 1.0, 2.0 };
    double with_name = 0, without = 0, unnamed = 0, cy;
    (void)with_name;
    for (int k = 0; k < 3; k++) {
        plot_series series[1] = { { .name = k == 0 ? "a method" : NULL, .color = { 1, 0, 0 }, .x = x, .y = y,
                                    .count = 2 } };
        plot_desc plot = { .series = series, .series_count = 1, .width = 400, .height = 300 };
        cg_image img = { 0 };
        cg_error err = { 0 };
        assert_cg_ok(plot_render(&plot, &img, &err), &err);
        double *cx = k == 0 ? &with_name : k == 1 ? &without : &unnamed;
        int n = centroid(&img, series[0].color, cx, &cy);
        assert_int_equal(n, k == 0 ? 3 * 49 : 2 * 49); /* two points, and the legend's marker */
        cg_image_free(&img);
    }
    assert_true(fabs(without - unnamed) < 1e-9);
}

/* The error heat map with its colour scale: the map on top (black where the images agree),
 * widened to 360 pixels in white, the bar beneath from black (0) to light yellow (the max). */
static void
heatmap_has_its_colour_scale(void **state)
{
    (void)state;
    cg_image test = { 0 }, ref = { 0 }, out = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(cg_image_alloc(&test, 32, 24, &err), &err);
    assert_cg_ok(cg_image_alloc(&ref, 32, 24, &err), &err);
    for (int i = 0; i < 32 * 24 * 4; i++)
        test.rgba[i] = ref.rgba[i] = 0.5f;
    assert_cg_ok(plot_error_heatmap(&test, &ref, 1.0, &out, &err), &err);
    assert_int_equal(out.width, 360);
    assert_true(out.height > 24 + 30);
    const float *agree = &out.rgba[4 * (5 * 360 + 5)], *pad = &out.rgba[4 * (5 * 360 + 100)];
    assert_true(agree[0] < 0.01f && agree[1] < 0.01f);
    assert_true(pad[0] == 1.0f && pad[1] == 1.0f && pad[2] == 1.0f);
    const float *left = &out.rgba[4 * ((24 + 10) * 360 + 13)], *right = &out.rgba[4 * ((24 + 10) * 360 + 346)];
    assert_true(left[0] < 0.01f);
    assert_true(right[0] > 0.9f && right[1] > 0.9f);
    cg_image_free(&test);
    cg_image_free(&ref);
    cg_image_free(&out);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(markers_follow_the_data),
             cmocka_unit_test(rings_and_lines_are_drawn),
             cmocka_unit_test(markers_and_labels),
             cmocka_unit_test(every_point_is_labelled),
             cmocka_unit_test(lower_case_has_its_own_glyphs),
             cmocka_unit_test(legend_beside_the_plot),
             cmocka_unit_test(heatmap_has_its_colour_scale))
