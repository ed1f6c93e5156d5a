/* builtin:plates: two parallel square plates, a lit source above a receiver in its shadow, whose
 * indirect light is the closed-form view factor from a point to a rectangle (docs/vct.md). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

/* Receiver y = 0 facing up and source y = h facing down, both w x w centred on the y axis; the sun
 * comes from below at beta from the vertical (default: the smallest angle whose shadow of the
 * receiver clears the source by 20%, atan(1.2 w / h)), so it lights the source's underside
 * uniformly (E cos beta) and the receiver's top not at all (its underside it does: a voxel that
 * shows the lit side to both sides lights the receiver from below). The camera between the plates
 * looks at the receiver. */
static bool
build_plates(cg_scene *scene, const char *query, cg_error *err)
{
    bs_param p[] = { BS_UNIT_PARAMS, { "w", 0.01, 100, 1, false, 0, false, NULL }, { "h", 0.01, 100, 1, false, 0, false, NULL },
                     { "beta", -1, 89, -1, false, 0, false, NULL }, { "E", 0, 1e6, 3, false, 0, false, NULL } };
    if (!bs_parse_params("plates", query, p, 7, err))
        return false;
    bs_unit_frame f;
    bs_unit_frame_make(&f, p[0].value, p[1].value);
    double w = p[3].value, h = p[4].value;
    double beta = p[5].value >= 0 ? p[5].value * BS_PI / 180 : atan(1.2 * w / h);
    int mat = bs_unit_material(scene, "plate", p[2].value, 0.0, err);
    if (mat < 0)
        return false;
    mesh_builder b = { 0 };
    double c0[3] = { -w / 2, 0, w / 2 }, u0[3] = { w, 0, 0 }, v0[3] = { 0, 0, -w }; /* normal +y */
    double c1[3] = { -w / 2, h, -w / 2 }, u1[3] = { w, 0, 0 }, v1[3] = { 0, 0, w }; /* normal -y */
    bs_rect_grid(&b, c0, u0, v0, 4);
    bs_rect_grid(&b, c1, u1, v1, 4);
    if (!mb_commit(scene, &b, "plates", mat, CG_MESH_COMPLEX, f.m, err))
        return false;
    double dir[3] = { sin(beta), cos(beta), 0 };
    if (!bs_unit_sun(scene, &f, dir, p[6].value, err))
        return false;
    double eye[3] = { 0, 0.5 * h, 0.75 * w + 0.3 * h }, at[3] = { 0, 0.38 * h, -0.5 * w };
    return bs_unit_camera(scene, &f, eye, at, 0.9f, (float)(0.01 * w), (float)(20.0 * (w + h)), err);
}

const cg_builtin_scene cg_builtin_plates = {
    .name = "plates",
    .doc = "unit scene: a w x w receiver (y = 0, facing up) under a parallel source plate at height h "
    "(facing down) whose underside the sun lights from below at beta from the vertical, the receiver's "
    "top in the dark: its indirect light is the closed-form point-to-rectangle view factor; "
    "?w=W (default 1)&h=H (default 1)&beta=DEG (default -1: atan(1.2 w / h))&E=E (irradiance, default 3)"
    "&yaw=DEG&tilt=DEG (the whole scene turned against the voxel axes)&albedo=A (default 0.8)",
    .build = build_plates,
};
