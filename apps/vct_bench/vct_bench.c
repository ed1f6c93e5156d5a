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

#include "../conegraph/app_common.h"
#include "sdk/builtin.h"
#include "cg/camera.h"
#include "cg/error.h"
#include "cg/gl.h"
#include "cg/gpu_scene.h"
#include "cg/graphfile.h"
#include "cg/image.h"
#include "cg/log.h"
#include "cg/scene.h"

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
            "(.png) or hdr (.exr) output of the last frame.\n");
}

static int
fail(const cg_error *err)
{
    fprintf(stderr, "vct-bench: %s\n", err->message);
    return cg_status_exit_code(err->status);
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
        bool has_value = i + 1 < argc;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "--graph") && has_value) {
            graph_arg = argv[++i];
        } else if (!strcmp(a, "--size") && has_value) {
            if (!app_parse_size(argv[++i], &width, &height)) {
                fprintf(stderr, "vct-bench: --size expects WxH, got '%s'\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "--warmup") && has_value) {
            if (!app_parse_int(argv[++i], 0, 100, &warmup)) {
                fprintf(stderr, "vct-bench: --warmup expects 0..100, got '%s'\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "--frames") && has_value) {
            if (!app_parse_int(argv[++i], 1, MAX_FRAMES, &frames)) {
                fprintf(stderr, "vct-bench: --frames expects 1..%d, got '%s'\n", MAX_FRAMES, argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "--set") && has_value) {
            if (set_count == MAX_SETS) {
                fprintf(stderr, "vct-bench: at most %d --set\n", MAX_SETS);
                return 2;
            }
            sets[set_count++] = argv[++i];
        } else if (!strcmp(a, "--context") && has_value) {
            if (!cg_context_backend_parse(argv[++i], &backend)) {
                fprintf(stderr, "vct-bench: --context expects egl, osmesa or glfw, got '%s'\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "-o") && has_value) {
            image_path = argv[++i];
        } else if (a[0] == '-') {
            fprintf(stderr, "vct-bench: unknown or incomplete option '%s'\n", a);
            usage(stderr);
            return 2;
        } else {
            scene_name = a;
        }
    }

    char graph_path[4096];
    app_resolve_graph(graph_arg, graph_path, sizeof graph_path);
    cg_error err = {0};
    cg_scene scene;
    if (!cg_scene_load(scene_name, &scene, &err))
        return fail(&err);
    cg_context *ctx = NULL;
    cg_context_desc desc = {.backend = backend};
    if (!cg_context_create(&desc, &ctx, &err)) {
        cg_scene_free(&scene);
        return fail(&err);
    }
    int status = 1;
    fg_registry *registry = fg_registry_create();
    fg_graph *graph = NULL;
    cg_gpu_scene gpu;
    bool uploaded = false;
    double *samples = NULL;
    if (!registry || !cg_builtin_passes_register(registry, &err))
        goto done;
    if (!cg_gpu_scene_upload(&scene, &gpu, &err))
        goto done;
    uploaded = true;
    graph = fg_graph_create(registry);
    if (!graph || !fg_graph_load_file(graph, graph_path, &err))
        goto done;
    for (int i = 0; i < set_count; i++)
        if (!fg_graph_apply_override(graph, sets[i], &err))
            goto done;
    fg_frame frame = {.scene = &scene, .gpu_scene = &gpu, .width = width, .height = height};
    cg_view_from_scene(&scene, scene.camera_count > 0 ? 0 : -1, width, height, &frame.view);
    fg_compile_options options = {0};
    if (!fg_graph_compile(graph, &frame, &options, &err) || !fg_graph_prepare(graph, &err))
        goto done;
    int passes = fg_graph_pass_count(graph);
    samples = calloc((size_t)(passes + 1) * (size_t)frames, sizeof *samples);
    if (!samples) {
        cg_fail(&err, CG_ERR_OUT_OF_MEMORY, "vct-bench: samples");
        goto done;
    }
    for (long f = 0; f < warmup + frames; f++) {
        double t0 = app_now_ms();
        if (!fg_graph_execute(graph, &frame, FG_TIMING_SYNC, &err))
            goto done;
        glFinish();
        double total = app_now_ms() - t0;
        frame.index++;
        if (f < warmup)
            continue;
        long k = f - warmup;
        for (int p = 0; p < passes; p++)
            samples[(size_t)p * (size_t)frames + (size_t)k] = fg_pass_milliseconds(fg_graph_pass_at(graph, p));
        samples[(size_t)passes * (size_t)frames + (size_t)k] = total;
    }
    printf("scene %s, graph %s, %dx%d, median of %ld frames after %ld warm-up\n", scene_name, graph_path,
           width, height, frames, warmup);
    for (int p = 0; p <= passes; p++) {
        double *s = &samples[(size_t)p * (size_t)frames];
        if (p < passes && fg_pass_is_culled(fg_graph_pass_at(graph, p)))
            continue;
        qsort(s, (size_t)frames, sizeof *s, app_compare_double);
        printf("  %-12s %9.2f ms\n", p < passes ? fg_pass_name(fg_graph_pass_at(graph, p)) : "frame",
               s[frames / 2]);
    }
    fg_memory_report mem;
    fg_graph_memory_report(graph, &mem);
    printf("  gi_bytes     %zu\n  peak_bytes   %zu\n", mem.gi_bytes, mem.peak_bytes);
    if (image_path) {
        size_t n = strlen(image_path);
        bool png = n > 4 && !strcmp(image_path + n - 4, ".png");
        const char *source = app_find_output(graph, png ? "ldr" : "hdr");
        cg_image img = {0};
        if (!source) {
            cg_fail(&err, CG_ERR_USAGE, "vct-bench: the graph marks no %s output for %s", png ? "ldr" : "hdr",
                    image_path);
            goto done;
        }
        if (!app_read_resource(graph, source, png, &img, &err) ||
            !cg_image_write(image_path, &img, CG_EXR_HALF, &err)) {
            cg_image_free(&img);
            goto done;
        }
        cg_image_free(&img);
    }
    status = 0;
done:
    if (status != 0)
        status = fail(&err);
    free(samples);
    fg_graph_destroy(graph);
    if (uploaded)
        cg_gpu_scene_destroy(&gpu);
    fg_registry_destroy(registry);
    cg_context_destroy(ctx);
    cg_scene_free(&scene);
    return status;
}
