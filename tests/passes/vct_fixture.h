/* tests/passes/vct_fixture.h: scenes of a few free triangles and a graph runner for the
 * VCT pass tests (voxelize, mip3d, cone_gather).
 *
 * Declares: vf_scene, vf_scene_init, vf_add_triangle, vf_finish, vf_runner, vf_start, vf_run_format,
 *           vf_frame, vf_next_frame, vf_stop, vf_rebuilt, vf_reads, vf_read_image, vf_read_volume.
 */
#ifndef CG_TEST_VCT_FIXTURE_H
#define CG_TEST_VCT_FIXTURE_H

#include <stdbool.h>

#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/scene.h"

#define VF_MAX_TRIANGLES 16

/* One mesh of up to VF_MAX_TRIANGLES unshared triangles, one material, lights. */
typedef struct vf_scene {
    cg_scene scene;
    cg_mesh mesh;
    cg_instance instance;
    cg_material materials[2];
    cg_light lights[2];
    float positions[VF_MAX_TRIANGLES * 9], normals[VF_MAX_TRIANGLES * 9], texcoords[VF_MAX_TRIANGLES * 6];
    uint32_t indices[VF_MAX_TRIANGLES * 3];
} vf_scene;

/* Material 1 (the mesh's) has albedo `albedo` and emits `emission`; no lights. */
void vf_scene_init(vf_scene *s, float albedo, float emission);
void vf_add_triangle(vf_scene *s, const double a[3], const double b[3], const double c[3]);
/* Normals, bounds. */
void vf_finish(vf_scene *s);

typedef struct vf_runner {
    fg_registry *registry;
    fg_graph *graph;
    cg_gpu_scene gpu;
    bool uploaded;
    fg_frame frame;
} vf_runner;

/* Uploads the scene, loads `json`, applies `overrides` ("pass.param=value", NULL-terminated
 * list, may be NULL), compiles and prepares; fails the test on error. */
void vf_start(vf_runner *r, const cg_scene *scene, int width, int height, const char *json,
              const char *const *overrides);
/* The same with a file of $CONEGRAPH_GRAPH_DIR (e.g. "vct.json"). */
void vf_start_file(vf_runner *r, const cg_scene *scene, int width, int height, const char *graph,
                   const char *const *overrides);
/* vf_start with the graph JSON formatted from `format` and what follows (printf), no
 * overrides, then one frame (vf_frame): a graph with a setting or two filled in, run once. */
void vf_run_format(vf_runner *r, const cg_scene *scene, int width, int height, const char *format, ...)
    __attribute__((format(printf, 5, 6)));
/* Re-uploads the (changed) scene and runs one frame. */
void vf_frame(vf_runner *r);
/* One more frame without uploading the scene again, as the apps run an animation (the graph's
 * caches see only what changed in the scene's instances). */
void vf_next_frame(vf_runner *r);
void vf_stop(vf_runner *r);

/* What pass `pass` of the runner's graph reported rebuilding in the last frame ("" when
 * nothing); fails the test when the graph has no such pass. */
const char *vf_rebuilt(const vf_runner *r, const char *pass);
/* The texture reads pass `pass` counted in the last frame (fg_pass_reads), with *items the items
 * they were for; fails the test unless it counted, of `item`s. */
double vf_reads(const vf_runner *r, const char *pass, const char *item, double *items);
/* A graph's 2D output `source` ("pass.output") as RGBA floats, rows bottom to top; fails the
 * test when the graph has no such output or its size is not width x height. */
float *vf_read_image(const vf_runner *r, const char *source, int width, int height);
/* Level `level` of a graph resource as RGBA floats (x fastest, then y, then z). */
float *vf_read_volume(const vf_runner *r, const char *source, int level, int *size);

#endif
