// voxelize/surface_sums.glsl: the surface model's 18 sums of one surface point into one voxel
// (voxelize.frag's header says what each slab holds), written once for the two voxelizers,
// the geometry shader's (voxelize.frag, SURFACE) and the compute one (voxelize_tri.comp), so
// that both fill the same slabs with the same fixed-point rounding.
//
// The includer includes common/scene.glsl (the materials) and declares u_accum (the R32UI
// accumulation volume), u_slab_size (one slab's voxels along x, y, z: the volume's x and y, the
// depth of one of voxelize's slices along z), u_box_lo (the voxels written start at z = u_box_lo.z,
// the first of the slice the accumulation holds now),
// u_surface_fixed (x: fixed-point units per unit of albedo, normal, offset in voxels and coverage;
// y: per unit of emitted radiance; w: 1 where transmissive materials cover only what they reflect,
// voxelize's `transmissive`) and u_origin_voxel (xyz: the volume's origin, w: a voxel's size).
#ifndef VOXELIZE_SURFACE_SUMS_GLSL
#define VOXELIZE_SURFACE_SUMS_GLSL

#include "common/blocks.h"

// The specular lobe's (Abar, Bbar) per perceptual roughness (passes/sdk/cone.h,
// cgp_brdf_hemispherical_fill).
layout(binding = CG_UNIT_SPECULAR_HEMISPHERICAL) uniform sampler2D u_specular_hemispherical;

// Where slab k of the surface model's CG_SURFACE_SLABS lies in the accumulation volume (common/blocks.h):
// 0 count, 1..3 albedo RGB, 4..6 emission RGB, 7..9 normal xyz, 10 plane offset, 11..13 coverage
// xyz, 14..16 specular albedo RGB, 17 its luminance times the lobe's GGX alpha.
ivec3
surface_slab(int k)
{
    return ivec3(CG_SURFACE_SLAB_X(k), CG_SURFACE_SLAB_Y(k), CG_SURFACE_SLAB_Z(k)) * u_slab_size;
}

// What one surface point adds, in fixed point: the same for every voxel it reaches but the
// offset (surface_offset).
struct SurfaceSums {
    uvec3 albedo;
    uvec3 emission;
    uvec3 normal;   // two's complement
    uvec3 share;    // per axis |n_i| / |n|_1 of the triangle's plane, added by maximum
    uvec3 specular;
    uint alpha;     // the specular albedo's luminance (Rec. 709) x GGX alpha = roughness^2
};

// What the specular lobe reflects, as voxels store it: F0 Abar + F90 Bbar, the lobe's directional
// albedo averaged over the outgoing directions (cosine-weighted), so that a voxel radiating one
// radiance every way returns the lobe's exitance under uniform light, x the coverage alpha of a
// BLEND layer as cg_material_diffuse. 0 for a Lambertian material (F0 = F90 = 0). A metal's voxel
// holds its light here (its diffuse albedo is 0), for voxel_light's `glossy`.
vec3
surface_specular(int material, vec2 uv)
{
    CgBsdf b = cg_material_bsdf(material, uv);
    // Texel j at roughness j / (size - 1) (cgp_brdf_hemispherical_fill).
    float size = float(textureSize(u_specular_hemispherical, 0).x);
    vec2 terms = textureLod(u_specular_hemispherical, vec2((clamp(b.roughness, 0.0, 1.0) * (size - 1.0) + 0.5) / size, 0.5), 0.0).rg;
    vec3 specular = b.f0 * terms.x + b.f90 * terms.y;
    if (cg_material_alpha_mode(material) == CG_ALPHA_BLEND)
        specular *= clamp(cg_material_base_color(material, uv).a, 0.0, 1.0);
    return specular;
}

// The sums of a point of `material` at texture coordinate uv: its diffuse albedo
// (cg_material_diffuse: a metal's and a glass's are 0, while their coverage still makes their
// voxels opaque: with caustics off, glass and metal shadow fully), emission and specular albedo,
// its normal (unit) and the triangle's share (summing to 1).
SurfaceSums
surface_sums(int material, vec2 uv, vec3 normal, vec3 share)
{
    vec3 albedo = clamp(cg_material_diffuse(material, uv), 0.0, 1.0);
    vec3 emission = max(cg_material_emissive(material, uv), vec3(0.0));
    vec3 specular = clamp(surface_specular(material, uv), 0.0, 1.0);
    if (u_surface_fixed.w > 0.0) {
        // What a transmissive interface lets through of light from every side: tau (1 - F), F the
        // Fresnel term averaged over the hemisphere (cosine-weighted, as cg_bsdf_diffuse_hemispherical):
        // the cones crossing its voxels see that share of what lies behind (untinted: coverage is one
        // number; a departure), as path_trace with caustics sees the sky through glass.
        CgBsdf b = cg_material_bsdf(material, uv);
        float fresnel = dot(b.f0, vec3(0.2126, 0.7152, 0.0722)) * CG_BSDF_DIFFUSE_HEMISPHERICAL_A +
                        b.f90 * CG_BSDF_DIFFUSE_HEMISPHERICAL_B;
        float through = dot(b.transmission, vec3(0.2126, 0.7152, 0.0722)) * (1.0 - fresnel);
        share *= clamp(1.0 - through, 0.0, 1.0);
    }
    float alpha = dot(specular, vec3(0.2126, 0.7152, 0.0722)) * cg_material_bsdf(material, uv).alpha;
    SurfaceSums s;
    s.albedo = uvec3(albedo * u_surface_fixed.x + 0.5);
    s.emission = uvec3(min(emission * u_surface_fixed.y + 0.5, vec3(4294967295.0)));
    s.normal = uvec3(ivec3(round(normal * u_surface_fixed.x)));
    s.share = uvec3(ceil(share * u_surface_fixed.x));
    s.specular = uvec3(specular * u_surface_fixed.x + 0.5);
    s.alpha = uint(clamp(alpha, 0.0, 1.0) * u_surface_fixed.x + 0.5);
    return s;
}

// The offset n . (x - c) / voxel of the point's plane from the centre c of voxel v, in fixed
// point (two's complement).
uint
surface_offset(vec3 normal, vec3 world, ivec3 v)
{
    vec3 centre = u_origin_voxel.xyz + (vec3(v) + 0.5) * u_origin_voxel.w;
    return uint(int(round(dot(normal, world - centre) / u_origin_voxel.w * u_surface_fixed.x)));
}

// Adds the point to voxel v: integer sums and maxima, so the order of the points does not matter.
void
surface_add(ivec3 voxel, SurfaceSums s, uint offset)
{
    // The accumulation holds the slice that starts at z = u_box_lo.z (voxelize's `slices`).
    ivec3 v = voxel - ivec3(0, 0, u_box_lo.z);
    imageAtomicAdd(u_accum, v, 1u);
    imageAtomicAdd(u_accum, v + surface_slab(1), s.albedo.r);
    imageAtomicAdd(u_accum, v + surface_slab(2), s.albedo.g);
    imageAtomicAdd(u_accum, v + surface_slab(3), s.albedo.b);
    imageAtomicAdd(u_accum, v + surface_slab(4), s.emission.r);
    imageAtomicAdd(u_accum, v + surface_slab(5), s.emission.g);
    imageAtomicAdd(u_accum, v + surface_slab(6), s.emission.b);
    imageAtomicAdd(u_accum, v + surface_slab(7), s.normal.x);
    imageAtomicAdd(u_accum, v + surface_slab(8), s.normal.y);
    imageAtomicAdd(u_accum, v + surface_slab(9), s.normal.z);
    imageAtomicAdd(u_accum, v + surface_slab(10), offset);
    imageAtomicMax(u_accum, v + surface_slab(11), s.share.x);
    imageAtomicMax(u_accum, v + surface_slab(12), s.share.y);
    imageAtomicMax(u_accum, v + surface_slab(13), s.share.z);
    // A Lambertian point adds nothing: no atomic where it would add 0.
    if (s.specular != uvec3(0u)) {
        imageAtomicAdd(u_accum, v + surface_slab(14), s.specular.r);
        imageAtomicAdd(u_accum, v + surface_slab(15), s.specular.g);
        imageAtomicAdd(u_accum, v + surface_slab(16), s.specular.b);
        imageAtomicAdd(u_accum, v + surface_slab(17), s.alpha);
    }
}

#endif
