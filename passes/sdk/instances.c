/* Whether the instances a pass draws changed since its last build (sdk/instances.h). */
#include "sdk/instances.h"

#include <stdlib.h>
#include <string.h>

#include "sdk/scene.h"

/* Whether instance `b->index` is as it was at the build: its world matrix, its revision, its
 * mesh (counts, arrays, kind, bounds) and its material, compared by value. */
static bool
instance_unchanged(const cg_scene *scene, const cgp_kept_instance *b)
{
    if (b->index >= scene->instance_count)
        return false;
    const cg_instance *inst = &scene->instances[b->index];
    if (inst->mesh != b->mesh || inst->revision != b->revision ||
        memcmp(inst->world, b->world, sizeof b->world) || b->mesh >= scene->mesh_count)
        return false;
    const cg_mesh *mesh = &scene->meshes[b->mesh];
    return !memcmp(mesh, &b->mesh_data, sizeof *mesh) && mesh->material >= 0 &&
           mesh->material < scene->material_count &&
           !memcmp(&scene->materials[mesh->material], &b->material, sizeof b->material);
}

const char *
cgp_instances_changed(const cgp_instance_record *record, const fg_frame *frame, cg_mesh_filter filter,
                      const char *changed)
{
    const cg_scene *scene = frame->scene;
    if (!record->taken)
        return "first frame";
    if (scene != record->scene || frame->gpu_scene != record->gpu_scene ||
        frame->gpu_scene->generation != record->generation || scene->instance_count != record->instance_count ||
        filter != record->filter)
        return "scene uploaded again";
    int n = 0;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        if (inst->mesh < 0 || inst->mesh >= scene->mesh_count || !cgp_mesh_passes(scene->meshes[inst->mesh].kind, filter))
            continue;
        if (n >= record->count || record->instances[n].index != i || !instance_unchanged(scene, &record->instances[n]))
            return changed;
        n++;
    }
    return n == record->count ? NULL : changed;
}

bool
cgp_instances_changed_slots(const cgp_instance_record *record, const fg_frame *frame, cg_mesh_filter filter,
                            int *changed, int *count)
{
    const cg_scene *scene = frame->scene;
    *count = 0;
    if (!record->taken || scene != record->scene || frame->gpu_scene != record->gpu_scene ||
        frame->gpu_scene->generation != record->generation || scene->instance_count != record->instance_count ||
        filter != record->filter)
        return false;
    int n = 0;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        if (inst->mesh < 0 || inst->mesh >= scene->mesh_count || !cgp_mesh_passes(scene->meshes[inst->mesh].kind, filter))
            continue;
        if (n >= record->count || record->instances[n].index != i)
            return false;
        if (!instance_unchanged(scene, &record->instances[n]))
            changed[(*count)++] = n;
        n++;
    }
    return n == record->count;
}

bool
cgp_instances_remember(cgp_instance_record *record, const fg_frame *frame, cg_mesh_filter filter, cg_error *err)
{
    const cg_scene *scene = frame->scene;
    record->taken = false;
    record->count = 0;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        if (inst->mesh < 0 || inst->mesh >= scene->mesh_count)
            continue;
        const cg_mesh *mesh = &scene->meshes[inst->mesh];
        if (!cgp_mesh_passes(mesh->kind, filter))
            continue;
        if (record->count == record->cap) {
            int cap = record->cap ? 2 * record->cap : 8;
            cgp_kept_instance *grown = realloc(record->instances, sizeof *grown * (size_t)cap);
            if (!grown)
                return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory recording %d drawn instances", cap);
            record->instances = grown;
            record->cap = cap;
        }
        cgp_kept_instance *b = &record->instances[record->count++];
        memset(b, 0, sizeof *b);
        b->index = i;
        b->mesh = inst->mesh;
        memcpy(b->world, inst->world, sizeof b->world);
        b->revision = inst->revision;
        /* memcpy, not assignment: memcmp then compares the padding too, byte for byte. */
        memcpy(&b->mesh_data, mesh, sizeof *mesh);
        if (mesh->material >= 0 && mesh->material < scene->material_count)
            memcpy(&b->material, &scene->materials[mesh->material], sizeof b->material);
    }
    record->filter = filter;
    record->scene = scene;
    record->gpu_scene = frame->gpu_scene;
    record->generation = frame->gpu_scene->generation;
    record->instance_count = scene->instance_count;
    record->taken = true;
    return true;
}

void
cgp_instance_record_free(cgp_instance_record *record)
{
    free(record->instances);
    *record = (cgp_instance_record){0};
}
