/* Unit tests of the image metrics on image pairs whose answers are known in closed form. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/metrics.h"
#include "test_support.h"

enum { W = 48, H = 32 };

static cg_image
image_new(int w, int h)
{
    cg_image img = { w, h, calloc((size_t)w * h * 4, sizeof(float)) };
    assert_non_null(img.rgba);
    return img;
}

static void
image_release(cg_image *img)
{
    free(img->rgba);
    img->rgba = NULL;
}

static void
fill_constant(cg_image *img, float v)
{
    for (int i = 0; i < img->width * img->height; i++) {
        img->rgba[4 * i + 0] = img->rgba[4 * i + 1] = img->rgba[4 * i + 2] = v;
        img->rgba[4 * i + 3] = 1.0f;
    }
}

/* A smooth colour ramp with some structure, all values in (0, 1). */
static void
fill_pattern(cg_image *img)
{
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < img->width; x++) {
            float *p = &img->rgba[4 * (y * img->width + x)];
            p[0] = 0.05f + 0.9f * (float)x / (float)img->width;
            p[1] = 0.05f + 0.9f * (float)y / (float)img->height;
            p[2] = ((x / 4 + y / 4) & 1) ? 0.8f : 0.1f;
            p[3] = 1.0f;
        }
}

static double
srgb_encode(double y)
{
    return y <= 0.0031308 ? 12.92 * y : 1.055 * pow(y, 1.0 / 2.4) - 0.055;
}

static void
identical_images_have_zero_error(void **state)
{
    (void)state;
    cg_image a = image_new(W, H), b = image_new(W, H);
    fill_pattern(&a);
    fill_pattern(&b);
    cg_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_compute(&a, &b, &m, &err), &err);
    assert_int_equal(m.width, W);
    assert_true(m.rmse == 0.0 && m.rel_mse == 0.0 && m.max_error == 0.0);
    assert_float_equal(m.ssim, 1.0, 1e-12);
    assert_float_equal(m.mean_luminance_ratio, 1.0, 1e-12);
    assert_int_equal(m.nonfinite_pixels, 0);
    image_release(&a);
    image_release(&b);
}

static void
constant_offset_gives_closed_form(void **state)
{
    (void)state;
    const float r = 0.25f, c = 0.05f;
    cg_image t = image_new(W, H), ref = image_new(W, H);
    fill_constant(&ref, r);
    fill_constant(&t, r + c);
    cg_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_compute(&t, &ref, &m, &err), &err);
    double d = (double)(r + c) - (double)r; /* c as the float sum rounds it */
    assert_float_equal(m.rmse, d, 1e-9);
    assert_float_equal(m.max_error, d, 1e-9);
    assert_float_equal(m.rel_mse, d * d / ((double)r * r + 0.01), 1e-9);
    assert_float_equal(m.mean_luminance_ratio, (double)(r + c) / r, 1e-6);
    /* Uniform images: both variances vanish and SSIM is its luminance term alone. */
    double mx = srgb_encode(r + c), my = srgb_encode(r), c1 = 0.01 * 0.01;
    assert_float_equal(m.ssim, (2 * mx * my + c1) / (mx * mx + my * my + c1), 1e-6);
    assert_true(m.ssim < 1.0);
    image_release(&t);
    image_release(&ref);
}

static void
scaled_image_gives_closed_form(void **state)
{
    (void)state;
    const double s = 1.5;
    cg_image t = image_new(W, H), ref = image_new(W, H);
    fill_pattern(&ref);
    fill_pattern(&t);
    double sq = 0.0, rel = 0.0, max_r = 0.0, lum = 0.0;
    for (int i = 0; i < W * H; i++) {
        for (int c = 0; c < 3; c++) {
            double r = ref.rgba[4 * i + c];
            t.rgba[4 * i + c] = (float)(s * r);
            double d = (double)t.rgba[4 * i + c] - r;
            sq += d * d;
            rel += d * d / (r * r + 0.01);
            if (r > max_r)
                max_r = r;
        }
        lum += cg_luminance(&ref.rgba[4 * i]);
    }
    cg_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_compute(&t, &ref, &m, &err), &err);
    assert_float_equal(m.rmse, sqrt(sq / (3.0 * W * H)), 1e-9);
    assert_float_equal(m.rel_mse, rel / (3.0 * W * H), 1e-9);
    assert_float_equal(m.max_error, (s - 1.0) * max_r, 1e-6);
    assert_float_equal(m.mean_luminance_ratio, s, 1e-6);
    assert_float_equal(m.mean_luminance_ref, lum / (W * H), 1e-9);
    assert_true(m.ssim > 0.5 && m.ssim < 1.0);
    image_release(&t);
    image_release(&ref);
}

static void
nonfinite_pixels_are_counted_and_left_out(void **state)
{
    (void)state;
    cg_image t = image_new(W, H), ref = image_new(W, H);
    fill_constant(&ref, 0.5f);
    fill_constant(&t, 0.5f);
    t.rgba[4 * 3 + 1] = NAN;
    t.rgba[4 * 10 + 0] = INFINITY;
    ref.rgba[4 * 20 + 2] = NAN;
    cg_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_compute(&t, &ref, &m, &err), &err);
    assert_int_equal(m.nonfinite_pixels, 3);
    assert_int_equal(m.nonfinite_test, 2);
    assert_true(m.rmse == 0.0 && m.max_error == 0.0);
    assert_float_equal(m.mean_luminance_ratio, 1.0, 1e-12);
    image_release(&t);
    image_release(&ref);
}

static void
black_reference_ratio(void **state)
{
    (void)state;
    cg_image t = image_new(8, 8), ref = image_new(8, 8);
    fill_constant(&ref, 0.0f);
    fill_constant(&t, 0.0f);
    cg_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_compute(&t, &ref, &m, &err), &err);
    assert_float_equal(m.mean_luminance_ratio, 1.0, 0.0);
    fill_constant(&t, 0.1f);
    assert_cg_ok(cg_metrics_compute(&t, &ref, &m, &err), &err);
    assert_true(isinf(m.mean_luminance_ratio));
    /* eps = 0.01 bounds the relative error of a black reference: 0.1^2 / 0.01 = 1. */
    assert_float_equal(m.rel_mse, 1.0, 1e-6);
    image_release(&t);
    image_release(&ref);
}

static void
size_mismatch_is_an_image_format_error(void **state)
{
    (void)state;
    cg_image a = image_new(W, H), b = image_new(W, H + 1);
    cg_metrics m;
    cg_image out;
    cg_error err = { 0 };
    assert_cg_status(cg_metrics_compute(&a, &b, &m, &err), &err, CG_ERR_IMAGE_FORMAT);
    assert_cg_status(cg_image_subtract(&a, &b, &out, &err), &err, CG_ERR_IMAGE_FORMAT);
    assert_cg_status(cg_metrics_heatmap(&a, &b, 1.0, &out, &err), &err, CG_ERR_IMAGE_FORMAT);
    image_release(&a);
    image_release(&b);
}

static void
subtract_gives_the_indirect_part(void **state)
{
    (void)state;
    cg_image full = image_new(W, H), direct = image_new(W, H), indirect;
    fill_pattern(&full);
    fill_constant(&direct, 0.05f);
    cg_error err = { 0 };
    assert_cg_ok(cg_image_subtract(&full, &direct, &indirect, &err), &err);
    for (int i = 0; i < W * H * 4; i++)
        assert_float_equal(indirect.rgba[i], (i & 3) == 3 ? 1.0f : full.rgba[i] - 0.05f, 0.0);
    image_release(&full);
    image_release(&direct);
    image_release(&indirect);
}

/* Half the pixels 0.25, half 0.75 (grey): mean 0.5, mean square 0.3125. */
static void
fill_halves(cg_image *img)
{
    fill_constant(img, 0.25f);
    for (int i = 0; i < img->width * img->height / 2; i++)
        img->rgba[4 * i + 0] = img->rgba[4 * i + 1] = img->rgba[4 * i + 2] = 0.75f;
}

static void
part_metrics_of_a_known_pair(void **state)
{
    (void)state;
    cg_image est = image_new(W, H), truth = image_new(W, H);
    fill_halves(&truth);
    fill_constant(&est, 0.375f);
    cg_part_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_part(&est, &truth, &m, &err), &err);
    /* energy 0.375 / 0.5; rmse^2 = (0.125^2 + 0.375^2) / 2 = 0.078125 against 0.3125: nrmse 0.5. */
    assert_int_equal(m.width, W);
    assert_int_equal(m.height, H);
    assert_float_equal(m.energy, 0.75, 1e-12);
    assert_float_equal(m.rmse, sqrt(0.078125), 1e-12);
    assert_float_equal(m.rms_truth, sqrt(0.3125), 1e-12);
    assert_float_equal(m.nrmse, 0.5, 1e-12);
    assert_float_equal(m.mean_luminance_estimate, 0.375, 1e-12);
    assert_float_equal(m.mean_luminance_truth, 0.5, 1e-12);
    assert_int_equal(m.nonfinite_pixels, 0);
    /* Colour: energy weighs luminance, nrmse the RGB channels alike. Red against green:
     * energy 0.7152 / 0.2126, rmse^2 = 2/3 against 1/3. */
    for (int i = 0; i < W * H; i++) {
        float *t = &truth.rgba[4 * i], *e = &est.rgba[4 * i];
        t[0] = 1.0f, t[1] = t[2] = 0.0f;
        e[1] = 1.0f, e[0] = e[2] = 0.0f;
    }
    assert_cg_ok(cg_metrics_part(&est, &truth, &m, &err), &err);
    assert_float_equal(m.energy, 0.7152 / 0.2126, 1e-12);
    assert_float_equal(m.nrmse, sqrt(2.0), 1e-12);
    image_release(&est);
    image_release(&truth);
}

/* Leaving the part out is exactly nrmse 1 and energy 0; the truth itself exactly 0 and 1. */
static void
part_metrics_of_nothing_and_of_the_truth(void **state)
{
    (void)state;
    cg_image zero = image_new(W, H), truth = image_new(W, H);
    fill_pattern(&truth);
    cg_part_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_part(&zero, &truth, &m, &err), &err);
    assert_true(m.nrmse == 1.0);
    assert_true(m.energy == 0.0);
    assert_true(m.rmse == m.rms_truth);
    assert_cg_ok(cg_metrics_part(&truth, &truth, &m, &err), &err);
    assert_true(m.nrmse == 0.0);
    assert_true(m.energy == 1.0);
    image_release(&zero);
    image_release(&truth);
}

/* A truth of 0 (a scene without indirect light): defined values, not NaN. */
static void
part_metrics_against_a_black_truth(void **state)
{
    (void)state;
    cg_image est = image_new(W, H), truth = image_new(W, H);
    cg_part_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_part(&est, &truth, &m, &err), &err);
    assert_true(m.energy == 1.0);
    assert_true(m.nrmse == 0.0);
    est.rgba[0] = 0.5f;
    assert_cg_ok(cg_metrics_part(&est, &truth, &m, &err), &err);
    assert_true(isinf(m.energy) && m.energy > 0.0);
    assert_true(isinf(m.nrmse) && m.nrmse > 0.0);
    est.rgba[0] = -0.5f;
    assert_cg_ok(cg_metrics_part(&est, &truth, &m, &err), &err);
    assert_true(isinf(m.energy) && m.energy < 0.0);
    image_release(&est);
    image_release(&truth);
}

static void
part_metrics_leave_nonfinite_pixels_out(void **state)
{
    (void)state;
    cg_image est = image_new(W, H), truth = image_new(W, H), small = image_new(W, H + 1);
    fill_constant(&truth, 0.5f);
    fill_constant(&est, 0.5f);
    est.rgba[0] = NAN;
    truth.rgba[4 * 7 + 2] = INFINITY;
    cg_part_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_part(&est, &truth, &m, &err), &err);
    assert_int_equal(m.nonfinite_pixels, 2);
    assert_true(m.nrmse == 0.0);
    assert_true(m.energy == 1.0);
    for (int i = 0; i < W * H; i++)
        est.rgba[4 * i] = NAN;
    assert_cg_ok(cg_metrics_part(&est, &truth, &m, &err), &err);
    assert_int_equal(m.nonfinite_pixels, W * H);
    assert_true(isnan(m.energy) && isnan(m.nrmse));
    assert_cg_status(cg_metrics_part(&est, &small, &m, &err), &err, CG_ERR_IMAGE_FORMAT);
    image_release(&est);
    image_release(&truth);
    image_release(&small);
}

static void
heatmap_is_dark_where_equal_and_bright_where_wrong(void **state)
{
    (void)state;
    cg_image t = image_new(W, H), ref = image_new(W, H), map;
    fill_constant(&ref, 0.5f);
    fill_constant(&t, 0.5f);
    t.rgba[0] = 5.0f;                    /* pixel 0: far off */
    t.rgba[4 * 1 + 0] = NAN;             /* pixel 1: not finite */
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_heatmap(&t, &ref, 1.0, &map, &err), &err);
    assert_true(map.rgba[4 * 5 + 0] < 0.01f && map.rgba[4 * 5 + 1] < 0.01f);
    assert_true(map.rgba[0] > 0.9f && map.rgba[1] > 0.9f);
    assert_float_equal(map.rgba[4 + 0], 1.0f, 0.0);
    assert_float_equal(map.rgba[4 + 1], 0.0f, 0.0);
    image_release(&t);
    image_release(&ref);
    image_release(&map);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(identical_images_have_zero_error),
             cmocka_unit_test(constant_offset_gives_closed_form),
             cmocka_unit_test(scaled_image_gives_closed_form),
             cmocka_unit_test(nonfinite_pixels_are_counted_and_left_out),
             cmocka_unit_test(black_reference_ratio),
             cmocka_unit_test(size_mismatch_is_an_image_format_error),
             cmocka_unit_test(subtract_gives_the_indirect_part),
             cmocka_unit_test(heatmap_is_dark_where_equal_and_bright_where_wrong),
             cmocka_unit_test(part_metrics_of_a_known_pair),
             cmocka_unit_test(part_metrics_of_nothing_and_of_the_truth),
             cmocka_unit_test(part_metrics_against_a_black_truth),
             cmocka_unit_test(part_metrics_leave_nonfinite_pixels_out))
