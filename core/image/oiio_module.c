/* Loads the OpenImageIO module (image_oiio.cpp, libcg-oiio.so) on first use: see image_oiio.h.
 *
 * The module is $CONEGRAPH_OIIO_MODULE when set (a relocated installation; tests), else the
 * one this build made when it is still there, else the installed one, as with shaders
 * (cg_shader_dir): a build directory runs its own module, an installed program the installed
 * one. It is never unloaded: OpenImageIO keeps threads and caches to the end. */
#include <dlfcn.h>
#include <pthread.h>
#include <stdlib.h>
#include <unistd.h>

#include "image_oiio.h"

static const cg_oiio_host host = { cg_fail, cg_image_alloc, cg_image_free };

static pthread_once_t load_once = PTHREAD_ONCE_INIT;
static const cg_oiio_api *api;
static cg_error load_error;

static void *module;

static void
load(void)
{
    const char *path = getenv("CONEGRAPH_OIIO_MODULE");
    if (!path || !*path)
        path = access(CG_OIIO_MODULE_BUILD_PATH, F_OK) == 0 ? CG_OIIO_MODULE_BUILD_PATH : CG_OIIO_MODULE_INSTALL_PATH;
    module = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!module) {
        const char *why = dlerror();
        cg_fail(&load_error, CG_ERR_IO,
                "cannot load conegraph's OpenImageIO module, needed to read and write images: %s", why ? why : path);
        return;
    }
    cg_oiio_module_fn *entry;
    /* POSIX's way to turn dlsym's object pointer into a function pointer. */
    *(void **)&entry = dlsym(module, CG_OIIO_MODULE_ENTRY);
    api = entry ? entry(CG_OIIO_MODULE_ABI, &host) : NULL;
    if (!api)
        cg_fail(&load_error, CG_ERR_IO, "%s: %s", path,
                entry ? "built for another version of conegraph (module ABI mismatch)"
                      : "not conegraph's OpenImageIO module (no " CG_OIIO_MODULE_ENTRY ")");
}

const cg_oiio_api *
cg_oiio(cg_error *err)
{
    pthread_once(&load_once, load);
    if (!api)
        cg_fail(err, load_error.status, "%s", load_error.message);
    return api;
}
