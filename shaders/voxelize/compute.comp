// voxelize/compute.comp: the surface model's voxelization (voxelize.geom + voxelize.frag with
// SURFACE and conservative coverage) as a compute shader, for the comparison the dynamic-scenes
// issue asks for (tests/passes/bench_voxelizer.c; docs/dynamic.md): no rasterizer, each
// triangle visits the voxel columns of its bounding rectangle on its dominant axis itself.
//
// The same voxels and the same sums as the rasterized path: per column (a pixel of the
// dominant-axis projection) the 1-3 voxels the plane crosses (voxelize.frag's depth range) that
// pass the exact triangle/box test (tribox.glsl), each adding the 14 slabs of voxelize.frag with
// the attributes interpolated at the column's centre, as the rasterizer interpolates them there.
// Binning (Schwarz and Seidel 2010, "Fast parallel surface and solid voxelization on GPUs"):
// one invocation a triangle whose rectangle holds at most CG_VOXELIZE_SMALL columns; a larger
// one is appended to a list that a second dispatch (LARGE) works through with a whole work group
// per triangle, its columns shared among the group's invocations.
#version 450 core
#include "common/scene.glsl"
#include "voxelize/tribox.glsl"

#define CG_VOXELIZE_SMALL 64
#define GROUP 64
#define FACE_TOLERANCE 1e-4

layout(local_size_x = GROUP) in;

layout(std430, binding = 2) readonly buffer Vertices { float vertices[]; };  // position, normal, uv
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 4) buffer Large { uint large_count; uint large[]; };

layout(location = 8) uniform vec4 u_origin_voxel;
layout(location = 9) uniform int u_resolution;
layout(location = 10) uniform uint u_triangles;
layout(location = 13) uniform vec4 u_surface_fixed;
layout(r32ui, binding = 0) uniform coherent uimage3D u_accum;

struct Triangle {
    vec3 p[3];   // volume coordinates (voxels)
    vec3 w[3];   // world
    vec3 n[3];   // world normals
    vec2 uv[3];
};

Triangle
fetch(uint t)
{
    Triangle tri;
    for (int i = 0; i < 3; i++) {
        uint base = indices[3u * t + uint(i)] * 8u;
        vec3 p = vec3(vertices[base], vertices[base + 1u], vertices[base + 2u]);
        vec3 n = vec3(vertices[base + 3u], vertices[base + 4u], vertices[base + 5u]);
        tri.w[i] = (cg_model * vec4(p, 1.0)).xyz;
        tri.n[i] = cg_normal_matrix * n;
        tri.uv[i] = vec2(vertices[base + 6u], vertices[base + 7u]);
        tri.p[i] = (tri.w[i] - u_origin_voxel.xyz) / u_origin_voxel.w;
    }
    return tri;
}

vec3
swizzle(vec3 p, int axis)
{
    return axis == 0 ? p.yzx : axis == 1 ? p.zxy : p;
}

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

ivec3
surface_slab(int k)
{
    return ivec3(k & 1, (k >> 1) & 1, k >> 2) * u_resolution;
}

float
cross2(vec2 a, vec2 b)
{
    return a.x * b.y - a.y * b.x;
}

int
dominant_axis(Triangle tri)
{
    vec3 n = abs(cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]));
    return n.x >= n.y && n.x >= n.z ? 0 : n.y >= n.z ? 1 : 2;
}

// The columns of the triangle's projection: [lo, hi] inclusive, clipped to the volume.
void
columns(Triangle tri, int axis, out ivec2 lo, out ivec2 hi)
{
    vec2 a = swizzle(tri.p[0], axis).xy, b = swizzle(tri.p[1], axis).xy, c = swizzle(tri.p[2], axis).xy;
    lo = max(ivec2(floor(min(a, min(b, c)) - FACE_TOLERANCE)), ivec2(0));
    hi = min(ivec2(floor(max(a, max(b, c)) + FACE_TOLERANCE)), ivec2(u_resolution - 1));
}

// One column: voxelize.frag's body for the pixel `column`.
void
column_voxels(Triangle tri, int axis, ivec2 column)
{
    vec3 a = swizzle(tri.p[0], axis), b = swizzle(tri.p[1], axis), c = swizzle(tri.p[2], axis);
    vec3 n = cross(b - a, c - a);
    if (n.z == 0.0)
        return;
    vec2 centre = vec2(column) + 0.5;
    float z = a.z - (n.x * (centre.x - a.x) + n.y * (centre.y - a.y)) / n.z;
    float spread = 0.5 * (abs(n.x) + abs(n.y)) / abs(n.z);
    float z_lo = max(z - spread, min(a.z, min(b.z, c.z))) - FACE_TOLERANCE;
    float z_hi = min(z + spread, max(a.z, max(b.z, c.z))) + FACE_TOLERANCE;
    int k_lo = max(int(floor(z_lo)), 0);
    int k_hi = min(int(floor(z_hi)), u_resolution - 1);
    if (k_lo > k_hi)
        return;
    // The attributes at the column's centre: the triangle's barycentric extension, as the
    // rasterizer interpolates them at a pixel centre.
    float area = cross2(b.xy - a.xy, c.xy - a.xy);
    vec2 d = centre - a.xy;
    float l1 = cross2(d, c.xy - a.xy) / area, l2 = cross2(b.xy - a.xy, d) / area, l0 = 1.0 - l1 - l2;
    vec3 world = l0 * tri.w[0] + l1 * tri.w[1] + l2 * tri.w[2];
    vec3 normal = normalize(l0 * tri.n[0] + l1 * tri.n[1] + l2 * tri.n[2]);
    vec2 uv = l0 * tri.uv[0] + l1 * tri.uv[1] + l2 * tri.uv[2];
    vec3 albedo = clamp(cg_material_albedo(cg_material_index, uv).rgb, 0.0, 1.0);
    vec3 emission = max(cg_material_emissive(cg_material_index, uv), vec3(0.0));
    vec3 plane = abs(unswizzle_vector(n, axis));
    vec3 share = plane / (plane.x + plane.y + plane.z);
    uvec3 q_albedo = uvec3(albedo * u_surface_fixed.x + 0.5);
    uvec3 q_emission = uvec3(min(emission * u_surface_fixed.y + 0.5, vec3(4294967295.0)));
    uvec3 q_normal = uvec3(ivec3(round(normal * u_surface_fixed.x)));
    uvec3 q_share = uvec3(ceil(share * u_surface_fixed.x));
    const vec3 half_voxel = vec3(0.5 + FACE_TOLERANCE);
    for (int k = k_lo; k <= k_hi; k++) {
        ivec3 cell = ivec3(column, k);
        if (!tribox_overlap(vec3(cell) + 0.5, half_voxel, a, b, c))
            continue;
        ivec3 v = unswizzle(cell, axis);
        vec3 voxel_centre = u_origin_voxel.xyz + (vec3(v) + 0.5) * u_origin_voxel.w;
        uint q_offset = uint(int(round(dot(normal, world - voxel_centre) / u_origin_voxel.w * u_surface_fixed.x)));
        imageAtomicAdd(u_accum, v, 1u);
        imageAtomicAdd(u_accum, v + surface_slab(1), q_albedo.r);
        imageAtomicAdd(u_accum, v + surface_slab(2), q_albedo.g);
        imageAtomicAdd(u_accum, v + surface_slab(3), q_albedo.b);
        imageAtomicAdd(u_accum, v + surface_slab(4), q_emission.r);
        imageAtomicAdd(u_accum, v + surface_slab(5), q_emission.g);
        imageAtomicAdd(u_accum, v + surface_slab(6), q_emission.b);
        imageAtomicAdd(u_accum, v + surface_slab(7), q_normal.x);
        imageAtomicAdd(u_accum, v + surface_slab(8), q_normal.y);
        imageAtomicAdd(u_accum, v + surface_slab(9), q_normal.z);
        imageAtomicAdd(u_accum, v + surface_slab(10), q_offset);
        imageAtomicMax(u_accum, v + surface_slab(11), q_share.x);
        imageAtomicMax(u_accum, v + surface_slab(12), q_share.y);
        imageAtomicMax(u_accum, v + surface_slab(13), q_share.z);
    }
}

void
main()
{
#ifndef LARGE
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_triangles)
        return;
    Triangle tri = fetch(t);
    int axis = dominant_axis(tri);
    ivec2 lo, hi;
    columns(tri, axis, lo, hi);
    ivec2 size = hi - lo + 1;
    if (any(lessThanEqual(size, ivec2(0))))
        return;
    if (size.x * size.y > CG_VOXELIZE_SMALL) {
        large[atomicAdd(large_count, 1u)] = t;
        return;
    }
    for (int y = lo.y; y <= hi.y; y++)
        for (int x = lo.x; x <= hi.x; x++)
            column_voxels(tri, axis, ivec2(x, y));
#else
    // One work group a large triangle; its columns strided over the group.
    uint t = large[gl_WorkGroupID.x];
    Triangle tri = fetch(t);
    int axis = dominant_axis(tri);
    ivec2 lo, hi;
    columns(tri, axis, lo, hi);
    ivec2 size = hi - lo + 1;
    for (int i = int(gl_LocalInvocationID.x); i < size.x * size.y; i += GROUP)
        column_voxels(tri, axis, lo + ivec2(i % size.x, i / size.x));
#endif
}
