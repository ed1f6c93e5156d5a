/* apps/conegraph/bench/plot.h: scatter and line plots drawn in C into a cg_image (for bench).
 *
 * Declares: plot_marker, plot_series, plot_desc, plot_render, plot_write_png, plot_colour_scale,
 *           plot_error_heatmap.
 *
 * No plotting dependency: axes with decade ticks (and 2, 5 between them on short log axes) or
 * round linear steps, their numbers thinned until they stand apart; a 5x7 bitmap font (upper
 * and lower case with descenders, digits, punctuation); markers of six shapes; point labels
 * that every labelled point gets (moved clear of markers and other labels, with a thin line to
 * their point when moved away); lines; the legend right of the plot area, clear of the points.
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
    const char *name;       /* legend text; NULL: no legend entry (e.g. a second part of one) */
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
    int width, height;      /* 0 = 960 x 560 */
} plot_desc;

/* Draws into *out (allocated here). Non-finite and, on log axes, non-positive points are skipped. */
bool plot_render(const plot_desc *plot, cg_image *out, cg_error *err);
bool plot_write_png(const plot_desc *plot, const char *path, cg_error *err);

/* *out (allocated here) = `map` with a colour scale beneath it (the image widened to 360
 * pixels with white where narrower): `ramp`'s columns stretched into a bar from 0 (left) to
 * max_value (right, "MAX+": values above are clamped to it), five numbered ticks and
 * `caption` (what the colour measures; '\n' starts a new line) under them. `ramp` is one row of the map's own colours
 * for values 0..max_value evenly spaced, so that the bar is drawn by the same colour map. */
bool plot_colour_scale(const cg_image *map, const cg_image *ramp, double max_value, const char *caption, cg_image *out,
                       cg_error *err);

/* *out (allocated here) = cg_metrics_heatmap of test against ref, with its colour scale
 * (plot_colour_scale) from 0 to max_value (<= 0: 1) and a caption saying what it measures. */
bool plot_error_heatmap(const cg_image *test, const cg_image *ref, double max_value, cg_image *out, cg_error *err);

#endif
