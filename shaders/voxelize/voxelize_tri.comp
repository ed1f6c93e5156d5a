#version 450 core
// voxelize/voxelize_tri.comp (voxelizer=compute, surface model): the compute-shader voxelizer
// measured against the geometry-shader one (docs/dynamic.md): one invocation per triangle tests
// every voxel of its box against it (Akenine-Moller 2001, "Fast 3D triangle-box overlap testing",
// voxelize/tribox.glsl, with voxelize.frag's face tolerance: the same voxels) and adds the sums of
// voxelize.frag's SURFACE (voxelize/surface_sums.glsl), its attributes taken at the voxel
// centre's projection onto the triangle (clamped to it) rather than at a pixel centre of the
// projected triangle, so its volumes differ from the geometry shader's in the last bits of
// albedo, normal and offset.
layout(local_size_x = 64) in;
#include "common/scene.glsl"
#include "voxelize/tribox.glsl"

layout(std430, binding = 11) readonly buffer CgVoxVertices { float cg_vertices[]; };
layout(std430, binding = 12) readonly buffer CgVoxIndices { uint cg_indices[]; };
layout(r32ui, binding = 0) uniform coherent uimage3D u_accum;
layout(location = 8) uniform vec4 u_origin_voxel;
// One accumulation slab's voxels: the volume's x and y, a slice's depth (surface_sums.glsl).
layout(location = 11) uniform ivec3 u_slab_size;
layout(location = 13) uniform vec4 u_surface_fixed;
layout(location = 16) uniform uint u_triangles;
// The voxels this dispatch may write, [lo, hi): the whole volume or a partial region (as in
// voxelize.geom).
layout(location = 14) uniform ivec3 u_box_lo;
layout(location = 15) uniform ivec3 u_box_hi;

#define FACE_TOLERANCE 1e-4

#include "voxelize/surface_sums.glsl"

void
main()
{
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_triangles)
        return;
    vec3 p[3], nv[3], w[3];
    vec2 uv[3];
    for (int i = 0; i < 3; i++) {
        uint v = cg_indices[3u * t + uint(i)] * CG_VERTEX_FLOATS;
        vec3 pos = vec3(cg_vertices[v], cg_vertices[v + 1u], cg_vertices[v + 2u]);
        w[i] = (cg_model * vec4(pos, 1.0)).xyz;
        p[i] = (w[i] - u_origin_voxel.xyz) / u_origin_voxel.w;
        nv[i] = cg_normal_matrix * vec3(cg_vertices[v + 3u], cg_vertices[v + 4u], cg_vertices[v + 5u]);
        uv[i] = vec2(cg_vertices[v + 6u], cg_vertices[v + 7u]);
    }
    vec3 e0 = p[1] - p[0], e1 = p[2] - p[0];
    vec3 n = cross(e0, e1);
    float area2 = dot(n, n);
    if (area2 == 0.0)
        return;
    ivec3 lo = max(ivec3(floor(min(p[0], min(p[1], p[2])) - FACE_TOLERANCE)), u_box_lo);
    ivec3 hi = min(ivec3(floor(max(p[0], max(p[1], p[2])) + FACE_TOLERANCE)), u_box_hi - 1);
    vec3 plane = abs(n);
    vec3 share = plane / (plane.x + plane.y + plane.z);
    const vec3 half_voxel = vec3(0.5 + FACE_TOLERANCE);
    for (int z = lo.z; z <= hi.z; z++)
        for (int y = lo.y; y <= hi.y; y++)
            for (int x = lo.x; x <= hi.x; x++) {
                ivec3 v = ivec3(x, y, z);
                vec3 c = vec3(v) + 0.5;
                if (!tribox_overlap(c, half_voxel, p[0], p[1], p[2]))
                    continue;
                // Barycentrics of the centre's projection onto the plane, clamped to the triangle.
                vec3 d = c - p[0];
                float l1 = dot(cross(d, e1), n) / area2, l2 = dot(cross(e0, d), n) / area2;
                l1 = clamp(l1, 0.0, 1.0);
                l2 = clamp(l2, 0.0, 1.0 - l1);
                float l0 = 1.0 - l1 - l2;
                vec3 world = l0 * w[0] + l1 * w[1] + l2 * w[2];
                vec3 normal = normalize(l0 * nv[0] + l1 * nv[1] + l2 * nv[2]);
                vec2 tex = l0 * uv[0] + l1 * uv[1] + l2 * uv[2];
                // alphaMode MASK: nothing there below the cutoff (voxelize.frag).
                if (cg_material_masked_out(cg_material_index, tex))
                    continue;
                surface_add(v, surface_sums(cg_material_index, tex, normal, share), surface_offset(normal, world, v));
            }
}
