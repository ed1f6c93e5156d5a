/* tests/passes/path_trace_fixture.h: scenes built in code, views and statistics for the
 * path tracer's tests (test_path_trace_render.c, test_path_trace_sky.c). No GL.
 *
 * Declares: PTF_PI, ptf_grow, ptf_add_material, ptf_scene_init, ptf_floor_scene, ptf_add_quad_mesh,
 *           ptf_add_instance, ptf_add_quad_at, ptf_add_light, ptf_scene_release,
 *           ptf_view_finish, ptf_view_top_ortho, ptf_view_perspective, ptf_pixel_on_plane,
 *           ptf_settings, ptf_render, ptf_assert_rel, ptf_residual_mean, ptf_corner_view_factor.
 */
#ifndef CG_TEST_PATH_TRACE_FIXTURE_H
#define CG_TEST_PATH_TRACE_FIXTURE_H

#include <cglm/cglm.h>
#include <stddef.h>

#include "cg/camera.h"
#include "cg/pt_render.h"
#include "cg/scene.h"

#define PTF_PI 3.14159265358979323846

/* Grows an array by one zeroed element (fails the test when out of memory). */
void *ptf_grow(void *array, int count, size_t elem);
/* A Lambertian material of albedo (r, g, b) emitting radiance `emission` (grey). */
int ptf_add_material(cg_scene *s, float r, float g, float b, float emission);
/* An empty scene with the default white material at 0. */
void ptf_scene_init(cg_scene *s);
/* ptf_scene_init and a grey Lambertian floor of albedo `albedo`: the plane z = 0 over
 * [-10, 10]^2, facing +z (what ptf_view_top_ortho looks down at). */
void ptf_floor_scene(cg_scene *s, float albedo);
/* The quad [-1,1]^2 in the xy plane facing +z, uv = (x+1)/2, (y+1)/2. */
int ptf_add_quad_mesh(cg_scene *s, int material);
void ptf_add_instance(cg_scene *s, int mesh, mat4 world);
/* A quad of half extents (hx, hy) centred at (cx, cy, cz) in a plane z = cz, facing +z. */
void ptf_add_quad_at(cg_scene *s, int material, float cx, float cy, float cz, float hx, float hy);
cg_light *ptf_add_light(cg_scene *s, cg_light_type type, float intensity);
void ptf_scene_release(cg_scene *s);

/* Fills the matrices of a view from view and projection matrices. */
void ptf_view_finish(cg_view *v, mat4 view, mat4 proj);
/* Orthographic, from z = 5 looking down -z at the square [-1,1]^2: world x = NDC x, y = NDC y. */
cg_view ptf_view_top_ortho(int w, int h);
cg_view ptf_view_perspective(int w, int h, vec3 eye, vec3 at);
/* World point on the plane z = 0 at the centre of pixel (x, y) of ptf_view_top_ortho. */
void ptf_pixel_on_plane(int x, int y, int w, int h, double *px, double *py);

/* pt_settings_default() with `spp` samples per pixel and `bounces` diffuse bounces. */
pt_settings ptf_settings(int spp, int bounces);
/* pt_render's image (w x h x 4 floats, to be freed). */
float *ptf_render(const cg_scene *scene, const cg_view *view, pt_settings st);
/* Fails the test unless |got - want| <= tol x |want| (tol absolute when |want| < 1e-6). */
void ptf_assert_rel(double got, double want, double tol, const char *what, int x, int y);
/* Mean over n pixels of the RGB mean minus want[i] (or 0 when want is NULL), and the
 * standard error of that mean from the spread over pixels (each pixel has its own random
 * numbers, so pixels are independent). */
void ptf_residual_mean(const float *img, const double *want, int n, double *mean, double *std_error);
/* Signed view factor from a point to the rectangle [0, X] x [0, Y] of a plane at height h
 * above it and parallel to its surface, the corner over the point (the differential area to
 * rectangle form factor, e.g. Howell's catalogue, case B-3); odd in X and Y, so rectangles
 * anywhere in the plane are sums of four corners. */
double ptf_corner_view_factor(double x, double y, double h);

#endif
