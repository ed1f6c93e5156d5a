// voxelize: each fragment of the projected triangle lights its surface point once and adds
// the outgoing diffuse radiance (direct light, shadowed by the shadow map when there is
// one, plus emission: VCT paper 3.1 and 4, emissive materials) to every voxel of its pixel
// column that the triangle touches.
// SURFACE (the surface model, docs/vct.md): no light; each fragment adds its geometry instead,
// to 17 slabs: count, albedo RGB, emission RGB, unit normal xyz (as authored, two's-complement
// sums), the offset n . (x - c) / voxel of its plane from the voxel's centre c (likewise),
// per axis i the largest |n_i| / |n|_1 of its triangle's plane (imageAtomicMax): crossing the
// voxels a plane touches (a slab |n|_1 voxels thick along n) along axis i, a path meets the
// plane's coverage at the rate |n_i| / |n|_1 per voxel of path, 1 in all (docs/vct.md), and the
// specular albedo RGB (surface_sums.glsl).
//
// Averaging: the sums are fixed-point integers added with imageAtomicAdd into R32UI slabs
// (red, green, blue, count), and resolve.comp divides by the count. Integer addition is
// associative, so the result is the same whatever order the rasterizer produces fragments
// in: no last-writer-wins flicker (VCT paper 4) and no compare-and-swap retry loop, which
// on llvmpipe serialises badly. u_fixed_scale is chosen per frame from a bound on the
// scene's radiance (passes/voxelize/voxelize.c) so that 1024 fragments of the brightest
// radiance still fit in 32 bits.
#version 450 core
#include "common/scene.glsl"
#include "common/lights.glsl"
#include "common/shadow.glsl"
#include "voxelize/tribox.glsl"

layout(location = 0) in vec3 gs_world;
layout(location = 1) in vec3 gs_normal;
layout(location = 2) in vec2 gs_texcoord;
layout(location = 3) flat in vec3 gs_tri_a;
layout(location = 4) flat in vec3 gs_tri_b;
layout(location = 5) flat in vec3 gs_tri_c;
layout(location = 6) flat in int gs_axis;

// Voxels: how far off a face a triangle still counts as on it (float rounding of voxel
// coordinates up to the resolution, 512 x 6e-8 = 3e-5, stays below it).
#define FACE_TOLERANCE 1e-4

layout(location = 9) uniform int u_resolution;
layout(location = 10) uniform float u_fixed_scale;
layout(location = 12) uniform bool u_conservative;
#ifdef SURFACE
layout(location = 8) uniform vec4 u_origin_voxel;   // as in voxelize.geom
// x: fixed-point units per unit of albedo, normal, offset (voxels) and coverage; y: per unit of
// emitted radiance (passes/voxelize/voxelize.c).
layout(location = 13) uniform vec4 u_surface_fixed;
// The voxels this draw may write, [lo, hi) (as in voxelize.geom): a partial re-voxelization
// sums every fragment that falls in its region, and only those, so that the region's sums are
// those of a whole voxelization, bit for bit (integer sums and maxima do not depend on order),
// while the voxels outside it keep what they hold.
layout(location = 14) uniform ivec3 u_box_lo;
layout(location = 15) uniform ivec3 u_box_hi;
// One accumulation slab's voxels: the volume's x and y, a slice's depth (surface_sums.glsl).
layout(location = 11) uniform ivec3 u_slab_size;
#endif

layout(binding = 2) uniform sampler2D u_shadow_map;
layout(r32ui, binding = 0) uniform coherent uimage3D u_accum;
#ifdef SURFACE
#include "voxelize/surface_sums.glsl"
#endif

// Inverse of the geometry shader's swizzle: back to volume coordinates.
ivec3
unswizzle(ivec3 s, int axis)
{
    return axis == 0 ? s.zxy : axis == 1 ? s.yzx : s;
}

vec3
unswizzle_vector(vec3 s, int axis)
{
    return axis == 0 ? s.zxy : axis == 1 ? s.yzx : s;
}

vec3
outgoing_radiance()
{
    vec3 n = normalize(gs_normal);
    vec3 albedo = cg_material_diffuse(cg_material_index, gs_texcoord);
    vec3 radiance = cg_material_emissive(cg_material_index, gs_texcoord);
    for (uint i = 0u; i < cg_light_count(); i++) {
        CgLightSample s = cg_light_sample(cg_lights[i], gs_world);
        // A voxel is seen from every side: the surface is lit on whichever side faces the
        // light, as the G-buffer shades both sides.
        vec3 lit_n = dot(n, s.to_light) < 0.0 ? -n : n;
        // Without a shadow map the pass binds a block that shadows no light.
        float visibility = cg_shadow_visibility(u_shadow_map, int(i), gs_world, lit_n);
        radiance += visibility * cg_lambert_radiance(albedo, lit_n, s);
    }
    return radiance;
}

void
main()
{
    // alphaMode MASK: below the cutoff the surface is not there, for the voxels too (glTF 3.9.4).
    if (cg_material_masked_out(cg_material_index, gs_texcoord))
        return;
    ivec2 column = ivec2(floor(gl_FragCoord.xy));
    vec3 a = gs_tri_a, b = gs_tri_b, c = gs_tri_c;
    // Depth range of the triangle's plane over this pixel's square; the dominant axis
    // bounds the slopes by 1, so at most three voxels deep.
    vec3 n = cross(b - a, c - a);
    vec2 centre = vec2(column) + 0.5;
    float z = a.z - (n.x * (centre.x - a.x) + n.y * (centre.y - a.y)) / n.z;
    float spread = u_conservative ? 0.5 * (abs(n.x) + abs(n.y)) / abs(n.z) : 0.0;
    // Conservative: widened by the overlap test's tolerance, so that a triangle on a voxel face
    // (z on an integer) reaches the voxels of both sides whatever the rounding of z; without it,
    // which side a wall landed on followed the last bit of (world - origin) / voxel, and with it
    // the scale of the scene (a furnace's walls lie on faces: 0.2% of its mean luminance).
    float tolerance = u_conservative ? FACE_TOLERANCE : 0.0;
    float z_lo = max(z - spread, min(a.z, min(b.z, c.z))) - tolerance;
    float z_hi = min(z + spread, max(a.z, max(b.z, c.z))) + tolerance;
    int k_lo = max(int(floor(z_lo)), 0);
    int k_hi = min(int(floor(z_hi)), u_resolution - 1);
    if (k_lo > k_hi)
        return;

#ifdef SURFACE
    vec3 normal = normalize(gs_normal);
    // The triangle's own plane (in volume axes) for the coverage: the voxels it touches form a
    // slab of its geometric normal, whatever the shading normal says.
    vec3 plane = abs(unswizzle_vector(n, gs_axis));
    vec3 share = plane / (plane.x + plane.y + plane.z);
    SurfaceSums sums = surface_sums(cg_material_index, gs_texcoord, normal, share);
#else
    uvec3 value = uvec3(min(max(outgoing_radiance(), vec3(0.0)) * u_fixed_scale + 0.5,
                            vec3(4294967295.0)));
#endif
    int slab = u_resolution;
    // A hair over half a voxel: a triangle lying exactly on a voxel face counts for both
    // voxels, whatever the rounding.
    const vec3 half_voxel = vec3(0.5 + FACE_TOLERANCE);
    for (int k = k_lo; k <= k_hi; k++) {
        ivec3 cell = ivec3(column, k);
        if (u_conservative && !tribox_overlap(vec3(cell) + 0.5, half_voxel, a, b, c))
            continue;
        ivec3 v = unswizzle(cell, gs_axis);
        if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, ivec3(u_resolution))))
            continue;
#ifdef SURFACE
        if (any(lessThan(v, u_box_lo)) || any(greaterThanEqual(v, u_box_hi)))
            continue;
        surface_add(v, sums, surface_offset(normal, gs_world, v));
#else
        imageAtomicAdd(u_accum, v, value.r);
        imageAtomicAdd(u_accum, v + ivec3(0, 0, slab), value.g);
        imageAtomicAdd(u_accum, v + ivec3(0, 0, 2 * slab), value.b);
        imageAtomicAdd(u_accum, v + ivec3(0, 0, 3 * slab), 1u);
#endif
    }
}
