#version 450 core
// voxel_light/fill.comp: the gathered light of each voxel of `mixed` (sort.comp), both sides, as the
// weighted mean of its representatives' (voxel_light/spacing.glsl), which gather.comp wrote before
// into the same images (a representative is never mixed, so no texel is both read and written).
// u_source: the gather was G(V_0); the mix goes to u_source_front and u_source_back too, as gather.comp's.
layout(local_size_x = 64) in;

layout(rgba16f, binding = 0) uniform image3D u_gathered_front;
layout(rgba16f, binding = 1) uniform image3D u_gathered_back;

#define VOXEL_LIGHT_FILL
#include "voxel_light/spacing.glsl"

layout(binding = 2) uniform sampler3D u_normal;     // voxelize's normal: N, delta

layout(location = 3) uniform uint u_list_capacity;
layout(location = 4) uniform bool u_source;
layout(r11f_g11f_b10f, binding = 2) writeonly uniform image3D u_source_front;
layout(r11f_g11f_b10f, binding = 3) writeonly uniform image3D u_source_back;

void
main()
{
    VOXEL_LIGHT_LISTED_VOXEL(voxel_light_mixed, u_list_capacity, v);
    CgVolume vol = cg_volume();
    vec4 nd = texelFetch(u_normal, v, 0);
    float coherence = length(nd.xyz);
    vec4 front = vec4(0.0), back = vec4(0.0);
    if (coherence >= VOXEL_LIGHT_MIN_COHERENCE) {
        float sum = voxel_light_mix(vol, v, voxel_light_point(vol, v, nd.xyz, nd.w), nd.xyz, front, back);
        // sum > 0: sort.comp sent the voxels without a weight to trace. Should the two programs round
        // a weight differently, a voxel of no weight keeps 0 here rather than a division by it.
        front = sum > 0.0 ? front / sum : vec4(0.0);
        back = sum > 0.0 ? back / sum : vec4(0.0);
    }
    imageStore(u_gathered_front, v, front);
    imageStore(u_gathered_back, v, back);
    if (u_source) {
        imageStore(u_source_front, v, front);
        imageStore(u_source_back, v, back);
    }
}
