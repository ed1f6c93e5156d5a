// common/heightmap.glsl: where a 2D lightmap of the height-field meshes lies in the world,
// as the heightmap_raster pass publishes it (its `region` output, a std140 uniform block
// at CG_BINDING_HEIGHTMAP).
//
// Provides: CgHeightmap, cg_heightmap(), cg_heightmap_uv(), cg_heightmap_xel().
// The block's layout, CG_HEIGHTMAP_BLOCK, is common/blocks.h's, the one the C side writes.
//
// The lightmap covers the height-field meshes' xz bounds [origin, origin + texel * resolution]
// with resolution x resolution texels (texel row j at z = origin.y + (j + 0.5) texel.y);
// rgb = outgoing diffuse radiance / radiance_scale (1 for RGBA32F; for RGBA16F a pre-exposure,
// a radiance bound / 32768, sdk/radiance.h), a = height as world y (not normalised: a fp32 texel keeps a
// centimetre at 100 km; [y_min, y_max] bounds every stored height).
#ifndef CG_COMMON_HEIGHTMAP_GLSL
#define CG_COMMON_HEIGHTMAP_GLSL

#include "common/blocks.h"

struct CgHeightmap {
    vec2 origin;        // world xz of the map's minimum corner
    vec2 texel;         // world size of a level-0 texel along x and z
    float resolution;   // texels per edge at level 0
    float levels;       // mip levels present
    float y_min, y_max; // range of the heights stored (the meshes' y bounds)
    float radiance_scale; // stored rgb x radiance_scale = radiance
};

CG_UNIFORM_BLOCK(CgHeightmapBlock, cg_heightmap_block, CG_BINDING_HEIGHTMAP, CG_HEIGHTMAP_BLOCK);

CgHeightmap
cg_heightmap()
{
    vec4 a = cg_heightmap_block.origin_texel, b = cg_heightmap_block.info;
    return CgHeightmap(a.xy, a.zw, b.x, b.y, b.z, b.w, cg_heightmap_block.radiance.x);
}

// Hybrid eq. 9 for the 2D lightmap: a world position's normalised map coordinates
// ([0,1]^2 inside the map): the one world frame is rescaled by each lightmap's own extent.
vec2
cg_heightmap_uv(CgHeightmap m, vec2 xz)
{
    return (xz - m.origin) / (m.texel * m.resolution);
}

// xelworldsize of hybrid eq. 8 for the 2D lightmap: max(Dx, Dz) / texel_resolution.
float
cg_heightmap_xel(CgHeightmap m)
{
    return max(m.texel.x, m.texel.y);
}

#endif
