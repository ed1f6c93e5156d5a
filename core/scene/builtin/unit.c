/* What the unit scenes share (builtin:plates, wallfloor, thinwall, boxplane, terrain): the whole
 * scene turned against the voxel axes, its sun and camera turned with it, and rectangles. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

void
bs_unit_frame_make(bs_unit_frame *f, double yaw_deg, double tilt_deg)
{
    double y = yaw_deg * BS_PI / 180, t = tilt_deg * BS_PI / 180;
    double cy = cos(y), sy = sin(y), ct = cos(t), st = sin(t);
    /* Ry(yaw): x' = cy x + sy z, z' = -sy x + cy z; then Rz(tilt): x'' = ct x' - st y, y'' = st x' + ct y. */
    double ry[3][3] = { { cy, 0, sy }, { 0, 1, 0 }, { -sy, 0, cy } };
    double rz[3][3] = { { ct, -st, 0 }, { st, ct, 0 }, { 0, 0, 1 } };
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            f->r[i][j] = 0;
            for (int k = 0; k < 3; k++)
                f->r[i][j] += rz[i][k] * ry[k][j];
        }
    memset(f->m, 0, sizeof f->m);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            f->m[j * 4 + i] = (float)f->r[i][j];
    f->m[15] = 1;
}

static void
unit_apply(const bs_unit_frame *f, const double in[3], double out[3])
{
    double o[3];
    for (int i = 0; i < 3; i++)
        o[i] = f->r[i][0] * in[0] + f->r[i][1] * in[1] + f->r[i][2] * in[2];
    memcpy(out, o, sizeof o);
}

bool
bs_unit_sun(cg_scene *scene, const bs_unit_frame *f, const double dir[3], double irradiance, cg_error *err)
{
    if (!(irradiance > 0.0))
        return true;    /* E = 0: a scene lit by its emitters alone */
    double d[3];
    unit_apply(f, dir, d);
    cg_light sun = { .type = CG_LIGHT_DIRECTIONAL, .color = { 1, 1, 1 }, .intensity = (float)irradiance };
    for (int k = 0; k < 3; k++)
        sun.direction[k] = (float)d[k];
    bs_normalize3(sun.direction);
    cg_copy_name(sun.name, "sun");
    return cg_scene_add_light(scene, &sun, err) >= 0;
}

bool
bs_unit_camera(cg_scene *scene, const bs_unit_frame *f, const double eye[3], const double at[3], float yfov,
               float znear, float zfar, cg_error *err)
{
    /* Built unturned, then turned: the camera's up stays the scene's local +y. */
    cg_camera cam = { .type = CG_CAMERA_PERSPECTIVE, .yfov = yfov, .aspect = 0, .znear = znear, .zfar = zfar };
    cg_copy_name(cam.name, "view");
    float local[16];
    bs_look_at_world(eye, at, local);
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double v = 0;
            for (int k = 0; k < 4; k++)
                v += (double)f->m[k * 4 + r] * local[c * 4 + k];
            cam.world[c * 4 + r] = (float)v;
        }
    return cg_scene_add_camera(scene, &cam, err) >= 0;
}

void
bs_rect_grid(mesh_builder *b, const double c[3], const double u[3], const double v[3], int n)
{
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double p[4][3];
            for (int k = 0; k < 3; k++) {
                double base = c[k] + u[k] * i / n + v[k] * j / n;
                p[0][k] = base;
                p[1][k] = base + u[k] / n;
                p[2][k] = base + u[k] / n + v[k] / n;
                p[3][k] = base + v[k] / n;
            }
            mb_quad(b, p[0], p[1], p[2], p[3]);
        }
}

int
bs_unit_material(cg_scene *scene, const char *name, double albedo, double emission, cg_error *err)
{
    cg_material m = cg_material_default(name);
    m.base_color[0] = m.base_color[1] = m.base_color[2] = (float)albedo;
    if (emission > 0.0) {
        /* glTF keeps emissiveFactor in [0, 1]: the radiance goes in the strength. */
        m.emissive[0] = m.emissive[1] = m.emissive[2] = 1;
        m.emissive_strength = (float)emission;
    }
    return cg_scene_add_material(scene, &m, err);
}
