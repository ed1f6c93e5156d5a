/* conegraph graph: reads a graph file and compiles it without GL against a scene: prints the
 * execution order, the culled passes with their reasons and the resources, or Graphviz DOT. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_registry.h"
#include "cg/camera.h"
#include "cg/graphfile.h"
#include "cg/scene.h"
#include "commands.h"

#define MAX_REPEATED 64

static void
graph_usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph graph FILE [--check] [--dot] [--set PASS.PARAM=VALUE]... [--plugin PATH]...\n"
        "                       [--size WxH] [--max-gpu-memory MIB] [--no-pool] [--report FILE]\n"
        "                       [SCENE]\n"
        "\n"
        "Reads graph file FILE and compiles it against SCENE (a .gltf/.glb path or builtin:NAME;\n"
        "default builtin:openworld) without GL: declares every pass, validates, culls, orders,\n"
        "computes lifetimes, pooled storage and barriers, and checks the sizes against the GL\n"
        "limits given here (no GL context is made).\n"
        "\n"
        "  --check                compile and print the execution order, the culled passes with\n"
        "                         their reasons, and the resources with their bytes (the default)\n"
        "  --dot                  print the compiled graph as Graphviz DOT instead (culled passes\n"
        "                         dashed, edges labelled with resource, format and size)\n"
        "  --set PASS.PARAM=VALUE override a parameter, validated as in a file; may be repeated\n"
        "  --plugin PATH          load a pass plugin first; may be repeated\n"
        "  --size WxH             output image size (default 1280x720)\n"
        "  --max-gpu-memory MIB   fail when the graph needs more GPU memory than this\n"
        "  --max-texture-size N   largest 2D texture side (default 16384)\n"
        "  --max-3d-texture-size N  largest 3D texture side (default 2048)\n"
        "  --no-pool              give every transient resource its own storage\n"
        "  --report FILE          also write the compile report as JSON (atomically)\n"
        "\n"
        "Exit codes: 0 the graph compiles, 1 failed while running (writing the report),\n"
        "2 bad usage, bad graph file (with file:line:column) or unloadable scene.\n");
}

static bool
parse_positive(const char *text, long max, long *out)
{
    char *end;
    long v = strtol(text, &end, 10);
    if (*text == '\0' || *end != '\0' || v <= 0 || v > max)
        return false;
    *out = v;
    return true;
}

int
cmd_graph(int argc, char **argv)
{
    const char *file = NULL, *scene_source = "builtin:openworld", *report = NULL;
    const char *sets[MAX_REPEATED] = { 0 }, *plugins[MAX_REPEATED] = { 0 };
    int set_count = 0, plugin_count = 0, width = 1280, height = 720;
    bool dot = false;
    fg_compile_options options = { false, 0, 16384, 2048 };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool has_value = i + 1 < argc;
        long v;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            graph_usage(stdout);
            return 0;
        } else if (!strcmp(a, "--check")) {
            dot = false;
        } else if (!strcmp(a, "--dot")) {
            dot = true;
        } else if (!strcmp(a, "--set") && has_value && set_count < MAX_REPEATED) {
            sets[set_count++] = argv[++i];
        } else if (!strcmp(a, "--plugin") && has_value && plugin_count < MAX_REPEATED) {
            plugins[plugin_count++] = argv[++i];
        } else if (!strcmp(a, "--size") && has_value) {
            if (sscanf(argv[++i], "%dx%d", &width, &height) != 2 || width < 1 || height < 1 ||
                width > 65536 || height > 65536) {
                fprintf(stderr, "conegraph graph: --size %s: expected WxH, e.g. 1280x720\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "--max-gpu-memory") && has_value) {
            if (!parse_positive(argv[++i], 1L << 30, &v)) {
                fprintf(stderr, "conegraph graph: --max-gpu-memory %s: expected MiB, a positive integer\n",
                        argv[i]);
                return 2;
            }
            options.max_gpu_memory = (size_t)v << 20;
        } else if ((!strcmp(a, "--max-texture-size") || !strcmp(a, "--max-3d-texture-size")) && has_value) {
            if (!parse_positive(argv[++i], 1 << 20, &v)) {
                fprintf(stderr, "conegraph graph: %s %s: expected a positive integer\n", a, argv[i]);
                return 2;
            }
            if (!strcmp(a, "--max-texture-size"))
                options.max_texture_size_2d = (int)v;
            else
                options.max_texture_size_3d = (int)v;
        } else if (!strcmp(a, "--no-pool")) {
            options.no_pool = true;
        } else if (!strcmp(a, "--report") && has_value) {
            report = argv[++i];
        } else if (a[0] == '-') {
            fprintf(stderr, "conegraph graph: unknown or incomplete option '%s'\n", a);
            graph_usage(stderr);
            return 2;
        } else if (!file) {
            file = a;
        } else {
            scene_source = a;
        }
    }
    if (!file) {
        fprintf(stderr, "conegraph graph: no graph file given\n");
        graph_usage(stderr);
        return 2;
    }

    cg_error err = { 0 };
    fg_registry *registry = app_registry_create(plugins, plugin_count, &err);
    if (!registry) {
        fprintf(stderr, "conegraph graph: %s\n", err.message);
        return cg_status_exit_code(err.status);
    }
    fg_graph *graph = fg_graph_create(registry);
    cg_scene scene;
    memset(&scene, 0, sizeof scene);
    bool scene_loaded = false;
    bool ok = fg_graph_load_file(graph, file, &err);
    for (int i = 0; ok && i < set_count; i++)
        ok = fg_graph_apply_override(graph, sets[i], &err);
    if (ok)
        ok = scene_loaded = cg_scene_load(scene_source, &scene, &err);
    int camera = -1;
    if (ok)
        ok = cg_camera_select(&scene, NULL, &camera, &err);
    if (ok) {
        fg_frame frame;
        memset(&frame, 0, sizeof frame);
        frame.scene = &scene;
        frame.width = width;
        frame.height = height;
        cg_view_from_scene(&scene, camera, width, height, &frame.view);
        ok = fg_graph_compile(graph, &frame, &options, &err);
    }
    int code = 0;
    if (!ok) {
        fprintf(stderr, "conegraph graph: %s\n", err.message);
        code = cg_status_exit_code(err.status);
    } else if (dot) {
        fg_graph_write_dot(graph, stdout);
    } else {
        const int *order;
        int live = fg_graph_order(graph, &order);
        printf("%s: compiles for %s at %dx%d: %d of %d passes run\n\n", file, scene_source, width, height, live,
               fg_graph_pass_count(graph));
        fg_graph_print_report(graph, stdout);
    }
    if (ok && report && !fg_graph_write_report_json(graph, report, &err)) {
        fprintf(stderr, "conegraph graph: %s\n", err.message);
        code = 1;
    }
    if (scene_loaded)
        cg_scene_free(&scene);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
    return code;
}
