/* core/scene/builtin/builtin_internal.h: what the built-in scenes share: their table entry,
 * query parameters, random numbers and noise, a mesh builder, materials and cameras.
 *
 * Declares: cg_builtin_scene, bs_param, bs_parse_params, bs_rng, bs_mix64, bs_rng_next,
 *           bs_rng_range, bs_value_noise, bs_fbm, mesh_builder, mb_vertex, mb_triangle,
 *           mb_flat_triangle, mb_quad, mb_box, mb_free, mb_commit, bs_identity, bs_unit_cube,
 *           bs_trs_matrix, bs_add_material, bs_look_at_world, bs_add_perspective_camera,
 *           bs_normalize3, bs_quat_from_minus_z, BS_PI, and one cg_builtin_scene per scene file.
 *
 * A scene is one file defining a cg_builtin_scene; builtin.c lists them. Every scene is a
 * pure function of its parameters (no global state), so the same query gives a
 * bit-identical scene.
 */
#ifndef CG_BUILTIN_INTERNAL_H
#define CG_BUILTIN_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "cg/error.h"
#include "cg/scene.h"

#define BS_PI 3.14159265358979323846

/* One built-in scene: its name (builtin:NAME), one line for `info --help`, and its builder,
 * which adds meshes, materials, lights and cameras to `scene` (material 0, the default
 * white, is already there) from the query string after '?' (NULL when none). */
typedef struct cg_builtin_scene {
    const char *name;
    const char *doc;
    bool (*build)(cg_scene *scene, const char *query, cg_error *err);
} cg_builtin_scene;

extern const cg_builtin_scene cg_builtin_openworld;
extern const cg_builtin_scene cg_builtin_cornell;
extern const cg_builtin_scene cg_builtin_furnace;

/* ---------------------------------------------------------------- query parameters */

typedef struct bs_param {
    const char *key;
    double min, max, value; /* value: the default, replaced by the query's */
    bool integer;           /* then `count` holds the exact value too */
    uint64_t count;
    bool seen;
    const char *const *choices; /* NULL-terminated names: the value is a name, `count` its index */
} bs_param;

/* Parses "key=value&..." into the specs: unknown keys, repeats, malformed or out-of-range
 * values fail with CG_ERR_SCENE_PARAM naming the scene and the key. */
bool bs_parse_params(const char *scene, const char *query, bs_param *specs, int count, cg_error *err);

/* ---------------------------------------------------------------- random numbers and noise */

/* splitmix64 (Steele, Lea, Flood 2014): tiny, full period, good enough for placement. */
typedef struct bs_rng {
    uint64_t state;
} bs_rng;

uint64_t bs_mix64(uint64_t z);
uint64_t bs_rng_next(bs_rng *r);
/* Uniform in [lo, hi). */
double bs_rng_range(bs_rng *r, double lo, double hi);
/* Value noise in [0, 1): smooth interpolation of random values on the integer lattice. */
double bs_value_noise(double x, double z, uint64_t seed);
/* Fractal Brownian motion: 5 octaves; centred on 0, in about [-1, 1]. */
double bs_fbm(double x, double z, uint64_t seed);

/* ---------------------------------------------------------------- meshes */

typedef struct mesh_builder {
    float *positions, *normals, *texcoords;
    uint32_t *indices;
    uint32_t vertex_count, vertex_cap, index_count, index_cap;
    bool failed;
} mesh_builder;

uint32_t mb_vertex(mesh_builder *b, const double p[3], const double n[3]);
void mb_triangle(mesh_builder *b, uint32_t i0, uint32_t i1, uint32_t i2);
/* A flat triangle, counter-clockwise seen from the side its normal points to. */
void mb_flat_triangle(mesh_builder *b, const double p0[3], const double p1[3], const double p2[3]);
/* A flat quad p0 p1 p2 p3, counter-clockwise seen from its front. */
void mb_quad(mesh_builder *b, const double p0[3], const double p1[3], const double p2[3], const double p3[3]);
/* An oriented box: centre c, half extents h along the axes rotated by `yaw` about +y; faces
 * point outwards; `bottom` adds the underside. */
void mb_box(mesh_builder *b, const double c[3], const double h[3], double yaw, bool bottom);
void mb_free(mesh_builder *b);
/* Moves the builder's arrays into a new mesh with one instance at `world`. */
bool mb_commit(cg_scene *scene, mesh_builder *b, const char *name, int material, cg_mesh_kind kind,
               const float world[16], cg_error *err);

extern const float bs_identity[16];
/* A unit cube [-0.5, 0.5]^3 with outward faces, placed by instance transforms. */
void bs_unit_cube(mesh_builder *b);
/* Translation, rotation by `yaw` about +y, and scale, as a column-major matrix. */
void bs_trs_matrix(double tx, double ty, double tz, double yaw, double sx, double sy, double sz, float m[16]);

/* ---------------------------------------------------------------- materials and cameras */

int bs_add_material(cg_scene *scene, const char *name, float r, float g, float b, cg_error *err);
/* Camera-to-world matrix of a camera at `eye` looking at `target` with +y up. */
void bs_look_at_world(const double eye[3], const double target[3], float world[16]);
bool bs_add_perspective_camera(cg_scene *scene, const char *name, const double eye[3], const double target[3],
                               float yfov, float znear, float zfar, cg_error *err);
void bs_normalize3(float v[3]);
/* The unit quaternion (x, y, z, w) that turns -z onto the unit vector d (a glTF light's node). */
void bs_quat_from_minus_z(const float d[3], double q[4]);

#endif
