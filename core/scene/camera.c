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
 * - The image's aspect ratio is always width / height: pixels stay square, nothing is
 *   stretched. A camera with an aspect ratio of its own (glTF aspectRatio) that is not the
 *   image's has its frame fitted inside the image: the field of view is widened across the
 *   image's longer side, so the image shows everything the camera's frame holds and more on
 *   two sides (glTF 2.0, 3.10.2, leaves a client free to stretch, crop or letterbox; widening
 *   loses nothing and needs no bars). An image wider than the camera keeps its yfov; a
 *   narrower one keeps its horizontal field of view, tan(xfov/2) = aspect tan(yfov/2).
 * - Perspective: vertical field of view yfov (fitted as above). zfar 0 (glTF: infinite)
 *   becomes a finite far plane just beyond the farthest corner of the scene bounds (1.05x the
 *   distance, at least 10 x znear), because the shadow, voxel and depth passes need finite
 *   depth ranges.
 * - Orthographic: ymag is the vertical half extent (fitted as above); the horizontal half
 *   extent is that times width / height. glTF's xmag is kept in cg_camera for export but not
 *   used for the image.
 * - No camera (index -1, or "auto"): a perspective view with yfov 45 degrees framing the
 *   bounding sphere of the scene from the direction (1, 0.6, 1) (above, front-right), at the
 *   distance where the sphere fits the narrower field of view; znear = 1% of the radius,
 *   zfar past the far side of the sphere.
 * - A view spec (cg_view_spec: --from, --look-at, --fov) moves, aims and zooms either: the
 *   eye goes to `from`; with `look_at` the camera turns to it with world +y up (+-z up when
 *   looking straight up or down), without it a scene camera keeps its orientation and the
 *   framing keeps looking at the centre of the bounds; `yfov` is the image's vertical field
 *   of view (no fitting). A framing that was moved or aimed gets the planes of the bounding
 *   sphere seen from the new eye: znear = max(1% of the radius, half the distance to the
 *   sphere), zfar = the distance to the centre + 1.5 radii. A scene camera keeps its planes.
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
    if (!strcmp(which, "auto"))
        return true;
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
    return cg_fail(err, CG_ERR_USAGE, "%s: no camera named '%s' (cameras: %s; or auto: framed from the bounds)",
                   scene->name, which, scene->camera_count ? names : "none");
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
bounding_sphere(const cg_scene *scene, vec3 centre, float *radius)
{
    vec3 lo = { scene->bounds_min[0], scene->bounds_min[1], scene->bounds_min[2] };
    vec3 hi = { scene->bounds_max[0], scene->bounds_max[1], scene->bounds_max[2] };
    glm_vec3_center(lo, hi, centre);
    *radius = 0.5f * glm_vec3_distance(lo, hi);
    if (!(*radius > 0) || !isfinite(*radius))
        *radius = 1;
}

static void
framed_view(const cg_scene *scene, float aspect, float yfov, mat4 cam_to_world, mat4 proj, float *znear,
            float *zfar)
{
    vec3 centre;
    float radius;
    bounding_sphere(scene, centre, &radius);
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

/* Turns the camera at `eye` to look at `target`, world +y up (+-z when looking along y). */
static void
aim(const vec3 eye, const vec3 target, mat4 cam_to_world)
{
    vec3 e = { eye[0], eye[1], eye[2] }, t = { target[0], target[1], target[2] }, f;
    glm_vec3_sub(t, e, f);
    glm_vec3_normalize(f);
    vec3 up = { 0, 1, 0 };
    if (fabsf(f[1]) > 0.9999f) {
        /* Straight down: the image's top towards -z; straight up: towards +z. */
        up[1] = 0;
        up[2] = f[1] > 0 ? 1.0f : -1.0f;
    }
    mat4 view;
    glm_lookat(e, t, up, view);
    glm_mat4_inv(view, cam_to_world);
}

/* The camera's field of view fitted to the image (see the top of the file): the vertical
 * tangent tan(fov/2) that shows all of a frame of aspect `own` in an image of aspect `image`. */
static float
fitted_tan(float tan_half_y, float own, float image)
{
    return own > 0 && image < own ? tan_half_y * own / image : tan_half_y;
}

static float
degrees(double radians)
{
    return (float)(radians * 180.0 / 3.14159265358979323846);
}

bool
cg_view_spec_check(const cg_scene *scene, const cg_view_spec *spec, cg_error *err)
{
    if (spec->camera >= scene->camera_count)
        return cg_fail(err, CG_ERR_USAGE, "%s: no camera %d (the scene has %d)", scene->name, spec->camera,
                       scene->camera_count);
    if (spec->yfov != 0 && !(spec->yfov > 0 && spec->yfov < 3.1415f))
        return cg_fail(err, CG_ERR_USAGE, "--fov %g: expected a vertical field of view above 0 and below 180 degrees",
                       (double)degrees(spec->yfov));
    if (spec->yfov > 0 && spec->camera >= 0 && scene->cameras[spec->camera].type == CG_CAMERA_ORTHOGRAPHIC)
        return cg_fail(err, CG_ERR_USAGE, "--fov: camera '%s' is orthographic and has no field of view",
                       scene->cameras[spec->camera].name);
    const float *p[2] = { spec->from_given ? spec->from : NULL, spec->look_at_given ? spec->look_at : NULL };
    for (int i = 0; i < 2; i++)
        if (p[i] && !(isfinite(p[i][0]) && isfinite(p[i][1]) && isfinite(p[i][2])))
            return cg_fail(err, CG_ERR_USAGE, "--%s: expected finite coordinates", i ? "look-at" : "from");
    if (spec->look_at_given) {
        /* The eye the camera is aimed from: --from, else the camera's or the framing's. */
        cg_view base;
        cg_view_spec plain = { .camera = spec->camera, .yfov = spec->yfov, .from_given = spec->from_given };
        memcpy(plain.from, spec->from, sizeof plain.from);
        cg_view_from_spec(scene, &plain, 64, 64, &base);
        double d2 = 0;
        for (int k = 0; k < 3; k++)
            d2 += ((double)spec->look_at[k] - base.position[k]) * ((double)spec->look_at[k] - base.position[k]);
        if (!(d2 > 1e-12))
            return cg_fail(err, CG_ERR_USAGE, "--look-at %g,%g,%g: that is where the camera is; look at another point",
                           (double)spec->look_at[0], (double)spec->look_at[1], (double)spec->look_at[2]);
    }
    return true;
}

bool
cg_view_aspect_note(const cg_scene *scene, const cg_view_spec *spec, int width, int height, char *note,
                    size_t size)
{
    if (spec->camera < 0 || spec->camera >= scene->camera_count || width <= 0 || height <= 0)
        return false;
    const cg_camera *cam = &scene->cameras[spec->camera];
    float image = (float)width / (float)height;
    if (!(cam->aspect > 0) || fabsf(image / cam->aspect - 1.0f) < 1e-3f)
        return false;
    int n = snprintf(note, size, "camera '%s' has aspect ratio %.3g and the %dx%d image %.3g: ", cam->name,
                     (double)cam->aspect, width, height, (double)image);
    if (n < 0 || (size_t)n >= size)
        return true;
    char *rest = note + n;
    size_t left = size - (size_t)n;
    if (spec->yfov > 0) {
        snprintf(rest, left, "--fov sets the image's vertical field of view (%.1f degrees), nothing is stretched",
                 (double)degrees(spec->yfov));
    } else if (cam->type == CG_CAMERA_ORTHOGRAPHIC) {
        float ymag = cam->ymag * fitted_tan(1.0f, cam->aspect, image);
        snprintf(rest, left, "the view is widened to %g x %g m (half extents; the camera's %g x %g m kept whole), "
                 "nothing is stretched", (double)(ymag * image), (double)ymag, (double)(cam->ymag * cam->aspect),
                 (double)cam->ymag);
    } else {
        double t = tan(0.5 * (double)cam->yfov);
        double xfov = 2.0 * atan(t * cam->aspect);
        if (image > cam->aspect)
            snprintf(rest, left, "the horizontal field of view is widened from %.1f to %.1f degrees (the vertical "
                     "one, %.1f degrees, kept), nothing is stretched", (double)degrees(xfov),
                     (double)degrees(2.0 * atan(t * image)), (double)degrees(cam->yfov));
        else
            snprintf(rest, left, "the vertical field of view is widened from %.1f to %.1f degrees (the horizontal "
                     "one, %.1f degrees, kept), nothing is stretched", (double)degrees(cam->yfov),
                     (double)degrees(2.0 * atan(t * cam->aspect / image)), (double)degrees(xfov));
    }
    return true;
}

void
cg_view_from_spec(const cg_scene *scene, const cg_view_spec *spec, int width, int height, cg_view *out)
{
    memset(out, 0, sizeof *out);
    out->width = width;
    out->height = height;
    float image_aspect = (width > 0 && height > 0) ? (float)width / (float)height : 1.0f;
    mat4 cam_to_world, proj, view, view_proj;
    int camera_index = spec->camera;
    if (camera_index < 0 || camera_index >= scene->camera_count) {
        float yfov = spec->yfov > 0 ? spec->yfov : glm_rad(45.0f);
        framed_view(scene, image_aspect, yfov, cam_to_world, proj, &out->znear, &out->zfar);
        if (spec->from_given || spec->look_at_given) {
            vec3 centre, eye, target;
            float radius;
            bounding_sphere(scene, centre, &radius);
            glm_vec3_copy(spec->from_given ? (float *)spec->from : cam_to_world[3], eye);
            glm_vec3_copy(spec->look_at_given ? (float *)spec->look_at : centre, target);
            aim(eye, target, cam_to_world);
            float d = glm_vec3_distance(eye, centre);
            out->znear = fmaxf(radius * 0.01f, 0.5f * (d - radius));
            out->zfar = d + radius * 1.5f;
            glm_perspective(yfov, image_aspect, out->znear, out->zfar, proj);
        }
    } else {
        const cg_camera *cam = &scene->cameras[camera_index];
        orthonormal_camera_to_world(cam->world, cam_to_world);
        if (spec->from_given)
            glm_vec3_copy((float *)spec->from, cam_to_world[3]);
        if (spec->look_at_given) {
            vec3 eye;
            glm_vec3_copy(cam_to_world[3], eye);
            aim(eye, spec->look_at, cam_to_world);
        }
        out->znear = cam->znear;
        out->zfar = cam->zfar;
        if (cam->type == CG_CAMERA_ORTHOGRAPHIC) {
            out->orthographic = true;
            float ymag = cam->ymag * fitted_tan(1.0f, cam->aspect, image_aspect);
            glm_ortho(-ymag * image_aspect, ymag * image_aspect, -ymag, ymag, cam->znear, cam->zfar, proj);
        } else {
            if (cam->zfar <= 0) {
                float far = farthest_corner_distance(scene, cam_to_world[3]) * 1.05f;
                out->zfar = far > cam->znear * 10 ? far : cam->znear * 10;
            }
            /* cam->yfov itself where nothing is fitted: no round trip through the tangent. */
            float yfov = spec->yfov > 0 ? spec->yfov : cam->yfov;
            if (!(spec->yfov > 0) && cam->aspect > 0 && image_aspect < cam->aspect)
                yfov = 2.0f * atanf(fitted_tan(tanf(0.5f * cam->yfov), cam->aspect, image_aspect));
            glm_perspective(yfov, image_aspect, out->znear, out->zfar, proj);
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

void
cg_view_from_scene(const cg_scene *scene, int camera_index, int width, int height, cg_view *out)
{
    cg_view_spec spec = { .camera = camera_index };
    cg_view_from_spec(scene, &spec, width, height, out);
}
