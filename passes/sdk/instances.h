/* sdk/instances.h (pass SDK): whether the instances a pass draws changed since it last built
 * something from them, for the passes that keep what they drew across frames (heightmap_raster's
 * rasterized geometry, voxelize's surface volumes).
 *
 * Declares: cgp_kept_instance, cgp_instance_record, cgp_instances_changed, cgp_instances_changed_slots,
 *           cgp_instances_remember, cgp_instance_record_free.
 *
 * The record holds, for every instance whose mesh passes the pass's filter, what a draw of it
 * reads (world matrix, revision, mesh, material), copied by value, and the scene, GPU scene and
 * upload (cg_gpu_scene.generation) it was drawn from. Compared by value, not by revision alone:
 * a world changed by hand without a new revision is seen too. Any doubt reports a change. What
 * else the pass's build reads (its region, its scales) the pass compares itself.
 */
#ifndef CGP_INSTANCES_H
#define CGP_INSTANCES_H

#include <stdbool.h>
#include <stdint.h>

#include "cg/error.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/scene.h"

/* What one drawn instance was at the build. */
typedef struct cgp_kept_instance {
    int index, mesh;
    float world[16];
    uint64_t revision;
    cg_mesh mesh_data;          /* its counts, arrays, kind and bounds */
    cg_material material;
} cgp_kept_instance;

/* What a pass drew from; zero-initialised: nothing recorded yet. */
typedef struct cgp_instance_record {
    bool taken;
    cg_mesh_filter filter;
    const cg_scene *scene;
    const cg_gpu_scene *gpu_scene;
    uint64_t generation;        /* the GPU scene's upload */
    int instance_count;
    cgp_kept_instance *instances;
    int count, cap;
} cgp_instance_record;

/* Why what was drawn from the instances `filter` keeps in `frame` may differ from the record, as
 * words fit for a pass's report: "first frame", "scene uploaded again", or `changed` (the pass's
 * words for "one of my instances changed", e.g. "a height-field instance changed"); NULL when
 * every such instance is as recorded. */
const char *cgp_instances_changed(const cgp_instance_record *record, const fg_frame *frame,
                                  cg_mesh_filter filter, const char *changed);

/* Which recorded instances changed, for a pass that updates only what they cover (voxelize's
 * partial re-voxelization): true when the instances `filter` keeps in `frame` are the recorded
 * ones (the record taken from this scene and upload, the same instance indices), with
 * changed[0 .. *count) the slots in record->instances of those that differ (as
 * cgp_instances_changed compares them; `changed` has room for record->count). False when the set
 * itself differs or nothing is recorded: then only a whole rebuild is right. */
bool cgp_instances_changed_slots(const cgp_instance_record *record, const fg_frame *frame, cg_mesh_filter filter,
                                 int *changed, int *count);

/* Records the instances `filter` keeps in `frame` (after a build from them). False only when out
 * of memory; the record then holds nothing (the next check reports "first frame"). */
bool cgp_instances_remember(cgp_instance_record *record, const fg_frame *frame, cg_mesh_filter filter,
                            cg_error *err);

void cgp_instance_record_free(cgp_instance_record *record);

#endif
