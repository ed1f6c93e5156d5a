/* builtin:cornell: a Cornell box, 1 m by default, open at +z, lit by a spot light under the
 * ceiling pointing down (a perspective shadow map covers its cone). ?scale=S&light_scale=K: the
 * box is S metres and the spot's intensity 2 K S^2 W/sr, so that E = I / d^2 on every surface is
 * 2.1 K W/m^2 at the floor's centre whatever S: the same image at every scale, K times brighter
 * (what the scale sweep and the radiance range tests render). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

static bool
build_cornell(cg_scene *scene, const char *query, cg_error *err)
{
    bs_param params[] = {
        { "scale", 1e-6, 1e7, 1, false, 0, false, NULL },
        { "light_scale", 0, 1e12, 1, false, 0, false, NULL },
    };
    if (!bs_parse_params("cornell", query, params, 2, err))
        return false;
    if (!(params[0].value > 0))
        return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:cornell: scale must be > 0");
    const double s = params[0].value, k = params[1].value;
    int white = bs_add_material(scene, "white", 0.73f, 0.73f, 0.73f, err);
    int red = bs_add_material(scene, "red", 0.63f, 0.065f, 0.05f, err);
    int green = bs_add_material(scene, "green", 0.14f, 0.45f, 0.091f, err);
    if (white < 0 || red < 0 || green < 0)
        return false;
    /* Box x in [-0.5, 0.5], y in [0, 1], z in [-0.5, 0.5], open at z = +0.5; faces point in. */
    double p[8][3];
    for (int i = 0; i < 8; i++) {
        p[i][0] = ((i & 1) ? 0.5 : -0.5) * s;
        p[i][1] = ((i & 2) ? 1.0 : 0.0) * s;
        p[i][2] = ((i & 4) ? 0.5 : -0.5) * s;
    }
    mesh_builder shell = { 0 }, left = { 0 }, right = { 0 }, cube = { 0 };
    mb_quad(&shell, p[0], p[4], p[5], p[1]); /* floor, +y */
    mb_quad(&shell, p[2], p[3], p[7], p[6]); /* ceiling, -y */
    mb_quad(&shell, p[0], p[1], p[3], p[2]); /* back, +z */
    mb_quad(&left, p[0], p[2], p[6], p[4]);  /* left, +x */
    mb_quad(&right, p[1], p[5], p[7], p[3]); /* right, -x */
    bs_unit_cube(&cube);
    /* The two blocks are one unit cube placed twice by instance transforms (scaled, turned). */
    float tall[16], low[16];
    bs_trs_matrix(-0.17 * s, 0.30 * s, -0.15 * s, 0.30, 0.28 * s, 0.60 * s, 0.28 * s, tall);
    bs_trs_matrix(0.18 * s, 0.15 * s, 0.14 * s, -0.30, 0.28 * s, 0.30 * s, 0.28 * s, low);
    bool ok = mb_commit(scene, &shell, "white_walls", white, CG_MESH_COMPLEX, bs_identity, err) &&
              mb_commit(scene, &left, "left_wall", red, CG_MESH_COMPLEX, bs_identity, err) &&
              mb_commit(scene, &right, "right_wall", green, CG_MESH_COMPLEX, bs_identity, err) &&
              mb_commit(scene, &cube, "block", white, CG_MESH_COMPLEX, tall, err) &&
              cg_scene_add_instance(scene, scene->mesh_count - 1, low, err) >= 0;
    mb_free(&shell);
    mb_free(&left);
    mb_free(&right);
    mb_free(&cube);
    if (!ok)
        return false;

    /* The light: a spot 3 cm (at S = 1) under the ceiling pointing straight down. Its 60-degree
     * outer cone fits one perspective shadow map (120-degree field of view). Intensity 2 W/sr
     * gives E = 2 / 0.97^2 = 2.1 W/m^2 at the centre of the floor; S^2 keeps that at any size. */
    cg_light spot = { .type = CG_LIGHT_SPOT, .color = { 1, 1, 1 }, .intensity = (float)(2.0 * k * s * s),
                      .position = { 0, (float)(0.97 * s), 0 }, .direction = { 0, -1, 0 },
                      .inner_cone_angle = 0.75f, .outer_cone_angle = (float)(BS_PI / 3) };
    cg_copy_name(spot.name, "ceiling_spot");
    if (cg_scene_add_light(scene, &spot, err) < 0)
        return false;
    double eye[3] = { 0, 0.5 * s, 1.85 * s }, at[3] = { 0, 0.5 * s, 0 };
    return bs_add_perspective_camera(scene, "front", eye, at, 0.70f, (float)(0.05 * s), (float)(5.0 * s), err);
}

const cg_builtin_scene cg_builtin_cornell = {
    .name = "cornell",
    .doc = "Cornell box, red left and green right walls, two white blocks, open front, spot light "
    "under the ceiling pointing down; ?scale=S (metres, 1e-6..1e7, default 1: the spot's intensity "
    "follows S^2, so the image does not change)&light_scale=K (0..1e12, default 1: the spot's "
    "intensity times K, E = 2.1 K W/m^2 at the floor's centre)",
    .build = build_cornell,
};
