/* passes/voxelize: the scene voxelized into a cubic volume (VCT paper 3.1), in one of two models.
 *
 * model = radiance (the VCT paper's): the scene's direct light in a 3D lightmap.
 *   radiance      3D, resolution^3, RGBA16F or RGBA8, full mip chain declared (mip3d fills
 *                 levels 1..): premultiplied outgoing diffuse radiance (direct light, shadowed
 *                 through the optional shadow map, plus emission) and opacity in alpha.
 * model = surface (docs/vct.md, "surface voxels"): the geometry alone, level 0, which a voxel_light
 *   pass lights (it reads no light, so it can be kept while the light changes):
 *   albedo        RGBA8: mean albedo of the voxel's fragments, a = 1 where a surface is.
 *   coverage      RGBA8: per axis i, the largest |n_i| / |n|_1 of its fragments' planes, rounded up
 *                 to the next 1/255: the coverage a path along axis i meets crossing them.
 *   normal        RGBA8_SNORM: xyz the mean of the fragments' unit normals as authored (|N| <= 1,
 *                 1 for one plane), w the mean of n . (x - c) / voxel over its fragments, the
 *                 offset of their plane from the voxel's centre c, in voxels.
 *   emission      RGBA16F: mean emitted radiance (rgb) / the region's radiance scale, a = 1 where a
 *                 surface is.
 * Both models:
 *   region        std140 block CG_VOLUME_BLOCK (common/blocks.h) for common/volume.glsl: where
 *                 the volume lies and how its values decode (consumers bind it at CG_BINDING_VOLUME).
 *   accumulation  3D R32UI, resolution^2 x 4 resolution (surface model: 2 resolution x 2 resolution x
 *                 4 resolution, 14 of its 16 slabs used): the fixed-point sums and counts
 *                 of the fragments (shaders/voxelize/voxelize.frag), transient working memory,
 *                 declared so that the memory report counts it.
 * Inputs (optional, together, model = radiance): shadow (depth) and shadow_matrix (buffer) of a
 * shadow_map pass.
 *
 * Caching (model = surface, cache=true, the default): the four geometry volumes are persistent and
 * kept across frames; they read no light, so a turning sun leaves them as they are. They are
 * voxelized again only when what the voxelization reads may have changed: the first frame after
 * prepare, an instance the mesh filter keeps (its world matrix, revision, mesh or material, compared
 * by value, sdk/instances.h), the set of instances, the GPU scene's upload, the region, or the
 * fixed-point and radiance scales (the emission volume stores emission / the radiance scale). Any
 * such change clears and voxelizes the whole volume again: conservative, and a frame that rebuilds
 * costs what an uncached one does (re-voxelizing only the voxels of the instances that moved is not
 * done). The light (voxel_light) and its mips are recomputed every frame from the kept volumes.
 * The pass reports which it did through fg_pass_report_rebuilt. Model radiance, and cache=false (the
 * VCT paper's), clear and voxelize everything every frame, so the volume follows moving lights and
 * geometry.
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

/* Fragments of the brightest radiance that one voxel can sum without overflowing 32 bits. */
#define FRAGMENT_HEADROOM 1024.0

enum { FORMAT_RGBA8, FORMAT_RGBA16F };
enum { MODEL_RADIANCE, MODEL_SURFACE };

/* Accumulation slabs of the surface model (shaders/voxelize/voxelize.frag): count, albedo RGB,
 * emission RGB, normal xyz, plane offset, coverage xyz; 14 of 2 x 2 x 4. */
/* Fragments one voxel may sum without overflowing 32 bits, surface model. */
#define SURFACE_HEADROOM 4096.0
/* The surface model's pre-exposure over sdk/radiance.h's (voxelize_execute). */
#define SURFACE_PRE_EXPOSURE 32.0
enum { REGION_MESHES, REGION_SCENE, REGION_EXPLICIT };

static const fg_param_desc voxelize_params[] = {
    { .name = "model", .type = FG_PARAM_ENUM, .default_value = MODEL_RADIANCE, .choices = "radiance|surface",
      .doc = "radiance: the direct light and opacity of each voxel, lit per fragment (VCT paper 3.1; "
             "mip3d, cone_gather); surface: the geometry alone (albedo, mean normal and plane, per-axis "
             "coverage, emission), lit by a voxel_light pass (docs/vct.md)" },
    { .name = "resolution", .type = FG_PARAM_INT, .default_value = 128, .min = 16, .max = 512,
      .power_of_two = true,
      .doc = "voxels per edge of the cubic volume at level 0" },
    { .name = "format", .type = FG_PARAM_ENUM, .default_value = FORMAT_RGBA16F, .choices = "rgba8|rgba16f",
      .active_when = "model=radiance",
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
    { .name = "cache", .type = FG_PARAM_BOOL, .default_value = 1, .active_when = "model=surface",
      .doc = "keep the geometry volumes across frames and voxelize them again (all of them) only when an "
             "instance the mesh filter keeps, the region or the scales changed; false: voxelize every "
             "frame (the VCT paper's rebuild)" },
};

/* Where the volume lies: a cube. */
typedef struct voxel_region {
    double origin[3];
    double voxel;
} voxel_region;

/* Beside the instances, what the surface model's voxelization reads (compared by value). */
typedef struct surface_build {
    voxel_region region;
    int resolution, conservative;
    double unit_fixed, emission_fixed, radiance_scale;
} surface_build;

typedef struct voxelize_state {
    bool surface;
    bool cache;             /* surface model only */
    GLuint program;
    GLuint resolve;
    GLuint find_max;        /* RGBA8 only: the largest radiance, for the stored scale */
    GLuint max_buffer;
    GLuint fbo;
    cgp_no_shadow no_shadow;
    GLenum format;
    /* Nearest-surface distance per point/spot light, recomputed when a light moves. */
    cgp_light_distances light_distances;
    /* cache: what the kept volumes were voxelized from (instances.taken = false: nothing yet). */
    cgp_instance_record instances;
    surface_build built;
    uint64_t builds;        /* voxelizations since prepare */
} voxelize_state;

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
    bool surface = fg_param_enum(pass, "model") == MODEL_SURFACE;
    if (surface) {
        /* Level 0 only: voxel_light lights it into volumes of its own, which it mips. */
        static const char *const names[4] = {"albedo", "coverage", "normal", "emission"};
        static const GLenum formats[4] = {GL_RGBA8, GL_RGBA8, GL_RGBA8_SNORM, GL_RGBA16F};
        for (int i = 0; i < 4; i++) {
            /* cache: kept across frames; persistent storage is never pooled, so nothing else writes
             * it between two frames. */
            fg_resource_desc geometry = {
                .kind = FG_TEXTURE_3D, .format = formats[i],
                .width = resolution, .height = resolution, .depth = resolution, .levels = 1, .gi = true,
                .persistent = fg_param_bool(pass, "cache"),
            };
            fg_declare_output(decl, names[i], &geometry, FG_ACCESS_IMAGE_STORE);
        }
    } else {
        fg_resource_desc radiance = {
            .kind = FG_TEXTURE_3D,
            .format = fg_param_enum(pass, "format") == FORMAT_RGBA8 ? GL_RGBA8 : GL_RGBA16F,
            .width = resolution, .height = resolution, .depth = resolution,
            .levels = fg_mip_levels(resolution, resolution, resolution),
            .gi = true,
        };
        fg_declare_output(decl, "radiance", &radiance, FG_ACCESS_IMAGE_STORE);
    }
    fg_resource_desc block = cgp_buffer_desc(sizeof(cg_volume_block));
    fg_declare_output(decl, "region", &block, FG_ACCESS_TRANSFER | FG_ACCESS_STORAGE);
    fg_resource_desc accumulation = {
        .kind = FG_TEXTURE_3D, .format = GL_R32UI,
        .width = (surface ? 2 : 1) * resolution, .height = (surface ? 2 : 1) * resolution, .depth = 4 * resolution,
        .levels = 1,
        .gi = true,
    };
    fg_declare_output(decl, "accumulation", &accumulation, FG_ACCESS_IMAGE_STORE | FG_ACCESS_TRANSFER);
    return true;
}

/* What the state holds beside its GL objects: the light cache of cgp_radiance_bound() and the
 * record of the kept volumes' instances. */
static void
voxelize_cleanup(void *state)
{
    voxelize_state *s = state;
    cgp_light_distances_free(&s->light_distances);
    cgp_instance_record_free(&s->instances);
}

static bool
voxelize_prepare(fg_pass *pass, voxelize_state *s, cg_error *err)
{
    cgp_state_on_destroy(s, voxelize_cleanup);
    s->surface = fg_param_enum(pass, "model") == MODEL_SURFACE;
    s->max_buffer = cgp_buffer(s, sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    s->fbo = cgp_framebuffer(s);
    cgp_no_shadow_create(s, &s->no_shadow);
    if (s->surface) {
        s->cache = fg_param_bool(pass, "cache");
        s->format = GL_RGBA16F;
        return cgp_graphics_program(s, "voxelize/voxelize.vert", "voxelize/voxelize.geom", "voxelize/voxelize.frag",
                                    "#define SURFACE\n", &s->program, err) &&
               cgp_compute_program(s, "voxelize/resolve.comp", "#define SURFACE\n", &s->resolve, err);
    }
    s->format = fg_resource(pass, "radiance")->format;
    char defines[64];
    snprintf(defines, sizeof defines, "#define FORMAT %s\n", s->format == GL_RGBA8 ? "rgba8" : "rgba16f");
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
     * region block. A scene with no light and no emission is black.
     * The surface model stores emission / scale and publishes the scale for the voxel_light pass
     * that lights it, whose volumes hold the radiance premultiplied by the coverage sum (up to 3)
     * plus up to 8 bounces (at most 9 x the bound): its pre-exposure is 32 times larger, bound /
     * 1024, so that 3 x 9 x 1024 stays below the half-float maximum. */
    double fixed_scale = bound > 0.0 ? 4294967295.0 / (bound * FRAGMENT_HEADROOM) : 1.0;
    double radiance_scale = s->format != GL_RGBA8 ? cgp_half_float_scale(bound) : 1.0;
    if (s->surface)
        radiance_scale *= SURFACE_PRE_EXPOSURE;
    /* Surface model: quantities in [-1, 1] (albedo, normals, offsets in voxels, coverage) at 2^32 /
     * (2 SURFACE_HEADROOM) per unit, so that SURFACE_HEADROOM fragments sum within a signed 32-bit
     * integer; emission per unit of the brightest emission. */
    double emission = 0.0;
    for (int m = 0; m < scene->material_count; m++)
        for (int k = 0; k < 3; k++)
            emission = fmax(emission, (double)scene->materials[m].emissive[k] * scene->materials[m].emissive_strength);
    double unit_fixed = 2147483647.0 / SURFACE_HEADROOM;
    double emission_fixed = emission > 0.0 ? 4294967295.0 / (emission * SURFACE_HEADROOM) : 1.0;

    /* The region block is not kept: written every frame, cached or not. */
    const cg_volume_block block = {
        .origin_voxel = {(float)region.origin[0], (float)region.origin[1], (float)region.origin[2],
                         (float)region.voxel},
        .info = {(float)resolution, (float)fg_mip_levels(resolution, resolution, resolution), (float)radiance_scale,
                 0.0f},
    };
    GLuint region_buffer = fg_buffer(pass, "region");
    glNamedBufferSubData(region_buffer, 0, sizeof block, &block);

    const char *why = NULL;
    surface_build build;
    if (s->surface && s->cache) {
        memset(&build, 0, sizeof build);    /* memcmp compares the padding too */
        build.region = region;
        build.resolution = resolution;
        build.conservative = fg_param_bool(pass, "conservative");
        build.unit_fixed = unit_fixed;
        build.emission_fixed = emission_fixed;
        build.radiance_scale = radiance_scale;
        why = cgp_instances_changed(&s->instances, frame, filter, "a voxelized instance changed");
        if (!why && memcmp(&build, &s->built, sizeof build))
            why = "region or scales changed";
        if (!why) {
            fg_pass_report_rebuilt(pass, "geometry kept (%llu geometry build%s since prepare)",
                                   (unsigned long long)s->builds, s->builds == 1 ? "" : "s");
            return true;
        }
    }

    GLuint accum = fg_texture(pass, "accumulation");
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
    glUniform1i(12, fg_param_bool(pass, "conservative") ? 1 : 0);
    if (s->surface)
        glUniform4f(13, (float)unit_fixed, (float)emission_fixed, 0.0f, 0.0f);
    else
        glUniform1f(10, (float)fixed_scale);
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &s->no_shadow, 2);
    glBindImageTexture(0, accum, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    cg_gpu_scene_draw(frame->gpu_scene, filter);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);


    GLuint groups = (GLuint)((resolution + 3) / 4);
    if (s->surface) {
        static const char *const names[4] = {"albedo", "coverage", "normal", "emission"};
        static const GLenum formats[4] = {GL_RGBA8, GL_RGBA8, GL_RGBA8_SNORM, GL_RGBA16F};
        glUseProgram(s->resolve);
        glUniform1i(0, resolution);
        glUniform4f(4, (float)unit_fixed, (float)emission_fixed, (float)radiance_scale, 0.0f);
        glBindImageTexture(0, accum, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        for (int i = 0; i < 4; i++)
            glBindImageTexture(1 + (GLuint)i, fg_texture(pass, names[i]), 0, GL_TRUE, 0, GL_WRITE_ONLY, formats[i]);
        glDispatchCompute(groups, groups, groups);
        for (int i = 0; i < 5; i++)
            glBindImageTexture((GLuint)i, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
        glUseProgram(0);
        if (!s->cache) {
            fg_pass_report_rebuilt(pass, "geometry voxelized (cache=false)");
            return true;
        }
        s->built = build;
        if (!cgp_instances_remember(&s->instances, frame, filter, err))
            return false;
        s->builds++;
        fg_pass_report_rebuilt(pass, "geometry voxelized (%s; %llu geometry build%s since prepare)", why,
                               (unsigned long long)s->builds, s->builds == 1 ? "" : "s");
        return true;
    }
    GLuint radiance = fg_texture(pass, "radiance");
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
         "Voxelizes the scene into a cubic volume (VCT paper 3.1): model radiance, the outgoing "
         "diffuse radiance of the direct light (shadowed through the optional shadow map) plus "
         "emission, opacity in alpha; model surface, the geometry a voxel_light pass lights "
         "(albedo, mean normal and plane offset, per-axis coverage, emission). Dominant-axis "
         "projection in a geometry shader, conservative coverage by triangle dilation and an "
         "exact triangle/voxel test, fragments averaged by fixed-point atomic sums. Model radiance is "
         "rebuilt every frame; model surface keeps its volumes across frames (cache=true) and voxelizes "
         "them again, whole, only when an instance it voxelizes, the region or the scales changed.");
