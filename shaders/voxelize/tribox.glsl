// voxelize/tribox.glsl: does a triangle touch an axis-aligned box? Separating-axis test
// of Akenine-Moller (2001, "Fast 3D triangle-box overlap testing"): the 3 box normals,
// the triangle normal and the 9 edge-cross-axis directions. tests/passes/tribox_ref.h
// is the same test in C, used to compute the voxels a triangle must occupy.
#ifndef CG_VOXELIZE_TRIBOX_GLSL
#define CG_VOXELIZE_TRIBOX_GLSL

// Triangle v0..v2 (already relative to the box centre) against the box [-h, h]^3.
bool
tribox_axis_separates(vec3 axis, vec3 v0, vec3 v1, vec3 v2, vec3 h)
{
    float p0 = dot(axis, v0), p1 = dot(axis, v1), p2 = dot(axis, v2);
    float r = dot(h, abs(axis));
    return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

bool
tribox_overlap(vec3 centre, vec3 h, vec3 a, vec3 b, vec3 c)
{
    vec3 v0 = a - centre, v1 = b - centre, v2 = c - centre;
    // Box normals: the triangle's bounding box against the box.
    if (any(greaterThan(min(v0, min(v1, v2)), h)) || any(lessThan(max(v0, max(v1, v2)), -h)))
        return false;
    vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
    // Triangle plane against the box.
    vec3 n = cross(e0, e1);
    float d = dot(n, v0);
    if (abs(d) > dot(h, abs(n)))
        return false;
    // Edge x axis directions.
    vec3 axes[3] = vec3[3](vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0));
    vec3 edges[3] = vec3[3](e0, e1, e2);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (tribox_axis_separates(cross(edges[i], axes[j]), v0, v1, v2, h))
                return false;
    return true;
}

#endif
