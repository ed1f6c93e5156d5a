/* vct-bench: per-pass milliseconds and GI memory of a graph on a scene, for docs/vct.md.
 *
 *   vct-bench [SCENE] [--graph FILE] [--size WxH] [--warmup N] [--frames N]
 *             [--set pass.param=value]... [--context egl|osmesa] [-o IMAGE.png|.exr]
 *             [--sky SKY] [--no-default-light]
 *
 * Runs the graph synchronously (glFinish + CPU clock around each pass: FG_TIMING_SYNC, the
 * only timing llvmpipe gets right), discards the warm-up frames (shader JIT), and prints the
 * median of each pass over the timed frames, the median whole frame, and the graph's memory
 * report (GI bytes: resources flagged gi). Exit codes: 0 done, 1 failed while running, 2 bad
 * usage, scene or graph, found by the app session before anything runs.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "app_options.h"
#include "app_session.h"
#include "cg/error.h"
#include "cg/fg.h"
#include "cg/gl.h"

#define TOOL "vct-bench"

static void
usage(FILE *out)
{
    fprintf(out,
            "usage: vct-bench [SCENE] [--graph FILE] [--size WxH] [--warmup N] [--frames N]\n"
            "                 [--set pass.param=value]... [--context egl|osmesa] [-o IMAGE]\n"
            "                 [--sky SKY] [--no-default-light]\n"
            "Per-pass median milliseconds (synchronous timing, after warm-up frames) and the\n"
            "graph's memory report. SCENE defaults to builtin:openworld, the graph to vct.json,\n"
            "the size to 640x360, 2 warm-up and 5 timed frames. -o writes the graph's ldr\n"
            "(.png) or hdr (.exr) output of the last frame. The scene's lighting:\n"
            APP_LIGHT_USAGE
            "Exit codes: 0 done, 1 failed while running, 2 bad usage, scene or graph (found\n"
            "before anything runs).\n");
}

static int
usage_error(const char *fmt, const char *arg)
{
    return app_usage_error(TOOL, fmt, arg);
}

typedef struct vct_options {
    app_options common;         /* scene, graph, size, sets, frames, context */
    long warmup;
    const char *image_path;
} vct_options;

/* --warmup, -o: vct-bench's own options. */
static int
own_option(void *user, const char *a, const char *v)
{
    vct_options *o = user;
    if (!strcmp(a, "--warmup")) {
        if (!app_parse_int(v, 0, 100, &o->warmup))
            return usage_error("--warmup wants 0 to 100, not '%s'", v);
    } else if (!strcmp(a, "-o")) {
        if (!app_has_extension(v, ".png") && !app_has_extension(v, ".exr"))
            return usage_error("-o wants a .png or .exr file, not '%s'", v);
        o->image_path = v;
    } else {
        return -1;
    }
    return 0;
}

int
main(int argc, char **argv)
{
    if (app_wants_help(argc, argv)) {
        usage(stdout);
        return 0;
    }
    vct_options o = { .common = { .width = 640, .height = 360, .frames = 5 }, .warmup = 2 };
    int code = app_parse_options(TOOL, argc, argv, APP_OPT_GRAPH | APP_OPT_SIZE | APP_OPT_SET | APP_OPT_FRAMES |
                                 APP_OPT_CONTEXT, &o.common, own_option, &o);
    if (code)
        return code;
    if (!o.common.scene)
        o.common.scene = "builtin:openworld";

    bool png = o.image_path && app_has_extension(o.image_path, ".png");
    cg_error err = { 0 };
    app_session s;
    app_frame_stats stats = { 0 };
    app_session_desc desc = app_options_session(&o.common);
    app_graph_desc graph = app_options_graph(&o.common);
    graph.image = o.image_path ? (png ? "ldr" : "hdr") : NULL;
    /* No debug context: synchronous KHR_debug output would be part of every pass's time. */
    cg_context_desc context = { .backend = o.common.backend };
    app_run_desc run = { .warmup = (int)o.warmup, .frames = o.common.frames, .timing = FG_TIMING_SYNC };
    bool ok = app_session_open(&s, &desc, &err) && app_session_load_graph(&s, &graph, &err) &&
              app_session_check(&s, &err) && app_session_start_gl(&s, &context, &err) &&
              app_session_compile(&s, &err) && app_session_run(&s, &run, &stats, &err);
    if (ok) {
        printf("scene %s, graph %s, %dx%d, median of %d frames after %ld warm-up\n", o.common.scene, s.graph_path,
               o.common.width, o.common.height, o.common.frames, o.warmup);
        for (int p = 0; p < stats.pass_count; p++)
            if (!fg_pass_is_culled(fg_graph_pass_at(s.graph, p)))
                printf("  %-12s %9.2f ms\n", fg_pass_name(fg_graph_pass_at(s.graph, p)),
                       app_frame_stats_pass_median(&stats, p));
        printf("  %-12s %9.2f ms\n", "frame", stats.median_frame_ms);
        fg_memory_report mem;
        fg_graph_memory_report(s.graph, &mem);
        printf("  gi_bytes     %zu\n  peak_bytes   %zu\n", mem.gi_bytes, mem.peak_bytes);
    }
    if (ok && o.image_path)
        ok = app_session_write_image(&s, s.image_source, png, o.image_path, CG_EXR_HALF, &err);
    code = ok ? 0 : app_fail(TOOL, NULL, &err);
    app_frame_stats_free(&stats);
    app_session_close(&s);
    return code;
}
