// voxelize: dominant-axis projection of each triangle onto the volume's face (VCT paper
// 3.1, after Crassin & Green 2012): the axis maximising |n . axis| gives the largest
// projected area, so the triangle covers the most pixels and no voxel column is skipped.
//
// llvmpipe (like most GPUs) has no conservative rasterization, so coverage is made
// conservative here: each edge is pushed outwards by the half pixel diagonal along its
// normal, 0.5 (|n.x| + |n.y|) (Hasselgren et al. 2005, GPU Gems 2 ch. 42), which makes
// the rasterizer visit every pixel whose square touches the triangle. The extra pixels
// this dilation brings (chiefly at sharp corners) are rejected in the fragment shader by
// an exact triangle/voxel overlap test, so the result is exactly the set of voxels the
// triangle touches, independent of orientation (tests/passes/test_voxelize.c).
// A very acute triangle's dilated corners shoot far out (by 0.7 / sin(angle / 2) pixels)
// and lose precision where nearly parallel edges meet; such a triangle is drawn as its
// bounding rectangle grown by half a pixel instead, which the overlap test trims as well.
#version 450 core
#include "common/scene.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;

layout(location = 0) in vec3 vs_world[];
layout(location = 1) in vec3 vs_normal[];
layout(location = 2) in vec2 vs_texcoord[];

layout(location = 0) out vec3 gs_world;
layout(location = 1) out vec3 gs_normal;
layout(location = 2) out vec2 gs_texcoord;
// The original triangle in swizzled voxel coordinates (xy = projection plane, z = depth).
layout(location = 3) flat out vec3 gs_tri_a;
layout(location = 4) flat out vec3 gs_tri_b;
layout(location = 5) flat out vec3 gs_tri_c;
layout(location = 6) flat out int gs_axis;

layout(location = 8) uniform vec4 u_origin_voxel;  // xyz volume min corner, w voxel size
layout(location = 9) uniform int u_resolution;
layout(location = 12) uniform bool u_conservative;
#ifdef SURFACE
// The voxels this draw may write, [lo, hi) in volume axes: the whole volume, or one region of a
// partial re-voxelization (passes/voxelize/voxelize.c); the fragment shader tests each voxel.
layout(location = 14) uniform ivec3 u_box_lo;
layout(location = 15) uniform ivec3 u_box_hi;
#endif

// Volume coordinates with the dominant axis moved to z.
vec3
swizzle(vec3 p, int axis)
{
    return axis == 0 ? p.yzx : axis == 1 ? p.zxy : p;
}

float
cross2(vec2 a, vec2 b)
{
    return a.x * b.y - a.y * b.x;
}

void
main()
{
    vec3 p[3];
    for (int i = 0; i < 3; i++)
        p[i] = (vs_world[i] - u_origin_voxel.xyz) / u_origin_voxel.w;
#ifdef SURFACE
    // A triangle writes only voxels within a hair of its box (the overlap test's tolerance, or
    // its pixel centres' columns without it): one whose box, grown by a voxel, misses the region
    // has nothing to add there, and is dropped before it is rasterized.
    vec3 lo = min(p[0], min(p[1], p[2])), hi = max(p[0], max(p[1], p[2]));
    if (any(lessThan(hi + 1.0, vec3(u_box_lo))) || any(greaterThanEqual(lo - 1.0, vec3(u_box_hi))))
        return;
#endif
    vec3 n = abs(cross(p[1] - p[0], p[2] - p[0]));
    int axis = n.x >= n.y && n.x >= n.z ? 0 : n.y >= n.z ? 1 : 2;
    vec3 s[3];
    for (int i = 0; i < 3; i++)
        s[i] = swizzle(p[i], axis);
    vec2 q[3] = vec2[3](s[0].xy, s[1].xy, s[2].xy);
    float area = cross2(q[1] - q[0], q[2] - q[0]);
    if (area == 0.0)
        return;  // degenerate: no surface to voxelize

    vec2 out_q[4] = vec2[4](q[0], q[1], q[2], q[2]);
    int corners = 3;
    if (u_conservative) {
        // Edge lines n_i . x = c_i with outward unit normals, pushed out by the half diagonal.
        float orient = area > 0.0 ? 1.0 : -1.0;
        vec3 lines[3];
        for (int i = 0; i < 3; i++) {
            vec2 e = q[(i + 1) % 3] - q[i];
            vec2 en = normalize(vec2(e.y, -e.x) * orient);
            lines[i] = vec3(en, dot(en, q[i]) + 0.5 * (abs(en.x) + abs(en.y)));
        }
        // New vertex i is where the lines of its two edges (i-1 and i) meet.
        bool acute = false;
        for (int i = 0; i < 3; i++) {
            vec3 a = lines[(i + 2) % 3], b = lines[i];
            float det = a.x * b.y - a.y * b.x;
            out_q[i] = vec2(a.z * b.y - b.z * a.y, a.x * b.z - b.x * a.z) / det;
            // 4 pixels: corners sharper than about 20 degrees.
            acute = acute || abs(det) < 1e-6 || distance(out_q[i], q[i]) > 4.0;
        }
        if (acute) {
            vec2 lo = min(q[0], min(q[1], q[2])) - 0.5, hi = max(q[0], max(q[1], q[2])) + 0.5;
            out_q = vec2[4](lo, vec2(hi.x, lo.y), vec2(lo.x, hi.y), hi);
            corners = 4;
        }
    }

    for (int i = 0; i < corners; i++) {
        // Attributes at the moved vertex: the original triangle's barycentric extension.
        vec2 d = out_q[i] - q[0];
        float l1 = cross2(d, q[2] - q[0]) / area;
        float l2 = cross2(q[1] - q[0], d) / area;
        float l0 = 1.0 - l1 - l2;
        gs_world = l0 * vs_world[0] + l1 * vs_world[1] + l2 * vs_world[2];
        gs_normal = l0 * vs_normal[0] + l1 * vs_normal[1] + l2 * vs_normal[2];
        gs_texcoord = l0 * vs_texcoord[0] + l1 * vs_texcoord[1] + l2 * vs_texcoord[2];
        gs_tri_a = s[0];
        gs_tri_b = s[1];
        gs_tri_c = s[2];
        gs_axis = axis;
        gl_Position = vec4(out_q[i] / float(u_resolution) * 2.0 - 1.0, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
