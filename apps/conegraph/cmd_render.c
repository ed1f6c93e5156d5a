/* conegraph render: loads a scene and a graph file, runs the graph for N frames and writes
 * the final image (.exr: the graph's linear `hdr` output; .png: its tonemapped `ldr`). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>

#include "app_common.h"
#include "app_registry.h"
#include "cg/camera.h"
#include "cg/error.h"
#include "cg/fg.h"
#include "cg/gl.h"
#include "cg/gpu_scene.h"
#include "cg/graphfile.h"
#include "cg/image.h"
#include "cg/log.h"
#include "cg/scene.h"
#include "commands.h"

#define MAX_LIST 64

typedef struct dump_request {
    char source[256];       /* pass.output */
    const char *path;
} dump_request;

typedef struct render_options {
    const char *scene;
    const char *graph;
    const char *output;
    int width, height;
    const char *camera;
    int frames;
    const char *report;
    dump_request dumps[MAX_LIST];
    int dump_count;
    const char *sets[MAX_LIST];
    int set_count;
    const char *plugins[MAX_LIST];
    int plugin_count;
    cg_context_backend backend;
    size_t max_gpu_memory;
    fg_timing_mode timing;
} render_options;

static void
render_usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph render [SCENE] -o OUT.exr|OUT.png [options]\n"
        "\n"
        "Renders SCENE through a frame graph and writes the final image.\n"
        "\n"
        "  SCENE                   a .gltf/.glb file or builtin:NAME[?key=value&...]\n"
        "                          (default builtin:openworld)\n"
        "  -o, --output FILE       .exr: the graph output named *.hdr, linear radiance (float);\n"
        "                          .png: the graph output named *.ldr (exposed, tonemapped, sRGB)\n"
        "  --graph FILE            graph file (default: vct.json if it exists, else direct.json,\n"
        "                          from the graph directory). A FILE without '/' that does not\n"
        "                          exist here is looked up in the graph directory too.\n"
        "  --size WxH              image size in pixels (default 1280x720)\n"
        "  --camera NAME|INDEX     scene camera (default: the first; framed from the bounds if none)\n"
        "  --frames N              frames to run (default 1); the image is the last frame's;\n"
        "                          progress and the median frame time go to stderr\n"
        "  --report FILE           per-pass times and resource bytes as JSON (written atomically)\n"
        "  --dump PASS.OUT=FILE.exr  also write that resource of the last frame (2D: as is;\n"
        "                          3D and arrays: slices stacked top to bottom); repeatable\n"
        "  --set PASS.PARAM=VALUE  override a parameter, validated like the file; repeatable\n"
        "  --plugin PATH           load a pass plugin (.so); repeatable. Directories in\n"
        "                          $CONEGRAPH_PLUGIN_PATH are loaded too\n"
        "  --context egl|osmesa|glfw  GL context (default: $CONEGRAPH_CONTEXT, else EGL, then OSMesa)\n"
        "  --max-gpu-memory BYTES  refuse graphs needing more (suffixes K, M, G = 1024^n)\n"
        "  --timing sync|queries|none  per-pass timing: glFinish + CPU clock (default, right on\n"
        "                          llvmpipe), GL_TIMESTAMP queries read a frame late, or none\n"
        "\n"
        "The graph directory is $CONEGRAPH_GRAPH_DIR if set, else the source tree's graphs/\n"
        "(a build run from its build tree), else the installed %s.\n"
        "After the run, the per-pass times and resources of the last frame go to stdout.\n"
        "Bad input (scene, graph, parameters, sizes, memory budget) exits with 2 before\n"
        "anything is rendered or written; a failure while rendering exits with 1.\n",
        CONEGRAPH_GRAPH_INSTALL_DIR);
}

static int
usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "conegraph render: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see conegraph render --help)\n");
    return 2;
}

static bool
parse_bytes(const char *text, size_t *out)
{
    char *end;
    errno = 0;
    if (!isdigit((unsigned char)text[0]))
        return false;
    unsigned long long v = strtoull(text, &end, 10);
    if (errno || end == text)
        return false;
    unsigned long long scale = 1;
    if (*end == 'K' || *end == 'k')
        scale = 1ull << 10;
    else if (*end == 'M' || *end == 'm')
        scale = 1ull << 20;
    else if (*end == 'G' || *end == 'g')
        scale = 1ull << 30;
    if (scale != 1)
        end++;
    if (*end || v == 0 || v > (unsigned long long)SIZE_MAX / scale)
        return false;
    *out = (size_t)(v * scale);
    return true;
}

static bool
has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && !strcasecmp(path + n - e, ext);
}

static int
parse_args(int argc, char **argv, render_options *o)
{
    memset(o, 0, sizeof *o);
    o->width = 1280;
    o->height = 720;
    o->frames = 1;
    o->timing = FG_TIMING_SYNC;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        bool takes_value = a[0] == '-' && a[1] != '\0';
        if (takes_value && !v && strcmp(a, "--help") && strcmp(a, "-h"))
            return usage_error("%s needs a value", a);
        if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            o->output = v;
        } else if (!strcmp(a, "--graph")) {
            o->graph = v;
        } else if (!strcmp(a, "--size")) {
            if (!app_parse_size(v, &o->width, &o->height))
                return usage_error("--size wants WxH with 1..65536 pixels each, not '%s'", v);
        } else if (!strcmp(a, "--camera")) {
            o->camera = v;
        } else if (!strcmp(a, "--frames")) {
            long n;
            if (!app_parse_int(v, 1, 1000000, &n))
                return usage_error("--frames wants a count from 1 to 1000000, not '%s'", v);
            o->frames = (int)n;
        } else if (!strcmp(a, "--report")) {
            o->report = v;
        } else if (!strcmp(a, "--dump")) {
            const char *eq = strchr(v, '=');
            if (!eq || eq == v || !eq[1] || (size_t)(eq - v) >= sizeof o->dumps[0].source)
                return usage_error("--dump wants PASS.OUTPUT=FILE.exr, not '%s'", v);
            if (!has_extension(eq + 1, ".exr"))
                return usage_error("--dump writes .exr files only, not '%s'", eq + 1);
            if (o->dump_count == MAX_LIST)
                return usage_error("%s: too many --dump options", v);
            dump_request *d = &o->dumps[o->dump_count++];
            memcpy(d->source, v, (size_t)(eq - v));
            d->source[eq - v] = '\0';
            d->path = eq + 1;
        } else if (!strcmp(a, "--set")) {
            if (o->set_count == MAX_LIST)
                return usage_error("%s: too many --set options", v);
            o->sets[o->set_count++] = v;
        } else if (!strcmp(a, "--plugin")) {
            if (o->plugin_count == MAX_LIST)
                return usage_error("%s: too many --plugin options", v);
            o->plugins[o->plugin_count++] = v;
        } else if (!strcmp(a, "--context")) {
            if (!cg_context_backend_parse(v, &o->backend))
                return usage_error("--context wants egl, osmesa, glfw or auto, not '%s'", v);
        } else if (!strcmp(a, "--max-gpu-memory")) {
            if (!parse_bytes(v, &o->max_gpu_memory))
                return usage_error("--max-gpu-memory wants a positive byte count (suffix K, M or G), not '%s'", v);
        } else if (!strcmp(a, "--timing")) {
            if (!app_parse_timing(v, &o->timing))
                return usage_error("--timing wants sync, queries or none, not '%s'", v);
        } else if (a[0] == '-' && a[1] != '\0') {
            return usage_error("unknown option '%s'", a);
        } else {
            if (o->scene)
                return usage_error("one scene only; '%s' is a second one", a);
            o->scene = a;
            continue;
        }
        i++;
    }
    if (!o->output)
        return usage_error("%s", "-o OUT.exr|OUT.png is required");
    if (!has_extension(o->output, ".exr") && !has_extension(o->output, ".png"))
        return usage_error("-o wants a .exr or .png file, not '%s'", o->output);
    if (!o->scene)
        o->scene = "builtin:openworld";
    return 0;
}

static int
fail_with(const char *what, const cg_error *err)
{
    fprintf(stderr, "conegraph render: %s: %s\n", what, err->message);
    int code = cg_status_exit_code(err->status);
    return code ? code : 1;
}

/* Builds the graph: file, --set overrides, --dump sources marked as outputs. */
static bool
build_graph(const render_options *o, const char *graph_path, fg_graph *graph, cg_error *err)
{
    if (!app_load_graph(graph, graph_path, o->sets, o->set_count, err))
        return false;
    for (int i = 0; i < o->dump_count; i++) {
        /* Marked as outputs so that they are kept and never pooled away before the read-back. */
        bool marked = false;
        for (int k = 0; k < fg_graph_output_count(graph); k++)
            marked |= !strcmp(fg_graph_output_at(graph, k), o->dumps[i].source);
        if (!marked && !fg_graph_mark_output(graph, o->dumps[i].source, NULL, err))
            return false;
    }
    return true;
}

/* Everything to be written as an image must be a texture that this scene produces (a pass
 * with nothing to do leaves its outputs absent): known after compile, before rendering. */
static bool
check_images(const render_options *o, const fg_graph *graph, const char *image_source, cg_error *err)
{
    for (int i = -1; i < o->dump_count; i++) {
        const char *source = i < 0 ? image_source : o->dumps[i].source;
        const fg_resource_info *info = fg_graph_find_resource(graph, source);
        char pass_name[256];
        snprintf(pass_name, sizeof pass_name, "%.*s", (int)strcspn(source, "."), source);
        const fg_pass *pass = fg_graph_find_pass(graph, pass_name);
        if ((!info || info->absent) && pass && fg_pass_is_culled(pass))
            return cg_fail(err, CG_ERR_USAGE, "%s: absent for scene '%s' (pass '%s': %s), so it cannot "
                           "be written", source, o->scene, pass_name, fg_pass_cull_reason(pass));
        if (!info || info->absent)
            return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%s: no such resource", source);
        if (info->desc.kind == FG_BUFFER)
            return cg_fail(err, CG_ERR_USAGE, "%s: a buffer; only textures can be written as images", source);
    }
    return true;
}

static int
render(const render_options *o)
{
    cg_error err = { 0 };
    int code = 1;
    char graph_path[4096];
    app_resolve_graph(o->graph, graph_path, sizeof graph_path);
    const char *image_source = NULL;

    cg_scene scene;
    memset(&scene, 0, sizeof scene);
    if (!cg_scene_load(o->scene, &scene, &err))
        return fail_with("scene", &err);
    int camera = -1;
    if (!cg_camera_select(&scene, o->camera, &camera, &err)) {
        cg_scene_free(&scene);
        return fail_with("camera", &err);
    }

    fg_registry *registry = NULL;
    fg_graph *graph = NULL;
    cg_context *ctx = NULL;
    cg_gpu_scene gpu;
    bool uploaded = false;
    double *frame_ms = NULL;
    cg_image image = { 0 };
    memset(&gpu, 0, sizeof gpu);
    registry = app_registry_create(o->plugins, o->plugin_count, &err);
    if (!registry) {
        code = fail_with("passes", &err);
        goto done;
    }

    graph = fg_graph_create(registry);
    if (!graph || !build_graph(o, graph_path, graph, &err)) {
        code = graph ? fail_with("graph", &err) : 1;
        goto done;
    }
    image_source = app_find_output(graph, has_extension(o->output, ".exr") ? "hdr" : "ldr");
    if (!image_source) {
        fprintf(stderr, "conegraph render: %s: the graph marks no output named '%s' for %s\n",
                graph_path, has_extension(o->output, ".exr") ? "*.hdr" : "*.ldr", o->output);
        code = 2;
        goto done;
    }

    fg_frame frame = { .scene = &scene, .gpu_scene = NULL, .width = o->width, .height = o->height };
    cg_view_from_scene(&scene, camera, o->width, o->height, &frame.view);
    fg_compile_options copts = { .max_gpu_memory = o->max_gpu_memory };
    /* A first compile without GL finds every bad-input error before the scene goes to the GPU. */
    if (!fg_graph_compile(graph, &frame, &copts, &err)) {
        code = fail_with("graph", &err);
        goto done;
    }
    if (!check_images(o, graph, image_source, &err)) {
        code = fail_with("graph", &err);
        goto done;
    }

    cg_context_desc cdesc = { .backend = o->backend, .width = o->width, .height = o->height, .debug = true };
    if (!cg_context_create(&cdesc, &ctx, &err)) {
        code = fail_with("GL context", &err);
        goto done;
    }
    if (!cg_gpu_scene_upload(&scene, &gpu, &err)) {
        code = fail_with("scene upload", &err);
        goto done;
    }
    uploaded = true;
    frame.gpu_scene = &gpu;
    /* Again with GL: the texture size limits are the context's. */
    if (!fg_graph_compile(graph, &frame, &copts, &err)) {
        code = fail_with("graph", &err);
        goto done;
    }
    if (!fg_graph_prepare(graph, &err)) {
        code = fail_with("prepare", &err);
        goto done;
    }

    frame_ms = calloc((size_t)o->frames, sizeof *frame_ms);
    if (!frame_ms) {
        fprintf(stderr, "conegraph render: out of memory\n");
        goto done;
    }
    for (int f = 0; f < o->frames; f++) {
        frame.index = (uint64_t)f;
        double t0 = app_now_ms();
        if (!fg_graph_execute(graph, &frame, o->timing, &err)) {
            code = fail_with("frame", &err);
            goto done;
        }
        glFinish();
        frame_ms[f] = app_now_ms() - t0;
        if (o->frames > 1)
            fprintf(stderr, "render: frame %d/%d %.1f ms\n", f + 1, o->frames, frame_ms[f]);
    }
    if (cg_context_gl_error_count(ctx) > 0) {
        fprintf(stderr, "conegraph render: %d GL error(s) while rendering (logged above); nothing written\n",
                cg_context_gl_error_count(ctx));
        goto done;
    }

    if (!app_read_resource(graph, image_source, has_extension(o->output, ".png"), &image, &err)) {
        code = fail_with(image_source, &err);
        goto done;
    }
    if (!cg_image_write(o->output, &image, CG_EXR_FLOAT, &err)) {
        code = fail_with(o->output, &err);
        goto done;
    }
    for (int i = 0; i < o->dump_count; i++) {
        cg_image dump = { 0 };
        if (!app_read_resource(graph, o->dumps[i].source, false, &dump, &err) ||
            !cg_image_write(o->dumps[i].path, &dump, CG_EXR_FLOAT, &err)) {
            cg_image_free(&dump);
            code = fail_with(o->dumps[i].source, &err);
            goto done;
        }
        cg_image_free(&dump);
    }
    if (o->report && !fg_graph_write_report_json(graph, o->report, &err)) {
        code = fail_with(o->report, &err);
        goto done;
    }

    fg_graph_print_report(graph, stdout);
    qsort(frame_ms, (size_t)o->frames, sizeof *frame_ms, app_compare_double);
    fprintf(stderr, "render: %s %dx%d, graph %s, %s on %s: median frame %.1f ms over %d frame(s); wrote %s\n",
            scene.name, o->width, o->height, graph_path, cg_context_backend_name(cg_context_get_backend(ctx)),
            cg_context_renderer(ctx), frame_ms[o->frames / 2], o->frames, o->output);
    code = 0;

done:
    cg_image_free(&image);
    free(frame_ms);
    if (graph)
        fg_graph_destroy(graph);
    if (uploaded)
        cg_gpu_scene_destroy(&gpu);
    if (ctx)
        cg_context_destroy(ctx);
    if (registry)
        fg_registry_destroy(registry);
    cg_scene_free(&scene);
    return code;
}

int
cmd_render(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            render_usage(stdout);
            return 0;
        }
    render_options o;
    int code = parse_args(argc, argv, &o);
    if (code)
        return code;
    return render(&o);
}
