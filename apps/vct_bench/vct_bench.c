/* vct-bench: per-pass milliseconds and GI memory of a graph on a scene, for docs/vct.md.
 *
 *   vct-bench [SCENE] [--graph FILE] [--size WxH] [--warmup N] [--frames N]
 *             [--set pass.param=value]... [--context egl|osmesa] [-o IMAGE.png|.exr]
 *
 * Runs the graph synchronously (glFinish + CPU clock around each pass: FG_TIMING_SYNC, the
 * only timing llvmpipe gets right), discards the warm-up frames (shader JIT), and prints the
 * median of each pass over the timed frames, the median whole frame, and the graph's memory
 * report (GI bytes: resources flagged gi). Exit codes: 0 done, 1 failed, 2 bad usage.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "app_session.h"
#include "cg/error.h"
#include "cg/fg.h"
#include "cg/gl.h"

#define TOOL "vct-bench"
#define MAX_SETS 64
#define MAX_FRAMES 1000

static void
usage(FILE *out)
{
    fprintf(out,
            "usage: vct-bench [SCENE] [--graph FILE] [--size WxH] [--warmup N] [--frames N]\n"
            "                 [--set pass.param=value]... [--context egl|osmesa] [-o IMAGE]\n"
            "Per-pass median milliseconds (synchronous timing, after warm-up frames) and the\n"
            "graph's memory report. SCENE defaults to builtin:openworld, the graph to vct.json,\n"
            "the size to 640x360, 2 warm-up and 5 timed frames. -o writes the graph's ldr\n"
            "(.png) or hdr (.exr) output of the last frame. Exit codes: 0 done, 1 failed while\n"
            "running, 2 bad usage, scene or graph (found before anything runs).\n");
}

static int
usage_error(const char *fmt, const char *arg)
{
    return app_usage_error(TOOL, fmt, arg);
}

int
main(int argc, char **argv)
{
    const char *scene_name = "builtin:openworld", *graph_arg = NULL, *image_path = NULL;
    const char *sets[MAX_SETS];
    int set_count = 0, width = 640, height = 360;
    long warmup = 2, frames = 5;
    cg_context_backend backend = CG_CONTEXT_AUTO;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        if (a[0] != '-') {
            scene_name = a;
            continue;
        }
        if (!v)
            return usage_error("%s needs a value", a);
        i++;
        if (!strcmp(a, "--graph")) {
            graph_arg = v;
        } else if (!strcmp(a, "--size")) {
            if (!app_parse_size(v, &width, &height))
                return usage_error("--size wants WxH with 1..65536 pixels each, not '%s'", v);
        } else if (!strcmp(a, "--warmup")) {
            if (!app_parse_int(v, 0, 100, &warmup))
                return usage_error("--warmup wants 0 to 100, not '%s'", v);
        } else if (!strcmp(a, "--frames")) {
            if (!app_parse_int(v, 1, MAX_FRAMES, &frames))
                return usage_error("--frames wants 1 to 1000, not '%s'", v);
        } else if (!strcmp(a, "--set")) {
            if (set_count == MAX_SETS)
                return usage_error("%s: too many --set options", v);
            sets[set_count++] = v;
        } else if (!strcmp(a, "--context")) {
            if (!cg_context_backend_parse(v, &backend))
                return usage_error("--context wants egl, osmesa, glfw or auto, not '%s'", v);
        } else if (!strcmp(a, "-o")) {
            if (!app_has_extension(v, ".png") && !app_has_extension(v, ".exr"))
                return usage_error("-o wants a .png or .exr file, not '%s'", v);
            image_path = v;
        } else {
            return usage_error("unknown option '%s'", a);
        }
    }

    bool png = image_path && app_has_extension(image_path, ".png");
    cg_error err = { 0 };
    app_session s;
    app_frame_stats stats = { 0 };
    app_session_desc desc = { .scene = scene_name, .width = width, .height = height };
    app_graph_desc graph = { .graph = graph_arg, .sets = sets, .set_count = set_count,
                             .image = image_path ? (png ? "ldr" : "hdr") : NULL };
    /* No debug context: synchronous KHR_debug output would be part of every pass's time. */
    cg_context_desc context = { .backend = backend };
    app_run_desc run = { .warmup = (int)warmup, .frames = (int)frames, .timing = FG_TIMING_SYNC };
    bool ok = app_session_open(&s, &desc, &err) && app_session_load_graph(&s, &graph, &err) &&
              app_session_check(&s, &err) && app_session_start_gl(&s, &context, &err) &&
              app_session_compile(&s, &err) && app_session_run(&s, &run, &stats, &err);
    if (ok) {
        printf("scene %s, graph %s, %dx%d, median of %ld frames after %ld warm-up\n", scene_name, s.graph_path,
               width, height, frames, warmup);
        for (int p = 0; p < stats.pass_count; p++)
            if (!fg_pass_is_culled(fg_graph_pass_at(s.graph, p)))
                printf("  %-12s %9.2f ms\n", fg_pass_name(fg_graph_pass_at(s.graph, p)),
                       app_frame_stats_pass_median(&stats, p));
        printf("  %-12s %9.2f ms\n", "frame", stats.median_frame_ms);
        fg_memory_report mem;
        fg_graph_memory_report(s.graph, &mem);
        printf("  gi_bytes     %zu\n  peak_bytes   %zu\n", mem.gi_bytes, mem.peak_bytes);
    }
    if (ok && image_path)
        ok = app_session_write_image(&s, s.image_source, png, image_path, CG_EXR_HALF, &err);
    int code = ok ? 0 : app_fail(TOOL, NULL, &err);
    app_frame_stats_free(&stats);
    app_session_close(&s);
    return code;
}
