/* conegraph compare: error metrics of an image against a reference (cg/metrics.h), and of
 * its parts when their direct parts are given: the indirect light with each side's own direct
 * light taken away, and the direct parts themselves. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench/plot.h"
#include "cg/error.h"
#include "cg/fs.h"
#include "cg/image.h"
#include "cg/metrics.h"
#include "commands.h"

/* Images one --direct or --ref-direct list may sum. */
#define MAX_PART_IMAGES 8

void
cmd_compare_usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph compare TEST REF [--direct TEST_DIRECT]... [--ref-direct REF_DIRECT]...\n"
        "                         [--json] [--heatmap FILE.png] [--heatmap-max V]\n"
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
        "The indirect light alone, each side's own direct light taken away:\n"
        "  --direct TEST_DIRECT      TEST's own direct image (for a GI graph: its direct light and\n"
        "                            the emission it adds, e.g. render --dump direct.radiance=D.exr\n"
        "                            --dump gbuf.emissive=E.exr, or the image of direct.json with\n"
        "                            the same shadow settings)\n"
        "  --ref-direct REF_DIRECT   the reference's direct part (e.g. path_trace's parts emitted and\n"
        "                            direct_punctual: render --set trace.parts=true --dump ...)\n"
        "  Each may be given several times: the images are summed. With both, two more lines:\n"
        "  indirect    TEST - TEST_DIRECT against REF - REF_DIRECT (the GI estimate against the\n"
        "              truth: shadow-map edges in the direct light cancel on each side)\n"
        "  direct      TEST_DIRECT against REF_DIRECT\n"
        "  each with the metrics above and\n"
        "  energy      mean luminance of the estimate / of the truth (1: the right amount of light;\n"
        "              0: none; when the truth's is 0: 1 if the estimate's is too, else inf)\n"
        "  nrmse       rmse(estimate - truth) / rms(truth): 0 is the truth, 1 no better than\n"
        "              leaving the part out (0 if both are 0, inf if only the truth is)\n"
        "  With --ref-direct alone, indirect is TEST - REF_DIRECT against REF - REF_DIRECT: the\n"
        "  reference's direct light taken from both, so where TEST's own direct light differs\n"
        "  (shadow-map edges) that counts as indirect error. --direct needs --ref-direct.\n"
        "\n"
        "  --json               print the figures as one JSON object instead of a table\n"
        "                       (non-finite figures as null)\n"
        "  --heatmap FILE.png   write the per-pixel relative error sqrt(mean (t-r)^2/(r^2+0.01))\n"
        "                       of the full images as an 'inferno' colour map, black = 0, yellow\n"
        "                       >= --heatmap-max (default 1); magenta = non-finite. Beneath the\n"
        "                       map (widened to 360 pixels where narrower, in white) its colour\n"
        "                       scale, numbered, and what it measures. The path is checked before\n"
        "                       the images are read (a missing directory exits 2)\n"
        "\n"
        "All images must hold the same kind of values: linear (EXR, HDR, float TIFF: radiance)\n"
        "or display-encoded (PNG, JPEG: sRGB or another transfer function, decoded on reading),\n"
        "and have the same size. An 8-bit sRGB image beside a linear one is refused: a PNG of\n"
        "`conegraph render` is exposed and tonemapped, so its decoded values are not radiance.\n"
        "Compare the .exr outputs, or convert a file that truly holds linear values stored as\n"
        "sRGB first:\n"
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

/* The metrics' fields, without the braces: a part's section adds its own. */
static void
print_metrics_fields(const cg_metrics *m)
{
    print_number_json("rmse", m->rmse, false);
    print_number_json("relmse", m->rel_mse, false);
    print_number_json("ssim", m->ssim, false);
    print_number_json("max_error", m->max_error, false);
    print_number_json("mean_luminance_test", m->mean_luminance_test, false);
    print_number_json("mean_luminance_ref", m->mean_luminance_ref, false);
    print_number_json("lum_ratio", m->mean_luminance_ratio, false);
    printf("\"nonfinite\": %zu, \"nonfinite_test\": %zu", m->nonfinite_pixels, m->nonfinite_test);
}

/* A part's section: how its estimate was made, the metrics, energy and nrmse. */
static void
print_part_json(const char *name, const char *estimate, const char *truth, const cg_metrics *m,
                const cg_part_metrics *p)
{
    printf(", \"%s\": {\"estimate\": ", name);
    print_string_json(estimate);
    printf(", \"truth\": ");
    print_string_json(truth);
    printf(", ");
    print_metrics_fields(m);
    printf(", ");
    print_number_json("energy", p->energy, false);
    print_number_json("nrmse", p->nrmse, false);
    print_number_json("rms_truth", p->rms_truth, true);
    printf("}");
}

static void
print_metrics_table(const char *label, const cg_metrics *m, const cg_part_metrics *p)
{
    printf("%-9s rmse %.6g  relmse %.6g  ssim %.6f  max_error %.6g  lum_ratio %.6f  nonfinite %zu", label,
           m->rmse, m->rel_mse, m->ssim, m->max_error, m->mean_luminance_ratio, m->nonfinite_pixels);
    if (p)
        printf("  energy %.6g  nrmse %.6g", p->energy, p->nrmse);
    printf("\n");
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

/* One input image: read, with what the file holds. */
typedef struct input_image {
    const char *path;
    cg_image image;
    cg_image_file_info info;
} input_image;

/* The sum of a list of images (one: a copy), all of one size (checked before), alpha 1. */
static bool
sum_images(const input_image *list, int count, cg_image *out, cg_error *err)
{
    if (!cg_image_alloc(out, list[0].image.width, list[0].image.height, err))
        return false;
    size_t n = (size_t)out->width * (size_t)out->height;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) {
            float v = 0.0f;
            for (int k = 0; k < count; k++)
                v += list[k].image.rgba[4 * i + c];
            out->rgba[4 * i + c] = v;
        }
        out->rgba[4 * i + 3] = 1.0f;
    }
    return true;
}

/* The metrics of a part, and its energy and nrmse. */
static bool
part_metrics(const cg_image *estimate, const cg_image *truth, cg_metrics *m, cg_part_metrics *p, cg_error *err)
{
    return cg_metrics_compute(estimate, truth, m, err) && cg_metrics_part(estimate, truth, p, err);
}

int
cmd_compare(int argc, char **argv)
{
    /* inputs[0] TEST, [1] REF, then the --direct images, then the --ref-direct ones. */
    input_image inputs[2 + 2 * MAX_PART_IMAGES];
    const char *paths[2] = { NULL, NULL }, *direct_paths[MAX_PART_IMAGES], *ref_direct_paths[MAX_PART_IMAGES];
    const char *heatmap_path = NULL;
    int path_count = 0, direct_count = 0, ref_direct_count = 0;
    bool json = false;
    double heatmap_max = 1.0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--json")) {
            json = true;
        } else if (!strcmp(a, "--direct") || !strcmp(a, "--ref-direct") || !strcmp(a, "--heatmap") ||
                   !strcmp(a, "--heatmap-max")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "conegraph compare: %s needs a value (see --help)\n", a);
                return 2;
            }
            const char *v = argv[++i];
            if (!strcmp(a, "--direct") || !strcmp(a, "--ref-direct")) {
                bool test_side = !strcmp(a, "--direct");
                int *count = test_side ? &direct_count : &ref_direct_count;
                if (*count == MAX_PART_IMAGES) {
                    fprintf(stderr, "conegraph compare: %s: at most %d images\n", a, MAX_PART_IMAGES);
                    return 2;
                }
                (test_side ? direct_paths : ref_direct_paths)[(*count)++] = v;
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
    if (direct_count && !ref_direct_count) {
        /* --direct once named the reference's direct part: say so rather than guess. */
        fprintf(stderr, "conegraph compare: --direct names TEST's own direct image; the reference's direct part\n"
                        "  goes with --ref-direct (give both to compare the indirect parts, or --ref-direct\n"
                        "  alone to take the reference's direct light from both images)\n");
        return 2;
    }

    if (heatmap_path) {
        cg_error path_err = { 0 };
        if (!cg_output_path_check(heatmap_path, ".png", &path_err)) {
            fprintf(stderr, "conegraph compare: --heatmap: %s\n", path_err.message);
            return 2;
        }
    }

    int count = 0;
    inputs[count++] = (input_image){ .path = paths[0] };
    inputs[count++] = (input_image){ .path = paths[1] };
    for (int i = 0; i < direct_count; i++)
        inputs[count++] = (input_image){ .path = direct_paths[i] };
    for (int i = 0; i < ref_direct_count; i++)
        inputs[count++] = (input_image){ .path = ref_direct_paths[i] };
    const input_image *test = &inputs[0], *ref = &inputs[1];
    const input_image *test_direct_list = &inputs[2], *ref_direct_list = &inputs[2 + direct_count];

    cg_error err = { 0 };
    cg_image test_direct = { 0 }, ref_direct = { 0 }, test_ind = { 0 }, ref_ind = { 0 }, map = { 0 };
    cg_metrics full, indirect, direct;
    cg_part_metrics indirect_part, direct_part;
    int code = 0;
    for (int i = 0; i < count; i++)
        if (!cg_image_read_info(inputs[i].path, &inputs[i].image, &inputs[i].info, &err)) {
            code = fail_exit("", &err);
            goto done;
        }
    /* Every image against the reference: one kind of values, one size. */
    for (int i = 0; i < count; i++) {
        if (i == 1)
            continue;
        if (!same_kind(inputs[i].path, &inputs[i].info, ref->path, &ref->info)) {
            code = 2;
            goto done;
        }
        if (inputs[i].image.width != ref->image.width || inputs[i].image.height != ref->image.height) {
            fprintf(stderr, "conegraph compare: %s is %dx%d but %s is %dx%d: images must have the same size\n",
                    inputs[i].path, inputs[i].image.width, inputs[i].image.height, ref->path, ref->image.width,
                    ref->image.height);
            code = 2;
            goto done;
        }
    }
    if (!cg_metrics_compute(&test->image, &ref->image, &full, &err)) {
        code = fail_exit("", &err);
        goto done;
    }
    /* The indirect estimate takes TEST's own direct image away when it is given, else the
     * reference's; the truth is always the reference minus its direct part. */
    if (ref_direct_count &&
        (!sum_images(ref_direct_list, ref_direct_count, &ref_direct, &err) ||
         (direct_count && !sum_images(test_direct_list, direct_count, &test_direct, &err)) ||
         !cg_image_subtract(&test->image, direct_count ? &test_direct : &ref_direct, &test_ind, &err) ||
         !cg_image_subtract(&ref->image, &ref_direct, &ref_ind, &err) ||
         !part_metrics(&test_ind, &ref_ind, &indirect, &indirect_part, &err) ||
         (direct_count && !part_metrics(&test_direct, &ref_direct, &direct, &direct_part, &err)))) {
        code = fail_exit("parts: ", &err);
        goto done;
    }
    if (json) {
        printf("{\"test\": ");
        print_string_json(paths[0]);
        printf(", \"ref\": ");
        print_string_json(paths[1]);
        printf(", \"width\": %d, \"height\": %d, \"full\": {", full.width, full.height);
        print_metrics_fields(&full);
        printf("}");
        if (ref_direct_count)
            print_part_json("indirect", direct_count ? "TEST - TEST_DIRECT" : "TEST - REF_DIRECT", "REF - REF_DIRECT",
                            &indirect, &indirect_part);
        if (direct_count)
            print_part_json("direct", "TEST_DIRECT", "REF_DIRECT", &direct, &direct_part);
        printf("}\n");
    } else {
        printf("%s against %s (%dx%d)\n", paths[0], paths[1], full.width, full.height);
        print_metrics_table("full", &full, NULL);
        if (ref_direct_count)
            print_metrics_table("indirect", &indirect, &indirect_part);
        if (direct_count)
            print_metrics_table("direct", &direct, &direct_part);
        if (ref_direct_count && !direct_count)
            printf("(indirect: TEST - REF_DIRECT against REF - REF_DIRECT: without --direct, TEST's own direct\n"
                   " light is taken to be the reference's)\n");
    }
    if (heatmap_path) {
        if (!plot_error_heatmap(&test->image, &ref->image, heatmap_max, &map, &err) ||
            !cg_image_write(heatmap_path, &map, CG_EXR_HALF, &err)) {
            code = fail_exit("heat map: ", &err);
            goto done;
        }
    }
done:
    for (int i = 0; i < count; i++)
        cg_image_free(&inputs[i].image);
    cg_image_free(&test_direct);
    cg_image_free(&ref_direct);
    cg_image_free(&test_ind);
    cg_image_free(&ref_ind);
    cg_image_free(&map);
    return code;
}
