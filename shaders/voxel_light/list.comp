#version 450 core
// voxel_light/list.comp: the occupied voxels of voxelize's surface model (albedo a > 0) into
// voxel_light_list, for the listed inject (inject.comp with VOXEL_LIGHT_LISTED) and the gathers at
// the voxels (gather.comp): one texel read per voxel of the volume is all the full-volume work left,
// the light's own work follows the occupied voxels. Run when the geometry may have changed.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

#include "voxel_light/surface.glsl"

layout(binding = 0) uniform sampler3D u_albedo;

layout(location = 3) uniform uint u_list_capacity;

void
main()
{
    CgVolume vol = cg_volume();
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, ivec3(vol.dims))) || texelFetch(u_albedo, v, 0).a <= 0.0)
        return;
    VOXEL_LIGHT_APPEND(voxel_light_list, u_list_capacity, v);
}
