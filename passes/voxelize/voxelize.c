/* passes/voxelize: the scene voxelized into a cubic volume (VCT paper 3.1), or with fit = box (model
 * surface) into a box of the same voxels that holds only what the bounds need, in one of two models.
 *
 * model = radiance (the VCT paper's): the scene's direct light in a 3D lightmap.
 *   radiance      3D, resolution^3, RGBA16F or RGBA8, full mip chain declared (mip3d fills
 *                 levels 1..): premultiplied outgoing diffuse radiance (direct light, shadowed
 *                 through the optional shadow map, plus emission) and opacity in alpha.
 * model = surface (docs/vct.md, "surface voxels"): the geometry alone, level 0, which a voxel_light
 *   pass lights (it reads no light, so it can be kept while the light changes); resolution^3, or
 *   with fit = box dims x, y, z (box_dims; each side resolution at most):
 *   albedo        RGBA8: mean albedo of the voxel's fragments, a = 1 where a surface is.
 *   coverage      RGBA8: per axis i, the largest |n_i| / |n|_1 of its fragments' planes, rounded up
 *                 to the next 1/255: the coverage a path along axis i meets crossing them.
 *   normal        RGBA8_SNORM: xyz the mean of the fragments' unit normals as authored (|N| <= 1,
 *                 1 for one plane), w the mean of n . (x - c) / voxel over its fragments, the
 *                 offset of their plane from the voxel's centre c, in voxels.
 *   emission      RGBA16F: mean emitted radiance (rgb) / the region's radiance scale, a = 1 where a
 *                 surface is.
 *   specular      RGBA8: mean specular albedo of the voxel's fragments (F0 Abar + F90 Bbar, the GGX
 *                 lobe's directional albedo averaged over the outgoing directions, sdk/cone.h), a = 1
 *                 where a surface is: the light a metal's voxel returns, which voxel_light's `glossy`
 *                 holds (0 for a Lambertian material).
 * Both models:
 *   region        std140 block CG_VOLUME_BLOCK (common/blocks.h) for common/volume.glsl: where
 *                 the volume lies and how its values decode (consumers bind it at CG_BINDING_VOLUME).
 *   accumulation  3D R32UI, resolution^2 x 4 resolution (surface model: 3 x 2 x 3 slabs of one
 *                 slice of the volume, its x and y sides by depth / slices, common/blocks.h): the
 *                 fixed-point sums and counts of the fragments (shaders/voxelize/voxelize.frag),
 *                 transient working memory, declared so that the memory report counts it. The
 *                 surface model voxelizes and resolves one slice of z after the other, so that this
 *                 transient is 1/slices of the whole volume's 72 bytes a voxel.
 * Inputs (optional, together, model = radiance): shadow (depth) and shadow_matrix (buffer) of a
 * shadow_map pass.
 *
 * Voxelizer (model = surface): `geometry` (the default) projects each triangle on its dominant
 * axis in a geometry shader and rasterizes it dilated (voxelize.geom, voxelize.frag); `compute`
 * runs one invocation per triangle over the voxels of its box (voxelize_tri.comp), the same
 * voxels by the same overlap test, its attributes at the voxel centres: 2 to 3 times faster for a
 * whole build on llvmpipe, slower for a partial one (it dispatches whole meshes, not chunks), and
 * its values differ in the last bits, so the images are of the geometry one (docs/dynamic.md).
 *
 * Caching (model = surface, cache=true, the default): the four geometry volumes are persistent and
 * kept across frames; they read no light, so a turning sun leaves them as they are. They are
 * voxelized again only when what the voxelization reads may have changed: the first frame after
 * prepare, an instance the mesh filter keeps (its world matrix, revision, mesh or material, compared
 * by value, sdk/instances.h), the set of instances, the GPU scene's upload, the region, or the
 * fixed-point and radiance scales (the emission volume stores emission / the radiance scale).
 * When only some instances changed (their matrices or materials; the set, the upload, the region
 * and the scales as they were), the pass re-voxelizes in part: per changed instance the voxels of
 * its box before and after (grown by a voxel, clipped to the volume; overlapping boxes merged) are
 * cleared in the accumulation and voxelized again from every instance whose box reaches them (the
 * moved ones and their static neighbours, such as the terrain under a building), the shaders
 * writing only the region's voxels, then resolved there alone. The sums are integers (atomic adds
 * and maxima), which do not depend on the order or grouping of the fragments, and a region
 * receives every fragment a whole voxelization would put in it, so the volumes equal a whole
 * voxelization bit for bit (tests/passes/test_voxelize_partial.c). A mesh of many triangles
 * (openworld's terrain) is sorted once into chunks by position (build_chunks), so that a region
 * draws only the chunks whose box reaches it, not the whole mesh. When the regions hold more than
 * PARTIAL_LIMIT of the volume, or a changed instance's mesh itself changed, the whole volume is
 * cleared and voxelized again. The light (voxel_light) and its mips are recomputed every frame
 * from the kept volumes. The pass reports which it did through fg_pass_report_rebuilt. Model
 * radiance, and cache=false (the VCT paper's), clear and voxelize everything every frame, so the
 * volume follows moving lights and geometry.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/blocks.h"
#include "sdk/cone.h"
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

/* The surface model's geometry volumes (level 0), as resolve.comp writes them. */
static const char *const geometry_names[5] = {"albedo", "coverage", "normal", "emission", "specular"};
static const GLenum geometry_formats[5] = {GL_RGBA8, GL_RGBA8, GL_RGBA8_SNORM, GL_RGBA16F, GL_RGBA8};
/* Fragments one voxel may sum without overflowing 32 bits, surface model. */
#define SURFACE_HEADROOM 4096.0
/* The surface model's pre-exposure over sdk/radiance.h's (voxelize_execute). */
#define SURFACE_PRE_EXPOSURE 32.0
enum { REGION_MESHES, REGION_SCENE, REGION_EXPLICIT };
enum { FIT_CUBE, FIT_BOX };

static const fg_param_desc voxelize_params[] = {
    { .name = "model", .type = FG_PARAM_ENUM, .default_value = MODEL_RADIANCE, .choices = "radiance|surface",
      .doc = "radiance: the direct light and opacity of each voxel, lit per fragment (VCT paper 3.1; "
             "mip3d, cone_gather); surface: the geometry alone (albedo, mean normal and plane, per-axis "
             "coverage, emission), lit by a voxel_light pass (docs/vct.md)" },
    { .name = "resolution", .type = FG_PARAM_INT, .default_value = 128, .min = 16, .max = 512,
      .power_of_two = true,
      .doc = "voxels along the volume's longest side at level 0 (every side of a cube)" },
    { .name = "fit", .type = FG_PARAM_ENUM, .default_value = FIT_CUBE, .choices = "cube|box",
      .active_when = "model=surface",
      .doc = "cube: a cube of resolution^3 voxels (VCT paper 3.1); box: the same voxels, each side only as "
             "long as the bounds and the padding need, in whole blocks of B voxels (B a power of two: the "
             "shortest side's need, at least resolution / 8), with log2(B) + 1 mip levels: a town of low "
             "buildings in a fraction of the cube's memory (docs/hybrid.md)" },
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
    { .name = "voxelizer", .type = FG_PARAM_ENUM, .default_value = 0, .choices = "geometry|compute",
      .active_when = "model=surface",
      .doc = "geometry: dominant-axis projection in a geometry shader, conservative by dilation (the default); "
             "compute: one invocation per triangle testing the voxels of its box, the same voxels, its attributes "
             "taken at the voxel centres (docs/dynamic.md compares them)" },
    { .name = "cache", .type = FG_PARAM_BOOL, .default_value = 1, .active_when = "model=surface",
      .doc = "keep the geometry volumes across frames; when instances the mesh filter keeps move, voxelize "
             "again only the voxels they covered and cover (the whole volume when the region or the scales "
             "changed, or the changed voxels are over half of it); false: voxelize every frame (the VCT "
             "paper's rebuild)" },
    { .name = "slices", .type = FG_PARAM_INT, .default_value = 8, .min = 1, .max = 64,
      .active_when = "model=surface",
      .doc = "the volume is voxelized in this many slices along z, one after the other, and the accumulation "
             "(the fragments' fixed-point sums, 18 x 4 bytes a voxel) holds one slice: 1/slices of the volume's "
             "(at 128^3: 144 MiB whole, 18 MiB at 8); each slice draws the meshes that reach it again" },
    { .name = "transmissive", .type = FG_PARAM_BOOL, .active_when = "model=surface",
      .doc = "a transmissive material's voxels cover only what its interface reflects, 1 - tau (1 - F), F "
             "the hemispherical Fresnel: cones pass through glass (untinted), as path_trace with "
             "caustics = true sees the sky through it (the lights stop at glass either way: shadow map, "
             "light sampling); false: glass is opaque, as path_trace with caustics = false has it" },
};

/* Where the volume lies: dims voxels along x, y, z (all resolution for a cube), each a cube of
 * edge `voxel`, from `origin`. */
typedef struct voxel_region {
    double origin[3];
    double voxel;
    int dims[3];
} voxel_region;

/* Voxels [lo, hi) of the volume, per axis. */
typedef struct voxel_box {
    int lo[3], hi[3];
} voxel_box;

/* A large mesh's triangles sorted by where they lie (partial re-voxelization): chunk c is the
 * indices [first[c], first[c] + count[c]) of index_buffer, its triangles within the local box
 * lo[c]..hi[c]. index_buffer 0: the mesh is small and drawn whole. */
typedef struct mesh_chunks {
    GLuint index_buffer;
    int count;
    GLsizeiptr *first;
    GLsizei *counts;
    float (*lo)[3], (*hi)[3];
} mesh_chunks;

/* Beside the instances, what the surface model's voxelization reads (compared by value). */
typedef struct surface_build {
    voxel_region region;
    int conservative;
    double unit_fixed, emission_fixed, radiance_scale;
} surface_build;

typedef struct voxelize_state {
    bool surface;
    bool cache;             /* surface model only */
    bool transmissive;      /* surface model: the parameter (surface_sums.glsl) */
    GLuint program;
    GLuint resolve;
    GLuint tri_program;     /* voxelizer=compute */
    GLuint specular_hemispherical;  /* surface model: (Abar, Bbar) per roughness (sdk/cone.h) */
    bool compute;
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
    uint64_t builds;        /* whole voxelizations since prepare */
    uint64_t partial_builds;    /* partial re-voxelizations since prepare */
    /* Partial re-voxelization: the large meshes' triangles sorted into chunks (mesh_count of
     * them, from the upload `chunk_generation`), and scratch for the changed slots and regions. */
    mesh_chunks *chunks;
    int chunk_mesh_count;
    uint64_t chunk_generation;
    int *changed;
    voxel_box *boxes;
    int changed_cap;
    GLsizei *range_counts;
    GLsizeiptr *range_firsts;
    int range_cap;
    fg_slot block, accumulation;
    int slice_depth;        /* the surface model: voxels along z that the accumulation holds (slices) */
    fg_slot radiance;       /* the radiance model */
    fg_slot geometry[5];    /* the surface model: geometry_names */
} voxelize_state;

/* The sides of a `fit = box` volume: with `voxel` the cube's voxel (the longest side's bounds and
 * padding in `resolution` voxels), side k needs need_k = its bounds / voxel + 2 padding voxels (at
 * least one voxel between the paddings); each side is the smallest multiple of a block of B voxels
 * that holds its need, B the largest power of two at most the shortest need, at least
 * resolution / 8 and at most resolution. A cube's bounds give the cube (B = resolution). */
static void
box_dims(int resolution, double padding, const double extent[3], double voxel, int dims[3])
{
    double need[3], shortest = resolution;
    for (int k = 0; k < 3; k++) {
        need[k] = fmax(extent[k] / voxel + 2.0 * padding, 2.0 * padding + 1.0);
        shortest = fmin(shortest, need[k]);
    }
    int block = resolution / 8;
    while (block * 2 <= shortest)  /* shortest starts at resolution: B stays within it */
        block *= 2;
    for (int k = 0; k < 3; k++) {
        /* The longest side's need is resolution up to rounding: never more than resolution. */
        int blocks = (int)ceil(need[k] / block - 1e-9);
        dims[k] = blocks * block < resolution ? blocks * block : resolution;
    }
}

/* The volume over the meshes `meshes` keeps (or the region's bounds); false when there is nothing
 * to voxelize. `dims`: the sides the volume was declared with (execute), or NULL to size it
 * (declare). Voxels are cubes (VCT paper 3.1); the padding is in voxels. With declared sides the
 * voxel grows, should the bounds have outgrown them since (a moved instance), so that the volume
 * still holds them. The parameters met their table (max_* > min_*, padding below a quarter of the
 * resolution) before declare(). */
static bool
voxelize_region(const fg_pass *pass, const cg_scene *scene, const int *dims, voxel_region *out)
{
    memset(out, 0, sizeof *out);    /* surface_build compares regions with memcmp */
    int mode = fg_param_enum(pass, "region");
    cg_mesh_filter filter = (cg_mesh_filter)fg_param_enum(pass, "meshes");
    int resolution = fg_param_int(pass, "resolution");
    double padding = fg_param_float(pass, "padding");
    bool box = fg_param_enum(pass, "model") == MODEL_SURFACE && fg_param_enum(pass, "fit") == FIT_BOX;
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
    double size[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    double extent = fmax(size[0], fmax(size[1], size[2]));
    if (!(extent > 0.0) || !isfinite(extent)) {
        return false;   /* all geometry in one point: no surface to voxelize */
    }
    double side = extent * resolution / (resolution - 2.0 * padding);
    out->voxel = side / resolution;
    if (!box) {
        for (int k = 0; k < 3; k++)
            out->dims[k] = resolution;
    } else if (!dims) {
        box_dims(resolution, padding, size, out->voxel, out->dims);
    } else {
        for (int k = 0; k < 3; k++) {
            out->dims[k] = dims[k];
            if (dims[k] > 2.0 * padding)
                out->voxel = fmax(out->voxel, size[k] / (dims[k] - 2.0 * padding));
        }
    }
    for (int k = 0; k < 3; k++)
        out->origin[k] = 0.5 * (lo[k] + hi[k]) - 0.5 * (box ? out->dims[k] * out->voxel : side);
    return true;
}

/* The surface model's slices (parameter slices): voxels along z of each, the last one thinner
 * where they do not divide the depth (and fewer slices where the depth is short of them); the
 * accumulation holds one. */
static int
slice_depth(const fg_pass *pass, int depth)
{
    int slices = fg_param_int(pass, "slices");
    return (depth + slices - 1) / slices;
}

static bool
voxelize_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    int resolution = fg_param_int(pass, "resolution");
    if (!cgp_declare_shadow_inputs(pass, decl, err))
        return false;

    voxel_region region;
    if (!voxelize_region(pass, frame->scene, NULL, &region)) {
        fg_declare_nothing_to_do(decl, "no mesh passes the 'meshes' filter (or all are degenerate)");
        return true;
    }
    bool surface = fg_param_enum(pass, "model") == MODEL_SURFACE;
    if (surface) {
        /* Level 0 only: voxel_light lights it into volumes of its own, which it mips. */
        for (int i = 0; i < 5; i++) {
            /* cache: kept across frames; persistent storage is never pooled, so nothing else writes
             * it between two frames. */
            fg_resource_desc geometry = {
                .kind = FG_TEXTURE_3D, .format = geometry_formats[i],
                .width = region.dims[0], .height = region.dims[1], .depth = region.dims[2], .levels = 1, .gi = true,
                .persistent = fg_param_bool(pass, "cache"),
            };
            fg_declare_output(decl, geometry_names[i], &geometry, FG_ACCESS_IMAGE_STORE);
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
        .width = (surface ? CG_SURFACE_SLAB_GRID_X : 1) * region.dims[0],
        .height = (surface ? CG_SURFACE_SLAB_GRID_Y : 1) * region.dims[1],
        .depth = surface ? CG_SURFACE_SLAB_GRID_Z * slice_depth(pass, region.dims[2]) : 4 * region.dims[2],
        .levels = 1,
        .gi = true,
    };
    fg_declare_output(decl, "accumulation", &accumulation, FG_ACCESS_IMAGE_STORE | FG_ACCESS_TRANSFER);
    return true;
}

/* What the state holds beside its GL objects: the light cache of cgp_radiance_bound() and the
 * record of the kept volumes' instances. */
static void
free_chunks(voxelize_state *s)
{
    for (int m = 0; m < s->chunk_mesh_count; m++) {
        mesh_chunks *c = &s->chunks[m];
        if (c->index_buffer)
            glDeleteBuffers(1, &c->index_buffer);
        free(c->first);
        free(c->counts);
        free(c->lo);
        free(c->hi);
    }
    free(s->chunks);
    s->chunks = NULL;
    s->chunk_mesh_count = 0;
    s->chunk_generation = 0;
}

static void
voxelize_cleanup(void *state)
{
    voxelize_state *s = state;
    cgp_light_distances_free(&s->light_distances);
    cgp_instance_record_free(&s->instances);
    free_chunks(s);
    free(s->changed);
    free(s->boxes);
    free(s->range_counts);
    free(s->range_firsts);
}

static bool
voxelize_prepare(fg_pass *pass, voxelize_state *s, cg_error *err)
{
    cgp_state_on_destroy(s, voxelize_cleanup);
    s->surface = fg_param_enum(pass, "model") == MODEL_SURFACE;
    s->block = fg_pass_slot(pass, "region");
    s->accumulation = fg_pass_slot(pass, "accumulation");
    if (s->surface)
        s->slice_depth = fg_slot_resource(pass, s->accumulation)->depth / CG_SURFACE_SLAB_GRID_Z;
    for (int i = 0; i < 5 && s->surface; i++)
        s->geometry[i] = fg_pass_slot(pass, geometry_names[i]);
    s->radiance = s->surface ? FG_NO_SLOT : fg_pass_slot(pass, "radiance");
    s->max_buffer = cgp_buffer(s, sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    s->fbo = cgp_framebuffer(s);
    cgp_no_shadow_create(s, pass, &s->no_shadow);
    if (s->surface) {
        s->cache = fg_param_bool(pass, "cache");
        s->transmissive = fg_param_bool(pass, "transmissive");
        s->format = GL_RGBA16F;
        s->compute = fg_param_enum(pass, "voxelizer") == 1;
        s->specular_hemispherical = cgp_brdf_hemispherical_texture(s);
        if (s->compute && !cgp_compute_program(s, "voxelize/voxelize_tri.comp", NULL, &s->tri_program, err))
            return false;
        return cgp_graphics_program(s, "voxelize/voxelize.vert", "voxelize/voxelize.geom", "voxelize/voxelize.frag",
                                    "#define SURFACE\n", &s->program, err) &&
               cgp_compute_program(s, "voxelize/resolve.comp", "#define SURFACE\n", &s->resolve, err);
    }
    s->format = fg_slot_resource(pass, s->radiance)->format;
    char defines[64];
    snprintf(defines, sizeof defines, "#define FORMAT %s\n", s->format == GL_RGBA8 ? "rgba8" : "rgba16f");
    return cgp_graphics_program(s, "voxelize/voxelize.vert", "voxelize/voxelize.geom", "voxelize/voxelize.frag", NULL,
                                &s->program, err) &&
           cgp_compute_program(s, "voxelize/resolve.comp", defines, &s->resolve, err) &&
           (s->format != GL_RGBA8 || cgp_compute_program(s, "voxelize/resolve.comp",
                                                         "#define FORMAT rgba8\n#define FIND_MAX\n", &s->find_max, err));
}

/* Meshes of fewer triangles are drawn whole by a partial re-voxelization: sorting them buys
 * nothing against the cost of a draw. */
#define CHUNK_MIN_TRIANGLES 16384
/* Chunks along the longest axis of a large mesh's box (fewer along the others, in proportion):
 * openworld's terrain (400 m wide, 37 m high) gets a grid of 32 x 3 x 32 cells, a layer or two of
 * them filled per column, so that a region the size of a building draws a few chunks, not the
 * whole terrain. */
#define CHUNKS_PER_AXIS 32
/* A partial re-voxelization when the changed regions hold at most this share of the volume's
 * voxels; above it, the whole volume. Measured on llvmpipe at 128^3 (docs/dynamic.md): a partial
 * one costs about its share of 0.45 s (the clear of 14 slabs, the fragments and the resolve
 * follow the voxels) beside the triangles it draws, a whole one at least 0.23 s (200 k triangles)
 * to 0.5 s (2 M): at 52% of the volume the partial one still cost 0.6 to 0.9 times the whole one
 * on 200 k triangles, and would pass it a little above. */
#define PARTIAL_LIMIT 0.5

/* Sorts the triangles of every large mesh into chunks by the cell of a grid over its box that
 * holds their centroid (a counting sort: order within a cell stays the mesh's), and uploads the
 * sorted indices. The vertices are the mesh's own: only the order in which triangles are drawn
 * changes, which the integer sums of the voxelization do not see. */
static bool
build_chunks(voxelize_state *s, const fg_frame *frame, cg_error *err)
{
    const cg_scene *scene = frame->scene;
    free_chunks(s);
    s->chunks = calloc((size_t)(scene->mesh_count > 0 ? scene->mesh_count : 1), sizeof *s->chunks);
    if (!s->chunks)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory sorting %d meshes into chunks", scene->mesh_count);
    s->chunk_mesh_count = scene->mesh_count;
    for (int m = 0; m < scene->mesh_count; m++) {
        const cg_mesh *mesh = &scene->meshes[m];
        uint32_t triangles = mesh->index_count / 3u;
        if (triangles < CHUNK_MIN_TRIANGLES || !mesh->positions || !mesh->indices)
            continue;
        float extent[3], longest = 0.0f;
        for (int k = 0; k < 3; k++) {
            extent[k] = mesh->bounds_max[k] - mesh->bounds_min[k];
            longest = fmaxf(longest, extent[k]);
        }
        int dims[3];
        for (int k = 0; k < 3; k++)
            dims[k] = longest > 0.0f ? (int)fmaxf(1.0f, fminf((float)CHUNKS_PER_AXIS,
                                                               roundf(CHUNKS_PER_AXIS * extent[k] / longest)))
                                     : 1;
        int cells = dims[0] * dims[1] * dims[2];
        mesh_chunks *c = &s->chunks[m];
        uint32_t *cell_of = malloc(sizeof *cell_of * triangles);
        uint32_t *sorted = malloc(sizeof *sorted * mesh->index_count);
        uint32_t *start = calloc((size_t)cells + 1, sizeof *start);
        c->first = malloc(sizeof *c->first * (size_t)cells);
        c->counts = malloc(sizeof *c->counts * (size_t)cells);
        c->lo = malloc(sizeof *c->lo * (size_t)cells);
        c->hi = malloc(sizeof *c->hi * (size_t)cells);
        if (!cell_of || !sorted || !start || !c->first || !c->counts || !c->lo || !c->hi) {
            free(cell_of);
            free(sorted);
            free(start);
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory sorting mesh '%s' (%u triangles) into chunks",
                           mesh->name, triangles);
        }
        for (uint32_t t = 0; t < triangles; t++) {
            int cell[3];
            for (int k = 0; k < 3; k++) {
                float centroid = 0.0f;
                for (int v = 0; v < 3; v++)
                    centroid += mesh->positions[3 * mesh->indices[3 * t + (uint32_t)v] + (uint32_t)k];
                float u = extent[k] > 0.0f ? (centroid / 3.0f - mesh->bounds_min[k]) / extent[k] : 0.0f;
                cell[k] = (int)fminf(fmaxf(u * (float)dims[k], 0.0f), (float)(dims[k] - 1));
            }
            cell_of[t] = (uint32_t)((cell[2] * dims[1] + cell[1]) * dims[0] + cell[0]);
            start[cell_of[t] + 1]++;
        }
        for (int i = 0; i < cells; i++)
            start[i + 1] += start[i];
        for (int i = 0; i < cells; i++) {
            c->lo[i][0] = c->lo[i][1] = c->lo[i][2] = INFINITY;
            c->hi[i][0] = c->hi[i][1] = c->hi[i][2] = -INFINITY;
        }
        for (uint32_t t = 0; t < triangles; t++) {
            uint32_t cell = cell_of[t], at = start[cell]++;
            for (uint32_t v = 0; v < 3; v++) {
                uint32_t index = mesh->indices[3 * t + v];
                sorted[3 * at + v] = index;
                for (int k = 0; k < 3; k++) {
                    c->lo[cell][k] = fminf(c->lo[cell][k], mesh->positions[3 * index + (uint32_t)k]);
                    c->hi[cell][k] = fmaxf(c->hi[cell][k], mesh->positions[3 * index + (uint32_t)k]);
                }
            }
        }
        /* start[i] now ends cell i; the cells with triangles become the chunks, in order. */
        uint32_t begin = 0;
        for (int i = 0; i < cells; i++) {
            if (start[i] > begin) {
                c->first[c->count] = (GLsizeiptr)begin * 3;
                c->counts[c->count] = (GLsizei)((start[i] - begin) * 3u);
                memmove(c->lo[c->count], c->lo[i], sizeof c->lo[i]);
                memmove(c->hi[c->count], c->hi[i], sizeof c->hi[i]);
                c->count++;
            }
            begin = start[i];
        }
        glCreateBuffers(1, &c->index_buffer);
        glNamedBufferStorage(c->index_buffer, (GLsizeiptr)(sizeof *sorted * mesh->index_count), sorted, 0);
        free(cell_of);
        free(sorted);
        free(start);
    }
    s->chunk_generation = frame->gpu_scene->generation;
    return true;
}

/* The voxels a local box (lo, hi) under `world` may write, grown by a voxel on every side (a
 * triangle reaches the voxels within a hair of its box), clipped to the volume. */
static voxel_box
box_voxels(const voxel_region *region, const float world[16], const float lo[3], const float hi[3])
{
    double wlo[3] = {INFINITY, INFINITY, INFINITY}, whi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int c = 0; c < 8; c++) {
        float corner[3] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]};
        double w[3];
        cgp_transform_point(world, corner, w);
        for (int k = 0; k < 3; k++) {
            wlo[k] = fmin(wlo[k], w[k]);
            whi[k] = fmax(whi[k], w[k]);
        }
    }
    voxel_box box;
    for (int k = 0; k < 3; k++) {
        double a = floor((wlo[k] - region->origin[k]) / region->voxel) - 1.0;
        double b = floor((whi[k] - region->origin[k]) / region->voxel) + 2.0;
        box.lo[k] = (int)fmin(fmax(a, 0.0), (double)region->dims[k]);
        box.hi[k] = (int)fmin(fmax(b, 0.0), (double)region->dims[k]);
    }
    return box;
}

/* Voxels of the whole volume. */
static double
volume_voxels(const voxel_region *region)
{
    return (double)region->dims[0] * region->dims[1] * region->dims[2];
}

static bool
box_empty(const voxel_box *b)
{
    return b->lo[0] >= b->hi[0] || b->lo[1] >= b->hi[1] || b->lo[2] >= b->hi[2];
}

static bool
boxes_overlap(const voxel_box *a, const voxel_box *b)
{
    for (int k = 0; k < 3; k++)
        if (a->hi[k] <= b->lo[k] || b->hi[k] <= a->lo[k])
            return false;
    return true;
}

static double
box_voxel_count(const voxel_box *b)
{
    return box_empty(b) ? 0.0 : (double)(b->hi[0] - b->lo[0]) * (b->hi[1] - b->lo[1]) * (b->hi[2] - b->lo[2]);
}

/* The regions to re-voxelize for the changed record slots: each changed instance's box before
 * and after, overlapping ones merged (a building that moved a little covers one region, not two
 * that would draw its neighbours twice). False when a slot's mesh itself changed: its chunks
 * would be stale, and only a whole rebuild is right. */
static bool
changed_regions(voxelize_state *s, const cg_scene *scene, const voxel_region *region, int changed,
                int *box_count)
{
    int n = 0;
    for (int i = 0; i < changed; i++) {
        const cgp_kept_instance *kept = &s->instances.instances[s->changed[i]];
        const cg_instance *inst = &scene->instances[kept->index];
        const cg_mesh *mesh = &scene->meshes[inst->mesh];
        if (inst->mesh != kept->mesh || memcmp(mesh, &kept->mesh_data, sizeof *mesh))
            return false;
        voxel_box before = box_voxels(region, kept->world, kept->mesh_data.bounds_min,
                                      kept->mesh_data.bounds_max);
        voxel_box after = box_voxels(region, inst->world, mesh->bounds_min, mesh->bounds_max);
        if (!box_empty(&before))
            s->boxes[n++] = before;
        if (!box_empty(&after))
            s->boxes[n++] = after;
    }
    for (bool merged = true; merged;) {
        merged = false;
        for (int a = 0; a < n && !merged; a++)
            for (int b = a + 1; b < n && !merged; b++)
                if (boxes_overlap(&s->boxes[a], &s->boxes[b])) {
                    for (int k = 0; k < 3; k++) {
                        s->boxes[a].lo[k] = s->boxes[a].lo[k] < s->boxes[b].lo[k] ? s->boxes[a].lo[k] : s->boxes[b].lo[k];
                        s->boxes[a].hi[k] = s->boxes[a].hi[k] > s->boxes[b].hi[k] ? s->boxes[a].hi[k] : s->boxes[b].hi[k];
                    }
                    s->boxes[b] = s->boxes[--n];
                    merged = true;
                }
    }
    *box_count = n;
    return true;
}

/* Room for `n` draw ranges. */
static bool
reserve_ranges(voxelize_state *s, int n, cg_error *err)
{
    if (n <= s->range_cap)
        return true;
    GLsizei *counts = realloc(s->range_counts, sizeof *counts * (size_t)n);
    if (counts)
        s->range_counts = counts;
    GLsizeiptr *firsts = realloc(s->range_firsts, sizeof *firsts * (size_t)n);
    if (firsts)
        s->range_firsts = firsts;
    if (!counts || !firsts)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory for %d draw ranges", n);
    s->range_cap = n;
    return true;
}

/* The mesh of instance `i` when the mesh filter keeps it and its box reaches `box`; else NULL.
 * Both voxelizers redraw exactly these instances. */
static const cg_mesh *
instance_in_box(const cg_scene *scene, int i, cg_mesh_filter filter, const voxel_region *region,
                const voxel_box *box)
{
    const cg_instance *inst = &scene->instances[i];
    if (inst->mesh < 0 || inst->mesh >= scene->mesh_count)
        return NULL;
    const cg_mesh *mesh = &scene->meshes[inst->mesh];
    if (!cgp_mesh_passes(mesh->kind, filter) || mesh->index_count == 0)
        return NULL;
    voxel_box whole = box_voxels(region, inst->world, mesh->bounds_min, mesh->bounds_max);
    return box_empty(&whole) || !boxes_overlap(&whole, box) ? NULL : mesh;
}

/* Draws, with the voxelization program bound, every instance `filter` keeps that may write a
 * voxel of `box`: of a chunked mesh only the chunks that may (neighbouring chunks in one range).
 * Returns the triangles drawn through *triangles. */
static bool
draw_box(voxelize_state *s, const fg_frame *frame, cg_mesh_filter filter, const voxel_region *region,
         const voxel_box *box, size_t *triangles, cg_error *err)
{
    const cg_scene *scene = frame->scene;
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_mesh *mesh = instance_in_box(scene, i, filter, region, box);
        if (!mesh)
            continue;
        const cg_instance *inst = &scene->instances[i];
        const mesh_chunks *c = &s->chunks[inst->mesh];
        if (!c->index_buffer) {
            GLsizei count = (GLsizei)mesh->index_count;
            GLsizeiptr first = 0;
            *triangles += cg_gpu_scene_draw_ranges(frame->gpu_scene, i, 0, &count, &first, 1);
            continue;
        }
        if (!reserve_ranges(s, c->count, err))
            return false;
        int ranges = 0;
        for (int k = 0; k < c->count; k++) {
            voxel_box chunk = box_voxels(region, inst->world, c->lo[k], c->hi[k]);
            if (box_empty(&chunk) || !boxes_overlap(&chunk, box))
                continue;
            if (ranges > 0 && s->range_firsts[ranges - 1] + s->range_counts[ranges - 1] == c->first[k]) {
                s->range_counts[ranges - 1] += c->counts[k];
                continue;
            }
            s->range_firsts[ranges] = c->first[k];
            s->range_counts[ranges] = c->counts[k];
            ranges++;
        }
        *triangles += cg_gpu_scene_draw_ranges(frame->gpu_scene, i, c->index_buffer, s->range_counts,
                                               s->range_firsts, ranges);
    }
    return true;
}

/* voxelizer=compute: every instance's triangles, one invocation each (voxelize_tri.comp). */
static size_t
dispatch_triangles(voxelize_state *s, const fg_frame *frame, cg_mesh_filter filter, const voxel_region *region,
                   const voxel_box *box, double unit_fixed, double emission_fixed)
{
    const cg_scene *scene = frame->scene;
    const cg_gpu_scene *gpu = frame->gpu_scene;
    size_t triangles = 0;
    glUseProgram(s->tri_program);
    glUniform4f(8, (float)region->origin[0], (float)region->origin[1], (float)region->origin[2], (float)region->voxel);
    glUniform3i(11, region->dims[0], region->dims[1], s->slice_depth);
    glUniform4f(13, (float)unit_fixed, (float)emission_fixed, 0.0f, s->transmissive ? 1.0f : 0.0f);
    glUniform3i(14, box->lo[0], box->lo[1], box->lo[2]);
    glUniform3i(15, box->hi[0], box->hi[1], box->hi[2]);
    for (int i = 0; i < scene->instance_count; i++) {
        const cg_mesh *mesh = instance_in_box(scene, i, filter, region, box);
        if (!mesh)
            continue;
        const cg_instance *inst = &scene->instances[i];
        /* The matrices, material and textures as the geometry-shader path's draw sets them. */
        cg_gpu_scene_bind_instance(gpu, i);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, gpu->meshes[inst->mesh].vertex_buffer);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, gpu->meshes[inst->mesh].index_buffer);
        GLuint n = mesh->index_count / 3u;
        glUniform1ui(16, n);
        glDispatchCompute((n + 63u) / 64u, 1, 1);
        triangles += n;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, 0);
    glBindVertexArray(0);   /* cg_gpu_scene_bind_instance binds the mesh's */
    return triangles;
}

/* The surface model's resolve (shaders/voxelize/resolve.comp) of the voxels of `box`. */
static void
resolve_surface(fg_pass *pass, voxelize_state *s, const voxel_region *region, const voxel_box *box, double unit_fixed,
                double emission_fixed, double radiance_scale)
{
    glUseProgram(s->resolve);
    glUniform3i(7, region->dims[0], region->dims[1], s->slice_depth);
    glUniform4f(4, (float)unit_fixed, (float)emission_fixed, (float)radiance_scale, 0.0f);
    glUniform3i(5, box->lo[0], box->lo[1], box->lo[2]);
    glUniform3i(6, box->hi[0], box->hi[1], box->hi[2]);
    glBindImageTexture(0, fg_slot_texture(pass, s->accumulation), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
    for (int i = 0; i < 5; i++)
        glBindImageTexture(1 + (GLuint)i, fg_slot_texture(pass, s->geometry[i]), 0, GL_TRUE, 0, GL_WRITE_ONLY,
                           geometry_formats[i]);
    glDispatchCompute((GLuint)(box->hi[0] - box->lo[0] + 3) / 4, (GLuint)(box->hi[1] - box->lo[1] + 3) / 4,
                      (GLuint)(box->hi[2] - box->lo[2] + 3) / 4);
    cgp_compute_end(6, 0, NULL);
}

static bool
voxelize_execute(fg_pass *pass, voxelize_state *s, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    const cg_scene *scene = frame->scene;
    cg_mesh_filter filter = (cg_mesh_filter)fg_param_enum(pass, "meshes");
    int resolution = fg_param_int(pass, "resolution");
    /* The sides declared at compile: the volume's textures are of them. */
    const fg_resource_desc *output = fg_slot_resource(pass, s->surface ? s->geometry[0] : s->radiance);
    const int declared[3] = {output->width, output->height, output->depth};
    voxel_region region;
    if (!voxelize_region(pass, scene, declared, &region))
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
        .info = {(float)resolution, (float)cgp_volume_levels(region.dims[0], region.dims[1], region.dims[2]),
                 (float)radiance_scale, 0.0f},
        .dims = {(float)region.dims[0], (float)region.dims[1], (float)region.dims[2], 0.0f},
    };
    GLuint region_buffer = fg_slot_buffer(pass, s->block);
    glNamedBufferSubData(region_buffer, 0, sizeof block, &block);

    const char *why = NULL;
    surface_build build;
    if (s->surface && s->cache) {
        memset(&build, 0, sizeof build);    /* memcmp compares the padding too */
        memcpy(&build.region, &region, sizeof region);  /* with its padding, zeroed by voxelize_region */
        build.conservative = fg_param_bool(pass, "conservative");
        build.unit_fixed = unit_fixed;
        build.emission_fixed = emission_fixed;
        build.radiance_scale = radiance_scale;
        why = cgp_instances_changed(&s->instances, frame, filter, "a voxelized instance changed");
        if (!why && memcmp(&build, &s->built, sizeof build))
            why = "region or scales changed";
        if (!why) {
            if (s->partial_builds)
                fg_pass_report_rebuilt(pass, "geometry kept (builds: %llu whole, %llu partial)",
                                       (unsigned long long)s->builds, (unsigned long long)s->partial_builds);
            else
                fg_pass_report_rebuilt(pass, "geometry kept (%llu geometry build%s since prepare)",
                                       (unsigned long long)s->builds, s->builds == 1 ? "" : "s");
            return true;
        }
    }

    /* A partial re-voxelization (surface model, cache=true) when what changed is only some
     * instances, the region and scales as they were: the voxels those instances covered before
     * and cover now are cleared, and every instance that may write one of them (the moved ones
     * and their static neighbours, e.g. the terrain under a building) is voxelized again into
     * them alone. The accumulation is of integer sums and maxima, which do not depend on the
     * order or the grouping of the fragments, and every fragment that falls in a region is drawn
     * again, so the region's voxels equal those of a whole voxelization bit for bit; the voxels
     * outside it hold what the same whole voxelization gave them. */
    int box_count = 0;
    bool partial = false;
    char why_full[160] = "";
    if (s->surface && s->cache && s->builds > 0 && !memcmp(&build, &s->built, sizeof build)) {
        if (s->changed_cap < s->instances.count) {
            int cap = s->instances.count;
            int *changed = realloc(s->changed, sizeof *changed * (size_t)cap);
            if (changed)
                s->changed = changed;
            voxel_box *boxes = realloc(s->boxes, sizeof *boxes * 2 * (size_t)cap);
            if (boxes)
                s->boxes = boxes;
            if (!changed || !boxes)
                return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory listing %d changed instances", cap);
            s->changed_cap = cap;
        }
        int changed = 0;
        if (cgp_instances_changed_slots(&s->instances, frame, filter, s->changed, &changed) && changed > 0 &&
            changed_regions(s, scene, &region, changed, &box_count)) {
            double voxels = 0.0;
            for (int i = 0; i < box_count; i++)
                voxels += box_voxel_count(&s->boxes[i]);
            double share = voxels / volume_voxels(&region);
            partial = share <= PARTIAL_LIMIT;
            if (!partial)
                snprintf(why_full, sizeof why_full, "%s; changed regions %.0f%% of the volume > %.0f%%", why,
                         100.0 * share, 100.0 * PARTIAL_LIMIT);
        }
    }
    /* Sorted with the whole build that a partial one may follow (sorting 2 M triangles costs about
     * 0.1 s on llvmpipe: in the frame that voxelizes everything, not in the first that moves). */
    if (s->surface && s->cache &&
        (s->chunk_generation != frame->gpu_scene->generation || s->chunk_mesh_count != scene->mesh_count) &&
        !build_chunks(s, frame, err))
        return false;

    GLuint accum = fg_slot_texture(pass, s->accumulation);
    const GLuint zero = 0;
    if (!s->surface) {
        glClearTexImage(accum, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }

    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    glNamedFramebufferParameteri(s->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, resolution);
    glNamedFramebufferParameteri(s->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, resolution);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glViewport(0, 0, resolution, resolution);
    /* VCT paper 3.1: no depth test, no culling; the fragments go to images only. */
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &s->no_shadow, 2);
    if (s->surface)
        glBindTextureUnit(CG_UNIT_SPECULAR_HEMISPHERICAL, s->specular_hemispherical);

    const voxel_box volume = {{0, 0, 0}, {region.dims[0], region.dims[1], region.dims[2]}};
    size_t triangles = 0;
    double voxels = 0.0;
    for (int b = 0; b < (partial ? box_count : 1); b++) {
        const voxel_box *whole = partial ? &s->boxes[b] : &volume;
        if (partial)
            voxels += box_voxel_count(whole);
        /* The surface model's accumulation holds slice_depth voxels along z (parameter slices):
         * a box deeper than that is voxelized and resolved a slice at a time, each slice's sums
         * starting at the accumulation's z = 0 (surface_sums.glsl). The sums are integers, and a
         * slice receives every fragment that falls in it, so the volumes do not depend on the
         * slicing. */
        int step = s->surface ? s->slice_depth : whole->hi[2] - whole->lo[2];
        for (int z = whole->lo[2]; z < whole->hi[2]; z += step) {
            voxel_box slice = *whole;
            slice.lo[2] = z;
            slice.hi[2] = z + step < whole->hi[2] ? z + step : whole->hi[2];
            const voxel_box *box = &slice;
            if (s->surface) {
                /* The slice's sums start from zero in each slab (surface_sums.glsl's surface_slab);
                 * what the accumulation holds elsewhere is never read. */
                for (int k = 0; k < CG_SURFACE_SLABS; k++)
                    glClearTexSubImage(accum, 0, box->lo[0] + CG_SURFACE_SLAB_X(k) * region.dims[0],
                                       box->lo[1] + CG_SURFACE_SLAB_Y(k) * region.dims[1],
                                       CG_SURFACE_SLAB_Z(k) * s->slice_depth, box->hi[0] - box->lo[0],
                                       box->hi[1] - box->lo[1], box->hi[2] - box->lo[2], GL_RED_INTEGER,
                                       GL_UNSIGNED_INT, &zero);
                glMemoryBarrier(GL_ALL_BARRIER_BITS);
            }
            glUseProgram(s->program);
            glUniform4f(8, (float)region.origin[0], (float)region.origin[1], (float)region.origin[2],
                        (float)region.voxel);
            glUniform1i(9, resolution);
            glUniform1i(12, fg_param_bool(pass, "conservative") ? 1 : 0);
            if (s->surface) {
                glUniform3i(11, region.dims[0], region.dims[1], s->slice_depth);
                glUniform4f(13, (float)unit_fixed, (float)emission_fixed, 0.0f, s->transmissive ? 1.0f : 0.0f);
                glUniform3i(14, box->lo[0], box->lo[1], box->lo[2]);
                glUniform3i(15, box->hi[0], box->hi[1], box->hi[2]);
            } else {
                glUniform1f(10, (float)fixed_scale);
            }
            glBindImageTexture(0, accum, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
            if (s->surface && s->compute) {
                /* Whole meshes, the shader clamping each triangle's voxels to the slice. */
                triangles += dispatch_triangles(s, frame, filter, &region, box, unit_fixed, emission_fixed);
            } else if (partial || (s->cache && box->hi[2] - box->lo[2] < region.dims[2])) {
                /* The chunks of a sorted mesh that reach the slice (build_chunks ran: cache). */
                if (!draw_box(s, frame, filter, &region, box, &triangles, err))
                    return false;
            } else {
                /* The geometry shader drops the triangles that miss the slice (voxelize.geom). */
                triangles += cg_gpu_scene_draw(frame->gpu_scene, filter);
            }
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            if (s->surface) {
                resolve_surface(pass, s, &region, box, unit_fixed, emission_fixed, radiance_scale);
                /* The next slice clears the accumulation this resolve read. */
                glMemoryBarrier(GL_ALL_BARRIER_BITS);
            }
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);

    if (s->surface) {
        glBindTextureUnit(CG_UNIT_SPECULAR_HEMISPHERICAL, 0);
        if (!s->cache) {
            fg_pass_report_rebuilt(pass, "geometry voxelized (cache=false)");
            return true;
        }
        s->built = build;
        if (!cgp_instances_remember(&s->instances, frame, filter, err))
            return false;
        if (partial) {
            s->partial_builds++;
            fg_pass_report_rebuilt(pass, "geometry re-voxelized in part (%s: %d region%s, %.0f voxels (%.2f%%), "
                                   "%zu triangles; builds: %llu whole, %llu partial)",
                                   why, box_count, box_count == 1 ? "" : "s", voxels,
                                   100.0 * voxels / volume_voxels(&region), triangles,
                                   (unsigned long long)s->builds, (unsigned long long)s->partial_builds);
            return true;
        }
        s->builds++;
        if (s->partial_builds)
            fg_pass_report_rebuilt(pass, "geometry voxelized (%s; builds: %llu whole, %llu partial)",
                                   why_full[0] ? why_full : why, (unsigned long long)s->builds,
                                   (unsigned long long)s->partial_builds);
        else
            fg_pass_report_rebuilt(pass, "geometry voxelized (%s; %llu geometry build%s since prepare)",
                                   why_full[0] ? why_full : why, (unsigned long long)s->builds,
                                   s->builds == 1 ? "" : "s");
        return true;
    }
    GLuint groups = (GLuint)((resolution + 3) / 4);
    GLuint radiance = fg_slot_texture(pass, s->radiance);
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
    cgp_compute_end(2, 2, (const GLuint[]){ CG_BINDING_RESOLVE_MAX, CG_BINDING_RESOLVE_REGION });
    return true;
}

CGP_PASS(voxelize, CGP_PARAMS(voxelize_params),
         "Voxelizes the scene into a cubic volume (VCT paper 3.1), or (fit=box) a box of the same voxels "
         "fitted to the bounds: model radiance, the outgoing "
         "diffuse radiance of the direct light (shadowed through the optional shadow map) plus "
         "emission, opacity in alpha; model surface, the geometry a voxel_light pass lights "
         "(albedo, mean normal and plane offset, per-axis coverage, emission). Dominant-axis "
         "projection in a geometry shader, conservative coverage by triangle dilation and an "
         "exact triangle/voxel test, fragments averaged by fixed-point atomic sums. Model radiance is "
         "rebuilt every frame; model surface keeps its volumes across frames (cache=true) and voxelizes "
         "again only the voxels that moved instances covered and cover, from every instance reaching them.");
