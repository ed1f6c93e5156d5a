/* builtin:boxplane: a box on a sunlit plane (the path tracer is the truth, docs/vct.md). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

/* A box s x s x s (turned by boxyaw about +y) on a square plane of side L; the sun at elevation
 * gamma, azimuth 30 degrees off +z, lights the plane and two of the box's sides. */
static bool
build_boxplane(cg_scene *scene, const char *query, cg_error *err)
{
    bs_param p[] = { BS_UNIT_PARAMS, { "s", 0.01, 100, 1, false, 0, false, NULL }, { "L", 0.1, 1000, 6, false, 0, false, NULL },
                     { "boxyaw", -360, 360, 0, false, 0, false, NULL }, { "gamma", 1, 89, 45, false, 0, false, NULL },
                     { "E", 0, 1e6, 3, false, 0, false, NULL } };
    if (!bs_parse_params("boxplane", query, p, 8, err))
        return false;
    bs_unit_frame f;
    bs_unit_frame_make(&f, p[0].value, p[1].value);
    double s = p[3].value, L = p[4].value, g = p[6].value * BS_PI / 180;
    if (L < 1.5 * s)
        return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:boxplane: L=%g must be at least 1.5 s (%g): the box "
                       "stands on the plane", L, 1.5 * s);
    int mat = bs_unit_material(scene, "white", p[2].value, 0.0, err);
    if (mat < 0)
        return false;
    mesh_builder b = { 0 };
    double cf[3] = { -L / 2, 0, L / 2 }, uf[3] = { L, 0, 0 }, vf[3] = { 0, 0, -L };
    bs_rect_grid(&b, cf, uf, vf, 8);
    double bc[3] = { 0, s / 2, 0 }, bh[3] = { s / 2, s / 2, s / 2 };
    mb_box(&b, bc, bh, p[5].value * BS_PI / 180, false);
    if (!mb_commit(scene, &b, "boxplane", mat, CG_MESH_COMPLEX, f.m, err))
        return false;
    double az = 30 * BS_PI / 180;
    double dir[3] = { -cos(g) * sin(az), -sin(g), -cos(g) * cos(az) };
    if (!bs_unit_sun(scene, &f, dir, p[7].value, err))
        return false;
    double eye[3] = { 1.2 * s, 1.6 * s, 3.2 * s }, at[3] = { 0, 0.35 * s, 0 };
    return bs_unit_camera(scene, &f, eye, at, 0.9f, (float)(0.01 * s), (float)(100.0 * L), err);
}

const cg_builtin_scene cg_builtin_boxplane = {
    .name = "boxplane",
    .doc = "unit scene: a box (s x s x s, turned by boxyaw) on a sunlit square plane of side L, the sun at "
    "elevation gamma; ?s=S (default 1)&L=L (6, at least 1.5 s)&boxyaw=DEG (0)&gamma=DEG (45)&E=E (3)"
    "&yaw=DEG&tilt=DEG&albedo=A (0.8)",
    .build = build_boxplane,
};
