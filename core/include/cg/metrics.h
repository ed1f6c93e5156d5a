/* cg/metrics.h: image error metrics against a reference, and an error heat map.
 *
 * Declares: cg_metrics, CG_RELMSE_EPSILON, CG_SSIM_WINDOW, CG_SSIM_SIGMA, CG_SSIM_K1, CG_SSIM_K2,
 *           cg_metrics_compute, cg_part_metrics, cg_metrics_part, cg_image_subtract,
 *           cg_metrics_heatmap, cg_luminance.
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
 *
 * One part of an image against the same part of the truth (cg_metrics_part): the indirect
 * light a GI method adds (its image minus its own direct image) against the reference's
 * (the reference minus its own direct part), or a direct part against the reference's:
 *   energy     mean Y(estimate) / mean Y(truth) over the finite pixels: 1 is the right amount
 *              of light, 0 none. When the truth's mean is 0: 1 if the estimate's is 0 too,
 *              else +inf or -inf by the sign of the estimate's mean.
 *   nrmse      rmse(estimate - truth) / rms(truth), over pixels and RGB channels, where
 *              rms(truth) = rmse(0 - truth) is the error of leaving the part out: 0 is the truth,
 *              1 no better than leaving the part out (an all-zero estimate gives exactly 1).
 *              When rms(truth) is 0: 0 if the estimate is 0 wherever the truth is, else +inf.
 * Both are NaN when no pixel is finite in both images.
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

/* One part of an image against the same part of the truth: see the definitions above. */
typedef struct cg_part_metrics {
    int width, height;
    double energy;                  /* mean Y(estimate) / mean Y(truth) */
    double nrmse;                   /* rmse / rms_truth */
    double rmse;                    /* rmse(estimate - truth) over pixels and RGB channels */
    double rms_truth;               /* rmse(0 - truth): the error of leaving the part out */
    double mean_luminance_estimate;
    double mean_luminance_truth;
    size_t nonfinite_pixels;        /* pixels left out because either image is not finite there */
} cg_part_metrics;

/* Fails with CG_ERR_IMAGE_FORMAT when the sizes differ or an image is empty. */
bool cg_metrics_part(const cg_image *estimate, const cg_image *truth, cg_part_metrics *out, cg_error *err);

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
