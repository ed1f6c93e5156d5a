// common/volume.glsl: where a 3D lightmap lies in the world, as the voxelize pass
// publishes it (its `region` output, a std140 uniform block at CG_BINDING_VOLUME).
//
// Provides: CgVolume, cg_volume(), cg_volume_uvw(), cg_volume_extent().
// The block's layout, CG_VOLUME_BLOCK, is common/blocks.h's, the one the C side writes.
#ifndef CG_COMMON_VOLUME_GLSL
#define CG_COMMON_VOLUME_GLSL

#include "common/blocks.h"

struct CgVolume {
    vec3 origin;          // world position of the volume's minimum corner
    float voxel_size;     // world edge length of a level-0 voxel (voxels are cubes)
    vec3 dims;            // voxels along x, y, z at level 0 (a box; all equal for a cube)
    float levels;         // mip levels present
    float radiance_scale; // stored RGB x radiance_scale = radiance (1 for RGBA16F)
};

CG_UNIFORM_BLOCK(CgVolumeBlock, cg_volume_block, CG_BINDING_VOLUME, CG_VOLUME_BLOCK);

CgVolume
cg_volume()
{
    return CgVolume(cg_volume_block.origin_voxel.xyz, cg_volume_block.origin_voxel.w, cg_volume_block.dims.xyz,
                    cg_volume_block.info.y, cg_volume_block.info.z);
}

// World size of the volume along x, y, z.
vec3
cg_volume_extent(CgVolume v)
{
    return v.voxel_size * v.dims;
}

// Normalised texture coordinates of a world position ([0,1]^3 inside the volume).
vec3
cg_volume_uvw(CgVolume v, vec3 world)
{
    return (world - v.origin) / cg_volume_extent(v);
}

#endif
