/* Animation: the samplers against values computed by hand (LINEAR, STEP, CUBICSPLINE, slerp
 * along the shorter arc), a hierarchy (the parent turns, the child moves) with an instance, a
 * light and a camera following it, what cg_scene_evaluate reports and stamps, the bounds over
 * the whole animation, an animated glTF written here that loads, evaluates and survives
 * export (.gltf and .glb), the animated built-in variants, and a skinned strip (glTF skins
 * posed at two times, stamped, bounded). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/scene.h"
#include "test_support.h"

#define S45 0.70710678118654752440

static cg_anim_channel
make_channel(int node, cg_anim_path path, cg_anim_interpolation interpolation, int keys, const float *times,
             const float *values)
{
    cg_anim_channel c = { .node = node, .path = path, .interpolation = interpolation, .key_count = keys };
    int n = path == CG_ANIM_ROTATION ? 4 : 3, per_key = interpolation == CG_INTERP_CUBICSPLINE ? 3 : 1;
    c.times = malloc(sizeof(float) * (size_t)keys);
    c.values = malloc(sizeof(float) * (size_t)(keys * n * per_key));
    assert_non_null(c.times);
    assert_non_null(c.values);
    memcpy(c.times, times, sizeof(float) * (size_t)keys);
    memcpy(c.values, values, sizeof(float) * (size_t)(keys * n * per_key));
    return c;
}

static void
free_channel(cg_anim_channel *c)
{
    free(c->times);
    free(c->values);
}

static void
assert_sample(const cg_anim_channel *c, double t, double x, double y, double z, double tolerance)
{
    double v[4];
    cg_anim_channel_sample(c, t, v);
    if (fabs(v[0] - x) > tolerance || fabs(v[1] - y) > tolerance || fabs(v[2] - z) > tolerance)
        fail_msg("at t = %g: (%.9g, %.9g, %.9g), expected (%.9g, %.9g, %.9g)", t, v[0], v[1], v[2], x, y, z);
}

static void
linear_and_step(void **state)
{
    (void)state;
    const float times[3] = { 0, 1, 3 };
    const float values[9] = { 0, 0, 0, 2, 4, 6, 2, 0, 0 };
    cg_anim_channel c = make_channel(0, CG_ANIM_TRANSLATION, CG_INTERP_LINEAR, 3, times, values);
    assert_sample(&c, -1, 0, 0, 0, 0);        /* before the first key: the first value */
    assert_sample(&c, 0, 0, 0, 0, 0);
    assert_sample(&c, 0.25, 0.5, 1, 1.5, 1e-12);
    assert_sample(&c, 1, 2, 4, 6, 0);         /* on a key: its value */
    assert_sample(&c, 2, 2, 2, 3, 1e-12);     /* halfway through the second segment */
    assert_sample(&c, 3, 2, 0, 0, 0);
    assert_sample(&c, 99, 2, 0, 0, 0);        /* after the last key: the last value, no looping */
    c.interpolation = CG_INTERP_STEP;
    assert_sample(&c, 0.999, 0, 0, 0, 0);
    assert_sample(&c, 1, 2, 4, 6, 0);
    assert_sample(&c, 2.999, 2, 4, 6, 0);
    assert_sample(&c, 3, 2, 0, 0, 0);
    free_channel(&c);
    /* One key: that value at any time. */
    cg_anim_channel one = make_channel(0, CG_ANIM_SCALE, CG_INTERP_LINEAR, 1, times + 1, values + 3);
    assert_sample(&one, 0, 2, 4, 6, 0);
    assert_sample(&one, 5, 2, 4, 6, 0);
    free_channel(&one);
}

/* glTF 2.0 Appendix C: p(u) = h00 v0 + h10 dt b0 + h01 v1 + h11 dt a1 with dt = 2 here. At u
 * = 1/4: h00 = 27/32, h10 = 9/64, h01 = 5/32, h11 = -3/64; at u = 1/2: 1/2, 1/8, 1/2, -1/8. */
static void
cubic_spline(void **state)
{
    (void)state;
    const float times[2] = { 0, 2 };
    const float values[18] = {
        9, 9, 9,  0, 1, 5,  1, 0, 0,  /* key 0: in-tangent (unused), value, out-tangent */
        3, 0, 0,  1, 1, 5,  7, 7, 7,  /* key 1: in-tangent, value, out-tangent (unused) */
    };
    cg_anim_channel c = make_channel(0, CG_ANIM_TRANSLATION, CG_INTERP_CUBICSPLINE, 2, times, values);
    /* x: 27/32 0 + 9/64 2 1 + 5/32 1 - 3/64 2 3 = 0.15625; y: 27/32 + 5/32 = 1; z: 5. */
    assert_sample(&c, 0.5, 0.15625, 1, 5, 1e-12);
    assert_sample(&c, 1, 0, 1, 5, 1e-12);     /* 1/8 2 + 1/2 - 1/8 6 = 0 */
    assert_sample(&c, 0, 0, 1, 5, 0);         /* the values, not the tangents, at the ends */
    assert_sample(&c, 2, 1, 1, 5, 0);
    assert_sample(&c, -3, 0, 1, 5, 0);
    assert_sample(&c, 30, 1, 1, 5, 0);
    free_channel(&c);
    /* A rotation through a cubic spline comes out normalised. */
    const float qs[24] = { 0, 0, 0, 0,  0, 0, 0, 1,  0, 0, 1, 0,
                           0, 0, 1, 0,  0, 0, (float)S45, (float)S45,  0, 0, 0, 0 };
    cg_anim_channel r = make_channel(0, CG_ANIM_ROTATION, CG_INTERP_CUBICSPLINE, 2, times, qs);
    double q[4];
    cg_anim_channel_sample(&r, 0.7, q);
    assert_float_equal(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-12);
    free_channel(&r);
}

static void
slerp_rotations(void **state)
{
    (void)state;
    const float times[2] = { 0, 1 };
    /* Identity to a quarter turn about +z: at u the rotation by u x 90 degrees. */
    const float qs[8] = { 0, 0, 0, 1, 0, 0, (float)S45, (float)S45 };
    cg_anim_channel c = make_channel(0, CG_ANIM_ROTATION, CG_INTERP_LINEAR, 2, times, qs);
    const double us[3] = { 0.25, 0.5, 0.8 };
    for (int i = 0; i < 3; i++) {
        double q[4], half = us[i] * M_PI / 4;
        cg_anim_channel_sample(&c, us[i], q);
        assert_float_equal(q[0], 0, 1e-7);
        assert_float_equal(q[1], 0, 1e-7);
        assert_float_equal(q[2], sin(half), 1e-7);
        assert_float_equal(q[3], cos(half), 1e-7);
    }
    /* The same end rotation written as -q: still the shorter arc, the same result (not the
     * 270-degree way round that a plain blend towards -q would take). */
    const float flipped[8] = { 0, 0, 0, 1, 0, 0, -(float)S45, -(float)S45 };
    cg_anim_channel f = make_channel(0, CG_ANIM_ROTATION, CG_INTERP_LINEAR, 2, times, flipped);
    double q[4];
    cg_anim_channel_sample(&f, 0.5, q);
    double sign = q[3] < 0 ? -1 : 1; /* q and -q are the same rotation */
    assert_float_equal(sign * q[2], sin(M_PI / 8), 1e-7);
    assert_float_equal(sign * q[3], cos(M_PI / 8), 1e-7);
    /* A STEP rotation is normalised too (a file may store it to 0.00769 of unit length). */
    const float loose[8] = { 0, 0, 0, 1.005f, 0, 0, 0, 1 };
    cg_anim_channel s = make_channel(0, CG_ANIM_ROTATION, CG_INTERP_STEP, 2, times, loose);
    cg_anim_channel_sample(&s, 0.5, q);
    assert_float_equal(q[3], 1, 1e-12);
    free_channel(&c);
    free_channel(&f);
    free_channel(&s);
}

/* ------------------------------------------------------------------ a hierarchy by hand */

/* Node 0 ("arm") turns a quarter turn about +y over 1 s; node 1 ("hand"), its child, moves
 * from x = 1 to x = 3 along its parent's x. A unit cube and a spot light hang on the hand, a
 * camera on the arm; a static cube at x = 10. */
static void
hierarchy_scene(cg_scene *s)
{
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "hierarchy");
    s->material_count = 1;
    s->materials = calloc(1, sizeof *s->materials);
    s->materials[0].base_color_texture = s->materials[0].emissive_texture = -1;
    /* The material's other textures none too, and no attenuation (cg_scene_validate checks them). */
    s->materials[0].metallic_roughness_texture = s->materials[0].normal_texture = -1;
    s->materials[0].occlusion_texture = s->materials[0].transmission_texture = -1;
    s->materials[0].attenuation_distance = INFINITY;
    s->mesh_count = 1;
    s->meshes = calloc(1, sizeof *s->meshes);
    cg_mesh *m = &s->meshes[0];
    m->vertex_count = 3;
    m->index_count = 3;
    m->positions = calloc(9, sizeof(float));
    m->normals = calloc(9, sizeof(float));
    m->indices = calloc(3, sizeof(uint32_t));
    for (int k = 0; k < 3; k++)
        m->bounds_min[k] = -0.5f, m->bounds_max[k] = 0.5f;
    s->instance_count = 2;
    s->instances = calloc(2, sizeof *s->instances);
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 4; k++)
            s->instances[i].world[5 * k] = 1;
    s->instances[1].world[12] = 10;
    s->instances[0].moving = true;
    s->light_count = 1;
    s->lights = calloc(1, sizeof *s->lights);
    s->lights[0] = (cg_light){ .type = CG_LIGHT_SPOT, .intensity = 1, .outer_cone_angle = 0.5f };
    s->camera_count = 1;
    s->cameras = calloc(1, sizeof *s->cameras);
    s->cameras[0] = (cg_camera){ .type = CG_CAMERA_PERSPECTIVE, .yfov = 1, .znear = 0.1f };
    s->node_count = 2;
    s->nodes = calloc(2, sizeof *s->nodes);
    for (int i = 0; i < 2; i++) {
        s->nodes[i].parent = i - 1;
        s->nodes[i].rotation[3] = 1;
        for (int k = 0; k < 3; k++)
            s->nodes[i].scale[k] = 1;
    }
    s->attachment_count = 3;
    s->attachments = calloc(3, sizeof *s->attachments);
    s->attachments[0] = (cg_attachment){ CG_ATTACH_INSTANCE, 0, 1 };
    s->attachments[1] = (cg_attachment){ CG_ATTACH_LIGHT, 0, 1 };
    s->attachments[2] = (cg_attachment){ CG_ATTACH_CAMERA, 0, 0 };
    const float times[2] = { 0, 1 };
    const float turn[8] = { 0, 0, 0, 1, 0, (float)S45, 0, (float)S45 };
    const float move[6] = { 1, 0, 0, 3, 0, 0 };
    s->animation_count = 1;
    s->animations = calloc(1, sizeof *s->animations);
    s->animations[0].channel_count = 2;
    s->animations[0].channels = calloc(2, sizeof(cg_anim_channel));
    s->animations[0].channels[0] = make_channel(0, CG_ANIM_ROTATION, CG_INTERP_LINEAR, 2, times, turn);
    s->animations[0].channels[1] = make_channel(1, CG_ANIM_TRANSLATION, CG_INTERP_LINEAR, 2, times, move);
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_validate(s, &err), &err);
}

static void
hierarchy_follows(void **state)
{
    (void)state;
    cg_scene s;
    hierarchy_scene(&s);
    cg_scene_changes ch;
    cg_scene_evaluate(&s, 0.5, &ch);
    assert_int_equal(ch.instances_moved, 1);
    assert_true(ch.lights);
    assert_true(ch.cameras);
    /* At t = 0.5 the arm has turned 45 degrees about +y (x goes to (cos, 0, -sin)), the hand
     * sits at 2 along the arm's x: (2 cos 45, 0, -2 sin 45). */
    const float *w = s.instances[0].world;
    assert_float_equal(w[12], 2 * S45, 1e-6);
    assert_float_equal(w[13], 0, 1e-6);
    assert_float_equal(w[14], -2 * S45, 1e-6);
    assert_float_equal(w[0], S45, 1e-6);      /* its x axis turned with the arm */
    assert_float_equal(w[2], -S45, 1e-6);
    /* The light at the hand's origin, shining down its -z: -(sin 45, 0, cos 45). */
    assert_float_equal(s.lights[0].position[0], 2 * S45, 1e-6);
    assert_float_equal(s.lights[0].position[2], -2 * S45, 1e-6);
    assert_float_equal(s.lights[0].direction[0], -S45, 1e-6);
    assert_float_equal(s.lights[0].direction[1], 0, 1e-6);
    assert_float_equal(s.lights[0].direction[2], -S45, 1e-6);
    /* The camera turns with the arm and stays at its origin. */
    assert_float_equal(s.cameras[0].world[8], S45, 1e-6);
    assert_float_equal(s.cameras[0].world[10], S45, 1e-6);
    assert_float_equal(s.cameras[0].world[12], 0, 0);
    /* The static instance never moves. */
    assert_float_equal(s.instances[1].world[12], 10, 0);
    assert_int_equal(s.instances[1].revision, 0);

    /* The stamps: what changed carries the revision it changed at. */
    uint64_t r = s.revision;
    assert_true(r > 0);
    assert_int_equal(s.instances[0].revision, r);
    assert_int_equal(s.instances_revision, r);
    assert_int_equal(s.lights_revision, r);
    assert_int_equal(s.cameras_revision, r);
    /* The same time again changes nothing, and stamps nothing. */
    cg_scene_evaluate(&s, 0.5, &ch);
    assert_int_equal(ch.instances_moved, 0);
    assert_false(ch.lights);
    assert_false(ch.cameras);
    assert_int_equal(s.revision, r);
    /* After the last key the last pose: the arm a quarter turn round, the hand at 3 along it. */
    cg_scene_evaluate(&s, 7, &ch);
    assert_float_equal(w[12], 0, 1e-6);
    assert_float_equal(w[14], -3, 1e-6);
    assert_int_equal(s.revision, r + 1);
    cg_scene_evaluate(&s, 8, &ch);
    assert_int_equal(ch.instances_moved, 0);
    /* A light moved by hand is stamped too. */
    cg_scene_lights_changed(&s);
    assert_int_equal(s.lights_revision, r + 2);
    assert_int_equal(s.instances_revision, r + 1);
    cg_scene_free(&s);
}

static void
bounds_cover_the_animation(void **state)
{
    (void)state;
    cg_scene s;
    hierarchy_scene(&s);
    cg_scene_evaluate(&s, 0.3, NULL);
    cg_scene_compute_bounds(&s);
    assert_float_equal(s.time, 0.3, 0); /* left posed where it was */
    float lo[3], hi[3];
    memcpy(lo, s.bounds_min, sizeof lo);
    memcpy(hi, s.bounds_max, sizeof hi);
    /* The hand's cube over [0, 1] s: from x = 1 to z = -3, and the static cube at x = 10. */
    assert_true(hi[0] >= 10.5f && lo[2] <= -3.5f);
    /* Every pose, sampled far more densely than the bounds were, lies inside: posed at every key
     * and 15 times between, the union leaves at most the arc's sagitta between two samples out,
     * 2r sin^2(a/4) for a = 90/16 degrees at r < 4 m: under 5 mm; 1 cm allows for it. */
    for (int i = 0; i <= 400; i++) {
        double t = -0.5 + 2.0 * i / 400;
        cg_scene_evaluate(&s, t, NULL);
        const float *w = s.instances[0].world;
        for (int c = 0; c < 8; c++) {
            double p[3] = { c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5 };
            for (int k = 0; k < 3; k++) {
                double x = w[k] * p[0] + w[4 + k] * p[1] + w[8 + k] * p[2] + w[12 + k];
                assert_true(x >= lo[k] - 0.01 && x <= hi[k] + 0.01);
                assert_true(x >= s.instances[0].motion_min[k] - 0.01 && x <= s.instances[0].motion_max[k] + 0.01);
            }
        }
    }
    /* Evaluating does not move the bounds. */
    assert_memory_equal(lo, s.bounds_min, sizeof lo);
    /* A static instance's motion box is its box. */
    assert_float_equal(s.instances[1].motion_min[0], 9.5, 0);
    assert_float_equal(s.instances[1].motion_max[0], 10.5, 0);
    cg_scene_free(&s);
}

/* ------------------------------------------------------------------ an animated glTF */

static void
base64(const unsigned char *data, size_t n, char *out)
{
    static const char abc[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)data[i] << 16 | (i + 1 < n ? (uint32_t)data[i + 1] << 8 : 0) |
                     (i + 2 < n ? data[i + 2] : 0);
        out[o++] = abc[v >> 18 & 63];
        out[o++] = abc[v >> 12 & 63];
        out[o++] = i + 1 < n ? abc[v >> 6 & 63] : '=';
        out[o++] = i + 2 < n ? abc[v & 63] : '=';
    }
    out[o] = '\0';
}

/* Nodes: 0 "arm" (children 1, 2) turns a quarter turn about +y over [0, 1] s (LINEAR); 1
 * "hand" (a triangle, and a child node with a point light) jumps from x = 1 to x = 3 at 0.5 s
 * (STEP) and scales along x by a CUBICSPLINE over [0, 2] s; 2 "eye" holds the camera 5 m along
 * the arm's +z; 3 the light node; 4 a static triangle at x = 10. */
static const char *
write_animated_gltf(void)
{
    float data[47] = {
        0, 0, 0,  1, 0, 0,  0, 1, 0,                                 /* 0: positions (36 bytes) */
        0, 1,                                                        /* 36: rotation times */
        0, 0, 0, 1,  0, (float)S45, 0, (float)S45,                   /* 44: rotations */
        0, 0.5f,                                                     /* 76: translation times */
        1, 0, 0,  3, 0, 0,                                           /* 84: translations */
        0, 2,                                                        /* 108: scale times */
        0, 0, 0,  1, 1, 1,  1, 0, 0,   3, 0, 0,  2, 1, 1,  0, 0, 0, /* 116: in, value, out x 2 */
    };
    char b64[300];
    base64((const unsigned char *)data, sizeof data, b64);
    static char json[8192];
    snprintf(json, sizeof json,
             "{\"asset\": {\"version\": \"2.0\"}, \"extensionsUsed\": [\"KHR_lights_punctual\"],\n"
             " \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"point\", \"intensity\": 2}]}},\n"
             " \"scene\": 0, \"scenes\": [{\"nodes\": [0, 4]}],\n"
             " \"nodes\": [{\"name\": \"arm\", \"children\": [1, 2]},\n"
             "  {\"name\": \"hand\", \"mesh\": 0, \"translation\": [1, 0, 0], \"children\": [3]},\n"
             "  {\"name\": \"eye\", \"camera\": 0, \"translation\": [0, 0, 5]},\n"
             "  {\"name\": \"lamp\", \"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}},\n"
             "  {\"name\": \"still\", \"mesh\": 0, \"translation\": [10, 0, 0]}],\n"
             " \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": 1, \"znear\": 0.1}}],\n"
             " \"meshes\": [{\"name\": \"tri\", \"primitives\": [{\"attributes\": {\"POSITION\": 0}}]}],\n"
             " \"animations\": [\n"
             "  {\"name\": \"swing\", \"samplers\": [{\"input\": 1, \"output\": 2},\n"
             "     {\"input\": 3, \"output\": 4, \"interpolation\": \"STEP\"}],\n"
             "   \"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"rotation\"}},\n"
             "     {\"sampler\": 1, \"target\": {\"node\": 1, \"path\": \"translation\"}}]},\n"
             "  {\"name\": \"stretch\", \"samplers\": [{\"input\": 5, \"output\": 6, \"interpolation\": \"CUBICSPLINE\"}],\n"
             "   \"channels\": [{\"sampler\": 0, \"target\": {\"node\": 1, \"path\": \"scale\"}}]}],\n"
             " \"buffers\": [{\"byteLength\": %zu, \"uri\": \"data:application/octet-stream;base64,%s\"}],\n"
             " \"bufferViews\": [{\"buffer\": 0, \"byteLength\": 36, \"target\": 34962},\n"
             "  {\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 8}, {\"buffer\": 0, \"byteOffset\": 44, \"byteLength\": 32},\n"
             "  {\"buffer\": 0, \"byteOffset\": 76, \"byteLength\": 8}, {\"buffer\": 0, \"byteOffset\": 84, \"byteLength\": 24},\n"
             "  {\"buffer\": 0, \"byteOffset\": 108, \"byteLength\": 8}, {\"buffer\": 0, \"byteOffset\": 116, \"byteLength\": 72}],\n"
             " \"accessors\": [\n"
             "  {\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"min\": [0, 0, 0], \"max\": [1, 1, 0]},\n"
             "  {\"bufferView\": 1, \"componentType\": 5126, \"count\": 2, \"type\": \"SCALAR\", \"min\": [0], \"max\": [1]},\n"
             "  {\"bufferView\": 2, \"componentType\": 5126, \"count\": 2, \"type\": \"VEC4\"},\n"
             "  {\"bufferView\": 3, \"componentType\": 5126, \"count\": 2, \"type\": \"SCALAR\", \"min\": [0], \"max\": [0.5]},\n"
             "  {\"bufferView\": 4, \"componentType\": 5126, \"count\": 2, \"type\": \"VEC3\"},\n"
             "  {\"bufferView\": 5, \"componentType\": 5126, \"count\": 2, \"type\": \"SCALAR\", \"min\": [0], \"max\": [2]},\n"
             "  {\"bufferView\": 6, \"componentType\": 5126, \"count\": 6, \"type\": \"VEC3\"}]}\n",
             sizeof data, b64);
    return cg_test_write_file("animated.gltf", json, 0);
}

/* The pose at t = 0.5: the arm at 45 degrees, the hand at x = 3 (the STEP's second key) scaled
 * by 1.15625 along x (the spline of cubic_spline, x: 27/32 1 + 9/64 2 1 + 5/32 2 - 3/64 2 3). */
static void
assert_pose_at_half(const cg_scene *s)
{
    int hand = -1, still = -1;
    for (int i = 0; i < s->instance_count; i++)
        *(s->instances[i].moving ? &hand : &still) = i;
    assert_true(hand >= 0 && still >= 0);
    const float *w = s->instances[hand].world;
    assert_float_equal(w[12], 3 * S45, 1e-5);
    assert_float_equal(w[14], -3 * S45, 1e-5);
    assert_float_equal(w[0], 1.15625 * S45, 1e-5);
    assert_float_equal(w[2], -1.15625 * S45, 1e-5);
    assert_float_equal(w[5], 1, 1e-6);
    assert_float_equal(s->instances[still].world[12], 10, 0);
    /* The light's node is collapsed onto the hand (no transform of its own). */
    assert_float_equal(s->lights[0].position[0], 3 * S45, 1e-5);
    assert_float_equal(s->lights[0].position[2], -3 * S45, 1e-5);
    /* The camera, 5 m along the arm's z: (5 sin 45, 0, 5 cos 45). */
    assert_float_equal(s->cameras[0].world[12], 5 * S45, 1e-5);
    assert_float_equal(s->cameras[0].world[14], 5 * S45, 1e-5);
}

static void
animated_gltf_round_trip(void **state)
{
    (void)state;
    const char *path = write_animated_gltf();
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(path, &s, &err), &err);
    assert_true(cg_scene_is_animated(&s));
    assert_int_equal(s.animation_count, 2);
    assert_int_equal(s.node_count, 3);        /* arm, hand, eye; the lamp collapses onto the hand */
    assert_int_equal(s.attachment_count, 3);
    double start, end;
    cg_scene_animation_range(&s, &start, &end);
    assert_float_equal(start, 0, 0);
    assert_float_equal(end, 2, 0);
    /* Loaded, it is posed at t = 0: the hand at x = 1, unturned. */
    assert_float_equal(s.time, 0, 0);
    int hand = s.instances[0].moving ? 0 : 1;
    assert_float_equal(s.instances[hand].world[12], 1, 1e-6);
    assert_int_equal(s.meshes[s.instances[hand].mesh].kind, CG_MESH_COMPLEX); /* moving: complex */
    cg_scene_evaluate(&s, 0.5, NULL);
    assert_pose_at_half(&s);

    static const char *const outputs[2] = { "animated_out.gltf", "animated_out.glb" };
    for (int i = 0; i < 2; i++) {
        char out[4096];
        snprintf(out, sizeof out, "%s/%s", cg_test_tmpdir(), outputs[i]);
        assert_cg_ok(cg_scene_export_gltf(&s, out, &err), &err);
        cg_scene back;
        assert_cg_ok(cg_scene_load(out, &back, &err), &err);
        assert_int_equal(back.node_count, s.node_count);
        assert_int_equal(back.attachment_count, s.attachment_count);
        assert_int_equal(back.animation_count, 2);
        cg_scene_evaluate(&back, 0.5, NULL);
        assert_pose_at_half(&back);
        for (int k = 0; k < 3; k++) {
            assert_float_equal(back.bounds_min[k], s.bounds_min[k], 1e-5);
            assert_float_equal(back.bounds_max[k], s.bounds_max[k], 1e-5);
        }
        cg_scene_free(&back);
    }
    cg_scene_free(&s);
}

/* ------------------------------------------------------------------ built-in motion */

static void
load(const char *source, cg_scene *s)
{
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(source, s, &err), &err);
}

static void
openworld_motion(void **state)
{
    (void)state;
    cg_scene still, sun, one, all;
    load("builtin:openworld?triangles=20000", &still);
    load("builtin:openworld?triangles=20000&motion=sun&period=8", &sun);
    load("builtin:openworld?triangles=20000&motion=one", &one);
    load("builtin:openworld?triangles=20000&motion=all", &all);
    assert_false(cg_scene_is_animated(&still));
    size_t triangles = cg_scene_triangle_count(&still);
    assert_int_equal(cg_scene_triangle_count(&sun), triangles);
    assert_int_equal(cg_scene_triangle_count(&one), triangles);
    assert_int_equal(cg_scene_triangle_count(&all), triangles);

    /* The sun turns about the vertical at a constant rate, keeping its elevation: after a
     * quarter of the period its direction is the first one turned 90 degrees about +y. */
    const float *d0 = still.lights[0].direction;
    assert_float_equal(sun.lights[0].direction[0], d0[0], 1e-6);
    assert_float_equal(sun.lights[0].direction[2], d0[2], 1e-6);
    for (int i = 1; i <= 7; i++) {
        double t = i, a = 2 * M_PI * t / 8;
        cg_scene_changes ch;
        cg_scene_evaluate(&sun, t, &ch);
        assert_true(ch.lights);
        assert_int_equal(ch.instances_moved, 0);
        const float *d = sun.lights[0].direction;
        assert_float_equal(d[1], d0[1], 1e-6);
        /* Turning by a about +y: (x, z) -> (x cos a + z sin a, -x sin a + z cos a). */
        assert_float_equal(d[0], d0[0] * cos(a) + d0[2] * sin(a), 1e-5);
        assert_float_equal(d[2], -d0[0] * sin(a) + d0[2] * cos(a), 1e-5);
    }

    /* One building moves (walls, and roof when it has one); at half the period (20 s by
     * default) it is sunk into the ground, roof and all: its top at its base. */
    int moving = 0;
    float base = INFINITY, top = -INFINITY;
    for (int i = 0; i < one.instance_count; i++) {
        const cg_instance *in = &one.instances[i];
        moving += in->moving;
        if (in->moving)
            base = fminf(base, one.meshes[in->mesh].bounds_min[1]);
    }
    assert_true(moving == 1 || moving == 2);
    cg_scene_evaluate(&one, 10, NULL);
    for (int i = 0; i < one.instance_count; i++)
        if (one.instances[i].moving) {
            assert_true(one.instances[i].world[13] < -5);
            top = fmaxf(top, one.meshes[one.instances[i].mesh].bounds_max[1] + one.instances[i].world[13]);
        }
    assert_float_equal(top, base, 1e-3);
    cg_scene_evaluate(&one, 20, NULL);
    for (int i = 0; i < one.instance_count; i++)
        assert_float_equal(one.instances[i].world[13], 0, 0); /* back up at the end */

    /* Every complex instance moves, and nothing else. */
    cg_scene_changes ch;
    cg_scene_evaluate(&all, 3, &ch);
    int complex = 0;
    for (int i = 0; i < all.instance_count; i++) {
        bool is_complex = all.meshes[all.instances[i].mesh].kind == CG_MESH_COMPLEX;
        assert_int_equal(all.instances[i].moving, is_complex);
        complex += is_complex;
    }
    assert_int_equal(ch.instances_moved, complex);
    assert_false(ch.lights);

    /* Without motion nothing changes; the default is what it always was (regression_images
     * holds it to the bit). */
    cg_scene_evaluate(&still, 5, &ch);
    assert_int_equal(ch.instances_moved, 0);
    assert_int_equal(still.node_count, 0);
    cg_scene_free(&still);
    cg_scene_free(&sun);
    cg_scene_free(&one);
    cg_scene_free(&all);

    cg_scene bad;
    cg_error err = { 0 };
    assert_cg_status(cg_scene_load("builtin:openworld?motion=spin", &bad, &err), &err, CG_ERR_SCENE_PARAM);
    assert_non_null(strstr(err.message, "none, sun, one, all"));
    assert_cg_status(cg_scene_load("builtin:openworld?period=5", &bad, &err), &err, CG_ERR_SCENE_PARAM);
    assert_cg_status(cg_scene_load("builtin:openworld?motion=sun&period=0", &bad, &err), &err, CG_ERR_SCENE_PARAM);
}

/* ------------------------------------------------------------------ skins
 *
 * tests/data/gltf/skin/bend.gltf (its README gives the figures): a strip whose top row turns a
 * quarter turn about +z over [0, 1] s with the joint "upper", its middle row half way. */

static void
assert_vertex(const cg_mesh *m, int v, double x, double y, double z)
{
    const float *p = m->positions + 3 * v;
    if (!(fabs(p[0] - x) < 1e-5 && fabs(p[1] - y) < 1e-5 && fabs(p[2] - z) < 1e-5))
        fail_msg("vertex %d at (%g, %g, %g), expected (%g, %g, %g)", v, p[0], p[1], p[2], x, y, z);
}

static void
skin_bends_the_strip(void **state)
{
    (void)state;
    cg_scene s;
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_load(cg_test_data_path("gltf/skin/bend.gltf"), &s, &err), &err);
    assert_int_equal(s.skin_count, 1);
    assert_int_equal(s.skinned_count, 1);
    assert_int_equal(s.skins[0].joint_count, 2);
    const cg_skinned_mesh *sk = &s.skinned[0];
    const cg_instance *inst = &s.instances[sk->instance];
    const cg_mesh *m = &s.meshes[sk->mesh];
    assert_int_equal(inst->mesh, sk->mesh);
    assert_true(inst->moving);
    /* The skin places the vertices; the node's translation by 5 is ignored (glTF 3.7.3.3). */
    for (int i = 0; i < 16; i++)
        assert_float_equal(inst->world[i], (i % 5 == 0 ? 1.0 : 0.0), 0);
    /* At t = 0 the joints are where their inverse bind matrices undo: the bind pose. */
    assert_vertex(m, 4, 0, 2, 0);
    assert_vertex(m, 3, 1, 1, 0);
    assert_int_equal(m->revision, 0);
    assert_int_equal(inst->revision, 0);

    cg_scene_changes ch;
    cg_scene_evaluate(&s, 1, &ch);
    assert_int_equal(ch.meshes_deformed, 1);
    assert_int_equal(ch.instances_moved, 1);
    assert_true(m->revision == s.revision && inst->revision == s.revision && s.instances_revision == s.revision);
    assert_vertex(m, 0, 0, 0, 0);          /* the bottom row follows "lower", which stays */
    assert_vertex(m, 2, 0.25, 0.75, 0);    /* half of each joint */
    assert_vertex(m, 3, 0.75, 1.25, 0);
    assert_vertex(m, 4, -0.5, 0.5, 0);     /* a quarter turn about (0.5, 1, 0) */
    assert_vertex(m, 5, -0.5, 1.5, 0);
    for (int v = 0; v < 6; v++) /* a turn about z leaves the normals of the z = 0 plane */
        assert_float_equal(m->normals[3 * v + 2], 1, 1e-6);
    assert_float_equal(m->bounds_min[0], -0.5, 1e-5);
    assert_float_equal(m->bounds_max[1], 1.5, 1e-5);

    /* Halfway: the top row turned by 45 degrees; nothing changes after the last key. */
    cg_scene_evaluate(&s, 0.5, &ch);
    assert_int_equal(ch.meshes_deformed, 1);
    assert_vertex(m, 4, 0.5 - 0.5 * S45 - S45, 1 - 0.5 * S45 + S45, 0);
    cg_scene_evaluate(&s, 1, &ch);
    uint64_t at_one = s.revision;
    cg_scene_evaluate(&s, 7, &ch);
    assert_int_equal(ch.meshes_deformed, 0);
    assert_int_equal(ch.instances_moved, 0);
    assert_true(s.revision == at_one);

    /* The bounds hold every pose: the bind pose's top (y = 2) and the bent one's left (x = -0.5). */
    assert_true(s.bounds_max[1] >= 2 - 1e-5 && s.bounds_min[0] <= -0.5 + 1e-5);
    assert_true(inst->motion_max[1] >= 2 - 1e-5 && inst->motion_min[0] <= -0.5 + 1e-5);
    cg_scene_free(&s);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(linear_and_step),
             cmocka_unit_test(cubic_spline),
             cmocka_unit_test(slerp_rotations),
             cmocka_unit_test(hierarchy_follows),
             cmocka_unit_test(bounds_cover_the_animation),
             cmocka_unit_test(animated_gltf_round_trip),
             cmocka_unit_test(openworld_motion),
             cmocka_unit_test(skin_bends_the_strip))
