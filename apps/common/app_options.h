/* apps/common/app_options.h: the command-line options of the apps that run one graph on one
 * scene (render, conegraph-demo, vct-bench), parsed once: the scene, --graph, --size,
 * --camera (with --from, --look-at, --fov), --set, --plugin, --frames, --timing, --context,
 * --max-gpu-memory. Each app says which of them it takes and parses its own beside them.
 * The scene's lighting, --sky and --no-default-light, every one of these apps takes: each
 * renders the scene, and a scene nothing lights renders black.
 *
 * Declares: APP_MAX_LIST, app_option, app_options, app_own_option_fn, app_wants_help,
 *           app_parse_options, app_options_session, app_options_graph.
 */
#ifndef CONEGRAPH_APP_OPTIONS_H
#define CONEGRAPH_APP_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>

#include "app_session.h"
#include "cg/fg.h"
#include "cg/gl.h"

#define APP_MAX_LIST 64

/* The common options, as bits of what an app takes. */
typedef enum app_option {
    APP_OPT_GRAPH = 1 << 0,             /* --graph FILE */
    APP_OPT_SIZE = 1 << 1,              /* --size WxH */
    APP_OPT_CAMERA = 1 << 2,            /* --camera NAME|INDEX|auto, --from X,Y,Z, --look-at X,Y,Z,
                                         * --fov DEG */
    APP_OPT_SET = 1 << 3,               /* --set PASS.PARAM=VALUE, repeatable */
    APP_OPT_PLUGIN = 1 << 4,            /* --plugin PATH, repeatable */
    APP_OPT_FRAMES = 1 << 5,            /* --frames N, 1..1000000 */
    APP_OPT_TIMING = 1 << 6,            /* --timing sync|queries|none */
    APP_OPT_CONTEXT = 1 << 7,           /* --context egl|osmesa|glfw|auto */
    APP_OPT_MAX_GPU_MEMORY = 1 << 8,    /* --max-gpu-memory SIZE (app_parse_bytes) */
    APP_OPT_VERBOSITY = 1 << 9,         /* --verbose, --quiet: flags, no value */
} app_option;

typedef struct app_options {
    const char *tool;                   /* as app_parse_options was given it: names the notices */
    const char *scene;                  /* the one argument that is not an option; NULL: none */
    const char *graph, *camera;         /* NULL: not given */
    bool from_given, look_at_given;
    float from[3], look_at[3];          /* --from, --look-at: world, metres */
    float yfov;                         /* --fov in radians; 0: not given */
    bool sky_given;                     /* --sky */
    cg_sky sky;
    bool no_default_light;              /* --no-default-light */
    bool verbose, quiet;                /* --verbose (more on stdout), --quiet (errors only) */
    int width, height;
    const char *sets[APP_MAX_LIST];
    int set_count;
    const char *plugins[APP_MAX_LIST];
    int plugin_count;
    int frames;
    fg_timing_mode timing;
    bool timing_given;
    cg_context_backend backend;
    size_t max_gpu_memory;              /* 0: no budget */
} app_options;

/* An app's own option NAME VALUE: 0 taken, 2 a bad value (the usage error printed),
 * -1 not one of its options. */
typedef int (*app_own_option_fn)(void *user, const char *name, const char *value);

/* Whether --help or -h is among the arguments. */
bool app_wants_help(int argc, char **argv);
/* Walks argv[1..]: every option but the flags --no-default-light, --verbose and --quiet takes a
 * value; the common ones in
 * `accepted` and the lighting ones go into *o (whose defaults the caller set), the others to
 * `own` (may be NULL). Returns 0, or 2 after printing the usage error (unknown option,
 * missing or bad value, a second scene). */
int app_parse_options(const char *tool, int argc, char **argv, unsigned accepted, app_options *o,
                      app_own_option_fn own, void *user);

/* "X,Y,Z": three finite numbers. */
bool app_parse_point(const char *text, float out[3]);

/* The usage lines of --sky and --no-default-light, for an app's --help. */
#define APP_LIGHT_USAGE                                                                            \
    "  --sky none|L|R,G,B|preetham[:T[,SCALE]]  the scene's sky, seen where no surface is and\n"  \
    "                          lighting it: uniform radiance L or R,G,B in W/(m^2 sr), or the\n"  \
    "                          Preetham daylight of turbidity T (1.7..10, default 3) around the\n" \
    "                          first directional light. Overrides a graph file's \"sky\". Every\n" \
    "                          graph renders it: the path tracer, and the cone tracers through\n" \
    "                          what each cone leaves open (docs/reference.md, docs/vct.md)\n"      \
    "  --no-default-light      a scene with no light, no emissive surface and no sky gets a sun\n" \
    "                          and a sky (a notice says so on stderr); this leaves it dark\n"

/* The usage lines of --camera, --from, --look-at and --fov. */
#define APP_CAMERA_USAGE                                                                           \
    "  --camera NAME|INDEX|auto  scene camera (default: the first; framed from the bounds if\n"  \
    "                          none); auto: framed from the bounds even when there are cameras.\n" \
    "                          The image's aspect is --size's: a camera's own aspect ratio is\n"  \
    "                          fitted inside by widening its field of view (a notice says so)\n"  \
    "  --from X,Y,Z            put the camera's eye there (world, metres)\n"                       \
    "  --look-at X,Y,Z         turn the camera to look at that point (world +y up)\n"              \
    "  --fov DEG               the image's vertical field of view in degrees (perspective)\n"

/* The session and graph descriptions of the options (pointing into *o). */
app_session_desc app_options_session(const app_options *o);
app_graph_desc app_options_graph(const app_options *o);

#endif
