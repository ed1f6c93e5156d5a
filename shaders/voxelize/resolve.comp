#version 450 core
// voxelize/resolve.comp: turns the fixed-point sums of the voxelization into the lightmap's
// level 0: mean radiance of the fragments that fell in each voxel (averaged, never
// last-writer-wins, so the result does not depend on rasterization order), opacity 1
// where any fragment fell and 0 elsewhere (premultiplied colour: rgb = radiance there).
// The accumulation volume stacks four R32UI slabs along z: red, green, blue sums and the
// fragment count, each `resolution` deep.
// Defines: FORMAT (rgba16f or rgba8); FIND_MAX for the first of RGBA8's two dispatches,
// which finds the largest radiance component so that the second stores radiance / max and
// publishes max as the region block's radiance scale (8 bits span the scene's real range,
// not a loose bound).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

#include "common/blocks.h"

layout(r32ui, binding = 0) readonly uniform uimage3D u_accum;
#ifndef FIND_MAX
layout(FORMAT, binding = 1) writeonly uniform image3D u_radiance;
#endif

layout(location = 0) uniform int u_resolution;
// Fixed-point units per unit of radiance (see voxelize.frag).
layout(location = 1) uniform float u_fixed_scale;
// Stored value = radiance / u_radiance_scale (1 for RGBA16F in range).
layout(location = 2) uniform float u_radiance_scale;
// Whether the scale comes from the FIND_MAX dispatch (RGBA8).
layout(location = 3) uniform bool u_scale_from_max;

// x: float bits of the largest radiance component (positive floats order as their bits).
layout(std430, binding = CG_BINDING_RESOLVE_MAX) buffer ResolveMax { uint max_bits; };
// The region block of common/volume.glsl, bound as storage to write its radiance scale.
CG_STORAGE_BLOCK(, CgVolumeRegion, cg_volume_region, CG_BINDING_RESOLVE_REGION, CG_VOLUME_BLOCK);

shared uint group_max;

vec4
mean_radiance(ivec3 v)
{
    int slab = u_resolution;
    uint count = imageLoad(u_accum, v + ivec3(0, 0, 3 * slab)).r;
    if (count == 0u)
        return vec4(0.0);
    vec3 sum = vec3(imageLoad(u_accum, v).r,
                    imageLoad(u_accum, v + ivec3(0, 0, slab)).r,
                    imageLoad(u_accum, v + ivec3(0, 0, 2 * slab)).r);
    return vec4(sum / (float(count) * u_fixed_scale), 1.0);
}

void
main()
{
    ivec3 v = ivec3(gl_GlobalInvocationID);
    bool inside = all(lessThan(v, ivec3(u_resolution)));
#ifdef FIND_MAX
    if (gl_LocalInvocationIndex == 0u)
        group_max = 0u;
    barrier();
    if (inside) {
        vec3 l = mean_radiance(v).rgb;
        atomicMax(group_max, floatBitsToUint(max(l.r, max(l.g, l.b))));
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u)
        atomicMax(max_bits, group_max);
#else
    float scale = u_radiance_scale;
    if (u_scale_from_max) {
        float m = uintBitsToFloat(max_bits);
        scale = m > 0.0 ? m : 1.0;
        if (gl_GlobalInvocationID == uvec3(0))
            cg_volume_region.info.z = scale;
    }
    if (!inside)
        return;
    vec4 l = mean_radiance(v);
    imageStore(u_radiance, v, vec4(l.rgb / scale, l.a));
#endif
}
