/* conegraph render: loads a scene and a graph file, runs the graph for N frames (an animated
 * scene posed at T + k / F for frame k) and writes the final image (.exr: the graph's linear
 * `hdr` output; .png: its tonemapped `ldr`). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "app_options.h"
#include "app_session.h"
#include "cg/error.h"
#include "cg/fg.h"
#include "cg/fs.h"
#include "cg/gl.h"
#include "cg/image.h"
#include "cg/log.h"
#include "cg/progress.h"
#include "commands.h"

typedef struct dump_request {
    char source[256];       /* pass.output */
    const char *path;
} dump_request;

typedef struct render_options {
    app_options common;     /* scene, graph, size, camera, frames, sets, plugins, context, budget, timing */
    const char *output;
    const char *report;
    const char *pass_costs;  /* --pass-costs FILE.csv */
    double fps, time;       /* frame k is posed at time + k / fps */
    dump_request dumps[APP_MAX_LIST];
    int dump_count;
    bool sequence;          /* -o holds one %d conversion: every frame is written */
} render_options;

void
cmd_render_usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph render [SCENE] -o OUT.exr|OUT.png [options]\n"
        "\n"
        "Renders SCENE through a frame graph and writes the final image.\n"
        "\n"
        "  SCENE                   a .gltf/.glb file or builtin:NAME[?key=value&...]\n"
        "                          (default builtin:openworld)\n"
        "  -o, --output FILE       .exr: the graph output named *.hdr, linear radiance (float);\n"
        "                          .png: the graph output named *.ldr (exposed, tonemapped, sRGB).\n"
        "                          With a %%d conversion (f-%%04d.png) every frame is written, the\n"
        "                          frame's number (0, 1, ...) in its place\n"
        "  --graph FILE            graph file (default: vct.json if it exists, else direct.json,\n"
        "                          from the graph directory). A FILE without '/' that does not\n"
        "                          exist here is looked up in the graph directory too.\n"
        "  --size WxH              image size in pixels (default 1280x720)\n"
        APP_CAMERA_USAGE
        APP_LIGHT_USAGE
        "  --frames N              frames to run (default 1); the image is the last frame's\n"
        "                          unless -o holds a %%d. Progress with the time left goes to\n"
        "                          stderr when the frames take over 2 s ($CONEGRAPH_PROGRESS_DELAY\n"
        "                          seconds); --verbose: a line per frame instead\n"
        "  --time T                seconds into the scene's animation of the first frame\n"
        "                          (default 0; 0..1e9)\n"
        "  --fps F                 frames per second of animation time (default 30; above 0,\n"
        "                          at most 1e6): frame k is posed at T + k / F\n"
        "  --report FILE           per-pass times, texture reads and resource bytes as JSON\n"
        "                          (written atomically)\n"
        "  --pass-costs FILE.csv   every frame's per-pass times, texture reads and what each pass rebuilt\n"
        "                          (frame,time,pass,type,ms,reads,items,item,rebuilt; written\n"
        "                          atomically; reads: a pass's counted texture reads, empty\n"
        "                          for a pass that counts none)\n"
        "  --dump PASS.OUT=FILE.exr  also write that resource of the last frame (2D: as is;\n"
        "                          3D and arrays: slices stacked top to bottom); repeatable\n"
        "  --set PASS.PARAM=VALUE  override a parameter, validated like the file; repeatable\n"
        "  --plugin PATH           load a pass plugin (.so); repeatable. Directories in\n"
        "                          $CONEGRAPH_PLUGIN_PATH are loaded too\n"
        "  --context egl|osmesa|glfw  GL context (default: $CONEGRAPH_CONTEXT, else EGL, then OSMesa)\n"
        "  --max-gpu-memory SIZE   refuse graphs needing more GPU memory: a number with its\n"
        "                          unit, e.g. 512M or 2G (B, K, M, G, T: powers of 1024)\n"
        "  --timing sync|queries|none  per-pass timing: glFinish + CPU clock (default, right on\n"
        "                          llvmpipe), GL_TIMESTAMP queries read a frame late, or none\n"
        "  --verbose               also print the compiled graph's passes, barriers and\n"
        "                          resources of the last frame on stdout\n"
        "  --quiet                 print errors only (no progress either)\n"
        "\n"
        "The graph directory is $CONEGRAPH_GRAPH_DIR if set, else the source tree's graphs/\n"
        "(a build run from its build tree), else the installed %s.\n"
        "After the run one line on stderr says what was written, the image size, the graph,\n"
        "the median frame time and the GI memory (--verbose: the tables too, on stdout).\n"
        "Work that takes over 2 s (loading and classifying the scene, the frames, the path\n"
        "tracer) reports its progress and the time left on stderr: on a terminal one line\n"
        "updated in place, into a file or pipe a line per 10%% (never a carriage return).\n"
        "Bad input (scene, graph, parameters, sizes, memory budget, an output path whose\n"
        "directory is missing or not writable or whose extension is wrong) exits with 2\n"
        "before anything is rendered or written; a failure while rendering exits with 1.\n",
        CONEGRAPH_GRAPH_INSTALL_DIR);
}

#define TOOL "conegraph render"

static int
usage_error(const char *fmt, const char *arg)
{
    return app_usage_error(TOOL, fmt, arg);
}

/* -o, --report, --dump: the options of render's own. */
static int
own_option(void *user, const char *a, const char *v)
{
    render_options *o = user;
    if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
        o->output = v;
    } else if (!strcmp(a, "--fps")) {
        if (!app_parse_double(v, 0, 1e6, true, &o->fps))
            return usage_error("--fps wants frames per second above 0 and at most 1e6, not '%s'", v);
    } else if (!strcmp(a, "--time")) {
        if (!app_parse_double(v, 0, 1e9, false, &o->time))
            return usage_error("--time wants seconds from 0 to 1e9, not '%s'", v);
    } else if (!strcmp(a, "--report")) {
        o->report = v;
    } else if (!strcmp(a, "--pass-costs")) {
        if (!app_has_extension(v, ".csv"))
            return usage_error("--pass-costs writes a .csv file, not '%s'", v);
        o->pass_costs = v;
    } else if (!strcmp(a, "--dump")) {
        const char *eq = strchr(v, '=');
        if (!eq || eq == v || !eq[1] || (size_t)(eq - v) >= sizeof o->dumps[0].source)
            return usage_error("--dump wants PASS.OUTPUT=FILE.exr, not '%s'", v);
        if (!app_has_extension(eq + 1, ".exr"))
            return usage_error("--dump writes .exr files only, not '%s'", eq + 1);
        if (o->dump_count == APP_MAX_LIST)
            return usage_error("%s: too many --dump options", v);
        dump_request *d = &o->dumps[o->dump_count++];
        memcpy(d->source, v, (size_t)(eq - v));
        d->source[eq - v] = '\0';
        d->path = eq + 1;
    } else {
        return -1;
    }
    return 0;
}

/* Whether `pattern` holds exactly one %d conversion (flag 0 and a width of at most two digits
 * allowed, as in f-%04d.png) and no other conversion than %%: what -o may hold for a sequence.
 * *sequence tells whether it held one. False for any other conversion, which would make the
 * name a format the caller cannot trust. */
static bool
frame_pattern(const char *pattern, bool *sequence)
{
    int conversions = 0;
    for (const char *p = pattern; *p; p++) {
        if (*p != '%')
            continue;
        if (p[1] == '%') {
            p++;
            continue;
        }
        const char *q = p + 1;
        if (*q == '0')
            q++;
        for (int digits = 0; *q >= '0' && *q <= '9'; q++)
            if (++digits > 2)
                return false;
        if (*q != 'd')
            return false;
        conversions++;
        p = q;
    }
    *sequence = conversions == 1;
    return conversions <= 1;
}

/* The file of frame `frame` of a sequence's pattern (or the path itself). */
static void
frame_path(const render_options *o, int frame, char *out, size_t size)
{
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
    if (o->sequence)
        snprintf(out, size, o->output, frame); /* checked by frame_pattern */
    else
        snprintf(out, size, "%s", o->output);
#pragma GCC diagnostic pop
}

/* Every file the run will write, checked before any work (cg_output_path_check): exit 2. */
static int
check_output_paths(const render_options *o)
{
    cg_error err = { 0 };
    char first[4096];
    frame_path(o, 0, first, sizeof first);
    bool ok = cg_output_path_check(first, ".exr|.png", &err) &&
              (!o->report || cg_output_path_check(o->report, NULL, &err)) &&
              (!o->pass_costs || cg_output_path_check(o->pass_costs, ".csv", &err));
    for (int i = 0; ok && i < o->dump_count; i++)
        ok = cg_output_path_check(o->dumps[i].path, ".exr", &err);
    return ok ? 0 : app_fail(TOOL, NULL, &err);
}

static int
parse_args(int argc, char **argv, render_options *o)
{
    memset(o, 0, sizeof *o);
    o->common.width = 1280;
    o->common.height = 720;
    o->common.frames = 1;
    o->common.timing = FG_TIMING_SYNC;
    o->fps = 30;
    int code = app_parse_options(TOOL, argc, argv, ~0u, &o->common, own_option, o);
    if (code)
        return code;
    if (!o->output)
        return usage_error("%s", "-o OUT.exr|OUT.png is required");
    if (!app_has_extension(o->output, ".exr") && !app_has_extension(o->output, ".png"))
        return usage_error("-o wants a .exr or .png file, not '%s'", o->output);
    if (!frame_pattern(o->output, &o->sequence))
        return usage_error("-o may hold one %%d conversion (f-%%04d.png) and %%%% only, not '%s'", o->output);
    if (!o->common.scene)
        o->common.scene = "builtin:openworld";
    return check_output_paths(o);
}

/* What the per-frame callback sees: the session, and the --pass-costs rows so far (in memory
 * until the run is over, so that a failed run leaves no file). */
typedef struct render_progress {
    app_session *s;
    const render_options *o;
    char *costs;
    size_t costs_size;
    FILE *costs_fp;         /* open_memstream over costs; NULL without --pass-costs */
    cg_progress frames;     /* the frames done, with the time left (cg/progress.h) */
} render_progress;

/* The frame's image of a sequence (-o f-%04d.png), the progress of the frames (with --verbose a
 * line per frame on stderr, with what each pass that said so rebuilt), and the frame's rows of
 * --pass-costs. */
static bool
on_frame(void *user, int frame, int frames, double ms, cg_error *err)
{
    render_progress *p = user;
    fg_graph *graph = p->s->graph;
    const render_options *o = p->o;
    if (o->sequence) {
        char path[4096];
        frame_path(o, frame, path, sizeof path);
        if (!app_session_write_image(p->s, p->s->image_source, app_has_extension(o->output, ".png"), path,
                                     CG_EXR_FLOAT, err))
            return false;
    }
    cg_progress_update(&p->frames, frame + 1);
    if (frames > 1 && o->common.verbose && !o->common.quiet) {
        fprintf(stderr, "render: frame %d/%d %.1f ms", frame + 1, frames, ms);
        for (int i = 0; i < fg_graph_pass_count(graph); i++) {
            const fg_pass *pass = fg_graph_pass_at(graph, i);
            if (!fg_pass_is_culled(pass) && fg_pass_rebuilt(pass)[0])
                fprintf(stderr, "; %s: %s", fg_pass_name(pass), fg_pass_rebuilt(pass));
        }
        fputc('\n', stderr);
    }
    if (!p->costs_fp)
        return true;
    for (int i = 0; i < fg_graph_pass_count(graph); i++) {
        const fg_pass *pass = fg_graph_pass_at(graph, i);
        if (fg_pass_is_culled(pass))
            continue;
        fprintf(p->costs_fp, "%d,%.17g,%s,%s,%.6f,", frame, p->s->scene.time, fg_pass_name(pass),
                fg_pass_type_of(pass)->name, fg_pass_milliseconds(pass));
        /* The texture reads, empty where the pass counts none (fg_pass_reads). */
        double reads, items;
        const char *item;
        if (fg_pass_reads(pass, &reads, &items, &item))
            fprintf(p->costs_fp, "%.0f,%.0f,%s,", reads, items, item);
        else
            fputs(",,,", p->costs_fp);
        app_csv_field(p->costs_fp, fg_pass_rebuilt(pass));
        fputc('\n', p->costs_fp);
    }
    return true;
}

static bool
write_pass_costs(const char *path, render_progress *p, cg_error *err)
{
    if (!p->costs_fp || fflush(p->costs_fp) != 0)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory for the per-pass rows", path);
    cg_atomic_file f;
    if (!cg_atomic_open(&f, path, err))
        return false;
    fputs("frame,time,pass,type,ms,reads,items,item,rebuilt\n", f.fp);
    fwrite(p->costs, 1, p->costs_size, f.fp);
    return cg_atomic_commit(&f, err);
}

/* The one line a run ends with: what it wrote (every file), from what, how fast, how much GI
 * memory. */
static void
print_summary(const render_options *o, app_session *s, const app_frame_stats *stats)
{
    const app_options *c = &o->common;
    fg_memory_report memory;
    fg_graph_memory_report(s->graph, &memory);
    char when[96] = "";
    if (cg_scene_is_animated(&s->scene))
        snprintf(when, sizeof when, " (animated: the last at t = %g s)", s->scene.time);
    fprintf(stderr, "render: %s %dx%d, graph %s, %s on %s: median frame %.1f ms over %d frame(s)%s, GI %.1f MiB; wrote %s",
            s->scene.name, c->width, c->height, s->graph_path,
            cg_context_backend_name(cg_context_get_backend(s->ctx)), cg_context_renderer(s->ctx),
            stats->median_frame_ms, c->frames, when, (double)memory.gi_bytes / (1024.0 * 1024.0), o->output);
    if (o->sequence)
        fprintf(stderr, " (%d frames)", c->frames);
    for (int i = 0; i < o->dump_count; i++)
        fprintf(stderr, ", %s", o->dumps[i].path);
    if (o->report)
        fprintf(stderr, ", %s", o->report);
    if (o->pass_costs)
        fprintf(stderr, ", %s", o->pass_costs);
    fputc('\n', stderr);
}

/* Bad input (scene, graph, parameters, read-backs) exits 2 from app_session_check, before
 * the scene goes to the GPU and before any file is written. */
static int
render(const render_options *o)
{
    cg_error err = { 0 };
    app_session s;
    app_frame_stats stats = { 0 };
    bool png = app_has_extension(o->output, ".png");
    const app_options *c = &o->common;
    const char *reads[APP_MAX_LIST];
    for (int i = 0; i < o->dump_count; i++)
        reads[i] = o->dumps[i].source;
    app_session_desc desc = app_options_session(c);
    app_graph_desc graph = app_options_graph(c);
    graph.image = png ? "ldr" : "hdr";
    graph.reads = reads;
    graph.read_count = o->dump_count;
    cg_context_desc context = { .backend = c->backend, .width = c->width, .height = c->height, .debug = true };
    render_progress progress = { .s = &s, .o = o };
    if (c->quiet)
        cg_log_set_level(CG_LOG_ERROR);
    if (o->pass_costs)
        progress.costs_fp = open_memstream(&progress.costs, &progress.costs_size);
    app_run_desc run = { .frames = c->frames, .timing = c->timing, .on_frame = on_frame,
                         .user = &progress, .animate = true, .time = o->time, .fps = o->fps };
    bool ok = app_session_open(&s, &desc, &err) && app_session_load_graph(&s, &graph, &err) &&
              app_session_check(&s, &err) && cg_image_io_check(&err) && app_session_start_gl(&s, &context, &err) &&
              app_session_compile(&s, &err);
    /* Progress over the frames (--verbose has its own line per frame; one frame has nothing to
     * count: the scene load and the path tracer report their own); a frame that takes over the
     * delay by itself is reported as it ends, with the time the others will take. */
    char what[64];
    snprintf(what, sizeof what, "rendering %d frame%s", c->frames, c->frames == 1 ? "" : "s");
    cg_progress_begin(&progress.frames, &(cg_progress_desc){ .what = what, .total = c->frames, .unit = "frames" });
    if ((c->verbose && c->frames > 1) || c->frames == 1)
        progress.frames.enabled = false;
    ok = ok && app_session_run(&s, &run, &stats, &err) &&
         (o->sequence || app_session_write_image(&s, s.image_source, png, o->output, CG_EXR_FLOAT, &err));
    if (ok)
        cg_progress_end(&progress.frames);
    for (int i = 0; ok && i < o->dump_count; i++)
        ok = app_session_write_image(&s, o->dumps[i].source, false, o->dumps[i].path, CG_EXR_FLOAT, &err);
    if (ok && o->report)
        ok = fg_graph_write_report_json(s.graph, o->report, &err);
    if (ok && o->pass_costs)
        ok = write_pass_costs(o->pass_costs, &progress, &err);
    if (progress.costs_fp)
        fclose(progress.costs_fp);
    free(progress.costs);
    int code = ok ? 0 : app_fail(TOOL, NULL, &err);
    if (ok && c->verbose)
        fg_graph_print_report(s.graph, stdout);
    if (ok && !c->quiet)
        print_summary(o, &s, &stats);
    app_frame_stats_free(&stats);
    app_session_close(&s);
    return code;
}

int
cmd_render(int argc, char **argv)
{
    render_options o;
    int code = parse_args(argc, argv, &o);
    return code ? code : render(&o);
}
