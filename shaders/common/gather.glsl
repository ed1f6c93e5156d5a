// common/gather.glsl: the interface of a cone gather's shader, as the pass SDK binds it
// (cgp_gather_begin, passes/sdk/cone.c): the mipped 3D lightmap, the G-buffer's position and
// normal, the output image `radiance`, and the pixel and surface point of an invocation.
//
// Provides: cg_gather_volume, cg_gather_radiance, cg_gather_pixel(), cg_gather_surface().
#ifndef CG_COMMON_GATHER_GLSL
#define CG_COMMON_GATHER_GLSL

#include "common/blocks.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = CG_UNIT_VOLUME) uniform sampler3D cg_gather_volume;
layout(binding = CG_UNIT_POSITION) uniform sampler2D cg_gather_position;
layout(binding = CG_UNIT_NORMAL) uniform sampler2D cg_gather_normal;

// fp32: gathered radiance has the range of the scene's light (no clipping at 65504, no
// denormals under 6e-5), as direct_light's output.
layout(binding = 0, rgba32f) writeonly uniform image2D cg_gather_radiance;

// This invocation's pixel; false past the image's edge, where there is nothing to write. A work
// group is an 8x8 tile, and llvmpipe runs its invocations eight at a time in lockstep (SIMD lanes,
// in the order of gl_LocalInvocationIndex), each loop until its slowest lane is done: so the eight
// are a 4x2 block of the tile rather than one of its rows, whose cones, from nearer points, march
// more alike (cone_gather on Cornell and the open world: 8-10% less CPU time, docs/vct.md, Cost).
// Which invocation takes which pixel changes no pixel's result.
bool
cg_gather_pixel(out ivec2 pixel)
{
    uint i = gl_LocalInvocationIndex;
    uvec2 in_tile = uvec2(((i >> 1u) & 4u) | (i & 3u), ((i >> 3u) & 6u) | ((i >> 2u) & 1u));
    pixel = ivec2(gl_WorkGroupID.xy * uvec2(gl_WorkGroupSize.xy) + in_tile);
    return all(lessThan(pixel, imageSize(cg_gather_radiance)));
}

// The G-buffer's surface at `pixel`, its unit normal n; false on the background (w = 0) and for
// a degenerate normal, which gather nothing (the normal is a unit vector: its 1e-12 has no unit).
bool
cg_gather_surface(ivec2 pixel, out vec3 position, out vec3 n)
{
    vec4 p = texelFetch(cg_gather_position, pixel, 0);
    vec3 normal = texelFetch(cg_gather_normal, pixel, 0).xyz;
    position = p.xyz;
    n = vec3(0.0, 0.0, 1.0);
    if (!(p.w > 0.0 && dot(normal, normal) > 1e-12))
        return false;
    n = normalize(normal);
    return true;
}

#endif
