/* tests/tools/gi_metric.c: the two figures of docs/vct.md's GI measurements that `conegraph
 * compare` does not give, from images that `conegraph render` wrote (tests/tools/gi_measure.sh
 * runs the renders; the indirect light's energy and nrmse are compare's --direct/--ref-direct,
 * core/metrics' cg_metrics_part, so that there is one implementation of them).
 *
 *   gi-metric furnace IMG.exr ALBEDO RADIANCE [BOUNCES]
 *       the white furnace: every pixel should be L sum_{k=0..B+1} a^k, path_trace's value at
 *       `bounces` B (default 0: the emission seen plus one gathered reflection, what a radiance-
 *       model graph returns); prints the mean of (pixel - L) / (L sum_{k=1..B+1} a^k) over pixels
 *       and RGB and the worst |. - 1|.
 *   gi-metric mean IMG.exr [--rect x0 y0 x1 y1]
 *       mean red channel over the pixels whose red is above 0 (a gather's `reads` output: volume
 *       reads per covered pixel), and its distribution: median, 99th percentile and maximum (a
 *       group of pixels runs in lockstep on llvmpipe, so the slowest pixels set the cost).
 * Exit codes: 0, 2 for bad arguments or unreadable images.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/error.h"
#include "cg/image.h"

static void
load(const char *path, cg_image *img)
{
    cg_error err = {0};
    if (!cg_image_read(path, img, &err)) {
        fprintf(stderr, "gi-metric: %s\n", err.message);
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
compare_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
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
    float *values = malloc(sizeof *values * (size_t)(r.x1 - r.x0) * (size_t)(r.y1 - r.y0));
    if (!values) {
        fprintf(stderr, "gi-metric: out of memory\n");
        return 1;
    }
    double sum = 0;
    size_t n = 0;
    for (int y = r.y0; y < r.y1; y++)
        for (int x = r.x0; x < r.x1; x++) {
            float v = a.rgba[4 * ((size_t)y * (size_t)a.width + (size_t)x)];
            if (v > 0.0f) {
                sum += v;
                values[n++] = v;
            }
        }
    qsort(values, n, sizeof *values, compare_float);
    printf("mean %.2f over %zu pixels", n > 0 ? sum / (double)n : 0.0, n);
    if (n > 0)
        printf(" median %.0f p99 %.0f max %.0f", values[n / 2], values[(n * 99) / 100], values[n - 1]);
    printf("\n");
    free(values);
    return 0;
}

int
main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "furnace"))
        return furnace(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "mean"))
        return mean(argc, argv);
    fprintf(stderr, "usage: gi-metric furnace|mean ... (tests/tools/gi_metric.c)\n");
    return 2;
}
