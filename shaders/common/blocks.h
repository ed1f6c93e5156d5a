/* common/blocks.h: the buffer bindings, texture units and block layouts that C and GLSL share,
 * each written once. C includes it through the pass SDK (sdk/blocks.h); GLSL through the shader
 * loader (#include "common/blocks.h"). C compilers define __STDC__, GLSL never does.
 *
 * Provides: CG_BINDING_* and CG_UNIT_* numbers; the member lists CG_*_BLOCK(M, A); in C the
 *           structs cg_shadow_block, cg_volume_block, cg_heightmap_block, cg_hsat_info_block,
 *           cg_cone_set_block, cg_cone_gather_block, cg_hybrid_gather_block, cg_sky_block,
 *           cg_voxel_list_block, cg_gather_deferred_block; in GLSL the
 *           declarations CG_UNIFORM_BLOCK() and CG_STORAGE_BLOCK() that consumers write once.
 *
 * A block is a member list, CG_NAME_BLOCK(M, A), that calls M(type, name) for each member and
 * A(type, name, count) for each array. Members are vec4, ivec4, uvec4 or mat4 and arrays of them
 * only: std140 and std430 lay those out at 16-byte strides with no padding, exactly as a C struct
 * of float[4], int32_t[4], uint32_t[4] and float[16] members, which _Static_assert checks below.
 * In C the list becomes a struct (CG_C_BLOCK); in GLSL a shader declares the block with
 *     CG_UNIFORM_BLOCK(CgVolumeBlock, cg_volume_block, CG_BINDING_VOLUME, CG_VOLUME_BLOCK)
 * and reads cg_volume_block.origin_voxel; the C struct has the name of the GLSL instance. Comments
 * inside the lists are block comments: a line comment would swallow the continued lines.
 *
 * Binding namespaces: uniform blocks (UBO), storage blocks (SSBO) and texture units are three
 * separate sets of numbers in GL, kept apart here so that a reader can tell which is which. GL 4.5
 * guarantees 8 SSBO bindings in a program and 36 UBO bindings.
 */
#ifndef CG_COMMON_BLOCKS_H
#define CG_COMMON_BLOCKS_H

/* ---- storage blocks (SSBO bindings) */
/* 0 and 1 are core's (cg/gpu_scene.h, common/scene.glsl, common/lights.glsl). */
#define CG_BINDING_MATERIALS 0
#define CG_BINDING_LIGHTS 1
/* A pass's counter of its cone marches' texture reads (common/reads.glsl; FG_READS_COUNTER bytes:
 * reads low and high word, the invocations that traced, 0). */
#define CG_BINDING_READS 2
/* hsat's `info` (CG_HSAT_INFO_BLOCK): written by hsat/sat.comp, read by common/hsat.glsl. */
#define CG_BINDING_HSAT 5
/* Private to one pass's programs. */
#define CG_BINDING_HSAT_ROWS 6          /* hsat/sat.comp: the row sums of a level */
#define CG_BINDING_RESOLVE_MAX 4        /* voxelize/resolve.comp: the largest radiance (RGBA8) */
#define CG_BINDING_RESOLVE_REGION 5     /* voxelize/resolve.comp: writes the radiance scale of `region` */
#define CG_BINDING_VOXEL_LIST 4         /* voxel_light: the occupied voxels (CG_VOXEL_LIST_BLOCK) */
#define CG_BINDING_VOXEL_TRACED 5       /* voxel_light, bounce_spacing > 1: the voxels that trace */
#define CG_BINDING_VOXEL_MIXED 6        /* voxel_light, bounce_spacing > 1: the voxels mixed from them */
#define CG_BINDING_VOXEL_BLOCKS 7       /* voxel_light, bounce_spacing > 1: each block's representative */

/* ---- uniform blocks (UBO bindings) */
#define CG_BINDING_SHADOW 2             /* CG_SHADOW_BLOCK, a shadow_map pass's `matrix` */
#define CG_BINDING_VOLUME 3             /* CG_VOLUME_BLOCK, a voxelize pass's `region` */
#define CG_BINDING_HEIGHTMAP 4          /* CG_HEIGHTMAP_BLOCK, a heightmap_raster pass's `region` */
#define CG_BINDING_CONES 7              /* CG_CONE_SET_BLOCK, the cone set and march of a gather */
#define CG_BINDING_GATHER 8             /* a gather pass's own switches (CG_*_GATHER_BLOCK) */
#define CG_BINDING_SKY 10               /* CG_SKY_BLOCK, the baked sky (sdk/sky.h, common/sky.glsl) */

/* ---- texture units of the gather passes (cone_gather, hybrid_gather) */
#define CG_UNIT_VOLUME 0                /* the mipped 3D lightmap */
#define CG_UNIT_POSITION 1              /* G-buffer world position */
#define CG_UNIT_NORMAL 2                /* G-buffer world normal */
#define CG_UNIT_ANISO 3                 /* 3..8: mip3d's directional chains px nx py ny pz nz */
#define CG_UNIT_LIGHTMAP2D 9            /* the mipped 2D lightmap */
#define CG_UNIT_HSAT 10                 /* the HSAT tables */
/* ---- texture units of every pass that reads the sky (the gathers, composite) */
#define CG_UNIT_SKY 11                  /* the baked sky (sdk/sky.h): lat-long x cone aperture, 3D */
#define CG_UNIT_SIDES 12                /* surface voxels (voxel_light): w beta, w delta, -, alpha_y */
#define CG_UNIT_NORMALS 13              /* surface voxels (voxel_light): w N, alpha_z */
#define CG_UNIT_OCCUPANCY 14            /* surface voxels: CG_UNIT_VOLUME's texture, one level a read */
/* ---- texture units of a gather's material inputs (common/gather.glsl, CG_GATHER_MATERIAL): the
 * G-buffer's material outputs (docs/passes.md, gbuffer) and the split-sum table (sdk/cone.h) */
#define CG_UNIT_ALBEDO 15               /* rgb diffuse weight rho, a occlusion */
#define CG_UNIT_SPECULAR 16             /* rgb F0, a F90 */
#define CG_UNIT_MATERIAL 17             /* x roughness, y metallic, z thickness (m) */
#define CG_UNIT_TRANSMISSION 18         /* rgb tau, a ior */
#define CG_UNIT_ATTENUATION 19          /* rgb sigma (1/m) */
#define CG_UNIT_BRDF_TABLE 20           /* the GGX directional-albedo table (cgp_brdf_table_fill) */
#define CG_UNIT_GLOSSY 22               /* voxel_light's glossy: its light one diffuse bounce further */
#define CG_UNIT_GATHER_BLOCKS 21        /* a gather's diffuse light of one pixel per block (sdk/upsample.h) */
/* A gather's blocks with temporal > 1 (sdk/upsample.h, common/upsample.glsl): image units of the
 * surface each block's light was traced at (position, then normal at the next unit), texture units
 * of the last frame's (the same two), the uniforms of the frame's turn and of the last camera. */
#define CG_IMAGE_BLOCK_HISTORY 5
#define CG_UNIT_BLOCK_PREVIOUS 29
#define CG_UPSAMPLE_TEMPORAL_LOCATION 20
#define CG_UPSAMPLE_PREVIOUS_LOCATION 21
/* A gather's pixels that no block agrees with (sdk/upsample.h): SSBO, CG_GATHER_DEFERRED_BLOCK. */
#define CG_BINDING_GATHER_DEFERRED 3
/* ---- texture units of voxelize's surface model beside the scene's (common/scene.glsl: 0, 1, 24..27) */
#define CG_UNIT_SPECULAR_HEMISPHERICAL 28 /* the specular lobe's (Abar, Bbar) per roughness (cgp_brdf_hemispherical_fill) */

/* voxelize's surface model: its accumulation volume holds CG_SURFACE_SLABS R32UI slabs of the volume's
 * size (shaders/voxelize/surface_sums.glsl: count, albedo RGB, emission RGB, normal xyz, plane offset,
 * coverage xyz, specular albedo RGB, GGX alpha) on a grid of 3 x 2 x 3, slab k at (k % 3, (k / 3) % 2,
 * k / 6): 512^3 voxels then fit GL_MAX_3D_TEXTURE_SIZE 2048 along every axis, which 18 along one would
 * not. */
#define CG_SURFACE_SLABS 18
#define CG_SURFACE_SLAB_GRID_X 3
#define CG_SURFACE_SLAB_GRID_Y 2
#define CG_SURFACE_SLAB_GRID_Z 3
#define CG_SURFACE_SLAB_X(k) ((k) % 3)
#define CG_SURFACE_SLAB_Y(k) (((k) / 3) % 2)
#define CG_SURFACE_SLAB_Z(k) ((k) / 6)

/* The most cones a diffuse set holds (sdk/cone.h: CGP_CONE_MAX): the largest set, 26, rounded up to
 * a multiple of 4, as cell_width packs four cones per vec4. */
#define CG_CONE_SET_MAX 28
/* Levels the hsat info block has means for. */
#define CG_HSAT_MAX_LEVELS 16

/* ---- block layouts */

/* One shadow map's lookup (common/shadow.glsl), written by the shadow_map pass; 192 bytes. */
#define CG_SHADOW_BLOCK(M, A)                                                                     \
    M(mat4, view)       /* world -> light view (looks down -z) */                                \
    M(mat4, view_proj)  /* world -> light clip */                                                \
    M(vec4, params)     /* x constant bias, y slope bias (texels), z filter radius (texels), w resolution */ \
    M(vec4, frustum)    /* x light index (-1: no shadow map), y 1 orthographic / 0 perspective, z near, w far */ \
    M(vec4, light)      /* xyz: towards the light (orthographic) or the light's position */      \
    M(vec4, texel)      /* xy: texel world size along light x, y (orthographic), or per metre of distance */

/* Where a 3D lightmap lies (common/volume.glsl), a voxelize pass's `region`; 48 bytes. */
#define CG_VOLUME_BLOCK(M, A)                                                                     \
    M(vec4, origin_voxel) /* xyz: world position of the minimum corner; w: voxel edge at level 0 */ \
    M(vec4, info)         /* x voxels along the longest side, y mip levels, z radiance scale */    \
                          /* (stored x scale = radiance) */                                       \
    M(vec4, dims)         /* xyz: voxels along x, y, z at level 0 (all equal for a cube) */

/* Where a 2D lightmap lies (common/heightmap.glsl), a heightmap_raster pass's `region`; 48 bytes. */
#define CG_HEIGHTMAP_BLOCK(M, A)                                                                  \
    M(vec4, origin_texel) /* xy: world (x, z) of the minimum corner; zw: texel size along x and z */ \
    M(vec4, info)         /* x texels per edge, y mip levels, z y_min, w y_max */                 \
    M(vec4, radiance)     /* x: radiance scale (stored rgb x scale = radiance; 1 for RGBA32F) */

/* An hsat pass's `info` (common/hsat.glsl), std430; 272 bytes. */
#define CG_HSAT_INFO_BLOCK(M, A)                                                                  \
    M(vec4, params)                       /* x mode, y exponent p, z levels */                    \
    A(vec4, means, CG_HSAT_MAX_LEVELS)    /* per level: means of x, x^p, (1 - x)^p subtracted from the tables */

/* A gather's diffuse cone set and march (common/cone_trace.glsl), uploaded by cgp_cone_upload; 928 bytes. */
#define CG_CONE_SET_BLOCK(M, A)                                                                   \
    A(vec4, cones, CG_CONE_SET_MAX)       /* xyz: tangent-space direction (z = normal), w: weight W_k */ \
    A(vec4, apertures, CG_CONE_SET_MAX)   /* x: tan of the half apex angle */                     \
    M(ivec4, count)                       /* x: cones in the set */                               \
    M(vec4, march)        /* x step (fraction of the diameter), y start offset (xels), */        \
                          /* z max distance (m; <= 0: the maps' diagonal), w lod bias */

/* cone_gather's specular, refracted and shadow cones; 48 bytes. */
#define CG_CONE_GATHER_BLOCK(M, A)                                                                \
    M(vec4, camera)       /* xyz: the camera's world position (the specular cone's view direction) */ \
    M(vec4, tan_half)     /* x: specular cone without a material input (its roughness^2), y: shadow cone */ \
    M(ivec4, shadow)      /* x: index of the light the shadow cone points at */

/* voxel_light's occupied voxels, std430: this header, then one uint per voxel (its level-0 index,
 * x | y << 10 | z << 20); the header is an indirect dispatch (glDispatchComputeIndirect reads x, y,
 * z: groups of 64 voxels) and w the voxels found; 16 bytes before the list. */
#define CG_VOXEL_LIST_BLOCK(M, A)                                                                 \
    M(uvec4, dispatch)    /* x groups of 64 voxels, y = z = 1, w voxels listed */

/* A gather's pixels that trace their own diffuse cones (common/upsample.glsl), std430: this header,
 * then one uint per pixel (x | y << 16); the header is an indirect dispatch (x groups of 64 pixels,
 * y = z = 1) and w the pixels listed. */
#define CG_GATHER_DEFERRED_BLOCK(M, A)                                                             \
    M(uvec4, dispatch)    /* x groups of 64 pixels, y = z = 1, w pixels listed */

/* Quadrature points per cone cell in hybrid_gather's horizon method. */
#define CG_HYBRID_CELL_POINTS 6

/* hybrid_gather's horizon method samples the 3D lightmap on the part of a cone's footprint the
 * terrain left open: a unit disc above the chord at height u, whose open share a is
 * (acos u - u sqrt(1 - u^2)) / pi. The step samples it at that circular segment's centroid,
 * S(a) = (2/3) (1 - u^2)^(3/2) / (pi a) radii above the centre. Inverting the area for u takes
 * iterations (asin in each) that llvmpipe would run at every step of the march, so S is a
 * closed form here, shared by the shader and its unit test:
 *   - for a <= 1/2, S is a degree-4 polynomial in w = a^(2/3), in which it is smooth
 *     (1 - 0.84 w + ... as a -> 0); a least-squares fit, within 1.7e-5 radii of the exact
 *     centroid (degree 3: 1.1e-4; the 33-point table this replaces: 6e-4);
 *   - for a > 1/2, the disc's centroid is its centre, so a S(a) = (1 - a) S(1 - a) gives
 *     S(a) = (1 - a) S(1 - a) / a, with no fit of its own (S -> 0 linearly as a -> 1).
 * CG_SEGMENT_CENTROID_FIT(w) is the polynomial, for w = min(a, 1 - a)^(2/3); GLSL and C alike
 * (tests/tools/fit_segment_centroid.py fits it). */
#define CG_SEGMENT_CENTROID_FIT(w)                                                                \
    ((((-0.04480492 * (w) - 0.0066729) * (w) - 0.09072905) * (w) - 0.84263419) * (w) + 0.99998642)

/* hybrid_gather's parameters (passes/hybrid_gather/hybrid_gather.c); 2944 bytes. */
#define CG_HYBRID_GATHER_BLOCK(M, A)                                                              \
    M(vec4, camera)       /* xyz: the camera's world position (the specular and refracted cones' view) */ \
    M(ivec4, maps)        /* x: a 3D lightmap is bound */                                          \
    M(ivec4, switches)    /* x: eq. 11 (else eq. 10), y: occlusion (0 eq. 16, 1 eq. 17), z: the morphology search, w: skipping */ \
    M(ivec4, paper)       /* x: abandon buried cubes, y: the Case-1 latch, z: the paper's mix case, w: sub-mesh levels below eq. 8 */ \
    M(ivec4, paper2)      /* x: backface culling, y: normal/cone weighting, z: contiguous cubes (else step x d) */ \
    M(ivec4, levels)      /* x: 3D levels used (0: all), y: no surface cap on the height field, z: eq. 8 itself (else one finer) */ \
    M(vec4, params)       /* x: bounding-ball threshold (level-0 voxels), y: terrain step, z: terrain lod bias */ \
    M(vec4, box3_lo)      /* xyz: the 3D lightmap's box of eq. 12 (the complex meshes' bounds in the volume) */ \
    M(vec4, box3_hi)                                                                              \
    A(vec4, cell_width, CG_CONE_SET_MAX / 4) /* per cone: the half width (radians) of a quadrature point's band */ \
    A(vec4, cells, CG_CONE_SET_MAX * CG_HYBRID_CELL_POINTS) /* xyz: tangent-space quadrature points of each cone's cell */

/* The baked sky (common/sky.glsl), uploaded by cgp_sky_bind (sdk/sky.h); 16 bytes. */
#define CG_SKY_BLOCK(M, A)                                                                        \
    M(vec4, info)         /* x: 1 a sky is baked (0: none, nothing is added), y: aperture layers, */ \
                          /* z: half angle of layer 1 (radians; layer k > 0: z 2^(k-1)) */

#ifdef __STDC__
/* ---- C: one struct per block (sdk/blocks.h includes <stdint.h> first: the shader loader
 * expands every #include, also under #ifdef, and knows no system headers) */

typedef float cg_block_vec4[4];
typedef int32_t cg_block_ivec4[4];
typedef uint32_t cg_block_uvec4[4];
typedef float cg_block_mat4[16];    /* column-major, as GLSL reads it */

#define CG_C_MEMBER(type, name) cg_block_##type name;
#define CG_C_ARRAY(type, name, count) cg_block_##type name[count];
#define CG_C_MEMBER_BYTES(type, name) +sizeof(cg_block_##type)
#define CG_C_ARRAY_BYTES(type, name, count) +(count) * sizeof(cg_block_##type)
/* The struct `name` of a block; asserts its size (`bytes`, as documented) and that C added no
 * padding, i.e. that it has the std140 / std430 layout. */
#define CG_C_BLOCK(name, MEMBERS, bytes)                                                          \
    typedef struct name {                                                                         \
        MEMBERS(CG_C_MEMBER, CG_C_ARRAY)                                                          \
    } name;                                                                                       \
    _Static_assert(sizeof(name) == (0 MEMBERS(CG_C_MEMBER_BYTES, CG_C_ARRAY_BYTES)), #name " is padded"); \
    _Static_assert(sizeof(name) == (bytes), #name " is " #bytes " bytes")

CG_C_BLOCK(cg_shadow_block, CG_SHADOW_BLOCK, 192);
CG_C_BLOCK(cg_volume_block, CG_VOLUME_BLOCK, 48);
CG_C_BLOCK(cg_heightmap_block, CG_HEIGHTMAP_BLOCK, 48);
CG_C_BLOCK(cg_hsat_info_block, CG_HSAT_INFO_BLOCK, 272);
CG_C_BLOCK(cg_cone_set_block, CG_CONE_SET_BLOCK, 928);
CG_C_BLOCK(cg_cone_gather_block, CG_CONE_GATHER_BLOCK, 48);
CG_C_BLOCK(cg_hybrid_gather_block, CG_HYBRID_GATHER_BLOCK, 2944);
CG_C_BLOCK(cg_sky_block, CG_SKY_BLOCK, 16);
CG_C_BLOCK(cg_voxel_list_block, CG_VOXEL_LIST_BLOCK, 16);
CG_C_BLOCK(cg_gather_deferred_block, CG_GATHER_DEFERRED_BLOCK, 16);

#else
/* ---- GLSL: the declaration of a block, written once by its consumer */
#define CG_GLSL_MEMBER(type, name) type name;
#define CG_GLSL_ARRAY(type, name, count) type name[count];
/* A std140 uniform block `block` at `binding_point` with the instance name `instance`. */
#define CG_UNIFORM_BLOCK(block, instance, binding_point, MEMBERS)                                 \
    layout(std140, binding = binding_point) uniform block {                                       \
        MEMBERS(CG_GLSL_MEMBER, CG_GLSL_ARRAY)                                                    \
    } instance
/* A std430 storage block; `qualifier` is readonly for a reader, empty for a writer. */
#define CG_STORAGE_BLOCK(qualifier, block, instance, binding_point, MEMBERS)                      \
    layout(std430, binding = binding_point) qualifier buffer block {                              \
        MEMBERS(CG_GLSL_MEMBER, CG_GLSL_ARRAY)                                                    \
    } instance
#endif

#endif
