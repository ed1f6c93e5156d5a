/* builtin:thinwall: one wall, a single quad, lit on one side only: nothing may reach its dark
 * side, whose indirect light is exactly 0 (docs/vct.md). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

/* The wall z = 0 (x in [-1, 1], y in [0, 1]) stands on a floor z in [-back, front]; the sun from +z
 * at elevation gamma lights the wall's front and the front floor, and the wall's shadow covers the
 * whole back floor (back <= 1 / tan gamma), so nothing lit is in sight of the dark side. view=0:
 * the camera on the dark side; 1: on the lit side. */
static bool
build_thinwall(cg_scene *scene, const char *query, cg_error *err)
{
    bs_param p[] = { BS_UNIT_PARAMS, { "back", 0.05, 10, 1.2, false, 0, false, NULL },
                     { "front", 0.05, 10, 1.5, false, 0, false, NULL }, { "gamma", 1, 89, 30, false, 0, false, NULL },
                     { "view", 0, 1, 0, true, 0, false, NULL }, { "E", 0, 1e6, 3, false, 0, false, NULL } };
    if (!bs_parse_params("thinwall", query, p, 8, err))
        return false;
    bs_unit_frame f;
    bs_unit_frame_make(&f, p[0].value, p[1].value);
    double back = p[3].value, front = p[4].value, g = p[5].value * BS_PI / 180;
    if (back > 1.0 / tan(g) - 1e-6)
        return cg_fail(err, CG_ERR_SCENE_PARAM,
                       "builtin:thinwall: back=%g is not all in the wall's shadow (at most 1/tan(gamma) = %g)", back,
                       1.0 / tan(g));
    int mat = bs_unit_material(scene, "white", p[2].value, 0.0, err);
    if (mat < 0)
        return false;
    mesh_builder b = { 0 };
    /* The floor as wide as the wall: the wall's shadow (sun in the yz plane) covers x in [-1, 1]. */
    double cf[3] = { -1, 0, front }, uf[3] = { 2, 0, 0 }, vf[3] = { 0, 0, -(front + back) };
    double cw[3] = { -1, 0, 0 }, uw[3] = { 2, 0, 0 }, vw[3] = { 0, 1, 0 };
    bs_rect_grid(&b, cf, uf, vf, 4);
    bs_rect_grid(&b, cw, uw, vw, 4);
    if (!mb_commit(scene, &b, "thinwall", mat, CG_MESH_COMPLEX, f.m, err))
        return false;
    double dir[3] = { 0, -sin(g), -cos(g) };
    if (!bs_unit_sun(scene, &f, dir, p[7].value, err))
        return false;
    double side = p[6].count == 0 ? -1.0 : 1.0, depth = p[6].count == 0 ? back : front;
    double eye[3] = { 0.5, 0.8, side * (depth + 0.8) }, at[3] = { 0, 0.3, side * 0.3 * depth };
    return bs_unit_camera(scene, &f, eye, at, 0.9f, 0.01f, 100.0f, err);
}

const cg_builtin_scene cg_builtin_thinwall = {
    .name = "thinwall",
    .doc = "unit scene: one wall (a single quad, 2 x 1) on a floor, the sun lighting its front, its shadow "
    "covering the whole back floor: the dark side's indirect light is exactly 0; ?view=0|1 (camera on the "
    "dark side, default, or the lit side)&back=B (1.2, at most 1/tan(gamma))&front=F (1.5)&gamma=DEG (30)"
    "&E=E (3)&yaw=DEG&tilt=DEG&albedo=A (0.8)",
    .build = build_thinwall,
};
