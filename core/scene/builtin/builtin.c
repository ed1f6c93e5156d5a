/* core/scene/builtin: the procedural built-in scenes ("builtin:NAME?key=value&..."), one file
 * each, listed here. builtin_internal.h has what they share. */
#include <stdio.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

static const cg_builtin_scene *const builtin_scenes[] = {
    &cg_builtin_openworld,
    &cg_builtin_cornell,
    &cg_builtin_furnace,
    &cg_builtin_plates,
    &cg_builtin_wallfloor,
    &cg_builtin_thinwall,
    &cg_builtin_boxplane,
    &cg_builtin_terrain,
};
#define BUILTIN_COUNT (sizeof builtin_scenes / sizeof builtin_scenes[0])

const char *const *
cg_scene_builtin_names(void)
{
    static const char *names[BUILTIN_COUNT + 1];
    for (size_t i = 0; i < BUILTIN_COUNT; i++)
        names[i] = builtin_scenes[i]->name;
    return names;
}

const char *
cg_scene_builtin_doc(const char *name)
{
    for (size_t i = 0; i < BUILTIN_COUNT; i++)
        if (name && !strcmp(name, builtin_scenes[i]->name))
            return builtin_scenes[i]->doc;
    return NULL;
}

bool
cg_builtin_scene_load(const char *name, const char *query, cg_scene *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "builtin:%s", name);
    cg_material white = cg_material_default("default");
    if (cg_scene_add_material(out, &white, err) < 0)
        return false;
    const cg_builtin_scene *scene = NULL;
    for (size_t i = 0; i < BUILTIN_COUNT; i++)
        if (!strcmp(name, builtin_scenes[i]->name))
            scene = builtin_scenes[i];
    bool ok;
    if (scene) {
        ok = scene->build(out, query, err);
    } else {
        char known[256] = "";
        for (size_t i = 0; i < BUILTIN_COUNT; i++)
            snprintf(known + strlen(known), sizeof known - strlen(known), "%sbuiltin:%s",
                     i ? ", " : "", builtin_scenes[i]->name);
        ok = cg_fail(err, CG_ERR_SCENE_UNKNOWN, "builtin:%s: unknown built-in scene (known: %s)",
                     name, known);
    }
    if (!ok)
        cg_scene_free(out);
    return ok;
}
