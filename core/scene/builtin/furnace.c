/* builtin:furnace: a closed box, normals inward, uniform albedo and emitted radiance, camera
 * inside. ?scale=S&albedo=A&radiance=L&heightfield=H; with H = 1 the floor is a mesh of its own
 * of kind height field, so that the hybrid graphs trace it through their 2D lightmap. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

static bool
build_furnace(cg_scene *scene, const char *query, cg_error *err)
{
    bs_param p[] = {
        { "scale", 1e-6, 1e7, 1, false, 0, false, NULL },
        { "albedo", 0, 1, 0.5, false, 0, false, NULL },
        { "radiance", 0, 1e12, 1, false, 0, false, NULL },
        { "heightfield", 0, 1, 0, true, 0, false, NULL },
    };
    if (!bs_parse_params("furnace", query, p, 4, err))
        return false;
    if (!(p[0].value > 0))
        return cg_fail(err, CG_ERR_SCENE_PARAM, "builtin:furnace: scale must be > 0");
    double s = p[0].value * 0.5;
    float a = (float)p[1].value;
    cg_material m = cg_material_default("furnace");
    m.base_color[0] = m.base_color[1] = m.base_color[2] = a;
    /* glTF keeps emissiveFactor in [0, 1]: the radiance goes in the strength. */
    m.emissive[0] = m.emissive[1] = m.emissive[2] = 1;
    m.emissive_strength = (float)p[2].value;
    int mat = cg_scene_add_material(scene, &m, err);
    if (mat < 0)
        return false;
    double v[8][3];
    for (int i = 0; i < 8; i++) {
        v[i][0] = (i & 1) ? s : -s;
        v[i][1] = (i & 2) ? s : -s;
        v[i][2] = (i & 4) ? s : -s;
    }
    mesh_builder b = { 0 };
    /* The faces of mb_box, wound the other way round: normals point into the box. */
    mb_quad(&b, v[4], v[6], v[7], v[5]); /* z = +s, facing -z */
    mb_quad(&b, v[1], v[3], v[2], v[0]); /* z = -s, facing +z */
    mb_quad(&b, v[5], v[7], v[3], v[1]); /* x = +s, facing -x */
    mb_quad(&b, v[0], v[2], v[6], v[4]); /* x = -s, facing +x */
    mb_quad(&b, v[2], v[3], v[7], v[6]); /* y = +s, facing -y */
    bool heightfield = p[3].count == 1;
    mesh_builder floor = { 0 };
    mb_quad(heightfield ? &floor : &b, v[0], v[4], v[5], v[1]); /* y = -s, facing +y */
    if (!mb_commit(scene, &b, "furnace_box", mat, CG_MESH_COMPLEX, bs_identity, err)) {
        mb_free(&floor);
        return false;
    }
    if (heightfield && !mb_commit(scene, &floor, "furnace_floor", mat, CG_MESH_HEIGHTFIELD, bs_identity, err))
        return false;
    double eye[3] = { 0, 0, 0 }, at[3] = { 0, 0, -s };
    return bs_add_perspective_camera(scene, "inside", eye, at, 1.2f, (float)(s * 1e-2), (float)(s * 4), err);
}

const cg_builtin_scene cg_builtin_furnace = {
    .name = "furnace",
    .doc = "closed box with inward normals for energy tests: every surface has albedo A and emits "
    "radiance L, camera at the centre; ?scale=S (metres, 1e-6..1e7, default 1)&albedo=A "
    "(0..1, default 0.5)&radiance=L (0..1e12, default 1)&heightfield=H (0 or 1, default 0: the floor "
    "a height-field mesh of its own, for the hybrid graphs' 2D lightmap)",
    .build = build_furnace,
};
