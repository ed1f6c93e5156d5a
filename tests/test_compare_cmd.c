/* `conegraph compare` end to end: known image pairs written as EXR, the command's JSON
 * figures and exit codes checked. The executable comes from $CONEGRAPH_EXE (tests/meson.build). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "cg/image.h"
#include "test_support.h"

enum { W = 32, H = 24 };

static const char *
write_constant(const char *name, float v, int w, int h)
{
    cg_image img = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(cg_image_alloc(&img, w, h, &err), &err);
    for (int i = 0; i < w * h; i++) {
        img.rgba[4 * i] = img.rgba[4 * i + 1] = img.rgba[4 * i + 2] = v;
        img.rgba[4 * i + 3] = 1.0f;
    }
    const char *path = cg_test_tmp_path(name);
    assert_cg_ok(cg_image_write(path, &img, CG_EXR_FLOAT, &err), &err);
    cg_image_free(&img);
    return path;
}

/* Runs conegraph with `args`; returns the exit code. */
static int
run(const char *args, char *out, size_t size)
{
    return cg_test_run_conegraph(args, false, out, size);
}

/* An 8-bit sRGB PNG beside a linear EXR: refused with exit 2, naming both and the way out;
 * two PNGs, or two EXRs, are compared. */
static void
display_image_beside_linear_one_is_refused(void **state)
{
    (void)state;
    const char *exr = write_constant("lin.exr", 0.2f, W, H);
    const char *png = write_constant("disp.png", 0.2f, W, H);
    const char *other = write_constant("other.exr", 0.25f, W, H);
    char args[9000], out[8192];
    snprintf(args, sizeof args, "compare '%s' '%s'", png, exr);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 2);
    assert_non_null(strstr(out, "disp.png holds 8-bit integer sRGB values"));
    assert_non_null(strstr(out, "lin.exr 32-bit float linear ones"));
    assert_non_null(strstr(out, "--colorconvert sRGB linear -d float -o "));
    assert_non_null(strstr(out, "disp-linear.exr"));
    snprintf(args, sizeof args, "compare '%s' '%s'", exr, png);
    assert_int_equal(run(args, out, sizeof out), 2);
    /* The direct parts must be of the reference's kind too, each of the images summed. */
    snprintf(args, sizeof args, "compare '%s' '%s' --ref-direct '%s'", other, exr, png);
    assert_int_equal(run(args, out, sizeof out), 2);
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --direct '%s' --ref-direct '%s'", other, exr, exr,
             png, exr);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 2);
    assert_non_null(strstr(out, "disp.png holds 8-bit integer sRGB values"));
    snprintf(args, sizeof args, "compare '%s' '%s' --json", png, png);
    assert_int_equal(run(args, out, sizeof out), 0);
    snprintf(args, sizeof args, "compare '%s' '%s' --ref-direct '%s' --json", other, exr, exr);
    assert_int_equal(run(args, out, sizeof out), 0);
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --ref-direct '%s' --json", other, exr, exr, exr);
    assert_int_equal(run(args, out, sizeof out), 0);
}

static void
identical_images(void **state)
{
    (void)state;
    const char *a = write_constant("a.exr", 0.4f, W, H);
    char args[9000], out[4096];
    snprintf(args, sizeof args, "compare '%s' '%s' --json", a, a);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_float_equal(cg_test_json_number(out, "\"full\"", "rmse"), 0.0, 0.0);
    assert_float_equal(cg_test_json_number(out, "\"full\"", "relmse"), 0.0, 0.0);
    assert_float_equal(cg_test_json_number(out, "\"full\"", "ssim"), 1.0, 1e-9);
    assert_float_equal(cg_test_json_number(out, "\"full\"", "lum_ratio"), 1.0, 1e-9);
}

static void
offset_and_indirect_part(void **state)
{
    (void)state;
    const char *t = write_constant("t.exr", 0.5f, W, H);
    const char *r = write_constant("r.exr", 0.25f, W, H);
    const char *d = write_constant("d.exr", 0.125f, W, H);
    char heatmap[4200];
    snprintf(heatmap, sizeof heatmap, "%s/heat.png", cg_test_tmpdir());
    char args[20000], out[4096];
    snprintf(args, sizeof args, "compare '%s' '%s' --ref-direct '%s' --json --heatmap '%s'", t, r, d, heatmap);
    assert_int_equal(run(args, out, sizeof out), 0);
    /* Offset 0.25 on 0.25: relMSE 0.0625 / (0.0625 + 0.01); indirect 0.375 against 0.125
     * (the reference's direct part taken from both). */
    assert_float_equal(cg_test_json_number(out, "\"full\"", "rmse"), 0.25, 1e-7);
    assert_float_equal(cg_test_json_number(out, "\"full\"", "relmse"), 0.0625 / 0.0725, 1e-7);
    assert_float_equal(cg_test_json_number(out, "\"full\"", "lum_ratio"), 2.0, 1e-7);
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "lum_ratio"), 3.0, 1e-6);
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "relmse"), 0.0625 / (0.015625 + 0.01), 1e-6);
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "energy"), 3.0, 1e-6);
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "nrmse"), 2.0, 1e-6);
    assert_non_null(strstr(out, "\"estimate\": \"TEST - REF_DIRECT\""));
    assert_null(strstr(out, "\"direct\": {"));
    cg_image map = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(cg_image_read(heatmap, &map, &err), &err);
    /* The map on top, widened to 360 pixels in white, its colour scale beneath it: the scale's
     * bar runs from black (0) at its left end to light yellow (--heatmap-max) at its right. */
    assert_int_equal(map.width, 360);
    assert_true(map.height > H + 30);
    const float *bar_left = &map.rgba[4 * ((size_t)(H + 10) * map.width + 14)];
    const float *bar_right = &map.rgba[4 * ((size_t)(H + 10) * map.width + 360 - 14)];
    assert_true(bar_left[0] < 0.01f && bar_left[1] < 0.01f);
    assert_true(bar_right[0] > 0.9f && bar_right[1] > 0.9f);
    const float *pad = &map.rgba[4 * ((size_t)2 * map.width + W + 5)];
    assert_true(pad[0] == 1.0f && pad[1] == 1.0f && pad[2] == 1.0f);
    cg_image_free(&map);
}

/* An image whose columns x < edge hold `lit` and the others `dark` (grey), plus `add`. */
static const char *
write_edge(const char *name, int edge, float lit, float dark, float add)
{
    cg_image img = { 0 };
    cg_error err = { 0 };
    assert_cg_ok(cg_image_alloc(&img, W, H, &err), &err);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = &img.rgba[4 * (y * W + x)];
            p[0] = p[1] = p[2] = (x < edge ? lit : dark) + add;
            p[3] = 1.0f;
        }
    const char *path = cg_test_tmp_path(name);
    assert_cg_ok(cg_image_write(path, &img, CG_EXR_FLOAT, &err), &err);
    cg_image_free(&img);
    return path;
}

/* A shadow edge two columns off in TEST's own direct light (a shadow map's step) and exactly
 * the right indirect light 0.25 on top: with each side's own direct light taken away the
 * indirect part is exact; with the reference's taken from both, the edge counts against it. */
static void
own_direct_light_cancels_shadow_edges(void **state)
{
    (void)state;
    const char *ref = write_edge("edge-ref.exr", 16, 1.0f, 0.0f, 0.25f);
    const char *rd_a = write_edge("edge-rd-a.exr", 16, 0.75f, 0.0f, 0.0f);
    const char *rd_b = write_edge("edge-rd-b.exr", 16, 0.25f, 0.0f, 0.0f);
    const char *test = write_edge("edge-test.exr", 18, 1.0f, 0.0f, 0.25f);
    const char *td = write_edge("edge-td.exr", 18, 1.0f, 0.0f, 0.0f);
    char args[30000], out[8192];
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --ref-direct '%s' --ref-direct '%s' --json", test, ref,
             td, rd_a, rd_b);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_non_null(strstr(out, "\"estimate\": \"TEST - TEST_DIRECT\""));
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "energy"), 1.0, 1e-9);
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "nrmse"), 0.0, 1e-9);
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "rms_truth"), 0.25, 1e-9);
    /* The direct parts: 18 lit columns for 16, an error of 1 on 2 of 32 columns. */
    assert_float_equal(cg_test_json_number(out, "\"direct\"", "energy"), 18.0 / 16.0, 1e-9);
    assert_float_equal(cg_test_json_number(out, "\"direct\"", "nrmse"), sqrt(2.0 / 32.0) / sqrt(0.5), 1e-9);
    assert_float_equal(cg_test_json_number(out, "\"direct\"", "rmse"), 0.25, 1e-9);
    /* The reference's direct light taken from both: the edge's 2 columns of 1.0 are indirect error. */
    snprintf(args, sizeof args, "compare '%s' '%s' --ref-direct '%s' --ref-direct '%s' --json", test, ref, rd_a, rd_b);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "energy"), 1.25, 1e-9);
    assert_float_equal(cg_test_json_number(out, "\"indirect\"", "nrmse"), 1.0, 1e-9);
    /* The table prints the same figures. */
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --ref-direct '%s' --ref-direct '%s'", test, ref, td,
             rd_a, rd_b);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_non_null(strstr(out, "indirect"));
    assert_non_null(strstr(out, "energy 1  nrmse 0\n"));
    assert_non_null(strstr(out, "direct    rmse 0.25"));
    assert_non_null(strstr(out, "energy 1.125  nrmse 0.353553\n"));
}

/* No GI (TEST is its own direct image): energy 0 and nrmse 1 exactly; the reference against
 * itself: 1 and 0. */
static void
no_indirect_light_and_the_reference_itself(void **state)
{
    (void)state;
    const char *ref = write_edge("none-ref.exr", 10, 0.8f, 0.1f, 0.3f);
    const char *rd = write_edge("none-rd.exr", 12, 0.8f, 0.1f, 0.0f);
    const char *test = write_edge("none-test.exr", 14, 0.6f, 0.05f, 0.0f);
    char args[30000], out[8192];
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --ref-direct '%s' --json", test, ref, test, rd);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_true(cg_test_json_number(out, "\"indirect\"", "energy") == 0.0);
    assert_true(cg_test_json_number(out, "\"indirect\"", "nrmse") == 1.0);
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --ref-direct '%s' --json", ref, ref, rd, rd);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_true(cg_test_json_number(out, "\"indirect\"", "energy") == 1.0);
    assert_true(cg_test_json_number(out, "\"indirect\"", "nrmse") == 0.0);
    assert_true(cg_test_json_number(out, "\"direct\"", "nrmse") == 0.0);
}

static void
bad_input_exits_with_2(void **state)
{
    (void)state;
    const char *a = write_constant("s1.exr", 0.4f, W, H);
    const char *b = write_constant("s2.exr", 0.4f, W, H + 1);
    char args[9000], out[4096];
    snprintf(args, sizeof args, "compare '%s' '%s'", a, b);
    assert_int_equal(run(args, out, sizeof out), 2);
    snprintf(args, sizeof args, "compare '%s' '%s/missing.exr'", a, cg_test_tmpdir());
    assert_int_equal(run(args, out, sizeof out), 2);
    snprintf(args, sizeof args, "compare '%s'", a);
    assert_int_equal(run(args, out, sizeof out), 2);
    snprintf(args, sizeof args, "compare '%s' '%s' --bogus", a, a);
    assert_int_equal(run(args, out, sizeof out), 2);
    /* The parts: --direct without --ref-direct (it once named the reference's), a part of
     * another size, an unreadable one, a missing value. */
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s'", a, a, a);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 2);
    assert_non_null(strstr(out, "--ref-direct"));
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --ref-direct '%s'", a, a, b, a);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 2);
    assert_non_null(strstr(out, "images must have the same size"));
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --ref-direct '%s' --ref-direct '%s'", a, a, a, a, b);
    assert_int_equal(run(args, out, sizeof out), 2);
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --ref-direct '%s/missing.exr'", a, a, a,
             cg_test_tmpdir());
    assert_int_equal(run(args, out, sizeof out), 2);
    snprintf(args, sizeof args, "compare '%s' '%s' --ref-direct", a, a);
    assert_int_equal(run(args, out, sizeof out), 2);
    /* The heat map's path is checked before the images are read: a missing directory, a
     * directory named as the file, another extension. */
    const char *heat[] = { "/nonexistent-dir/h.png", "/tmp", "h.exr" };
    const char *said[] = { "--heatmap: /nonexistent-dir/h.png: directory '/nonexistent-dir' does not exist",
                           "--heatmap: /tmp: expected a file name ending in .png", "h.exr" };
    for (int i = 0; i < 3; i++) {
        snprintf(args, sizeof args, "compare '%s' '%s/missing.exr' --heatmap '%s'", a, cg_test_tmpdir(), heat[i]);
        assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 2);
        if (!strstr(out, said[i]) || strstr(out, "missing.exr"))
            fail_msg("--heatmap %s: expected '%s' before the images are read: %s", heat[i], said[i], out);
    }
    assert_int_equal(run("compare --help", out, sizeof out), 0);
    assert_non_null(strstr(out, "usage: conegraph compare"));
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(identical_images),
             cmocka_unit_test(offset_and_indirect_part),
             cmocka_unit_test(own_direct_light_cancels_shadow_edges),
             cmocka_unit_test(no_indirect_light_and_the_reference_itself),
             cmocka_unit_test(bad_input_exits_with_2),
             cmocka_unit_test(display_image_beside_linear_one_is_refused))
