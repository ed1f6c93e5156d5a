/* tests/passes/hybrid_fixture.h: small scenes for the hybrid pass tests: a height-field grid
 * (terrain) and a complex quad, with materials, an optional sun and an optional camera.
 *
 * Declares: hf_scene, hf_height_fn, hf_init, hf_grid, hf_quad, hf_sun, hf_camera_looking,
 *           hf_turn_sun, hf_plate_under_sun, hf_finish, hf_free, hf_read_2d, hf_read_2d_sized, hf_flat.
 */
#ifndef CG_TEST_HYBRID_FIXTURE_H
#define CG_TEST_HYBRID_FIXTURE_H

#include "cg/scene.h"
#include "vct_fixture.h"

typedef double (*hf_height_fn)(double x, double z, const void *user);
/* The flat ground y = 0, a height function for hf_grid. */
double hf_flat(double x, double z, const void *user);

typedef struct hf_scene {
    cg_scene scene;
    cg_mesh meshes[3];          /* 0: terrain (height field), 1 and 2: quads (complex) */
    cg_instance instances[3];
    cg_material materials[4];   /* 0 default, 1 terrain, 2 and 3 quads */
    cg_light light;
    cg_camera camera;
} hf_scene;

void hf_init(hf_scene *s);
/* Material `m` (1 terrain, 2 and 3 quads): albedo and emitted radiance, grey. */
void hf_material(hf_scene *s, int m, float albedo, float emission);
/* A (n+1) x (n+1) vertex grid over [x0, x0 + size] x [z0, z0 + size], y = height(x, z), facing up. */
void hf_grid(hf_scene *s, int n, double x0, double z0, double size, hf_height_fn height, const void *user);
/* A complex parallelogram corner, corner + e1, corner + e1 + e2, corner + e2 (normal e1 x e2),
 * in the next free quad slot (1, then 2), with material 2 or 3 (the slot's number + 1). */
void hf_quad(hf_scene *s, const double corner[3], const double e1[3], const double e2[3]);
/* A directional light travelling along `direction` (normalised here) with irradiance E. */
void hf_sun(hf_scene *s, const double direction[3], float irradiance);
/* A perspective camera at `eye` looking along `forward` with `up`, vertical field of view yfov. */
void hf_camera_looking(hf_scene *s, const double eye[3], const double forward[3], const double up[3], float yfov);
/* A small town (the voxelize tests'): hf_init, then a rolling terrain of n x n quads over
 * [-3.9, 3.9]^2 (albedo 0.4), a wall standing on it (albedo 0.8, emitting `wall_emission`) and a
 * tilted roof-like quad (albedo 0.6), about 2.6 m high in all; not finished (add lights, then
 * hf_finish). */
void hf_town(hf_scene *s, int n, float wall_emission);
/* The shadow cones' scene: a flat ground 100 m square at y = 0 (material 1, albedo 0.5), a plate of
 * 40 x 80 m facing up 10 m above it over x in [-40, 0] (material 2, albedo 0.5), and a sun of
 * `irradiance` (W/m^2) and `angular_diameter` (radians) from nearly overhead, direction
 * (0.05, -1, 0.02); no camera, not finished. */
void hf_plate_under_sun(hf_scene *s, float irradiance, float angular_diameter);
/* Turns the sun about +y by `degrees` and uploads the scene's lights to the runner's GPU scene
 * again, as an app does when only the lighting changed. */
void hf_turn_sun(vf_runner *r, hf_scene *s, double degrees);
/* Bounds and counts. */
void hf_finish(hf_scene *s);
void hf_free(hf_scene *s);

/* Level `level` of a graph's 2D resource as RGBA floats; sizes to w, h. */
float *hf_read_2d(const vf_runner *r, const char *source, int level, int *w, int *h);
/* Level 0 of a graph's 2D resource, which must be width x height. */
float *hf_read_2d_sized(const vf_runner *r, const char *source, int width, int height);

#endif
