/* cg/metrics.h: image error metrics against a reference, and an error heat map.
 *
 * Declares: cg_metrics, CG_RELMSE_EPSILON, CG_SSIM_WINDOW, CG_SSIM_SIGMA, CG_SSIM_K1, CG_SSIM_K2,
 *           cg_metrics_compute, cg_image_subtract, cg_metrics_heatmap, cg_luminance.
 *
 * Both images are linear float RGBA of the same size; alpha is ignored. A pixel counts
 * as non-finite when any of its RGB channels in TEST or REF is NaN or infinite; such
 * pixels are counted and left out of every other metric (so one NaN cannot hide the
 * rest of the comparison, and the count says it is there).
 *
 *   rmse       sqrt(mean over pixels and RGB channels of (t - r)^2)
 *   rel_mse    mean over pixels and RGB channels of (t - r)^2 / (r^2 + eps), eps = 0.01:
 *              the relative MSE of Rousselle, Knaus and Zwicker, "Adaptive sampling and
 *              reconstruction using greedy error minimization", SIGGRAPH Asia 2011, the
 *              form used by most Monte Carlo denoising papers since; eps keeps black
 *              reference pixels from dominating.
 *   ssim       mean SSIM (Wang, Bovik, Sheikh, Simoncelli, IEEE TIP 13(4) 2004, eq. 13) on
 *              display luminance: Y = 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709) clamped to
 *              [0,1] and sRGB-encoded, so that dark regions weigh as they look; dynamic
 *              range L = 1, K1 = 0.01, K2 = 0.03, Gaussian window 11x11 with sigma 1.5 as in
 *              the paper, truncated at the image border and renormalised there.
 *   max_error  largest |t - r| over pixels and RGB channels.
 *   mean_luminance_ratio  mean Y(test) / mean Y(ref) over the finite pixels; 1 when both
 *              means are 0, +inf when only the reference's is. It catches energy errors.
 */
#ifndef CG_METRICS_H
#define CG_METRICS_H

#include <stdbool.h>
#include <stddef.h>

#include "cg/error.h"
#include "cg/image.h"

#define CG_RELMSE_EPSILON 0.01
#define CG_SSIM_WINDOW 11
#define CG_SSIM_SIGMA 1.5
#define CG_SSIM_K1 0.01
#define CG_SSIM_K2 0.03

typedef struct cg_metrics {
    int width, height;
    double rmse;
    double rel_mse;
    double ssim;
    double max_error;
    double mean_luminance_test;
    double mean_luminance_ref;
    double mean_luminance_ratio;
    size_t nonfinite_pixels;   /* pixels left out because TEST or REF is not finite there */
    size_t nonfinite_test;     /* of those, pixels where TEST is not finite */
} cg_metrics;

/* Rec. 709 luminance of linear RGB. */
double cg_luminance(const float *rgb);

/* Fails with CG_ERR_IMAGE_FORMAT when the sizes differ or an image is empty. */
bool cg_metrics_compute(const cg_image *test, const cg_image *ref, cg_metrics *out, cg_error *err);

/* out = a - b per channel (alpha = 1): the indirect part of an image given its direct part.
 * Allocates out; fails with CG_ERR_IMAGE_FORMAT when the sizes differ. */
bool cg_image_subtract(const cg_image *a, const cg_image *b, cg_image *out, cg_error *err);

/* Per-pixel relative error sqrt(mean over RGB of (t - r)^2 / (r^2 + eps)) mapped through the
 * 'inferno' colour ramp from 0 (black) to `max_value` (light yellow; values above are
 * clamped: the map is a picture, the numbers come from cg_metrics_compute). Non-finite
 * pixels are magenta. max_value <= 0 picks 1. Allocates out (linear RGBA, ready for
 * cg_image_write to PNG). */
bool cg_metrics_heatmap(const cg_image *test, const cg_image *ref, double max_value, cg_image *out,
                        cg_error *err);

#endif
