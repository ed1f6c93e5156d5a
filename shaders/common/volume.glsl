// common/volume.glsl: where a 3D lightmap lies in the world, as the voxelize pass
// publishes it (its `region` output, a std140 uniform block at CG_BINDING_VOLUME).
//
// Provides: CG_BINDING_VOLUME, CgVolume, cg_volume(), cg_volume_uvw(), cg_volume_extent().
// The C side is passes/voxelize/voxelize.c (struct volume_region); keep the two in step.
#ifndef CG_COMMON_VOLUME_GLSL
#define CG_COMMON_VOLUME_GLSL

// UBO bindings 0..2 belong to the scene, lights and shadow map (cg/gpu_scene.h).
#define CG_BINDING_VOLUME 3

struct CgVolume {
    vec3 origin;          // world position of the volume's minimum corner
    float voxel_size;     // world edge length of a level-0 voxel (voxels are cubes)
    float resolution;     // voxels per edge at level 0
    float levels;         // mip levels present
    float radiance_scale; // stored RGB x radiance_scale = radiance (1 for RGBA16F)
};

layout(std140, binding = CG_BINDING_VOLUME) uniform CgVolumeBlock {
    vec4 cg_volume_origin_voxel;  // xyz origin, w voxel size
    vec4 cg_volume_info;          // x resolution, y levels, z radiance scale, w unused
};

CgVolume
cg_volume()
{
    return CgVolume(cg_volume_origin_voxel.xyz, cg_volume_origin_voxel.w,
                    cg_volume_info.x, cg_volume_info.y, cg_volume_info.z);
}

float
cg_volume_extent(CgVolume v)
{
    return v.voxel_size * v.resolution;
}

// Normalised texture coordinates of a world position ([0,1]^3 inside the volume).
vec3
cg_volume_uvw(CgVolume v, vec3 world)
{
    return (world - v.origin) / cg_volume_extent(v);
}

#endif
