// voxel_light/surface.glsl: where a voxel's surface lies, from voxelize's surface model
// (voxelize/resolve.comp): the mean normal N of its fragments (|N| <= 1) and the mean offset delta of
// their planes from the voxel's centre c, in voxels. Their mean plane is N . (x - c) = delta voxel,
// i.e. N^ . (x - c) = delta voxel / |N|, and the surface point is the foot of c on it,
// x = c + N delta voxel / |N|^2, kept inside the voxel; the voxel's own light is evaluated there.
// For one plane that is the plane itself; for two perpendicular planes with equal offsets (an
// edge, |N|^2 = 1/2) it is the point of their common edge nearest c.
//
// Provides: voxel_light_list (the occupied voxels, CG_VOXEL_LIST_BLOCK), voxel_light_pack(),
//           voxel_light_unpack(), voxel_light_point(), VOXEL_LIGHT_APPEND, VOXEL_LIGHT_LISTED_VOXEL.
#ifndef CG_VOXEL_LIGHT_SURFACE_GLSL
#define CG_VOXEL_LIGHT_SURFACE_GLSL

#include "common/blocks.h"
#include "common/volume.glsl"

layout(std430, binding = CG_BINDING_VOXEL_LIST) buffer VoxelLightList {
    CG_VOXEL_LIST_BLOCK(CG_GLSL_MEMBER, CG_GLSL_ARRAY)
    uint voxels[];
} voxel_light_list;

uint
voxel_light_pack(ivec3 v)
{
    return uint(v.x) | (uint(v.y) << 10) | (uint(v.z) << 20);
}

ivec3
voxel_light_unpack(uint p)
{
    return ivec3(p & 1023u, (p >> 10) & 1023u, (p >> 20) & 1023u);
}

// Appends voxel v to `list`, a buffer of CG_VOXEL_LIST_BLOCK and `voxels[]` with room for `capacity`:
// its header counts every voxel offered (w) and the groups of 64 an indirect dispatch over them takes (x).
#define VOXEL_LIGHT_APPEND(list, capacity, v)                                                      \
    do {                                                                                           \
        uint appended_ = atomicAdd(list.dispatch.w, 1u);                                          \
        if (appended_ < (capacity))                                                                \
            list.voxels[appended_] = voxel_light_pack(v);                                         \
        if (appended_ % 64u == 0u)                                                                 \
            atomicAdd(list.dispatch.x, 1u);                                                        \
    } while (false)

// Declares `v`, the voxel of `list` this invocation of an indirect dispatch over it runs for (one a
// voxel, in order), and returns from main where the list holds fewer (at most `capacity`).
#define VOXEL_LIGHT_LISTED_VOXEL(list, capacity, v)                                               \
    if (gl_GlobalInvocationID.x >= min(list.dispatch.w, (capacity)))                              \
        return;                                                                                    \
    ivec3 v = voxel_light_unpack(list.voxels[gl_GlobalInvocationID.x])

// The surface point of voxel v whose mean normal is n (|n| > 0) and plane offset delta (voxels).
vec3
voxel_light_point(CgVolume vol, ivec3 v, vec3 n, float delta)
{
    vec3 c = vol.origin + (vec3(v) + 0.5) * vol.voxel_size;
    vec3 x = c + n * (delta * vol.voxel_size / max(dot(n, n), 1e-8));
    return clamp(x, c - 0.5 * vol.voxel_size, c + 0.5 * vol.voxel_size);
}

#endif
