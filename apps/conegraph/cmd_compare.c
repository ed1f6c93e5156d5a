/* conegraph compare: error metrics of an image against a reference (cg/metrics.h), and of
 * the indirect part alone when the reference's direct part is given. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/error.h"
#include "cg/image.h"
#include "cg/metrics.h"
#include "commands.h"

void
cmd_compare_usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph compare TEST REF [--direct REF_DIRECT] [--json] [--heatmap FILE.png]\n"
        "                         [--heatmap-max V]\n"
        "\n"
        "Compares image TEST with the reference REF (any format OpenImageIO reads; EXR for\n"
        "linear radiance) and prints, over the RGB channels:\n"
        "  rmse        root mean squared error\n"
        "  relmse      mean of (t - r)^2 / (r^2 + 0.01) (Rousselle et al. 2011)\n"
        "  ssim        mean SSIM on display luminance (Wang et al. 2004; Gaussian 11x11,\n"
        "              sigma 1.5, K1 0.01, K2 0.03, luminance clamped to [0,1], sRGB-encoded)\n"
        "  max_error   largest absolute difference\n"
        "  lum_ratio   mean luminance of TEST / mean luminance of REF (energy check)\n"
        "  nonfinite   pixels where TEST or REF is NaN or infinite (left out of the others)\n"
        "\n"
        "  --direct REF_DIRECT  also compare the indirect parts: TEST - REF_DIRECT against\n"
        "                       REF - REF_DIRECT (REF_DIRECT: the reference at 0 bounces)\n"
        "  --json               print the figures as one JSON object instead of a table\n"
        "  --heatmap FILE.png   write the per-pixel relative error sqrt(mean (t-r)^2/(r^2+0.01))\n"
        "                       as an 'inferno' colour map, black = 0, yellow >= --heatmap-max\n"
        "                       (default 1); magenta = non-finite\n"
        "\n"
        "Both images must hold the same kind of values: linear (EXR, HDR, float TIFF: radiance)\n"
        "or display-encoded (PNG, JPEG: sRGB or another transfer function, decoded on reading).\n"
        "An 8-bit sRGB image beside a linear one is refused: a PNG of `conegraph render` is\n"
        "exposed and tonemapped, so its decoded values are not radiance. Compare the .exr\n"
        "outputs, or convert a file that truly holds linear values stored as sRGB first:\n"
        "  oiiotool IN.png --colorconvert sRGB linear -d float -o IN.exr\n"
        "\n"
        "Exit codes: 0 compared, 1 failed while writing, 2 bad usage, unreadable image,\n"
        "images of different sizes, or a display-encoded image beside a linear one.\n");
}

static void
print_string_json(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            printf("\\%c", c);
        else if (c < 0x20)
            printf("\\u%04x", c);
        else
            putchar(c);
    }
    putchar('"');
}

static void
print_number_json(const char *name, double v, bool last)
{
    if (isfinite(v))
        printf("\"%s\": %.9g%s", name, v, last ? "" : ", ");
    else
        printf("\"%s\": null%s", name, last ? "" : ", ");
}

static void
print_metrics_json(const cg_metrics *m)
{
    printf("{");
    print_number_json("rmse", m->rmse, false);
    print_number_json("relmse", m->rel_mse, false);
    print_number_json("ssim", m->ssim, false);
    print_number_json("max_error", m->max_error, false);
    print_number_json("mean_luminance_test", m->mean_luminance_test, false);
    print_number_json("mean_luminance_ref", m->mean_luminance_ref, false);
    print_number_json("lum_ratio", m->mean_luminance_ratio, false);
    printf("\"nonfinite\": %zu, \"nonfinite_test\": %zu}", m->nonfinite_pixels, m->nonfinite_test);
}

static void
print_metrics_table(const char *label, const cg_metrics *m)
{
    printf("%-9s rmse %.6g  relmse %.6g  ssim %.6f  max_error %.6g  lum_ratio %.6f  nonfinite %zu\n",
           label, m->rmse, m->rel_mse, m->ssim, m->max_error, m->mean_luminance_ratio,
           m->nonfinite_pixels);
}

/* "8-bit sRGB", "32-bit float linear", ... for messages. */
static void
describe(const cg_image_file_info *info, char *out, size_t size)
{
    snprintf(out, size, "%d-bit %s %s", info->bits, info->floating ? "float" : "integer",
             info->display_encoded ? (info->colour_space[0] ? info->colour_space : "display-encoded")
                                   : "linear");
}

/* A display-encoded image beside a linear one: refused (exit 2), naming both and what to do. */
static bool
same_kind(const char *a, const cg_image_file_info *ia, const char *b, const cg_image_file_info *ib)
{
    if (ia->display_encoded == ib->display_encoded)
        return true;
    char da[128], db[128];
    describe(ia, da, sizeof da);
    describe(ib, db, sizeof db);
    const char *display = ia->display_encoded ? a : b;
    /* The converted file's name: the stem with -linear.exr, never one of the inputs. */
    const char *slash = strrchr(display, '/'), *dot = strrchr(display, '.');
    int stem = dot && (!slash || dot > slash) ? (int)(dot - display) : (int)strlen(display);
    fprintf(stderr,
            "conegraph compare: %s holds %s values and %s %s ones.\n"
            "  An image made for display (a render's .png is exposed and tonemapped) is not linear\n"
            "  radiance, so their difference means nothing. Compare linear images (render -o OUT.exr\n"
            "  writes the linear hdr output), or two display images; if %s truly holds linear\n"
            "  values stored as sRGB, convert it first:\n"
            "    oiiotool %s --colorconvert sRGB linear -d float -o %.*s-linear.exr\n",
            a, da, b, db, display, display, stem, display);
    return false;
}

static int
fail_exit(const char *what, const cg_error *err)
{
    fprintf(stderr, "conegraph compare: %s%s\n", what, err->message);
    return cg_status_exit_code(err->status);
}

int
cmd_compare(int argc, char **argv)
{
    const char *paths[2] = { NULL, NULL }, *direct_path = NULL, *heatmap_path = NULL;
    int path_count = 0;
    bool json = false;
    double heatmap_max = 1.0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--json")) {
            json = true;
        } else if (!strcmp(a, "--direct") || !strcmp(a, "--heatmap") || !strcmp(a, "--heatmap-max")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "conegraph compare: %s needs a value (see --help)\n", a);
                return 2;
            }
            const char *v = argv[++i];
            if (!strcmp(a, "--direct")) {
                direct_path = v;
            } else if (!strcmp(a, "--heatmap")) {
                heatmap_path = v;
            } else {
                char *end;
                heatmap_max = strtod(v, &end);
                if (*end || !(heatmap_max > 0.0) || !isfinite(heatmap_max)) {
                    fprintf(stderr, "conegraph compare: --heatmap-max '%s': expected a positive number\n", v);
                    return 2;
                }
            }
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "conegraph compare: unknown option '%s' (see --help)\n", a);
            return 2;
        } else if (path_count < 2) {
            paths[path_count++] = a;
        } else {
            fprintf(stderr, "conegraph compare: unexpected argument '%s' (see --help)\n", a);
            return 2;
        }
    }
    if (path_count != 2) {
        fprintf(stderr, "conegraph compare: expected TEST and REF images (see --help)\n");
        return 2;
    }

    cg_error err = { 0 };
    cg_image test = { 0 }, ref = { 0 }, direct = { 0 }, test_ind = { 0 }, ref_ind = { 0 }, map = { 0 };
    cg_metrics full, indirect;
    int code = 0;
    cg_image_file_info test_info, ref_info, direct_info;
    if (!cg_image_read_info(paths[0], &test, &test_info, &err) || !cg_image_read_info(paths[1], &ref, &ref_info, &err) ||
        (direct_path && !cg_image_read_info(direct_path, &direct, &direct_info, &err))) {
        code = fail_exit("", &err);
        goto done;
    }
    if (!same_kind(paths[0], &test_info, paths[1], &ref_info) ||
        (direct_path && !same_kind(direct_path, &direct_info, paths[1], &ref_info))) {
        code = 2;
        goto done;
    }
    if (test.width != ref.width || test.height != ref.height) {
        fprintf(stderr, "conegraph compare: %s is %dx%d but %s is %dx%d: images must have the same size\n",
                paths[0], test.width, test.height, paths[1], ref.width, ref.height);
        code = 2;
        goto done;
    }
    if (direct_path && (direct.width != ref.width || direct.height != ref.height)) {
        fprintf(stderr, "conegraph compare: %s is %dx%d but %s is %dx%d: images must have the same size\n",
                direct_path, direct.width, direct.height, paths[1], ref.width, ref.height);
        code = 2;
        goto done;
    }
    if (!cg_metrics_compute(&test, &ref, &full, &err)) {
        code = fail_exit("", &err);
        goto done;
    }
    if (direct_path &&
        (!cg_image_subtract(&test, &direct, &test_ind, &err) || !cg_image_subtract(&ref, &direct, &ref_ind, &err) ||
         !cg_metrics_compute(&test_ind, &ref_ind, &indirect, &err))) {
        code = fail_exit("indirect part: ", &err);
        goto done;
    }
    if (json) {
        printf("{\"test\": ");
        print_string_json(paths[0]);
        printf(", \"ref\": ");
        print_string_json(paths[1]);
        printf(", \"width\": %d, \"height\": %d, \"full\": ", full.width, full.height);
        print_metrics_json(&full);
        if (direct_path) {
            printf(", \"indirect\": ");
            print_metrics_json(&indirect);
        }
        printf("}\n");
    } else {
        printf("%s against %s (%dx%d)\n", paths[0], paths[1], full.width, full.height);
        print_metrics_table("full", &full);
        if (direct_path)
            print_metrics_table("indirect", &indirect);
    }
    if (heatmap_path) {
        if (!cg_metrics_heatmap(&test, &ref, heatmap_max, &map, &err) ||
            !cg_image_write(heatmap_path, &map, CG_EXR_HALF, &err)) {
            code = fail_exit("heat map: ", &err);
            goto done;
        }
    }
done:
    cg_image_free(&test);
    cg_image_free(&ref);
    cg_image_free(&direct);
    cg_image_free(&test_ind);
    cg_image_free(&ref_ind);
    cg_image_free(&map);
    return code;
}
