/* apps/common/app_options.h: the command-line options of the apps that run one graph on one
 * scene (render, conegraph-demo, vct-bench), parsed once: the scene, --graph, --size,
 * --camera, --set, --plugin, --frames, --timing, --context, --max-gpu-memory. Each app says
 * which of them it takes and parses its own beside them.
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
    APP_OPT_CAMERA = 1 << 2,            /* --camera NAME|INDEX */
    APP_OPT_SET = 1 << 3,               /* --set PASS.PARAM=VALUE, repeatable */
    APP_OPT_PLUGIN = 1 << 4,            /* --plugin PATH, repeatable */
    APP_OPT_FRAMES = 1 << 5,            /* --frames N, 1..1000000 */
    APP_OPT_TIMING = 1 << 6,            /* --timing sync|queries|none */
    APP_OPT_CONTEXT = 1 << 7,           /* --context egl|osmesa|glfw|auto */
    APP_OPT_MAX_GPU_MEMORY = 1 << 8,    /* --max-gpu-memory SIZE (app_parse_bytes) */
} app_option;

typedef struct app_options {
    const char *scene;                  /* the one argument that is not an option; NULL: none */
    const char *graph, *camera;         /* NULL: not given */
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
/* Walks argv[1..]: every option takes a value; the common ones in `accepted` go into *o (whose
 * defaults the caller set), the others to `own` (may be NULL). Returns 0, or 2 after printing
 * the usage error (unknown option, missing or bad value, a second scene). */
int app_parse_options(const char *tool, int argc, char **argv, unsigned accepted, app_options *o,
                      app_own_option_fn own, void *user);

/* The session and graph descriptions of the options (pointing into *o). */
app_session_desc app_options_session(const app_options *o);
app_graph_desc app_options_graph(const app_options *o);

#endif
