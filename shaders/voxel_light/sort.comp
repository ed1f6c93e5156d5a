#version 450 core
// voxel_light/sort.comp: each listed voxel into `traced` (the representatives, and the voxels no
// representative agrees with: they trace their own cones, gather.comp) or `mixed` (the others:
// fill.comp mixes their light from the representatives'). A voxel with no side to gather on is mixed:
// fill.comp writes it 0, as gather.comp would.
layout(local_size_x = 64) in;

#include "voxel_light/spacing.glsl"

layout(binding = 2) uniform sampler3D u_normal;     // voxelize's normal: N, delta

layout(location = 3) uniform uint u_list_capacity;

// Both lists hold at most the listed voxels, which fit u_list_capacity (passes/voxel_light sorts only then).
#define append_traced(v) VOXEL_LIGHT_APPEND(voxel_light_traced, u_list_capacity, v)
#define append_mixed(v) VOXEL_LIGHT_APPEND(voxel_light_mixed, u_list_capacity, v)

void
main()
{
    VOXEL_LIGHT_LISTED_VOXEL(voxel_light_list, u_list_capacity, v);
    CgVolume vol = cg_volume();
    vec4 nd = texelFetch(u_normal, v, 0);
    float coherence = length(nd.xyz);
    if (coherence < VOXEL_LIGHT_MIN_COHERENCE) {
        append_mixed(v);
        return;
    }
    ivec3 b = v / VOXEL_LIGHT_SPACING;
    if (voxel_light_spacing.blocks[voxel_light_block_index(vol, b)].key == voxel_light_block_key(v)) {
        append_traced(v);
        return;
    }
    vec4 front, back;
    if (voxel_light_mix(vol, v, voxel_light_point(vol, v, nd.xyz, nd.w), nd.xyz, front, back) > 0.0)
        append_mixed(v);
    else
        append_traced(v);
}
