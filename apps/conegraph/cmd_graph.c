/* conegraph graph: reads a graph file and compiles it without GL against a scene: prints the
 * execution order, the culled passes with their reasons and the resources, or Graphviz DOT. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "app_session.h"
#include "cg/fg.h"
#include "commands.h"

#define TOOL "conegraph graph"

#define MAX_REPEATED 64

void
cmd_graph_usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph graph FILE [--check] [--dot] [--set PASS.PARAM=VALUE]... [--plugin PATH]...\n"
        "                       [--size WxH] [--max-gpu-memory SIZE] [--no-pool] [--report FILE]\n"
        "                       [--camera NAME|INDEX|auto] [--sky SKY] [--no-default-light] [SCENE]\n"
        "\n"
        "Reads graph file FILE and compiles it against SCENE (a .gltf/.glb path or builtin:NAME;\n"
        "default builtin:openworld) without GL: declares every pass, validates, culls, orders,\n"
        "computes lifetimes, pooled storage and barriers, and checks the sizes against the GL\n"
        "limits given here (no GL context is made). A FILE without '/' that does not exist here\n"
        "is looked up in the graph directory, as render --graph does. The scene is lit as render\n"
        "lights it (--sky, the file's \"sky\", the default light), since what a scene's lights\n"
        "are decides which passes run.\n"
        "\n"
        "  --check                compile and print the execution order, the culled passes with\n"
        "                         their reasons, and the resources with their bytes (the default)\n"
        "  --dot                  print the compiled graph as Graphviz DOT instead (culled passes\n"
        "                         dashed, edges labelled with resource, format and size)\n"
        "  --set PASS.PARAM=VALUE override a parameter, validated as in a file; may be repeated\n"
        "  --plugin PATH          load a pass plugin first; may be repeated\n"
        "  --size WxH             output image size (default 1280x720)\n"
        "  --max-gpu-memory SIZE  fail when the graph needs more GPU memory than this: a number\n"
        "                         with its unit, e.g. 512M or 2G (B, K, M, G, T: powers of 1024)\n"
        "  --max-texture-size N   largest 2D texture side (default 16384)\n"
        "  --max-3d-texture-size N  largest 3D texture side (default 2048)\n"
        "  --no-pool              give every transient resource its own storage\n"
        "  --report FILE          also write the compile report as JSON (atomically)\n"
        "  --camera NAME|INDEX|auto  the scene camera the view comes from (as render)\n"
        "  --sky SKY              the scene's sky, as render --sky (overrides the file's \"sky\")\n"
        "  --no-default-light     no sun and sky for a scene that nothing lights\n"
        "\n"
        "Exit codes: 0 the graph compiles, 1 failed while running (writing the report),\n"
        "2 bad usage, bad graph file (with file:line:column) or unloadable scene.\n");
}

int
cmd_graph(int argc, char **argv)
{
    const char *file = NULL, *scene_source = "builtin:openworld", *report = NULL, *camera = NULL;
    cg_sky sky;
    bool sky_given = false, no_default_light = false;
    const char *sets[MAX_REPEATED] = { 0 }, *plugins[MAX_REPEATED] = { 0 };
    int set_count = 0, plugin_count = 0, width = 1280, height = 720;
    bool dot = false;
    fg_compile_options options = { false, 0, 16384, 2048 };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool has_value = i + 1 < argc;
        long v;
        if (!strcmp(a, "--check")) {
            dot = false;
        } else if (!strcmp(a, "--dot")) {
            dot = true;
        } else if (!strcmp(a, "--set") && has_value && set_count < MAX_REPEATED) {
            sets[set_count++] = argv[++i];
        } else if (!strcmp(a, "--plugin") && has_value && plugin_count < MAX_REPEATED) {
            plugins[plugin_count++] = argv[++i];
        } else if (!strcmp(a, "--size") && has_value) {
            if (!app_parse_size(argv[++i], &width, &height)) {
                fprintf(stderr, "conegraph graph: --size %s: expected WxH, e.g. 1280x720\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "--max-gpu-memory") && has_value) {
            if (!app_parse_bytes(argv[++i], &options.max_gpu_memory)) {
                fprintf(stderr, "conegraph graph: --max-gpu-memory wants " APP_BYTES_SYNTAX ", not '%s'\n",
                        argv[i]);
                return 2;
            }
        } else if ((!strcmp(a, "--max-texture-size") || !strcmp(a, "--max-3d-texture-size")) && has_value) {
            if (!app_parse_int(argv[++i], 1, 1 << 20, &v)) {
                fprintf(stderr, "conegraph graph: %s %s: expected a positive integer\n", a, argv[i]);
                return 2;
            }
            if (!strcmp(a, "--max-texture-size"))
                options.max_texture_size_2d = (int)v;
            else
                options.max_texture_size_3d = (int)v;
        } else if (!strcmp(a, "--no-pool")) {
            options.no_pool = true;
        } else if (!strcmp(a, "--no-default-light")) {
            no_default_light = true;
        } else if (!strcmp(a, "--camera") && has_value) {
            camera = argv[++i];
        } else if (!strcmp(a, "--sky") && has_value) {
            cg_error why = { 0 };
            if (!cg_sky_parse(argv[++i], &sky, &why)) {
                fprintf(stderr, "conegraph graph: --sky: %s\n", why.message);
                return 2;
            }
            sky_given = true;
        } else if (!strcmp(a, "--report") && has_value) {
            report = argv[++i];
        } else if (a[0] == '-') {
            fprintf(stderr, "conegraph graph: unknown or incomplete option '%s'\n", a);
            cmd_graph_usage(stderr);
            return 2;
        } else if (!file) {
            file = a;
        } else {
            scene_source = a;
        }
    }
    if (!file) {
        fprintf(stderr, "conegraph graph: no graph file given\n");
        cmd_graph_usage(stderr);
        return 2;
    }

    /* The app session without GL: scene, registry with plugins, graph with overrides, and the
     * compile that every app runs first. */
    cg_error err = { 0 };
    app_session session;
    app_session_desc desc = { .tool = TOOL, .scene = scene_source, .camera = camera, .plugins = plugins,
                              .plugin_count = plugin_count, .width = width, .height = height, .compile = options,
                              .sky = sky_given ? &sky : NULL, .no_default_light = no_default_light };
    app_graph_desc graph = { .graph = file, .sets = sets, .set_count = set_count };
    bool ok = app_session_open(&session, &desc, &err) && app_session_load_graph(&session, &graph, &err) &&
              app_session_check(&session, &err);
    int code = ok ? 0 : app_fail(TOOL, NULL, &err);
    if (ok && dot) {
        fg_graph_write_dot(session.graph, stdout);
    } else if (ok) {
        const int *order;
        int live = fg_graph_order(session.graph, &order);
        printf("%s: compiles for %s at %dx%d: %d of %d passes run\n\n", file, scene_source, width, height, live,
               fg_graph_pass_count(session.graph));
        fg_graph_print_report(session.graph, stdout);
    }
    if (ok && report && !fg_graph_write_report_json(session.graph, report, &err))
        code = app_fail(TOOL, NULL, &err);
    app_session_close(&session);
    return code;
}
