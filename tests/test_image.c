/* Images: EXR float bit-exact and half within half precision, PNG 8-bit sRGB encoding,
 * reading other formats (grey, no alpha, row order), clear errors for bad files, and
 * writes that never leave a partial file or clobber an existing one. */
#include "test_support.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cg/fs.h"
#include "cg/image.h"

/* A 7x5 image (odd sizes catch stride mistakes) whose pixels all differ. */
static cg_image
make_test_image(void)
{
    cg_image img;
    cg_error err = { 0 };
    assert_cg_ok(cg_image_alloc(&img, 7, 5, &err), &err);
    for (int y = 0; y < img.height; y++) {
        for (int x = 0; x < img.width; x++) {
            float *p = img.rgba + 4 * (y * img.width + x);
            p[0] = (float)x / 7.0f;
            p[1] = (float)y / 3.0f + 0.001f * (float)x;
            p[2] = 0.5f + (float)(x * y) / 35.0f;
            p[3] = 1.0f - (float)(x + y) / 16.0f;
        }
    }
    return img;
}

static bool
exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Counts the entries of a directory other than . and .., and those that look like
 * cg_temp_path_for's temporaries. */
static int
count_entries(const char *dir, int *temporaries)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    *temporaries = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        n++;
        if (strstr(e->d_name, ".tmp-"))
            (*temporaries)++;
    }
    closedir(d);
    return n;
}

static void
test_srgb_transfer(void **state)
{
    (void)state;
    assert_true(cg_srgb_encode(0.0f) == 0.0f);
    assert_true(fabsf(cg_srgb_encode(1.0f) - 1.0f) < 1e-6f);
    /* linear 0.5 is 0.7354 encoded, 187.5 in 8 bits: rounds to 188 */
    assert_int_equal(lrintf(cg_srgb_encode(0.5f) * 255.0f), 188);
    assert_true(fabsf(cg_srgb_encode(0.5f) - 0.735357f) < 1e-5f);
    /* linear segment below the threshold (IEC 61966-2-1) */
    assert_true(fabsf(cg_srgb_encode(0.002f) - 0.02584f) < 1e-6f);
    for (int k = 0; k <= 255; k++) {
        float e = (float)k / 255.0f;
        assert_true(fabsf(cg_srgb_encode(cg_srgb_decode(e)) - e) < 1e-5f);
    }
}

static void
test_exr_float_round_trip_is_bit_exact(void **state)
{
    (void)state;
    cg_image img = make_test_image(), back;
    /* values no half can hold, negative, tiny and huge */
    img.rgba[0] = 1.0f / 3.0f;
    img.rgba[1] = -123.456f;
    img.rgba[2] = 1e-30f;
    img.rgba[3] = 3.0e38f;
    const char *path = cg_test_tmp_path("float.exr");
    cg_error err = { 0 };
    assert_cg_ok(cg_image_write(path, &img, CG_EXR_FLOAT, &err), &err);
    assert_cg_ok(cg_image_read(path, &back, &err), &err);
    assert_int_equal(back.width, img.width);
    assert_int_equal(back.height, img.height);
    assert_memory_equal(back.rgba, img.rgba, sizeof(float) * 4 * img.width * img.height);
    cg_image_free(&back);
    cg_image_free(&img);
}

/* What the file held: an EXR's linear floats, a PNG's 8-bit sRGB (decoded on reading). */
static void
test_read_info_says_how_the_file_stored_its_values(void **state)
{
    (void)state;
    cg_image img = make_test_image(), back;
    cg_image_file_info info;
    cg_error err = { 0 };
    const struct { const char *name; cg_image_exr_type type; bool display, floating; int bits; } cases[] = {
        { "info.exr", CG_EXR_FLOAT, false, true, 32 },
        { "info_half.exr", CG_EXR_HALF, false, true, 16 },
        { "info.png", CG_EXR_FLOAT, true, false, 8 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *path = cg_test_tmp_path(cases[i].name);
        assert_cg_ok(cg_image_write(path, &img, cases[i].type, &err), &err);
        assert_cg_ok(cg_image_read_info(path, &back, &info, &err), &err);
        assert_int_equal(info.display_encoded, cases[i].display);
        assert_int_equal(info.floating, cases[i].floating);
        assert_int_equal(info.bits, cases[i].bits);
        if (cases[i].display)
            assert_string_equal(info.colour_space, "sRGB");
        cg_image_free(&back);
    }
    cg_image_free(&img);
}

static void
test_exr_half_within_half_precision(void **state)
{
    (void)state;
    cg_image img = make_test_image(), back;
    img.rgba[0] = 1.0f / 3.0f;
    img.rgba[1] = 1000.1f;
    const char *path = cg_test_tmp_path("half.exr");
    cg_error err = { 0 };
    assert_cg_ok(cg_image_write(path, &img, CG_EXR_HALF, &err), &err);
    assert_cg_ok(cg_image_read(path, &back, &err), &err);
    assert_int_equal(back.width, img.width);
    assert_int_equal(back.height, img.height);
    size_t n = (size_t)4 * img.width * img.height;
    for (size_t i = 0; i < n; i++) {
        /* half: 11 significant bits, round to nearest: relative error <= 2^-11 (normal range) */
        float v = img.rgba[i];
        assert_true(fabsf(back.rgba[i] - v) <= fabsf(v) * 0x1p-11f + 0x1p-25f);
    }
    /* it really is half: 1/3 and 1000.1 are not representable */
    assert_true(back.rgba[0] != img.rgba[0]);
    assert_true(back.rgba[1] == 1000.0f);
    cg_image_free(&back);
    cg_image_free(&img);
}

static void
test_png_srgb_round_trip(void **state)
{
    (void)state;
    cg_image img, back;
    cg_error err = { 0 };
    /* row 0: every 8-bit code, as the linear value it decodes to; row 1: linear 0.5,
     * out-of-range values (clamped after encoding, cg/image.h) and a linear ramp */
    assert_cg_ok(cg_image_alloc(&img, 256, 2, &err), &err);
    for (int k = 0; k < 256; k++) {
        float *p = img.rgba + 4 * k;
        p[0] = p[1] = p[2] = cg_srgb_decode((float)k / 255.0f);
        p[3] = (float)(255 - k) / 255.0f; /* alpha is stored linearly */
        float *q = img.rgba + 4 * (256 + k);
        q[0] = 0.5f;
        q[1] = k < 128 ? -1.0f : 7.0f;
        q[2] = (float)k / 255.0f;
        q[3] = 1.0f;
    }
    const char *path = cg_test_tmp_path("srgb.png");
    assert_cg_ok(cg_image_write(path, &img, CG_EXR_HALF, &err), &err);
    assert_cg_ok(cg_image_read(path, &back, &err), &err);
    assert_int_equal(back.width, 256);
    assert_int_equal(back.height, 2);
    for (int k = 0; k < 256; k++) {
        const float *p = back.rgba + 4 * k;
        for (int c = 0; c < 3; c++) /* the same code comes back */
            assert_true(fabsf(cg_srgb_encode(p[c]) * 255.0f - (float)k) < 0.01f);
        assert_true(fabsf(p[3] * 255.0f - (float)(255 - k)) < 0.01f);
        const float *q = back.rgba + 4 * (256 + k);
        /* linear 0.5 is stored as 188 */
        assert_true(fabsf(cg_srgb_encode(q[0]) * 255.0f - 188.0f) < 0.01f);
        assert_true(q[1] == (k < 128 ? 0.0f : 1.0f));
        /* within half a code of the exact encoding: rounding, not truncation */
        assert_true(fabsf(cg_srgb_encode(q[2]) - cg_srgb_encode((float)k / 255.0f)) <= 0.5f / 255.0f + 1e-5f);
        assert_true(q[3] == 1.0f);
    }
    cg_image_free(&back);
    cg_image_free(&img);
}

/* cg_image rows run top to bottom: the first row of a file is row 0. */
static void
test_row_order_and_round_trip_orientation(void **state)
{
    (void)state;
    /* PPM: 1 wide, 2 high, first (top) row red, second blue */
    const char *ppm = cg_test_write_file("rb.ppm", "P3\n1 2\n255\n255 0 0\n0 0 255\n", 0);
    cg_image img, back;
    cg_error err = { 0 };
    assert_cg_ok(cg_image_read(ppm, &img, &err), &err);
    assert_int_equal(img.width, 1);
    assert_int_equal(img.height, 2);
    const float top[4] = { 1, 0, 0, 1 }, bottom[4] = { 0, 0, 1, 1 };
    assert_memory_equal(img.rgba, top, sizeof top);
    assert_memory_equal(img.rgba + 4, bottom, sizeof bottom);
    /* and writing keeps it */
    const char *exr = cg_test_tmp_path("rb.exr");
    assert_cg_ok(cg_image_write(exr, &img, CG_EXR_FLOAT, &err), &err);
    assert_cg_ok(cg_image_read(exr, &back, &err), &err);
    assert_memory_equal(back.rgba, img.rgba, sizeof(float) * 8);
    cg_image_free(&back);
    cg_image_free(&img);
}

static void
test_grey_without_alpha(void **state)
{
    (void)state;
    const char *pgm = cg_test_write_file("grey.pgm", "P2\n3 1\n255\n0 255 0\n", 0);
    cg_image img;
    cg_error err = { 0 };
    assert_cg_ok(cg_image_read(pgm, &img, &err), &err);
    assert_int_equal(img.width, 3);
    assert_int_equal(img.height, 1);
    const float black[4] = { 0, 0, 0, 1 }, white[4] = { 1, 1, 1, 1 };
    assert_memory_equal(img.rgba, black, sizeof black);
    assert_memory_equal(img.rgba + 4, white, sizeof white);
    assert_memory_equal(img.rgba + 8, black, sizeof black);
    cg_image_free(&img);
}

static void
test_bad_files_fail_clearly(void **state)
{
    (void)state;
    cg_image img = { 0 };
    cg_error err;
    const char *garbage = cg_test_write_file("garbage.png", "this is not an image at all\n", 0);
    assert_cg_status(cg_image_read(garbage, &img, &err), &err, CG_ERR_IMAGE_FORMAT);
    assert_non_null(strstr(err.message, garbage));
    assert_null(img.rgba);
    const char *noext = cg_test_write_file("garbage", "\x01\x02\x03", 3);
    assert_cg_status(cg_image_read(noext, &img, &err), &err, CG_ERR_IMAGE_FORMAT);
    assert_cg_status(cg_image_read(cg_test_tmp_path("does-not-exist.exr"), &img, &err), &err, CG_ERR_FILE_NOT_FOUND);
    assert_non_null(strstr(err.message, "does-not-exist.exr"));
}

static void
test_unsupported_extension_writes_nothing(void **state)
{
    (void)state;
    cg_image img = make_test_image();
    cg_error err;
    const char *path = cg_test_tmp_path("out.bmp");
    assert_cg_status(cg_image_write(path, &img, CG_EXR_HALF, &err), &err, CG_ERR_IMAGE_FORMAT);
    assert_non_null(strstr(err.message, "out.bmp"));
    assert_false(exists(path));
    assert_cg_status(cg_image_write(cg_test_tmp_path("no_extension"), &img, CG_EXR_HALF, &err), &err,
                     CG_ERR_IMAGE_FORMAT);
    cg_image_free(&img);
}

/* Each failure leaves the directory as it was: no target, no temporary, and an
 * existing file with its old bytes. */
static void
test_failed_write_leaves_nothing_and_clobbers_nothing(void **state)
{
    (void)state;
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/writes", cg_test_tmpdir());
    assert_int_equal(mkdir(dir, 0755), 0);
    cg_image img = make_test_image();
    cg_error err;
    int temps = 0;
    char path[4200];

    /* the parent directory does not exist */
    snprintf(path, sizeof path, "%s/missing/out.exr", dir);
    assert_cg_status(cg_image_write(path, &img, CG_EXR_FLOAT, &err), &err, CG_ERR_IO);
    assert_int_equal(count_entries(dir, &temps), 0);

    /* an existing file survives a write that fails (NaN has no PNG value) */
    snprintf(path, sizeof path, "%s/existing.png", dir);
    const char old[] = "previous contents";
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    fwrite(old, 1, sizeof old, fp);
    fclose(fp);
    img.rgba[4 * 9 + 1] = NAN;
    assert_cg_status(cg_image_write(path, &img, CG_EXR_HALF, &err), &err, CG_ERR_IMAGE_FORMAT);
    assert_non_null(strstr(err.message, "(2, 1)"));
    char *data = NULL;
    size_t size = 0;
    cg_error read_err = { 0 };
    assert_cg_ok(cg_read_file(path, &data, &size, &read_err), &read_err);
    assert_int_equal(size, sizeof old);
    assert_memory_equal(data, old, sizeof old);
    free(data);
    assert_int_equal(count_entries(dir, &temps), 1);
    assert_int_equal(temps, 0);

    /* the file was written completely, but it cannot be renamed over a directory:
     * the temporary is removed and the directory is untouched */
    img.rgba[4 * 9 + 1] = 0.5f;
    snprintf(path, sizeof path, "%s/taken.exr", dir);
    assert_int_equal(mkdir(path, 0755), 0);
    assert_cg_status(cg_image_write(path, &img, CG_EXR_HALF, &err), &err, CG_ERR_IO);
    assert_non_null(strstr(err.message, "rename"));
    assert_int_equal(count_entries(dir, &temps), 2);
    assert_int_equal(temps, 0);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    assert_true(S_ISDIR(st.st_mode));

    /* a successful write replaces the existing file whole */
    snprintf(path, sizeof path, "%s/existing.png", dir);
    cg_error ok_err = { 0 };
    assert_cg_ok(cg_image_write(path, &img, CG_EXR_HALF, &ok_err), &ok_err);
    cg_image back;
    assert_cg_ok(cg_image_read(path, &back, &ok_err), &ok_err);
    assert_int_equal(back.width, img.width);
    cg_image_free(&back);
    assert_int_equal(count_entries(dir, &temps), 2);
    assert_int_equal(temps, 0);
    cg_image_free(&img);
}

static void
test_alloc_rejects_bad_sizes(void **state)
{
    (void)state;
    cg_image img;
    cg_error err;
    assert_cg_status(cg_image_alloc(&img, 0, 4, &err), &err, CG_ERR_IMAGE_FORMAT);
    assert_null(img.rgba);
    assert_cg_status(cg_image_alloc(&img, 4, -1, &err), &err, CG_ERR_IMAGE_FORMAT);
    cg_error ok = { 0 };
    assert_cg_ok(cg_image_alloc(&img, 3, 2, &ok), &ok);
    for (int i = 0; i < 3 * 2 * 4; i++)
        assert_true(img.rgba[i] == 0.0f);
    cg_image_free(&img);
    assert_null(img.rgba);
    cg_image_free(&img); /* twice is harmless */
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_srgb_transfer),
             cmocka_unit_test(test_exr_float_round_trip_is_bit_exact),
             cmocka_unit_test(test_exr_half_within_half_precision),
             cmocka_unit_test(test_read_info_says_how_the_file_stored_its_values),
             cmocka_unit_test(test_png_srgb_round_trip),
             cmocka_unit_test(test_row_order_and_round_trip_orientation),
             cmocka_unit_test(test_grey_without_alpha),
             cmocka_unit_test(test_bad_files_fail_clearly),
             cmocka_unit_test(test_unsupported_extension_writes_nothing),
             cmocka_unit_test(test_failed_write_leaves_nothing_and_clobbers_nothing),
             cmocka_unit_test(test_alloc_rejects_bad_sizes))
