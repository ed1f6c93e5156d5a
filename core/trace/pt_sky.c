/* core/trace/pt_sky.c: the importance table of an analytic sky (see pt_sky.h). */
#include "pt_sky.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SKY_PI 3.14159265358979323846

static double
luminance(const float rgb[3])
{
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

/* Direction of (theta, phi): theta from the zenith (+y), phi about y from +x towards +z. */
static void
direction(double theta, double phi, float dir[3])
{
    double st = sin(theta);
    dir[0] = (float)(st * cos(phi));
    dir[1] = (float)cos(theta);
    dir[2] = (float)(st * sin(phi));
}

bool
pt_sky_create(const cg_scene *scene, pt_sky *sky, cg_error *err)
{
    memset(sky, 0, sizeof *sky);
    if (!cg_sky_model_init(scene, &sky->model, err))
        return false;
    if (sky->model.type != CG_SKY_PREETHAM)
        return true;
    sky->row_cdf = malloc(sizeof *sky->row_cdf * (PT_SKY_ROWS + 1));
    sky->col_cdf = malloc(sizeof *sky->col_cdf * PT_SKY_ROWS * (PT_SKY_COLS + 1));
    sky->cell = malloc(sizeof *sky->cell * PT_SKY_ROWS * PT_SKY_COLS);
    if (!sky->row_cdf || !sky->col_cdf || !sky->cell) {
        pt_sky_destroy(sky);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "path_trace: sky table");
    }
    /* Each cell weighs luminance x sin(theta) at its centre (the density over (theta, phi)
     * of a direction density proportional to luminance). A cell whose centre is dark but
     * whose sky is not is left to the BRDF samples, which MIS weighs in full there. */
    sky->row_cdf[0] = 0.0;
    for (int r = 0; r < PT_SKY_ROWS; r++) {
        double theta = (r + 0.5) * (0.5 * SKY_PI) / PT_SKY_ROWS;
        double *cdf = &sky->col_cdf[r * (PT_SKY_COLS + 1)];
        cdf[0] = 0.0;
        for (int c = 0; c < PT_SKY_COLS; c++) {
            double phi = (c + 0.5) * (2.0 * SKY_PI) / PT_SKY_COLS;
            float dir[3], rgb[3];
            direction(theta, phi, dir);
            cg_sky_model_radiance(&sky->model, dir, rgb);
            double w = luminance(rgb) * sin(theta);
            sky->cell[r * PT_SKY_COLS + c] = w > 0.0 ? w : 0.0;
            cdf[c + 1] = cdf[c] + sky->cell[r * PT_SKY_COLS + c];
        }
        sky->row_cdf[r + 1] = sky->row_cdf[r] + cdf[PT_SKY_COLS];
    }
    return true;
}

void
pt_sky_destroy(pt_sky *sky)
{
    free(sky->row_cdf);
    free(sky->col_cdf);
    free(sky->cell);
    sky->row_cdf = sky->col_cdf = sky->cell = NULL;
}

/* The first index i in [0, n) with cdf[i + 1] > target (cdf has n + 1 entries). */
static int
find(const double *cdf, int n, double target)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (cdf[mid + 1] > target)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* Density over the unit square (u = theta / (pi/2), v = phi / 2 pi) of the table's cell, over
 * the solid angle: dOmega = sin(theta) dtheta dphi = (pi/2)(2 pi) sin(theta) du dv. */
static double
cell_pdf(const pt_sky *sky, int r, int c, double sin_theta)
{
    double total = sky->row_cdf[PT_SKY_ROWS];
    if (!(total > 0.0) || !(sin_theta > 0.0))
        return 0.0;
    double density_uv = sky->cell[r * PT_SKY_COLS + c] * (PT_SKY_ROWS * PT_SKY_COLS) / total;
    return density_uv / (SKY_PI * SKY_PI * sin_theta);
}

bool
pt_sky_sample(const pt_sky *sky, float u1, float u2, float dir[3], double *pdf)
{
    *pdf = 0.0;
    double total = sky->row_cdf ? sky->row_cdf[PT_SKY_ROWS] : 0.0;
    if (!(total > 0.0))
        return false;
    double t1 = u1 * total;
    int r = find(sky->row_cdf, PT_SKY_ROWS, t1);
    double row_w = sky->row_cdf[r + 1] - sky->row_cdf[r];
    const double *cdf = &sky->col_cdf[r * (PT_SKY_COLS + 1)];
    double t2 = u2 * cdf[PT_SKY_COLS];
    int c = find(cdf, PT_SKY_COLS, t2);
    double cell_w = cdf[c + 1] - cdf[c];
    if (!(row_w > 0.0) || !(cell_w > 0.0))
        return false;
    /* Uniform within the cell in (theta, phi), the remainder of each draw reused. */
    double fu = (t1 - sky->row_cdf[r]) / row_w, fv = (t2 - cdf[c]) / cell_w;
    double theta = (r + fmin(fmax(fu, 0.0), 1.0)) * (0.5 * SKY_PI) / PT_SKY_ROWS;
    double phi = (c + fmin(fmax(fv, 0.0), 1.0)) * (2.0 * SKY_PI) / PT_SKY_COLS;
    direction(theta, phi, dir);
    *pdf = cell_pdf(sky, r, c, sin(theta));
    return *pdf > 0.0;
}

double
pt_sky_pdf(const pt_sky *sky, const float dir[3])
{
    if (!sky->row_cdf)
        return 0.0;
    double len = sqrt((double)dir[0] * dir[0] + (double)dir[1] * dir[1] + (double)dir[2] * dir[2]);
    double cos_theta = dir[1] / len;
    if (!(cos_theta > 0.0))
        return 0.0;
    double theta = acos(fmin(cos_theta, 1.0));
    double phi = atan2(dir[2], dir[0]);
    if (phi < 0.0)
        phi += 2.0 * SKY_PI;
    int r = (int)(theta / (0.5 * SKY_PI) * PT_SKY_ROWS);
    int c = (int)(phi / (2.0 * SKY_PI) * PT_SKY_COLS);
    r = r < 0 ? 0 : (r >= PT_SKY_ROWS ? PT_SKY_ROWS - 1 : r);
    c = c < 0 ? 0 : (c >= PT_SKY_COLS ? PT_SKY_COLS - 1 : c);
    return cell_pdf(sky, r, c, sqrt(fmax(0.0, 1.0 - cos_theta * cos_theta)));
}
