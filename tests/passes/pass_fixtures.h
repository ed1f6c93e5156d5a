/* tests/passes/pass_fixtures.h: small scenes built in code and a graph runner for the
 * per-pass tests.
 *
 * Declares: fx_scene, fx_scene_init, fx_add_quad, fx_add_material, fx_add_light,
 *           fx_scene_finish, fx_view_look_at, fx_run, fx_runner, fx_runner_free,
 *           fx_read_depth, fx_pixel_of.
 */
#ifndef CG_TEST_PASS_FIXTURES_H
#define CG_TEST_PASS_FIXTURES_H

#include <stdbool.h>

#include "cg/camera.h"
#include "cg/fg.h"
#include "cg/gl.h"
#include "cg/gpu_scene.h"
#include "cg/scene.h"

#define FX_MAX 8

/* A scene of axis-aligned quads held in fixed arrays (nothing to free). */
typedef struct fx_scene {
    cg_scene scene;
    cg_mesh meshes[FX_MAX];
    cg_instance instances[FX_MAX];
    cg_material materials[FX_MAX];
    cg_light lights[FX_MAX];
    cg_texture textures[FX_MAX];
    float positions[FX_MAX][12], normals[FX_MAX][12], texcoords[FX_MAX][8];
    uint32_t indices[FX_MAX][6];
} fx_scene;

/* Material 0 is white (albedo 1). */
void fx_scene_init(fx_scene *s);
int fx_add_material(fx_scene *s, float r, float g, float b);
/* A quad perpendicular to `axis` (0 x, 1 y, 2 z) at coordinate `at`, spanning
 * [lo0, hi0] x [lo1, hi1] over the two other axes in order, normal along +axis. */
void fx_add_quad(fx_scene *s, int axis, float at, float lo0, float hi0, float lo1, float hi1, int material);
cg_light *fx_add_light(fx_scene *s, cg_light_type type, float intensity);
/* Computes the world bounds. */
void fx_scene_finish(fx_scene *s);

/* A perspective view (vertical field of view in degrees) from eye to target. */
void fx_view_look_at(const float eye[3], const float target[3], const float up[3], float fovy_degrees,
                     int width, int height, cg_view *out);
/* Pixel (x, y from the bottom, as GL stores rows) that sees world point p. */
void fx_pixel_of(const cg_view *view, const float p[3], int *x, int *y);

/* A graph from JSON run for one frame on an uploaded scene. */
typedef struct fx_runner {
    fg_registry *registry;
    fg_graph *graph;
    cg_gpu_scene gpu;
    fg_frame frame;
} fx_runner;

/* Registers the built-in passes plus `extra` (may be NULL), loads `json`, compiles,
 * prepares and executes one frame; fails the test on any error. */
void fx_run(fx_runner *r, const fx_scene *s, const cg_view *view, const char *json,
            const fg_pass_type *extra);
void fx_runner_free(fx_runner *r);

/* Depth texture as floats, rows bottom to top; the caller frees. */
float *fx_read_depth(GLuint texture, int *w, int *h);

#endif
