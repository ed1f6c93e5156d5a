/* passes/heightmap_raster: the height-field meshes rasterized from above into a 2D lightmap
 * (hybrid paper V.B, "multi-resolution sampling" of height-field meshes).
 *
 * Outputs
 *   lightmap  2D, resolution^2, RGBA32F (default) or RGBA16F, full mip chain declared (mip2d
 *             fills levels 1..): rgb = outgoing diffuse radiance of the direct light
 *             (shadowed through the optional shadow map) plus emission, a = height, world y.
 *             Texels no height-field mesh covers hold black radiance at the lowest height.
 *   region    48-byte std140 block for shaders/common/heightmap.glsl: where the map lies.
 *   depth     the depth buffer of the raster (transient working memory, counted).
 * Inputs (optional, together): shadow (depth) and shadow_matrix (buffer) of a shadow_map pass.
 *
 * Height precision: heights are stored as world y, not normalised. RGBA16F keeps 11
 * significant bits: on builtin:openworld (heights up to 30 m) that is 1.6 cm, but 16 m on a
 * terrain 30 km above sea level, and a mip level's average inherits the error; RGBA32F
 * keeps 24 bits (about 2 mm at 30 km), hence the default. A scene without height-field
 * meshes declares nothing to do, and the graph culls the whole 2D branch.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

#define REGION_BYTES 48

enum { FORMAT_RGBA16F, FORMAT_RGBA32F };

static const fg_param_desc heightmap_params[] = {
    { .name = "resolution", .type = FG_PARAM_INT, .default_value = 1024, .min = 16, .max = 8192,
      .power_of_two = true,
      .doc = "texels per edge of the 2D lightmap at level 0" },
    { .name = "format", .type = FG_PARAM_ENUM, .default_value = FORMAT_RGBA32F, .choices = "rgba16f|rgba32f",
      .doc = "texel format; rgba32f keeps heights to 24 bits (rgba16f: 11 bits, centimetres at 30 m, metres at 10 km)" },
};

typedef struct heightmap_state {
    GLuint program;
    GLuint fbo;
} heightmap_state;

typedef struct heightmap_region {
    double lo[3], hi[3];    /* world bounds of the height-field instances */
} heightmap_region;

static void
transform_point(const float m[16], const float p[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

/* World bounds of the height-field instances; false when there is none or all lie in a
 * line or a point seen from above (no area to rasterize). */
static bool
heightfield_bounds(const cg_scene *scene, heightmap_region *out)
{
    bool any = false;
    for (int k = 0; k < 3; k++)
        out->lo[k] = DBL_MAX, out->hi[k] = -DBL_MAX;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_instance *inst = &scene->instances[i];
        const cg_mesh *mesh = &scene->meshes[inst->mesh];
        if (mesh->kind != CG_MESH_HEIGHTFIELD || mesh->index_count == 0)
            continue;
        if (inst->moving) {
            /* Its box over the whole animation, so that the map stays put from frame to frame. */
            for (int k = 0; k < 3; k++) {
                out->lo[k] = fmin(out->lo[k], inst->motion_min[k]);
                out->hi[k] = fmax(out->hi[k], inst->motion_max[k]);
            }
            any = true;
            continue;
        }
        for (int c = 0; c < 8; c++) {
            float corner[3] = {
                (c & 1) ? mesh->bounds_max[0] : mesh->bounds_min[0],
                (c & 2) ? mesh->bounds_max[1] : mesh->bounds_min[1],
                (c & 4) ? mesh->bounds_max[2] : mesh->bounds_min[2],
            };
            double w[3];
            transform_point(inst->world, corner, w);
            for (int k = 0; k < 3; k++) {
                out->lo[k] = fmin(out->lo[k], w[k]);
                out->hi[k] = fmax(out->hi[k], w[k]);
            }
        }
        any = true;
    }
    return any && out->hi[0] > out->lo[0] && out->hi[2] > out->lo[2] &&
           isfinite(out->hi[0] - out->lo[0]) && isfinite(out->hi[2] - out->lo[2]);
}

static bool
heightmap_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    int resolution = fg_param_int(pass, "resolution");
    const fg_resource_desc *shadow = fg_declare_input(decl, "shadow", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    const fg_resource_desc *matrix = fg_declare_input(decl, "shadow_matrix", FG_BUFFER, FG_ACCESS_UNIFORM, false);
    if (!shadow != !matrix)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': inputs 'shadow' and 'shadow_matrix' go together (a shadow_map "
                       "pass's outputs 'depth' and 'matrix'); only one is present", fg_pass_name(pass));
    if (shadow && shadow->format != GL_DEPTH_COMPONENT32F)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'shadow' must be a GL_DEPTH_COMPONENT32F shadow map", fg_pass_name(pass));
    if (matrix && matrix->buffer_bytes < CG_SHADOW_BLOCK_BYTES)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'shadow_matrix' holds %zu bytes, a shadow_map 'matrix' %d",
                       fg_pass_name(pass), matrix->buffer_bytes, CG_SHADOW_BLOCK_BYTES);
    heightmap_region region;
    if (!heightfield_bounds(frame->scene, &region)) {
        fg_declare_nothing_to_do(decl, "the scene has no height-field mesh (with area seen from above)");
        return true;
    }
    fg_resource_desc lightmap = {
        .kind = FG_TEXTURE_2D,
        .format = fg_param_enum(pass, "format") == FORMAT_RGBA16F ? GL_RGBA16F : GL_RGBA32F,
        .width = resolution, .height = resolution, .depth = 1,
        .levels = fg_mip_levels(resolution, resolution, 1),
        .gi = true,
    };
    fg_declare_output(decl, "lightmap", &lightmap, FG_ACCESS_ATTACHMENT | FG_ACCESS_TRANSFER);
    fg_resource_desc block = {.kind = FG_BUFFER, .depth = 1, .levels = 1, .buffer_bytes = REGION_BYTES};
    fg_declare_output(decl, "region", &block, FG_ACCESS_TRANSFER);
    fg_resource_desc depth = {
        .kind = FG_TEXTURE_2D, .format = GL_DEPTH_COMPONENT32F,
        .width = resolution, .height = resolution, .depth = 1, .levels = 1, .gi = true,
    };
    fg_declare_output(decl, "depth", &depth, FG_ACCESS_ATTACHMENT);
    return true;
}

static bool
heightmap_prepare(fg_pass *pass, void **state, cg_error *err)
{
    heightmap_state *s = calloc(1, sizeof *s);
    if (!s)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "pass '%s': out of memory", fg_pass_name(pass));
    if (!cg_program_graphics("heightmap_raster/raster.vert", NULL, "heightmap_raster/raster.frag", NULL,
                             &s->program, err)) {
        free(s);
        return false;
    }
    glCreateFramebuffers(1, &s->fbo);
    *state = s;
    return true;
}

static bool
heightmap_execute(fg_pass *pass, void *state, cg_error *err)
{
    heightmap_state *s = state;
    const fg_frame *frame = fg_pass_frame(pass);
    heightmap_region region;
    if (!heightfield_bounds(frame->scene, &region))
        return cg_fail(err, CG_ERR_PASS, "pass '%s': the height-field meshes vanished since compile",
                       fg_pass_name(pass));
    const fg_resource_desc *desc = fg_resource(pass, "lightmap");
    int resolution = desc->width;
    GLuint lightmap = fg_texture(pass, "lightmap");
    /* Depth: 0 at the top of the bounds, 1 at the bottom, with 1% slack on each side so
     * that the highest and lowest vertices are not clipped. A flat height field has no
     * extent: the slack is then 1e-6 of its height (well above a float's 6e-8 ulp, so the
     * uniform `top` stays above it) or 1e-6 m. */
    double dy = region.hi[1] - region.lo[1];
    double slack = fmax(0.01 * dy, 1e-6 * fmax(fabs(region.hi[1]), 1.0));
    double top = region.hi[1] + slack, range = dy + 2.0 * slack;

    glNamedFramebufferTexture(s->fbo, GL_COLOR_ATTACHMENT0, lightmap, 0);
    glNamedFramebufferTexture(s->fbo, GL_DEPTH_ATTACHMENT, fg_texture(pass, "depth"), 0);
    glNamedFramebufferDrawBuffer(s->fbo, GL_COLOR_ATTACHMENT0);
    if (glCheckNamedFramebufferStatus(s->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return cg_fail(err, CG_ERR_GL, "pass '%s': lightmap framebuffer incomplete", fg_pass_name(pass));
    /* Texels no mesh covers: no radiance, at the lowest height (nothing rises there). */
    const float clear[4] = {0.0f, 0.0f, 0.0f, (float)region.lo[1]};
    const float clear_depth = 1.0f;
    glClearNamedFramebufferfv(s->fbo, GL_COLOR, 0, clear);
    glClearNamedFramebufferfv(s->fbo, GL_DEPTH, 0, &clear_depth);

    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glViewport(0, 0, resolution, resolution);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);

    glUseProgram(s->program);
    glUniform4f(8, (float)region.lo[0], (float)region.lo[2], (float)(1.0 / (region.hi[0] - region.lo[0])),
                (float)(1.0 / (region.hi[2] - region.lo[2])));
    glUniform2f(9, (float)top, (float)(1.0 / range));
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cg_gpu_scene_bind_shadow(frame->gpu_scene, fg_texture(pass, "shadow"), fg_buffer(pass, "shadow_matrix"), 2);
    cg_gpu_scene_draw(frame->gpu_scene, CG_MESHES_HEIGHTFIELD);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(0);

    const float block[REGION_BYTES / 4] = {
        (float)region.lo[0], (float)region.lo[2],
        (float)((region.hi[0] - region.lo[0]) / resolution), (float)((region.hi[2] - region.lo[2]) / resolution),
        (float)resolution, (float)desc->levels, (float)region.lo[1], (float)region.hi[1],
        0.0f, 0.0f, 0.0f, 0.0f,
    };
    glNamedBufferSubData(fg_buffer(pass, "region"), 0, sizeof block, block);
    return true;
}

static void
heightmap_destroy(void *state)
{
    heightmap_state *s = state;
    if (!s)
        return;
    glDeleteProgram(s->program);
    glDeleteFramebuffers(1, &s->fbo);
    free(s);
}

static const fg_pass_type heightmap_type = {
    .abi_version = FG_ABI_VERSION,
    .name = "heightmap_raster",
    .doc = "Rasterizes the scene's height-field meshes from above (orthographic, looking down -y) "
           "into a 2D lightmap over their xz bounds (hybrid paper V.B): rgb = outgoing diffuse "
           "radiance of the direct light, shadowed through the optional shadow map, plus emission; "
           "alpha = height (world y). Nothing to do for a scene without height-field meshes.",
    .params = heightmap_params,
    .param_count = (int)(sizeof heightmap_params / sizeof heightmap_params[0]),
    .declare = heightmap_declare,
    .prepare = heightmap_prepare,
    .execute = heightmap_execute,
    .destroy = heightmap_destroy,
};

bool
cg_pass_register_heightmap_raster(fg_registry *registry, uint32_t host_abi, cg_error *err)
{
    if (host_abi != FG_ABI_VERSION)
        return cg_fail(err, CG_ERR_PLUGIN_ABI, "pass heightmap_raster: built for frame-graph ABI %u, host has %u",
                       FG_ABI_VERSION, host_abi);
    return fg_registry_add(registry, &heightmap_type, err);
}
