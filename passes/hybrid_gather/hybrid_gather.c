/* passes/hybrid_gather: indirect light by hybrid cone tracing (hybrid paper VI, eq. 8-17)
 * through a 3D lightmap of the complex meshes and a 2D lightmap of the height-field meshes.
 *
 * A separate pass rather than a mode of cone_gather, each shader reading as one method, but
 * no copy of it: both take the 3D steps of shaders/common/cone_trace.glsl (cg_cone_step, here
 * at the sample position of eq. 15) and share the pass SDK's cgp_gather (cone set, blocks,
 * bindings). Without the 2D branch (a scene with no height field, where the graph culls
 * heightmap_raster, mip2d and hsat) the shader compiles without HAS_2D and runs the very VCT
 * gather of cone_gather.
 *
 * Inputs: position, normal (G-buffer, required); volume + region (mip3d'd voxelize radiance
 * and its block); lightmap + region2d (mip2d'd heightmap_raster lightmap and its block) and
 * hsat + hsat_info (an hsat pass's table and info). Each group is optional; with neither
 * lightmap the pass has nothing to do.
 * Output: radiance, RGBA32F: rgb = sum_k W_k L_k (E_i / pi, composite multiplies by the
 * albedo), a = ambient visibility. The same convention as cone_gather.
 */
#include <stdio.h>
#include <stdlib.h>

#include "sdk/blocks.h"
#include "sdk/pass.h"
#include "sdk/sampler.h"
#include "sdk/cone.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

enum { CUBE_EQ11, CUBE_EQ10 };
enum { OCCLUSION_EQ16, OCCLUSION_EQ17 };

static const fg_param_desc hybrid_gather_params[] = {
    { .name = "cones", .type = FG_PARAM_INT, .default_value = 6, .min = 1, .max = 16,
      .allowed = FG_PARAM_VALUES(CGP_CONE_SET_SIZES),
      .doc = "diffuse cones: 1, 6, 9 or 16; weights integrate the cosine lobe to 1 (hybrid eq. 3-4)" },
    { .name = "aperture", .type = FG_PARAM_FLOAT, .min = 0, .max = 150,
      .step = 5,
      .doc = "full apex angle of the diffuse cones in degrees; 0: per cone, the cone with its cell's solid angle" },
    { .name = "step", .type = FG_PARAM_FLOAT, .default_value = 0.25, .min = 0.05, .max = 4,
      .doc = "step length as a fraction of the cone diameter" },
    { .name = "start_offset", .type = FG_PARAM_FLOAT, .default_value = 1.5, .min = 0, .max = 16,
      .doc = "xels the cone origin is moved along the normal (the coarser of voxel and 2D texel)" },
    { .name = "lod_bias", .type = FG_PARAM_FLOAT, .default_value = -2, .min = -4, .max = 4,
      .step = 0.25,
      .doc = "added to the 3D lightmap's matched level (one below hybrid eq. 8, as cone_gather) and to the 2D "
             "lightmap's eq. 8" },
    { .name = "max_distance", .type = FG_PARAM_FLOAT, .min = 0, .max = 1e9,
      .doc = "metres a cone travels at most; 0: the maps' diagonal" },
    { .name = "cube", .type = FG_PARAM_ENUM, .default_value = CUBE_EQ11, .choices = "eq11|eq10",
      .doc = "fitting cube: eq. 11 for cones off the axes (eq. 10 on them, the paper), or eq. 10's inscribed cube always" },
    { .name = "occlusion", .type = FG_PARAM_ENUM, .default_value = OCCLUSION_EQ16, .choices = "eq16|eq17",
      .doc = "height-field occlusion per step: eq. 16 (newly covered part of the section) or eq. 17 (d / t)" },
    { .name = "dda", .type = FG_PARAM_BOOL, .default_value = 1,
      .doc = "walk the 2D lightmap along the cone's projection by a 2D DDA (else one sample at the cube's centre)" },
    { .name = "skip", .type = FG_PARAM_BOOL, .default_value = 1,
      .doc = "skip steps above the highest terrain under the cube (HSAT)" },
};

typedef struct hybrid_gather_state {
    cgp_gather gather;      /* its block: CG_HYBRID_GATHER_BLOCK */
    GLuint map_sampler, table_sampler;
    GLuint empty_block;     /* bound where a map is absent, so no block is left unbound */
    bool has_2d, has_3d;
} hybrid_gather_state;

static bool
check_buffer(const fg_pass *pass, const fg_resource_desc *desc, const char *name, size_t bytes,
             const char *what, cg_error *err)
{
    if (desc->buffer_bytes < bytes)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE, "pass '%s': input '%s' holds %zu bytes; %s holds %zu",
                       fg_pass_name(pass), name, desc->buffer_bytes, what, bytes);
    return true;
}

static bool
hybrid_gather_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *position = fg_declare_input(decl, "position", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    fg_declare_input(decl, "normal", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    const fg_resource_desc *volume = fg_declare_input(decl, "volume", FG_TEXTURE_3D, FG_ACCESS_SAMPLED, false);
    const fg_resource_desc *region = fg_declare_input(decl, "region", FG_BUFFER, FG_ACCESS_UNIFORM, false);
    const fg_resource_desc *lightmap = fg_declare_input(decl, "lightmap2d", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    const fg_resource_desc *region2d = fg_declare_input(decl, "region2d", FG_BUFFER, FG_ACCESS_UNIFORM, false);
    const fg_resource_desc *hsat = fg_declare_input(decl, "hsat", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    const fg_resource_desc *hsat_info = fg_declare_input(decl, "hsat_info", FG_BUFFER, FG_ACCESS_STORAGE, false);
    if (volume && !region)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': input 'volume' needs input 'region' (a voxelize pass's output 'region')",
                       fg_pass_name(pass));
    if (lightmap && (!region2d || !hsat || !hsat_info))
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': input 'lightmap2d' needs 'region2d' (heightmap_raster's 'region'), "
                       "'hsat' and 'hsat_info' (an hsat pass's 'table' and 'info')", fg_pass_name(pass));
    if (region && !check_buffer(pass, region, "region", sizeof(cg_volume_block), "a voxelize 'region'", err))
        return false;
    if (lightmap &&
        (!check_buffer(pass, region2d, "region2d", sizeof(cg_heightmap_block), "a heightmap_raster 'region'", err) ||
         !check_buffer(pass, hsat_info, "hsat_info", sizeof(cg_hsat_info_block), "an hsat 'info'", err)))
        return false;
    if (lightmap && hsat && hsat->levels < lightmap->levels)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'hsat' has %d levels, the lightmap %d: connect the hsat of this lightmap",
                       fg_pass_name(pass), hsat->levels, lightmap->levels);
    if (!volume && !lightmap) {
        fg_declare_nothing_to_do(decl, "no lightmap (inputs 'volume' and 'lightmap2d' both absent)");
        return true;
    }
    if (!position)
        return true;
    fg_resource_desc out = cgp_image_like(pass, position, GL_RGBA32F);
    fg_declare_output(decl, "radiance", &out, FG_ACCESS_IMAGE_STORE);
    return true;
}

static bool
hybrid_gather_prepare(fg_pass *pass, hybrid_gather_state *s, cg_error *err)
{
    s->has_3d = fg_input_present(pass, "volume");
    s->has_2d = fg_input_present(pass, "lightmap2d");
    /* The cube-centre sample (dda = false) reads the 2D lightmap filtered; the DDA and HSAT fetch. */
    s->map_sampler = cgp_sampler_lightmap2d(s);
    s->table_sampler = cgp_sampler_table(s);
    static const cg_hsat_info_block zero;
    s->empty_block = cgp_buffer(s, sizeof zero, &zero, 0);
    return cgp_gather_prepare(s, pass, &s->gather, "hybrid_gather/hybrid_gather.comp",
                              s->has_2d ? "#define HAS_2D\n" : NULL, sizeof(cg_hybrid_gather_block), err);
}

static bool
hybrid_gather_execute(fg_pass *pass, hybrid_gather_state *s, cg_error *err)
{
    const cg_hybrid_gather_block block = {
        .maps = {s->has_3d},
        .switches = {fg_param_enum(pass, "cube") == CUBE_EQ11, fg_param_enum(pass, "occlusion"),
                     fg_param_bool(pass, "dda"), fg_param_bool(pass, "skip")},
    };

    if (!cgp_gather_begin(pass, &s->gather, &block, sizeof block, s->has_3d ? fg_texture(pass, "volume") : 0,
                          s->has_3d ? fg_buffer(pass, "region") : s->empty_block, err))
        return false;
    glBindBufferBase(GL_UNIFORM_BUFFER, CG_BINDING_HEIGHTMAP, s->has_2d ? fg_buffer(pass, "region2d") : s->empty_block);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_HSAT,
                     s->has_2d ? fg_buffer(pass, "hsat_info") : s->empty_block);
    glBindTextureUnit(CG_UNIT_LIGHTMAP2D, s->has_2d ? fg_texture(pass, "lightmap2d") : 0);
    glBindSampler(CG_UNIT_LIGHTMAP2D, s->map_sampler);
    glBindTextureUnit(CG_UNIT_HSAT, s->has_2d ? fg_texture(pass, "hsat") : 0);
    glBindSampler(CG_UNIT_HSAT, s->table_sampler);
    cgp_gather_end(pass);
    glBindSampler(CG_UNIT_LIGHTMAP2D, 0);
    glBindSampler(CG_UNIT_HSAT, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_HSAT, 0);
    return true;
}

CGP_PASS(hybrid_gather, CGP_PARAMS(hybrid_gather_params),
         "Indirect diffuse light by hybrid cone tracing (hybrid paper VI): per step an "
         "axis-aligned fitting cube (eq. 10-11) tested against the 3D lightmap's box (eq. 12) "
         "and the terrain's height range from HSAT (eq. 13-14, empty space skipped), the 3D "
         "lightmap sampled at the intersection's centre (eq. 15) by cone_gather's step (matched "
         "level of eq. 8, surface cap, coverage compositing), the 2D lightmap walked by a DDA, "
         "occlusion by eq. 16 or 17. Cone weights integrate the cosine lobe to 1. Without a 2D "
         "lightmap: the VCT march of cone_gather.");
