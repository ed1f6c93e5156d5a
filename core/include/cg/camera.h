/* cg/camera.h: view and projection matrices for an image, from a scene camera or framed from the bounds.
 *
 * Declares: cg_view, cg_view_from_scene, cg_camera_select.
 *
 * The raster passes and the path tracer both build their rays and matrices from
 * cg_view, so that they see exactly the same image.
 */
#ifndef CG_CAMERA_H
#define CG_CAMERA_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/scene.h"

typedef struct cg_view {
    int width, height;          /* image size in pixels */
    bool orthographic;
    float view[16];             /* world to camera, column-major */
    float proj[16];             /* camera to clip (GL convention, z in [-1,1]) */
    float view_proj[16];
    float inv_view[16];         /* camera to world */
    float inv_proj[16];
    float inv_view_proj[16];
    float position[3];          /* camera position, world */
    float znear, zfar;
} cg_view;

/* Finds a camera by name, or by index when `which` is all digits; NULL or "" picks the
 * first camera. *index = -1 when the scene has no camera (the view is then framed from
 * the bounds). Fails with CG_ERR_USAGE when no camera matches. */
bool cg_camera_select(const cg_scene *scene, const char *which, int *index, cg_error *err);

/* Fills *out for camera `camera_index` (-1 = framed from the scene bounds) at width x height. */
void cg_view_from_scene(const cg_scene *scene, int camera_index, int width, int height, cg_view *out);

#endif
