/* passes/cone_gather: indirect light by voxel cone tracing through a mipped 3D lightmap
 * (VCT paper 3.2; hybrid eq. 3-4 and 8 for the weights and the level of detail).
 *
 * Inputs: position, normal (G-buffer), volume + region: a mip3d'd voxelize radiance and voxelize's
 * block, optionally with mip3d's directional chains px .. nz; or a voxel_light pass's radiance,
 * sides, normals and region (surface voxels, docs/vct.md). Without a volume the pass has nothing
 * to do and composite adapts. Optional, all five or none: the G-buffer's material, albedo,
 * specular, material, transmission, attenuation (cgp_gather_declare_material): the cones' weights.
 * Outputs
 *   radiance    RGBA32F: rgb = sum_k W_k L_k, the incident radiance integral E_i/pi that
 *               composite multiplies by the albedo (with the material: x the diffuse lobe's share
 *               1 - F0 - (F90 - F0) c(n.v), and 0 where rho = 0); a = ambient visibility (AO).
 *   reflection  RGBA32F (param specular): the specular cone's radiance x the lobe's directional
 *               albedo F0 A + F90 B (split sum; without the material: weight 1), a = its opacity.
 *   refraction  RGBA32F (param refraction, needs the material): the refracted cone's radiance x
 *               tau x the interfaces' transmission x Beer-Lambert, a = its opacity.
 *   (fp32, as direct_light's: radiance of any brightness, no clipping at 65504.)
 *   visibility  R16F (param shadow_cone): transmittance of a cone towards one light.
 *   reads       R32F (param count_reads): volume reads (textureLod calls) of the pixel's diffuse cones.
 * With downsample = 2, 4 or 8 (0: 4 or 8 by the image's height) the diffuse cones are traced at one
 * pixel of each block, with temporal > 1 only a turn of the blocks a frame, and `radiance` is
 * upsampled from them by the G-buffer's position and normal (sdk/upsample.h); the other outputs
 * stay per pixel.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sdk/blocks.h"
#include "sdk/pass.h"
#include "sdk/sampler.h"
#include "sdk/cone.h"
#include "sdk/upsample.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

static const fg_param_desc cone_gather_params[] = {
    CGP_MARCH_PARAMS,
    { .name = "specular", .type = FG_PARAM_BOOL,
      .doc = "also trace a specular cone (output 'reflection', VCT paper 3.2.2): its aperture from the pixel's "
             "roughness, weighted by the GGX lobe's directional albedo (split sum) with the material inputs" },
    { .name = "roughness", .type = FG_PARAM_FLOAT, .default_value = 0.3, .min = 0, .max = 1,
      .step = 0.05, .active_when = "specular", .stage = FG_STAGE_FRAME,
      .doc = "specular cone without the material inputs: its half-angle has tangent roughness^2, at least 0.01" },
    { .name = "refraction", .type = FG_PARAM_BOOL,
      .doc = "also trace a refracted cone where the material transmits (output 'refraction', VCT paper 3.2.2; "
             "needs the material inputs)" },
    { .name = "shadow_cone", .type = FG_PARAM_BOOL,
      .doc = "also trace a cone towards a light (output 'visibility', VCT paper 3.2.3)" },
    { .name = "shadow_light", .type = FG_PARAM_INT, .min = 0, .max = 65535,
      .active_when = "shadow_cone", .stage = FG_STAGE_FRAME,
      .doc = "shadow cone: index of the scene light" },
    { .name = "shadow_aperture", .type = FG_PARAM_FLOAT, .default_value = 10, .min = 0.1, .max = 90,
      .step = 1, .active_when = "shadow_cone", .stage = FG_STAGE_FRAME,
      .doc = "shadow cone: full apex angle in degrees; a directional light with an angular diameter takes that instead" },
    { .name = "count_reads", .type = FG_PARAM_BOOL,
      .doc = "also output 'reads': the volume reads of each pixel's diffuse cones (a cost measure that does "
             "not depend on the machine's load); with downsample, a block's at its representative pixel" },
    CGP_DOWNSAMPLE_PARAM,
    CGP_TEMPORAL_PARAM,
    CGP_INTERLEAVE_PARAM,
};

typedef struct cone_gather_state {
    cgp_gather gather;      /* its block: CG_CONE_GATHER_BLOCK */
    cgp_gather_blocks blocks; /* downsample > 1: the diffuse cones of one pixel a block */
    bool specular, refraction, shadow_cone, count_reads;
    fg_slot visibility, reads; /* declared with their parameters */
} cone_gather_state;

static bool
cone_gather_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *position =
        fg_declare_input(decl, "position", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    fg_declare_input(decl, "normal", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    const fg_resource_desc *volume, *region;
    if (!cgp_gather_declare_volume(pass, decl, &volume, &region, err))
        return false;
    if (!volume) {
        fg_declare_nothing_to_do(decl, "no 3D lightmap (input 'volume' absent)");
        return true;
    }
    bool material = false;
    if (!cgp_gather_declare_material(pass, decl, &material, err))
        return false;
    if (fg_param_bool(pass, "refraction") && !material)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': refraction = true needs the material inputs (albedo, specular, material, "
                       "transmission, attenuation: a gbuffer pass's outputs)", fg_pass_name(pass));
    if (!position)
        return true;
    fg_resource_desc out = cgp_gather_declare_outputs(pass, decl, position);
    if (fg_param_bool(pass, "shadow_cone")) {
        out.format = GL_R16F;
        fg_declare_output(decl, "visibility", &out, FG_ACCESS_IMAGE_STORE);
    }
    if (fg_param_bool(pass, "count_reads")) {
        out.format = GL_R32F;
        fg_declare_output(decl, "reads", &out, FG_ACCESS_IMAGE_STORE);
    }
    return true;
}

static bool
cone_gather_prepare(fg_pass *pass, cone_gather_state *s, cg_error *err)
{
    s->specular = fg_param_bool(pass, "specular");
    s->refraction = fg_param_bool(pass, "refraction");
    s->shadow_cone = fg_param_bool(pass, "shadow_cone");
    s->count_reads = fg_param_bool(pass, "count_reads");
    s->visibility = s->shadow_cone ? fg_pass_slot(pass, "visibility") : FG_NO_SLOT;
    s->reads = s->count_reads ? fg_pass_slot(pass, "reads") : FG_NO_SLOT;
    const cgp_gather_io io = {fg_pass_slot(pass, "position"), fg_pass_slot(pass, "normal"),
                              fg_pass_slot(pass, "radiance")};
    char downsample[64], defines[224];
    snprintf(defines, sizeof defines, "%s%s%s%s%s", s->specular ? "#define SPECULAR\n" : "",
             s->refraction ? "#define REFRACTION\n" : "", s->shadow_cone ? "#define SHADOW_CONE\n" : "",
             s->count_reads ? "#define CG_CONE_COUNT_READS\n" : "",
             cgp_gather_blocks_define(pass, downsample, sizeof downsample));
    return cgp_gather_prepare(s, pass, &s->gather, io, "cone_gather/cone_gather.comp", defines,
                              sizeof(cg_cone_gather_block), err) &&
           cgp_gather_blocks_prepare(s, pass, &s->gather, &s->blocks, "cone_gather/cone_gather.comp", defines, err);
}

static double
tan_half_degrees(double full_degrees)
{
    return tan(0.5 * full_degrees * M_PI / 180.0);
}

static bool
cone_gather_execute(fg_pass *pass, cone_gather_state *s, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    double roughness = fg_param_float(pass, "roughness");
    int light = fg_param_int(pass, "shadow_light");
    /* The shadow cone of a sun with an angular diameter is the sun's disc (VCT paper 3.2.3: the
     * shadow cone as a cone towards the light; its transmittance is the disc's visible share). */
    double shadow_tan = tan_half_degrees(fg_param_float(pass, "shadow_aperture"));
    if (frame->scene && light >= 0 && light < frame->scene->light_count &&
        frame->scene->lights[light].type == CG_LIGHT_DIRECTIONAL && frame->scene->lights[light].angular_diameter > 0.0f)
        shadow_tan = tan(0.5 * frame->scene->lights[light].angular_diameter);
    const cg_cone_gather_block block = {
        .camera = {frame->view.position[0], frame->view.position[1], frame->view.position[2], 0.0f},
        .tan_half = {(float)fmax(roughness * roughness, 0.01), (float)shadow_tan},
        .shadow = {light},
    };

    if (!cgp_gather_begin(pass, &s->gather, &block, sizeof block, fg_slot_texture(pass, s->gather.slots.volume),
                          fg_slot_buffer(pass, s->gather.slots.region), err))
        return false;
    if (frame->gpu_scene)
        cg_gpu_scene_bind_lights(frame->gpu_scene);
    if (s->shadow_cone)
        glBindImageTexture(2, fg_slot_texture(pass, s->visibility), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    if (s->count_reads)
        glBindImageTexture(3, fg_slot_texture(pass, s->reads), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    cgp_gather_blocks_trace(pass, &s->gather, &s->blocks);
    cgp_gather_dispatch(pass, &s->gather);
    cgp_gather_blocks_deferred(pass, &s->gather, &s->blocks);
    cgp_gather_end(pass, &s->gather);
    cgp_gather_blocks_end(&s->blocks);
    return true;
}

CGP_PASS(cone_gather, CGP_PARAMS(cone_gather_params),
         "Indirect diffuse light by voxel cone tracing (VCT paper 3.2.1): 1, 6, 9, 16 or 26 cones "
         "around the normal, weighted by their share of the cosine lobe (hybrid eq. 3-4), each "
         "accumulated front to back through the mip level of its diameter (hybrid eq. 8). "
         "Output: the incident radiance integral E/pi (composite multiplies by the albedo) and "
         "ambient visibility; optional specular and refracted cones (3.2.2), weighted by the G-buffer's "
         "material (split sum) so that a white furnace returns what the BSDF reflects and transmits, and "
         "a shadow cone (3.2.3).");
