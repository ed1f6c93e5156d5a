/* apps/common/app_session.h: one graph run on one scene, the sequence every app goes through,
 * written once: load the scene and pick its camera; make the pass registry (built-in passes,
 * then plugins); load a graph file, apply --set overrides, mark the resources to read back as
 * outputs; compile without GL, so that every bad-input error is found before the scene goes
 * to the GPU; make the GL context and upload the scene; compile again with GL (the context's
 * texture limits) and prepare; run frames with timing; check for GL errors; read outputs back
 * into images; tear everything down, on every path.
 *
 * Declares: app_session_desc, app_graph_desc, app_session, app_run_desc, app_frame_stats,
 *           app_light_scene, app_session_open, app_session_load_graph, app_session_check,
 *           app_session_start_gl, app_session_compile, app_session_mark_output, app_session_set_time,
 *           app_session_run, app_session_check_gl, app_session_read_image,
 *           app_session_write_image, app_session_stop_gl, app_session_close,
 *           app_frame_stats_pass_median, app_frame_stats_free.
 *
 * The scene's lighting belongs to the scene and is settled once, when the first graph is
 * loaded (before anything compiles): the sky of --sky, else the one the graph file asks for;
 * then, when nothing lights the scene, the default light (a sun and a sky) with a notice on
 * stderr. A later graph asking for another sky is bad input (a bench compares every graph
 * with one reference per scene): --sky chooses one for all. A camera whose own aspect ratio
 * is not the image's gets a notice of how its view was fitted.
 *
 * Order: open, load_graph, check (no GL), start_gl, compile, run, read or write images,
 * close. An animated scene is posed per frame by app_session_set_time (run does it when asked):
 * the same update for every app, so that render, bench and the demo show the same frame at the
 * same time. A graph may be loaded again (bench: one setting after another) and compiled again
 * after its parameters, the view or the size changed (the demo); stop_gl gives up the context
 * and the GPU scene while the CPU scene stays (bench: one context per scene at a time).
 *
 * Errors: every function that can fail returns false and fills err, its message prefixed with
 * where it failed ("scene: ...", "graph: ...", "GL context: ..."); the status gives the exit
 * code (2: bad scene, camera, plugin, graph, parameter, size or budget; 1: a failure while
 * running), which app_fail prints and returns. After a failure the session is still in a
 * state app_session_close tears down.
 */
#ifndef CONEGRAPH_APP_SESSION_H
#define CONEGRAPH_APP_SESSION_H

#include <stdbool.h>
#include <stddef.h>

#include "cg/camera.h"
#include "cg/error.h"
#include "cg/fg.h"
#include "cg/gl.h"
#include "cg/gpu_scene.h"
#include "cg/image.h"
#include "cg/scene.h"

typedef struct app_session_desc {
    const char *tool;               /* names the notices on stderr ("conegraph render"); NULL: "conegraph" */
    const char *scene;              /* a .gltf/.glb file or builtin:NAME[?key=value&...] */
    const char *camera;             /* name, index or auto; NULL: the first (framed from the bounds if none) */
    bool from_given, look_at_given; /* --from, --look-at (cg_view_spec) */
    float from[3], look_at[3];
    float yfov;                     /* --fov, radians; 0: the camera's */
    const cg_sky *sky;              /* --sky; NULL: the graph file's, else none */
    bool no_default_light;          /* --no-default-light */
    const char *const *plugins;     /* loaded after those of $CONEGRAPH_PLUGIN_PATH */
    int plugin_count;
    int width, height;              /* output image size */
    fg_compile_options compile;     /* memory budget, texture limits, pooling */
} app_session_desc;

typedef struct app_graph_desc {
    const char *graph;              /* as given on a command line: app_resolve_graph finds it */
    const char *const *sets;        /* "pass.param=value", applied in order */
    int set_count;
    /* The output read back or shown: the graph's output named *.IMAGE ("hdr", "ldr");
     * a graph without one is bad input. NULL: none. */
    const char *image;
    /* More resources ("pass.output") read back as images: marked as outputs so that they are
     * kept (never pooled away) until the read-back. */
    const char *const *reads;
    int read_count;
    /* An interactive application (the demo): the passes' interactive values where neither the
     * file nor `sets` set them (fg_graph_apply_interactive); the session's `interactive` lists them. */
    bool interactive;
} app_graph_desc;

typedef struct app_session {
    const char *scene_source;       /* as in the desc */
    const char *tool;               /* for notices */
    cg_scene scene;                 /* an app may change its lights (then cg_scene_lights_changed and
                                     * cg_gpu_scene_update_lights); posed by app_session_set_time */
    int camera;                     /* scene camera index, -1: framed from the bounds */
    cg_view_spec view_spec;         /* the camera, moved, aimed, zoomed: what frame.view was made from */
    /* Lighting (settled by the first app_session_load_graph): the sky asked for (--sky, else
     * the first graph's, else none) and who asked. */
    bool sky_given, no_default_light;
    cg_sky sky_requested;
    char sky_origin[4200];
    bool lighting_settled;
    fg_registry *registry;
    fg_graph *graph;                /* the loaded graph; NULL before app_session_load_graph */
    char graph_path[4096];          /* the file it came from */
    char interactive[512];          /* the interactive values applied ("gather.temporal=4"), or "" */
    const char *image_source;       /* the graph's output named *.IMAGE; NULL without one */
    const char *const *reads;       /* the desc's read-backs, checked after each compile */
    int read_count;
    /* Scene, GPU scene, view, size and index of the frames: an app may change the view and
     * the size, then compile again. */
    fg_frame frame;
    fg_compile_options compile;
    cg_context *ctx;                /* NULL before app_session_start_gl */
    cg_gpu_scene gpu;
    bool scene_loaded, uploaded;
} app_session;

/* The scene's lighting: sets `sky` (NULL: none; `origin` says who asked, for messages), then,
 * unless no_default_light, adds the default light (cg/scene.h) when nothing lights the scene
 * (a sun and a sky), or the default sun alone when a Preetham sky has no directional light to
 * follow; each with one notice on stderr, "TOOL: ...". With no_default_light a scene nothing
 * lights gets a warning that it renders black. Fails (CG_ERR_USAGE) on a sky the scene
 * cannot have. */
bool app_light_scene(const char *tool, cg_scene *scene, const cg_sky *sky, const char *origin,
                     bool no_default_light, cg_error *err);

/* Loads the scene, selects the camera, makes the registry and frames the view at the desc's
 * size. On failure what was made is freed again. */
bool app_session_open(app_session *s, const app_session_desc *desc, cg_error *err);
/* Replaces the session's graph (if any) by the file with its overrides and read-backs marked. */
bool app_session_load_graph(app_session *s, const app_graph_desc *desc, cg_error *err);
/* Compiles without GL (the GPU scene left out even when there is one) and checks that the
 * image output and every read-back are textures this scene produces: bad input, found before
 * anything goes to the GPU. */
bool app_session_check(app_session *s, cg_error *err);
/* Makes the GL context and uploads the scene. */
bool app_session_start_gl(app_session *s, const cg_context_desc *context, cg_error *err);
/* Compiles with GL for the current frame (view, size) and prepares; the read-backs checked
 * again. Again after a parameter change, a new view or a new size. */
bool app_session_compile(app_session *s, cg_error *err);

/* Marks `source` as a graph output, so that it is kept and not pooled away before a read-back
 * or a blit; *added: it was not one before (the graph must then be compiled again). */
bool app_session_mark_output(app_session *s, const char *source, bool *added, cg_error *err);

/* Poses the scene at time t seconds (cg_scene_evaluate) and brings the frame up to date: the GPU
 * scene's lights when a light changed (cg_gpu_scene_update_lights; meshes stay where they are,
 * the passes read each instance's world matrix at every draw, except the vertices of skinned
 * meshes a skin posed: cg_gpu_scene_update_meshes), and the view when the session's
 * camera (not a view framed from the bounds) moved, made from view_spec (so moved, aimed and
 * zoomed as asked). *changes (may be NULL) says what changed.
 * Works before start_gl too (the GPU scene is then brought up to date when it is uploaded). */
bool app_session_set_time(app_session *s, double t, cg_scene_changes *changes, cg_error *err);

typedef struct app_run_desc {
    int warmup;                     /* untimed frames first (shader JIT, caches) */
    int frames;                     /* timed frames, at least 1 */
    fg_timing_mode timing;
    /* With `animate`, timed frame k (from 0) is posed at time + k / fps by app_session_set_time
     * before it runs, and its time includes that update; warm-up frames are posed at `time`. */
    bool animate;
    double time, fps;
    /* Called after each timed frame (0-based) with its duration in ms; NULL for none. */
    /* After each timed frame; false (err filled) ends the run as a failed frame does. */
    bool (*on_frame)(void *user, int frame, int frames, double ms, cg_error *err);
    void *user;
} app_run_desc;

typedef struct app_frame_stats {
    int frames, pass_count;
    double *frame_ms;               /* [frames]: execute to glFinish, wall clock, in frame order */
    double *pass_ms;                /* [pass_count][frames]: fg_pass_milliseconds, passes in file order
                                     * (-1: not measured, as for a culled pass) */
    double *pass_sum_ms;            /* [frames]: the sum of the measured passes of each frame */
    double median_frame_ms;
    double median_pass_sum_ms;
} app_frame_stats;

/* Runs warmup + frames frames (frame.index from 0), glFinish after each, then checks for GL
 * errors. *stats is filled (free it with app_frame_stats_free) when this returns true. */
bool app_session_run(app_session *s, const app_run_desc *run, app_frame_stats *stats, cg_error *err);
/* Median over the timed frames of pass `pass` (file order); NAN when never measured. */
double app_frame_stats_pass_median(const app_frame_stats *stats, int pass);
void app_frame_stats_free(app_frame_stats *stats);

/* Fails with CG_ERR_GL when the context has reported any GL error since it was made. */
bool app_session_check_gl(const app_session *s, cg_error *err);

/* Reads a texture resource into a top-to-bottom float image: 2D as is, 3D and array layers
 * stacked top to bottom (layer 0 first); depth formats land in RGB. srgb_encoded: the texels
 * hold sRGB-encoded values (an ldr output), decoded here so that the image is linear. */
bool app_session_read_image(const app_session *s, const char *source, bool srgb_encoded, cg_image *out,
                            cg_error *err);
/* Reads `source` and writes it to `path` (.exr with exr_type samples, or .png), atomically. */
bool app_session_write_image(const app_session *s, const char *source, bool srgb_encoded, const char *path,
                             cg_image_exr_type exr_type, cg_error *err);

/* Destroys the graph, the GPU scene and the context; the scene and registry stay. */
void app_session_stop_gl(app_session *s);
/* Frees everything; safe on a session that failed to open (zeroed by app_session_open). */
void app_session_close(app_session *s);

#endif
