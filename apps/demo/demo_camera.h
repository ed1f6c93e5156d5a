/* apps/demo/demo_camera.h: the demo's fly camera: a position, yaw and pitch (world y up),
 * started from the scene's view and turned back into a cg_view with that view's projection.
 *
 * Declares: demo_camera, demo_camera_from_view, demo_camera_forward, demo_camera_move,
 *           demo_camera_look, demo_camera_view.
 */
#ifndef CONEGRAPH_DEMO_CAMERA_H
#define CONEGRAPH_DEMO_CAMERA_H

#include "cg/camera.h"
#include "cg/scene.h"

typedef struct demo_camera {
    float position[3];      /* world, metres */
    float yaw;              /* radians about +y; 0 looks down -z, pi/2 down +x */
    float pitch;            /* radians, positive looks up; kept within +-89 degrees */
} demo_camera;

/* The camera of `view` (its roll is dropped: the fly camera keeps the horizon level). */
void demo_camera_from_view(const cg_view *view, demo_camera *out);
/* Unit vector the camera looks along. */
void demo_camera_forward(const demo_camera *cam, float out[3]);
/* Moves by `forward` metres along the view direction, `right` along the horizontal right
 * vector and `up` along world +y. */
void demo_camera_move(demo_camera *cam, float forward, float right, float up);
/* Turns by yaw and pitch in radians (positive: right, up). */
void demo_camera_look(demo_camera *cam, float yaw, float pitch);
/* The view of `cam` with the projection of `base` (cg_view_from_scene at the output size).
 * A perspective far plane moves out so that the scene bounds stay inside it. */
void demo_camera_view(const demo_camera *cam, const cg_scene *scene, const cg_view *base, cg_view *out);

#endif
