/* sdk/radiance.h (pass SDK): how bright the light that a pass stores can get, and the
 * pre-exposure that keeps it inside a half-float texture.
 *
 * Declares: cgp_light_distances, cgp_radiance_bound, cgp_light_distances_free, CGP_HALF_TOP,
 *           cgp_half_float_scale.
 *
 * voxelize (its fixed-point sums and its RGBA16F volume) and heightmap_raster (an RGBA16F 2D
 * lightmap) store outgoing radiance, which ranges over the scene's light: 1e-6 W/sr/m^2 under
 * starlight and 1e9 in a sunlit snowfield seen through a lens. A half float holds 6.1e-5 to
 * 65504 at full precision (11 bits), so such a texture stores radiance / scale with a scale
 * chosen per frame from the bound, and its region block carries the scale to the readers.
 */
#ifndef CGP_RADIANCE_H
#define CGP_RADIANCE_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/gpu_scene.h"
#include "cg/scene.h"

/* The distance from each point and spot light to the nearest surface of a mesh filter, kept by a
 * pass between frames and recomputed for a light that moved, or all of them once instances moved
 * (a walk over every triangle). */
typedef struct cgp_light_distances {
    float *positions;   /* xyz per light: where it was when its distance was found */
    double *nearest;    /* per light; < 0: not found yet */
    int count;          /* lights the arrays hold */
    uint64_t revision;  /* cg_scene.instances_revision the distances were found at */
} cgp_light_distances;

/* An upper bound on the outgoing radiance (W/sr/m^2) of any surface of the meshes `filter`
 * keeps: the brightest emission plus the brightest albedo lit by every light at once, point and
 * spot lights at their nearest surface but never nearer than `min_distance` (the size over which
 * the pass averages radiance: half a voxel, half a texel). False only when out of memory. */
bool cgp_radiance_bound(cgp_light_distances *cache, const cg_scene *scene, cg_mesh_filter filter,
                        double min_distance, double *bound, cg_error *err);

void cgp_light_distances_free(cgp_light_distances *cache);

/* Stored values of a half-float texture stay at or below CGP_HALF_TOP = 32768, half its largest
 * finite value (65504). */
#define CGP_HALF_TOP 32768.0

/* The pre-exposure of a half-float texture whose radiance never exceeds `bound`: s = bound /
 * CGP_HALF_TOP, so that the 2^30 of normal half floats sit just below the bound at any brightness
 * (denormals go down another 2^10), and a scene lit k times brighter stores the very same values
 * (its bound is k times larger): its image is k times brighter to within fp32 rounding, not only
 * to a half float's 2^-11. Never below fp32's smallest normal (shaders divide by it); 1 for a
 * bound that is zero or not finite (no light: black). */
double cgp_half_float_scale(double bound);

#endif
