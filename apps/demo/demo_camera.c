/* The demo's fly camera: see demo_camera.h. */
#include "demo_camera.h"

#include <math.h>
#include <string.h>

#include <cglm/cglm.h>

#define PITCH_LIMIT 1.5533430342749532f /* 89 degrees: lookat needs forward not parallel to up */

static float
clamp_pitch(float pitch)
{
    return pitch > PITCH_LIMIT ? PITCH_LIMIT : pitch < -PITCH_LIMIT ? -PITCH_LIMIT : pitch;
}

void
demo_camera_from_view(const cg_view *view, demo_camera *out)
{
    /* inv_view is camera-to-world; the camera looks down its -z (cg/camera.h). */
    vec3 f = { -view->inv_view[8], -view->inv_view[9], -view->inv_view[10] };
    glm_vec3_normalize(f);
    memcpy(out->position, view->position, sizeof out->position);
    out->yaw = atan2f(f[0], -f[2]);
    out->pitch = clamp_pitch(asinf(f[1] > 1 ? 1 : f[1] < -1 ? -1 : f[1]));
}

void
demo_camera_forward(const demo_camera *cam, float out[3])
{
    out[0] = sinf(cam->yaw) * cosf(cam->pitch);
    out[1] = sinf(cam->pitch);
    out[2] = -cosf(cam->yaw) * cosf(cam->pitch);
}

void
demo_camera_move(demo_camera *cam, float forward, float right, float up)
{
    float f[3];
    demo_camera_forward(cam, f);
    /* Right is horizontal: forward x world up, (cos yaw, 0, sin yaw). */
    float r[3] = { cosf(cam->yaw), 0, sinf(cam->yaw) };
    for (int k = 0; k < 3; k++)
        cam->position[k] += forward * f[k] + right * r[k];
    cam->position[1] += up;
}

void
demo_camera_look(demo_camera *cam, float yaw, float pitch)
{
    cam->yaw = remainderf(cam->yaw + yaw, 2 * GLM_PIf);
    cam->pitch = clamp_pitch(cam->pitch + pitch);
}

static float
farthest_corner(const cg_scene *scene, const float from[3])
{
    float far = 0;
    for (int c = 0; c < 8; c++) {
        vec3 p = { (c & 1) ? scene->bounds_max[0] : scene->bounds_min[0],
                   (c & 2) ? scene->bounds_max[1] : scene->bounds_min[1],
                   (c & 4) ? scene->bounds_max[2] : scene->bounds_min[2] };
        float d = glm_vec3_distance(p, (float *)from);
        far = d > far ? d : far;
    }
    return far;
}

void
demo_camera_view(const demo_camera *cam, const cg_scene *scene, const cg_view *base, cg_view *out)
{
    *out = *base;
    vec3 eye = { cam->position[0], cam->position[1], cam->position[2] }, f, centre;
    demo_camera_forward(cam, f);
    glm_vec3_add(eye, f, centre);
    mat4 view, proj, view_proj, inv;
    glm_lookat(eye, centre, (vec3){ 0, 1, 0 }, view);
    memcpy(proj, base->proj, sizeof proj);
    if (!base->orthographic) {
        /* Flown away from where the scene camera stood, the scene may reach past its far
         * plane: move the plane out (the same 1.05 margin as cg_view_from_scene). */
        float far = farthest_corner(scene, cam->position) * 1.05f;
        if (far > out->zfar) {
            float n = out->znear;
            out->zfar = far;
            proj[2][2] = -(far + n) / (far - n);
            proj[3][2] = -2 * far * n / (far - n);
        }
    }
    glm_mat4_mul(proj, view, view_proj);
    memcpy(out->view, view, sizeof out->view);
    memcpy(out->proj, proj, sizeof out->proj);
    memcpy(out->view_proj, view_proj, sizeof out->view_proj);
    glm_mat4_inv(view, inv);
    memcpy(out->inv_view, inv, sizeof out->inv_view);
    glm_mat4_inv(proj, inv);
    memcpy(out->inv_proj, inv, sizeof out->inv_proj);
    glm_mat4_inv(view_proj, inv);
    memcpy(out->inv_view_proj, inv, sizeof out->inv_view_proj);
    memcpy(out->position, cam->position, sizeof out->position);
}
