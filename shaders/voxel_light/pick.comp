#version 450 core
// voxel_light/pick.comp: each block's representative (voxel_light/spacing.glsl): the least key of
// its listed voxels that have a side to gather on, the keys set to VOXEL_LIGHT_NO_KEY before.
layout(local_size_x = 64) in;

#include "voxel_light/spacing.glsl"

layout(binding = 2) uniform sampler3D u_normal;     // voxelize's normal: N, delta

layout(location = 3) uniform uint u_list_capacity;

void
main()
{
    VOXEL_LIGHT_LISTED_VOXEL(voxel_light_list, u_list_capacity, v);
    if (length(texelFetch(u_normal, v, 0).xyz) < VOXEL_LIGHT_MIN_COHERENCE)
        return;
    CgVolume vol = cg_volume();
    atomicMin(voxel_light_spacing.blocks[voxel_light_block_index(vol, v / VOXEL_LIGHT_SPACING)].key,
              voxel_light_block_key(v));
}
