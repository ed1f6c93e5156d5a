#version 450 core
// voxel_light/planes.comp: each block's representative's tangent plane (voxel_light/spacing.glsl's
// voxel_light_spacing), after pick.comp: one invocation a block.
layout(local_size_x = 64) in;

#include "voxel_light/spacing.glsl"

layout(binding = 2) uniform sampler3D u_normal;     // voxelize's normal: N, delta

void
main()
{
    CgVolume vol = cg_volume();
    ivec3 blocks = voxel_light_blocks(vol);
    uint index = gl_GlobalInvocationID.x;
    if (index >= uint(blocks.x * blocks.y * blocks.z))
        return;
    uint key = voxel_light_spacing.blocks[index].key;
    if (key == VOXEL_LIGHT_NO_KEY)
        return;
    ivec3 b = ivec3(int(index) % blocks.x, (int(index) / blocks.x) % blocks.y, int(index) / (blocks.x * blocks.y));
    ivec3 r = voxel_light_key_voxel(b, key);
    vec4 nd = texelFetch(u_normal, r, 0);
    vec3 m = nd.xyz / length(nd.xyz);   // a representative has coherence >= VOXEL_LIGHT_MIN_COHERENCE
    voxel_light_spacing.blocks[index].plane = vec4(m, dot(m, voxel_light_point(vol, r, nd.xyz, nd.w)));
}
