/* core/trace/pt_sky.h: the sky as the path tracer samples it (private to core/trace).
 *
 * The radiance comes from cg_sky_model (cg/scene.h). A uniform sky needs no table: the path
 * tracer samples it by the cosine about the shading normal. A Preetham sky is sampled from
 * a piecewise-constant density over (theta, phi) of the upper hemisphere, tabulated once per
 * scene from luminance x sin(theta) (the solid angle of a cell), as pbrt's 2D distribution
 * does for environment maps (Pharr, Jakob, Humphreys, "Physically Based Rendering", 3rd ed.,
 * sections 13.6.7 and 14.2.4).
 */
#ifndef CG_PT_SKY_H
#define CG_PT_SKY_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/scene.h"

#define PT_SKY_ROWS 64   /* theta in [0, pi/2] */
#define PT_SKY_COLS 128  /* phi in [0, 2 pi) */

typedef struct pt_sky {
    cg_sky_model model;
    double *row_cdf;     /* PT_SKY_ROWS + 1 running sums of the rows' weights (Preetham only) */
    double *col_cdf;     /* PT_SKY_ROWS x (PT_SKY_COLS + 1), per row */
    double *cell;        /* PT_SKY_ROWS x PT_SKY_COLS weights */
} pt_sky;

/* Builds the model and, for a Preetham sky, its table. */
bool pt_sky_create(const cg_scene *scene, pt_sky *sky, cg_error *err);
void pt_sky_destroy(pt_sky *sky);

/* A direction from the table (Preetham only): u1, u2 in [0, 1). Returns false when the draw
 * hit a cell of zero weight or the pole (no usable direction). *pdf is its solid-angle density. */
bool pt_sky_sample(const pt_sky *sky, float u1, float u2, float dir[3], double *pdf);
/* The table's solid-angle density of the unit direction dir (Preetham only; 0 below the horizon). */
double pt_sky_pdf(const pt_sky *sky, const float dir[3]);

#endif
