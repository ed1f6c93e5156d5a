// voxelize/surface_sums.glsl: the surface model's 14 sums of one surface point into one voxel
// (voxelize.frag's header says what each slab holds), written once for the two voxelizers,
// the geometry shader's (voxelize.frag, SURFACE) and the compute one (voxelize_tri.comp), so
// that both fill the same slabs with the same fixed-point rounding.
//
// The includer declares u_accum (the R32UI accumulation volume), u_dims (the volume's voxels
// along x, y, z: one slab's size), u_surface_fixed (x: fixed-point units per unit of albedo,
// normal, offset in voxels and coverage; y: per unit of emitted radiance) and u_origin_voxel
// (xyz: the volume's origin, w: a voxel's size).
#ifndef VOXELIZE_SURFACE_SUMS_GLSL
#define VOXELIZE_SURFACE_SUMS_GLSL

// Where slab k of the surface model's 14 lies in the accumulation volume, 2 x 2 x 4 slabs of the
// volume's size (so that 512^3 fits GL_MAX_3D_TEXTURE_SIZE 2048, which 14 along z would not).
ivec3
surface_slab(int k)
{
    return ivec3(k & 1, (k >> 1) & 1, k >> 2) * u_dims;
}

// What one surface point adds, in fixed point: the same for every voxel it reaches but the
// offset (surface_offset).
struct SurfaceSums {
    uvec3 albedo;
    uvec3 emission;
    uvec3 normal;   // two's complement
    uvec3 share;    // per axis |n_i| / |n|_1 of the triangle's plane, added by maximum
};

// albedo clamped to [0, 1], emission >= 0, normal of unit length, share summing to 1.
SurfaceSums
surface_sums(vec3 albedo, vec3 emission, vec3 normal, vec3 share)
{
    SurfaceSums s;
    s.albedo = uvec3(albedo * u_surface_fixed.x + 0.5);
    s.emission = uvec3(min(emission * u_surface_fixed.y + 0.5, vec3(4294967295.0)));
    s.normal = uvec3(ivec3(round(normal * u_surface_fixed.x)));
    s.share = uvec3(ceil(share * u_surface_fixed.x));
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
surface_add(ivec3 v, SurfaceSums s, uint offset)
{
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
}

#endif
