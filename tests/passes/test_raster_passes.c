/* Per-pass tests of shadow_map, gbuffer, direct_light and composite, each on a headless
 * GL context with scenes of a few quads built in code (tests/passes/pass_fixtures.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/builtin.h"
#include "cg/bsdf.h"
#include "cg/error.h"
#include "cg/graphfile.h"
#include "cg/image.h"
#include "pass_fixtures.h"
#include "test_support.h"

#define SIZE 64
#define PI 3.14159265358979323846

static const float up_y[3] = { 0.0f, 1.0f, 0.0f };
static const float up_z[3] = { 0.0f, 0.0f, -1.0f };

static const float *
texel(const float *rgba, int w, int x, int y)
{
    return rgba + ((size_t)y * (size_t)w + (size_t)x) * 4;
}

/* A 4x4 floor at y = 0 and a 0.5x0.5 occluder at y = 1 above its centre. */
static void
floor_and_occluder(fx_scene *s)
{
    fx_scene_init(s);
    fx_add_quad(s, 1, 0.0f, -2.0f, 2.0f, -2.0f, 2.0f, 0);
    fx_add_quad(s, 1, 1.0f, -0.25f, 0.25f, -0.25f, 0.25f, 0);
}

/* Straight down onto the floor: the orthographic map of a directional light fitted to the
 * bounds sees the floor 1 m behind the occluder. Expected depths follow the fit: bounds
 * y in [0, 1], radius = half the diagonal = 0.5 * sqrt(4^2 + 1 + 4^2) = sqrt(33)/2, the eye
 * at the bounds' centre + radius up, a margin of 1% of the radius on near and far. */
static void
test_shadow_map_depth_of_plane(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    floor_and_occluder(&s);
    fx_add_light(&s, CG_LIGHT_DIRECTIONAL, 1.0f);
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 5, 0 }, (float[3]){ 0, 0, 0 }, up_z, 60.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view,
           "{ \"version\": 1, \"passes\": { \"shadow\": { \"type\": \"shadow_map\","
           "  \"params\": { \"resolution\": 64, \"filter\": \"none\" } } },"
           "  \"outputs\": [ \"shadow.depth\", \"shadow.matrix\" ] }", NULL);
    int w, h;
    float *depth = fx_read_depth(fg_graph_texture(r.graph, "shadow.depth"), &w, &h);
    assert_int_equal(w, 64);
    assert_int_equal(h, 64);

    double radius = 0.5 * sqrt(33.0), margin = 0.01 * radius;
    double eye_y = 0.5 + radius;
    double znear = (eye_y - 1.0) - margin, zfar = eye_y + margin;
    double floor_depth = (eye_y - znear) / (zfar - znear);
    double occluder_depth = (eye_y - 1.0 - znear) / (zfar - znear);
    /* Near the map's corners the floor is seen; at its centre the occluder. */
    assert_float_equal(depth[8 * w + 8], floor_depth, 1e-5);
    assert_float_equal(depth[(h - 9) * w + (w - 9)], floor_depth, 1e-5);
    assert_float_equal(depth[(h / 2) * w + w / 2], occluder_depth, 1e-5);
    free(depth);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

/* shadow_map's cache (the default): the first frame draws; a frame with nothing changed keeps the
 * depth map (the same bits, no draw); an instance moved, or the light turned, draws again, and the
 * map equals a fresh render's of the changed scene (drawn with cache = false). */
static void
expect_shadow_rebuilt(const fx_runner *r, const char *text)
{
    const char *said = fg_pass_rebuilt(fg_graph_find_pass(r->graph, "shadow"));
    if (strcmp(said, text))
        fail_msg("shadow_map reported \"%s\", expected \"%s\"", said, text);
}

static void
expect_depth_equal(const fx_runner *a, const fx_runner *b)
{
    int w, h, w2, h2;
    float *da = fx_read_depth(fg_graph_texture(a->graph, "shadow.depth"), &w, &h);
    float *db = fx_read_depth(fg_graph_texture(b->graph, "shadow.depth"), &w2, &h2);
    assert_int_equal(w, w2);
    assert_int_equal(h, h2);
    assert_memory_equal(da, db, sizeof(float) * (size_t)w * (size_t)h);
    free(da);
    free(db);
}

static void
test_shadow_map_cache(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    floor_and_occluder(&s);
    cg_light *sun = fx_add_light(&s, CG_LIGHT_DIRECTIONAL, 1.0f);
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 5, 0 }, (float[3]){ 0, 0, 0 }, up_z, 60.0f, SIZE, SIZE, &view);
    static const char *cached = "{ \"version\": 1, \"passes\": { \"shadow\": { \"type\": \"shadow_map\","
                                "  \"params\": { \"resolution\": 64 } } },"
                                "  \"outputs\": [ \"shadow.depth\", \"shadow.matrix\" ] }";
    static const char *drawn = "{ \"version\": 1, \"passes\": { \"shadow\": { \"type\": \"shadow_map\","
                               "  \"params\": { \"resolution\": 64, \"cache\": false } } },"
                               "  \"outputs\": [ \"shadow.depth\", \"shadow.matrix\" ] }";
    fx_runner r, fresh;
    cg_error err = { 0 };
    fx_run(&r, &s, &view, cached, NULL);
    expect_shadow_rebuilt(&r, "depth drawn (first frame; 1 draw since prepare)");
    assert_true(fg_graph_find_resource(r.graph, "shadow.depth")->desc.persistent);
    fx_run(&fresh, &s, &view, drawn, NULL);
    expect_shadow_rebuilt(&fresh, "depth drawn (cache=false)");
    r.frame.index = 1;
    assert_cg_ok(fg_graph_execute(r.graph, &r.frame, FG_TIMING_SYNC, &err), &err);
    expect_shadow_rebuilt(&r, "depth kept (1 draw since prepare)");
    expect_depth_equal(&r, &fresh);
    fx_runner_free(&fresh);

    /* The occluder 0.25 m along x: an instance changed (its world, compared by value). */
    s.instances[1].world[12] += 0.25f;
    r.frame.index = 2;
    assert_cg_ok(fg_graph_execute(r.graph, &r.frame, FG_TIMING_SYNC, &err), &err);
    expect_shadow_rebuilt(&r, "depth drawn (an instance changed; 2 draws since prepare)");
    fx_run(&fresh, &s, &view, drawn, NULL);
    expect_depth_equal(&r, &fresh);
    fx_runner_free(&fresh);

    /* The sun tilted: its fit changes. */
    sun->direction[0] = 0.28734789f;     /* (0.3, -1, 0), normalised */
    sun->direction[1] = -0.95782629f;
    r.frame.index = 3;
    assert_cg_ok(fg_graph_execute(r.graph, &r.frame, FG_TIMING_SYNC, &err), &err);
    expect_shadow_rebuilt(&r, "depth drawn (light, fit or parameters changed; 3 draws since prepare)");
    fx_run(&fresh, &s, &view, drawn, NULL);
    expect_depth_equal(&r, &fresh);
    fx_runner_free(&fresh);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

/* A quad facing +z seen head-on: normal (0,0,1), albedo = factor x sRGB-decoded texture,
 * emissive = factor x strength, position on the quad; background pixels are empty. */
static void
test_gbuffer_normal_albedo(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    fx_scene_init(&s);
    int m = fx_add_material(&s, 0.25f, 0.5f, 0.75f);
    static uint8_t grey[2 * 2 * 4];
    memset(grey, 128, sizeof grey);
    s.textures[0] = (cg_texture){ .name = "grey", .width = 2, .height = 2, .rgba = grey, .srgb = true };
    s.scene.texture_count = 1;
    s.materials[m].base_color_texture = 0;
    s.materials[m].emissive[0] = 1.0f;
    s.materials[m].emissive[1] = 2.0f;
    s.materials[m].emissive[2] = 3.0f;
    s.materials[m].emissive_strength = 2.0f;
    fx_add_quad(&s, 2, 0.0f, -1.0f, 1.0f, -1.0f, 1.0f, m);
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 0, 3 }, (float[3]){ 0, 0, 0 }, up_y, 90.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view,
           "{ \"version\": 1, \"passes\": { \"gbuf\": { \"type\": \"gbuffer\" } },"
           "  \"outputs\": [ \"gbuf.position\", \"gbuf.normal\", \"gbuf.albedo\", \"gbuf.emissive\", \"gbuf.depth\" ] }",
           NULL);
    float *position = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.position"), 0, NULL, NULL, NULL);
    float *normal = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.normal"), 0, NULL, NULL, NULL);
    float *albedo = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.albedo"), 0, NULL, NULL, NULL);
    float *emissive = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.emissive"), 0, NULL, NULL, NULL);

    double grey_linear = cg_srgb_decode(128.0f / 255.0f);
    const float *n = texel(normal, SIZE, SIZE / 2, SIZE / 2);
    assert_float_equal(n[0], 0.0, 1e-3);
    assert_float_equal(n[1], 0.0, 1e-3);
    assert_float_equal(n[2], 1.0, 1e-3);
    const float *a = texel(albedo, SIZE, SIZE / 2, SIZE / 2);
    assert_float_equal(a[0], 0.25 * grey_linear, 2e-3);
    assert_float_equal(a[1], 0.50 * grey_linear, 2e-3);
    assert_float_equal(a[2], 0.75 * grey_linear, 2e-3);
    const float *e = texel(emissive, SIZE, SIZE / 2, SIZE / 2);
    assert_float_equal(e[0], 2.0, 1e-3);
    assert_float_equal(e[1], 4.0, 1e-3);
    assert_float_equal(e[2], 6.0, 1e-3);
    const float *p = texel(position, SIZE, SIZE / 2, SIZE / 2);
    assert_float_equal(p[2], 0.0, 1e-5);
    assert_float_equal(p[3], 1.0, 0.0);
    /* The quad covers the middle third of a 90-degree view from 3 m: corners are background. */
    assert_float_equal(texel(position, SIZE, 2, 2)[3], 0.0, 0.0);
    assert_float_equal(texel(albedo, SIZE, 2, 2)[0], 0.0, 0.0);
    free(position);
    free(normal);
    free(albedo);
    free(emissive);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

static const char *const direct_graph =
    "{ \"version\": 1, \"passes\": {"
    "  \"shadow\": { \"type\": \"shadow_map\", \"params\": { \"resolution\": 256, \"filter\": \"FILTER\" } },"
    "  \"gbuf\": { \"type\": \"gbuffer\" },"
    "  \"direct\": { \"type\": \"direct_light\", \"inputs\": { \"position\": \"gbuf\", \"normal\": \"gbuf\","
    "               \"albedo\": \"gbuf\", \"shadow\": \"shadow.depth\", \"shadow_matrix\": \"shadow.matrix\" } } },"
    "  \"outputs\": [ \"direct.radiance\", \"gbuf.position\" ] }";

static char *
graph_with_filter(const char *filter)
{
    static char json[2048];
    const char *at = strstr(direct_graph, "FILTER");
    snprintf(json, sizeof json, "%.*s%s%s", (int)(at - direct_graph), direct_graph, filter, at + 6);
    return json;
}

/* A white floor facing a directional light of irradiance E: radiance E/pi within 1%, and 0
 * in the occluder's shadow (seen from a camera off to the side, past the occluder). */
static void
run_directional(void **state, const char *filter)
{
    cg_context *ctx = cg_test_gl_context(state);
    const float E = 3.0f;
    fx_scene s;
    floor_and_occluder(&s);
    fx_add_light(&s, CG_LIGHT_DIRECTIONAL, E);
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 3, 4, 0 }, (float[3]){ 0, 0, 0 }, up_y, 60.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view, graph_with_filter(filter), NULL);
    float *radiance = cg_test_read_texture(fg_graph_texture(r.graph, "direct.radiance"), 0, NULL, NULL, NULL);
    float *position = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.position"), 0, NULL, NULL, NULL);

    int x, y;
    fx_pixel_of(&view, (float[3]){ 0.0f, 0.0f, 0.0f }, &x, &y);
    const float *p = texel(position, SIZE, x, y);
    assert_float_equal(p[1], 0.0, 1e-4);  /* the floor, not the occluder */
    for (int c = 0; c < 3; c++)
        assert_float_equal(texel(radiance, SIZE, x, y)[c], 0.0, 1e-6);

    const float lit_points[3][3] = { { -1.5f, 0.0f, 1.0f }, { 1.5f, 0.0f, -1.5f }, { -0.8f, 0.0f, -0.8f } };
    for (int i = 0; i < 3; i++) {
        fx_pixel_of(&view, lit_points[i], &x, &y);
        assert_float_equal(texel(position, SIZE, x, y)[1], 0.0, 1e-4);
        for (int c = 0; c < 3; c++)
            assert_float_equal(texel(radiance, SIZE, x, y)[c], E / PI, 0.01 * E / PI);
    }
    /* The occluder's top is lit too. */
    fx_pixel_of(&view, (float[3]){ 0.0f, 1.0f, 0.0f }, &x, &y);
    assert_float_equal(texel(position, SIZE, x, y)[1], 1.0, 1e-4);
    assert_float_equal(texel(radiance, SIZE, x, y)[0], E / PI, 0.01 * E / PI);
    free(radiance);
    free(position);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

static void
test_direct_directional_pcf3(void **state)
{
    run_directional(state, "pcf3");
}

static void
test_direct_directional_unfiltered(void **state)
{
    run_directional(state, "none");
}

static void
test_direct_directional_pcf5(void **state)
{
    run_directional(state, "pcf5");
}

/* A spot whose cone one perspective map cannot cover (outer angle 1.5 rad): shadow_map has
 * nothing to do, and direct_light still lights the floor, unshadowed. */
static void
test_wide_spot_is_unshadowed(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    floor_and_occluder(&s);
    cg_light *l = fx_add_light(&s, CG_LIGHT_SPOT, 4.0f);
    l->position[1] = 2.0f;
    l->inner_cone_angle = 1.2f;
    l->outer_cone_angle = 1.5f;
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 3, 4, 0 }, (float[3]){ 0, 0, 0 }, up_y, 60.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view, graph_with_filter("pcf3"), NULL);
    assert_true(fg_pass_is_culled(fg_graph_find_pass(r.graph, "shadow")));
    float *radiance = cg_test_read_texture(fg_graph_texture(r.graph, "direct.radiance"), 0, NULL, NULL, NULL);
    int x, y;
    /* Under the occluder: lit, since nothing shadows this light (I cos / (pi d^2), d = 2). */
    fx_pixel_of(&view, (float[3]){ 0.0f, 0.0f, 0.0f }, &x, &y);
    assert_float_equal(texel(radiance, SIZE, x, y)[0], 4.0 / (PI * 4.0), 0.01 * 4.0 / (PI * 4.0));
    free(radiance);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

/* A point light of intensity I at height h over the floor: radiance I cos / (pi d^2) at every
 * covered pixel (cos = h/d), checked against the G-buffer's own positions; with a range, times
 * the window clamp(1 - (d/range)^4, 0, 1)^2. The scene has no directional or spot light, so
 * shadow_map has nothing to do and direct_light runs unshadowed. */
static void
run_point_light(void **state, float range)
{
    cg_context *ctx = cg_test_gl_context(state);
    const float I = 5.0f;
    const float light_pos[3] = { 0.5f, 2.0f, -0.3f };
    fx_scene s;
    fx_scene_init(&s);
    fx_add_quad(&s, 1, 0.0f, -2.0f, 2.0f, -2.0f, 2.0f, 0);
    cg_light *l = fx_add_light(&s, CG_LIGHT_POINT, I);
    memcpy(l->position, light_pos, sizeof light_pos);
    l->range = range;
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 6, 0.01f }, (float[3]){ 0, 0, 0 }, up_z, 60.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view, graph_with_filter("pcf3"), NULL);
    assert_true(fg_pass_is_culled(fg_graph_find_pass(r.graph, "shadow")));
    float *radiance = cg_test_read_texture(fg_graph_texture(r.graph, "direct.radiance"), 0, NULL, NULL, NULL);
    float *position = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.position"), 0, NULL, NULL, NULL);
    int covered = 0, beyond = 0;
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++) {
            const float *p = texel(position, SIZE, x, y);
            if (p[3] == 0.0f)
                continue;
            covered++;
            double dx = light_pos[0] - p[0], dy = light_pos[1] - p[1], dz = light_pos[2] - p[2];
            double d2 = dx * dx + dy * dy + dz * dz;
            double expected = I * (dy / sqrt(d2)) / (PI * d2);
            if (range > 0.0f) {
                double q = d2 / ((double)range * range);
                double window = 1.0 - q * q;
                window = window < 0.0 ? 0.0 : window;
                expected *= window * window;
                beyond += window == 0.0;
            }
            assert_float_equal(texel(radiance, SIZE, x, y)[1], expected, 0.01 * expected + 1e-6);
        }
    assert_true(covered > SIZE * SIZE / 4);
    if (range > 0.0f)
        assert_true(beyond > 10);
    free(radiance);
    free(position);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

static void
test_direct_point_light(void **state)
{
    run_point_light(state, 0.0f);
}

static void
test_direct_point_light_range(void **state)
{
    run_point_light(state, 3.0f);
}

/* A spot light straight down at height 2: at every covered pixel, I cos / (pi d^2) times the
 * KHR_lights_punctual falloff ((cd - cos outer) / (cos inner - cos outer))^2 clamped to
 * [0, 1], checked against the G-buffer's positions: inside the inner cone, on the ramp and
 * outside the outer cone. The floor is lit (no occluder) although the spot's map is live. */
static void
test_direct_spot_light(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const float I = 4.0f, inner = 0.3f, outer = 0.4f;
    fx_scene s;
    fx_scene_init(&s);
    fx_add_quad(&s, 1, 0.0f, -2.0f, 2.0f, -2.0f, 2.0f, 0);
    cg_light *l = fx_add_light(&s, CG_LIGHT_SPOT, I);
    l->position[1] = 2.0f;
    l->inner_cone_angle = inner;
    l->outer_cone_angle = outer;
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 6, 0.01f }, (float[3]){ 0, 0, 0 }, up_z, 60.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view, graph_with_filter("pcf3"), NULL);
    assert_false(fg_pass_is_culled(fg_graph_find_pass(r.graph, "shadow")));
    float *radiance = cg_test_read_texture(fg_graph_texture(r.graph, "direct.radiance"), 0, NULL, NULL, NULL);
    float *position = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.position"), 0, NULL, NULL, NULL);
    int inside = 0, ramp = 0, outside = 0;
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++) {
            const float *p = texel(position, SIZE, x, y);
            if (p[3] == 0.0f)
                continue;
            double dx = -p[0], dy = 2.0 - p[1], dz = -p[2];
            double d2 = dx * dx + dy * dy + dz * dz, d = sqrt(d2);
            double cd = dy / d; /* cosine to the spot axis, and to the floor normal */
            double t = (cd - cos(outer)) / (cos(inner) - cos(outer));
            t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
            double expected = I * t * t * cd / (PI * d2);
            inside += t == 1.0;
            ramp += t > 0.0 && t < 1.0;
            outside += t == 0.0;
            assert_float_equal(texel(radiance, SIZE, x, y)[0], expected, 0.01 * expected + 1e-6);
        }
    assert_true(inside > 10 && ramp > 10 && outside > 10);
    free(radiance);
    free(position);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

/* A test-only pass that fills its output `color` (RGBA16F, output size) with (r, g, b, 1). */
static const fg_param_desc constant_params[] = {
    { .name = "r", .type = FG_PARAM_FLOAT, .min = -100.0, .max = 100.0, .doc = "red" },
    { .name = "g", .type = FG_PARAM_FLOAT, .min = -100.0, .max = 100.0, .doc = "green" },
    { .name = "b", .type = FG_PARAM_FLOAT, .min = -100.0, .max = 100.0, .doc = "blue" },
};

static bool
constant_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)err;
    const fg_frame *frame = fg_pass_frame(pass);
    fg_resource_desc desc = { .kind = FG_TEXTURE_2D, .format = GL_RGBA16F, .width = frame->width,
                              .height = frame->height, .depth = 1, .levels = 1 };
    fg_declare_output(decl, "color", &desc, FG_ACCESS_TRANSFER);
    return true;
}

static bool
constant_execute(fg_pass *pass, void *state, cg_error *err)
{
    (void)state;
    (void)err;
    const float value[4] = { fg_param_float(pass, "r"), fg_param_float(pass, "g"), fg_param_float(pass, "b"), 1.0f };
    glClearTexImage(fg_texture(pass, "color"), 0, GL_RGBA, GL_FLOAT, value);
    return true;
}

static const fg_pass_type constant_type = {
    .abi_version = FG_ABI_VERSION,
    .name = "test_constant",
    .doc = "Test pass: a constant colour.",
    .params = constant_params,
    .param_count = 3,
    .declare = constant_declare,
    .execute = constant_execute,
};

static float
srgb_encode(float x)
{
    x = fminf(fmaxf(x, 0.0f), 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
}

/* hdr = direct + albedo x indirect + emissive; ldr = encode(tonemap(hdr x 2^EV)). */
static void
test_composite_sums_inputs(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    fx_scene_init(&s);
    fx_add_quad(&s, 1, 0.0f, -1.0f, 1.0f, -1.0f, 1.0f, 0);
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 3, 0.01f }, (float[3]){ 0, 0, 0 }, up_z, 60.0f, 8, 8, &view);
    fx_runner r;
    fx_run(&r, &s, &view,
           "{ \"version\": 1, \"passes\": {"
           "  \"d\": { \"type\": \"test_constant\", \"params\": { \"r\": 0.1, \"g\": 0.2, \"b\": 0.3 } },"
           "  \"i\": { \"type\": \"test_constant\", \"params\": { \"r\": 1.0, \"g\": 2.0, \"b\": 4.0 } },"
           "  \"a\": { \"type\": \"test_constant\", \"params\": { \"r\": 0.5, \"g\": 0.25, \"b\": 0.125 } },"
           "  \"e\": { \"type\": \"test_constant\", \"params\": { \"r\": 0.0, \"g\": 0.05, \"b\": 0.5 } },"
           "  \"final\": { \"type\": \"composite\", \"params\": { \"exposure\": 1, \"tonemap\": \"reinhard\" },"
           "    \"inputs\": { \"direct\": \"d.color\", \"indirect\": \"i.color\", \"albedo\": \"a.color\","
           "                  \"emissive\": \"e.color\" } },"
           "  \"plain\": { \"type\": \"composite\", \"params\": { \"tonemap\": \"none\" },"
           "    \"inputs\": { \"direct\": \"d.color\" } } },"
           "  \"outputs\": [ \"final.hdr\", \"final.ldr\", \"plain.hdr\", \"plain.ldr\" ] }",
           &constant_type);
    float *hdr = cg_test_read_texture(fg_graph_texture(r.graph, "final.hdr"), 0, NULL, NULL, NULL);
    float *ldr = cg_test_read_texture(fg_graph_texture(r.graph, "final.ldr"), 0, NULL, NULL, NULL);
    float *plain_hdr = cg_test_read_texture(fg_graph_texture(r.graph, "plain.hdr"), 0, NULL, NULL, NULL);
    float *plain_ldr = cg_test_read_texture(fg_graph_texture(r.graph, "plain.ldr"), 0, NULL, NULL, NULL);
    const double expected[3] = { 0.1 + 0.5 * 1.0 + 0.0, 0.2 + 0.25 * 2.0 + 0.05, 0.3 + 0.125 * 4.0 + 0.5 };
    const double direct[3] = { 0.1, 0.2, 0.3 };
    double lum = 2.0 * (0.2126 * expected[0] + 0.7152 * expected[1] + 0.0722 * expected[2]);
    for (int i = 0; i < 8 * 8; i++)
        for (int c = 0; c < 3; c++) {
            /* Inputs are half floats: 1e-3 relative. */
            assert_float_equal(hdr[4 * i + c], expected[c], 1e-3 * expected[c]);
            assert_float_equal(ldr[4 * i + c], srgb_encode((float)(2.0 * expected[c] / (1.0 + lum))), 1.0 / 255.0);
            assert_float_equal(plain_hdr[4 * i + c], direct[c], 1e-3);
            assert_float_equal(plain_ldr[4 * i + c], srgb_encode((float)direct[c]), 1.0 / 255.0);
        }
    free(hdr);
    free(ldr);
    free(plain_hdr);
    free(plain_ldr);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

static const char *const gbuffer_material_graph =
    "{ \"version\": 1, \"passes\": { \"gbuf\": { \"type\": \"gbuffer\" } },"
    "  \"outputs\": [ \"gbuf.position\", \"gbuf.normal\", \"gbuf.albedo\", \"gbuf.specular\", \"gbuf.transmission\","
    "               \"gbuf.material\", \"gbuf.attenuation\" ] }";

/* The G-buffer of a material with known factors holds the contract's values (gbuffer.c): rho =
 * (1-m)(1-T) base, occlusion 1 + strength (occ - 1), F0 = mix(min(((ior-1)/(ior+1))^2 specColor, 1)
 * specular, base, m), F90 = mix(specular, 1, m), tau = (1-m) T base and the ior, roughness,
 * metallic, thickness x the instance's scale (world metres), sigma = -ln(colour)/distance; beside it
 * a Lambertian material (cg_material_default's: specular 0) gives its albedo, F0 = F90 = 0 and
 * transmission (0, 0, 0, 1.5), what direct_light and composite read as before. */
static void
test_gbuffer_material_outputs(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    fx_scene_init(&s);
    int lambert = fx_add_material(&s, 0.3f, 0.5f, 0.7f);
    int m = fx_add_material(&s, 0.8f, 0.6f, 0.4f);
    cg_material *mat = &s.materials[m];
    mat->metallic = 0.25f;
    mat->roughness = 0.4f;
    mat->transmission = 0.5f;
    mat->ior = 1.4f;
    mat->specular = 0.8f;
    mat->specular_color[1] = 0.5f;
    mat->thickness = 0.1f;
    mat->attenuation_distance = 0.5f;
    mat->attenuation_color[0] = 0.25f;
    mat->occlusion_texture = 0;
    mat->occlusion_strength = 0.5f;
    static uint8_t occlusion[4] = { 128, 0, 0, 255 };
    s.textures[0] = (cg_texture){ .name = "occlusion", .width = 1, .height = 1, .rgba = occlusion };
    s.scene.texture_count = 1;
    fx_add_quad(&s, 2, 0.0f, -0.75f, -0.05f, -0.5f, 0.5f, lambert);
    fx_add_quad(&s, 2, 0.0f, 0.025f, 0.375f, -0.25f, 0.25f, m);
    /* The second quad twice as large in the world: its thickness too. */
    for (int k = 0; k < 3; k++)
        s.instances[1].world[5 * k] = 2.0f;
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 0, 3 }, (float[3]){ 0, 0, 0 }, up_y, 60.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view, gbuffer_material_graph, NULL);
    float *out[6];
    static const char *const names[6] = { "gbuf.position", "gbuf.albedo", "gbuf.specular", "gbuf.transmission",
                                          "gbuf.material", "gbuf.attenuation" };
    for (int i = 0; i < 6; i++)
        out[i] = cg_test_read_texture(fg_graph_texture(r.graph, names[i]), 0, NULL, NULL, NULL);

    int x, y;
    fx_pixel_of(&view, (float[3]){ 0.4f, 0.0f, 0.0f }, &x, &y);
    assert_float_equal(texel(out[0], SIZE, x, y)[3], 1.0, 0.0);
    const double base[3] = { 0.8, 0.6, 0.4 }, spec_color[3] = { 1.0, 0.5, 1.0 };
    double metal = 0.25, trans = 0.5, specular = 0.8, r_ior = 0.4 / 2.4;
    for (int c = 0; c < 3; c++) {
        double rho = (1 - metal) * (1 - trans) * base[c];
        double f0_d = fmin(r_ior * r_ior * spec_color[c], 1.0) * specular;
        double f0 = f0_d + (base[c] - f0_d) * metal;
        double tau = (1 - metal) * trans * base[c];
        assert_float_equal(texel(out[1], SIZE, x, y)[c], rho, 1e-3 * rho);
        assert_float_equal(texel(out[2], SIZE, x, y)[c], f0, 1e-3 * f0);
        assert_float_equal(texel(out[3], SIZE, x, y)[c], tau, 1e-3 * tau);
    }
    assert_float_equal(texel(out[1], SIZE, x, y)[3], 1.0 + 0.5 * (128.0 / 255.0 - 1.0), 1e-3);
    assert_float_equal(texel(out[2], SIZE, x, y)[3], specular + (1 - specular) * metal, 1e-3);
    assert_float_equal(texel(out[3], SIZE, x, y)[3], 1.4, 1e-3);
    assert_float_equal(texel(out[4], SIZE, x, y)[0], 0.4, 1e-3);
    assert_float_equal(texel(out[4], SIZE, x, y)[1], 0.25, 1e-3);
    assert_float_equal(texel(out[4], SIZE, x, y)[2], 0.2, 1e-3);   /* 0.1 mesh units x 2 */
    assert_float_equal(texel(out[4], SIZE, x, y)[3], 1.0, 0.0);
    assert_float_equal(texel(out[5], SIZE, x, y)[0], -log(0.25) / 0.5, 1e-3 * -log(0.25) / 0.5);
    assert_float_equal(texel(out[5], SIZE, x, y)[1], 0.0, 0.0);
    assert_float_equal(texel(out[5], SIZE, x, y)[3], 1.0, 0.0);

    fx_pixel_of(&view, (float[3]){ -0.4f, 0.0f, 0.0f }, &x, &y);
    const float lambert_albedo[3] = { 0.3f, 0.5f, 0.7f };
    for (int c = 0; c < 3; c++) {
        /* Bit for bit what the Lambertian G-buffer held: the half float of the base colour. */
        assert_float_equal(texel(out[1], SIZE, x, y)[c], lambert_albedo[c], 5e-4);
        assert_float_equal(texel(out[2], SIZE, x, y)[c], 0.0, 0.0);
        assert_float_equal(texel(out[3], SIZE, x, y)[c], 0.0, 0.0);
    }
    assert_float_equal(texel(out[1], SIZE, x, y)[3], 1.0, 0.0);
    assert_float_equal(texel(out[2], SIZE, x, y)[3], 0.0, 0.0);
    assert_float_equal(texel(out[3], SIZE, x, y)[3], 1.5, 0.0);
    assert_float_equal(texel(out[4], SIZE, x, y)[0], 1.0, 0.0);
    for (int i = 0; i < 6; i++)
        free(out[i]);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

/* A normal map bends the normal in the tangent frame (glTF 3.9.3: T, B = w N x T, N; xy x scale);
 * alphaMode MASK leaves holes below the cutoff (the quad behind shows through); a single-sided
 * material's back face is not seen, a double-sided one's is, its normal turned to the viewer. */
static void
test_gbuffer_normal_map_mask_and_sides(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    fx_scene_init(&s);
    int bumpy = fx_add_material(&s, 1.0f, 1.0f, 1.0f);
    s.materials[bumpy].normal_texture = 0;
    s.materials[bumpy].normal_scale = 0.5f;
    int masked = fx_add_material(&s, 1.0f, 1.0f, 1.0f);
    s.materials[masked].alpha_mode = CG_ALPHA_MASK;
    s.materials[masked].alpha_cutoff = 0.5f;
    s.materials[masked].base_color_texture = 1;
    int one_sided = fx_add_material(&s, 1.0f, 1.0f, 1.0f);
    s.materials[one_sided].double_sided = false;
    static uint8_t normal_texel[4] = { 200, 90, 220, 255 };
    static uint8_t alpha_texels[16] = { 255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 255 };
    s.textures[0] = (cg_texture){ .name = "normal", .width = 1, .height = 1, .rgba = normal_texel };
    s.textures[1] = (cg_texture){ .name = "alpha", .width = 4, .height = 1, .rgba = alpha_texels };
    s.scene.texture_count = 2;
    fx_add_quad(&s, 2, 0.0f, -1.0f, -0.1f, -1.0f, 1.0f, bumpy);        /* left, facing +z */
    static float tangents[16] = { 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1 };
    s.meshes[0].tangents = tangents;
    fx_add_quad(&s, 2, 0.0f, 0.1f, 1.0f, -1.0f, 1.0f, masked);         /* right, u along x */
    fx_add_quad(&s, 2, -1.0f, -2.0f, 2.0f, -2.0f, 2.0f, 0);            /* behind both */
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 0, 3 }, (float[3]){ 0, 0, 0 }, up_y, 60.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view, gbuffer_material_graph, NULL);
    float *position = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.position"), 0, NULL, NULL, NULL);
    float *normal = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.normal"), 0, NULL, NULL, NULL);

    int x, y;
    fx_pixel_of(&view, (float[3]){ -0.55f, 0.0f, 0.0f }, &x, &y);
    double m[3];
    for (int c = 0; c < 3; c++)
        m[c] = normal_texel[c] / 255.0 * 2.0 - 1.0;
    m[0] *= 0.5, m[1] *= 0.5;
    double len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    /* T = +x, N = +z, B = N x T = +y. */
    for (int c = 0; c < 3; c++)
        assert_float_equal(texel(normal, SIZE, x, y)[c], m[c] / len, 2e-3);
    /* The masked quad: x = 0.1 + 0.9 u; texels 0 and 1 have alpha 0, 2 and 3 alpha 1, so between
     * the centres of 0 and 1 (u 0.125..0.375) the filtered alpha is 0: a hole, the quad behind shows;
     * between those of 2 and 3 it is 1. */
    fx_pixel_of(&view, (float[3]){ 0.1f + 0.9f * 0.25f, 0.0f, 0.0f }, &x, &y);
    assert_float_equal(texel(position, SIZE, x, y)[2], -1.0, 1e-4);
    fx_pixel_of(&view, (float[3]){ 0.1f + 0.9f * 0.75f, 0.0f, 0.0f }, &x, &y);
    assert_float_equal(texel(position, SIZE, x, y)[2], 0.0, 1e-4);
    free(position);
    free(normal);
    fx_runner_free(&r);

    /* From behind (-z): the single-sided quad is not there, the double-sided one is. */
    s.meshes[1].material = one_sided;
    fx_view_look_at((float[3]){ 0, 0, -3 }, (float[3]){ 0, 0, 0 }, up_y, 60.0f, SIZE, SIZE, &view);
    fx_scene_finish(&s);
    s.instances[2].world[14] = 2.0f;   /* the back quad to z = +1, behind both from here */
    fx_run(&r, &s, &view, gbuffer_material_graph, NULL);
    position = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.position"), 0, NULL, NULL, NULL);
    normal = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.normal"), 0, NULL, NULL, NULL);
    fx_pixel_of(&view, (float[3]){ 0.5f, 0.0f, 0.0f }, &x, &y);
    assert_float_equal(texel(position, SIZE, x, y)[2], 1.0, 1e-4);     /* through the culled quad */
    fx_pixel_of(&view, (float[3]){ -0.5f, 0.0f, 0.0f }, &x, &y);
    assert_float_equal(texel(position, SIZE, x, y)[2], 0.0, 1e-4);
    assert_true(texel(normal, SIZE, x, y)[2] < 0.0f);                   /* turned to the viewer */
    free(position);
    free(normal);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

/* alphaMode MASK in the shadow map: the occluder's cut-out half casts no shadow. */
static void
test_shadow_map_mask(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const float E = 3.0f;
    fx_scene s;
    floor_and_occluder(&s);
    int masked = fx_add_material(&s, 1.0f, 1.0f, 1.0f);
    s.materials[masked].alpha_mode = CG_ALPHA_MASK;
    s.materials[masked].base_color_texture = 0;
    /* u runs along z on a y quad (fx_add_quad), z = -0.25 + 0.5 u: texels 0 and 1 alpha 0, 2 and 3
     * alpha 1 (as in test_gbuffer_normal_map_mask_and_sides). */
    static uint8_t alpha_texels[16] = { 255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 255 };
    s.textures[0] = (cg_texture){ .name = "alpha", .width = 4, .height = 1, .rgba = alpha_texels };
    s.scene.texture_count = 1;
    s.meshes[1].material = masked;
    fx_add_light(&s, CG_LIGHT_DIRECTIONAL, E);
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 3, 4, 0 }, (float[3]){ 0, 0, 0 }, up_y, 60.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view, graph_with_filter("none"), NULL);
    float *radiance = cg_test_read_texture(fg_graph_texture(r.graph, "direct.radiance"), 0, NULL, NULL, NULL);
    int x, y;
    /* Under u = 0.25 (alpha 0): lit; under u = 0.75 (alpha 1): shadowed. */
    fx_pixel_of(&view, (float[3]){ 0.0f, 0.0f, -0.125f }, &x, &y);
    assert_float_equal(texel(radiance, SIZE, x, y)[0], E / PI, 0.01 * E / PI);
    fx_pixel_of(&view, (float[3]){ 0.0f, 0.0f, 0.125f }, &x, &y);
    assert_float_equal(texel(radiance, SIZE, x, y)[0], 0.0, 1e-6);
    free(radiance);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

static const char *const glossy_graph =
    "{ \"version\": 1, \"passes\": {"
    "  \"gbuf\": { \"type\": \"gbuffer\" },"
    "  \"direct\": { \"type\": \"direct_light\", \"inputs\": { \"position\": \"gbuf\", \"normal\": \"gbuf\","
    "               \"albedo\": \"gbuf\", \"specular\": \"gbuf\", \"material\": \"gbuf\", \"transmission\": \"gbuf\" } } },"
    "  \"outputs\": [ \"direct.radiance\", \"gbuf.position\", \"gbuf.normal\" ] }";

/* GGX highlights: a floor of a dielectric (left), a gold metal (middle) and a rough thin glass sheet
 * (right) under a directional light, seen near the mirror direction; at pixels across the highlight
 * direct_light's radiance equals the C BSDF's f |n.l| E (cg_bsdf_eval, reflection lobes) at the
 * pixel's G-buffer position and normal, v towards the camera. Light from below is not transmitted. */
static void
test_direct_ggx(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const float E = 2.0f;
    fx_scene s;
    fx_scene_init(&s);
    int dielectric = fx_add_material(&s, 0.5f, 0.3f, 0.2f);
    s.materials[dielectric].roughness = 0.3f;
    s.materials[dielectric].specular = 1.0f;
    int gold = fx_add_material(&s, 1.0f, 0.78f, 0.34f);
    s.materials[gold].metallic = 1.0f;
    s.materials[gold].roughness = 0.45f;
    s.materials[gold].specular = 1.0f;
    int glass = fx_add_material(&s, 1.0f, 1.0f, 1.0f);
    s.materials[glass].transmission = 1.0f;
    s.materials[glass].roughness = 0.5f;
    s.materials[glass].specular = 1.0f;
    /* Strips along z (a y quad's first span), side by side in x (its second). */
    fx_add_quad(&s, 1, 0.0f, -2.0f, 2.0f, -3.0f, -1.0f, dielectric);
    fx_add_quad(&s, 1, 0.0f, -2.0f, 2.0f, -1.0f, 1.0f, gold);
    fx_add_quad(&s, 1, 0.0f, -2.0f, 2.0f, 1.0f, 3.0f, glass);
    cg_light *sun = fx_add_light(&s, CG_LIGHT_DIRECTIONAL, E);
    sun->direction[0] = 0.0f;
    sun->direction[1] = -0.8f;
    sun->direction[2] = 0.6f;     /* travels down and towards +z: the mirror ray goes on to +z */
    fx_scene_finish(&s);
    const float eye[3] = { 0.0f, 2.5f, 2.0f };
    cg_view view;
    fx_view_look_at(eye, (float[3]){ 0, 0, 0 }, up_y, 90.0f, SIZE, SIZE, &view);
    fx_runner r;
    fx_run(&r, &s, &view, glossy_graph, NULL);
    float *radiance = cg_test_read_texture(fg_graph_texture(r.graph, "direct.radiance"), 0, NULL, NULL, NULL);
    float *position = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.position"), 0, NULL, NULL, NULL);
    float *normal = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.normal"), 0, NULL, NULL, NULL);
    float len = sqrtf(0.64f + 0.36f);
    const float l[3] = { 0.0f, 0.8f / len, -0.6f / len };
    /* The mirror ray of the eye meets the floor at z = 2 - 2.5 x 0.6/0.8 = 0.125. */
    const float points[][3] = { { 0.0f, 0.0f, 0.125f }, { 0.4f, 0.0f, -0.3f }, { -0.3f, 0.0f, 0.5f },
                                { -1.5f, 0.0f, 0.1f }, { -2.0f, 0.0f, -0.5f }, { 1.5f, 0.0f, 0.1f } };
    double highlight = 0.0;
    for (size_t i = 0; i < sizeof points / sizeof points[0]; i++) {
        int x, y;
        fx_pixel_of(&view, points[i], &x, &y);
        const float *pos = texel(position, SIZE, x, y);
        assert_float_equal(pos[3], 1.0, 0.0);
        int mat = pos[0] < -1.0f ? dielectric : pos[0] < 1.0f ? gold : glass;
        const cg_material *m = &s.materials[mat];
        cg_bsdf b;
        cg_bsdf_from_material(m, m->base_color, m->metallic, m->roughness, m->transmission, &b);
        float v[3] = { eye[0] - pos[0], eye[1] - pos[1], eye[2] - pos[2] };
        float vl = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (int k = 0; k < 3; k++)
            v[k] /= vl;
        float n[3] = { texel(normal, SIZE, x, y)[0], texel(normal, SIZE, x, y)[1], texel(normal, SIZE, x, y)[2] };
        float f[3];
        cg_bsdf_eval(&b, n, v, l, b.ior, CG_BSDF_DIFFUSE | CG_BSDF_GLOSSY, f);
        for (int c = 0; c < 3; c++) {
            double expected = (double)f[c] * E;
            assert_float_equal(texel(radiance, SIZE, x, y)[c], expected, 0.01 * expected + 1e-6);
        }
        highlight = fmax(highlight, texel(radiance, SIZE, x, y)[1] / (E / PI));
    }
    /* The grid reaches the highlights: well above what a white Lambertian floor would return. */
    print_message("# brightest sample: %.2f x E/pi\n", highlight);
    assert_true(highlight > 1.5);
    free(radiance);
    free(position);
    free(normal);
    fx_runner_free(&r);

    /* The sun from below: every floor is dark, the thin sheet too (no transmission of light from
     * behind: direct_light.c), though its BSDF has a transmission lobe there. */
    sun->direction[1] = 0.8f;
    fx_run(&r, &s, &view, glossy_graph, NULL);
    radiance = cg_test_read_texture(fg_graph_texture(r.graph, "direct.radiance"), 0, NULL, NULL, NULL);
    position = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.position"), 0, NULL, NULL, NULL);
    normal = cg_test_read_texture(fg_graph_texture(r.graph, "gbuf.normal"), 0, NULL, NULL, NULL);
    const float below[3] = { 0.0f, -0.8f / len, -0.6f / len };
    for (int i = 0; i < 3; i++) {
        int x, y;
        fx_pixel_of(&view, (float[3]){ -1.5f + 1.5f * (float)i, 0.0f, 0.1f }, &x, &y);
        assert_float_equal(texel(radiance, SIZE, x, y)[0], 0.0, 0.0);
    }
    int x, y;
    fx_pixel_of(&view, (float[3]){ 1.5f, 0.0f, 0.1f }, &x, &y);
    const float *pos = texel(position, SIZE, x, y);
    const cg_material *m = &s.materials[glass];
    cg_bsdf b;
    cg_bsdf_from_material(m, m->base_color, m->metallic, m->roughness, m->transmission, &b);
    float v[3] = { eye[0] - pos[0], eye[1] - pos[1], eye[2] - pos[2] };
    float vl = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= vl;
    float n[3] = { texel(normal, SIZE, x, y)[0], texel(normal, SIZE, x, y)[1], texel(normal, SIZE, x, y)[2] };
    float f[3];
    cg_bsdf_eval(&b, n, v, below, b.ior, CG_BSDF_TRANSMISSION, f);
    assert_true(f[0] > 0.0f);
    free(radiance);
    free(position);
    free(normal);
    fx_runner_free(&r);
    assert_no_gl_errors(ctx);
}

/* The parameter tables drive validation: a shadow map for a light the scene lacks, or for
 * a point light, is refused when the graph compiles. */
static void
test_shadow_map_refuses_bad_light(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    fx_scene_init(&s);
    fx_add_quad(&s, 1, 0.0f, -1.0f, 1.0f, -1.0f, 1.0f, 0);
    fx_add_light(&s, CG_LIGHT_POINT, 1.0f);
    fx_scene_finish(&s);
    cg_view view;
    fx_view_look_at((float[3]){ 0, 3, 0.01f }, (float[3]){ 0, 0, 0 }, up_z, 60.0f, 8, 8, &view);
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_ok(cg_builtin_passes_register(registry, &err), &err);
    const char *lights[] = { "0", "3" };
    for (int i = 0; i < 2; i++) {
        fg_graph *graph = fg_graph_create(registry);
        assert_cg_ok(fg_graph_load_string(graph,
            "{ \"version\": 1, \"passes\": { \"shadow\": { \"type\": \"shadow_map\" } },"
            "  \"outputs\": [ \"shadow.depth\" ] }", "test graph", &err), &err);
        assert_cg_ok(fg_graph_set_param(graph, "shadow", "light", lights[i], NULL, &err), &err);
        fg_frame frame = { .scene = &s.scene, .view = view, .width = 8, .height = 8 };
        fg_compile_options options = { 0 };
        assert_cg_status(fg_graph_compile(graph, &frame, &options, &err), &err, CG_ERR_GRAPH_PARAM_RANGE);
        fg_graph_destroy(graph);
    }
    fg_registry_destroy(registry);
    assert_no_gl_errors(ctx);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_shadow_map_depth_of_plane),
             cmocka_unit_test(test_shadow_map_cache),
             cmocka_unit_test(test_gbuffer_normal_albedo),
             cmocka_unit_test(test_direct_directional_pcf3),
             cmocka_unit_test(test_direct_directional_unfiltered),
             cmocka_unit_test(test_direct_directional_pcf5),
             cmocka_unit_test(test_wide_spot_is_unshadowed),
             cmocka_unit_test(test_direct_point_light),
             cmocka_unit_test(test_direct_point_light_range),
             cmocka_unit_test(test_direct_spot_light),
             cmocka_unit_test(test_composite_sums_inputs),
             cmocka_unit_test(test_shadow_map_refuses_bad_light),
             cmocka_unit_test(test_gbuffer_material_outputs),
             cmocka_unit_test(test_gbuffer_normal_map_mask_and_sides),
             cmocka_unit_test(test_shadow_map_mask),
             cmocka_unit_test(test_direct_ggx))
