/* passes/heightmap_raster: the height-field meshes rasterized from above into a 2D lightmap
 * (hybrid paper V.B, "multi-resolution sampling" of height-field meshes).
 *
 * Outputs
 *   lightmap  2D, resolution^2, RGBA32F (default) or RGBA16F, `levels` mip levels declared (0:
 *             the full chain; mip2d fills levels 1..): rgb = outgoing diffuse radiance of the direct light
 *             (shadowed through the optional shadow map) plus emission, a = height, world y.
 *             Texels no height-field mesh covers hold black radiance at the lowest height; where a
 *             MASK material's alpha is below its alphaCutoff the mesh is not there (raster.frag).
 *   region    std140 block CG_HEIGHTMAP_BLOCK (common/blocks.h) for common/heightmap.glsl:
 *             where the map lies and the scale that decodes its radiance.
 *   depth     the depth buffer of the raster (transient working memory, counted).
 *   geometry_position, geometry_normal, geometry_albedo, geometry_emission (cache=true only)
 *             2D, resolution^2, RGBA32F, persistent: the surface attributes under each texel
 *             (shaders/heightmap_raster/raster.frag), kept across frames.
 * Inputs (optional, together): shadow (depth) and shadow_matrix (buffer) of a shadow_map pass.
 *
 * Caching (cache=true, the default): the texels are split into geometry and light. The
 * geometry (position, normal, albedo, emission of the surface under each texel) is rasterized
 * into persistent textures only when it may have changed: the first frame after prepare, or
 * when a height-field instance's world matrix, revision, mesh or material, the set of
 * instances, the scene, the GPU scene's upload (cg_gpu_scene.generation) or the map's region
 * differ from the last build, compared by value (a world changed by hand without a revision
 * still rebuilds; any doubt rebuilds). The light is computed by a compute pass over the texels
 * (relight.comp), at a cost that follows texels, not triangles, with the formula the lit raster
 * uses (common/surface_light.glsl) on the values it would use, so that a cached frame equals a
 * rebuilt one bit for bit. The lightmap is persistent too, and a frame relights only when something
 * the light reads changed since the last relight: the geometry (a rasterization), the lights or
 * the shadow map (sdk/shadow.h's lighting record), any instance (a shadow caster: sdk/instances.h
 * over every mesh), the radiance scale or the lightmap itself; a static frame dispatches nothing
 * and keeps the map (mip2d and hsat after it filter the same level 0 again). cache=false is the
 * paper's full rebuild: every frame rasterizes the meshes and lights them in the raster. The pass
 * says which it did through fg_pass_report_rebuilt.
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
#include "sdk/instances.h"
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
    { .name = "cache", .type = FG_PARAM_BOOL, .default_value = 1,
      .doc = "keep the rasterized geometry and the lightmap across frames, re-rasterize the geometry "
             "only when a height-field instance changed and relight the texels only when the geometry, "
             "the lights, an instance (a shadow caster) or the shadow map changed; false: rasterize "
             "and light everything every frame (the paper's rebuild)" },
};

/* The kept surface attributes (raster.frag with CG_HEIGHTMAP_GEOMETRY, colour attachments in
 * this order). */
static const char *const geometry_outputs[] = {
    "geometry_position", "geometry_normal", "geometry_albedo", "geometry_emission",
};
enum { GEOMETRY_TARGETS = 4 };

typedef struct heightmap_region {
    double lo[3], hi[3];    /* world bounds of the height-field instances */
} heightmap_region;

typedef struct heightmap_raster_state {
    bool cache;
    GLuint program;         /* cache=false: the lit raster; cache=true: the geometry raster */
    GLuint relight;         /* cache=true: relight.comp */
    GLuint fbo;
    cgp_no_shadow no_shadow;
    /* RGBA16F: per point/spot light, the nearest height-field surface (the radiance bound). */
    cgp_light_distances light_distances;

    /* cache=true: what the kept geometry was rasterized from (instances.taken = false: nothing yet). */
    cgp_instance_record instances;  /* the height-field instances (sdk/instances.h) */
    int resolution;
    heightmap_region region;
    uint64_t builds;        /* geometry rasterizations since prepare */
    /* cache=true: what the kept light was computed from (lit = false: nothing yet). */
    bool lit;
    cgp_instance_record casters;    /* every instance: the shadow map's casters */
    cgp_lighting_record lighting;   /* the lights and the shadow map (sdk/shadow.h) */
    GLuint lit_map;                 /* the lightmap's texture */
    double lit_scale;               /* the radiance scale */
    uint64_t relights;      /* relights since prepare */
    fg_slot lightmap, block, depth;
    fg_slot geometry[GEOMETRY_TARGETS]; /* cache=true */
} heightmap_raster_state;

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
    bool cache = fg_param_bool(pass, "cache");
    fg_resource_desc lightmap = {
        .kind = FG_TEXTURE_2D,
        .format = fg_param_enum(pass, "format") == FORMAT_RGBA16F ? GL_RGBA16F : GL_RGBA32F,
        .width = resolution, .height = resolution, .depth = 1,
        .levels = levels > 0 && levels < full ? levels : full,
        .gi = true,
    };
    /* Kept across frames with cache: a static frame does not relight it. */
    lightmap.persistent = cache;
    fg_declare_output(decl, "lightmap", &lightmap,
                      cache ? FG_ACCESS_IMAGE_STORE : FG_ACCESS_ATTACHMENT | FG_ACCESS_TRANSFER);
    if (cache) {
        /* Kept across frames: persistent storage is never pooled, so nothing else writes it
         * between two frames. RGBA32F so that the relight sees the very values the lit
         * raster would compute with. */
        fg_resource_desc geometry = cgp_image_2d(GL_RGBA32F, resolution, resolution);
        geometry.persistent = true;
        geometry.gi = true;
        for (int i = 0; i < GEOMETRY_TARGETS; i++)
            fg_declare_output(decl, geometry_outputs[i], &geometry, FG_ACCESS_ATTACHMENT | FG_ACCESS_TRANSFER);
    }
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
    cgp_instance_record_free(&s->instances);
    cgp_instance_record_free(&s->casters);
    cgp_lighting_record_free(&s->lighting);
}

static bool
heightmap_raster_prepare(fg_pass *pass, heightmap_raster_state *s, cg_error *err)
{
    cgp_state_on_destroy(s, heightmap_raster_cleanup);
    s->cache = fg_param_bool(pass, "cache");
    s->lightmap = fg_pass_slot(pass, "lightmap");
    s->block = fg_pass_slot(pass, "region");
    s->depth = fg_pass_slot(pass, "depth");
    for (int i = 0; i < GEOMETRY_TARGETS && s->cache; i++)
        s->geometry[i] = fg_pass_slot(pass, geometry_outputs[i]);
    s->fbo = cgp_framebuffer(s);
    cgp_no_shadow_create(s, pass, &s->no_shadow);
    if (!s->cache)
        return cgp_graphics_program(s, "heightmap_raster/raster.vert", NULL, "heightmap_raster/raster.frag", NULL,
                                    &s->program, err);
    const fg_resource_desc *desc = fg_slot_resource(pass, s->lightmap);
    char defines[64];
    snprintf(defines, sizeof defines, "#define LIGHTMAP_FORMAT %s\n",
             desc && desc->format == GL_RGBA16F ? "rgba16f" : "rgba32f");
    return cgp_graphics_program(s, "heightmap_raster/raster.vert", NULL, "heightmap_raster/raster.frag",
                                "#define CG_HEIGHTMAP_GEOMETRY\n", &s->program, err) &&
           cgp_compute_program(s, "heightmap_raster/relight.comp", defines, &s->relight, err);
}

/* Why the kept geometry must be rasterized again this frame, or NULL when it is up to date.
 * Any doubt rebuilds: what is compared is everything the geometry raster reads. */
static const char *
geometry_stale(const heightmap_raster_state *s, const fg_frame *frame, const heightmap_region *region,
               int resolution)
{
    const char *why =
        cgp_instances_changed(&s->instances, frame, CG_MESHES_HEIGHTFIELD, "a height-field instance changed");
    if (why)
        return why;
    if (resolution != s->resolution || memcmp(region, &s->region, sizeof *region))
        return "region moved";
    return NULL;
}

/* Records what the geometry was rasterized from. */
static bool
remember_build(heightmap_raster_state *s, const fg_frame *frame, const heightmap_region *region, int resolution,
               cg_error *err)
{
    s->resolution = resolution;
    s->region = *region;
    return cgp_instances_remember(&s->instances, frame, CG_MESHES_HEIGHTFIELD, err);
}

/* Rasterizes the height-field meshes from above into the framebuffer as attached: the lit
 * texels (cache=false) or the surface attributes (cache=true), after clearing to `clears`. */
static void
raster(const fg_pass *pass, heightmap_raster_state *s, const heightmap_region *region, int resolution,
       double radiance_scale, const float (*clears)[4], int targets)
{
    const fg_frame *frame = fg_pass_frame(pass);
    /* Depth: 0 at the top of the bounds, 1 at the bottom, with 1% slack on each side so
     * that the highest and lowest vertices are not clipped. A flat height field has no
     * extent: the slack is then 1e-6 of its height (well above a float's 6e-8 ulp, so the
     * uniform `top` stays above it) or of the map's width, whichever is larger: relative to
     * the scene, not 1e-6 m. */
    double dy = region->hi[1] - region->lo[1];
    double width = fmax(region->hi[0] - region->lo[0], region->hi[2] - region->lo[2]);
    double slack = fmax(0.01 * dy, 1e-6 * fmax(fabs(region->hi[1]), width));
    double top = region->hi[1] + slack, range = dy + 2.0 * slack;

    const float clear_depth = 1.0f;
    for (int i = 0; i < targets; i++)
        glClearNamedFramebufferfv(s->fbo, GL_COLOR, i, clears[i]);
    glClearNamedFramebufferfv(s->fbo, GL_DEPTH, 0, &clear_depth);

    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    cgp_depth_draw_begin(s->fbo, resolution, resolution);
    glDisable(GL_BLEND);

    glUseProgram(s->program);
    glUniform4f(8, (float)region->lo[0], (float)region->lo[2], (float)(1.0 / (region->hi[0] - region->lo[0])),
                (float)(1.0 / (region->hi[2] - region->lo[2])));
    glUniform2f(9, (float)top, (float)(1.0 / range));
    if (!s->cache) {
        glUniform1f(10, (float)radiance_scale);
        cg_gpu_scene_bind_lights(frame->gpu_scene);
        cgp_bind_shadow(pass, &s->no_shadow, 2);
    }
    cg_gpu_scene_draw(frame->gpu_scene, CG_MESHES_HEIGHTFIELD);
    cgp_depth_draw_end();
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glUseProgram(0);
}

static bool
framebuffer_complete(const fg_pass *pass, const heightmap_raster_state *s, cg_error *err)
{
    if (glCheckNamedFramebufferStatus(s->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return cg_fail(err, CG_ERR_GL, "pass '%s': lightmap framebuffer incomplete", fg_pass_name(pass));
    return true;
}

/* Why the kept light must be computed again (NULL: nothing it reads changed since the last relight):
 * `geometry` says why the geometry was rasterized this frame, if it was; `lighting` is this
 * frame's lights and shadow map. */
static const char *
light_stale(const fg_pass *pass, const heightmap_raster_state *s, const char *geometry,
            const cgp_lighting_record *lighting, double radiance_scale)
{
    if (!s->lit)
        return "first frame";
    if (geometry)
        return "geometry rasterized";
    const char *why = cgp_instances_changed(&s->casters, fg_pass_frame(pass), CG_MESHES_ALL, "an instance changed");
    if (why)
        return why;
    switch (cgp_lighting_changed(&s->lighting, lighting)) {
    case CGP_LIGHTING_LIGHTS:
        return "lights changed";
    case CGP_LIGHTING_SHADOW:
        return "shadow map changed";
    case CGP_LIGHTING_SAME:
        break;
    }
    if (fg_slot_texture(pass, s->lightmap) != s->lit_map || radiance_scale != s->lit_scale)
        return "lightmap or radiance scale changed";
    return NULL;
}

/* Records what the light was computed from; on failure nothing is recorded (the next frame relights). */
static bool
remember_light(const fg_pass *pass, heightmap_raster_state *s, const cgp_lighting_record *lighting,
               double radiance_scale, cg_error *err)
{
    s->lit = false;
    if (!cgp_lighting_remember(&s->lighting, lighting, err) ||
        !cgp_instances_remember(&s->casters, fg_pass_frame(pass), CG_MESHES_ALL, err))
        return false;
    s->lit_map = fg_slot_texture(pass, s->lightmap);
    s->lit_scale = radiance_scale;
    s->lit = true;
    return true;
}

/* cache=true: rasterizes the surface attributes when they may have changed, then relights
 * every texel when the light may have changed. */
static bool
execute_cached(fg_pass *pass, heightmap_raster_state *s, const heightmap_region *region, int resolution,
               double radiance_scale, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    const char *why = geometry_stale(s, frame, region, resolution);
    if (why) {
        static const GLenum buffers[GEOMETRY_TARGETS] = {
            GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3,
        };
        for (int i = 0; i < GEOMETRY_TARGETS; i++)
            glNamedFramebufferTexture(s->fbo, buffers[i], fg_slot_texture(pass, s->geometry[i]), 0);
        glNamedFramebufferTexture(s->fbo, GL_DEPTH_ATTACHMENT, fg_slot_texture(pass, s->depth), 0);
        glNamedFramebufferDrawBuffers(s->fbo, GEOMETRY_TARGETS, buffers);
        if (!framebuffer_complete(pass, s, err))
            return false;
        /* Texels no mesh covers: position.w = 0 (the relight writes black at the lowest height). */
        static const float zero[GEOMETRY_TARGETS][4] = {{0.0f}};
        raster(pass, s, region, resolution, radiance_scale, zero, GEOMETRY_TARGETS);
        if (!remember_build(s, frame, region, resolution, err))
            return false;
        s->builds++;
    }

    cgp_lighting_record lighting;
    cgp_lighting_read(pass, &s->no_shadow, &lighting);
    const char *relight = light_stale(pass, s, why, &lighting, radiance_scale);
    if (!relight) {
        fg_pass_report_rebuilt(pass, "geometry kept; light kept (%llu geometry build%s, %llu relight%s since prepare)",
                               (unsigned long long)s->builds, s->builds == 1 ? "" : "s",
                               (unsigned long long)s->relights, s->relights == 1 ? "" : "s");
        return true;
    }
    glUseProgram(s->relight);
    glUniform1f(10, (float)radiance_scale);
    glUniform1f(11, (float)region->lo[1]);
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &s->no_shadow, 2);
    for (int i = 0; i < GEOMETRY_TARGETS; i++)
        glBindTextureUnit(3 + (GLuint)i, fg_slot_texture(pass, s->geometry[i]));
    const fg_resource_desc *desc = fg_slot_resource(pass, s->lightmap);
    glBindImageTexture(0, fg_slot_texture(pass, s->lightmap), 0, GL_FALSE, 0, GL_WRITE_ONLY, desc->format);
    /* The geometry raster's attachments are read as textures right after: framebuffer writes
     * are visible to later commands without a barrier. */
    cgp_dispatch_2d(resolution, resolution);
    for (int i = 0; i < GEOMETRY_TARGETS; i++)
        glBindTextureUnit(3 + (GLuint)i, 0);
    glUseProgram(0);

    s->relights++;
    fg_pass_report_rebuilt(pass, "geometry %s%s%s; light %d texels relit (%s; %llu geometry build%s since prepare)",
                           why ? "rasterized (" : "kept", why ? why : "", why ? ")" : "",
                           resolution * resolution, relight, (unsigned long long)s->builds, s->builds == 1 ? "" : "s");
    return remember_light(pass, s, &lighting, radiance_scale, err);
}

static bool
heightmap_raster_execute(fg_pass *pass, heightmap_raster_state *s, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    heightmap_region region;
    if (!heightfield_bounds(frame->scene, &region))
        return cg_fail(err, CG_ERR_PASS, "pass '%s': the height-field meshes vanished since compile",
                       fg_pass_name(pass));
    const fg_resource_desc *desc = fg_slot_resource(pass, s->lightmap);
    int resolution = desc->width;
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

    if (s->cache) {
        if (!execute_cached(pass, s, &region, resolution, radiance_scale, err))
            return false;
    } else {
        glNamedFramebufferTexture(s->fbo, GL_COLOR_ATTACHMENT0, fg_slot_texture(pass, s->lightmap), 0);
        glNamedFramebufferTexture(s->fbo, GL_DEPTH_ATTACHMENT, fg_slot_texture(pass, s->depth), 0);
        glNamedFramebufferDrawBuffer(s->fbo, GL_COLOR_ATTACHMENT0);
        if (!framebuffer_complete(pass, s, err))
            return false;
        /* Texels no mesh covers: no radiance, at the lowest height (nothing rises there). */
        const float clear[1][4] = {{0.0f, 0.0f, 0.0f, (float)region.lo[1]}};
        raster(pass, s, &region, resolution, radiance_scale, clear, 1);
        fg_pass_report_rebuilt(pass, "geometry and light rasterized (cache=false)");
    }

    const cg_heightmap_block block = {
        .origin_texel = {(float)region.lo[0], (float)region.lo[2], (float)((region.hi[0] - region.lo[0]) / resolution),
                         (float)((region.hi[2] - region.lo[2]) / resolution)},
        .info = {(float)resolution, (float)desc->levels, (float)region.lo[1], (float)region.hi[1]},
        .radiance = {(float)radiance_scale, 0.0f, 0.0f, 0.0f},
    };
    glNamedBufferSubData(fg_slot_buffer(pass, s->block), 0, sizeof block, &block);
    return true;
}

CGP_PASS(heightmap_raster, CGP_PARAMS(heightmap_params),
         "Rasterizes the scene's height-field meshes from above (orthographic, looking down -y) "
         "into a 2D lightmap over their xz bounds (hybrid paper V.B): rgb = outgoing diffuse "
         "radiance of the direct light, shadowed through the optional shadow map, plus emission; "
         "alpha = height (world y). With cache=true the meshes' surface attributes are kept across "
         "frames, re-rasterized only when a height-field instance changed, and relit by a compute "
         "pass over the texels when the geometry, the lights, an instance (a shadow caster) or the "
         "shadow map changed (a static frame keeps the map); cache=false rasterizes and lights everything every "
         "frame. Nothing to do for a scene without height-field meshes.");
