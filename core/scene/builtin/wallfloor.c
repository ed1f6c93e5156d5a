/* builtin:wallfloor: a floor and a wall meeting at a right angle, both lit by the sun from the
 * front; each one's indirect light is the closed-form form factor between perpendicular
 * rectangles (docs/vct.md). With emit=L the wall is an emitter instead. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

/* Floor y = 0 (x in [-w/2, w/2], z in [0, d]) and wall z = 0 (y in [0, H]); the sun comes from the
 * front (+z) at elevation gamma and lights the floor (E sin gamma) and the wall's front
 * (E cos gamma) uniformly. emit=L makes the wall emit radiance L on both sides (E = 0 for a scene
 * lit by the wall alone): the floor then receives the emitter's light directly, and the wall
 * receives it back by way of the floor. */
static bool
build_wallfloor(cg_scene *scene, const char *query, cg_error *err)
{
    bs_param p[] = { BS_UNIT_PARAMS, { "w", 0.01, 100, 2, false, 0, false, NULL }, { "d", 0.01, 100, 1, false, 0, false, NULL },
                     { "H", 0.01, 100, 1, false, 0, false, NULL }, { "gamma", 1, 89, 45, false, 0, false, NULL },
                     { "E", 0, 1e6, 3, false, 0, false, NULL }, { "emit", 0, 1e6, 0, false, 0, false, NULL } };
    if (!bs_parse_params("wallfloor", query, p, 9, err))
        return false;
    bs_unit_frame f;
    bs_unit_frame_make(&f, p[0].value, p[1].value);
    double w = p[3].value, d = p[4].value, H = p[5].value, g = p[6].value * BS_PI / 180;
    int floor_mat = bs_unit_material(scene, "floor", p[2].value, 0.0, err);
    int wall_mat = bs_unit_material(scene, "wall", p[2].value, p[8].value, err);
    if (floor_mat < 0 || wall_mat < 0)
        return false;
    mesh_builder floor = { 0 }, wall = { 0 };
    double cf[3] = { -w / 2, 0, d }, uf[3] = { w, 0, 0 }, vf[3] = { 0, 0, -d };  /* floor, +y */
    double cw[3] = { -w / 2, 0, 0 }, uw[3] = { w, 0, 0 }, vw[3] = { 0, H, 0 };   /* wall, +z */
    bs_rect_grid(&floor, cf, uf, vf, 4);
    bs_rect_grid(&wall, cw, uw, vw, 4);
    if (!mb_commit(scene, &floor, "floor", floor_mat, CG_MESH_COMPLEX, f.m, err)) {
        mb_free(&wall);
        return false;
    }
    if (!mb_commit(scene, &wall, "wall", wall_mat, CG_MESH_COMPLEX, f.m, err))
        return false;
    double dir[3] = { 0, -sin(g), -cos(g) };
    if (!bs_unit_sun(scene, &f, dir, p[7].value, err))
        return false;
    double eye[3] = { 0.3 * w, 0.8 * H, d + 0.6 * (w > H ? w : H) }, at[3] = { 0, 0.35 * H, 0.3 * d };
    return bs_unit_camera(scene, &f, eye, at, 0.9f, 0.01f, (float)(100.0 * (w + d + H)), err);
}

const cg_builtin_scene cg_builtin_wallfloor = {
    .name = "wallfloor",
    .doc = "unit scene: a floor (w x d) and a wall (w x H) meeting at a right angle, the sun from the front "
    "at elevation gamma lighting both; each one's indirect light is the closed-form form factor between "
    "perpendicular rectangles; ?w=W (default 2)&d=D (1)&H=H (1)&gamma=DEG (45)&E=E (irradiance, 3)"
    "&emit=L (the wall emits radiance L, default 0)&yaw=DEG&tilt=DEG&albedo=A (0.8)",
    .build = build_wallfloor,
};
