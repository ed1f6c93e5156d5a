/* Plots drawn in C into a cg_image: see plot.h. */
#include "plot.h"

#include "cg/metrics.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A 5x7 bitmap font (rows top to bottom, bit 4 = leftmost column), after the HD44780 ROM, with
 * two rows below the baseline for the descenders of g, j, p, q and y. */
#define GLYPH_ROWS 9
/* A line of text: the glyph rows and one row apart, in font pixels. */
#define LINE_ROWS (GLYPH_ROWS + 1)

typedef struct glyph {
    char c;
    unsigned char rows[GLYPH_ROWS];
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
    { '[', { 0x0E, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0E } }, { ']', { 0x0E, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0E } },
    { '<', { 0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02 } }, { '>', { 0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08 } },
    { '?', { 0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04 } }, { '!', { 0x04, 0x04, 0x04, 0x04, 0x04, 0x00, 0x04 } },
    { '\'', { 0x04, 0x04, 0x08, 0x00, 0x00, 0x00, 0x00 } }, { '#', { 0x0A, 0x0A, 0x1F, 0x0A, 0x1F, 0x0A, 0x0A } },
    { '&', { 0x0C, 0x12, 0x14, 0x08, 0x15, 0x12, 0x0D } }, { '^', { 0x04, 0x0A, 0x11, 0x00, 0x00, 0x00, 0x00 } },
    { ';', { 0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x04, 0x08 } },
    /* Lower case: the x-height is rows 2..6. */
    { 'a', { 0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F } }, { 'b', { 0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E } },
    { 'c', { 0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E } }, { 'd', { 0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F } },
    { 'e', { 0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E } }, { 'f', { 0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08 } },
    { 'g', { 0x00, 0x00, 0x0F, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x0E } },
    { 'h', { 0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11 } }, { 'i', { 0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E } },
    { 'j', { 0x02, 0x00, 0x06, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C } },
    { 'k', { 0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12 } }, { 'l', { 0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E } },
    { 'm', { 0x00, 0x00, 0x1A, 0x15, 0x15, 0x15, 0x15 } }, { 'n', { 0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11 } },
    { 'o', { 0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E } },
    { 'p', { 0x00, 0x00, 0x1E, 0x11, 0x11, 0x11, 0x1E, 0x10, 0x10 } },
    { 'q', { 0x00, 0x00, 0x0F, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x01 } },
    { 'r', { 0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10 } }, { 's', { 0x00, 0x00, 0x0F, 0x10, 0x0E, 0x01, 0x1E } },
    { 't', { 0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06 } }, { 'u', { 0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D } },
    { 'v', { 0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04 } }, { 'w', { 0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A } },
    { 'x', { 0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11 } },
    { 'y', { 0x00, 0x00, 0x11, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x0E } },
    { 'z', { 0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F } },
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
    for (size_t i = 0; i < sizeof font / sizeof font[0]; i++)
        if (font[i].c == c)
            return &font[i];
    char upper = (char)toupper((unsigned char)c);
    for (size_t i = 0; upper != c && i < sizeof font / sizeof font[0]; i++)
        if (font[i].c == upper)
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
        for (int r = 0; g && r < GLYPH_ROWS; r++)
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

typedef struct tick {
    double value;
    bool major;         /* a decade on a log axis; every tick on a linear one */
} tick;

/* Tick values: every decade on log axes, with 2 and 5 between them where there are at most two
 * decades (so that a short axis is not left with two numbers); on linear ones 1, 2 or 5 times
 * a power of ten, about five of them. */
static int
axis_ticks(const axis *a, tick *ticks, int max)
{
    int n = 0;
    if (a->log) {
        bool minor = a->hi - a->lo <= 2.0 + 1e-9;
        for (double e = a->lo; e <= a->hi + 1e-9 && n < max; e += 1.0) {
            double decade = pow(10.0, e);
            ticks[n++] = (tick){ decade, true };
            for (int m = 0; minor && m < 2 && n < max && e + 1.0 <= a->hi + 1e-9; m++)
                ticks[n++] = (tick){ decade * (m ? 5.0 : 2.0), false };
        }
        return n;
    }
    double span = a->hi - a->lo, step = pow(10.0, floor(log10(span / 4.0)));
    if (span / step > 10.0)
        step *= 5.0;
    else if (span / step > 5.0)
        step *= 2.0;
    for (double v = ceil(a->lo / step - 1e-9) * step; v <= a->hi + 1e-9 * span && n < max; v += step)
        ticks[n++] = (tick){ fabs(v) < 1e-9 * span ? 0.0 : v, true };
    return n;
}

static void
tick_text(double v, char *out, size_t size)
{
    snprintf(out, size, "%g", v);
}

/* Which ticks get a number: all where the numbers stay `gap` pixels apart along the axis,
 * else the major ones, else every second, third... major one. */
static void
tick_labelled(const axis *a, const tick *ticks, int n, bool horizontal, int scale, bool *labelled)
{
    for (int pass = 0; pass < 2 + n; pass++) {
        int stride = pass < 2 ? 1 : pass;
        int seen = 0, last_end = -1000000;
        bool clear = true;
        for (int i = 0; i < n; i++) {
            labelled[i] = false;
            if (pass > 0 && !ticks[i].major)
                continue;
            if (seen++ % stride)
                continue;
            labelled[i] = true;
            char t[32];
            tick_text(ticks[i].value, t, sizeof t);
            int p = axis_pixel(a, ticks[i].value);
            /* Horizontal axis: the numbers' widths; vertical: their heights (pixels run down). */
            int extent = horizontal ? text_width(t, scale) : 7 * scale;
            int start = horizontal ? p - extent / 2 : -p - extent / 2;
            if (start < last_end + 3 * scale * 2)
                clear = false;
            last_end = start + extent;
        }
        if (clear)
            return;
    }
}

typedef struct box {
    int x0, y0, x1, y1;
} box;

static bool
overlaps(const box *a, const box *b)
{
    return a->x0 <= b->x1 && b->x0 <= a->x1 && a->y0 <= b->y1 && b->y0 <= a->y1;
}

static long
overlap_area(const box *a, const box *b)
{
    if (!overlaps(a, b))
        return 0;
    long w = (a->x1 < b->x1 ? a->x1 : b->x1) - (a->x0 > b->x0 ? a->x0 : b->x0) + 1;
    long h = (a->y1 < b->y1 ? a->y1 : b->y1) - (a->y0 > b->y0 ? a->y0 : b->y0) + 1;
    return w * h;
}

/* The usable points of a series in x order (the caller's order may be anything): their
 * indices into order (sized ser->count); returns how many. */
static int
series_order(const plot_desc *plot, const plot_series *ser, int *order)
{
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
    return m;
}

/* Boxes a label should keep clear of: every marker, and the lines, as 5x5 boxes every 4 pixels
 * along them. *out is allocated here; returns the count, or -1 when out of memory. */
static int
obstacles(const plot_desc *plot, const axis *ax, const axis *ay, int extra, box **out)
{
    int cap = extra + 64, n = 0;
    box *b = malloc(sizeof *b * (size_t)cap);
    int *order = NULL;
    for (int s = 0; b && s < plot->series_count; s++) {
        const plot_series *ser = &plot->series[s];
        free(order);
        order = malloc(sizeof(int) * (size_t)(ser->count > 0 ? ser->count : 1));
        if (!order)
            break;
        int m = series_order(plot, ser, order), r = ser->ring ? 9 : 5;
        for (int k = 0; k < m; k++) {
            int px = axis_pixel(ax, ser->x[order[k]]), py = axis_pixel(ay, ser->y[order[k]]);
            int steps = 0, qx = px, qy = py;
            if (ser->line && k + 1 < m) {
                qx = axis_pixel(ax, ser->x[order[k + 1]]);
                qy = axis_pixel(ay, ser->y[order[k + 1]]);
                steps = (int)(hypot(qx - px, qy - py) / 4.0);
            }
            if (n + steps + 1 + extra > cap) {
                cap = 2 * (n + steps + 1 + extra);
                box *grown = realloc(b, sizeof *b * (size_t)cap);
                if (!grown) {
                    free(b);
                    b = NULL;
                    break;
                }
                b = grown;
            }
            b[n++] = (box){ px - r, py - r, px + r, py + r };
            for (int t = 1; t < steps; t++) {
                int lx = px + (qx - px) * t / steps, ly = py + (qy - py) * t / steps;
                b[n++] = (box){ lx - 2, ly - 2, lx + 2, ly + 2 };
            }
        }
    }
    free(order);
    *out = b;
    return b ? n : -1;
}

/* Point labels, after every marker, so that every labelled point shows its label: each goes to
 * the first place around its point that stays inside the plot area clear of every marker, every
 * line and the labels placed before it: right, left, above, below, the four corners, then the same
 * farther out, joined to the point by a thin grey line. Where no place is clear, the one that
 * covers least is taken (a crowded plot overlaps rather than hides a point's name). */
static bool
place_labels(canvas *cv, const plot_desc *plot, const axis *ax, const axis *ay, cg_error *err)
{
    static const float label_color[3] = { 0.25f, 0.25f, 0.25f }, leader[3] = { 0.62f, 0.62f, 0.62f };
    int labels = 0;
    for (int s = 0; s < plot->series_count; s++)
        labels += plot->series[s].labels ? plot->series[s].count : 0;
    box *taken;
    int n = obstacles(plot, ax, ay, labels, &taken);
    if (n < 0)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "plot labels");
    for (int s = 0; s < plot->series_count; s++) {
        const plot_series *ser = &plot->series[s];
        for (int i = 0; ser->labels && i < ser->count; i++) {
            const char *label = ser->labels[i];
            if (!label || !*label || !usable(ser->x[i], plot->logx) || !usable(ser->y[i], plot->logy))
                continue;
            int px = axis_pixel(ax, ser->x[i]), py = axis_pixel(ay, ser->y[i]), tw = text_width(label, 1) - 1;
            const int th = GLYPH_ROWS - 1;
            box best = { 0 };
            long best_cost = -1;
            int best_ring = 0;
            for (int ring_index = 0; ring_index < 3 && best_cost != 0; ring_index++) {
                /* Clear of a ring (radius 8) at the nearest. */
                int d = 12 + 14 * ring_index;
                const box candidates[8] = {
                    { px + d, py - 3, px + d + tw, py - 3 + th },
                    { px - d - tw, py - 3, px - d, py - 3 + th },
                    { px - tw / 2, py - d - th, px - tw / 2 + tw, py - d },
                    { px - tw / 2, py + d, px - tw / 2 + tw, py + d + th },
                    { px + d - 2, py - d - th, px + d - 2 + tw, py - d },
                    { px - d + 2 - tw, py - d - th, px - d + 2, py - d },
                    { px + d - 2, py + d, px + d - 2 + tw, py + d + th },
                    { px - d + 2 - tw, py + d, px - d + 2, py + d + th },
                };
                for (int k = 0; k < 8; k++) {
                    const box *b = &candidates[k];
                    bool inside = b->x0 >= ax->p0 + 2 && b->x1 <= ax->p1 && b->y0 >= ay->p1 && b->y1 <= ay->p0 - 2;
                    long cost = inside ? 0 : 1L << 40;
                    for (int j = 0; j < n; j++)
                        cost += overlap_area(b, &taken[j]);
                    /* Farther out costs a little, so that a nearer place wins a tie in overlap. */
                    if (cost > 0)
                        cost += ring_index;
                    if (best_cost < 0 || cost < best_cost) {
                        best_cost = cost;
                        best = *b;
                        best_ring = ring_index;
                    }
                    if (cost == 0)
                        break;
                }
            }
            if (best_ring > 0) {
                /* From the marker's edge to the label's nearest point. */
                int lx = px < best.x0 ? best.x0 - 1 : px > best.x1 ? best.x1 + 1 : px;
                int ly = py < best.y0 ? best.y0 - 1 : py > best.y1 ? best.y1 + 1 : py;
                double len = hypot(lx - px, ly - py);
                if (len > 7.0)
                    line(cv, px + (int)lround((lx - px) * 6.0 / len), py + (int)lround((ly - py) * 6.0 / len), lx, ly,
                         1, leader);
            }
            text(cv, best.x0, best.y0, label, 1, label_color);
            taken[n++] = best;
        }
    }
    free(taken);
    return true;
}

/* The largest scale (2 or 1) at which `s` fits in `room` pixels. */
static int
fitting_scale(const char *s, int room)
{
    return text_width(s, 2) <= room ? 2 : 1;
}

bool
plot_render(const plot_desc *plot, cg_image *out, cg_error *err)
{
    int w = plot->width > 0 ? plot->width : 960, h = plot->height > 0 ? plot->height : 560;
    size_t bytes = (size_t)w * (size_t)h * 4 * sizeof(float);
    out->rgba = malloc(bytes);
    if (!out->rgba)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "plot of %dx%d", w, h);
    out->width = w;
    out->height = h;
    for (size_t i = 0; i < (size_t)w * h * 4; i++)
        out->rgba[i] = 1.0f;
    canvas cv = { out };
    static const float black[3] = { 0, 0, 0 }, grid[3] = { 0.88f, 0.88f, 0.88f }, minor_grid[3] = { 0.95f, 0.95f, 0.95f };

    /* The legend stands right of the plot area, never over the points: at scale 2 where that
     * takes at most two fifths of the width, else at scale 1. */
    int legend_scale = 2, legend_text = 0, named = 0;
    for (int pass = 0; pass < 2; pass++) {
        legend_text = 0;
        for (int s = 0; s < plot->series_count; s++)
            if (plot->series[s].name) {
                int tw = text_width(plot->series[s].name, legend_scale);
                legend_text = tw > legend_text ? tw : legend_text;
                named += pass == 0;
            }
        if (legend_text + 40 <= w * 2 / 5)
            break;
        legend_scale = 1;
    }
    int legend_w = named ? legend_text + 40 : 0;
    const int left = 96, right = named ? legend_w + 24 : 40, top = 44, bottom = 64;
    axis ax = { .log = plot->logx, .p0 = left, .p1 = w - right - 1 };
    axis ay = { .log = plot->logy, .p0 = h - bottom, .p1 = top };
    axis_fit(&ax, plot, true);
    axis_fit(&ay, plot, false);

    tick ticks[64];
    bool labelled[64];
    char label[32];
    int n = axis_ticks(&ax, ticks, 64);
    tick_labelled(&ax, ticks, n, true, 2, labelled);
    for (int i = 0; i < n; i++) {
        int px = axis_pixel(&ax, ticks[i].value);
        line(&cv, px, ay.p1, px, ay.p0, 1, ticks[i].major ? grid : minor_grid);
        line(&cv, px, ay.p0, px, ay.p0 + (labelled[i] ? 5 : 3), 1, black);
        if (!labelled[i])
            continue;
        tick_text(ticks[i].value, label, sizeof label);
        text(&cv, px - text_width(label, 2) / 2, ay.p0 + 10, label, 2, black);
    }
    n = axis_ticks(&ay, ticks, 64);
    tick_labelled(&ay, ticks, n, false, 2, labelled);
    for (int i = 0; i < n; i++) {
        int py = axis_pixel(&ay, ticks[i].value);
        line(&cv, ax.p0, py, ax.p1, py, 1, ticks[i].major ? grid : minor_grid);
        line(&cv, ax.p0 - (labelled[i] ? 5 : 3), py, ax.p0, py, 1, black);
        if (!labelled[i])
            continue;
        tick_text(ticks[i].value, label, sizeof label);
        text(&cv, ax.p0 - 8 - text_width(label, 2), py - 7, label, 2, black);
    }
    line(&cv, ax.p0, ay.p0, ax.p1, ay.p0, 2, black);
    line(&cv, ax.p0, ay.p0, ax.p0, ay.p1, 2, black);
    if (plot->title) {
        int scale = fitting_scale(plot->title, w - 16);
        text(&cv, (w - text_width(plot->title, scale)) / 2, 12, plot->title, scale, black);
    }
    if (plot->xlabel) {
        int scale = fitting_scale(plot->xlabel, ax.p1 - ax.p0);
        text(&cv, (ax.p0 + ax.p1 - text_width(plot->xlabel, scale)) / 2, h - 26, plot->xlabel, scale, black);
    }
    if (plot->ylabel) {
        int scale = fitting_scale(plot->ylabel, ay.p0 - ay.p1);
        draw_text(&cv, 8, (ay.p0 + ay.p1 + text_width(plot->ylabel, scale)) / 2, plot->ylabel, scale, true, black);
    }

    for (int s = 0; s < plot->series_count; s++) {
        const plot_series *ser = &plot->series[s];
        if (ser->line) {
            /* Join in x order (the caller's order may be anything). */
            int *order = malloc(sizeof(int) * (size_t)(ser->count > 0 ? ser->count : 1));
            if (!order)
                return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "plot series");
            int m = series_order(plot, ser, order);
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
    /* Legend: one line per named series, its marker (or ring) in its colour. */
    if (named) {
        static const float frame[3] = { 0.6f, 0.6f, 0.6f };
        int line_h = legend_scale == 2 ? 22 : 14, lx = w - legend_w - 8, ly = ay.p1;
        int boxed_h = named * line_h + 8;
        line(&cv, lx, ly, lx + legend_w, ly, 1, frame);
        line(&cv, lx, ly + boxed_h, lx + legend_w, ly + boxed_h, 1, frame);
        line(&cv, lx, ly, lx, ly + boxed_h, 1, frame);
        line(&cv, lx + legend_w, ly, lx + legend_w, ly + boxed_h, 1, frame);
        ly += 6;
        for (int s = 0; s < plot->series_count; s++) {
            const plot_series *ser = &plot->series[s];
            if (!ser->name)
                continue;
            int cy = ly + (legend_scale * 7) / 2;
            if (ser->line)
                line(&cv, lx + 4, cy, lx + 24, cy, 2, ser->color);
            if (ser->ring)
                ring(&cv, lx + 14, cy, 6, ser->color);
            else
                marker(&cv, ser->markers && ser->count ? ser->markers[0] : PLOT_SQUARE, lx + 14, cy, ser->color);
            text(&cv, lx + 30, ly, ser->name, legend_scale, black);
            ly += line_h;
        }
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

bool
plot_colour_scale(const cg_image *map, const cg_image *ramp, double max_value, const char *caption, cg_image *out,
                  cg_error *err)
{
    memset(out, 0, sizeof *out);
    int caption_lines = caption ? 1 : 0;
    for (const char *c = caption; c && *c; c++)
        caption_lines += *c == '\n';
    const int band = 36 + caption_lines * (LINE_ROWS + 1), margin = 12;
    int w = map->width > 360 ? map->width : 360, h = map->height + band;
    out->rgba = malloc((size_t)w * (size_t)h * 4 * sizeof(float));
    if (!out->rgba)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "colour scale of %dx%d", w, h);
    out->width = w;
    out->height = h;
    for (size_t i = 0; i < (size_t)w * h * 4; i++)
        out->rgba[i] = 1.0f;
    for (int y = 0; y < map->height; y++)
        memcpy(&out->rgba[4 * (size_t)y * w], &map->rgba[4 * (size_t)y * map->width],
               sizeof(float) * 4 * (size_t)map->width);
    canvas cv = { out };
    static const float black[3] = { 0, 0, 0 };
    /* The ramp's columns stretched over the bar, left (0) to right (max_value). */
    int x0 = margin, x1 = w - margin - 1, y0 = map->height + 6, y1 = y0 + 11;
    for (int x = x0; x <= x1; x++) {
        int k = (int)lround((double)(x - x0) / (x1 - x0) * (ramp->width - 1));
        for (int y = y0; y <= y1; y++)
            memcpy(&out->rgba[4 * ((size_t)y * w + x)], &ramp->rgba[4 * (size_t)k], sizeof(float) * 4);
    }
    for (int q = 0; q <= 4; q++) {
        int x = x0 + (int)lround(q / 4.0 * (x1 - x0));
        char t[32];
        snprintf(t, sizeof t, q == 4 ? "%g+" : "%g", max_value * q / 4.0);
        line(&cv, x, y1 + 1, x, y1 + 4, 1, black);
        int tx = x - text_width(t, 1) / 2;
        tx = tx < 2 ? 2 : tx + text_width(t, 1) > w - 2 ? w - 2 - text_width(t, 1) : tx;
        text(&cv, tx, y1 + 7, t, 1, black);
    }
    /* The caption a line at a time ('\n' breaks it). */
    int line_y = y1 + 7 + LINE_ROWS + 4;
    for (const char *c = caption; c && *c; line_y += LINE_ROWS + 1) {
        const char *end = strchr(c, '\n');
        char part[256];
        snprintf(part, sizeof part, "%.*s", (int)(end ? end - c : (long)strlen(c)), c);
        text(&cv, x0, line_y, part, 1, black);
        c = end ? end + 1 : c + strlen(c);
    }
    return true;
}

bool
plot_error_heatmap(const cg_image *test, const cg_image *ref, double max_value, cg_image *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    if (!(max_value > 0.0))
        max_value = 1.0;
    /* The ramp through the same map: a test pixel of t = e * sqrt(eps) over a black reference
     * has the relative error sqrt(t^2 / eps) = e in every channel. */
    enum { STEPS = 256 };
    cg_image zero = { 0 }, levels = { 0 }, ramp = { 0 }, map = { 0 };
    bool ok = cg_image_alloc(&zero, STEPS, 1, err) && cg_image_alloc(&levels, STEPS, 1, err);
    for (int i = 0; ok && i < STEPS; i++)
        for (int c = 0; c < 4; c++) {
            zero.rgba[4 * i + c] = c == 3 ? 1.0f : 0.0f;
            levels.rgba[4 * i + c] =
                c == 3 ? 1.0f : (float)(max_value * i / (STEPS - 1) * sqrt(CG_RELMSE_EPSILON));
        }
    ok = ok && cg_metrics_heatmap(&levels, &zero, max_value, &ramp, err) &&
         cg_metrics_heatmap(test, ref, max_value, &map, err);
    char caption[160];
    snprintf(caption, sizeof caption, "Relative error per pixel, sqrt(mean (t-r)^2/(r^2+%g))\nover RGB; magenta: not finite",
             CG_RELMSE_EPSILON);
    ok = ok && plot_colour_scale(&map, &ramp, max_value, caption, out, err);
    cg_image_free(&zero);
    cg_image_free(&levels);
    cg_image_free(&ramp);
    cg_image_free(&map);
    return ok;
}
