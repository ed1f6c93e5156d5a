// common/heightmap.glsl: where a 2D lightmap of the height-field meshes lies in the world,
// as the heightmap_raster pass publishes it (its `region` output, a std140 uniform block
// at CG_BINDING_HEIGHTMAP).
//
// Provides: CG_BINDING_HEIGHTMAP, CgHeightmap, cg_heightmap(), cg_heightmap_uv(),
//           cg_heightmap_xel().
// The C side is passes/heightmap_raster/heightmap_raster.c (region_block); keep the two in step.
//
// The lightmap covers the height-field meshes' xz bounds [origin, origin + texel * resolution]
// with resolution x resolution texels (texel row j at z = origin.y + (j + 0.5) texel.y);
// rgb = outgoing diffuse radiance, a = height as world y (not normalised: a fp32 texel keeps
// a centimetre at 100 km; [y_min, y_max] bounds every stored height).
#ifndef CG_COMMON_HEIGHTMAP_GLSL
#define CG_COMMON_HEIGHTMAP_GLSL

// UBO bindings 0..3 belong to the scene, lights, shadow map and 3D lightmap.
#define CG_BINDING_HEIGHTMAP 4

struct CgHeightmap {
    vec2 origin;        // world xz of the map's minimum corner
    vec2 texel;         // world size of a level-0 texel along x and z
    float resolution;   // texels per edge at level 0
    float levels;       // mip levels present
    float y_min, y_max; // range of the heights stored (the meshes' y bounds)
};

layout(std140, binding = CG_BINDING_HEIGHTMAP) uniform CgHeightmapBlock {
    vec4 cg_heightmap_origin_texel; // xy origin (x, z), zw texel size (x, z)
    vec4 cg_heightmap_info;         // x resolution, y levels, z y_min, w y_max
};

CgHeightmap
cg_heightmap()
{
    return CgHeightmap(cg_heightmap_origin_texel.xy, cg_heightmap_origin_texel.zw,
                       cg_heightmap_info.x, cg_heightmap_info.y, cg_heightmap_info.z, cg_heightmap_info.w);
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
