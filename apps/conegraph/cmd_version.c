/* conegraph version (and conegraph --version): the version of conegraph and of the libraries it
 * runs on. A library with a C call that says its version is asked at run time (GL from a
 * context, Embree, jansson, GLFW); the others (OpenImageIO, whose call is C++ only, and the
 * header-only tinygltf and cglm) are given as the build found them (pkg-config, headers). */
#include <stdio.h>
#include <string.h>

#include "cg/error.h"
#include "cg/gl.h"
#include "commands.h"

/* After glad's gl.h (cg/gl.h): GLFW must not pull in the system's GL header. */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <cglm/version.h>
#include <embree3/rtcore.h>
#include <jansson.h>

void
cmd_version_usage(FILE *out)
{
    fprintf(out,
            "usage: conegraph version [--no-gl] [--context egl|osmesa|glfw|auto]\n"
            "       conegraph --version\n"
            "\n"
            "Prints the version of conegraph and of the libraries it runs on: OpenGL (version and\n"
            "renderer of a headless context made for the purpose), Embree, OpenImageIO, tinygltf,\n"
            "jansson, cglm and GLFW. Where a library can say its version at run time, that is the\n"
            "one printed, with the one conegraph was built against when they differ; the others\n"
            "are those of the build.\n"
            "\n"
            "  --no-gl          do not make a GL context (the OpenGL line says so)\n"
            "  --context NAME   the context's backend (default: $CONEGRAPH_CONTEXT, else egl, then\n"
            "                   osmesa)\n"
            "\n"
            "Exit codes: 0 printed (also when no GL context can be made: the OpenGL line says why),\n"
            "2 bad usage.\n");
}

/* "X (built with Y)" when the run-time version differs from the build's. */
static void
print_library(const char *name, const char *runtime, const char *built)
{
    if (!runtime || !runtime[0] || !strcmp(runtime, built))
        printf("%-12s %s%s\n", name, built, runtime && runtime[0] ? "" : " (at build time)");
    else
        printf("%-12s %s (built with %s)\n", name, runtime, built);
}

static void
print_gl(bool make_context, cg_context_backend backend)
{
    if (!make_context) {
        printf("%-12s not queried (--no-gl)\n", "OpenGL");
        return;
    }
    cg_context_desc desc = { .backend = backend };
    cg_context *ctx;
    cg_error err = { 0 };
    if (!cg_context_create(&desc, &ctx, &err)) {
        /* The first line of the reason: a context failure lists every backend tried. */
        printf("%-12s no context: %.*s\n", "OpenGL", (int)strcspn(err.message, "\n"), err.message);
        return;
    }
    printf("%-12s %s, %s (%s context)\n", "OpenGL", cg_context_version(ctx), cg_context_renderer(ctx),
           cg_context_backend_name(cg_context_get_backend(ctx)));
    cg_context_destroy(ctx);
}

static void
print_embree(void)
{
    char runtime[32] = "";
    /* One thread: the device is made only to be asked its version. */
    RTCDevice device = rtcNewDevice("threads=1");
    if (device) {
        long v = (long)rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION);
        snprintf(runtime, sizeof runtime, "%ld.%ld.%ld", v / 10000, v / 100 % 100, v % 100);
        rtcReleaseDevice(device);
    }
    print_library("Embree", runtime, RTC_VERSION_STRING);
}

int
cmd_version(int argc, char **argv)
{
    bool gl = true;
    cg_context_backend backend = CG_CONTEXT_AUTO;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--no-gl")) {
            gl = false;
        } else if (!strcmp(argv[i], "--context") && i + 1 < argc &&
                   cg_context_backend_parse(argv[i + 1], &backend)) {
            i++;
        } else {
            fprintf(stderr, "conegraph version: unexpected argument '%s' (see conegraph version --help)\n", argv[i]);
            return 2;
        }
    }
    printf("conegraph    %s\n", CONEGRAPH_VERSION);
    print_gl(gl, backend);
    print_embree();
    print_library("OpenImageIO", NULL, CG_BUILD_OIIO_VERSION);
    print_library("tinygltf", NULL, CG_BUILD_TINYGLTF_VERSION);
    print_library("jansson", jansson_version_str(), JANSSON_VERSION);
    char cglm[32];
    snprintf(cglm, sizeof cglm, "%d.%d.%d", CGLM_VERSION_MAJOR, CGLM_VERSION_MINOR, CGLM_VERSION_PATCH);
    print_library("cglm", NULL, cglm);
    /* glfwGetVersionString also names the platforms it was built for; the number is first. */
    const char *glfw = glfwGetVersionString();
    char glfw_runtime[32];
    snprintf(glfw_runtime, sizeof glfw_runtime, "%.*s", (int)strcspn(glfw, " "), glfw);
    char glfw_built[32];
    snprintf(glfw_built, sizeof glfw_built, "%d.%d.%d", GLFW_VERSION_MAJOR, GLFW_VERSION_MINOR, GLFW_VERSION_REVISION);
    print_library("GLFW", glfw_runtime, glfw_built);
    return 0;
}
