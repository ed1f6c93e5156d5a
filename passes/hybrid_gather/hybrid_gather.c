/* passes/hybrid_gather: indirect light by hybrid cone tracing (hybrid paper VI, eq. 8-17)
 * through a 3D lightmap of the complex meshes and a 2D lightmap of the height-field meshes.
 *
 * A separate pass rather than a mode of cone_gather, each shader reading as one method, but
 * no copy of it: both take the 3D steps of shaders/common/cone_trace.glsl (cg_cone_step) and
 * share the pass SDK's cgp_gather (cone set, blocks, bindings). Without the 2D branch (a scene
 * with no height field, where the graph culls heightmap_raster, mip2d and hsat) the shader
 * compiles without HAS_2D and runs the very VCT gather of cone_gather. With it, `method`
 * chooses the paper's steps (METHOD_PAPER) or ours, the horizon (shaders/hybrid_gather/
 * hybrid_gather.comp describes both; docs/hybrid.md measures them).
 *
 * Inputs: position, normal (G-buffer, required); volume + region (mip3d'd voxelize radiance
 * and its block, or voxel_light's surface voxels: its radiance, sides and normals, and voxelize's
 * region, declared by the SDK as cone_gather's); lightmap + region2d (mip2d'd heightmap_raster lightmap and its block) and
 * hsat + hsat_info (an hsat pass's table and info; mode pyramid for the horizon's skipping).
 * Each group is optional; with neither lightmap the pass has nothing to do.
 * Optional, all five or none: the G-buffer's material (albedo, specular, material, transmission,
 * attenuation), as cone_gather's (cgp_gather_declare_material).
 * Output: radiance, RGBA32F: rgb = sum_k W_k L_k (E_i / pi, composite multiplies by the
 * albedo), a = ambient visibility. The same convention as cone_gather, the material's diffuse
 * share included; with `specular` and `refraction` (and the material) also cone_gather's
 * `reflection` and `refraction`, the same cones (common/gather.glsl) through this gather's march.
 * With downsample = 2, 4 or 8 (0: 4 or 8 by the image's height) and temporal, cone_gather's decoupled
 * resolution (sdk/upsample.h): the diffuse cones at one pixel a block, `radiance` upsampled by the
 * G-buffer's position and normal.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/blocks.h"
#include "sdk/pass.h"
#include "sdk/sampler.h"
#include "sdk/cone.h"
#include "sdk/upsample.h"
#include "sdk/scene.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

enum { METHOD_PAPER, METHOD_HORIZON };
enum { LEVEL_MATCHED, LEVEL_EQ8 };
enum { CAP_COMPLEX, CAP_ALL };
enum { CUBE_EQ11, CUBE_EQ10 };
enum { OCCLUSION_EQ16, OCCLUSION_EQ17 };
enum { MIX_PAPER, MIX_SEQUENTIAL };
enum { ADVANCE_CUBE, ADVANCE_STEP };
enum { BOX_MESHES, BOX_VOLUME };

static const fg_param_desc hybrid_gather_params[] = {
    CGP_MARCH_PARAMS,
    { .name = "method", .type = FG_PARAM_ENUM, .default_value = METHOD_HORIZON, .choices = "paper|horizon",
      .doc = "paper: the steps of hybrid VI in the paper's order (fitting cubes, eq. 12-17, morphology search); "
             "horizon: cone_gather's 3D march and the terrain's horizon over each cone's cell (docs/hybrid.md)" },
    { .name = "level", .type = FG_PARAM_ENUM, .stage = FG_STAGE_FRAME, .default_value = LEVEL_MATCHED, .choices = "matched|eq8",
      .doc = "mip level of both lightmaps: eq8 = hybrid eq. 8 itself; matched = one level finer, cone_gather's "
             "(its sample's spread matches the cone's footprint)" },
    { .name = "levels3d", .type = FG_PARAM_INT, .stage = FG_STAGE_FRAME, .default_value = 0, .min = 0, .max = 16,
      .doc = "levels of the 3D lightmap used, from the finest (0: all): the paper's 128^3 in 7 levels" },
    { .name = "box3d", .type = FG_PARAM_ENUM, .stage = FG_STAGE_FRAME, .default_value = BOX_MESHES, .choices = "meshes|volume",
      .doc = "the 3D lightmap's box of eq. 12: the complex meshes' bounds (the paper's; the cubic volume has "
             "empty space around them) or the whole volume (a volume of all meshes)" },
    { .name = "skip", .type = FG_PARAM_BOOL, .default_value = 1,
      .doc = "skip empty space over the terrain: paper: a cube above the highest terrain under it (HSAT, VI.A); "
             "horizon: every block of the min-max pyramid that cannot raise the horizon, hierarchically, off "
             "the 3D lightmap's box (inside it the 3D steps pace the march)" },
    { .name = "terrain_step", .type = FG_PARAM_FLOAT, .stage = FG_STAGE_FRAME, .default_value = 0.25, .min = 0.05, .max = 4,
      .active_when = "method=horizon",
      .doc = "spacing of the terrain samples as a fraction of the cone diameter" },
    { .name = "terrain_lod_bias", .type = FG_PARAM_FLOAT, .stage = FG_STAGE_FRAME, .default_value = -2, .min = -6, .max = 4, .step = 0.25,
      .active_when = "method=horizon",
      .doc = "added to the 2D lightmap's level for the terrain samples: finer heights find the ridges' tops "
             "that a footprint-wide mean flattens" },
    { .name = "surface_cap", .type = FG_PARAM_ENUM, .stage = FG_STAGE_FRAME, .default_value = CAP_COMPLEX, .choices = "complex|all",
      .active_when = "method=horizon",
      .doc = "where cone_gather's handling of the cone's own surface applies (the level cap near the surface on "
             "radiance voxels, the own plane left out on surface voxels): complex = only on points off the height "
             "field (a terrain point has no voxels of its own), all = everywhere" },
    { .name = "cube", .type = FG_PARAM_ENUM, .stage = FG_STAGE_FRAME, .default_value = CUBE_EQ11, .choices = "eq11|eq10",
      .active_when = "method=paper",
      .doc = "fitting cube: eq. 11 for cones off the axes (eq. 10 on them, the paper), or eq. 10's inscribed cube always" },
    { .name = "advance", .type = FG_PARAM_ENUM, .stage = FG_STAGE_FRAME, .default_value = ADVANCE_CUBE, .choices = "cube|step",
      .active_when = "method=paper",
      .doc = "the next step: where the fitting cube ends along the axis (contiguous cubes), or step x diameter" },
    { .name = "ball_threshold", .type = FG_PARAM_FLOAT, .stage = FG_STAGE_FRAME, .default_value = 0.5, .min = 0, .max = 16,
      .active_when = "method=paper",
      .doc = "VI.B: no 3D sample where the cube's intersection with the 3D lightmap has a bounding ball of a "
             "smaller radius (level-0 voxels)" },
    { .name = "abandon", .type = FG_PARAM_BOOL, .stage = FG_STAGE_FRAME, .default_value = 1, .active_when = "method=paper",
      .doc = "VI.A: a cube below the lowest terrain under it (HSAT) ends the cone, lit by the terrain" },
    { .name = "latch", .type = FG_PARAM_BOOL, .stage = FG_STAGE_FRAME, .default_value = 1, .active_when = "method=paper",
      .doc = "VI.C: once a cube lies inside the 3D lightmap, Case 1 only for the rest of the cone" },
    { .name = "dda", .type = FG_PARAM_BOOL, .stage = FG_STAGE_FRAME, .default_value = 1, .active_when = "method=paper",
      .doc = "VI.B's morphology search (segmentation, DDA over sub-meshes, backface culling, dynamic distance, "
             "weighting); else one sample at the cube's centre" },
    { .name = "dda_refine", .type = FG_PARAM_INT, .stage = FG_STAGE_FRAME, .default_value = 1, .min = 0, .max = 4,
      .active_when = "method=paper",
      .doc = "sub-meshes of the search: texels this many levels below the 2D level (at most 8 per side)" },
    { .name = "backface", .type = FG_PARAM_BOOL, .stage = FG_STAGE_FRAME, .default_value = 1, .active_when = "method=paper",
      .doc = "VI.B: sub-meshes facing away from the cone add no radiance" },
    { .name = "weighting", .type = FG_PARAM_BOOL, .stage = FG_STAGE_FRAME, .default_value = 1, .active_when = "method=paper",
      .doc = "VI.B: sub-mesh radiance weighted by max(0, -n.v) (the normal and the cone direction)" },
    { .name = "occlusion", .type = FG_PARAM_ENUM, .stage = FG_STAGE_FRAME, .default_value = OCCLUSION_EQ17, .choices = "eq16|eq17",
      .active_when = "method=paper",
      .doc = "Case 2: eq. 16 (h2 A2 - h1 A1) / (h2 A2) or eq. 17 (step diameter / distance)" },
    { .name = "mix", .type = FG_PARAM_ENUM, .stage = FG_STAGE_FRAME, .default_value = MIX_PAPER, .choices = "paper|sequential",
      .active_when = "method=paper",
      .doc = "VI.C mix case: paper = the 3D sample's opacity raises the heights inside the 3D lightmap's "
             "projection before Case 2; sequential = 3D then 2D, each on its own" },
    { .name = "specular", .type = FG_PARAM_BOOL,
      .doc = "also trace a specular cone (output 'reflection', VCT paper 3.2.2) with the material inputs, as "
             "cone_gather's (common/gather.glsl), through this gather's march" },
    { .name = "refraction", .type = FG_PARAM_BOOL,
      .doc = "also trace a refracted cone where the material transmits (output 'refraction'), as cone_gather's" },
    CGP_DOWNSAMPLE_PARAM,
    CGP_TEMPORAL_PARAM,
    CGP_INTERLEAVE_PARAM,
};

typedef struct hybrid_gather_state {
    cgp_gather gather;      /* its block: CG_HYBRID_GATHER_BLOCK */
    cgp_gather_blocks blocks; /* downsample > 1: the diffuse cones of one pixel a block */
    GLuint map_sampler, table_sampler;
    GLuint empty_block;     /* bound where a map is absent, so no block is left unbound */
    bool has_2d, has_3d, specular, refraction;
    fg_slot lightmap2d, region2d, hsat, hsat_info;
    cg_hybrid_gather_block block;   /* 5.5 KiB: kept here rather than on the stack */
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
    /* The 3D lightmap as cone_gather takes it (sdk/cone.h): radiance voxels through mip3d, or
     * voxel_light's surface voxels with 'sides' and 'normals' (Case 1 is cg_cone_step either way). */
    const fg_resource_desc *volume, *region;
    if (!cgp_gather_declare_volume(pass, decl, &volume, &region, err))
        return false;
    const fg_resource_desc *lightmap = fg_declare_input(decl, "lightmap2d", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    const fg_resource_desc *region2d = fg_declare_input(decl, "region2d", FG_BUFFER, FG_ACCESS_UNIFORM, false);
    const fg_resource_desc *hsat = fg_declare_input(decl, "hsat", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    const fg_resource_desc *hsat_info = fg_declare_input(decl, "hsat_info", FG_BUFFER, FG_ACCESS_STORAGE, false);
    if (lightmap && (!region2d || !hsat || !hsat_info))
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': input 'lightmap2d' needs 'region2d' (heightmap_raster's 'region'), "
                       "'hsat' and 'hsat_info' (an hsat pass's 'table' and 'info')", fg_pass_name(pass));
    if (lightmap &&
        (!check_buffer(pass, region2d, "region2d", sizeof(cg_heightmap_block), "a heightmap_raster 'region'", err) ||
         !check_buffer(pass, hsat_info, "hsat_info", sizeof(cg_hsat_info_block), "an hsat 'info'", err)))
        return false;
    if (lightmap && hsat && fg_param_enum(pass, "method") == METHOD_HORIZON && fg_param_bool(pass, "skip") &&
        hsat->format != GL_RG32UI)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': method=horizon skips with the min-max pyramid: connect an hsat pass with "
                       "mode=pyramid (or set skip=false)", fg_pass_name(pass));
    if (lightmap && hsat && hsat->levels < lightmap->levels)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'hsat' has %d levels, the lightmap %d: connect the hsat of this lightmap",
                       fg_pass_name(pass), hsat->levels, lightmap->levels);
    if (!volume && !lightmap) {
        fg_declare_nothing_to_do(decl, "no lightmap (inputs 'volume' and 'lightmap2d' both absent)");
        return true;
    }
    bool material = false;
    if (!cgp_gather_declare_material(pass, decl, &material, err))
        return false;
    if ((fg_param_bool(pass, "specular") || fg_param_bool(pass, "refraction")) && !material)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': specular and refraction need the material inputs (albedo, specular, material, "
                       "transmission, attenuation: a gbuffer pass's outputs)", fg_pass_name(pass));
    if (!position)
        return true;
    cgp_gather_declare_outputs(pass, decl, position);
    return true;
}

/* The horizon method's quadrature of each cone's cell (sdk/cone.h: a polar band [lo, hi] split
 * into equal azimuth sectors, one per cone of the ring): CG_HYBRID_CELL_POINTS directions of equal
 * cosine weight, 3 polar bands of equal sin^2 (the cosine weight of a band is its share of
 * sin^2) by 2 azimuths, tangent space (z = normal), and the half width of a point's band of
 * polar angles, by which the shader smooths the share below a horizon. */
static void
cell_points(const cgp_cone_set *set, cg_hybrid_gather_block *b)
{
    enum { POLAR = 3, AZIMUTH = CG_HYBRID_CELL_POINTS / 3 };
    for (int k = 0; k < set->count; k++) {
        const cgp_cone *c = &set->cones[k];
        int in_ring = 0;
        for (int j = 0; j < set->count; j++)
            in_ring += set->cones[j].cell_lo == c->cell_lo;
        double sector = 2.0 * M_PI / in_ring;
        double phi0 = atan2(c->direction[1], c->direction[0]);
        double s_lo = sin(c->cell_lo) * sin(c->cell_lo), s_hi = sin(c->cell_hi) * sin(c->cell_hi);
        for (int i = 0; i < POLAR; i++) {
            double theta = asin(sqrt(s_lo + (i + 0.5) * (s_hi - s_lo) / POLAR));
            for (int j = 0; j < AZIMUTH; j++) {
                double phi = phi0 + sector * ((j + 0.5) / AZIMUTH - 0.5);
                float *q = b->cells[k * CG_HYBRID_CELL_POINTS + i * AZIMUTH + j];
                q[0] = (float)(sin(theta) * cos(phi));
                q[1] = (float)(sin(theta) * sin(phi));
                q[2] = (float)cos(theta);
                q[3] = 0.0f;
            }
        }
        b->cell_width[k / 4][k % 4] = (float)(0.5 * (c->cell_hi - c->cell_lo) / POLAR);
    }
}

static bool
hybrid_gather_prepare(fg_pass *pass, hybrid_gather_state *s, cg_error *err)
{
    CGP_SLOTS(pass, s, lightmap2d, region2d, hsat, hsat_info);
    s->has_2d = fg_slot_present(pass, s->lightmap2d);
    /* The cube-centre sample (dda = false) reads the 2D lightmap filtered; the DDA and HSAT fetch. */
    s->map_sampler = cgp_sampler_lightmap2d(s);
    s->table_sampler = cgp_sampler_table(s);
    static const cg_hsat_info_block zero;
    s->empty_block = cgp_buffer(s, sizeof zero, &zero, 0);
    s->specular = fg_param_bool(pass, "specular");
    s->refraction = fg_param_bool(pass, "refraction");
    const cgp_gather_io io = {fg_pass_slot(pass, "position"), fg_pass_slot(pass, "normal"),
                              fg_pass_slot(pass, "radiance")};
    const char *maps = !s->has_2d ? ""
                       : fg_param_enum(pass, "method") == METHOD_PAPER ? "#define HAS_2D\n#define METHOD_PAPER\n"
                                                                       : "#define HAS_2D\n";
    char downsample[64], defines[224];
    snprintf(defines, sizeof defines, "%s%s%s%s", maps, s->specular ? "#define SPECULAR\n" : "",
             s->refraction ? "#define REFRACTION\n" : "", cgp_gather_blocks_define(pass, downsample, sizeof downsample));
    if (!cgp_gather_prepare(s, pass, &s->gather, io, "hybrid_gather/hybrid_gather.comp", defines,
                            sizeof(cg_hybrid_gather_block), err))
        return false;
    s->has_3d = fg_slot_present(pass, s->gather.slots.volume);
    return cgp_gather_blocks_prepare(s, pass, &s->gather, &s->blocks, "hybrid_gather/hybrid_gather.comp", defines,
                                     err);
}

static bool
hybrid_gather_execute(fg_pass *pass, hybrid_gather_state *s, cg_error *err)
{
    cg_hybrid_gather_block *block = &s->block;
    const cg_view *view = &fg_pass_frame(pass)->view;
    *block = (cg_hybrid_gather_block){
        .camera = {view->position[0], view->position[1], view->position[2], 0.0f},
        .maps = {s->has_3d},
        .switches = {fg_param_enum(pass, "cube") == CUBE_EQ11, fg_param_enum(pass, "occlusion"),
                     fg_param_bool(pass, "dda"), fg_param_bool(pass, "skip")},
        .paper = {fg_param_bool(pass, "abandon"), fg_param_bool(pass, "latch"), fg_param_enum(pass, "mix") == MIX_PAPER,
                  fg_param_int(pass, "dda_refine")},
        .paper2 = {fg_param_bool(pass, "backface"), fg_param_bool(pass, "weighting"),
                   fg_param_enum(pass, "advance") == ADVANCE_CUBE},
        .levels = {fg_param_int(pass, "levels3d"), fg_param_enum(pass, "surface_cap") == CAP_COMPLEX,
                   fg_param_enum(pass, "level") == LEVEL_EQ8},
        .params = {fg_param_float(pass, "ball_threshold"), fg_param_float(pass, "terrain_step"),
                   fg_param_float(pass, "terrain_lod_bias")},
    };
    cell_points(&s->gather.set, block);
    /* Eq. 12's box: the complex meshes' bounds; the shader keeps its part inside the volume. */
    double lo[3] = { -1e30, -1e30, -1e30 }, hi[3] = { 1e30, 1e30, 1e30 };
    if (fg_param_enum(pass, "box3d") == BOX_MESHES && !cgp_mesh_bounds(fg_pass_frame(pass)->scene, CG_MESHES_COMPLEX, lo, hi))
        for (int k = 0; k < 3; k++)
            lo[k] = 1e30, hi[k] = -1e30;    /* no complex mesh: the box is empty */
    for (int k = 0; k < 3; k++) {
        block->box3_lo[k] = (float)lo[k];
        block->box3_hi[k] = (float)hi[k];
    }

    const cgp_gather_slots *slots = &s->gather.slots;
    if (!cgp_gather_begin(pass, &s->gather, block, sizeof *block, s->has_3d ? fg_slot_texture(pass, slots->volume) : 0,
                          s->has_3d ? fg_slot_buffer(pass, slots->region) : s->empty_block, err))
        return false;
    glBindBufferBase(GL_UNIFORM_BUFFER, CG_BINDING_HEIGHTMAP,
                     s->has_2d ? fg_slot_buffer(pass, s->region2d) : s->empty_block);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_HSAT,
                     s->has_2d ? fg_slot_buffer(pass, s->hsat_info) : s->empty_block);
    glBindTextureUnit(CG_UNIT_LIGHTMAP2D, s->has_2d ? fg_slot_texture(pass, s->lightmap2d) : 0);
    glBindSampler(CG_UNIT_LIGHTMAP2D, s->map_sampler);
    glBindTextureUnit(CG_UNIT_HSAT, s->has_2d ? fg_slot_texture(pass, s->hsat) : 0);
    glBindSampler(CG_UNIT_HSAT, s->table_sampler);
    cgp_gather_blocks_trace(pass, &s->gather, &s->blocks);
    cgp_gather_dispatch(pass, &s->gather);
    cgp_gather_blocks_deferred(pass, &s->gather, &s->blocks);
    cgp_gather_end(pass, &s->gather);
    cgp_gather_blocks_end(&s->blocks);
    glBindSampler(CG_UNIT_LIGHTMAP2D, 0);
    glBindSampler(CG_UNIT_HSAT, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_HSAT, 0);
    return true;
}

CGP_PASS(hybrid_gather, CGP_PARAMS(hybrid_gather_params),
         "Indirect diffuse light by hybrid cone tracing (hybrid paper VI) through a 3D lightmap of the "
         "complex meshes and a 2D lightmap of the height fields. method=paper: the paper's steps in its "
         "order: fitting cubes (eq. 10-11), the 3D lightmap's box (eq. 12, the Case-1 latch), HSAT skip "
         "and abandon (eq. 13-14), the 3D sample at the intersection's centre (eq. 15, bounding-ball "
         "threshold), the morphology search (Fig. 5 segmentation, DDA, backface culling, dynamic "
         "distance, normal weighting), eq. 16 or 17, the mix case. method=horizon (ours): cone_gather's "
         "3D march and the terrain's horizon over each cone's cell, empty spans skipped hierarchically "
         "with the min-max pyramid. Cone weights integrate the cosine lobe to 1. Without a 2D lightmap: "
         "the VCT march of cone_gather.");
