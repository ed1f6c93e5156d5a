/* The pass registry of the command line: see app_registry.h. */
#include "app_registry.h"

#include <stdlib.h>

#include "sdk/builtin.h"

fg_registry *
app_registry_create(const char *const *plugins, int plugin_count, cg_error *err)
{
    fg_registry *registry = fg_registry_create();
    if (!registry) {
        cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    bool ok = cg_builtin_passes_register(registry, err) &&
              fg_registry_load_plugin_dirs(registry, getenv("CONEGRAPH_PLUGIN_PATH"), err);
    for (int i = 0; ok && i < plugin_count; i++)
        ok = fg_registry_load_plugin(registry, plugins[i], err);
    if (!ok) {
        fg_registry_destroy(registry);
        return NULL;
    }
    return registry;
}
