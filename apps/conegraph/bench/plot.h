/* apps/conegraph/bench/plot.h: scatter and line plots drawn in C into a cg_image (for bench).
 *
 * Declares: plot_marker, plot_series, plot_desc, plot_render, plot_write_png.
 *
 * No plotting dependency: axes, decade ticks, a 5x7 bitmap font (upper-case letters,
 * digits and a little punctuation; lower case is drawn as upper case), markers of six
 * shapes, point labels and lines.
 */
#ifndef CONEGRAPH_PLOT_H
#define CONEGRAPH_PLOT_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/image.h"

/* Marker shapes, each filled with the series colour inside a black outline. */
typedef enum plot_marker {
    PLOT_SQUARE,
    PLOT_CIRCLE,
    PLOT_TRIANGLE,
    PLOT_DIAMOND,
    PLOT_CROSS,
    PLOT_PLUS,
    PLOT_MARKER_COUNT
} plot_marker;

typedef struct plot_series {
    const char *name;       /* legend text */
    float color[3];         /* sRGB 0..1 */
    const double *x, *y;
    int count;
    bool line;              /* join the points in x order */
    bool ring;              /* draw rings (a highlighted subset, such as a Pareto front) */
    const plot_marker *markers;     /* per point; NULL: squares */
    const char *const *labels;      /* per point, written beside it (NULL or "" for none); NULL: none */
} plot_series;

typedef struct plot_desc {
    const char *title;
    const char *xlabel, *ylabel;
    bool logx, logy;
    const plot_series *series;
    int series_count;
    int width, height;      /* 0 = 720 x 480 */
} plot_desc;

/* Draws into *out (allocated here). Non-finite and, on log axes, non-positive points are skipped. */
bool plot_render(const plot_desc *plot, cg_image *out, cg_error *err);
bool plot_write_png(const plot_desc *plot, const char *path, cg_error *err);

#endif
