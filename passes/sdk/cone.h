/* sdk/cone.h (pass SDK): diffuse cone sets for cone tracing: directions, apertures and weights.
 *
 * Declares: CGP_CONE_MAX, CGP_CONE_SET_SIZES, CGP_MARCH_PARAMS, cgp_cone, cgp_cone_set, cgp_cone_set_make,
 *           cgp_cone_set_sizes, cgp_cone_set_valid_size, cgp_cone_frame, cgp_cone_set_of_param,
 *           cgp_cone_set_of_pass,
 *           cgp_cone_block_fill, cgp_cone_block_fill_march, cgp_cone_upload, cgp_volume_model,
 *           cgp_gather_io, cgp_gather_slots, cgp_gather_find_slots,
 *           cgp_gather_declare_volume, cgp_gather_volume_model, cgp_gather_volume_define, cgp_gather,
 *           cgp_gather_prepare, cgp_gather_begin, cgp_gather_bind_volume, cgp_gather_dispatch,
 *           cgp_gather_end.
 *
 * Shared by every cone tracer (the VCT gather and the hybrid tracer), so it lives in the
 * pass SDK; core knows nothing of cones.
 *
 * A set covers the hemisphere around the normal with a central cone and rings of cones.
 * Each cone owns a cell: a polar band [b_lo, b_hi] split into equal azimuth sectors. Its
 * weight is the cell's share of the cosine lobe,
 *     w = (1/pi) * integral over the cell of cos(theta) d(omega)
 *       = (sin^2 b_hi - sin^2 b_lo) / count_in_ring            (hybrid eq. 3-4, W_k / pi)
 * so the weights telescope to sin^2(pi/2) - sin^2(0) = 1 exactly: a constant incident
 * radiance L gathers to exactly L (the white furnace). docs/vct.md has the derivation.
 */
#ifndef CGP_CONE_H
#define CGP_CONE_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/fg.h"
#include "sdk/blocks.h"
#include "sdk/sky.h"

#define CGP_CONE_MAX CG_CONE_SET_MAX
/* The sizes of the sets cgp_cone_set_make makes, as a list for parameter tables:
 * `.allowed = FG_PARAM_VALUES(CGP_CONE_SET_SIZES)`. */
#define CGP_CONE_SET_SIZES 1, 6, 9, 16, 26

/* The march parameters both gather passes take, the first six entries of their tables:
 * cgp_cone_set_of_param reads `cones` at prepare, cgp_gather_begin the others every frame
 * (cgp_cone_block_fill), so a change of those redoes nothing but the next frame. */
#define CGP_MARCH_PARAMS                                                                              \
    { .name = "cones", .type = FG_PARAM_INT, .default_value = 6, .min = 1, .max = 26,                 \
      .allowed = FG_PARAM_VALUES(CGP_CONE_SET_SIZES), .stage = FG_STAGE_PREPARE,                      \
      .doc = "diffuse cones: 1, 6 (Crassin et al.), 9 (VCT paper 3.2.1), 16 or 26 (16 with its outer " \
             "ring split in two); weights integrate the cosine lobe to 1 (hybrid eq. 3-4)" },          \
    { .name = "aperture", .type = FG_PARAM_FLOAT, .min = 0, .max = 150, .step = 5,                    \
      .stage = FG_STAGE_FRAME,                                                                       \
      .doc = "full apex angle of the diffuse cones in degrees; 0: per cone, the cone with its cell's " \
             "solid angle" },                                                                        \
    { .name = "step", .type = FG_PARAM_FLOAT, .default_value = 0.5, .min = 0.05, .max = 4,            \
      .stage = FG_STAGE_FRAME,                                                                       \
      .doc = "sample spacing as a fraction of the cone diameter (hybrid_gather: its 3D steps, and "   \
             "method=paper with advance=step); 0.5 and less: one sampled voxel or less, where the "   \
             "coverage per step is exact and the result independent of the step" },                  \
    { .name = "start_offset", .type = FG_PARAM_FLOAT, .default_value = 1.5, .min = 0, .max = 16,      \
      .stage = FG_STAGE_FRAME,                                                                       \
      .doc = "voxels the cone origin is moved along the normal, off the surface's own voxels "       \
             "(hybrid_gather with method=paper: the coarser of voxel and 2D texel)" },              \
    { .name = "lod_bias", .type = FG_PARAM_FLOAT, .min = -4, .max = 4, .step = 0.25,                  \
      .stage = FG_STAGE_FRAME,                                                                       \
      .doc = "added to the mip level (cone_gather: the matched level, one below hybrid eq. 8, where " \
             "a trilinear sample spans the footprint; hybrid_gather: both lightmaps', see level); -1 " \
             "(graphs/vct.json) measured closer to the path tracer, docs/vct.md" },                 \
    { .name = "max_distance", .type = FG_PARAM_FLOAT, .min = 0, .max = 1e9, .stage = FG_STAGE_FRAME,  \
      .doc = "metres a cone travels at most; 0: the volume's (hybrid_gather: the maps') diagonal" }

typedef struct cgp_cone {
    float direction[3];     /* tangent space, z = normal; unit length */
    float weight;           /* share of the cosine lobe; a set's weights sum to 1 */
    float half_angle;       /* radians: the cone whose solid angle equals its cell's */
    float cell_lo, cell_hi; /* polar band of the cone's cell, radians */
} cgp_cone;

typedef struct cgp_cone_set {
    int count;
    cgp_cone cones[CGP_CONE_MAX];
} cgp_cone_set;

/* The sizes offered: 1, 6, 9, 16. */
const int *cgp_cone_set_sizes(int *count);
bool cgp_cone_set_valid_size(int count);

/* Fills *out for `count` cones (one of cgp_cone_set_sizes); false for any other count.
 *   1: the normal, cell = the hemisphere.
 *   6: the normal + 5 at 60 deg (Crassin et al. 2011); weights 1/4 and 3/20.
 *   9: the normal + 8 at 45 deg, 45 deg apart in azimuth (VCT paper 3.2.1).
 *  16: the normal + 5 + 10, rings placed so that every cone weighs 1/16. */
bool cgp_cone_set_make(int count, cgp_cone_set *out);

/* Orthonormal tangent frame (t, b, n) for a unit normal n, continuous and free of NaN
 * for every n, the axes included (Duff et al. 2017, "Building an orthonormal basis, revisited"). */
void cgp_cone_frame(const float n[3], float t[3], float b[3]);

/* What every cone gather shares (cone_gather, hybrid_gather and a plugin that wants the same):
 * the parameter `cones` (a set size) and the march parameters `aperture` (full apex angle in
 * degrees, 0: each cone's own), `step`, `start_offset`, `max_distance` and `lod_bias`, which
 * shaders/common/cone_trace.glsl reads from CG_CONE_SET_BLOCK. */

/* The set of the pass's int parameter `param` (voxel_light's `bounce_cones`);
 * CG_ERR_GRAPH_PARAM_RANGE, naming the sets offered, for a size not offered. */
bool cgp_cone_set_of_param(const fg_pass *pass, const char *param, cgp_cone_set *out, cg_error *err);
/* The set of the pass's parameter `cones`. */
bool cgp_cone_set_of_pass(const fg_pass *pass, cgp_cone_set *out, cg_error *err);
/* The block of a set and the pass's march parameters. */
void cgp_cone_block_fill(const fg_pass *pass, const cgp_cone_set *set, cg_cone_set_block *out);
/* The same with the march given: step (fraction of the diameter), start offset (voxels), max
 * distance (m, 0: the volume's diagonal), lod bias; each cone its own aperture. */
void cgp_cone_block_fill_march(const cgp_cone_set *set, double step, double start_offset, double max_distance,
                               double lod_bias, cg_cone_set_block *out);
/* Fills the block and uploads it to `buffer` (cgp_uniform_buffer of its size), bound at CG_BINDING_CONES. */
void cgp_cone_upload(const fg_pass *pass, const cgp_cone_set *set, GLuint buffer);

/* The 3D lightmap a gather reads, by what is connected beside its `volume`
 * (shaders/common/cone_trace.glsl): */
typedef enum cgp_volume_model {
    CGP_VOLUME_RADIANCE,     /* voxelize's radiance model through mip3d: `volume` alone */
    CGP_VOLUME_ANISOTROPIC,  /* the same with mip3d's directional chains `px nx py ny pz nz` */
    CGP_VOLUME_SURFACE       /* voxel_light's surface voxels: `volume` (its radiance), `sides`, `normals` */
} cgp_volume_model;

/* Declares a gather's optional 3D lightmap: the inputs `volume` and `region` (a voxelize or
 * voxel_light pass's block), and with them the six directional chains or `sides` and `normals`.
 * *volume and *region are the inputs' descriptors, NULL when absent. Fails
 * (CG_ERR_GRAPH_MISSING_INPUT) when some of a model's inputs are connected and not the others, or
 * both models' are, and when `volume` comes without `region`; CG_ERR_GRAPH_INCOMPATIBLE when
 * `region` is smaller than a CG_VOLUME_BLOCK. The optional input `glossy` (the surface model only: a
 * voxel_light pass's output of that name, its light one diffuse bounce further) is what the material
 * lobes' cones read (CG_GATHER_GLOSSY, CG_GATHER_LOBE_VOLUME in common/gather.glsl, bound by
 * cgp_gather_begin at CG_UNIT_GLOSSY); without it they read `volume`. */
bool cgp_gather_declare_volume(fg_pass *pass, fg_declare *decl, const fg_resource_desc **volume,
                               const fg_resource_desc **region, cg_error *err);
/* The slots of a cone gather: its own G-buffer inputs and output, which the pass declares and
 * finds itself (cgp_gather_io), and the inputs that cgp_gather_declare_volume and
 * cgp_gather_declare_material declare, which cgp_gather_find_slots finds by the names they declared. */
typedef struct cgp_gather_io {
    fg_slot position, normal;   /* the G-buffer's: at CG_UNIT_POSITION and CG_UNIT_NORMAL */
    fg_slot radiance;           /* the output image (RGBA32F) at image unit 0, the dispatch's size */
} cgp_gather_io;
typedef struct cgp_gather_slots {
    fg_slot position, normal, radiance;
    fg_slot reflection, refraction; /* with parameters specular and refraction (cgp_gather_declare_outputs) */
    fg_slot volume, region, glossy;
    fg_slot directions[6];      /* px nx py ny pz nz */
    fg_slot surface[2];         /* sides, normals */
    fg_slot material[5];        /* albedo, specular, material, transmission, attenuation */
} cgp_gather_slots;
/* In prepare(): `io` and the SDK's slots (cgp_gather_prepare calls it). */
void cgp_gather_find_slots(const fg_pass *pass, cgp_gather_io io, cgp_gather_slots *out);
/* The model of a compiled pass's inputs, and the shader define it needs ("" for the radiance model). */
cgp_volume_model cgp_gather_volume_model(const fg_pass *pass, const cgp_gather_slots *slots);
const char *cgp_gather_volume_define(cgp_volume_model model);

/* What every cone gather's state holds, and its frame around the dispatch: the G-buffer inputs
 * `position` and `normal` at CG_UNIT_POSITION and CG_UNIT_NORMAL, the 3D lightmap at
 * CG_UNIT_VOLUME (trilinear, zero outside), the cone set at CG_BINDING_CONES and the pass's own
 * block at CG_BINDING_GATHER, the scene's baked sky at CG_UNIT_SKY and CG_BINDING_SKY (sdk/sky.h,
 * read by common/sky.glsl's cg_sky_gather at the end of each cone), and the output image
 * `radiance` (RGBA32F) at image unit 0. */
typedef struct cgp_gather {
    cgp_cone_set set;
    bool material;          /* the G-buffer's material inputs are connected (cgp_gather_declare_material) */
    GLuint brdf_table;      /* with `material`: the split-sum table at CG_UNIT_BRDF_TABLE */
    cgp_volume_model model;
    GLuint program;
    GLuint volume_sampler;
    GLuint one_level_sampler; /* the surface model's second binding of the volume (CG_UNIT_OCCUPANCY) */
    GLuint cone_block;      /* CG_CONE_SET_BLOCK */
    GLuint gather_block;    /* the pass's block */
    void *state;            /* the pass state that owns these objects */
    cgp_sky sky;            /* baked once per change of the frame's scene's sky */
    cgp_gather_slots slots; /* found by cgp_gather_prepare */
    GLuint reads;           /* the cone marches' texture reads (cgp_reads_counter), of the pixels
                             * whose own diffuse cones were traced */
} cgp_gather;

/* In prepare(): the slots (the pass's `io` and the SDK's), the cone set of the parameter `cones`,
 * the volume model of the inputs, the compute program `shader` with `defines` (and the model's), the
 * sampler and the blocks (`gather_bytes` for the pass's), owned by `state`. */
bool cgp_gather_prepare(void *state, const fg_pass *pass, cgp_gather *g, cgp_gather_io io, const char *shader,
                        const char *defines, size_t gather_bytes, cg_error *err);
/* In execute(): uses the program, uploads the cone set and the pass's block (`gather_bytes` at
 * `block`), bakes the sky if it changed (cgp_sky_update; fails as it does), binds the G-buffer,
 * `volume` with its `region` block (either may be 0), the model's other volumes
 * (cgp_gather_bind_volume), the sky and `radiance`. */
bool cgp_gather_begin(const fg_pass *pass, cgp_gather *g, const void *block, size_t gather_bytes, GLuint volume,
                      GLuint region, cg_error *err);
/* Binds g's model's volumes beside `volume` (the directional chains at CG_UNIT_ANISO.., or `sides`
 * and `normals` at CG_UNIT_SIDES and CG_UNIT_NORMALS) with `sampler`; with unbind, unbinds them. */
void cgp_gather_bind_volume(const fg_pass *pass, const cgp_gather *g, GLuint sampler, bool unbind);
/* ---- the material terms of a gather (common/gather.glsl, CG_GATHER_MATERIAL)
 *
 * The G-buffer's material outputs as optional inputs of a gather: `albedo` (rho, occlusion),
 * `specular` (F0, F90), `material` (roughness, metallic, thickness), `transmission` (tau, ior) and
 * `attenuation` (sigma), docs/passes.md. They come all five or none (CG_ERR_GRAPH_MISSING_INPUT
 * otherwise); with them the program gets CG_GATHER_MATERIAL and cgp_gather_begin binds them and the
 * split-sum table. Returns whether they are connected. */
bool cgp_gather_declare_material(fg_pass *pass, fg_declare *decl, bool *present, cg_error *err);

/* In declare(), once the G-buffer's `position` is known: the outputs both gathers write at its size,
 * RGBA32F: 'radiance', 'reflection' with parameter specular, 'refraction' with parameter refraction.
 * Returns their descriptor, for a pass's further outputs of the same size. */
fg_resource_desc cgp_gather_declare_outputs(fg_pass *pass, fg_declare *decl, const fg_resource_desc *position);

/* The split-sum table (Karis 2013, "Real Shading in Unreal Engine 4", eq. 8 and its environment BRDF)
 * of the GGX lobe with height-correlated Smith visibility and Schlick Fresnel (the glTF spec's
 * Appendix B), size x size texels, texel (i, j) at n.v = i / (size - 1) and perceptual roughness
 * j / (size - 1) (alpha = roughness^2): the edges hold n.v and roughness 0 and 1 themselves (read
 * at (x (size - 1) + 0.5) / size: common/gather.glsl's cg_gather_brdf), where texel centres at
 * (j + 0.5) / size clamped roughness 1 to 0.984, whose albedo is 5% higher (a rough metal in the
 * furnace read 1.05), RGBA:
 *   r = A(n.v, alpha) = integral of D V (1 - (1 - v.h)^5) n.l dl,
 *   g = B(n.v, alpha) = integral of D V (1 - v.h)^5 n.l dl,
 *     so that the lobe's directional albedo is F0 A + F90 B;
 *   b = c(n.v) = (1/pi) integral of (1 - v.h)^5 n.l dl, the cosine-weighted mean of (1 - v.h)^5 over
 *     the Lambertian lobe, so that the diffuse lobe rho/pi (1 - F(v.h)) has the directional albedo
 *     rho (1 - F0 - (F90 - F0) c);
 *   a = 1.
 * A and B are cg_bsdf_specular_albedo_terms, c is the b of cg_bsdf_diffuse_albedo_terms (cg/bsdf.h,
 * the path tracer's BSDF: 64 x 64 stratified points each). */
#define CGP_BRDF_TABLE_SIZE 32
void cgp_brdf_table_fill(int size, float *rgba);
/* The table of CGP_BRDF_TABLE_SIZE as an RGBA32F texture owned by `state` (linear, clamped),
 * computed once per process. */
GLuint cgp_brdf_table_texture(void *state);

/* The specular lobe's hemispherical albedo terms per roughness: texel j (perceptual roughness
 * j / (size - 1), as the table's rows) holds RG = (Abar, Bbar), the cosine-weighted means over n.v of
 * the table's A and B (2 integral of A(n.v) n.v dn.v, the trapezoid rule over the table's columns),
 * so that F0 Abar + F90 Bbar is
 * what the lobe returns of uniform incident light averaged over the outgoing directions: the
 * view-independent specular albedo a voxel stores (voxelize's `specular`), as
 * cg_bsdf_diffuse_hemispherical is the diffuse lobe's. */
void cgp_brdf_hemispherical_fill(int size, float *rg);
/* That table at CGP_BRDF_TABLE_SIZE as a size x 1 RG32F texture owned by `state` (linear, clamped). */
GLuint cgp_brdf_hemispherical_texture(void *state);

/* The gather's program over `radiance`, a pixel an invocation (after cgp_gather_begin and the pass's
 * own bindings; with sdk/upsample.h's blocks, after cgp_gather_blocks_trace). */
void cgp_gather_dispatch(const fg_pass *pass, const cgp_gather *g);
/* Unbinds what cgp_gather_begin bound (after the dispatches) and hands the frame's texture reads
 * to the graph (fg_pass_report_reads). */
void cgp_gather_end(fg_pass *pass, const cgp_gather *g);

#endif
