/* apps/demo/demo.h: the demo's state, shared by its main loop (demo.c) and its UI panels
 * (demo_ui.c), and what the panels may ask of the main loop (demo_actions): the same actions the
 * keys take. The panels read the state and change it only through d->actions, so that the main
 * loop calls the UI and the UI never calls the main loop by name.
 *
 * Declares: scripted_key, demo_options, pending_change, demo_actions, demo.
 */
#ifndef CONEGRAPH_DEMO_H
#define CONEGRAPH_DEMO_H

#include <stdbool.h>

#include "app_options.h"
#include "app_session.h"
#include "cg/fg.h"
#include "demo_anim.h"
#include "demo_camera.h"
#include "demo_params.h"
#include "demo_view.h"
#include "ui.h"

#define MAX_LIST 64
#define MAX_SHOWN 9
#define FRAME_HISTORY 64
#define MAX_UI_WINDOWS 16

/* A key press given on the command line (--keys). */
typedef struct scripted_key {
    int key;                    /* GLFW_KEY_* */
    int mods;                   /* GLFW_MOD_SHIFT or 0 */
} scripted_key;

typedef struct demo_options {
    app_options common;         /* scene, graph, size, camera, sets, plugins, timing; frames 0:
                                 * until the window closes */
    double time;                /* --time: seconds into the animation of the first frame */
    double fps;                 /* --fps: a fixed step of 1/fps a frame; 0: the frame's wall time */
    bool no_play;               /* --play off: start paused */
    const char *screenshot;     /* the window as shown (F12) */
    const char *image_screenshot; /* the image without the UI (Shift+F12) */
    bool no_ui;                 /* start with the UI hidden (F1 shows it) */
    const char *view;           /* the resource the viewer starts on; NULL: none */
    scripted_key keys[MAX_LIST];  /* --keys: pressed one per frame from the first */
    int key_count;
} demo_options;

struct demo;

/* What the UI panels may ask of the main loop, the one way they change what it owns; demo.c
 * fills it with the functions its keys use. */
typedef struct demo_actions {
    /* Selects a parameter (pass in file order, its index in the pass's table) for the keys. */
    void (*select)(struct demo *d, int pass, int param);
    /* Sets it from text as --set would, after checking its dependencies; the graph compiles
     * before the next frame, and a value that fails there is undone. The parameter is selected. */
    void (*set_param)(struct demo *d, int pass, int param, const char *text);
    /* One step up or down, as Right and Left do; the parameter is selected. */
    void (*step_param)(struct demo *d, int pass, int param, int direction);
    /* Shows the ldr output (0) or another of the keys' resources in the window, as keys 1..9. */
    void (*show)(struct demo *d, int index);
    /* Shows `source` in the viewer (marked as an output so that it is kept: a compile follows
     * when it was not one); "" shows none. */
    void (*view_resource)(struct demo *d, const char *source);
    /* Space: plays or pauses the animation (says so on stdout). */
    void (*toggle_play)(struct demo *d);
    /* [ and ]: pauses and moves the time by `frames` scrub steps (demo_clock_step). */
    void (*step_time)(struct demo *d, int frames);
    /* The UI's slider: pauses at t; `announce`: say the time on stdout (when the slider is let go). */
    void (*seek_time)(struct demo *d, double t, bool announce);
    /* L starts or stops turning the sun; Shift+L (reset) undoes the turn. */
    void (*sun_key)(struct demo *d, bool reset);
} demo_actions;

/* A parameter changed by a key or a control since the last compile, with its old text for
 * undoing it. */
typedef struct pending_change {
    char pass[128];
    char param[128];
    char previous[256];
} pending_change;

typedef struct demo {
    demo_options o;
    const demo_actions *actions; /* what the UI may ask (demo.c's) */
    /* Scene, registry, graph, context, GPU scene and the frame (view, size) it renders. */
    app_session s;
    fg_graph *graph;            /* s.graph: loaded once, compiled again after every change */
    void *window;               /* GLFWwindow */
    fg_timing_mode timing;
    GLuint read_fbo;

    /* Camera: the session's view (the scene camera or --camera, --from, --look-at, --fov)
     * until the first move or look. */
    demo_camera cam;
    bool flying;
    float speed, base_speed;    /* metres per second */
    bool dragging;
    bool have_cursor;
    double drag_x, drag_y;      /* the last cursor position seen */

    demo_selection sel;
    pending_change changes[MAX_LIST];
    int change_count;
    bool recompile;

    /* Keys 1..9: the ldr output, then the graph's other 2D colour textures. */
    char shown[MAX_SHOWN][256];
    int shown_count;
    int shown_index;

    demo_clock clock;           /* the time the scene is posed at, playing or paused */
    demo_sun sun;               /* L's turn of the directional lights */
    bool screenshot_requested;  /* F12: the window, UI included */
    bool image_screenshot_requested; /* Shift+F12: the image alone */
    int screenshot_serial;
    char last_screenshot[4096]; /* the latest path written, for the UI */
    bool print_report;
    bool report_rebuilt;        /* after a change: the next frame prints what each pass redid */

    double frame_ms[FRAME_HISTORY];
    int frame_ms_count;
    double frame_median_ms;     /* of frame_ms; 0 before the first frame */
    double *all_frame_ms;       /* --frames N: every frame, for the median */
    double last_status;
    char status[2048];          /* frame time, per-pass times, GI memory, size, shown resource */
    char selection[1536];       /* the selected parameter: value, type, range, doc */
    char notice[2200];          /* why the last change was refused or undone; "" when none */

    /* The UI (F1 hides and shows it) and its resource viewer. */
    ui_context *ui;
    bool ui_shown;
    double ui_ms;               /* the last frame's UI: building, viewer and drawing */
    ui_drawn ui_windows[MAX_UI_WINDOWS]; /* where the last frame's UI windows were drawn */
    int ui_window_count;
    int ui_layout_width, ui_layout_height; /* the window size the panels were laid out for (0: none yet) */
    demo_view view;
    char view_source[256];      /* the viewer's resource, "pass.output"; "" for none */
    bool view_fresh;            /* chosen since the last draw: its settings start from the defaults */
    char view_notice[2048];     /* why the last fit failed; "" when it did not */
    demo_view_settings view_settings;
    /* A slider or drag held: its value until let go, when it is set (one compile per drag). */
    int editing_pass, editing_param;
    double editing_value;
    char editing_text[256];     /* a string parameter's field while it is typed into */
} demo;

#endif
