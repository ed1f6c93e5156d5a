/* The path_trace pass in a frame graph: its `radiance` output is exactly pt_render's image
 * (rows flipped for GL), composite passes it through, parameters are validated, and the
 * built-in furnace gives the closed form through the whole graph. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/builtin.h"
#include "cg/camera.h"
#include "cg/fg.h"
#include "cg/fs.h"
#include "cg/gpu_scene.h"
#include "cg/graphfile.h"
#include "cg/scene.h"
#include "cg/pt_render.h"
#include "test_support.h"
#include "path_trace_fixture.h"

enum { W = 40, H = 24 };

static const char *reference_graph =
    "{ \"version\": 1, \"passes\": {"
    "  \"trace\": { \"type\": \"path_trace\", \"params\": { \"spp\": 4, \"bounces\": 1, \"seed\": 5, \"progress\": false } },"
    "  \"final\": { \"type\": \"composite\", \"params\": { \"tonemap\": \"none\" }, \"inputs\": { \"direct\": \"trace.radiance\" } } },"
    "  \"outputs\": [ \"final.hdr\", \"trace.radiance\" ] }";

typedef struct run {
    cg_scene scene;
    cg_gpu_scene gpu;
    fg_registry *registry;
    fg_graph *graph;
    fg_frame frame;
} run;

static void
run_graph(run *r, const char *scene, const char *json, int frames)
{
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(scene, &r->scene, &err), &err);
    int camera;
    assert_cg_ok(cg_camera_select(&r->scene, NULL, &camera, &err), &err);
    r->frame = (fg_frame){ .scene = &r->scene, .width = W, .height = H };
    cg_view_from_scene(&r->scene, camera, W, H, &r->frame.view);
    r->registry = fg_registry_create();
    assert_cg_ok(cg_builtin_passes_register(r->registry, &err), &err);
    r->graph = fg_graph_create(r->registry);
    assert_cg_ok(fg_graph_load_string(r->graph, json, "test.json", &err), &err);
    assert_cg_ok(cg_gpu_scene_upload(&r->scene, &r->gpu, &err), &err);
    r->frame.gpu_scene = &r->gpu;
    fg_compile_options options = { 0 };
    assert_cg_ok(fg_graph_compile(r->graph, &r->frame, &options, &err), &err);
    assert_cg_ok(fg_graph_prepare(r->graph, &err), &err);
    for (int f = 0; f < frames; f++) {
        r->frame.index = (uint64_t)f;
        assert_cg_ok(fg_graph_execute(r->graph, &r->frame, FG_TIMING_SYNC, &err), &err);
    }
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

static void
run_free(run *r)
{
    fg_graph_destroy(r->graph);
    fg_registry_destroy(r->registry);
    cg_gpu_scene_destroy(&r->gpu);
    cg_scene_free(&r->scene);
}

static void
output_is_the_traced_image(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    run r;
    run_graph(&r, "builtin:cornell", reference_graph, 2);
    int w, h;
    float *radiance = cg_test_read_texture(fg_graph_texture(r.graph, "trace.radiance"), 0, &w, &h, NULL);
    float *hdr = cg_test_read_texture(fg_graph_texture(r.graph, "final.hdr"), 0, NULL, NULL, NULL);
    assert_int_equal(w, W);
    assert_int_equal(h, H);

    pt_scene *pts;
    cg_error err = { 0 };
    assert_cg_ok(pt_scene_create(&r.scene, &pts, &err), &err);
    pt_settings s = ptf_settings(4, 1);
    s.seed = 5;
    float *direct = malloc(sizeof(float) * 4 * W * H);
    assert_non_null(direct);
    assert_cg_ok(pt_render(pts, &r.frame.view, &s, direct, NULL, &err), &err);
    double sum = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 4; c++) {
                /* GL rows bottom to top, pt_render's top to bottom. */
                float want = direct[4 * ((H - 1 - y) * W + x) + c];
                float got = radiance[4 * (y * W + x) + c];
                if (got != want)
                    fail_msg("radiance (%d,%d).%d = %g, pt_render %g", x, y, c, got, want);
                /* composite with no indirect and no emissive input: hdr = direct. */
                if (c < 3)
                    assert_float_equal(hdr[4 * (y * W + x) + c], want, 1e-6 * (1.0 + want));
                sum += c < 3 ? want : 0.0;
            }
    assert_true(sum > 0.0); /* the lit box is in view */
    assert_no_gl_errors(ctx);
    free(direct);
    free(radiance);
    free(hdr);
    pt_scene_destroy(pts);
    run_free(&r);
}

/* builtin:furnace through the graph: the camera sees L, each of the n + 1 vertices of an
 * n-bounce path receives L from all around: the mean over the image is L sum_{k=0..n+1} a^k
 * within 5 standard errors of the pixel spread (emitter and cosine samples are combined per
 * sample, so pixels are noisy). */
static void
builtin_furnace_through_the_graph(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const double a = 0.6, le = 0.5;
    for (int n = 0; n <= 2; n++) {
        char json[1024];
        snprintf(json, sizeof json,
                 "{ \"version\": 1, \"passes\": { \"trace\": { \"type\": \"path_trace\", \"params\": "
                 "{ \"spp\": 8, \"bounces\": %d, \"jitter\": true, \"progress\": false } } }, "
                 "\"outputs\": [ \"trace.radiance\" ] }", n);
        run r;
        run_graph(&r, "builtin:furnace?albedo=0.6&radiance=0.5&scale=3", json, 1);
        int w, h;
        float *img = cg_test_read_texture(fg_graph_texture(r.graph, "trace.radiance"), 0, &w, &h, NULL);
        double want = 0.0;
        for (int k = 0; k <= n + 1; k++)
            want += le * pow(a, k);
        double sum = 0.0, sum2 = 0.0;
        for (int i = 0; i < w * h; i++) {
            double v = (img[4 * i] + img[4 * i + 1] + img[4 * i + 2]) / 3.0;
            sum += v;
            sum2 += v * v;
        }
        double mean = sum / (w * h), se = sqrt((sum2 / (w * h) - mean * mean) / (w * h));
        print_message("# furnace through the graph, %d bounces: mean %.5f, L sum a^k = %.5f, standard error %.2g\n",
                      n, mean, want, se);
        assert_true(se < 3e-3 * want);
        if (!(fabs(mean - want) <= 5.0 * se))
            fail_msg("furnace, %d bounces: mean %.6f, expected L sum_{k=0..%d} a^k = %.6f", n, mean, n + 1, want);
        free(img);
        run_free(&r);
    }
    assert_no_gl_errors(ctx);
}

/* With parts=true the pass also outputs pt_render_parts' parts, bit for bit (rows flipped),
 * in the same trace; `radiance` is the same image as without parts. Without parts the part
 * outputs do not exist. */
static void
parts_are_outputs(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    static const char *json =
        "{ \"version\": 1, \"passes\": {"
        "  \"trace\": { \"type\": \"path_trace\", \"params\": { \"spp\": 2, \"bounces\": 1, \"seed\": 5, "
        "\"progress\": false, \"parts\": true } } },"
        "  \"outputs\": [ \"trace.radiance\", \"trace.emitted\", \"trace.direct_punctual\", "
        "\"trace.direct_emitters\", \"trace.direct_sky\", \"trace.indirect\" ] }";
    run r;
    run_graph(&r, "builtin:furnace?albedo=0.6&radiance=0.5", json, 1);
    pt_scene *pts;
    cg_error err = { 0 };
    assert_cg_ok(pt_scene_create(&r.scene, &pts, &err), &err);
    pt_settings s = ptf_settings(2, 1);
    s.seed = 5;
    float *want = malloc(sizeof(float) * 4 * W * H), *parts[PT_PART_COUNT];
    assert_non_null(want);
    for (int p = 0; p < PT_PART_COUNT; p++)
        assert_non_null(parts[p] = malloc(sizeof(float) * 4 * W * H));
    assert_cg_ok(pt_render_parts(pts, &r.frame.view, &s, want, parts, NULL, &err), &err);
    for (int k = -1; k < PT_PART_COUNT; k++) {
        char name[64];
        snprintf(name, sizeof name, "trace.%s", k < 0 ? "radiance" : pt_part_name((pt_part)k));
        float *got = cg_test_read_texture(fg_graph_texture(r.graph, name), 0, NULL, NULL, NULL);
        const float *ref = k < 0 ? want : parts[k];
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int c = 0; c < 4; c++)
                    if (got[4 * (y * W + x) + c] != ref[4 * ((H - 1 - y) * W + x) + c])
                        fail_msg("%s (%d,%d).%d = %g, pt_render_parts %g", name, x, y, c, got[4 * (y * W + x) + c],
                                 ref[4 * ((H - 1 - y) * W + x) + c]);
        free(got);
    }
    /* The furnace: the camera sees emission, the walls receive it, one bounce adds more. */
    assert_true(parts[PT_PART_EMITTED][0] > 0.0f && parts[PT_PART_DIRECT_EMITTERS][0] > 0.0f &&
                parts[PT_PART_INDIRECT][0] > 0.0f && parts[PT_PART_DIRECT_PUNCTUAL][0] == 0.0f);
    assert_no_gl_errors(ctx);
    free(want);
    for (int p = 0; p < PT_PART_COUNT; p++)
        free(parts[p]);
    pt_scene_destroy(pts);
    run_free(&r);

    /* Without parts, asking for one is a dangling reference. */
    fg_registry *registry = fg_registry_create();
    assert_cg_ok(cg_builtin_passes_register(registry, &err), &err);
    fg_graph *graph = fg_graph_create(registry);
    assert_cg_ok(fg_graph_load_string(graph,
                                      "{ \"version\": 1, \"passes\": { \"trace\": { \"type\": \"path_trace\" } }, "
                                      "\"outputs\": [ \"trace.indirect\" ] }",
                                      "noparts.json", &err),
                 &err);
    cg_scene scene = cg_test_load_scene("builtin:cornell");
    fg_frame frame = { .scene = &scene, .width = W, .height = H };
    cg_view_from_scene(&scene, 0, W, H, &frame.view);
    fg_compile_options options = { 0 };
    assert_cg_status(fg_graph_compile(graph, &frame, &options, &err), &err, CG_ERR_GRAPH_DANGLING);
    cg_scene_free(&scene);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

/* graphs/reference.json as shipped: loads, compiles and gives composite's hdr = the trace. */
static void
reference_graph_file_runs(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    char *json;
    size_t size;
    cg_error err = { 0 };
    assert_cg_ok(cg_read_file(cg_test_graph_path("reference.json"), &json, &size, &err), &err);
    /* A few samples keep the test fast; the file's own value is checked to be the documented one. */
    assert_non_null(strstr(json, "\"spp\": 256"));
    char *at = strstr(json, "\"spp\": 256");
    memcpy(at, "\"spp\":   2", 10);
    run r;
    run_graph(&r, "builtin:cornell", json, 1);
    int w, h;
    float *trace = cg_test_read_texture(fg_graph_texture(r.graph, "trace.radiance"), 0, &w, &h, NULL);
    float *hdr = cg_test_read_texture(fg_graph_texture(r.graph, "final.hdr"), 0, NULL, NULL, NULL);
    for (int i = 0; i < w * h; i++)
        for (int c = 0; c < 3; c++)
            assert_float_equal(hdr[4 * i + c], trace[4 * i + c], 1e-6 * (1.0 + trace[4 * i + c]));
    assert_no_gl_errors(ctx);
    free(trace);
    free(hdr);
    free(json);
    run_free(&r);
}

static void
parameters_are_validated(void **state)
{
    (void)state;
    fg_registry *registry = fg_registry_create();
    cg_error err = { 0 };
    assert_cg_ok(cg_builtin_passes_register(registry, &err), &err);
    const fg_pass_type *type = fg_registry_find(registry, "path_trace");
    assert_non_null(type);
    fg_graph *graph = fg_graph_create(registry);
    assert_cg_ok(fg_graph_add_pass(graph, "trace", "path_trace", NULL, &err), &err);
    assert_cg_status(fg_graph_set_param(graph, "trace", "spp", "0", NULL, &err), &err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_cg_status(fg_graph_set_param(graph, "trace", "bounces", "17", NULL, &err), &err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_cg_status(fg_graph_set_param(graph, "trace", "spp", "many", NULL, &err), &err, CG_ERR_GRAPH_PARAM_TYPE);
    assert_cg_ok(fg_graph_set_param(graph, "trace", "bounces", "0", NULL, &err), &err);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(output_is_the_traced_image),
             cmocka_unit_test(builtin_furnace_through_the_graph),
             cmocka_unit_test(parts_are_outputs),
             cmocka_unit_test(reference_graph_file_runs),
             cmocka_unit_test(parameters_are_validated))
