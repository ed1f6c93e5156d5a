/* passes/heightmap_raster: the height-field meshes rasterized from above into a 2D lightmap
 * (hybrid paper V.B, "multi-resolution sampling" of height-field meshes).
 *
 * Outputs
 *   lightmap  2D, resolution^2, RGBA32F (default) or RGBA16F, `levels` mip levels declared (0:
 *             the full chain; mip2d fills levels 1..): rgb = outgoing diffuse radiance of the direct light
 *             (shadowed through the optional shadow map) plus emission, a = height, world y.
 *             Texels no height-field mesh covers hold black radiance at the lowest height.
 *   region    std140 block CG_HEIGHTMAP_BLOCK (common/blocks.h) for common/heightmap.glsl:
 *             where the map lies and the scale that decodes its radiance.
 *   depth     the depth buffer of the raster (transient working memory, counted).
 * Inputs (optional, together): shadow (depth) and shadow_matrix (buffer) of a shadow_map pass.
 *
 * Radiance range: RGBA16F stores radiance / s, s = a bound on the height fields' radiance /
 * 32768 (sdk/radiance.h), published in the region block: neither 1e9 W/m^2 clips at 65504 nor
 * 1e-6 W/m^2 sinks into denormals. RGBA32F needs none (s = 1).
 *
 * Height precision: heights are stored as world y, not normalised. RGBA16F keeps 11
 * significant bits: on builtin:openworld (heights up to 30 m) that is 1.6 cm, but 16 m on a
 * terrain 30 km above sea level, and a mip level's average inherits the error; RGBA32F
 * keeps 24 bits (about 2 mm at 30 km), hence the default. A scene without height-field
 * meshes declares nothing to do, and the graph culls the whole 2D branch.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/blocks.h"
#include "sdk/pass.h"
#include "sdk/radiance.h"
#include "sdk/scene.h"
#include "sdk/shadow.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

enum { FORMAT_RGBA16F, FORMAT_RGBA32F };

static const fg_param_desc heightmap_params[] = {
    { .name = "resolution", .type = FG_PARAM_INT, .default_value = 1024, .min = 16, .max = 8192,
      .power_of_two = true,
      .doc = "texels per edge of the 2D lightmap at level 0" },
    { .name = "levels", .type = FG_PARAM_INT, .default_value = 0, .min = 0, .max = 14,
      .doc = "mip levels declared, from the finest (0: the full chain to 1 x 1); the paper's 2048^2 in 11 levels "
             "stops at 2 x 2" },
    { .name = "format", .type = FG_PARAM_ENUM, .default_value = FORMAT_RGBA32F, .choices = "rgba16f|rgba32f",
      .doc = "texel format; rgba32f keeps heights to 24 bits (rgba16f: 11 bits, centimetres at 30 m, metres at 10 km)" },
};

typedef struct heightmap_raster_state {
    GLuint program;
    GLuint fbo;
    cgp_no_shadow no_shadow;
    /* RGBA16F: per point/spot light, the nearest height-field surface (the radiance bound). */
    cgp_light_distances light_distances;
} heightmap_raster_state;

typedef struct heightmap_region {
    double lo[3], hi[3];    /* world bounds of the height-field instances */
} heightmap_region;

/* World bounds of the height-field instances; false when there is none or all lie in a
 * line or a point seen from above (no area to rasterize). */
static bool
heightfield_bounds(const cg_scene *scene, heightmap_region *out)
{
    bool any = cgp_mesh_bounds(scene, CG_MESHES_HEIGHTFIELD, out->lo, out->hi);
    return any && out->hi[0] > out->lo[0] && out->hi[2] > out->lo[2] &&
           isfinite(out->hi[0] - out->lo[0]) && isfinite(out->hi[2] - out->lo[2]);
}

static bool
heightmap_raster_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    int resolution = fg_param_int(pass, "resolution");
    int full = fg_mip_levels(resolution, resolution, 1), levels = fg_param_int(pass, "levels");
    if (!cgp_declare_shadow_inputs(pass, decl, err))
        return false;
    heightmap_region region;
    if (!heightfield_bounds(frame->scene, &region)) {
        fg_declare_nothing_to_do(decl, "the scene has no height-field mesh (with area seen from above)");
        return true;
    }
    fg_resource_desc lightmap = {
        .kind = FG_TEXTURE_2D,
        .format = fg_param_enum(pass, "format") == FORMAT_RGBA16F ? GL_RGBA16F : GL_RGBA32F,
        .width = resolution, .height = resolution, .depth = 1,
        .levels = levels > 0 && levels < full ? levels : full,
        .gi = true,
    };
    fg_declare_output(decl, "lightmap", &lightmap, FG_ACCESS_ATTACHMENT | FG_ACCESS_TRANSFER);
    fg_resource_desc block = cgp_buffer_desc(sizeof(cg_heightmap_block));
    fg_declare_output(decl, "region", &block, FG_ACCESS_TRANSFER);
    fg_resource_desc depth = cgp_image_2d(GL_DEPTH_COMPONENT32F, resolution, resolution);
    depth.gi = true;
    fg_declare_output(decl, "depth", &depth, FG_ACCESS_ATTACHMENT);
    return true;
}

static void
heightmap_raster_cleanup(void *state)
{
    heightmap_raster_state *s = state;
    cgp_light_distances_free(&s->light_distances);
}

static bool
heightmap_raster_prepare(fg_pass *pass, heightmap_raster_state *s, cg_error *err)
{
    (void)pass;
    cgp_state_on_destroy(s, heightmap_raster_cleanup);
    s->fbo = cgp_framebuffer(s);
    cgp_no_shadow_create(s, &s->no_shadow);
    return cgp_graphics_program(s, "heightmap_raster/raster.vert", NULL, "heightmap_raster/raster.frag", NULL,
                                &s->program, err);
}

static bool
heightmap_raster_execute(fg_pass *pass, heightmap_raster_state *s, cg_error *err)
{
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
     * uniform `top` stays above it) or of the map's width, whichever is larger: relative to
     * the scene, not 1e-6 m. */
    double dy = region.hi[1] - region.lo[1];
    double width = fmax(region.hi[0] - region.lo[0], region.hi[2] - region.lo[2]);
    double slack = fmax(0.01 * dy, 1e-6 * fmax(fabs(region.hi[1]), width));
    double top = region.hi[1] + slack, range = dy + 2.0 * slack;
    /* The pre-exposure of a half-float map; radiance is averaged over texels, so a point light
     * counts as never nearer than half a texel. */
    double radiance_scale = 1.0;
    if (desc->format == GL_RGBA16F) {
        double texel = fmax(region.hi[0] - region.lo[0], region.hi[2] - region.lo[2]) / resolution;
        double bound = 0.0;
        if (!cgp_radiance_bound(&s->light_distances, frame->scene, CG_MESHES_HEIGHTFIELD, 0.5 * texel, &bound, err))
            return false;
        radiance_scale = cgp_half_float_scale(bound);
    }

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
    glUniform1f(10, (float)radiance_scale);
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &s->no_shadow, 2);
    cg_gpu_scene_draw(frame->gpu_scene, CG_MESHES_HEIGHTFIELD);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(0);

    const cg_heightmap_block block = {
        .origin_texel = {(float)region.lo[0], (float)region.lo[2], (float)((region.hi[0] - region.lo[0]) / resolution),
                         (float)((region.hi[2] - region.lo[2]) / resolution)},
        .info = {(float)resolution, (float)desc->levels, (float)region.lo[1], (float)region.hi[1]},
        .radiance = {(float)radiance_scale, 0.0f, 0.0f, 0.0f},
    };
    glNamedBufferSubData(fg_buffer(pass, "region"), 0, sizeof block, &block);
    return true;
}

CGP_PASS(heightmap_raster, CGP_PARAMS(heightmap_params),
         "Rasterizes the scene's height-field meshes from above (orthographic, looking down -y) "
         "into a 2D lightmap over their xz bounds (hybrid paper V.B): rgb = outgoing diffuse "
         "radiance of the direct light, shadowed through the optional shadow map, plus emission; "
         "alpha = height (world y). Nothing to do for a scene without height-field meshes.");
