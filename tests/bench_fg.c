/* bench_fg: figures of the frame graph itself (a benchmark that prints, not a test).
 *
 *   build/tests/bench_fg [GRAPH.json [SCENE]]     (defaults: graphs/direct.json, builtin:openworld)
 *
 * 1. compile time of a synthetic 200-pass graph (median of 31 compiles, no GL);
 * 2. executor CPU overhead per pass and per frame: the same graph of empty passes executed
 *    on a headless GL context (median of 31 frames; with and without memory barriers);
 * 3. memory with and without the pool: GRAPH compiled against SCENE at 1280x720, and the
 *    synthetic graph. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sdk/builtin.h"
#include "cg/camera.h"
#include "cg/fg.h"
#include "cg/gl.h"
#include "cg/graphfile.h"
#include "cg/scene.h"

#define PASSES 200
#define RUNS 31

static const fg_param_desc bench_params[] = {
    { .name = "inputs", .type = FG_PARAM_INT, .min = 0, .max = 3,
      .doc = "number of inputs in0..in2 (sampled)" },
    { .name = "format", .type = FG_PARAM_ENUM, .choices = "rgba16f|r32f|rgba8",
      .doc = "format of the output" },
    { .name = "store", .type = FG_PARAM_BOOL,
      .doc = "write the output with image stores (else as an attachment)" },
};

static bool
bench_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)err;
    static const char *const names[] = { "in0", "in1", "in2" };
    static const GLenum formats[] = { GL_RGBA16F, GL_R32F, GL_RGBA8 };
    bool store = fg_param_bool(pass, "store");
    for (int i = 0; i < fg_param_int(pass, "inputs"); i++)
        fg_declare_input(decl, names[i], FG_TEXTURE_2D, store ? FG_ACCESS_IMAGE_LOAD : FG_ACCESS_SAMPLED, true);
    const fg_frame *frame = fg_pass_frame(pass);
    fg_resource_desc desc = { FG_TEXTURE_2D, formats[fg_param_enum(pass, "format")], frame->width,
                              frame->height, 1, 1, 0, false, false };
    fg_declare_output(decl, "out", &desc, store ? FG_ACCESS_IMAGE_STORE : FG_ACCESS_ATTACHMENT);
    return true;
}

static bool
bench_execute(fg_pass *pass, void *state, cg_error *err)
{
    (void)pass;
    (void)state;
    (void)err;
    return true;
}

static const fg_pass_type bench_type = {
    FG_ABI_VERSION, "bench", "An empty pass with 0-3 inputs and one output.", bench_params,
    (int)(sizeof bench_params / sizeof bench_params[0]), false, bench_declare, NULL, bench_execute, NULL,
};

static double
now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int
compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double
median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_double);
    return v[n / 2];
}

static bool
check(bool ok, const cg_error *err)
{
    if (!ok)
        fprintf(stderr, "bench_fg: %s: %s\n", cg_status_name(err->status), err->message);
    return ok;
}

/* 200 passes; each reads up to 3 of the 8 passes before it (a deep graph with local fan-in,
 * like a real pipeline), the last one is the output. Deterministic. */
static fg_graph *
synthetic_graph(const fg_registry *registry, bool store, cg_error *err)
{
    fg_graph *graph = fg_graph_create(registry);
    uint32_t seed = 2463534242u;
    for (int p = 0; p < PASSES; p++) {
        char name[16], value[16];
        snprintf(name, sizeof name, "p%d", p);
        seed ^= seed << 13, seed ^= seed >> 17, seed ^= seed << 5;
        int inputs = p == 0 ? 0 : 1 + (int)(seed % 3);
        if (inputs > p)
            inputs = p;
        if (!fg_graph_add_pass(graph, name, "bench", NULL, err))
            return graph;
        snprintf(value, sizeof value, "%d", inputs);
        fg_graph_set_param(graph, name, "inputs", value, NULL, err);
        static const char *const formats[] = { "rgba16f", "r32f", "rgba8" };
        fg_graph_set_param(graph, name, "format", formats[(seed >> 8) % 3], NULL, err);
        fg_graph_set_param(graph, name, "store", store ? "true" : "false", NULL, err);
        for (int i = 0; i < inputs; i++) {
            seed ^= seed << 13, seed ^= seed >> 17, seed ^= seed << 5;
            int back = 1 + (int)(seed % (p < 8 ? (unsigned)p : 8u));
            char slot[8], source[24];
            snprintf(slot, sizeof slot, "in%d", i);
            snprintf(source, sizeof source, "p%d.out", p - back);
            fg_graph_connect(graph, name, slot, source, NULL, err);
        }
    }
    char out[24];
    snprintf(out, sizeof out, "p%d.out", PASSES - 1);
    fg_graph_mark_output(graph, out, NULL, err);
    return graph;
}

static void
print_memory(const char *what, const fg_graph *graph)
{
    fg_memory_report m;
    fg_graph_memory_report(graph, &m);
    printf("  %-34s resources %8.2f MiB  allocated %8.2f MiB  peak live %8.2f MiB\n", what,
           m.resource_bytes / 1048576.0, m.allocated_bytes / 1048576.0, m.peak_bytes / 1048576.0);
}

int
main(int argc, char **argv)
{
    const char *graph_path = argc > 1 ? argv[1] : "graphs/direct.json";
    const char *scene_source = argc > 2 ? argv[2] : "builtin:openworld";
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    if (!check(fg_registry_add(registry, &bench_type, &err) && cg_builtin_passes_register(registry, &err), &err))
        return 1;

    /* 1. Compile time. */
    fg_frame frame;
    memset(&frame, 0, sizeof frame);
    frame.width = 1280;
    frame.height = 720;
    fg_compile_options options = { false, 0, 16384, 2048 };
    fg_graph *graph = synthetic_graph(registry, false, &err);
    if (!check(err.status == CG_OK, &err))
        return 1;
    double times[RUNS];
    for (int r = 0; r < RUNS; r++) {
        double t0 = now_ms();
        if (!check(fg_graph_compile(graph, &frame, &options, &err), &err))
            return 1;
        times[r] = now_ms() - t0;
    }
    printf("compile, synthetic %d-pass graph: median %.3f ms over %d compiles (no GL)\n", PASSES,
           median(times, RUNS), RUNS);
    print_memory("synthetic graph, pool:", graph);
    options.no_pool = true;
    fg_graph_compile(graph, &frame, &options, &err);
    print_memory("synthetic graph, no pool:", graph);
    options.no_pool = false;
    fg_graph_destroy(graph);

    /* 3. Memory of a real graph. */
    cg_scene scene;
    memset(&scene, 0, sizeof scene);
    if (!check(cg_scene_load(scene_source, &scene, &err), &err))
        return 1;
    int camera = -1;
    cg_camera_select(&scene, NULL, &camera, &err);
    frame.scene = &scene;
    cg_view_from_scene(&scene, camera, frame.width, frame.height, &frame.view);
    graph = fg_graph_create(registry);
    if (!check(fg_graph_load_file(graph, graph_path, &err) && fg_graph_compile(graph, &frame, &options, &err), &err))
        return 1;
    char what[512];
    snprintf(what, sizeof what, "%s, pool:", graph_path);
    print_memory(what, graph);
    options.no_pool = true;
    fg_graph_compile(graph, &frame, &options, &err);
    snprintf(what, sizeof what, "%s, no pool:", graph_path);
    print_memory(what, graph);
    options.no_pool = false;
    fg_graph_destroy(graph);
    frame.scene = NULL;

    /* 2. Executor overhead on GL, empty passes, small images so that storage creation is cheap. */
    cg_context *ctx = NULL;
    cg_context_desc desc = { 0 };
    if (!check(cg_context_create(&desc, &ctx, &err), &err))
        return 1;
    printf("executor, %s:\n", cg_context_renderer(ctx));
    frame.width = 64;
    frame.height = 64;
    for (int store = 0; store < 2; store++) {
        graph = synthetic_graph(registry, store, &err);
        if (!check(fg_graph_compile(graph, &frame, &options, &err) && fg_graph_prepare(graph, &err), &err))
            return 1;
        const int *order;
        int live = fg_graph_order(graph, &order);
        for (int r = -3; r < RUNS; r++) { /* three frames of warm-up */
            glFinish();
            double t0 = now_ms();
            if (!check(fg_graph_execute(graph, &frame, FG_TIMING_NONE, &err), &err))
                return 1;
            if (r >= 0)
                times[r] = now_ms() - t0;
        }
        double frame_ms = median(times, RUNS);
        printf("  %d empty passes, %-32s median %.4f ms per frame, %.2f us per pass (%d frames)\n", live,
               store ? "image stores (barriers issued):" : "attachments (no barriers):", frame_ms,
               frame_ms * 1000.0 / live, RUNS);
        fg_graph_destroy(graph);
    }
    cg_context_destroy(ctx);
    cg_scene_free(&scene);
    fg_registry_destroy(registry);
    return 0;
}
