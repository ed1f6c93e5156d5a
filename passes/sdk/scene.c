/* Mesh filters and bounds for passes (sdk/scene.h). */
#include "sdk/scene.h"

#include <float.h>
#include <math.h>

bool
cgp_mesh_passes(cg_mesh_kind kind, cg_mesh_filter filter)
{
    return filter == CG_MESHES_ALL || (filter == CG_MESHES_COMPLEX && kind == CG_MESH_COMPLEX) ||
           (filter == CG_MESHES_HEIGHTFIELD && kind == CG_MESH_HEIGHTFIELD);
}

void
cgp_transform_point(const float m[16], const float p[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

bool
cgp_mesh_bounds(const cg_scene *scene, cg_mesh_filter filter, double lo[3], double hi[3])
{
    bool any = false;
    for (int k = 0; k < 3; k++)
        lo[k] = DBL_MAX, hi[k] = -DBL_MAX;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        const cg_mesh *mesh = &scene->meshes[inst->mesh];
        if (!cgp_mesh_passes(mesh->kind, filter) || mesh->index_count == 0)
            continue;
        any = true;
        if (inst->moving) {
            /* Its box over the whole animation, so that what is fitted to these bounds stays put
             * from frame to frame. */
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], inst->motion_min[k]);
                hi[k] = fmax(hi[k], inst->motion_max[k]);
            }
            continue;
        }
        for (int c = 0; c < 8; c++) {
            float corner[3] = {
                (c & 1) ? mesh->bounds_max[0] : mesh->bounds_min[0],
                (c & 2) ? mesh->bounds_max[1] : mesh->bounds_min[1],
                (c & 4) ? mesh->bounds_max[2] : mesh->bounds_min[2],
            };
            double w[3];
            cgp_transform_point(inst->world, corner, w);
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], w[k]);
                hi[k] = fmax(hi[k], w[k]);
            }
        }
    }
    return any;
}
