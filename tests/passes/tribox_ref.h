/* tests/passes/tribox_ref.h: triangle/box overlap (Akenine-Moller 2001), the CPU twin of
 * shaders/voxelize/tribox.glsl, in double precision: the voxels a triangle must occupy. */
#ifndef CG_TEST_TRIBOX_REF_H
#define CG_TEST_TRIBOX_REF_H

#include <math.h>
#include <stdbool.h>

static inline void
tribox_cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline bool
tribox_separates(const double axis[3], const double v[3][3], double h)
{
    double p[3], r = h * (fabs(axis[0]) + fabs(axis[1]) + fabs(axis[2]));
    for (int i = 0; i < 3; i++)
        p[i] = axis[0] * v[i][0] + axis[1] * v[i][1] + axis[2] * v[i][2];
    double lo = fmin(p[0], fmin(p[1], p[2])), hi = fmax(p[0], fmax(p[1], p[2]));
    return lo > r || hi < -r;
}

/* Triangle abc against the cube of half size h centred at c. */
static inline bool
tribox_overlap_ref(const double c[3], double h, const double a[3], const double b[3], const double cc[3])
{
    double v[3][3];
    for (int k = 0; k < 3; k++) {
        v[0][k] = a[k] - c[k];
        v[1][k] = b[k] - c[k];
        v[2][k] = cc[k] - c[k];
    }
    for (int k = 0; k < 3; k++) {
        double lo = fmin(v[0][k], fmin(v[1][k], v[2][k])), hi = fmax(v[0][k], fmax(v[1][k], v[2][k]));
        if (lo > h || hi < -h)
            return false;
    }
    double e[3][3];
    for (int k = 0; k < 3; k++) {
        e[0][k] = v[1][k] - v[0][k];
        e[1][k] = v[2][k] - v[1][k];
        e[2][k] = v[0][k] - v[2][k];
    }
    double n[3];
    tribox_cross(e[0], e[1], n);
    if (tribox_separates(n, v, h))
        return false;
    static const double axes[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double axis[3];
            tribox_cross(e[i], axes[j], axis);
            if (tribox_separates(axis, v, h))
                return false;
        }
    return true;
}

#endif
