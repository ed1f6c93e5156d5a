/* Image error metrics: see cg/metrics.h for the definitions and their sources. */
#include "cg/metrics.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

double
cg_luminance(const float *rgb)
{
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

static bool
same_size(const cg_image *a, const cg_image *b, const char *what, cg_error *err)
{
    if (!a->rgba || !b->rgba || a->width <= 0 || a->height <= 0 || b->width <= 0 || b->height <= 0)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: empty image (%dx%d and %dx%d)", what, a->width,
                       a->height, b->width, b->height);
    if (a->width != b->width || a->height != b->height)
        return cg_fail(err, CG_ERR_IMAGE_FORMAT, "%s: image sizes differ: %dx%d against %dx%d", what,
                       a->width, a->height, b->width, b->height);
    return true;
}

/* Allocated here rather than through cg_image_alloc so that the metrics need nothing but
 * libc; the result is an ordinary cg_image (cg_image_free releases it). */
static bool
image_like(const cg_image *shape, cg_image *out, cg_error *err)
{
    size_t n = (size_t)shape->width * (size_t)shape->height * 4;
    out->rgba = calloc(n, sizeof(float));
    if (!out->rgba)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "image of %dx%d", shape->width, shape->height);
    out->width = shape->width;
    out->height = shape->height;
    return true;
}

static bool
pixel_finite(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static double
display_luminance(const float *rgb)
{
    /* sRGB encoding (IEC 61966-2-1) of luminance clamped to [0,1]. */
    double y = cg_luminance(rgb);
    y = y < 0.0 ? 0.0 : (y > 1.0 ? 1.0 : y);
    return y <= 0.0031308 ? 12.92 * y : 1.055 * pow(y, 1.0 / 2.4) - 0.055;
}

/* Separable Gaussian blur of `src` (w x h), truncated at the border and renormalised by the
 * weight that fell inside, so that border windows are proper weighted means. */
static void
gaussian_blur(const double *src, double *tmp, double *dst, int w, int h, const double *kernel, int radius)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double sum = 0.0, wsum = 0.0;
            for (int k = -radius; k <= radius; k++) {
                int xx = x + k;
                if (xx < 0 || xx >= w)
                    continue;
                sum += kernel[k + radius] * src[(size_t)y * w + xx];
                wsum += kernel[k + radius];
            }
            tmp[(size_t)y * w + x] = sum / wsum;
        }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double sum = 0.0, wsum = 0.0;
            for (int k = -radius; k <= radius; k++) {
                int yy = y + k;
                if (yy < 0 || yy >= h)
                    continue;
                sum += kernel[k + radius] * tmp[(size_t)yy * w + x];
                wsum += kernel[k + radius];
            }
            dst[(size_t)y * w + x] = sum / wsum;
        }
}

/* Mean SSIM, Wang et al. 2004 eq. 13 with the Gaussian-weighted statistics of their section
 * III-C. Non-finite pixels enter as 0 (they are counted separately). */
static bool
ssim_mean(const cg_image *test, const cg_image *ref, double *out, cg_error *err)
{
    int w = test->width, h = test->height;
    size_t n = (size_t)w * (size_t)h;
    double *buf = malloc(n * 7 * sizeof(double));
    if (!buf)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "SSIM buffers for %dx%d", w, h);
    double *x = buf, *y = buf + n, *prod = buf + 2 * n, *tmp = buf + 3 * n;
    double *mx = buf + 4 * n, *my = buf + 5 * n, *stat = buf + 6 * n;
    for (size_t i = 0; i < n; i++) {
        const float *t = &test->rgba[4 * i], *r = &ref->rgba[4 * i];
        bool ok = pixel_finite(t) && pixel_finite(r);
        x[i] = ok ? display_luminance(t) : 0.0;
        y[i] = ok ? display_luminance(r) : 0.0;
    }
    int radius = CG_SSIM_WINDOW / 2;
    double kernel[CG_SSIM_WINDOW];
    for (int k = -radius; k <= radius; k++)
        kernel[k + radius] = exp(-(double)(k * k) / (2.0 * CG_SSIM_SIGMA * CG_SSIM_SIGMA));
    gaussian_blur(x, tmp, mx, w, h, kernel, radius);
    gaussian_blur(y, tmp, my, w, h, kernel, radius);
    const double c1 = (CG_SSIM_K1 * 1.0) * (CG_SSIM_K1 * 1.0);
    const double c2 = (CG_SSIM_K2 * 1.0) * (CG_SSIM_K2 * 1.0);
    /* sigma_x^2 = E[x^2] - mu_x^2, and likewise; the three second moments one at a time. */
    double *sxx = malloc(n * 3 * sizeof(double));
    if (!sxx) {
        free(buf);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "SSIM buffers for %dx%d", w, h);
    }
    double *syy = sxx + n, *sxy = sxx + 2 * n;
    for (size_t i = 0; i < n; i++)
        prod[i] = x[i] * x[i];
    gaussian_blur(prod, tmp, stat, w, h, kernel, radius);
    for (size_t i = 0; i < n; i++)
        sxx[i] = stat[i] - mx[i] * mx[i];
    for (size_t i = 0; i < n; i++)
        prod[i] = y[i] * y[i];
    gaussian_blur(prod, tmp, stat, w, h, kernel, radius);
    for (size_t i = 0; i < n; i++)
        syy[i] = stat[i] - my[i] * my[i];
    for (size_t i = 0; i < n; i++)
        prod[i] = x[i] * y[i];
    gaussian_blur(prod, tmp, stat, w, h, kernel, radius);
    for (size_t i = 0; i < n; i++)
        sxy[i] = stat[i] - mx[i] * my[i];
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        double num = (2.0 * mx[i] * my[i] + c1) * (2.0 * sxy[i] + c2);
        double den = (mx[i] * mx[i] + my[i] * my[i] + c1) * (sxx[i] + syy[i] + c2);
        sum += num / den;
    }
    *out = sum / (double)n;
    free(sxx);
    free(buf);
    return true;
}

bool
cg_metrics_compute(const cg_image *test, const cg_image *ref, cg_metrics *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    if (!same_size(test, ref, "compare", err))
        return false;
    out->width = test->width;
    out->height = test->height;
    size_t n = (size_t)test->width * (size_t)test->height, used = 0;
    double se = 0.0, rel = 0.0, max_err = 0.0, lum_t = 0.0, lum_r = 0.0;
    for (size_t i = 0; i < n; i++) {
        const float *t = &test->rgba[4 * i], *r = &ref->rgba[4 * i];
        bool t_ok = pixel_finite(t), r_ok = pixel_finite(r);
        if (!t_ok || !r_ok) {
            out->nonfinite_pixels++;
            if (!t_ok)
                out->nonfinite_test++;
            continue;
        }
        used++;
        for (int c = 0; c < 3; c++) {
            double d = (double)t[c] - (double)r[c];
            se += d * d;
            rel += d * d / ((double)r[c] * (double)r[c] + CG_RELMSE_EPSILON);
            if (fabs(d) > max_err)
                max_err = fabs(d);
        }
        lum_t += cg_luminance(t);
        lum_r += cg_luminance(r);
    }
    if (used > 0) {
        out->rmse = sqrt(se / (3.0 * (double)used));
        out->rel_mse = rel / (3.0 * (double)used);
        out->mean_luminance_test = lum_t / (double)used;
        out->mean_luminance_ref = lum_r / (double)used;
    } else {
        out->rmse = out->rel_mse = NAN;
    }
    out->max_error = max_err;
    if (out->mean_luminance_ref != 0.0)
        out->mean_luminance_ratio = out->mean_luminance_test / out->mean_luminance_ref;
    else
        out->mean_luminance_ratio = out->mean_luminance_test == 0.0 ? 1.0 : INFINITY;
    return ssim_mean(test, ref, &out->ssim, err);
}

bool
cg_metrics_part(const cg_image *estimate, const cg_image *truth, cg_part_metrics *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    if (!same_size(estimate, truth, "compare parts", err))
        return false;
    out->width = estimate->width;
    out->height = estimate->height;
    size_t n = (size_t)estimate->width * (size_t)estimate->height, used = 0;
    /* se and st are summed alike, so that an all-zero estimate gives se == st exactly (d = -t,
     * d * d = t * t) and nrmse exactly 1. */
    double se = 0.0, st = 0.0, lum_e = 0.0, lum_t = 0.0;
    for (size_t i = 0; i < n; i++) {
        const float *e = &estimate->rgba[4 * i], *t = &truth->rgba[4 * i];
        if (!pixel_finite(e) || !pixel_finite(t)) {
            out->nonfinite_pixels++;
            continue;
        }
        used++;
        for (int c = 0; c < 3; c++) {
            double d = (double)e[c] - (double)t[c];
            se += d * d;
            st += (double)t[c] * (double)t[c];
        }
        lum_e += cg_luminance(e);
        lum_t += cg_luminance(t);
    }
    if (used == 0) {
        out->energy = out->nrmse = out->rmse = out->rms_truth = NAN;
        out->mean_luminance_estimate = out->mean_luminance_truth = NAN;
        return true;
    }
    out->rmse = sqrt(se / (3.0 * (double)used));
    out->rms_truth = sqrt(st / (3.0 * (double)used));
    out->mean_luminance_estimate = lum_e / (double)used;
    out->mean_luminance_truth = lum_t / (double)used;
    if (out->mean_luminance_truth != 0.0)
        out->energy = out->mean_luminance_estimate / out->mean_luminance_truth;
    else if (out->mean_luminance_estimate == 0.0)
        out->energy = 1.0;
    else
        out->energy = out->mean_luminance_estimate > 0.0 ? INFINITY : -INFINITY;
    if (out->rms_truth > 0.0)
        out->nrmse = out->rmse / out->rms_truth;
    else
        out->nrmse = out->rmse == 0.0 ? 0.0 : INFINITY;
    return true;
}

bool
cg_image_subtract(const cg_image *a, const cg_image *b, cg_image *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    if (!same_size(a, b, "subtract", err) || !image_like(a, out, err))
        return false;
    size_t n = (size_t)a->width * (size_t)a->height;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++)
            out->rgba[4 * i + c] = a->rgba[4 * i + c] - b->rgba[4 * i + c];
        out->rgba[4 * i + 3] = 1.0f;
    }
    return true;
}

/* The 'inferno' ramp of matplotlib (van der Walt and Smith, BIDS colormaps, CC0), sampled
 * at nine points, sRGB-encoded; interpolated linearly between them. */
static const float inferno[9][3] = {
    { 0.001f, 0.000f, 0.014f }, { 0.122f, 0.047f, 0.282f }, { 0.335f, 0.060f, 0.428f },
    { 0.533f, 0.134f, 0.416f }, { 0.729f, 0.212f, 0.333f }, { 0.891f, 0.333f, 0.200f },
    { 0.978f, 0.518f, 0.040f }, { 0.976f, 0.741f, 0.149f }, { 0.988f, 0.998f, 0.645f },
};

static float
srgb_to_linear(float v)
{
    return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

bool
cg_metrics_heatmap(const cg_image *test, const cg_image *ref, double max_value, cg_image *out,
                   cg_error *err)
{
    memset(out, 0, sizeof *out);
    if (!same_size(test, ref, "heatmap", err) || !image_like(test, out, err))
        return false;
    if (!(max_value > 0.0))
        max_value = 1.0;
    size_t n = (size_t)test->width * (size_t)test->height;
    for (size_t i = 0; i < n; i++) {
        const float *t = &test->rgba[4 * i], *r = &ref->rgba[4 * i];
        float *o = &out->rgba[4 * i];
        o[3] = 1.0f;
        if (!pixel_finite(t) || !pixel_finite(r)) {
            o[0] = 1.0f, o[1] = 0.0f, o[2] = 1.0f;
            continue;
        }
        double rel = 0.0;
        for (int c = 0; c < 3; c++) {
            double d = (double)t[c] - (double)r[c];
            rel += d * d / ((double)r[c] * (double)r[c] + CG_RELMSE_EPSILON);
        }
        double v = sqrt(rel / 3.0) / max_value;
        v = v > 1.0 ? 1.0 : v;
        double pos = v * 8.0;
        int k = (int)pos;
        if (k > 7)
            k = 7;
        float f = (float)(pos - k);
        for (int c = 0; c < 3; c++)
            o[c] = srgb_to_linear(inferno[k][c] + (inferno[k + 1][c] - inferno[k][c]) * f);
    }
    return true;
}
