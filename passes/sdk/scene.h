/* sdk/scene.h (pass SDK): what passes ask of the scene beside cg/scene.h: which meshes a
 * filter keeps and where they lie.
 *
 * Declares: cgp_mesh_passes, cgp_transform_point, cgp_mesh_bounds.
 */
#ifndef CGP_SCENE_H
#define CGP_SCENE_H

#include <stdbool.h>

#include "cg/gpu_scene.h"
#include "cg/scene.h"

/* Whether a mesh of `kind` passes `filter` (the filter of cg_gpu_scene_draw). */
bool cgp_mesh_passes(cg_mesh_kind kind, cg_mesh_filter filter);

/* m (column-major 4x4, cg_instance.world) applied to the point p, in double. */
void cgp_transform_point(const float m[16], const float p[3], double out[3]);

/* World bounds of the instances whose mesh passes `filter` and has triangles: the corners of
 * each mesh's box transformed by its instance, in double; a moving instance (an animated scene)
 * counts with its box over the whole animation (cg_instance.motion_min/max), so that a volume
 * or map fitted to these bounds stays put while it moves. False (lo = DBL_MAX, hi = -DBL_MAX)
 * when no instance passes. */
bool cgp_mesh_bounds(const cg_scene *scene, cg_mesh_filter filter, double lo[3], double hi[3]);

#endif
