/* builtin:terrain: a sunlit sinusoidal terrain (the path tracer is the truth; flat, A = 0, its
 * indirect light is exactly 0: docs/vct.md). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

/* y = A sin(2 pi x / lambda) sin(2 pi z / lambda) (with ridges=1: A sin(2 pi x / lambda)) over a
 * square of side L in n x n cells, smooth normals; the sun at elevation gamma, azimuth 30 degrees.
 * A = 0 is a flat sunlit plane. */
static bool
build_terrain(cg_scene *scene, const char *query, cg_error *err)
{
    bs_param p[] = { BS_UNIT_PARAMS, { "A", 0, 100, 0.5, false, 0, false, NULL }, { "lambda", 0.01, 1000, 4, false, 0, false, NULL },
                     { "L", 0.1, 1000, 16, false, 0, false, NULL }, { "n", 2, 1024, 128, true, 128, false, NULL },
                     { "ridges", 0, 1, 0, true, 0, false, NULL }, { "gamma", 1, 89, 40, false, 0, false, NULL },
                     { "E", 0, 1e6, 3, false, 0, false, NULL } };
    if (!bs_parse_params("terrain", query, p, 10, err))
        return false;
    bs_unit_frame f;
    bs_unit_frame_make(&f, p[0].value, p[1].value);
    double A = p[3].value, lambda = p[4].value, L = p[5].value, g = p[8].value * BS_PI / 180;
    int n = (int)p[6].count;
    bool ridges = p[7].count != 0;
    int mat = bs_unit_material(scene, "ground", p[2].value, 0.0, err);
    if (mat < 0)
        return false;
    mesh_builder b = { 0 };
    double k = 2 * BS_PI / lambda;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = -L / 2 + L * i / n, z = -L / 2 + L * j / n;
            double y, gx, gz;
            if (ridges) {
                y = A * sin(k * x);
                gx = A * k * cos(k * x);
                gz = 0;
            } else {
                y = A * sin(k * x) * sin(k * z);
                gx = A * k * cos(k * x) * sin(k * z);
                gz = A * k * sin(k * x) * cos(k * z);
            }
            double pos[3] = { x, y, z }, nn[3] = { -gx, 1, -gz };
            double l = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            for (int c = 0; c < 3; c++)
                nn[c] /= l;
            mb_vertex(&b, pos, nn);
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t v00 = (uint32_t)(j * (n + 1) + i), v10 = v00 + 1, v01 = v00 + (uint32_t)(n + 1), v11 = v01 + 1;
            /* counter-clockwise seen from +y */
            mb_triangle(&b, v00, v01, v10);
            mb_triangle(&b, v10, v01, v11);
        }
    /* Complex, not a height field: the unit scene measures the 3D volume, which the hybrid graphs
     * would otherwise leave out for their 2D lightmap. */
    if (!mb_commit(scene, &b, "terrain", mat, CG_MESH_COMPLEX, f.m, err))
        return false;
    double az = 30 * BS_PI / 180;
    double dir[3] = { -cos(g) * sin(az), -sin(g), -cos(g) * cos(az) };
    if (!bs_unit_sun(scene, &f, dir, p[9].value, err))
        return false;
    double eye[3] = { 0.1 * L, 0.3 * L + 2 * A, 0.45 * L }, at[3] = { 0, 0, -0.05 * L };
    return bs_unit_camera(scene, &f, eye, at, 0.9f, 0.01f, (float)(10.0 * L), err);
}

const cg_builtin_scene cg_builtin_terrain = {
    .name = "terrain",
    .doc = "unit scene: a sunlit sinusoidal terrain y = A sin(kx) sin(kz), k = 2 pi / lambda (ridges=1: "
    "y = A sin(kx)), over a square of side L in n x n cells, the sun at elevation gamma; A = 0 is a flat "
    "sunlit plane, whose indirect light is exactly 0; ?A=A (default 0.5)&lambda=W (4)&L=L (16)&n=N (128)"
    "&ridges=0|1&gamma=DEG (40)&E=E (3)&yaw=DEG&tilt=DEG&albedo=A (0.8)",
    .build = build_terrain,
};
