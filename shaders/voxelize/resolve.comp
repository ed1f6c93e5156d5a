#version 450 core
// voxelize/resolve.comp: turns the fixed-point sums of the voxelization into the lightmap's
// level 0: mean radiance of the fragments that fell in each voxel (averaged, never
// last-writer-wins, so the result does not depend on rasterization order), opacity 1
// where any fragment fell and 0 elsewhere (premultiplied colour: rgb = radiance there).
// The accumulation volume stacks four R32UI slabs along z: red, green, blue sums and the
// fragment count, each `resolution` deep.
// SURFACE (the surface model): the geometry of each voxel from its 17 slabs (voxelize.frag):
// means of albedo, emission, normal, plane offset and specular albedo over its fragments, and the coverage per
// axis rounded up to RGBA8's next step, so that quantisation never opens a wall.
// Defines: FORMAT (rgba16f or rgba8); FIND_MAX for the first of RGBA8's two dispatches,
// which finds the largest radiance component so that the second stores radiance / max and
// publishes max as the region block's radiance scale (8 bits span the scene's real range,
// not a loose bound).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

#include "common/blocks.h"

#ifdef SURFACE
layout(r32ui, binding = 0) readonly uniform uimage3D u_accum;
layout(rgba8, binding = 1) writeonly uniform image3D u_albedo;
layout(rgba8, binding = 2) writeonly uniform image3D u_coverage;
layout(rgba8_snorm, binding = 3) writeonly uniform image3D u_normal;
layout(rgba16f, binding = 4) writeonly uniform image3D u_emission;
layout(rgba8, binding = 5) writeonly uniform image3D u_specular;
// One accumulation slab's voxels: the volume's x and y, a slice's depth (surface_sums.glsl).
layout(location = 7) uniform ivec3 u_slab_size;
// x: fixed-point units per unit of albedo, normal, offset and coverage; y: per unit of emission;
// z: the region's radiance scale (pre-exposure, sdk/radiance.h): emission is stored divided by it.
layout(location = 4) uniform vec4 u_surface_fixed;
// The voxels resolved, [lo, hi): the whole volume, or the region of a partial re-voxelization
// (its accumulation holds the region's sums only; the voxels outside keep their geometry).
layout(location = 5) uniform ivec3 u_box_lo;
layout(location = 6) uniform ivec3 u_box_hi;

uint
slab(ivec3 v, int k)
{
    // surface_sums.glsl's surface_slab
    return imageLoad(u_accum, v - ivec3(0, 0, u_box_lo.z) +
                     ivec3(CG_SURFACE_SLAB_X(k), CG_SURFACE_SLAB_Y(k), CG_SURFACE_SLAB_Z(k)) * u_slab_size).r;
}

void
main()
{
    ivec3 v = u_box_lo + ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, u_box_hi)))
        return;
    uint count = slab(v, 0);
    if (count == 0u) {
        imageStore(u_albedo, v, vec4(0.0));
        imageStore(u_coverage, v, vec4(0.0));
        imageStore(u_normal, v, vec4(0.0));
        imageStore(u_emission, v, vec4(0.0));
        imageStore(u_specular, v, vec4(0.0));
        return;
    }
    float unit = float(count) * u_surface_fixed.x;
    vec3 albedo = vec3(slab(v, 1), slab(v, 2), slab(v, 3)) / unit;
    vec3 emission = vec3(slab(v, 4), slab(v, 5), slab(v, 6)) / (float(count) * u_surface_fixed.y) / u_surface_fixed.z;
    vec3 normal = vec3(int(slab(v, 7)), int(slab(v, 8)), int(slab(v, 9))) / unit;
    float offset = float(int(slab(v, 10))) / unit;
    vec3 coverage = min(vec3(slab(v, 11), slab(v, 12), slab(v, 13)) / u_surface_fixed.x, vec3(1.0));
    imageStore(u_albedo, v, vec4(albedo, 1.0));
    imageStore(u_coverage, v, vec4(ceil(coverage * 255.0 - 1e-3) / 255.0, 0.0));
    imageStore(u_normal, v, vec4(clamp(normal, -1.0, 1.0), clamp(offset, -1.0, 1.0)));
    imageStore(u_emission, v, vec4(emission, 1.0));
    // a: the fragments' GGX alpha, weighted by their specular albedo's luminance.
    vec3 specular = vec3(slab(v, 14), slab(v, 15), slab(v, 16)) / unit;
    float y = dot(specular, vec3(0.2126, 0.7152, 0.0722));
    imageStore(u_specular, v, vec4(specular, y > 0.0 ? clamp(float(slab(v, 17)) / unit / y, 0.0, 1.0) : 0.0));
}
#else

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
#endif
