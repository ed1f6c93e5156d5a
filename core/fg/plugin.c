/* Pass plugins: shared objects that export FG_PLUGIN_ENTRY and register pass types. */
#include <dirent.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fg_internal.h"

void
fg_registry_destroy(fg_registry *registry)
{
    if (!registry)
        return;
    free(registry->types);
    /* The pass types point into the plugins' data: close the plugins last. */
    for (int i = registry->plugin_count - 1; i >= 0; i--)
        dlclose(registry->plugins[i]);
    free(registry->plugins);
    free(registry);
}

bool
fg_registry_load_plugin(fg_registry *registry, const char *path, cg_error *err)
{
    /* dlopen() searches the library path for a bare name; a plugin is always named by path. */
    char resolved[4096];
    if (!strchr(path, '/')) {
        snprintf(resolved, sizeof resolved, "./%s", path);
        path = resolved;
    }
    dlerror();
    void *handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char *why = dlerror();
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "%s: cannot load plugin: %s", path,
                       why ? why : "unknown dlopen failure");
    }
    fg_plugin_register_fn entry;
    /* POSIX: converting the void * of dlsym() to a function pointer is how it is done. */
    *(void **)&entry = dlsym(handle, FG_PLUGIN_ENTRY);
    if (!entry) {
        dlclose(handle);
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "%s: not a conegraph plugin: it does not export '%s'", path, FG_PLUGIN_ENTRY);
    }
    if (!fg_grow((void **)&registry->plugins, &registry->plugin_cap, registry->plugin_count + 1,
                 sizeof *registry->plugins)) {
        dlclose(handle);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    int types_before = registry->count;
    cg_error local = { 0 };
    if (!entry(registry, FG_ABI_VERSION, &local)) {
        /* Forget whatever it registered before failing: those descriptors go away with dlclose. */
        registry->count = types_before;
        dlclose(handle);
        if (local.status == CG_OK)
            return cg_fail(err, CG_ERR_PLUGIN_LOAD, "%s: plugin registration failed without a reason",
                           path);
        return cg_fail(err, local.status, "%s: %s", path, local.message);
    }
    registry->plugins[registry->plugin_count++] = handle;
    return true;
}

static int
compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static bool
load_dir(fg_registry *registry, const char *dir, cg_error *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "%s: cannot open plugin directory", dir);
    char **names = NULL;
    int count = 0, cap = 0;
    bool ok = true;
    for (struct dirent *e; (e = readdir(d));) {
        size_t len = strlen(e->d_name);
        if (len < 4 || strcmp(e->d_name + len - 3, ".so"))
            continue;
        char *name = fg_strdup(e->d_name);
        if (!name || !fg_grow((void **)&names, &cap, count + 1, sizeof *names)) {
            free(name);
            ok = cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory listing plugins", dir);
            break;
        }
        names[count++] = name;
    }
    closedir(d);
    /* readdir order is arbitrary: load in name order so that runs are reproducible. */
    if (ok && count)
        qsort(names, (size_t)count, sizeof *names, compare_names);
    for (int i = 0; ok && i < count; i++) {
        char path[8192];
        if (snprintf(path, sizeof path, "%s/%s", dir, names[i]) >= (int)sizeof path)
            ok = cg_fail(err, CG_ERR_PLUGIN_LOAD, "%s/%s: path too long", dir, names[i]);
        else
            ok = fg_registry_load_plugin(registry, path, err);
    }
    for (int i = 0; i < count; i++)
        free(names[i]);
    free(names);
    return ok;
}

bool
fg_registry_load_plugin_dirs(fg_registry *registry, const char *dirs, cg_error *err)
{
    if (!dirs)
        return true;
    const char *start = dirs;
    while (*start) {
        const char *end = strchr(start, ':');
        size_t len = end ? (size_t)(end - start) : strlen(start);
        if (len > 0) {
            char dir[4096];
            if (len >= sizeof dir)
                return cg_fail(err, CG_ERR_PLUGIN_LOAD, "plugin directory path too long: %.*s",
                               (int)len, start);
            memcpy(dir, start, len);
            dir[len] = '\0';
            if (!load_dir(registry, dir, err))
                return false;
        }
        if (!end)
            break;
        start = end + 1;
    }
    return true;
}
