/* passes/voxelize: the scene's direct light voxelized into a 3D lightmap (VCT paper 3.1).
 *
 * Outputs
 *   radiance      3D, resolution^3, RGBA16F or RGBA8, full mip chain declared (mip3d fills
 *                 levels 1..): premultiplied outgoing diffuse radiance (direct light, shadowed
 *                 through the optional shadow map, plus emission) and opacity in alpha.
 *   region        std140 block CG_VOLUME_BLOCK (common/blocks.h) for common/volume.glsl: where
 *                 the volume lies and how its values decode (consumers bind it at CG_BINDING_VOLUME).
 *   accumulation  3D R32UI, resolution^2 x 4 resolution: the fixed-point sums and counts of
 *                 the fragments (shaders/voxelize/voxelize.frag), transient working memory,
 *                 declared so that the memory report counts it.
 * Inputs (optional, together): shadow (depth) and shadow_matrix (buffer) of a shadow_map pass.
 *
 * Cleared and rebuilt every frame, so the lightmap follows moving lights and geometry.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sdk/blocks.h"
#include "sdk/pass.h"
#include "sdk/radiance.h"
#include "sdk/scene.h"
#include "sdk/shadow.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

/* Fragments of the brightest radiance that one voxel can sum without overflowing 32 bits. */
#define FRAGMENT_HEADROOM 1024.0

enum { FORMAT_RGBA8, FORMAT_RGBA16F };
enum { REGION_MESHES, REGION_SCENE, REGION_EXPLICIT };

static const fg_param_desc voxelize_params[] = {
    { .name = "resolution", .type = FG_PARAM_INT, .default_value = 128, .min = 16, .max = 512,
      .power_of_two = true,
      .doc = "voxels per edge of the cubic volume at level 0" },
    { .name = "format", .type = FG_PARAM_ENUM, .default_value = FORMAT_RGBA16F, .choices = "rgba8|rgba16f",
      .doc = "texel format: rgba8 as in the VCT paper (radiance over the volume's maximum) or rgba16f" },
    { .name = "meshes", .type = FG_PARAM_ENUM, .default_value = CG_MESHES_ALL, .choices = "all|complex|heightfield",
      .doc = "which meshes to voxelize (the hybrid method voxelizes only complex meshes)" },
    { .name = "region", .type = FG_PARAM_ENUM, .default_value = REGION_MESHES, .choices = "meshes|scene|explicit",
      .doc = "volume bounds: the voxelized meshes' bounds, the whole scene's, or min_*/max_*" },
    { .name = "min_x", .type = FG_PARAM_FLOAT, .default_value = -1, .min = -1e9, .max = 1e9,
      .active_when = "region=explicit",
      .doc = "explicit region: minimum x (m)" },
    { .name = "min_y", .type = FG_PARAM_FLOAT, .default_value = -1, .min = -1e9, .max = 1e9,
      .active_when = "region=explicit",
      .doc = "explicit region: minimum y (m)" },
    { .name = "min_z", .type = FG_PARAM_FLOAT, .default_value = -1, .min = -1e9, .max = 1e9,
      .active_when = "region=explicit",
      .doc = "explicit region: minimum z (m)" },
    { .name = "max_x", .type = FG_PARAM_FLOAT, .default_value = 1, .min = -1e9, .max = 1e9,
      .active_when = "region=explicit", .greater_than = { .param = "min_x" },
      .doc = "explicit region: maximum x (m)" },
    { .name = "max_y", .type = FG_PARAM_FLOAT, .default_value = 1, .min = -1e9, .max = 1e9,
      .active_when = "region=explicit", .greater_than = { .param = "min_y" },
      .doc = "explicit region: maximum y (m)" },
    { .name = "max_z", .type = FG_PARAM_FLOAT, .default_value = 1, .min = -1e9, .max = 1e9,
      .active_when = "region=explicit", .greater_than = { .param = "min_z" },
      .doc = "explicit region: maximum z (m)" },
    { .name = "padding", .type = FG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 16,
      .less_than = { .param = "resolution", .scale = 0.25 },
      .doc = "empty voxels added on each side of the bounds, so that surfaces on them lie inside; "
             "the scene keeps at least half the volume's edge" },
    { .name = "conservative", .type = FG_PARAM_BOOL, .default_value = 1,
      .doc = "every voxel a triangle touches (dilation + exact overlap test); false: one voxel per "
             "covered pixel centre, as plain rasterization gives (leaves holes)" },
};

typedef struct voxelize_state {
    GLuint program;
    GLuint resolve;
    GLuint find_max;        /* RGBA8 only: the largest radiance, for the stored scale */
    GLuint max_buffer;
    GLuint fbo;
    cgp_no_shadow no_shadow;
    GLenum format;
    /* Nearest-surface distance per point/spot light, recomputed when a light moves. */
    cgp_light_distances light_distances;
} voxelize_state;

/* Where the volume lies: a cube. */
typedef struct voxel_region {
    double origin[3];
    double voxel;
} voxel_region;

/* The cube the volume covers; false when there is nothing to voxelize. The parameters met
 * their table (max_* > min_*, padding below a quarter of the resolution) before declare(). */
static bool
voxelize_region(const fg_pass *pass, const cg_scene *scene, voxel_region *out)
{
    int mode = fg_param_enum(pass, "region");
    cg_mesh_filter filter = (cg_mesh_filter)fg_param_enum(pass, "meshes");
    int resolution = fg_param_int(pass, "resolution");
    double padding = fg_param_float(pass, "padding");
    double lo[3], hi[3];
    bool has = cgp_mesh_bounds(scene, filter, lo, hi);
    if (mode == REGION_SCENE) {
        for (int k = 0; k < 3; k++)
            lo[k] = scene->bounds_min[k], hi[k] = scene->bounds_max[k];
    } else if (mode == REGION_EXPLICIT) {
        static const char *const mins[3] = {"min_x", "min_y", "min_z"};
        static const char *const maxs[3] = {"max_x", "max_y", "max_z"};
        for (int k = 0; k < 3; k++) {
            lo[k] = fg_param_float(pass, mins[k]);
            hi[k] = fg_param_float(pass, maxs[k]);
        }
    }
    if (!has)
        return false;
    double extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    if (!(extent > 0.0) || !isfinite(extent)) {
        return false;   /* all geometry in one point: no surface to voxelize */
    }
    /* Cubic voxels (VCT paper 3.1: the texture must be cubic); the padding is in voxels. */
    double side = extent * resolution / (resolution - 2.0 * padding);
    out->voxel = side / resolution;
    for (int k = 0; k < 3; k++)
        out->origin[k] = 0.5 * (lo[k] + hi[k]) - 0.5 * side;
    return true;
}

static bool
voxelize_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    int resolution = fg_param_int(pass, "resolution");
    if (!cgp_declare_shadow_inputs(pass, decl, err))
        return false;

    voxel_region region;
    if (!voxelize_region(pass, frame->scene, &region)) {
        fg_declare_nothing_to_do(decl, "no mesh passes the 'meshes' filter (or all are degenerate)");
        return true;
    }
    fg_resource_desc radiance = {
        .kind = FG_TEXTURE_3D,
        .format = fg_param_enum(pass, "format") == FORMAT_RGBA8 ? GL_RGBA8 : GL_RGBA16F,
        .width = resolution, .height = resolution, .depth = resolution,
        .levels = fg_mip_levels(resolution, resolution, resolution),
        .gi = true,
    };
    fg_declare_output(decl, "radiance", &radiance, FG_ACCESS_IMAGE_STORE);
    fg_resource_desc block = cgp_buffer_desc(sizeof(cg_volume_block));
    fg_declare_output(decl, "region", &block, FG_ACCESS_TRANSFER | FG_ACCESS_STORAGE);
    fg_resource_desc accumulation = {
        .kind = FG_TEXTURE_3D, .format = GL_R32UI,
        .width = resolution, .height = resolution, .depth = 4 * resolution, .levels = 1,
        .gi = true,
    };
    fg_declare_output(decl, "accumulation", &accumulation, FG_ACCESS_IMAGE_STORE | FG_ACCESS_TRANSFER);
    return true;
}

/* What the state holds beside its GL objects: the light cache of cgp_radiance_bound(). */
static void
voxelize_cleanup(void *state)
{
    voxelize_state *s = state;
    cgp_light_distances_free(&s->light_distances);
}

static bool
voxelize_prepare(fg_pass *pass, voxelize_state *s, cg_error *err)
{
    cgp_state_on_destroy(s, voxelize_cleanup);
    s->format = fg_resource(pass, "radiance")->format;
    char defines[64];
    snprintf(defines, sizeof defines, "#define FORMAT %s\n", s->format == GL_RGBA8 ? "rgba8" : "rgba16f");
    s->max_buffer = cgp_buffer(s, sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    s->fbo = cgp_framebuffer(s);
    cgp_no_shadow_create(s, &s->no_shadow);
    return cgp_graphics_program(s, "voxelize/voxelize.vert", "voxelize/voxelize.geom", "voxelize/voxelize.frag", NULL,
                                &s->program, err) &&
           cgp_compute_program(s, "voxelize/resolve.comp", defines, &s->resolve, err) &&
           (s->format != GL_RGBA8 || cgp_compute_program(s, "voxelize/resolve.comp",
                                                         "#define FORMAT rgba8\n#define FIND_MAX\n", &s->find_max, err));
}

static bool
voxelize_execute(fg_pass *pass, voxelize_state *s, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    const cg_scene *scene = frame->scene;
    cg_mesh_filter filter = (cg_mesh_filter)fg_param_enum(pass, "meshes");
    int resolution = fg_param_int(pass, "resolution");
    voxel_region region;
    if (!voxelize_region(pass, scene, &region))
        return cg_fail(err, CG_ERR_PASS, "pass '%s': the voxelized meshes vanished since compile", fg_pass_name(pass));
    /* Radiance is averaged over voxels: a point light is never nearer than half a voxel. */
    double bound = 0.0;
    if (!cgp_radiance_bound(&s->light_distances, scene, filter, 0.5 * region.voxel, &bound, err))
        return false;
    /* Fixed point: FRAGMENT_HEADROOM fragments at the bound sum to 2^32, so its precision is
     * bound / 2^22 at any brightness. RGBA16F stores radiance / (bound / 32768) (sdk/radiance.h),
     * so that neither 1e9 W/m^2 clips at 65504 nor 1e-6 W/m^2 sinks into denormals and zero, and
     * a scene k times brighter stores the same values; RGBA8 stores radiance / (the largest radiance in
     * the volume), found on the GPU by a first resolve dispatch. Both publish their scale in the
     * region block. A scene with no light and no emission is black. */
    double fixed_scale = bound > 0.0 ? 4294967295.0 / (bound * FRAGMENT_HEADROOM) : 1.0;
    double radiance_scale = s->format != GL_RGBA8 ? cgp_half_float_scale(bound) : 1.0;

    GLuint accum = fg_texture(pass, "accumulation");
    GLuint radiance = fg_texture(pass, "radiance");
    const GLuint zero = 0;
    glClearTexImage(accum, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    glNamedFramebufferParameteri(s->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, resolution);
    glNamedFramebufferParameteri(s->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, resolution);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glViewport(0, 0, resolution, resolution);
    /* VCT paper 3.1: no depth test, no culling; the fragments go to images only. */
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);

    glUseProgram(s->program);
    glUniform4f(8, (float)region.origin[0], (float)region.origin[1], (float)region.origin[2],
                (float)region.voxel);
    glUniform1i(9, resolution);
    glUniform1f(10, (float)fixed_scale);
    glUniform1i(12, fg_param_bool(pass, "conservative") ? 1 : 0);
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &s->no_shadow, 2);
    glBindImageTexture(0, accum, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    cg_gpu_scene_draw(frame->gpu_scene, filter);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);

    const cg_volume_block block = {
        .origin_voxel = {(float)region.origin[0], (float)region.origin[1], (float)region.origin[2],
                         (float)region.voxel},
        .info = {(float)resolution, (float)fg_resource(pass, "radiance")->levels, (float)radiance_scale, 0.0f},
    };
    GLuint region_buffer = fg_buffer(pass, "region");
    glNamedBufferSubData(region_buffer, 0, sizeof block, &block);

    GLuint groups = (GLuint)((resolution + 3) / 4);
    bool from_max = s->format == GL_RGBA8;
    glBindImageTexture(0, accum, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_RESOLVE_MAX, s->max_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_RESOLVE_REGION, region_buffer);
    if (from_max) {
        glClearNamedBufferData(s->max_buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glUseProgram(s->find_max);
        glUniform1i(0, resolution);
        glUniform1f(1, (float)fixed_scale);
        glDispatchCompute(groups, groups, groups);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glUseProgram(s->resolve);
    glUniform1i(0, resolution);
    glUniform1f(1, (float)fixed_scale);
    glUniform1f(2, (float)radiance_scale);
    glUniform1i(3, from_max ? 1 : 0);
    glBindImageTexture(1, radiance, 0, GL_TRUE, 0, GL_WRITE_ONLY, s->format);
    glDispatchCompute(groups, groups, groups);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, s->format);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_RESOLVE_MAX, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_RESOLVE_REGION, 0);
    glUseProgram(0);
    return true;
}

CGP_PASS(voxelize, CGP_PARAMS(voxelize_params),
         "Voxelizes the outgoing diffuse radiance of the scene's direct light (shadowed through "
         "the optional shadow map) plus emission into a cubic 3D lightmap, opacity in alpha "
         "(VCT paper 3.1): dominant-axis projection in a geometry shader, conservative coverage "
         "by triangle dilation and an exact triangle/voxel test, fragments averaged by "
         "fixed-point atomic sums. Rebuilt every frame.");
