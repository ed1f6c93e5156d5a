/* cg/camera.h: view and projection matrices for an image, from a scene camera or framed from the bounds.
 *
 * Declares: cg_view, cg_view_from_scene, cg_camera_select, cg_view_spec, cg_view_spec_check,
 *           cg_view_from_spec, cg_view_aspect_note.
 *
 * The raster passes and the path tracer both build their rays and matrices from
 * cg_view, so that they see exactly the same image.
 */
#ifndef CG_CAMERA_H
#define CG_CAMERA_H

#include <stdbool.h>
#include <stddef.h>

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
 * first camera, "auto" none (a camera named auto is reached by its index). *index = -1 when
 * there is none (the view is then framed from the bounds). Fails with CG_ERR_USAGE when no
 * camera matches. */
bool cg_camera_select(const cg_scene *scene, const char *which, int *index, cg_error *err);

/* Fills *out for camera `camera_index` (-1 = framed from the scene bounds) at width x height:
 * the image's aspect ratio is width / height, a camera's own one is fitted inside it by
 * widening the field of view (camera.c says how). */
void cg_view_from_scene(const cg_scene *scene, int camera_index, int width, int height, cg_view *out);

/* A view as the command line asks for it (--camera, --from, --look-at, --fov): a scene camera
 * or the framing, moved, aimed and zoomed (camera.c says how). Zeroed: the framing as is. */
typedef struct cg_view_spec {
    int camera;                 /* scene camera index; -1: framed from the bounds */
    bool from_given, look_at_given;
    float from[3];              /* the eye, world */
    float look_at[3];           /* the point looked at, world */
    float yfov;                 /* the image's vertical field of view, radians; 0: the camera's
                                 * (fitted to the image), or 45 degrees for the framing */
} cg_view_spec;

/* Fails with CG_ERR_USAGE, saying why, for a camera the scene lacks, a field of view outside
 * (0, 180) degrees or given to an orthographic camera, coordinates that are not finite, or a
 * point to look at where the eye is. */
bool cg_view_spec_check(const cg_scene *scene, const cg_view_spec *spec, cg_error *err);
/* cg_view_from_scene for a spec (checked with cg_view_spec_check). */
void cg_view_from_spec(const cg_scene *scene, const cg_view_spec *spec, int width, int height, cg_view *out);
/* True when the spec's camera has an aspect ratio of its own that is not the image's, with a
 * one-line note in `note` of how the view is fitted instead of stretched (a notice for users). */
bool cg_view_aspect_note(const cg_scene *scene, const cg_view_spec *spec, int width, int height, char *note,
                         size_t size);

#endif
