/* passes/voxel_light: the light of voxelize's surface model (docs/vct.md, "surface voxels"), the
 * volumes the cone tracers read with CG_CONE_SURFACE (shaders/common/cone_trace.glsl).
 *
 * Inputs: albedo, coverage, normal, emission and region of a voxelize pass with model = surface
 * (required); shadow and shadow_matrix of a shadow_map pass (optional, together).
 * Outputs, 3D RGBA16F, voxelize's voxels (a cube or a box), its mip chains (cgp_volume_levels):
 *   radiance  (w L_lit, w), w = alpha_x + alpha_y + alpha_z: the lit side's radiance premultiplied by
 *             the voxel's coverage sum (shaders/voxel_light/inject.comp)
 *   sides     (w beta, w delta, 0, alpha_y): the other side's luminance fraction, the plane offset
 *   normals   (w N, alpha_z): the mean normal of the lit side
 *   and, where a bounce is gathered (the header's recursion), the transient gathered_front, gathered_back
 *   (level 0: each side's gathered light) and voxels (the list of occupied voxels).
 *
 * The light is evaluated per voxel, at its surface point, from its geometry: a pass after
 * voxelize, so that the geometry can stay while the light changes. Bounces are counted as
 * path_trace counts them: with G the gather at the voxels (gather.comp) times the albedo, Le the
 * emission and D the direct light of the scene's lights (inject.comp),
 *     V_0 = Le,   V_(k+1) = Le + D + G(V_k),
 * and a cone gather of V_N at a pixel holds every path of up to N reflections between the pixel
 * and any source (emitter or punctual light), as path_trace with `bounces` N: an emitter's light
 * reaches the pixel's gather directly (0 reflections), a punctual light's through D (1), and each
 * G adds one more to both. Where no voxelized mesh emits and no sky shines, G(V_0) = 0 and the
 * first gather is skipped (V_1 = D): N - 1 gathers, N otherwise; each gather is followed by the mip chain
 * (mip.comp) of the new light.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sdk/blocks.h"
#include "sdk/cone.h"
#include "sdk/pass.h"
#include "sdk/sampler.h"
#include "sdk/shadow.h"
#include "sdk/sky.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

/* The march of the gathers at the voxels: the defaults of graphs/vct.json's cone_gather. */
#define BOUNCE_STEP 0.5
#define BOUNCE_START_OFFSET 1.0
#define BOUNCE_LOD_BIAS -1.0

static const fg_param_desc voxel_light_params[] = {
    { .name = "bounces", .type = FG_PARAM_INT, .default_value = 1, .min = 0, .max = 8,
      .doc = "diffuse bounces, counted as path_trace counts them (Cycles, pbrt): a cone gather after this "
             "pass adds what path_trace with the same bounces adds to direct_light's image. 0: the volume "
             "holds emission alone (the emitters' direct light on their neighbours); each bounce is one "
             "more diffuse reflection: the volume's light gathered at every occupied voxel and added to it "
             "(N - 1 gathers, N when the voxelized meshes emit: docs/vct.md)" },
    { .name = "bounce_cones", .type = FG_PARAM_INT, .default_value = 16, .min = 1, .max = 26,
      .allowed = FG_PARAM_VALUES(CGP_CONE_SET_SIZES),
      .doc = "diffuse cones of the gathers at the voxels: 1, 6, 9, 16 or 26" },
};

static const char *const geometry_names[4] = {"albedo", "coverage", "normal", "emission"};
static const GLenum geometry_formats[4] = {GL_RGBA8, GL_RGBA8, GL_RGBA8_SNORM, GL_RGBA16F};
static const char *const light_names[3] = {"radiance", "sides", "normals"};

typedef struct voxel_light_state {
    GLuint inject, mip, gather;
    GLuint sampler;         /* the volumes, for the gathers at the voxels */
    GLuint one_level;       /* the radiance again at CG_UNIT_OCCUPANCY (cgp_sampler_volume_one_level) */
    GLuint cone_block;
    cgp_cone_set set;
    cgp_no_shadow no_shadow;
    cgp_sky sky;            /* the scene's sky, which the gathers at the voxels see (common/sky.glsl) */
    bool gathers;           /* the transient bounce resources exist */
} voxel_light_state;

/* Entries of the list of occupied voxels: a quarter of the volume, far beyond what surfaces
 * occupy (a plane across a 128^3 volume takes 1 to 3 percent of it). */
static GLuint
list_capacity(const fg_resource_desc *volume)
{
    return (GLuint)((size_t)volume->width * (size_t)volume->height * (size_t)volume->depth / 4);
}

/* Whether any mesh that a voxelize pass may have voxelized emits (emission in the volume), or a
 * sky lights the voxels: then G(V_0) is not 0 (the header's recursion). */
static bool
scene_emits(const cg_scene *scene)
{
    if (!cg_sky_is_black(&scene->sky))
        return true;
    for (int i = 0; i < scene->material_count; i++) {
        const cg_material *m = &scene->materials[i];
        if (m->emissive_strength > 0.0f && (m->emissive[0] > 0.0f || m->emissive[1] > 0.0f || m->emissive[2] > 0.0f))
            return true;
    }
    return false;
}

/* Gathers at the voxels for the pass's bounces (the header's recursion). */
static int
gathers(const fg_pass *pass)
{
    int bounces = fg_param_int(pass, "bounces");
    const fg_frame *frame = fg_pass_frame(pass);
    bool emits = frame && frame->scene && scene_emits(frame->scene);
    if (bounces == 0)
        return 0;
    return emits ? bounces : bounces - 1;
}

static bool
voxel_light_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    if (!cgp_declare_shadow_inputs(pass, decl, err))
        return false;
    const fg_resource_desc *geometry[4];
    for (int i = 0; i < 4; i++)
        geometry[i] = fg_declare_input(decl, geometry_names[i], FG_TEXTURE_3D, FG_ACCESS_SAMPLED, true);
    const fg_resource_desc *region = fg_declare_input(decl, "region", FG_BUFFER, FG_ACCESS_UNIFORM, true);
    for (int i = 0; i < 4; i++)
        if (!geometry[i])
            return true;    /* the graph reports the missing input, or culls the pass */
    if (!region)
        return true;
    for (int i = 0; i < 4; i++)
        if (geometry[i]->format != geometry_formats[i] || geometry[i]->width != geometry[0]->width ||
            geometry[i]->height != geometry[0]->height || geometry[i]->depth != geometry[0]->depth)
            return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                           "pass '%s': input '%s' is not a voxelize pass's output of model surface (a volume "
                           "of its format, the size of the others): connect albedo, coverage, normal and emission "
                           "of one voxelize pass",
                           fg_pass_name(pass), geometry_names[i]);
    if (region->buffer_bytes < sizeof(cg_volume_block))
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'region' holds %zu bytes; a voxelize 'region' holds %zu",
                       fg_pass_name(pass), region->buffer_bytes, sizeof(cg_volume_block));
    const fg_resource_desc *g = geometry[0];
    fg_resource_desc light = {
        .kind = FG_TEXTURE_3D, .format = GL_RGBA16F,
        .width = g->width, .height = g->height, .depth = g->depth,
        .levels = cgp_volume_levels(g->width, g->height, g->depth), .gi = true,
    };
    for (int i = 0; i < 3; i++)
        fg_declare_output(decl, light_names[i], &light, FG_ACCESS_IMAGE_STORE);
    if (gathers(pass) > 0) {
        fg_resource_desc gathered = light;
        gathered.levels = 1;
        fg_declare_output(decl, "gathered_front", &gathered, FG_ACCESS_IMAGE_STORE);
        fg_declare_output(decl, "gathered_back", &gathered, FG_ACCESS_IMAGE_STORE);
        fg_resource_desc list = cgp_buffer_desc(sizeof(cg_voxel_list_block) + sizeof(GLuint) * list_capacity(g));
        list.gi = true;
        fg_declare_output(decl, "voxels", &list, FG_ACCESS_STORAGE | FG_ACCESS_TRANSFER);
    }
    return true;
}

static bool
voxel_light_prepare(fg_pass *pass, voxel_light_state *s, cg_error *err)
{
    s->gathers = fg_resource(pass, "voxels") != NULL;
    cgp_no_shadow_create(s, &s->no_shadow);
    cgp_sky_prepare(s, &s->sky);
    s->sampler = cgp_sampler_volume(s);
    s->one_level = cgp_sampler_volume_one_level(s);
    s->cone_block = cgp_uniform_buffer(s, sizeof(cg_cone_set_block));
    if (!cgp_cone_set_of_param(pass, "bounce_cones", &s->set, err))
        return false;
    return cgp_compute_program(s, "voxel_light/inject.comp", NULL, &s->inject, err) &&
           cgp_compute_program(s, "voxel_light/mip.comp", NULL, &s->mip, err) &&
           (!s->gathers ||
            cgp_compute_program(s, "voxel_light/gather.comp", "#define CG_CONE_SURFACE\n", &s->gather, err));
}

/* Level 0 of the three volumes. */
static void
inject(const fg_pass *pass, const voxel_light_state *s, bool direct, bool gathered, bool build_list)
{
    glUseProgram(s->inject);
    glUniform1i(4, direct);
    glUniform1i(1, gathered);
    glUniform1i(2, build_list);
    const fg_resource_desc *volume = fg_resource(pass, "radiance");
    glUniform1ui(3, s->gathers ? list_capacity(volume) : 0u);
    for (int i = 0; i < 3; i++)
        glBindImageTexture((GLuint)i, fg_texture(pass, light_names[i]), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute((GLuint)(volume->width + 3) / 4, (GLuint)(volume->height + 3) / 4, (GLuint)(volume->depth + 3) / 4);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT);
}

/* Levels 1.. of the three volumes from level 0. */
static void
mip(const fg_pass *pass, const voxel_light_state *s)
{
    glUseProgram(s->mip);
    const fg_resource_desc *volume = fg_resource(pass, "radiance");
    for (int level = 1; level < volume->levels; level++) {
        for (int i = 0; i < 3; i++) {
            GLuint tex = fg_texture(pass, light_names[i]);
            glBindImageTexture((GLuint)i, tex, level - 1, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
            glBindImageTexture(3 + (GLuint)i, tex, level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        }
        /* cgp_volume_levels: every side halves exactly. */
        glDispatchCompute((GLuint)((volume->width >> level) + 3) / 4, (GLuint)((volume->height >> level) + 3) / 4,
                          (GLuint)((volume->depth >> level) + 3) / 4);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    for (int i = 0; i < 6; i++)
        glBindImageTexture((GLuint)i, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
}

/* Each listed voxel's gathered light on both sides, through the current volumes. */
static void
gather(const fg_pass *pass, const voxel_light_state *s)
{
    glUseProgram(s->gather);
    glUniform1ui(3, list_capacity(fg_resource(pass, "radiance")));
    glBindTextureUnit(CG_UNIT_VOLUME, fg_texture(pass, "radiance"));
    glBindTextureUnit(CG_UNIT_SIDES, fg_texture(pass, "sides"));
    glBindTextureUnit(CG_UNIT_NORMALS, fg_texture(pass, "normals"));
    glBindSampler(CG_UNIT_VOLUME, s->sampler);
    glBindSampler(CG_UNIT_SIDES, s->sampler);
    glBindSampler(CG_UNIT_NORMALS, s->sampler);
    glBindTextureUnit(CG_UNIT_OCCUPANCY, fg_texture(pass, "radiance"));
    glBindSampler(CG_UNIT_OCCUPANCY, s->one_level);
    glBindTextureUnit(2, fg_texture(pass, "normal"));
    glBindImageTexture(0, fg_texture(pass, "gathered_front"), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(1, fg_texture(pass, "gathered_back"), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, fg_buffer(pass, "voxels"));
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindSampler(CG_UNIT_VOLUME, 0);
    glBindSampler(CG_UNIT_SIDES, 0);
    glBindSampler(CG_UNIT_NORMALS, 0);
    glBindSampler(CG_UNIT_OCCUPANCY, 0);
    glBindTextureUnit(CG_UNIT_OCCUPANCY, 0);
    /* inject.comp reads the geometry and the gathered light at units 0..5 again. */
    glBindTextureUnit(CG_UNIT_SIDES, 0);
    glBindTextureUnit(CG_UNIT_NORMALS, 0);
}

static void
bind_inject_inputs(const fg_pass *pass, const voxel_light_state *s)
{
    for (int i = 0; i < 4; i++)
        glBindTextureUnit((GLuint)i, fg_texture(pass, geometry_names[i]));
    glBindTextureUnit(4, s->gathers ? fg_texture(pass, "gathered_front") : 0);
    glBindTextureUnit(5, s->gathers ? fg_texture(pass, "gathered_back") : 0);
}

static bool
voxel_light_execute(fg_pass *pass, voxel_light_state *s, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    int bounces = fg_param_int(pass, "bounces");
    glBindBufferBase(GL_UNIFORM_BUFFER, CG_BINDING_VOLUME, fg_buffer(pass, "region"));
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &s->no_shadow, 6);
    if (s->gathers) {
        const cg_voxel_list_block header = {.dispatch = {0, 1, 1, 0}};
        glNamedBufferSubData(fg_buffer(pass, "voxels"), 0, sizeof header, &header);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, fg_buffer(pass, "voxels"));
        cg_cone_set_block cones;
        cgp_cone_block_fill_march(&s->set, BOUNCE_STEP, BOUNCE_START_OFFSET, 0.0, BOUNCE_LOD_BIAS, &cones);
        cgp_uniform_upload(s->cone_block, CG_BINDING_CONES, &cones, sizeof cones);
    }
    /* V_0 = Le, or V_1 = D where nothing emits (the header); then a gather per bounce left. */
    int count = s->gathers ? gathers(pass) : 0;
    bool skip_first = bounces > 0 && count < bounces;
    bind_inject_inputs(pass, s);
    inject(pass, s, skip_first, false, s->gathers);
    mip(pass, s);
    /* What a cone of a gather at the voxels leaves open sees the sky, as the screen's gather. */
    if (count > 0) {
        if (!cgp_sky_update(s, &s->sky, frame->scene, err))
            return false;
        cgp_sky_bind(&s->sky);
    }
    for (int b = 0; b < count; b++) {
        gather(pass, s);
        bind_inject_inputs(pass, s);
        inject(pass, s, true, true, false);
        mip(pass, s);
    }
    if (count > 0)
        cgp_sky_unbind();
    for (GLuint unit = 0; unit < 7; unit++)
        glBindTextureUnit(unit, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, 0);
    glUseProgram(0);
    return true;
}

CGP_PASS(voxel_light, CGP_PARAMS(voxel_light_params),
         "Lights voxelize's surface model (docs/vct.md): each side of every voxel's mean plane gets the "
         "direct light of the scene's lights at its surface point (shadowed through the optional shadow "
         "map, 2 x 2 points across the voxel), its emission and, per bounce as path_trace counts them, the light gathered "
         "at the voxels by the cone tracers' own march; writes the one-sided volumes "
         "radiance, sides and normals with their mip chains (per-axis additive coverage) that "
         "cone_gather and hybrid_gather read.");
