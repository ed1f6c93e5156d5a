/* passes/voxel_light: the light of voxelize's surface model (docs/vct.md, "surface voxels"), the
 * volumes the cone tracers read with CG_CONE_SURFACE (shaders/common/cone_trace.glsl).
 *
 * Inputs: albedo, coverage, normal, emission and region of a voxelize pass with model = surface
 * (required); its specular (optional: the voxels' specular albedo, which `glossy` reflects);
 * shadow and shadow_matrix of a shadow_map pass (optional, together).
 * Outputs, 3D RGBA16F, voxelize's voxels (a cube or a box), its mip chains (cgp_volume_levels):
 *   radiance  (w L_lit, w), w = alpha_x + alpha_y + alpha_z: the lit side's radiance premultiplied by
 *             the voxel's coverage sum (shaders/voxel_light/inject.comp)
 *   sides     (w beta, w delta, 0, alpha_y): the other side's luminance fraction, the plane offset
 *   normals   (w N, alpha_z): the mean normal of the lit side
 *   glossy    (with glossy = true) the radiance one diffuse bounce further, V_(N+1) of the recursion
 *             below, on the lit side that `normals` holds (its sides and normals are radiance's): what
 *             the gathers' specular and refracted cones read (sdk/cone.h, input 'glossy')
 *   voxels    the list of occupied voxels (list.comp), which the inject and the gathers run over
 *   and, where a bounce is gathered (the header's recursion), gathered_front, gathered_back (level 0:
 *   each side's gathered light); with glossy and specular, source_front and source_back (R11F_G11F_B10F,
 *   level 0: G(V_0), each side's light gathered straight from the sky and the emitters).
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
 *
 * `glossy` is what a specular or refracted cone from the camera sees: a surface that path_trace reaches
 * after a glossy or transmissive scattering at the first hit. Its diffuse lobe keeps every diffuse
 * bounce (V_(N+1): glossy scattering does not count against them); its specular lobe, with one glossy
 * bounce spent, shows the sources alone: the punctual lights and what it sees of the sky and the
 * emitters, as path_trace's next-event estimation and the emitters its BSDF sample hits. With rho the
 * diffuse albedo and rho_s the specular one (voxelize's `specular`, the lobe's hemispherical albedo: a
 * voxel radiates one radiance every way),
 *     glossy = Le + (rho + alpha rho_s) D + rho G(V_N) + rho_s G(V_0)
 * (inject.comp; D here the lights' irradiance / pi, alpha the lobe's GGX alpha: a punctual light's
 * reflection leaves in a lobe about its mirror direction, which one radiance every way cannot hold; a
 * rough lobe keeps it, a mirror's drops it: inject.comp gives the measurement). A metal (rho = 0) is
 * thus lit in the glossy volume and black in the diffuse ones, as path_trace with caustics off (no
 * glossy scattering after a diffuse bounce) has it.
 *
 * Relighting what can have changed (cache = true, the default):
 * the three light volumes are persistent, and a frame relights them only when something the light
 * reads changed since the last relight: the geometry (an instance as sdk/instances.h compares it, the
 * GPU scene's upload, voxelize's region block, read back: region, levels and scales; the input
 * textures), the lights and the shadow map (sdk/shadow.h's lighting record), the sky, or the
 * pass's parameters. A static frame dispatches nothing and keeps the volumes. Where the only gather is
 * the first (bounces = 1 with a sky or emitters: G(V_0), V_0 = Le, reads no punctual light), it is kept
 * too (gathered_front and gathered_back are then persistent) while only the lights or the shadow map
 * changed: a turning sun under a uniform sky costs one inject and its mips. cache = false relights
 * every frame. A relight's cost follows the occupied voxels, not the volume: they are listed (one read
 * per voxel of the volume, again only where the geometry may have changed), level 0 is cleared and the
 * inject and the gathers run over the list (over the whole volume only when it overflows). The pass
 * reports what it did through fg_pass_report_rebuilt, with the compute dispatches it made, so that a
 * test can see a static frame do nothing.
 *
 * The gathers at the voxels, one hemisphere of cones on each side of every occupied voxel, are most of
 * a relight's cost where they run (16 cones, 128^3: 3.6 s a gather on Debian's 12-triangle BoxTextured,
 * 190 150 voxels, on llvmpipe). bounce_spacing S > 1 traces them at one voxel of each S^3 block and
 * mixes the light of the others from the blocks around them where their surfaces agree, as the
 * screen's gathers do with `downsample` (shaders/voxel_light/spacing.glsl says how; the voxels that
 * no block agrees with trace their own). Its `spacing` buffer holds the sorted voxels and each block's
 * representative; they are sorted again only when the voxels are listed again.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/blocks.h"
#include "sdk/cone.h"
#include "sdk/instances.h"
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
    { .name = "bounce_spacing", .type = FG_PARAM_INT, .default_value = 1, .min = 1, .max = 8, .power_of_two = true,
      .doc = "voxels between the points that trace a gather at the voxels: 1 traces at every occupied voxel; S "
             "traces at one voxel of each S^3 block and mixes the others' light from the blocks around them "
             "where their surfaces agree (normal and plane), tracing where none does (docs/vct.md)" },
    { .name = "cache", .type = FG_PARAM_BOOL, .default_value = 1,
      .doc = "keep the light volumes across frames and relight them only when the geometry, the lights, "
             "the shadow map's matrix, the sky or the parameters changed (a static frame dispatches "
             "nothing); the first gather, which reads no punctual light, is kept too while only the "
             "lights changed (bounces = 1). false: relight every frame" },
    { .name = "glossy", .type = FG_PARAM_BOOL, .default_value = 0,
      .doc = "also output 'glossy': the light one diffuse bounce further (V_(N+1)), which the gathers' "
             "specular and refracted cones read (input 'glossy'): on a path from the camera, glossy and "
             "transmissive scattering do not count against the diffuse bounces (path_trace, Cycles), so the "
             "surface a mirror shows keeps its bounce. One more gather at the voxels" },
};

static const char *const geometry_names[5] = {"albedo", "coverage", "normal", "emission", "specular"};
static const GLenum geometry_formats[5] = {GL_RGBA8, GL_RGBA8, GL_RGBA8_SNORM, GL_RGBA16F, GL_RGBA8};
static const char *const light_names[3] = {"radiance", "sides", "normals"};
/* The outputs declared for some parameters only (voxel_light_declare), found by these names. */
static const char *const glossy_name = "glossy";
static const char *const gathered_names[2] = {"gathered_front", "gathered_back"};
static const char *const source_names[2] = {"source_front", "source_back"};

typedef struct voxel_light_state {
    GLuint inject, inject_listed, list, mip, gather;
    GLuint gather_whole;    /* gather.comp over the whole volume, for a list that overflowed */
    GLuint reads;           /* the gathers' cone reads (cgp_reads_counter), of the voxels that traced */
    GLuint pick, planes, sort, fill;    /* bounce_spacing > 1: spacing.glsl's programs (0 otherwise) */
    GLuint sampler;         /* the volumes, for the gathers at the voxels */
    GLuint one_level;       /* the radiance again at CG_UNIT_OCCUPANCY (cgp_sampler_volume_one_level) */
    GLuint cone_block;
    cgp_cone_set set;
    cgp_no_shadow no_shadow;
    cgp_sky sky;            /* the scene's sky, which the gathers at the voxels see (common/sky.glsl) */
    bool gathers;           /* the bounce resources exist */
    bool source;            /* source_front and source_back exist (glossy, with a specular input) */
    bool cache;             /* the light volumes (and gathered_*, when kept) are persistent */
    int spacing;            /* bounce_spacing where the `spacing` buffer exists, else 1 */
    bool spaced;            /* `spacing` sorts the listed voxels of the geometry (sort_voxels) */
    GLuint traced, mixed;   /* how many voxels trace and how many are mixed (sort_voxels) */
    /* What the last relight read (cache = true), to tell whether a frame must relight. */
    bool lit;               /* the volumes hold the light of `key` */
    bool first_gather_kept; /* gathered_* hold G(V_0) of `key` (the only gather of that relight) */
    bool list_kept;         /* `voxels` lists the occupied voxels of `key`'s geometry */
    GLuint listed;          /* occupied voxels found by the last listing (list_voxels) */
    cgp_instance_record instances;
    struct light_key {
        GLuint textures[5];         /* the geometry volumes */
        cg_volume_block region;     /* voxelize's region block as it was read back */
        int bounces, bounce_cones, bounce_spacing;
        bool glossy, lobes;     /* the parameter; whether a material has a lobe (glossy is lit then) */
        cg_sky sky;
    } key;
    cgp_lighting_record lighting;   /* the lights and the shadow map at the last relight (sdk/shadow.h) */
    uint64_t relights;      /* frames that relit since prepare */
    int dispatches;         /* compute dispatches of this frame's execute */
    fg_slot geometry[5];    /* geometry_names */
    fg_slot region, light[3], voxels;   /* light: light_names */
    fg_slot spacing_slot;   /* FG_NO_SLOT when not declared (bounce_spacing 1, or no gather) */
    fg_slot glossy_slot, gathered[2], source_slots[2]; /* FG_NO_SLOT when not declared */
} voxel_light_state;

/* Entries of the list of occupied voxels: a quarter of the volume, far beyond what surfaces
 * occupy in a large one (a plane across a 128^3 volume takes 1 to 3 percent of it), and at least the
 * volume's whole boundary two voxels thick, a closed box that fills the volume: at 32^3 that is 37%
 * of it (10 725 voxels against 8 192 entries before: the gathers at the voxels, which run over the
 * list, missed the rest). From 64^3 up (and for the open world's 128 x 32 x 128 box) the quarter is
 * more. */
static GLuint
list_capacity(const fg_resource_desc *volume)
{
    size_t w = (size_t)volume->width, h = (size_t)volume->height, d = (size_t)volume->depth;
    size_t voxels = w * h * d, shell = 4 * (w * h + h * d + d * w);
    if (shell > voxels)
        shell = voxels;
    return (GLuint)(voxels / 4 > shell ? voxels / 4 : shell);
}

/* The `spacing` buffer (bounce_spacing S > 1, shaders/voxel_light/spacing.glsl): the list of the voxels
 * that trace and that of those mixed, each a cg_voxel_list_block and list_capacity entries, then per
 * block of S^3 voxels its representative's plane and key (SPACING_BLOCK_BYTES, std430's VoxelLightBlock).
 * Each part starts on a multiple of SPACING_ALIGN bytes, so that it binds as a range of its own
 * (GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT is at most 256 on the GL 4.5 implementations this runs
 * on: llvmpipe's is 16). */
#define SPACING_ALIGN 256
#define SPACING_BLOCK_BYTES 32     /* vec4 plane, uint key, padded to the struct's 16-byte alignment */

static size_t
spacing_list_bytes(const fg_resource_desc *volume)
{
    size_t bytes = sizeof(cg_voxel_list_block) + sizeof(GLuint) * list_capacity(volume);
    return (bytes + SPACING_ALIGN - 1) / SPACING_ALIGN * SPACING_ALIGN;
}

static size_t
spacing_blocks(const fg_resource_desc *volume, int spacing)
{
    size_t sp = (size_t)spacing;
    return ((size_t)volume->width + sp - 1) / sp * (((size_t)volume->height + sp - 1) / sp) *
           (((size_t)volume->depth + sp - 1) / sp);
}

static size_t
spacing_bytes(const fg_resource_desc *volume, int spacing)
{
    return 2 * spacing_list_bytes(volume) + SPACING_BLOCK_BYTES * spacing_blocks(volume, spacing);
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
    const fg_resource_desc *geometry[5];
    for (int i = 0; i < 5; i++)
        geometry[i] = fg_declare_input(decl, geometry_names[i], FG_TEXTURE_3D, FG_ACCESS_SAMPLED, i < 4);
    const fg_resource_desc *region = fg_declare_input(decl, "region", FG_BUFFER, FG_ACCESS_UNIFORM, true);
    for (int i = 0; i < 4; i++)
        if (!geometry[i])
            return true;    /* the graph reports the missing input, or culls the pass */
    if (!region)
        return true;
    for (int i = 0; i < 5; i++)
        if (geometry[i] && (geometry[i]->format != geometry_formats[i] || geometry[i]->width != geometry[0]->width ||
            geometry[i]->height != geometry[0]->height || geometry[i]->depth != geometry[0]->depth))
            return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                           "pass '%s': input '%s' is not a voxelize pass's output of model surface (a volume "
                           "of its format, the size of the others): connect albedo, coverage, normal, emission "
                           "(and specular) of one voxelize pass",
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
        /* Kept across frames: a frame that changes nothing keeps them; persistent storage is
         * never pooled, so nothing else writes it between frames. */
        .persistent = fg_param_bool(pass, "cache"),
    };
    for (int i = 0; i < 3; i++)
        fg_declare_output(decl, light_names[i], &light, FG_ACCESS_IMAGE_STORE);
    bool glossy = fg_param_bool(pass, "glossy");
    if (glossy)
        fg_declare_output(decl, glossy_name, &light, FG_ACCESS_IMAGE_STORE);
    if (gathers(pass) > 0 || glossy) {
        fg_resource_desc gathered = light;
        gathered.levels = 1;
        /* G(V_0) is kept while only the lights change where it is the only gather (glossy's gather
         * overwrites it). */
        gathered.persistent = light.persistent && gathers(pass) == 1 && fg_param_int(pass, "bounces") == 1 && !glossy;
        for (int i = 0; i < 2; i++)
            fg_declare_output(decl, gathered_names[i], &gathered, FG_ACCESS_IMAGE_STORE);
    }
    const fg_frame *frame = fg_pass_frame(pass);
    if (glossy && geometry[4] && frame && frame->scene && cg_scene_has_lobes(frame->scene)) {
        /* G(V_0), which glossy's specular lobe reflects, kept past the gathers that follow it; only
         * where a material has a lobe, as `glossy` is lit only there (16 MiB at 128^3). */
        fg_resource_desc source = light;
        source.format = GL_R11F_G11F_B10F;
        source.levels = 1;
        source.persistent = false;
        for (int i = 0; i < 2; i++)
            fg_declare_output(decl, source_names[i], &source, FG_ACCESS_IMAGE_STORE);
    }
    fg_resource_desc list = cgp_buffer_desc(sizeof(cg_voxel_list_block) + sizeof(GLuint) * list_capacity(g));
    list.gi = true;
    list.persistent = light.persistent;     /* kept while the geometry is */
    fg_declare_output(decl, "voxels", &list, FG_ACCESS_STORAGE | FG_ACCESS_TRANSFER);
    /* Only where a gather runs: the bounces' own, or glossy's where a material has a lobe (execute). */
    int spacing = fg_param_int(pass, "bounce_spacing");
    if ((gathers(pass) > 0 || (glossy && frame && frame->scene && cg_scene_has_lobes(frame->scene))) && spacing > 1) {
        fg_resource_desc lists = cgp_buffer_desc(spacing_bytes(g, spacing));
        lists.gi = true;
        lists.persistent = light.persistent;    /* kept while the geometry is, as `voxels` */
        fg_declare_output(decl, "spacing", &lists, FG_ACCESS_STORAGE | FG_ACCESS_TRANSFER);
    }
    return true;
}

static void
voxel_light_cleanup(void *state)
{
    voxel_light_state *s = state;
    cgp_instance_record_free(&s->instances);
    cgp_lighting_record_free(&s->lighting);
}

static bool
voxel_light_prepare(fg_pass *pass, voxel_light_state *s, cg_error *err)
{
    cgp_state_on_destroy(s, voxel_light_cleanup);
    for (int i = 0; i < 5; i++)
        s->geometry[i] = fg_pass_slot(pass, geometry_names[i]);
    for (int i = 0; i < 3; i++)
        s->light[i] = fg_pass_slot(pass, light_names[i]);
    CGP_SLOTS(pass, s, region, voxels);
    s->glossy_slot = fg_pass_slot_if_declared(pass, glossy_name);
    for (int i = 0; i < 2; i++) {
        s->gathered[i] = fg_pass_slot_if_declared(pass, gathered_names[i]);
        s->source_slots[i] = fg_pass_slot_if_declared(pass, source_names[i]);
    }
    s->gathers = fg_slot_present(pass, s->gathered[0]);
    s->spacing_slot = fg_pass_slot_if_declared(pass, "spacing");
    s->spacing = fg_slot_present(pass, s->spacing_slot) ? fg_param_int(pass, "bounce_spacing") : 1;
    s->source = fg_slot_present(pass, s->source_slots[0]);
    s->cache = fg_param_bool(pass, "cache");
    cgp_no_shadow_create(s, pass, &s->no_shadow);
    cgp_sky_prepare(s, &s->sky);
    s->sampler = cgp_sampler_volume(s);
    s->one_level = cgp_sampler_volume_one_level(s);
    s->cone_block = cgp_uniform_buffer(s, sizeof(cg_cone_set_block));
    s->reads = cgp_reads_counter(s);
    if (!cgp_cone_set_of_param(pass, "bounce_cones", &s->set, err))
        return false;
    if (s->spacing > 1) {
        char defines[64];
        snprintf(defines, sizeof defines, "#define VOXEL_LIGHT_SPACING %d\n", s->spacing);
        if (!cgp_compute_program(s, "voxel_light/pick.comp", defines, &s->pick, err) ||
            !cgp_compute_program(s, "voxel_light/planes.comp", defines, &s->planes, err) ||
            !cgp_compute_program(s, "voxel_light/sort.comp", defines, &s->sort, err) ||
            !cgp_compute_program(s, "voxel_light/fill.comp", defines, &s->fill, err))
            return false;
    }
    return cgp_compute_program(s, "voxel_light/inject.comp", NULL, &s->inject, err) &&
           cgp_compute_program(s, "voxel_light/inject.comp", "#define VOXEL_LIGHT_LISTED\n", &s->inject_listed, err) &&
           cgp_compute_program(s, "voxel_light/list.comp", NULL, &s->list, err) &&
           cgp_compute_program(s, "voxel_light/mip.comp", NULL, &s->mip, err) &&
           (!s->gathers ||
            (cgp_compute_program(s, "voxel_light/gather.comp", "#define CG_CONE_SURFACE\n", &s->gather, err) &&
             cgp_compute_program(s, "voxel_light/gather.comp", "#define CG_CONE_SURFACE\n#define VOXEL_LIGHT_WHOLE\n",
                                 &s->gather_whole, err)));
}

/* Lists the occupied voxels (list.comp) into `voxels`; returns how many there are (the list holds
 * at most list_capacity of them). */
static GLuint
list_voxels(const fg_pass *pass, voxel_light_state *s)
{
    const fg_resource_desc *volume = fg_slot_resource(pass, s->light[0]);
    GLuint voxels = fg_slot_buffer(pass, s->voxels);
    const cg_voxel_list_block empty = {.dispatch = {0, 1, 1, 0}};
    glNamedBufferSubData(voxels, 0, sizeof empty, &empty);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, voxels);
    glUseProgram(s->list);
    glUniform1ui(3, list_capacity(volume));
    glBindTextureUnit(0, fg_slot_texture(pass, s->geometry[0]));
    glDispatchCompute((GLuint)(volume->width + 3) / 4, (GLuint)(volume->height + 3) / 4, (GLuint)(volume->depth + 3) / 4);
    s->dispatches++;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    cg_voxel_list_block header;
    glGetNamedBufferSubData(voxels, 0, sizeof header, &header);
    return header.dispatch[3];
}

/* Binds the parts of the `spacing` buffer (spacing_list_bytes) at their storage bindings. */
static void
bind_spacing(const fg_pass *pass, const voxel_light_state *s)
{
    const fg_resource_desc *volume = fg_slot_resource(pass, s->light[0]);
    GLuint buffer = fg_slot_buffer(pass, s->spacing_slot);
    GLintptr part = (GLintptr)spacing_list_bytes(volume);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_TRACED, buffer, 0, part);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_MIXED, buffer, part, part);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_BLOCKS, buffer, 2 * part,
                      (GLsizeiptr)(SPACING_BLOCK_BYTES * spacing_blocks(volume, s->spacing)));
}

static void
unbind_spacing(void)
{
    for (GLuint b = CG_BINDING_VOXEL_TRACED; b <= CG_BINDING_VOXEL_BLOCKS; b++)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
}

/* bounce_spacing > 1 (shaders/voxel_light/spacing.glsl): each block's representative among the listed
 * voxels (pick.comp) and its plane (planes.comp), then each listed voxel into the list of those that
 * trace or of those mixed (sort.comp); their counts into s->traced and s->mixed. Run after list_voxels,
 * with the list whole. */
static void
sort_voxels(const fg_pass *pass, voxel_light_state *s)
{
    const fg_resource_desc *volume = fg_slot_resource(pass, s->light[0]);
    GLuint buffer = fg_slot_buffer(pass, s->spacing_slot);
    GLintptr part = (GLintptr)spacing_list_bytes(volume);
    const cg_voxel_list_block empty = {.dispatch = {0, 1, 1, 0}};
    glNamedBufferSubData(buffer, 0, sizeof empty, &empty);
    glNamedBufferSubData(buffer, part, sizeof empty, &empty);
    /* Every byte of the blocks to all ones: each key VOXEL_LIGHT_NO_KEY (the planes are written where a key is). */
    const GLuint no_key = 0xffffffffu;
    glClearNamedBufferSubData(buffer, GL_R32UI, 2 * part, (GLsizeiptr)(SPACING_BLOCK_BYTES * spacing_blocks(volume, s->spacing)),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &no_key);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, fg_slot_buffer(pass, s->voxels));
    bind_spacing(pass, s);
    glBindTextureUnit(2, fg_slot_texture(pass, s->geometry[2]));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, fg_slot_buffer(pass, s->voxels));
    glUseProgram(s->pick);
    glUniform1ui(3, list_capacity(volume));
    glDispatchComputeIndirect(0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(s->planes);
    glDispatchCompute((GLuint)((spacing_blocks(volume, s->spacing) + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(s->sort);
    glUniform1ui(3, list_capacity(volume));
    glDispatchComputeIndirect(0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    s->dispatches += 3;
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    unbind_spacing();
    cg_voxel_list_block header;
    glGetNamedBufferSubData(buffer, 0, sizeof header, &header);
    s->traced = header.dispatch[3];
    glGetNamedBufferSubData(buffer, part, sizeof header, &header);
    s->mixed = header.dispatch[3];
}

/* Level 0 of the three volumes over the listed voxels alone (inject.comp with VOXEL_LIGHT_LISTED), the
 * level cleared first when `clear` (the occupied voxels may differ from those it was written for). */
static void
inject_listed(const fg_pass *pass, voxel_light_state *s, bool direct, bool gathered, bool clear)
{
    glUseProgram(s->inject_listed);
    glUniform1i(5, false);
    glUniform1i(4, direct);
    glUniform1i(1, gathered);
    glUniform1ui(3, list_capacity(fg_slot_resource(pass, s->light[0])));
    for (int i = 0; i < 3; i++) {
        GLuint tex = fg_slot_texture(pass, s->light[i]);
        if (clear)
            glClearTexImage(tex, 0, GL_RGBA, GL_FLOAT, NULL);
        glBindImageTexture((GLuint)i, tex, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, fg_slot_buffer(pass, s->voxels));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, fg_slot_buffer(pass, s->voxels));
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    s->dispatches++;
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT);
}

/* Level 0 of the three volumes, over the whole volume. */
static void
inject(const fg_pass *pass, voxel_light_state *s, bool direct, bool gathered, bool build_list)
{
    glUseProgram(s->inject);
    glUniform1i(5, false);
    glUniform1i(4, direct);
    glUniform1i(1, gathered);
    glUniform1i(2, build_list);
    const fg_resource_desc *volume = fg_slot_resource(pass, s->light[0]);
    glUniform1ui(3, s->gathers ? list_capacity(volume) : 0u);
    for (int i = 0; i < 3; i++)
        glBindImageTexture((GLuint)i, fg_slot_texture(pass, s->light[i]), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute((GLuint)(volume->width + 3) / 4, (GLuint)(volume->height + 3) / 4, (GLuint)(volume->depth + 3) / 4);
    s->dispatches++;
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT);
}

/* Level 0 of the three volumes: over the list where it holds every occupied voxel, else over the
 * whole volume. *clear: level 0 must be cleared before a listed inject (false after it). */
static void
inject_level0(const fg_pass *pass, voxel_light_state *s, bool direct, bool gathered, bool *clear)
{
    if (s->listed <= list_capacity(fg_slot_resource(pass, s->light[0]))) {
        inject_listed(pass, s, direct, gathered, *clear);
        *clear = false;
    } else {
        inject(pass, s, direct, gathered, false);
    }
}

/* Level 0 of `glossy`: inject's light with the gathered light of the last gather, and the specular
 * albedo's share of the direct light and of G(V_0) (source: source_* hold it; else it is 0), on the
 * side that `normals` holds (u_radiance_only: sides and normals, shared with `radiance`, are bound and not
 * written); over the list where it holds every occupied voxel (the level cleared first), as
 * inject_level0. */
static void
inject_glossy(const fg_pass *pass, voxel_light_state *s, bool source)
{
    const fg_resource_desc *volume = fg_slot_resource(pass, s->light[0]);
    bool listed = s->listed <= list_capacity(volume);
    GLuint glossy = fg_slot_texture(pass, s->glossy_slot);
    glUseProgram(listed ? s->inject_listed : s->inject);
    glUniform1i(5, true);
    glUniform1i(4, true);
    glUniform1i(1, true);
    glUniform1i(6, fg_slot_texture(pass, s->geometry[4]) != 0);
    glUniform1i(7, source);
    glUniform1ui(3, list_capacity(volume));
    if (!listed)
        glUniform1i(2, false);
    else
        glClearTexImage(glossy, 0, GL_RGBA, GL_FLOAT, NULL);
    glBindTextureUnit(7, fg_slot_texture(pass, s->light[2]));
    glBindImageTexture(0, glossy, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    for (int i = 1; i < 3; i++)
        glBindImageTexture((GLuint)i, fg_slot_texture(pass, s->light[i]), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    if (listed) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, fg_slot_buffer(pass, s->voxels));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, fg_slot_buffer(pass, s->voxels));
        glDispatchComputeIndirect(0);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    } else {
        glDispatchCompute((GLuint)(volume->width + 3) / 4, (GLuint)(volume->height + 3) / 4,
                          (GLuint)(volume->depth + 3) / 4);
    }
    s->dispatches++;
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glUniform1i(5, false);  /* the program's next inject writes all three volumes */
    glUniform1i(6, false);
    glUniform1i(7, false);
    glBindTextureUnit(7, 0);
}

/* Levels 1.. of the three volumes from level 0, the first being `first` ("radiance" or "glossy": the
 * sides and normals, the same geometry, are written again as they were). */
static void
mip_of(const fg_pass *pass, voxel_light_state *s, fg_slot first)
{
    glUseProgram(s->mip);
    const fg_resource_desc *volume = fg_slot_resource(pass, s->light[0]);
    for (int level = 1; level < volume->levels; level++) {
        for (int i = 0; i < 3; i++) {
            GLuint tex = fg_slot_texture(pass, i == 0 ? first : s->light[i]);
            glBindImageTexture((GLuint)i, tex, level - 1, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
            glBindImageTexture(3 + (GLuint)i, tex, level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        }
        /* cgp_volume_levels: every side halves exactly. */
        glDispatchCompute((GLuint)((volume->width >> level) + 3) / 4, (GLuint)((volume->height >> level) + 3) / 4,
                          (GLuint)((volume->depth >> level) + 3) / 4);
        s->dispatches++;
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    for (int i = 0; i < 6; i++)
        glBindImageTexture((GLuint)i, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
}

static void
mip(const fg_pass *pass, voxel_light_state *s)
{
    mip_of(pass, s, s->light[0]);
}

/* Each listed voxel's gathered light on both sides, through the current volumes; of_v0: they hold
 * V_0, and the gathered light G(V_0) is written to source_front and source_back too (s->source). */
static void
gather(const fg_pass *pass, voxel_light_state *s, bool of_v0)
{
    /* A list that overflowed misses voxels: then every voxel of the volume gathers (empty ones write 0). */
    bool whole = s->listed > list_capacity(fg_slot_resource(pass, s->light[0]));
    glUseProgram(whole ? s->gather_whole : s->gather);
    glUniform1ui(3, list_capacity(fg_slot_resource(pass, s->light[0])));
    bool source = of_v0 && s->source;
    glUniform1i(4, source);
    if (source) {
        for (int i = 0; i < 2; i++)
            glBindImageTexture(2 + (GLuint)i, fg_slot_texture(pass, s->source_slots[i]), 0, GL_TRUE, 0, GL_WRITE_ONLY,
                               GL_R11F_G11F_B10F);
    }
    glBindTextureUnit(CG_UNIT_VOLUME, fg_slot_texture(pass, s->light[0]));
    glBindTextureUnit(CG_UNIT_SIDES, fg_slot_texture(pass, s->light[1]));
    glBindTextureUnit(CG_UNIT_NORMALS, fg_slot_texture(pass, s->light[2]));
    glBindSampler(CG_UNIT_VOLUME, s->sampler);
    glBindSampler(CG_UNIT_SIDES, s->sampler);
    glBindSampler(CG_UNIT_NORMALS, s->sampler);
    glBindTextureUnit(CG_UNIT_OCCUPANCY, fg_slot_texture(pass, s->light[0]));
    glBindSampler(CG_UNIT_OCCUPANCY, s->one_level);
    glBindTextureUnit(2, fg_slot_texture(pass, s->geometry[2]));
    glBindImageTexture(0, fg_slot_texture(pass, s->gathered[0]), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(1, fg_slot_texture(pass, s->gathered[1]), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    /* Spaced: the voxels that trace (the list's first part, bound as the list), then the mix of the others. */
    const fg_resource_desc *volume = fg_slot_resource(pass, s->light[0]);
    GLuint list = s->spaced ? fg_slot_buffer(pass, s->spacing_slot) : fg_slot_buffer(pass, s->voxels);
    if (s->spaced)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, list, 0, (GLsizeiptr)spacing_list_bytes(volume));
    if (whole) {
        glDispatchCompute((GLuint)(volume->width + 3) / 4, (GLuint)(volume->height + 3) / 4, (GLuint)(volume->depth + 3) / 4);
    } else {
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, list);
        glDispatchComputeIndirect(0);
    }
    s->dispatches++;
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (s->spaced) {
        glUseProgram(s->fill);
        glUniform1ui(3, list_capacity(volume));
        glUniform1i(4, source);
        bind_spacing(pass, s);
        glBindImageTexture(0, fg_slot_texture(pass, s->gathered[0]), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA16F);
        glBindImageTexture(1, fg_slot_texture(pass, s->gathered[1]), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA16F);
        glDispatchComputeIndirect((GLintptr)spacing_list_bytes(volume));
        s->dispatches++;
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        unbind_spacing();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, fg_slot_buffer(pass, s->voxels));
    }
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
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
        glBindTextureUnit((GLuint)i, fg_slot_texture(pass, s->geometry[i]));
    glBindTextureUnit(4, s->gathers ? fg_slot_texture(pass, s->gathered[0]) : 0);
    glBindTextureUnit(5, s->gathers ? fg_slot_texture(pass, s->gathered[1]) : 0);
    glBindTextureUnit(8, fg_slot_texture(pass, s->geometry[4]));
    glBindTextureUnit(9, s->source ? fg_slot_texture(pass, s->source_slots[0]) : 0);
    glBindTextureUnit(10, s->source ? fg_slot_texture(pass, s->source_slots[1]) : 0);
}

/* Whether the frame's scene has a material with a specular or transmission lobe (cg_scene_has_lobes):
 * the gathers' lobe cones, which read `glossy`, are traced there only. */
static bool
key_lobes(const fg_frame *frame)
{
    return frame && frame->scene && cg_scene_has_lobes(frame->scene);
}

/* What a relight would read this frame beside the scene's instances and lights (cache = true). */
static void
read_key(const fg_pass *pass, const voxel_light_state *s, struct light_key *key)
{
    memset(key, 0, sizeof *key);
    for (int i = 0; i < 5; i++)
        key->textures[i] = fg_slot_texture(pass, s->geometry[i]);
    /* voxelize writes its region block every frame: read back, it says whether the region, the
     * levels or the radiance scale moved (48 bytes; the pass's work is done by then anyway). */
    glGetNamedBufferSubData(fg_slot_buffer(pass, s->region), 0, sizeof key->region, &key->region);
    key->bounces = fg_param_int(pass, "bounces");
    key->bounce_cones = fg_param_int(pass, "bounce_cones");
    key->bounce_spacing = fg_param_int(pass, "bounce_spacing");
    key->glossy = fg_param_bool(pass, "glossy");
    key->lobes = key_lobes(fg_pass_frame(pass));
    key->sky = fg_pass_frame(pass)->scene->sky;
}

/* Why this frame must relight (NULL: nothing the light reads changed since the last relight), `key`
 * and `lighting` being what it reads this frame. *lights_only: what changed is the lights or the
 * shadow map alone, which G(V_0) does not read (unless a Preetham sky follows the sun). */
static const char *
what_changed(const fg_pass *pass, const voxel_light_state *s, const struct light_key *key,
             const cgp_lighting_record *lighting, bool *lights_only)
{
    const fg_frame *frame = fg_pass_frame(pass);
    *lights_only = false;
    if (!s->lit)
        return "first frame";
    const char *why = cgp_instances_changed(&s->instances, frame, CG_MESHES_ALL, "an instance changed");
    if (why)
        return why;
    if (memcmp(key->textures, s->key.textures, 5 * sizeof key->textures[0]) ||
        memcmp(&key->region, &s->key.region, sizeof key->region))
        return "geometry volumes or region changed";
    if (key->bounces != s->key.bounces || key->bounce_cones != s->key.bounce_cones ||
        key->bounce_spacing != s->key.bounce_spacing || key->glossy != s->key.glossy ||
        key->lobes != s->key.lobes)
        return "parameters changed";
    if (!cg_sky_equal(&key->sky, &s->key.sky) || key->sky.type != s->key.sky.type)
        return "sky changed";
    cgp_lighting_change change = cgp_lighting_changed(&s->lighting, lighting);
    if (change == CGP_LIGHTING_SAME)
        return NULL;
    bool lights = change == CGP_LIGHTING_LIGHTS;
    *lights_only = !(lights && key->sky.type == CG_SKY_PREETHAM);
    return lights ? "lights changed" : "shadow map changed";
}

/* Keeps what this relight read, for the next frame's what_changed. */
static bool
remember(const fg_pass *pass, voxel_light_state *s, const struct light_key *key, const cgp_lighting_record *lighting,
         bool first_gather_kept, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    s->lit = false;
    if (!cgp_lighting_remember(&s->lighting, lighting, err) ||
        !cgp_instances_remember(&s->instances, frame, CG_MESHES_ALL, err))
        return false;
    s->key = *key;
    s->lit = true;
    s->first_gather_kept = first_gather_kept;
    s->list_kept = true;
    return true;
}

static bool
voxel_light_execute(fg_pass *pass, voxel_light_state *s, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    int bounces = fg_param_int(pass, "bounces");
    s->dispatches = 0;
    /* The gathers' cone reads (common/reads.glsl): 0 on a frame that relights nothing. */
    cgp_reads_begin(s->reads);
    glBindBufferBase(GL_UNIFORM_BUFFER, CG_BINDING_VOLUME, fg_slot_buffer(pass, s->region));
    struct light_key key;
    cgp_lighting_record lighting = {0};
    bool lights_only = false;
    const char *why = "cache=false";
    if (s->cache) {
        read_key(pass, s, &key);
        cgp_lighting_read(pass, &s->no_shadow, &lighting);
        why = what_changed(pass, s, &key, &lighting, &lights_only);
        if (!why) {
            fg_pass_report_rebuilt(pass, "volumes kept (0 dispatches; %llu relight%s since prepare)",
                                   (unsigned long long)s->relights, s->relights == 1 ? "" : "s");
            cgp_reads_end(pass, s->reads, "voxel");
            return true;
        }
    }
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &s->no_shadow, 6);
    /* V_0 = Le, or V_1 = D where nothing emits (the header); then a gather per bounce left. */
    int count = s->gathers ? gathers(pass) : 0;
    bool skip_first = bounces > 0 && count < bounces;
    /* G(V_0) kept where it is the only gather and its outputs persist (declare). */
    const fg_resource_desc *gathered = fg_slot_resource(pass, s->gathered[0]);
    bool keeps_first = s->cache && count == 1 && bounces == 1 && gathered && gathered->persistent;
    bool reuse_first = keeps_first && lights_only && s->first_gather_kept;
    /* The occupied voxels, listed again unless only the lights changed since they were. Level 0 is
     * cleared before the first listed inject of every relight all the same: what it held outside the
     * list is then never a question. */
    if (!(s->cache && lights_only && s->list_kept)) {
        s->listed = list_voxels(pass, s);
        /* Spaced where the list holds every occupied voxel; else each listed voxel traces, as with 1. */
        s->spaced = s->spacing > 1 && s->listed <= list_capacity(fg_slot_resource(pass, s->light[0]));
        if (s->spaced)
            sort_voxels(pass, s);
    }
    bool clear = true;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, fg_slot_buffer(pass, s->voxels));
    if (s->gathers && !reuse_first) {
        cg_cone_set_block cones;
        cgp_cone_block_fill_march(&s->set, BOUNCE_STEP, BOUNCE_START_OFFSET, 0.0, BOUNCE_LOD_BIAS, &cones);
        cgp_uniform_upload(s->cone_block, CG_BINDING_CONES, &cones, sizeof cones);
    }
    if (reuse_first) {
        /* V_1 = Le + D + G(V_0), G(V_0) as the last relight gathered it. */
        bind_inject_inputs(pass, s);
        inject_level0(pass, s, true, true, &clear);
        mip(pass, s);
    } else {
        bind_inject_inputs(pass, s);
        inject_level0(pass, s, skip_first, false, &clear);
        mip(pass, s);
        /* What a cone of a gather at the voxels leaves open sees the sky, as the screen's gather. */
        if (count > 0) {
            if (!cgp_sky_update(s, &s->sky, frame->scene, err))
                return false;
            cgp_sky_bind(&s->sky);
        }
        /* The volumes hold V_0 until the first gather where something emits (skip_first: G(V_0) = 0). */
        for (int b = 0; b < count; b++) {
            gather(pass, s, b == 0 && !skip_first);
            bind_inject_inputs(pass, s);
            inject_level0(pass, s, true, true, &clear);
            mip(pass, s);
        }
        /* V_(N+1) = Le + D + G(V_N) into `glossy` (keeps_first is false: its gather is the last), only
         * where a material has a lobe whose cone reads it (none in the built-in scenes: no cost there). */
        if (fg_slot_resource(pass, s->glossy_slot) && key_lobes(frame)) {
            if (count == 0) {
                if (!cgp_sky_update(s, &s->sky, frame->scene, err))
                    return false;
                cgp_sky_bind(&s->sky);
            }
            gather(pass, s, count == 0 && !skip_first);
            bind_inject_inputs(pass, s);
            inject_glossy(pass, s, s->source && !skip_first);
            mip_of(pass, s, s->glossy_slot);
            count++;
        }
        if (count > 0)
            cgp_sky_unbind();
    }
    for (GLuint unit = 0; unit < 11; unit++)
        glBindTextureUnit(unit, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_VOXEL_LIST, 0);
    glUseProgram(0);
    cgp_reads_end(pass, s->reads, "voxel");
    s->relights++;
    if (reuse_first)
        fg_pass_report_rebuilt(pass, "volumes relit (%s; first gather kept): %d dispatches", why, s->dispatches);
    else if (count > 0 && s->spaced)
        fg_pass_report_rebuilt(pass, "volumes relit (%s): %d dispatches, %d gather%s of %u voxels (%u more mixed: "
                               "bounce_spacing %d)", why, s->dispatches, count, count == 1 ? "" : "s", s->traced,
                               s->mixed, s->spacing);
    else if (count > 0)
        fg_pass_report_rebuilt(pass, "volumes relit (%s): %d dispatches, %d gather%s of %u voxels", why, s->dispatches,
                               count, count == 1 ? "" : "s", s->listed);
    else
        fg_pass_report_rebuilt(pass, "volumes relit (%s): %d dispatches", why, s->dispatches);
    return !s->cache || remember(pass, s, &key, &lighting, keeps_first, err);
}

CGP_PASS(voxel_light, CGP_PARAMS(voxel_light_params),
         "Lights voxelize's surface model (docs/vct.md): each side of every voxel's mean plane gets the "
         "direct light of the scene's lights at its surface point (shadowed through the optional shadow "
         "map, 2 x 2 points across the voxel), its emission and, per bounce as path_trace counts them, the light gathered "
         "at the voxels by the cone tracers' own march; writes the one-sided volumes "
         "radiance, sides and normals with their mip chains (per-axis additive coverage) that "
         "cone_gather and hybrid_gather read.");
