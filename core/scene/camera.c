/* core/scene/camera.c: view and projection matrices (cglm, OpenGL conventions).
 *
 * Conventions, shared by the raster passes and the path tracer:
 * - World: metres, y up. The camera looks down its local -z, +x right, +y up (glTF 3.10).
 *   The camera's world matrix is orthonormalised (scale and shear removed) before inverting:
 *   a camera node's scale must not change what it sees.
 * - proj maps camera space to GL clip space, NDC x, y, z in [-1, 1], z = -1 at znear.
 * - Pixels: (px, py) in window coordinates as GL rasterises them, px from the left, py
 *   from the BOTTOM row; pixel (i, j) has its centre at (i + 0.5, j + 0.5), so
 *   ndc = 2 * (p / size) - 1. A primary ray goes through inv_proj x (ndc, -1) (the near
 *   plane, camera space), from the eye (perspective) or along -z (orthographic), turned into
 *   the world by inv_view; images stored top to bottom flip y.
 * - Perspective: vertical field of view yfov; aspect = the camera's aspect when non-zero,
 *   else width / height (the image decides). zfar 0 (glTF: infinite) becomes a finite far
 *   plane just beyond the farthest corner of the scene bounds (1.05x the distance, at least
 *   10 x znear), because the shadow, voxel and depth passes need finite depth ranges.
 * - Orthographic: ymag is the vertical half extent; the horizontal half extent is
 *   ymag x aspect (the camera's when non-zero, else the image's) so pixels stay square.
 *   glTF's xmag is kept in cg_camera for export but not used for the image.
 * - No camera (index -1): a perspective view with yfov 45 degrees framing the bounding
 *   sphere of the scene from the direction (1, 0.6, 1) (above, front-right), at the distance
 *   where the sphere fits the narrower field of view; znear = 1% of the radius, zfar past the
 *   far side of the sphere.
 */
#include "cg/camera.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

bool
cg_camera_select(const cg_scene *scene, const char *which, int *index, cg_error *err)
{
    *index = -1;
    if (!which || !which[0]) {
        *index = scene->camera_count > 0 ? 0 : -1;
        return true;
    }
    bool digits = true;
    for (const char *p = which; *p; p++)
        digits = digits && isdigit((unsigned char)*p);
    if (digits) {
        long i = strlen(which) < 10 ? atol(which) : -1;
        if (i < 0 || i >= scene->camera_count)
            return cg_fail(err, CG_ERR_USAGE, "%s: no camera %s (the scene has %d camera%s)",
                           scene->name, which, scene->camera_count,
                           scene->camera_count == 1 ? "" : "s");
        *index = (int)i;
        return true;
    }
    for (int i = 0; i < scene->camera_count; i++)
        if (!strcmp(scene->cameras[i].name, which)) {
            *index = i;
            return true;
        }
    char names[1024] = "";
    for (int i = 0; i < scene->camera_count; i++)
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s'%s'", i ? ", " : "",
                 scene->cameras[i].name);
    return cg_fail(err, CG_ERR_USAGE, "%s: no camera named '%s' (cameras: %s)", scene->name, which,
                   scene->camera_count ? names : "none");
}

/* Gram-Schmidt on the rotation columns, keeping -z (the view direction) exact. */
static void
orthonormal_camera_to_world(const float world[16], mat4 out)
{
    vec3 x = { world[0], world[1], world[2] };
    vec3 y = { world[4], world[5], world[6] };
    vec3 z = { world[8], world[9], world[10] };
    glm_vec3_normalize(z);
    vec3 t;
    glm_vec3_scale(z, glm_vec3_dot(y, z), t);
    glm_vec3_sub(y, t, y);
    glm_vec3_normalize(y);
    glm_vec3_cross(y, z, x);
    glm_mat4_identity(out);
    for (int k = 0; k < 3; k++) {
        out[0][k] = x[k];
        out[1][k] = y[k];
        out[2][k] = z[k];
        out[3][k] = world[12 + k];
    }
}

static float
farthest_corner_distance(const cg_scene *scene, const vec3 from)
{
    float far = 0;
    for (int c = 0; c < 8; c++) {
        vec3 p = { (c & 1) ? scene->bounds_max[0] : scene->bounds_min[0],
                   (c & 2) ? scene->bounds_max[1] : scene->bounds_min[1],
                   (c & 4) ? scene->bounds_max[2] : scene->bounds_min[2] };
        float d = glm_vec3_distance(p, (float *)from);
        if (d > far)
            far = d;
    }
    return far;
}

static void
store(float dst[16], mat4 m)
{
    memcpy(dst, m, 16 * sizeof(float));
}

static void
framed_view(const cg_scene *scene, float aspect, mat4 cam_to_world, mat4 proj, float *znear, float *zfar)
{
    vec3 lo = { scene->bounds_min[0], scene->bounds_min[1], scene->bounds_min[2] };
    vec3 hi = { scene->bounds_max[0], scene->bounds_max[1], scene->bounds_max[2] };
    vec3 centre;
    glm_vec3_center(lo, hi, centre);
    float radius = 0.5f * glm_vec3_distance(lo, hi);
    if (!(radius > 0) || !isfinite(radius))
        radius = 1;
    const float yfov = glm_rad(45.0f);
    float half = yfov * 0.5f;
    float half_x = atanf(tanf(half) * aspect);
    float fit = half < half_x ? half : half_x;
    float dist = radius / sinf(fit);
    vec3 dir = { 1.0f, 0.6f, 1.0f };
    glm_vec3_normalize(dir);
    vec3 eye;
    glm_vec3_scale(dir, dist, eye);
    glm_vec3_add(eye, centre, eye);
    mat4 view;
    glm_lookat(eye, centre, (vec3){ 0, 1, 0 }, view);
    glm_mat4_inv(view, cam_to_world);
    *znear = radius * 0.01f;
    *zfar = dist + radius * 1.5f;
    glm_perspective(yfov, aspect, *znear, *zfar, proj);
}

void
cg_view_from_scene(const cg_scene *scene, int camera_index, int width, int height, cg_view *out)
{
    memset(out, 0, sizeof *out);
    out->width = width;
    out->height = height;
    float image_aspect = (width > 0 && height > 0) ? (float)width / (float)height : 1.0f;
    mat4 cam_to_world, proj, view, view_proj;
    if (camera_index < 0 || camera_index >= scene->camera_count) {
        framed_view(scene, image_aspect, cam_to_world, proj, &out->znear, &out->zfar);
    } else {
        const cg_camera *cam = &scene->cameras[camera_index];
        float aspect = cam->aspect > 0 ? cam->aspect : image_aspect;
        orthonormal_camera_to_world(cam->world, cam_to_world);
        out->znear = cam->znear;
        out->zfar = cam->zfar;
        if (cam->type == CG_CAMERA_ORTHOGRAPHIC) {
            out->orthographic = true;
            glm_ortho(-cam->ymag * aspect, cam->ymag * aspect, -cam->ymag, cam->ymag, cam->znear,
                      cam->zfar, proj);
        } else {
            if (cam->zfar <= 0) {
                float far = farthest_corner_distance(scene, cam_to_world[3]) * 1.05f;
                out->zfar = far > cam->znear * 10 ? far : cam->znear * 10;
            }
            glm_perspective(cam->yfov, aspect, out->znear, out->zfar, proj);
        }
    }
    glm_mat4_inv(cam_to_world, view);
    glm_mat4_mul(proj, view, view_proj);
    store(out->view, view);
    store(out->proj, proj);
    store(out->view_proj, view_proj);
    store(out->inv_view, cam_to_world);
    mat4 inv;
    glm_mat4_inv(proj, inv);
    store(out->inv_proj, inv);
    glm_mat4_inv(view_proj, inv);
    store(out->inv_view_proj, inv);
    for (int k = 0; k < 3; k++)
        out->position[k] = cam_to_world[3][k];
}
