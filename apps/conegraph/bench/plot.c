/* Plots drawn in C into a cg_image: see plot.h. */
#include "plot.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A 5x7 bitmap font (rows top to bottom, bit 4 = leftmost column), after the HD44780 ROM. */
typedef struct glyph {
    char c;
    unsigned char rows[7];
} glyph;

static const glyph font[] = {
    { '0', { 0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E } }, { '1', { 0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E } },
    { '2', { 0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F } }, { '3', { 0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E } },
    { '4', { 0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02 } }, { '5', { 0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E } },
    { '6', { 0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E } }, { '7', { 0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08 } },
    { '8', { 0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E } }, { '9', { 0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C } },
    { 'A', { 0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11 } }, { 'B', { 0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E } },
    { 'C', { 0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E } }, { 'D', { 0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C } },
    { 'E', { 0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F } }, { 'F', { 0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10 } },
    { 'G', { 0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F } }, { 'H', { 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11 } },
    { 'I', { 0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E } }, { 'J', { 0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C } },
    { 'K', { 0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11 } }, { 'L', { 0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F } },
    { 'M', { 0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11 } }, { 'N', { 0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11 } },
    { 'O', { 0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E } }, { 'P', { 0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10 } },
    { 'Q', { 0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D } }, { 'R', { 0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11 } },
    { 'S', { 0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E } }, { 'T', { 0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04 } },
    { 'U', { 0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E } }, { 'V', { 0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04 } },
    { 'W', { 0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A } }, { 'X', { 0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11 } },
    { 'Y', { 0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04 } }, { 'Z', { 0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F } },
    { '.', { 0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C } }, { '-', { 0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00 } },
    { '+', { 0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00 } }, { '(', { 0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02 } },
    { ')', { 0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08 } }, { '/', { 0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00 } },
    { ':', { 0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00 } }, { '=', { 0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00 } },
    { ',', { 0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08 } }, { '_', { 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F } },
    { '%', { 0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03 } }, { '*', { 0x00, 0x04, 0x15, 0x0E, 0x15, 0x04, 0x00 } },
};

typedef struct canvas {
    cg_image *img;
} canvas;

static float
srgb_to_linear(float v)
{
    return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

static void
put(canvas *cv, int x, int y, const float srgb[3])
{
    cg_image *img = cv->img;
    if (x < 0 || y < 0 || x >= img->width || y >= img->height)
        return;
    float *p = &img->rgba[4 * ((size_t)y * img->width + x)];
    for (int c = 0; c < 3; c++)
        p[c] = srgb_to_linear(srgb[c]);
    p[3] = 1.0f;
}

static void
fill_rect(canvas *cv, int x0, int y0, int x1, int y1, const float c[3])
{
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++)
            put(cv, x, y, c);
}

static void
line(canvas *cv, int x0, int y0, int x1, int y1, int thickness, const float c[3])
{
    int dx = abs(x1 - x0), dy = -abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int e = dx + dy, r = thickness / 2;
    for (;;) {
        fill_rect(cv, x0 - r, y0 - r, x0 - r + thickness - 1, y0 - r + thickness - 1, c);
        if (x0 == x1 && y0 == y1)
            break;
        int e2 = 2 * e;
        if (e2 >= dy) {
            e += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            e += dx;
            y0 += sy;
        }
    }
}

static void
ring(canvas *cv, int cx, int cy, int radius, const float c[3])
{
    for (int y = -radius - 1; y <= radius + 1; y++)
        for (int x = -radius - 1; x <= radius + 1; x++) {
            double d = sqrt((double)(x * x + y * y));
            if (d >= radius - 1.0 && d <= radius + 1.0)
                put(cv, cx + x, cy + y, c);
        }
}

static const glyph *
glyph_for(char c)
{
    c = (char)toupper((unsigned char)c);
    for (size_t i = 0; i < sizeof font / sizeof font[0]; i++)
        if (font[i].c == c)
            return &font[i];
    return NULL; /* space and characters without a glyph leave a gap */
}

static int
text_width(const char *s, int scale)
{
    return (int)strlen(s) * 6 * scale;
}

/* Text from (x, y), its glyphs' top-left corner; vertical: rotated 90 degrees counter-clockwise,
 * read bottom to top, (x, y) the bottom-left corner of the first glyph. */
static void
draw_text(canvas *cv, int x, int y, const char *s, int scale, bool vertical, const float c[3])
{
    for (; *s; s++) {
        const glyph *g = glyph_for(*s);
        for (int r = 0; g && r < 7; r++)
            for (int col = 0; col < 5; col++) {
                if (!(g->rows[r] & (0x10 >> col)))
                    continue;
                /* Glyph row r, column col: down and right, or right and up when vertical. */
                int px = vertical ? x + r * scale : x + col * scale;
                int py = vertical ? y - col * scale - scale + 1 : y + r * scale;
                fill_rect(cv, px, py, px + scale - 1, py + scale - 1, c);
            }
        if (vertical)
            y -= 6 * scale;
        else
            x += 6 * scale;
    }
}

static void
text(canvas *cv, int x, int y, const char *s, int scale, const float c[3])
{
    draw_text(cv, x, y, s, scale, false, c);
}

/* Whether (x, y) lies inside the marker of shape m of half-size r centred at the origin. */
static bool
inside_marker(plot_marker m, int x, int y, int r)
{
    int ax = abs(x), ay = abs(y);
    switch (m) {
    case PLOT_CIRCLE:
        return x * x + y * y <= r * r + r;
    case PLOT_TRIANGLE:
        /* Apex up: width grows from the top row (y = -r) to the full base at y = r. */
        return ay <= r && 2 * ax <= y + r;
    case PLOT_DIAMOND:
        return ax + ay <= r;
    case PLOT_CROSS:
        return ax <= r && ay <= r && abs(ax - ay) <= r / 3;
    case PLOT_PLUS:
        return ax <= r && ay <= r && (ax <= r / 3 || ay <= r / 3);
    case PLOT_SQUARE:
    default:
        return ax <= r && ay <= r;
    }
}

/* A marker: the shape in black at half-size 4, its inside at half-size 3 in the colour
 * (a square is thus 7x7 colour pixels in a 9x9 outline). */
static void
marker(canvas *cv, plot_marker m, int cx, int cy, const float c[3])
{
    static const float black[3] = { 0, 0, 0 };
    for (int y = -5; y <= 5; y++)
        for (int x = -5; x <= 5; x++) {
            if (inside_marker(m, x, y, 3))
                put(cv, cx + x, cy + y, c);
            else if (inside_marker(m, x, y, 4))
                put(cv, cx + x, cy + y, black);
        }
}

typedef struct axis {
    bool log;
    double lo, hi;      /* in axis units (log10 of the value on log axes) */
    int p0, p1;         /* pixel positions of lo and hi */
} axis;

static bool
usable(double v, bool log_axis)
{
    return isfinite(v) && (!log_axis || v > 0.0);
}

static void
axis_fit(axis *a, const plot_desc *plot, bool is_x)
{
    double lo = INFINITY, hi = -INFINITY;
    for (int s = 0; s < plot->series_count; s++) {
        const plot_series *ser = &plot->series[s];
        for (int i = 0; i < ser->count; i++) {
            double v = is_x ? ser->x[i] : ser->y[i];
            if (!usable(ser->x[i], plot->logx) || !usable(ser->y[i], plot->logy))
                continue;
            v = a->log ? log10(v) : v;
            lo = fmin(lo, v);
            hi = fmax(hi, v);
        }
    }
    if (!isfinite(lo)) {
        lo = 0.0;
        hi = 1.0;
    }
    if (a->log) {
        lo = floor(lo);
        hi = ceil(hi);
        if (hi <= lo)
            hi = lo + 1.0;
    } else {
        double span = hi - lo;
        if (span <= 0.0)
            span = fabs(hi) > 0.0 ? fabs(hi) : 1.0;
        double step = pow(10.0, floor(log10(span / 4.0)));
        bool non_negative = lo >= 0.0;
        lo = floor((lo - 0.05 * span) / step) * step;
        hi = ceil((hi + 0.05 * span) / step) * step;
        /* Quantities that cannot be negative (bytes, times) keep their axis at 0. */
        if (non_negative && lo < 0.0)
            lo = 0.0;
    }
    a->lo = lo;
    a->hi = hi;
}

static int
axis_pixel(const axis *a, double v)
{
    double t = ((a->log ? log10(v) : v) - a->lo) / (a->hi - a->lo);
    return (int)lround(a->p0 + t * (a->p1 - a->p0));
}

/* Tick values: every decade on log axes, about 5 round steps on linear ones. */
static int
axis_ticks(const axis *a, double *ticks, int max)
{
    int n = 0;
    if (a->log) {
        for (double e = a->lo; e <= a->hi + 1e-9 && n < max; e += 1.0)
            ticks[n++] = pow(10.0, e);
        return n;
    }
    double span = a->hi - a->lo, step = pow(10.0, floor(log10(span / 4.0)));
    if (span / step > 10.0)
        step *= 2.0;
    for (double v = ceil(a->lo / step) * step; v <= a->hi + 1e-9 * span && n < max; v += step)
        ticks[n++] = v;
    return n;
}

typedef struct box {
    int x0, y0, x1, y1;
} box;

static bool
overlaps(const box *a, const box *b)
{
    return a->x0 <= b->x1 && b->x0 <= a->x1 && a->y0 <= b->y1 && b->y0 <= a->y1;
}

/* Point labels, after every marker: each goes right of its point, else left, above or below,
 * whichever first stays inside the plot area clear of the labels placed before it; a label
 * with no such place is left out rather than drawn over another. */
static bool
place_labels(canvas *cv, const plot_desc *plot, const axis *ax, const axis *ay, cg_error *err)
{
    static const float label_color[3] = { 0.25f, 0.25f, 0.25f };
    int total = 0;
    for (int s = 0; s < plot->series_count; s++)
        total += plot->series[s].labels ? plot->series[s].count : 0;
    box *placed = malloc(sizeof *placed * (size_t)(total > 0 ? total : 1));
    if (!placed)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "plot labels");
    int n = 0;
    for (int s = 0; s < plot->series_count; s++) {
        const plot_series *ser = &plot->series[s];
        for (int i = 0; ser->labels && i < ser->count; i++) {
            const char *label = ser->labels[i];
            if (!label || !*label || !usable(ser->x[i], plot->logx) || !usable(ser->y[i], plot->logy))
                continue;
            int px = axis_pixel(ax, ser->x[i]), py = axis_pixel(ay, ser->y[i]), tw = text_width(label, 1);
            const box candidates[4] = {
                { px + 8, py - 3, px + 8 + tw, py + 4 }, { px - 8 - tw, py - 3, px - 8, py + 4 },
                { px - tw / 2, py - 16, px - tw / 2 + tw, py - 9 }, { px - tw / 2, py + 9, px - tw / 2 + tw, py + 16 },
            };
            for (int k = 0; k < 4; k++) {
                const box *b = &candidates[k];
                bool free_spot = b->x0 >= ax->p0 && b->x1 <= ax->p1 && b->y0 >= ay->p1 && b->y1 <= ay->p0;
                for (int j = 0; free_spot && j < n; j++)
                    free_spot = !overlaps(b, &placed[j]);
                if (free_spot) {
                    text(cv, b->x0, b->y0, label, 1, label_color);
                    placed[n++] = *b;
                    break;
                }
            }
        }
    }
    free(placed);
    return true;
}

bool
plot_render(const plot_desc *plot, cg_image *out, cg_error *err)
{
    int w = plot->width > 0 ? plot->width : 720, h = plot->height > 0 ? plot->height : 480;
    size_t bytes = (size_t)w * (size_t)h * 4 * sizeof(float);
    out->rgba = malloc(bytes);
    if (!out->rgba)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "plot of %dx%d", w, h);
    out->width = w;
    out->height = h;
    for (size_t i = 0; i < (size_t)w * h * 4; i++)
        out->rgba[i] = 1.0f;
    canvas cv = { out };
    static const float black[3] = { 0, 0, 0 }, grid[3] = { 0.88f, 0.88f, 0.88f };
    const int left = 96, right = 40, top = 40, bottom = 64;
    axis ax = { .log = plot->logx, .p0 = left, .p1 = w - right - 1 };
    axis ay = { .log = plot->logy, .p0 = h - bottom, .p1 = top };
    axis_fit(&ax, plot, true);
    axis_fit(&ay, plot, false);

    double ticks[32];
    char label[32];
    int n = axis_ticks(&ax, ticks, 32);
    for (int i = 0; i < n; i++) {
        int px = axis_pixel(&ax, ticks[i]);
        line(&cv, px, ay.p1, px, ay.p0, 1, grid);
        line(&cv, px, ay.p0, px, ay.p0 + 5, 1, black);
        snprintf(label, sizeof label, "%g", ticks[i]);
        text(&cv, px - text_width(label, 2) / 2, ay.p0 + 10, label, 2, black);
    }
    n = axis_ticks(&ay, ticks, 32);
    for (int i = 0; i < n; i++) {
        int py = axis_pixel(&ay, ticks[i]);
        line(&cv, ax.p0, py, ax.p1, py, 1, grid);
        line(&cv, ax.p0 - 5, py, ax.p0, py, 1, black);
        snprintf(label, sizeof label, "%g", ticks[i]);
        text(&cv, ax.p0 - 8 - text_width(label, 2), py - 7, label, 2, black);
    }
    line(&cv, ax.p0, ay.p0, ax.p1, ay.p0, 2, black);
    line(&cv, ax.p0, ay.p0, ax.p0, ay.p1, 2, black);
    if (plot->title)
        text(&cv, (w - text_width(plot->title, 2)) / 2, 10, plot->title, 2, black);
    if (plot->xlabel)
        text(&cv, (ax.p0 + ax.p1 - text_width(plot->xlabel, 2)) / 2, h - 24, plot->xlabel, 2, black);
    if (plot->ylabel)
        draw_text(&cv, 8, (ay.p0 + ay.p1 + text_width(plot->ylabel, 2)) / 2, plot->ylabel, 2, true, black);

    for (int s = 0; s < plot->series_count; s++) {
        const plot_series *ser = &plot->series[s];
        if (ser->line) {
            /* Join in x order (the caller's order may be anything). */
            int *order = malloc(sizeof(int) * (size_t)(ser->count > 0 ? ser->count : 1));
            if (!order)
                return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "plot series");
            int m = 0;
            for (int i = 0; i < ser->count; i++)
                if (usable(ser->x[i], plot->logx) && usable(ser->y[i], plot->logy))
                    order[m++] = i;
            for (int i = 1; i < m; i++)
                for (int j = i; j > 0 && ser->x[order[j]] < ser->x[order[j - 1]]; j--) {
                    int t = order[j];
                    order[j] = order[j - 1];
                    order[j - 1] = t;
                }
            for (int i = 1; i < m; i++)
                line(&cv, axis_pixel(&ax, ser->x[order[i - 1]]), axis_pixel(&ay, ser->y[order[i - 1]]),
                     axis_pixel(&ax, ser->x[order[i]]), axis_pixel(&ay, ser->y[order[i]]), 2, ser->color);
            free(order);
        }
        for (int i = 0; i < ser->count; i++) {
            if (!usable(ser->x[i], plot->logx) || !usable(ser->y[i], plot->logy))
                continue;
            int px = axis_pixel(&ax, ser->x[i]), py = axis_pixel(&ay, ser->y[i]);
            if (ser->ring)
                ring(&cv, px, py, 8, ser->color);
            else
                marker(&cv, ser->markers ? ser->markers[i] : PLOT_SQUARE, px, py, ser->color);
        }
    }
    if (!place_labels(&cv, plot, &ax, &ay, err))
        return false;
    /* Legend, top right inside the plot area. */
    int ly = ay.p1 + 8;
    for (int s = 0; s < plot->series_count; s++) {
        const plot_series *ser = &plot->series[s];
        if (!ser->name)
            continue;
        int tw = text_width(ser->name, 2);
        int lx = ax.p1 - tw - 30;
        fill_rect(&cv, lx - 4, ly - 2, ax.p1 - 4, ly + 16, (const float[3]){ 1, 1, 1 });
        if (ser->ring)
            ring(&cv, lx + 8, ly + 7, 6, ser->color);
        else
            marker(&cv, ser->markers && ser->count ? ser->markers[0] : PLOT_SQUARE, lx + 8, ly + 7, ser->color);
        text(&cv, lx + 22, ly, ser->name, 2, black);
        ly += 20;
    }
    return true;
}

bool
plot_write_png(const plot_desc *plot, const char *path, cg_error *err)
{
    cg_image img = { 0 };
    if (!plot_render(plot, &img, err))
        return false;
    bool ok = cg_image_write(path, &img, CG_EXR_HALF, err);
    cg_image_free(&img);
    return ok;
}
