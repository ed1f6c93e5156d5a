/* tests/tools/gi_metric.c: the figures of docs/vct.md's GI measurements, from images that
 * `conegraph render` wrote (tests/tools/gi_measure.sh runs the renders).
 *
 *   gi-metric indirect GI.exr DIRECT.exr TRUTH.exr [--rect x0 y0 x1 y1] [--label TEXT]
 *       estimate = GI - DIRECT (the graph's image minus direct.json's: the gathered light alone),
 *       truth = TRUTH (the path tracer's light reflected off surfaces: its parts direct_emitters
 *       + indirect, or reference(bounces N) - reference(bounces 0) for a scene without emitters);
 *       energy = mean Y(estimate) / mean Y(truth) (Rec. 709 Y), nrmse = rmse(estimate - truth) /
 *       rms(truth) over RGB, both over the pixels in the rectangle (default: all; x1, y1 exclusive,
 *       rows from the top as the file stores them). Prints the label, energy, nrmse and both means.
 *   gi-metric furnace IMG.exr ALBEDO RADIANCE [BOUNCES]
 *       the white furnace: every pixel should be L sum_{k=0..B+1} a^k, path_trace's value at
 *       `bounces` B (default 0: the emission seen plus one gathered reflection, what a radiance-
 *       model graph returns); prints the mean of (pixel - L) / (L sum_{k=1..B+1} a^k) over pixels
 *       and RGB and the worst |. - 1|.
 *   gi-metric mean IMG.exr [--rect x0 y0 x1 y1]
 *       mean red channel over the pixels whose red is above 0 (a gather's `reads` output: volume
 *       reads per covered pixel).
 *   gi-metric sum A.exr B.exr OUT.exr
 *       OUT = A + B (RGB; alpha 1): the path tracer's parts added up.
 * Exit codes: 0, 2 for bad arguments or unreadable images.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/error.h"
#include "cg/image.h"
#include "cg/metrics.h"

static void
load(const char *path, cg_image *img)
{
    cg_error err = {0};
    if (!cg_image_read(path, img, &err)) {
        fprintf(stderr, "gi-metric: %s\n", err.message);
        exit(2);
    }
}

static void
same_size(const cg_image *a, const cg_image *b, const char *what)
{
    if (a->width != b->width || a->height != b->height) {
        fprintf(stderr, "gi-metric: %s is %dx%d, expected %dx%d\n", what, b->width, b->height, a->width, a->height);
        exit(2);
    }
}

typedef struct rect {
    int x0, y0, x1, y1;
} rect;

/* Options after the positional arguments: --rect and --label. */
static void
options(int argc, char **argv, int first, const cg_image *img, rect *r, const char **label)
{
    *r = (rect){0, 0, img->width, img->height};
    for (int i = first; i < argc; i++) {
        if (!strcmp(argv[i], "--rect") && i + 4 < argc) {
            r->x0 = atoi(argv[i + 1]), r->y0 = atoi(argv[i + 2]), r->x1 = atoi(argv[i + 3]), r->y1 = atoi(argv[i + 4]);
            i += 4;
        } else if (!strcmp(argv[i], "--label") && i + 1 < argc && label) {
            *label = argv[++i];
        } else {
            fprintf(stderr, "gi-metric: unknown option '%s'\n", argv[i]);
            exit(2);
        }
    }
    if (r->x0 < 0 || r->y0 < 0 || r->x1 > img->width || r->y1 > img->height || r->x0 >= r->x1 || r->y0 >= r->y1) {
        fprintf(stderr, "gi-metric: rectangle outside the %dx%d image\n", img->width, img->height);
        exit(2);
    }
}

static int
indirect(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: gi-metric indirect GI DIRECT TRUTH [--rect x0 y0 x1 y1] [--label TEXT]\n");
        return 2;
    }
    cg_image g, d, t;
    load(argv[2], &g);
    load(argv[3], &d);
    load(argv[4], &t);
    same_size(&g, &d, argv[3]);
    same_size(&g, &t, argv[4]);
    rect r;
    const char *label = "";
    options(argc, argv, 5, &g, &r, &label);
    double ye = 0, yt = 0, se = 0, st = 0, n = 0;
    for (int y = r.y0; y < r.y1; y++)
        for (int x = r.x0; x < r.x1; x++) {
            size_t k = 4 * ((size_t)y * (size_t)g.width + (size_t)x);
            float e[3], tr[3];
            bool finite = true;
            for (int c = 0; c < 3; c++) {
                e[c] = g.rgba[k + c] - d.rgba[k + c];
                tr[c] = t.rgba[k + c];
                finite = finite && isfinite(e[c]) && isfinite(tr[c]);
            }
            if (!finite)
                continue;
            ye += cg_luminance(e);
            yt += cg_luminance(tr);
            for (int c = 0; c < 3; c++) {
                se += (double)(e[c] - tr[c]) * (e[c] - tr[c]);
                st += (double)tr[c] * tr[c];
            }
            n++;
        }
    printf("%s energy %.4f nrmse %.4f meanY_est %.6g meanY_truth %.6g\n", label, yt != 0 ? ye / yt : NAN,
           st > 0 ? sqrt(se / st) : NAN, n > 0 ? ye / n : NAN, n > 0 ? yt / n : NAN);
    return 0;
}

static int
furnace(int argc, char **argv)
{
    if (argc != 5 && argc != 6) {
        fprintf(stderr, "usage: gi-metric furnace IMG ALBEDO RADIANCE [BOUNCES]\n");
        return 2;
    }
    cg_image a;
    load(argv[2], &a);
    double albedo = atof(argv[3]), L = atof(argv[4]), sum = 0, worst = 0, n = 0;
    int bounces = argc == 6 ? atoi(argv[5]) : 0;
    if (!(albedo > 0) || !(L > 0) || bounces < 0) {
        fprintf(stderr, "gi-metric: furnace needs albedo and radiance above 0, bounces at least 0\n");
        return 2;
    }
    double series = 0, power = 1;
    for (int k = 1; k <= bounces + 1; k++)
        series += power *= albedo;
    for (size_t i = 0; i < (size_t)a.width * (size_t)a.height; i++)
        for (int c = 0; c < 3; c++) {
            double g = (a.rgba[4 * i + (size_t)c] - L) / (series * L);
            sum += g;
            n++;
            worst = fmax(worst, fabs(g - 1));
        }
    printf("furnace mean %.5f worst %.3f%%\n", sum / n, 100 * worst);
    return 0;
}

static int
mean(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: gi-metric mean IMG [--rect x0 y0 x1 y1]\n");
        return 2;
    }
    cg_image a;
    load(argv[2], &a);
    rect r;
    options(argc, argv, 3, &a, &r, NULL);
    double sum = 0, n = 0;
    for (int y = r.y0; y < r.y1; y++)
        for (int x = r.x0; x < r.x1; x++) {
            float v = a.rgba[4 * ((size_t)y * (size_t)a.width + (size_t)x)];
            if (v > 0.0f) {
                sum += v;
                n++;
            }
        }
    printf("mean %.2f over %.0f pixels\n", n > 0 ? sum / n : 0.0, n);
    return 0;
}

static int
sum(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: gi-metric sum A B OUT\n");
        return 2;
    }
    cg_image a, b;
    load(argv[2], &a);
    load(argv[3], &b);
    same_size(&a, &b, argv[3]);
    for (size_t i = 0; i < (size_t)a.width * (size_t)a.height; i++) {
        for (int c = 0; c < 3; c++)
            a.rgba[4 * i + (size_t)c] += b.rgba[4 * i + (size_t)c];
        a.rgba[4 * i + 3] = 1.0f;
    }
    cg_error err = {0};
    if (!cg_image_write(argv[4], &a, CG_EXR_FLOAT, &err)) {
        fprintf(stderr, "gi-metric: %s\n", err.message);
        return 2;
    }
    return 0;
}

int
main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "indirect"))
        return indirect(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "furnace"))
        return furnace(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "mean"))
        return mean(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "sum"))
        return sum(argc, argv);
    fprintf(stderr, "usage: gi-metric indirect|furnace|mean|sum ... (tests/tools/gi_metric.c)\n");
    return 2;
}
