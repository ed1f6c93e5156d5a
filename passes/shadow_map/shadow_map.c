/* shadow_map: depth of the scene seen from one directional or spot light, and the
 * matrices and bias that shaders/common/shadow.glsl needs to look it up.
 *
 * Directional light: orthographic projection fitted to the scene bounds seen along the
 * light. Spot light: perspective projection covering the outer cone. Point lights get no
 * shadow map (they light unshadowed; docs/passes.md). Used for direct light and for the
 * light injected into the voxel volume (VCT paper 3.1: "we render a shadow map").
 *
 * Caching (cache=true, the default): the depth map is persistent and drawn again only when what
 * it is drawn from may have changed: the first frame after prepare, the block (the light, the
 * projection fitted to the scene's bounds, the parameters), an instance (its world, mesh or
 * material: sdk/instances.h), the scene's upload, an alpha-masked material appearing, or the
 * storage. A kept frame equals a drawn one bit for bit (the same draw of the same inputs); it
 * saves the draw of every instance, on llvmpipe 30 ms a frame of builtin:openworld at 2048^2.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "sdk/blocks.h"
#include "sdk/instances.h"
#include "sdk/pass.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

enum { FILTER_NONE, FILTER_PCF3, FILTER_PCF5 };

/* Spot cones wider than this cannot be covered by one perspective projection with a
 * usable texel density. */
#define MAX_SPOT_FOV_DEGREES 170.0f

static const fg_param_desc shadow_params[] = {
    { .name = "light", .type = FG_PARAM_INT, .default_value = -1, .min = -1, .max = 65535,
      .doc = "index of the scene light to shadow (directional or spot); -1 = the first directional or spot light" },
    { .name = "resolution", .type = FG_PARAM_INT, .default_value = 2048, .min = 16, .max = 16384,
      .step_doubles = true,
      .doc = "width and height of the depth map, texels" },
    { .name = "bias", .type = FG_PARAM_FLOAT, .default_value = 1.0, .min = 0.0, .max = 64.0,
      .step = 0.25,
      .doc = "constant depth bias, in shadow-map texels (world size of a texel at the receiver)" },
    { .name = "slope_bias", .type = FG_PARAM_FLOAT, .default_value = 1.0, .min = 0.0, .max = 64.0,
      .step = 0.25,
      .doc = "depth bias per unit of tan(angle between normal and light), in texels; tan is capped at 10" },
    { .name = "filter", .type = FG_PARAM_ENUM, .default_value = FILTER_PCF3, .choices = "none|pcf3|pcf5",
      .doc = "percentage-closer filtering of the lookup: 1, 3x3 or 5x5 depth comparisons" },
    { .name = "cache", .type = FG_PARAM_BOOL, .default_value = 1,
      .doc = "keep the depth map across frames (persistent), drawn again only when the light, its fitted "
             "projection, the parameters, an instance or the scene's upload changed; false: drawn every frame" },
};

typedef struct shadow_map_state {
    GLuint program;
    GLuint masked_program;  /* with mask.frag, for scenes with an alphaMode MASK material; 0 until one */
    GLuint fbo;
    GLuint staging;
    fg_slot depth, matrix;
    /* cache=true: what the kept depth map was drawn from (instances.taken = false: nothing yet). */
    bool cache;
    cgp_instance_record instances;
    cg_shadow_block drawn_block;
    GLuint drawn_depth;
    bool drawn_masked;
    uint64_t draws;         /* since prepare */
} shadow_map_state;

/* The light this instance serves: the `light` parameter, or the first directional or spot
 * light. Returns false with an error for an index the scene does not have or a point light;
 * *index = -1 when the scene has no light a shadow map can serve. */
static bool
pick_light(const fg_pass *pass, const cg_scene *scene, int *index, cg_error *err)
{
    int wanted = fg_param_int(pass, "light");
    *index = -1;
    if (wanted < 0) {
        for (int i = 0; i < scene->light_count; i++)
            if (scene->lights[i].type != CG_LIGHT_POINT) {
                *index = i;
                break;
            }
        return true;
    }
    if (wanted >= scene->light_count)
        return cg_fail(err, CG_ERR_GRAPH_PARAM_RANGE,
                       "pass '%s': light %d does not exist (scene '%s' has %d lights)",
                       fg_pass_name(pass), wanted, scene->name, scene->light_count);
    if (scene->lights[wanted].type == CG_LIGHT_POINT)
        return cg_fail(err, CG_ERR_GRAPH_PARAM_RANGE,
                       "pass '%s': light %d ('%s') is a point light; shadow_map serves directional "
                       "and spot lights (point lights are unshadowed)",
                       fg_pass_name(pass), wanted, scene->lights[wanted].name);
    *index = wanted;
    return true;
}

static float
spot_fov(const cg_light *light)
{
    /* One degree beyond the outer cone, so that PCF taps at the cone's edge stay inside. */
    return 2.0f * light->outer_cone_angle + glm_rad(1.0f);
}

static bool
shadow_map_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    if (frame->scene) {
        int index;
        if (!pick_light(pass, frame->scene, &index, err))
            return false;
        if (index < 0) {
            fg_declare_nothing_to_do(decl, "the scene has no directional or spot light");
            return true;
        }
        const cg_light *light = &frame->scene->lights[index];
        if (light->type == CG_LIGHT_SPOT && spot_fov(light) > glm_rad(MAX_SPOT_FOV_DEGREES)) {
            fg_declare_nothing_to_do(decl, "the spot light's cone is too wide for one perspective "
                                           "shadow map (outer angle above 84 degrees)");
            return true;
        }
    }
    int resolution = fg_param_int(pass, "resolution");
    fg_resource_desc depth = cgp_image_2d(GL_DEPTH_COMPONENT32F, resolution, resolution);
    /* Kept across frames: persistent storage is never pooled, so nothing else writes it. */
    depth.persistent = fg_param_bool(pass, "cache");
    fg_declare_output(decl, "depth", &depth, FG_ACCESS_ATTACHMENT);
    fg_resource_desc matrix = cgp_buffer_desc(sizeof(cg_shadow_block));
    fg_declare_output(decl, "matrix", &matrix, FG_ACCESS_TRANSFER);
    return true;
}

static void
shadow_map_cleanup(void *state)
{
    shadow_map_state *st = state;
    cgp_instance_record_free(&st->instances);
}

static bool
shadow_map_prepare(fg_pass *pass, shadow_map_state *st, cg_error *err)
{
    cgp_state_on_destroy(st, shadow_map_cleanup);
    st->cache = fg_param_bool(pass, "cache");
    CGP_SLOTS(pass, st, depth, matrix);
    st->fbo = cgp_framebuffer(st);
    glNamedFramebufferDrawBuffer(st->fbo, GL_NONE);
    glNamedFramebufferReadBuffer(st->fbo, GL_NONE);
    /* The block is written here and copied into the graph's buffer `matrix`. */
    st->staging = cgp_buffer(st, sizeof(cg_shadow_block), NULL, GL_DYNAMIC_STORAGE_BIT);
    return cgp_graphics_program(st, "shadow_map/depth.vert", NULL, NULL, NULL, &st->program, err);
}

/* glTF alphaMode MASK: a texel below the cutoff casts no shadow. Only a scene that has such a
 * material pays for a fragment shader (llvmpipe runs none for a depth-only program). */
static bool
scene_has_mask(const cg_scene *scene)
{
    for (int i = 0; i < scene->material_count; i++)
        if (scene->materials[i].alpha_mode == CG_ALPHA_MASK)
            return true;
    return false;
}

static void
light_up_vector(const vec3 dir, vec3 up)
{
    /* Any vector not parallel to the light's direction. */
    if (fabsf(dir[1]) < 0.99f)
        glm_vec3_copy((vec3){ 0.0f, 1.0f, 0.0f }, up);
    else
        glm_vec3_copy((vec3){ 1.0f, 0.0f, 0.0f }, up);
}

static void
bounds_corner(const cg_scene *scene, int i, vec3 out)
{
    out[0] = (i & 1) ? scene->bounds_max[0] : scene->bounds_min[0];
    out[1] = (i & 2) ? scene->bounds_max[1] : scene->bounds_min[1];
    out[2] = (i & 4) ? scene->bounds_max[2] : scene->bounds_min[2];
}

/* The light's view, its projection and depth range into the block. */
static void
store_view(mat4 view, mat4 proj, bool orthographic, float znear, float zfar, cg_shadow_block *b)
{
    mat4 view_proj;
    glm_mat4_mul(proj, view, view_proj);
    memcpy(b->view, view, sizeof b->view);
    memcpy(b->view_proj, view_proj, sizeof b->view_proj);
    b->frustum[1] = orthographic ? 1.0f : 0.0f;
    b->frustum[2] = znear;
    b->frustum[3] = zfar;
}

/* Orthographic projection along the light that just holds the scene bounds; its matrix also into
 * proj_out. */
static void
fit_directional(const cg_scene *scene, const cg_light *light, int resolution, cg_shadow_block *b, mat4 proj_out)
{
    vec3 dir, up, center, eye, extent;
    glm_vec3_normalize_to((float *)light->direction, dir);
    light_up_vector(dir, up);
    glm_vec3_add((float *)scene->bounds_min, (float *)scene->bounds_max, center);
    glm_vec3_scale(center, 0.5f, center);
    glm_vec3_sub((float *)scene->bounds_max, (float *)scene->bounds_min, extent);
    float diagonal = glm_vec3_norm(extent);
    /* Geometry all in one point has no size to follow and nothing to shadow: any radius serves. */
    float radius = diagonal > 0.0f ? 0.5f * diagonal : 1.0f;
    glm_vec3_scale(dir, -radius, eye);
    glm_vec3_add(center, eye, eye);
    mat4 view, proj;
    glm_lookat(eye, center, up, view);

    vec3 lo = { INFINITY, INFINITY, INFINITY }, hi = { -INFINITY, -INFINITY, -INFINITY };
    for (int i = 0; i < 8; i++) {
        vec3 c, v;
        bounds_corner(scene, i, c);
        glm_mat4_mulv3(view, c, 1.0f, v);
        glm_vec3_minv(lo, v, lo);
        glm_vec3_maxv(hi, v, hi);
    }
    /* A margin so that geometry on the bounds is not clipped, nor flat scenes degenerate: 1% of
     * the radius, no floor in metres (a 0.1 mm floor widened the map of a millimetre scene
     * tenfold, and its texels with it). */
    float margin = 0.01f * radius;
    float left = lo[0] - margin, right = hi[0] + margin;
    float bottom = lo[1] - margin, top = hi[1] + margin;
    float znear = -hi[2] - margin, zfar = -lo[2] + margin;
    glm_ortho(left, right, bottom, top, znear, zfar, proj);
    glm_mat4_copy(proj, proj_out);

    store_view(view, proj, true, znear, zfar, b);
    glm_vec3_negate_to(dir, b->light);
    b->texel[0] = (right - left) / (float)resolution;
    b->texel[1] = (top - bottom) / (float)resolution;
}

/* Perspective projection from the spot light covering its outer cone and reaching the
 * farthest corner of the scene bounds; its matrix also into proj_out. */
static void
fit_spot(const cg_scene *scene, const cg_light *light, int resolution, cg_shadow_block *b, mat4 proj_out)
{
    vec3 dir, up, eye, target;
    glm_vec3_normalize_to((float *)light->direction, dir);
    light_up_vector(dir, up);
    glm_vec3_copy((float *)light->position, eye);
    glm_vec3_add(eye, dir, target);
    float zfar = 0.0f;
    for (int i = 0; i < 8; i++) {
        vec3 c;
        bounds_corner(scene, i, c);
        zfar = fmaxf(zfar, glm_vec3_distance(eye, c));
    }
    zfar = zfar > 0.0f ? zfar * 1.01f : 1.0f;
    /* fp32 depth linearised in shadow.glsl keeps ~1e-4 relative precision at far/near = 1e4. */
    float znear = zfar * 1e-4f;
    float fov = spot_fov(light);
    mat4 view, proj;
    glm_lookat(eye, target, up, view);
    glm_perspective(fov, 1.0f, znear, zfar, proj);
    glm_mat4_copy(proj, proj_out);

    store_view(view, proj, false, znear, zfar, b);
    glm_vec3_copy(eye, b->light);
    b->texel[0] = b->texel[1] = 2.0f * tanf(0.5f * fov) / (float)resolution;
}

static bool
shadow_map_execute(fg_pass *pass, shadow_map_state *st, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    int index;
    if (!pick_light(pass, frame->scene, &index, err))
        return false;
    if (index < 0)
        return cg_fail(err, CG_ERR_PASS, "pass '%s': the scene lost its shadowed light", fg_pass_name(pass));
    const cg_light *light = &frame->scene->lights[index];
    bool masked = scene_has_mask(frame->scene);
    if (masked && !st->masked_program &&
        !cgp_graphics_program(st, "shadow_map/depth.vert", NULL, "shadow_map/mask.frag", "#define CG_SHADOW_MASK\n",
                              &st->masked_program, err))
        return false;
    int resolution = fg_param_int(pass, "resolution");
    static const int filter_radius[] = { [FILTER_NONE] = 0, [FILTER_PCF3] = 1, [FILTER_PCF5] = 2 };

    cg_shadow_block block;
    memset(&block, 0, sizeof block);
    mat4 proj;
    if (light->type == CG_LIGHT_DIRECTIONAL)
        fit_directional(frame->scene, light, resolution, &block, proj);
    else
        fit_spot(frame->scene, light, resolution, &block, proj);
    block.params[0] = fg_param_float(pass, "bias");
    block.params[1] = fg_param_float(pass, "slope_bias");
    block.params[2] = (float)filter_radius[fg_param_enum(pass, "filter")];
    block.params[3] = (float)resolution;
    block.frustum[0] = (float)index;
    glNamedBufferSubData(st->staging, 0, sizeof block, &block);
    glCopyNamedBufferSubData(st->staging, fg_slot_buffer(pass, st->matrix), 0, 0, sizeof block);

    GLuint depth = fg_slot_texture(pass, st->depth);
    if (st->cache) {
        const char *why = cgp_instances_changed(&st->instances, frame, CG_MESHES_ALL, "an instance changed");
        if (!why && memcmp(&block, &st->drawn_block, sizeof block))
            why = "light, fit or parameters changed";
        if (!why && (depth != st->drawn_depth || masked != st->drawn_masked))
            why = "storage or masking changed";
        if (!why) {
            fg_pass_report_rebuilt(pass, "depth kept (%llu draw%s since prepare)", (unsigned long long)st->draws,
                                   st->draws == 1 ? "" : "s");
            return true;
        }
        fg_pass_report_rebuilt(pass, "depth drawn (%s; %llu draw%s since prepare)", why,
                               (unsigned long long)st->draws + 1, st->draws == 0 ? "" : "s");
    } else {
        fg_pass_report_rebuilt(pass, "depth drawn (cache=false)");
    }

    glNamedFramebufferTexture(st->fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    cgp_depth_draw_begin(st->fbo, resolution, resolution);
    /* Occluders in front of the near plane still cast shadows. */
    glEnable(GL_DEPTH_CLAMP);
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(st->fbo, GL_DEPTH, 0, &far_depth);
    glUseProgram(masked ? st->masked_program : st->program);
    /* The view and the projection apart, not view_proj (shaders/shadow_map/depth.vert). */
    glUniformMatrix4fv(8, 1, GL_FALSE, block.view);
    glUniformMatrix4fv(12, 1, GL_FALSE, (const float *)proj);
    cg_gpu_scene_draw(frame->gpu_scene, CG_MESHES_ALL);
    glUseProgram(0);
    glDisable(GL_DEPTH_CLAMP);
    cgp_depth_draw_end();
    st->draws++;
    if (!st->cache)
        return true;
    st->drawn_block = block;
    st->drawn_depth = depth;
    st->drawn_masked = masked;
    return cgp_instances_remember(&st->instances, frame, CG_MESHES_ALL, err);
}

CGP_PASS(shadow_map, CGP_PARAMS(shadow_params),
         "Depth map of the scene from one directional light (orthographic, fitted to the "
         "scene bounds) or spot light (perspective over the outer cone), and the matrices "
         "and bias of its lookup (shaders/common/shadow.glsl) in the buffer `matrix`. "
         "Point lights are unshadowed. Nothing to do without a directional or spot light.");
