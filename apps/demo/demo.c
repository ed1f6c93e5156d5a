/* conegraph-demo: renders a graph file on a scene in a GLFW window every frame, with a fly
 * camera, the pass parameters on the keyboard and in the window's UI (both driven by the
 * parameter tables), per-pass times, frame time and GI memory in the UI, the title and on
 * stdout, and a viewer for every texture of the graph. docs/demo.md describes it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app_common.h"
#include "app_options.h"
#include "app_session.h"
#include "cg/camera.h"
#include "cg/error.h"
#include "cg/fg.h"
#include "cg/fs.h"
#include "cg/gl.h"
#include "cg/gpu_scene.h"
#include "cg/image.h"
#include "cg/scene.h"
#include "demo.h"
#include "demo_anim.h"
#include "demo_camera.h"
#include "demo_params.h"
#include "demo_ui.h"
#include "demo_view.h"
#include "ui.h"

static void
usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph-demo [SCENE] [options]\n"
        "\n"
        "Opens a window and renders SCENE through a frame graph every frame, showing the\n"
        "graph's ldr output under a UI of per-pass times, frame time, GI memory, every pass\n"
        "parameter as a control and a viewer for any texture of the graph; with a fly camera\n"
        "and the pass parameters on the keyboard too. An animated scene plays, posed every\n"
        "frame as conegraph render poses it at the same time.\n"
        "\n"
        "  SCENE                   a .gltf/.glb file or builtin:NAME[?key=value&...]\n"
        "                          (default builtin:openworld)\n"
        "  --graph FILE            graph file (default: vct.json if it exists, else direct.json,\n"
        "                          from the graph directory); it must mark an output *.ldr\n"
        "  --size WxH              window size in pixels (default 1280x720); the graph renders\n"
        "                          at the window's framebuffer size and recompiles on resize\n"
        APP_CAMERA_USAGE
        "                          (the fly camera starts from the view these give; R goes\n"
        "                          back to it)\n"
        APP_LIGHT_USAGE
        "  --time T                seconds into the scene's animation of the first frame\n"
        "                          (default 0; 0..1e9)\n"
        "  --fps F                 play at a fixed step: each frame moves the animation (and\n"
        "                          L's turn of the sun) on by 1/F s whatever its wall time, so\n"
        "                          that frame k shows what frame k of render --time T --fps F\n"
        "                          does (above 0, at most 1e6). Default: real time; [ and ]\n"
        "                          step by 1/F s (1/30 s without --fps)\n"
        "  --play on|off           start with the animation playing (default) or paused\n"
        "  --set PASS.PARAM=VALUE  override a parameter, validated like the file; repeatable.\n"
        "                          A parameter that neither the file nor --set gives takes its\n"
        "                          interactive value where its table has one (printed at the\n"
        "                          start): the gathers' temporal=4, a quarter of the blocks traced\n"
        "                          a frame; --set gather.temporal=1 traces all, as render does\n"
        "  --plugin PATH           load a pass plugin (.so); repeatable. Directories in\n"
        "                          $CONEGRAPH_PLUGIN_PATH are loaded too\n"
        "  --frames N              run N frames, then exit (default: until the window closes)\n"
        "  --ui on|off             start with the UI shown (default) or hidden; F1 toggles it\n"
        "  --view PASS.OUTPUT      open the resource viewer on this texture of the graph\n"
        "  --screenshot FILE.png   where F12 writes the window as shown, UI included (default\n"
        "                          conegraph-demo-N.png); with --frames, the last frame is\n"
        "                          written there too\n"
        "  --image-screenshot FILE.png  where Shift+F12 writes the image without the UI\n"
        "                          (default conegraph-demo-image-N.png); with --frames, the\n"
        "                          last frame's is written there too. Both are checked before\n"
        "                          the window opens: a missing or unwritable directory exits 2\n"
        "  --timing sync|queries|none  per-pass timing: glFinish + CPU clock, GL_TIMESTAMP\n"
        "                          queries read a frame late, or none (default: sync on a\n"
        "                          software renderer such as llvmpipe, queries on a GPU)\n"
        "  --keys K1,K2,...        press these keys, one per frame from the first, as if typed\n"
        "                          (for recordings and tests): tab, up, down, left, right,\n"
        "                          1..9, r, l, p, space, [, ], f1, f12, esc, any of them after\n"
        "                          shift+; w, a, s, d, q, e (optionally shift+) are held for\n"
        "                          0.25 s of flight\n"
        "\n"
        "Keys: WASD fly, E/Q up/down, Shift x4 speed, left mouse drag to look, scroll for\n"
        "speed, R resets the camera; Tab/Shift+Tab pass, Up/Down parameter, Left/Right\n"
        "decrease/increase it; 1..9 shown resource; Space plays or pauses the animation,\n"
        "[ and ] step it back and forward a frame (Shift: ten), pausing; L starts or stops\n"
        "turning the sun (on top of the animation), Shift+L puts it back; P prints the\n"
        "per-pass report; F1 hides or shows the UI; F12 screenshot, Shift+F12 without the\n"
        "UI; Esc quits. Over the UI, the mouse and the keys a control takes are the UI's.\n"
        "docs/demo.md has the details.\n"
        "\n"
        "The selected parameter, per-pass milliseconds, frame time and GI memory are also in\n"
        "the window title and printed on stdout when they change (times once a second).\n"
        "Needs a display (DISPLAY; xvfb-run for a virtual one). Bad input (scene, graph,\n"
        "parameters, sizes) exits with 2; a failure while running, a GL error included,\n"
        "with 1.\n");
}

#define TOOL "conegraph-demo"

static int
usage_error(const char *fmt, const char *arg)
{
    return app_usage_error(TOOL, fmt, arg);
}

static const struct {
    const char *name;
    int key;
} key_names[] = {
    { "tab", GLFW_KEY_TAB }, { "up", GLFW_KEY_UP }, { "down", GLFW_KEY_DOWN },
    { "left", GLFW_KEY_LEFT }, { "right", GLFW_KEY_RIGHT }, { "1", GLFW_KEY_1 }, { "2", GLFW_KEY_2 },
    { "3", GLFW_KEY_3 }, { "4", GLFW_KEY_4 }, { "5", GLFW_KEY_5 }, { "6", GLFW_KEY_6 },
    { "7", GLFW_KEY_7 }, { "8", GLFW_KEY_8 }, { "9", GLFW_KEY_9 }, { "r", GLFW_KEY_R },
    { "l", GLFW_KEY_L }, { "p", GLFW_KEY_P }, { "f1", GLFW_KEY_F1 }, { "f12", GLFW_KEY_F12 },
    { "esc", GLFW_KEY_ESCAPE }, { "space", GLFW_KEY_SPACE }, { "[", GLFW_KEY_LEFT_BRACKET },
    { "]", GLFW_KEY_RIGHT_BRACKET },
    { "w", GLFW_KEY_W }, { "a", GLFW_KEY_A }, { "s", GLFW_KEY_S }, { "d", GLFW_KEY_D },
    { "q", GLFW_KEY_Q }, { "e", GLFW_KEY_E },
};

/* A scripted movement key is held for this long, whatever the frame's wall time, so that a
 * script moves the camera the same distance on any machine. */
#define SCRIPTED_HOLD_SECONDS 0.25f

static bool
is_movement_key(int key)
{
    return key == GLFW_KEY_W || key == GLFW_KEY_A || key == GLFW_KEY_S || key == GLFW_KEY_D ||
           key == GLFW_KEY_Q || key == GLFW_KEY_E;
}

/* "tab,shift+tab,right" into o->keys; false on an unknown name or too many keys. */
static bool
parse_keys(const char *list, demo_options *o)
{
    const char *p = list;
    while (*p) {
        size_t len = strcspn(p, ",");
        char name[32];
        if (len == 0 || len >= sizeof name || o->key_count == MAX_LIST)
            return false;
        memcpy(name, p, len);
        name[len] = '\0';
        scripted_key k = { 0, 0 };
        const char *base = name;
        if (!strncasecmp(name, "shift+", 6)) {
            k.mods = GLFW_MOD_SHIFT;
            base += 6;
        }
        for (size_t i = 0; i < sizeof key_names / sizeof key_names[0]; i++)
            if (!strcasecmp(base, key_names[i].name))
                k.key = key_names[i].key;
        if (!k.key)
            return false;
        o->keys[o->key_count++] = k;
        p += len;
        if (*p == ',' && *++p == '\0')
            return false;
    }
    return o->key_count > 0;
}

/* --screenshot, --image-screenshot, --ui, --view, --keys, --time, --fps, --play: the demo's
 * own options (--time and --fps as render takes them). */
static int
own_option(void *user, const char *a, const char *v)
{
    demo_options *o = user;
    if (!strcmp(a, "--screenshot") || !strcmp(a, "--image-screenshot")) {
        if (!app_has_extension(v, ".png"))
            return usage_error("--screenshot and --image-screenshot write .png files only, not '%s'", v);
        /* Where it will write, before the window opens and the graph runs (exit 2). */
        cg_error err = { 0 };
        if (!cg_output_path_check(v, ".png", &err))
            return app_fail(TOOL, a, &err);
        if (!strcmp(a, "--screenshot"))
            o->screenshot = v;
        else
            o->image_screenshot = v;
    } else if (!strcmp(a, "--ui")) {
        if (strcmp(v, "on") && strcmp(v, "off"))
            return usage_error("--ui wants on or off, not '%s'", v);
        o->no_ui = !strcmp(v, "off");
    } else if (!strcmp(a, "--view")) {
        o->view = v;
    } else if (!strcmp(a, "--time")) {
        if (!app_parse_double(v, 0, 1e9, false, &o->time))
            return usage_error("--time wants seconds from 0 to 1e9, not '%s'", v);
    } else if (!strcmp(a, "--fps")) {
        if (!app_parse_double(v, 0, 1e6, true, &o->fps))
            return usage_error("--fps wants frames per second above 0 and at most 1e6, not '%s'", v);
    } else if (!strcmp(a, "--play")) {
        if (strcmp(v, "on") && strcmp(v, "off"))
            return usage_error("--play wants on or off, not '%s'", v);
        o->no_play = !strcmp(v, "off");
    } else if (!strcmp(a, "--keys")) {
        if (!parse_keys(v, o))
            return usage_error("--keys wants a comma-separated list of tab, up, down, left, right, "
                               "1..9, r, l, p, space, [, ], f1, f12, esc, w, a, s, d, q, e, each "
                               "optionally after shift+ (at most 64), not '%s'", v);
    } else {
        return -1;
    }
    return 0;
}

static int
parse_args(int argc, char **argv, demo_options *o)
{
    memset(o, 0, sizeof *o);
    o->common.width = 1280;
    o->common.height = 720;
    int code = app_parse_options(TOOL, argc, argv,
                                 APP_OPT_GRAPH | APP_OPT_SIZE | APP_OPT_CAMERA | APP_OPT_SET | APP_OPT_PLUGIN |
                                 APP_OPT_FRAMES | APP_OPT_TIMING, &o->common, own_option, o);
    if (!code && !o->common.scene)
        o->common.scene = "builtin:openworld";
    return code;
}

/* ------------------------------------------------------------ view and graph */

/* The session's view (the scene camera, as posed, or --camera, --from, --look-at, --fov's),
 * or the fly camera's with its projection. */
static void
update_view(demo *d)
{
    cg_view base;
    cg_view_from_spec(&d->s.scene, &d->s.view_spec, d->s.frame.width, d->s.frame.height, &base);
    if (d->flying)
        demo_camera_view(&d->cam, &d->s.scene, &base, &d->s.frame.view);
    else
        d->s.frame.view = base;
}

static bool
is_depth_or_integer(GLenum format)
{
    switch (format) {
    case GL_DEPTH_COMPONENT16: case GL_DEPTH_COMPONENT24: case GL_DEPTH_COMPONENT32:
    case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_DEPTH32F_STENCIL8:
    case GL_STENCIL_INDEX8:
    case GL_R8UI: case GL_R16UI: case GL_R32UI: case GL_RG8UI: case GL_RG16UI: case GL_RG32UI:
    case GL_RGBA8UI: case GL_RGBA16UI: case GL_RGBA32UI: case GL_RGB10_A2UI:
    case GL_R8I: case GL_R16I: case GL_R32I: case GL_RG8I: case GL_RG16I: case GL_RG32I:
    case GL_RGBA8I: case GL_RGBA16I: case GL_RGBA32I:
        return true;
    default:
        return false;
    }
}

/* Keys 1..9: the ldr output first, then every present 2D colour texture in resource order
 * (a blit can show those; depth and integer formats it cannot). Kept by name so that a
 * recompile keeps what is shown when it still exists. */
static void
list_shown(demo *d, const char *ldr)
{
    char current[256];
    snprintf(current, sizeof current, "%s", d->shown_count ? d->shown[d->shown_index] : ldr);
    d->shown_count = 0;
    snprintf(d->shown[d->shown_count++], sizeof d->shown[0], "%s", ldr);
    for (int i = 0; i < fg_graph_resource_count(d->graph) && d->shown_count < MAX_SHOWN; i++) {
        const fg_resource_info *info = fg_graph_resource_at(d->graph, i);
        if (info->absent || info->desc.kind != FG_TEXTURE_2D || is_depth_or_integer(info->desc.format) ||
            !strcmp(info->name, ldr))
            continue;
        snprintf(d->shown[d->shown_count++], sizeof d->shown[0], "%s", info->name);
    }
    d->shown_index = 0;
    for (int i = 0; i < d->shown_count; i++)
        if (!strcmp(d->shown[i], current))
            d->shown_index = i;
}

/* Compiles for the current size and camera, then prepares (GL storage, programs); the
 * session checks that the ldr output is there for this scene. */
static bool
compile_and_prepare(demo *d, cg_error *err)
{
    update_view(d);
    if (!app_session_compile(&d->s, err))
        return false;
    list_shown(d, d->s.image_source);
    return true;
}

/* The title: the selected parameter line, then the latest status line. */
static void
update_title(demo *d)
{
    char title[sizeof d->selection + sizeof d->status + 32];
    snprintf(title, sizeof title, "conegraph-demo | %s | %s", d->selection, d->status);
    glfwSetWindowTitle(d->window, title);
}

static void
print_selection(demo *d)
{
    fg_pass *pass;
    const fg_param_desc *desc;
    char line[1024];
    if (!demo_selected(d->graph, &d->sel, &pass, &desc)) {
        snprintf(d->selection, sizeof d->selection, "the graph has no pass parameters");
    } else {
        demo_param_describe(pass, desc, line, sizeof line);
        const char *culled = fg_pass_cull_reason(pass);
        snprintf(d->selection, sizeof d->selection, "%s%s%s%s", line, culled ? " [pass culled: " : "",
                 culled ? culled : "", culled ? "]" : "");
    }
    printf("param: %s\n", d->selection);
    fflush(stdout);
    update_title(d);
}

/* Compiles again after parameter changes; when that fails, says why, undoes the changes
 * and compiles the graph as it was. False only when even that fails. */
static bool
apply_changes(demo *d, cg_error *err)
{
    d->recompile = false;
    cg_error why = { 0 };
    if (compile_and_prepare(d, &why)) {
        d->change_count = 0;
        d->report_rebuilt = true;
        return true;
    }
    fprintf(stderr, "conegraph-demo: %s; change undone\n", why.message);
    snprintf(d->notice, sizeof d->notice, "%s; change undone", why.message);
    for (int i = d->change_count - 1; i >= 0; i--) {
        const pending_change *c = &d->changes[i];
        cg_error undo = { 0 };
        if (!fg_graph_set_param(d->graph, c->pass, c->param, c->previous, NULL, &undo))
            fprintf(stderr, "conegraph-demo: undoing %s.%s: %s\n", c->pass, c->param, undo.message);
    }
    d->change_count = 0;
    if (!compile_and_prepare(d, err))
        return false;
    print_selection(d);
    return true;
}

/* ------------------------------------------------------------ input */

/* The slot for the next change; NULL when all are taken: what is pending is compiled first,
 * so that every change can still be undone, and the new one is dropped. */
static pending_change *
next_change(demo *d)
{
    if (d->change_count == MAX_LIST) {
        d->recompile = true;
        return NULL;
    }
    return &d->changes[d->change_count];
}

static void refuse(demo *d, const char *why);

/* A change of a parameter that execute reads (FG_STAGE_FRAME) or prepare (FG_STAGE_PREPARE) is
 * applied at once, without compiling the graph: the passes keep what they cached (the voxels when
 * only the gather's march changed). Its dependencies are checked as a compile would; what fails is
 * undone. False: the change needs the graph compiled (FG_STAGE_GRAPH). */
static bool
apply_in_place(demo *d, pending_change *c, const fg_pass *pass, const fg_param_desc *desc)
{
    if (desc->stage == FG_STAGE_GRAPH)
        return false;
    cg_error why = { 0 };
    bool ok = fg_pass_check_params(pass, &why) &&
              (desc->stage != FG_STAGE_PREPARE || fg_graph_prepare_pass(d->graph, fg_pass_name(pass), &why));
    if (!ok) {
        cg_error undo = { 0 };
        if (!fg_graph_set_param(d->graph, fg_pass_name(pass), desc->name, c->previous, NULL, &undo) ||
            (desc->stage == FG_STAGE_PREPARE && !fg_graph_prepare_pass(d->graph, fg_pass_name(pass), &undo)))
            d->recompile = true;    /* the pass could not go back as it was: compile it all */
        refuse(d, why.message);
        return true;
    }
    printf("param: %s.%s applied (%s)\n", fg_pass_name(pass), desc->name,
           desc->stage == FG_STAGE_FRAME ? "read by the next frame; nothing recompiled"
                                         : "the pass prepared again; the graph and the other passes kept");
    d->report_rebuilt = true;
    d->notice[0] = '\0';
    print_selection(d);
    return true;
}

static void
commit_change(demo *d, pending_change *c, const fg_pass *pass, const fg_param_desc *desc)
{
    if (apply_in_place(d, c, pass, desc))
        return;
    snprintf(c->pass, sizeof c->pass, "%s", fg_pass_name(pass));
    snprintf(c->param, sizeof c->param, "%s", desc->name);
    d->change_count++;
    d->recompile = true;
    d->notice[0] = '\0';
    print_selection(d);
}

/* A value the table or a dependency refuses: said on stderr and in the UI, nothing changed. */
static void
refuse(demo *d, const char *why)
{
    fprintf(stderr, "conegraph-demo: %s; not changed\n", why);
    snprintf(d->notice, sizeof d->notice, "%s; not changed", why);
}

/* Left/Right. The step lands on a value the table allows (demo_params.h), so nothing is
 * compiled to find it; a value whose dependencies fail is refused at once. The graph is
 * compiled before the next frame, and a value that still fails there (a resolution past the
 * GL limits) is undone by apply_changes. */
/* The change a step or a control is about to make to the selected parameter: a slot to undo
 * it from, the pass and the parameter; false when there is nothing selected or no slot left. */
static bool
begin_change(demo *d, pending_change **c, fg_pass **pass, const fg_param_desc **desc)
{
    *c = next_change(d);
    return *c && demo_selected(d->graph, &d->sel, pass, desc);
}

static void
adjust(demo *d, int direction)
{
    pending_change *c;
    fg_pass *pass;
    const fg_param_desc *desc;
    if (!begin_change(d, &c, &pass, &desc))
        return;
    cg_error err = { 0 };
    bool changed = false;
    if (!demo_adjust(d->graph, &d->sel, direction, &changed, c->previous, sizeof c->previous, &err)) {
        refuse(d, err.message);
        return;
    }
    if (!changed) {
        printf("param: %s.%s: no step %s from here\n", fg_pass_name(pass), desc->name,
               desc->type == FG_PARAM_STRING ? "(a string)" : direction > 0 ? "up" : "down");
        fflush(stdout);
        return;
    }
    commit_change(d, c, pass, desc);
}

static void
demo_select(demo *d, int pass, int param)
{
    if (d->sel.pass == pass && d->sel.param == param)
        return;
    d->sel.pass = pass;
    d->sel.param = param;
    print_selection(d);
}

static void
demo_step_param(demo *d, int pass, int param, int direction)
{
    d->sel.pass = pass;
    d->sel.param = param;
    adjust(d, direction);
}

/* A control's value: the same checks as a key's step (demo_param_set), the same undo. */
static void
demo_set_param(demo *d, int pass, int param, const char *text)
{
    d->sel.pass = pass;
    d->sel.param = param;
    pending_change *c;
    fg_pass *p;
    const fg_param_desc *desc;
    if (!begin_change(d, &c, &p, &desc))
        return;
    cg_error err = { 0 };
    if (!demo_param_set(d->graph, p, desc, text, c->previous, sizeof c->previous, &err)) {
        refuse(d, err.message);
        return;
    }
    commit_change(d, c, p, desc);
}

/* Marks `source` as a graph output so that it is kept and not pooled away before the blit
 * or the viewer reads it; the graph compiles again when it was not one. */
static bool
keep(demo *d, const char *source)
{
    cg_error err = { 0 };
    bool added = false;
    if (!app_session_mark_output(&d->s, source, &added, &err)) {
        fprintf(stderr, "conegraph-demo: %s\n", err.message);
        return false;
    }
    d->recompile |= added;
    return true;
}

static void
demo_show(demo *d, int index)
{
    if (index >= d->shown_count) {
        printf("show: no resource %d (1..%d: ", index + 1, d->shown_count);
        for (int i = 0; i < d->shown_count; i++)
            printf("%s%s", i ? ", " : "", d->shown[i]);
        printf(")\n");
        fflush(stdout);
        return;
    }
    if (!keep(d, d->shown[index])) {
        d->shown_index = 0;
        return;
    }
    d->shown_index = index;
    printf("show: %d %s%s\n", index + 1, d->shown[index],
           index ? " (raw values, clamped to [0,1] by the blit)" : "");
    fflush(stdout);
}

static void
demo_view_resource(demo *d, const char *source)
{
    if (!strcmp(source, d->view_source))
        return;
    if (*source && !keep(d, source))
        return;
    snprintf(d->view_source, sizeof d->view_source, "%s", source);
    d->view_fresh = true;
    d->view_notice[0] = '\0';
    printf("view: %s\n", *source ? source : "none");
    fflush(stdout);
}

/* "t = 1.25 s (playing)", for stdout and the status line. */
static void
format_time(const demo *d, char *out, size_t size)
{
    snprintf(out, size, "t = %.4g s (%s)", demo_clock_time(&d->clock), d->clock.playing ? "playing" : "paused");
}

static void
say_time(const demo *d)
{
    char when[96];
    format_time(d, when, sizeof when);
    printf("animation: %s\n", when);
    fflush(stdout);
}

/* Keys and controls that need an animation say so on a scene without one. */
static bool
has_animation(const demo *d)
{
    if (d->clock.animated)
        return true;
    printf("animation: scene %s has none\n", d->s.scene.name);
    fflush(stdout);
    return false;
}

static void
demo_toggle_play(demo *d)
{
    if (has_animation(d) && demo_clock_toggle(&d->clock))
        say_time(d);
}

static void
demo_step_time(demo *d, int frames)
{
    if (!has_animation(d))
        return;
    demo_clock_step(&d->clock, frames);
    say_time(d);
}

static void
demo_seek_time(demo *d, double t, bool announce)
{
    if (!d->clock.animated)
        return;
    demo_clock_seek(&d->clock, t);
    if (announce)
        say_time(d);
}

static void
demo_sun_key(demo *d, bool reset)
{
    demo_sun *sun = &d->sun;
    if (!sun->any) {
        printf("sun: scene %s has no directional light to turn\n", d->s.scene.name);
    } else if (reset) {
        demo_sun_reset(sun);
        printf("sun: back where the scene%s has it\n", d->clock.animated ? "'s animation" : "");
    } else {
        sun->moving = !sun->moving;
        printf("sun: %s, turned %.1f degrees about +y%s\n", sun->moving ? "moving" : "still",
               sun->angle * 180.0 / M_PI, d->clock.animated ? " on top of the animation" : "");
    }
    fflush(stdout);
}

/* What the UI panels may ask (demo.h): the keys' own paths. */
static const demo_actions actions = {
    .select = demo_select,
    .set_param = demo_set_param,
    .step_param = demo_step_param,
    .show = demo_show,
    .view_resource = demo_view_resource,
    .toggle_play = demo_toggle_play,
    .step_time = demo_step_time,
    .seek_time = demo_seek_time,
    .sun_key = demo_sun_key,
};

/* A key pressed (repeat: held down, auto-repeated), from the window or from --keys. */
static void
press(demo *d, int key, int mods, bool repeat)
{
    switch (key) {
    case GLFW_KEY_ESCAPE:
        glfwSetWindowShouldClose(d->window, GLFW_TRUE);
        break;
    case GLFW_KEY_TAB:
        demo_select_pass(d->graph, &d->sel, (mods & GLFW_MOD_SHIFT) ? -1 : 1);
        print_selection(d);
        break;
    case GLFW_KEY_UP:
    case GLFW_KEY_DOWN:
        demo_select_param(d->graph, &d->sel, key == GLFW_KEY_DOWN ? 1 : -1);
        print_selection(d);
        break;
    case GLFW_KEY_LEFT:
    case GLFW_KEY_RIGHT:
        adjust(d, key == GLFW_KEY_RIGHT ? 1 : -1);
        break;
    case GLFW_KEY_R:
        if (!repeat) {
            d->flying = false;
            d->speed = d->base_speed;
            const cg_view_spec *v = &d->s.view_spec;
            bool asked = v->from_given || v->look_at_given || v->yfov > 0 || d->o.common.camera;
            printf("camera: reset to %s\n", asked ? "the view of --camera, --from, --look-at, --fov"
                                                  : "the scene's view");
            fflush(stdout);
        }
        break;
    case GLFW_KEY_L:
        if (!repeat)
            demo_sun_key(d, (mods & GLFW_MOD_SHIFT) != 0);
        break;
    case GLFW_KEY_SPACE:
        if (!repeat)
            demo_toggle_play(d);
        break;
    case GLFW_KEY_LEFT_BRACKET:
    case GLFW_KEY_RIGHT_BRACKET:
        /* Held down, it scrubs on with the key's repeat. */
        demo_step_time(d, (key == GLFW_KEY_RIGHT_BRACKET ? 1 : -1) * ((mods & GLFW_MOD_SHIFT) ? 10 : 1));
        break;
    case GLFW_KEY_P:
        if (!repeat)
            d->print_report = true;
        break;
    case GLFW_KEY_F1:
        if (!repeat) {
            d->ui_shown = !d->ui_shown;
            printf("ui: %s\n", d->ui_shown ? "shown" : "hidden");
            fflush(stdout);
        }
        break;
    case GLFW_KEY_F12:
        if (!repeat) {
            if (mods & GLFW_MOD_SHIFT)
                d->image_screenshot_requested = true;
            else
                d->screenshot_requested = true;
        }
        break;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && !repeat)
            demo_show(d, key - GLFW_KEY_1);
        break;
    }
}

/* The UI gets every event while it is shown; the demo's own action follows unless the UI
 * has the keyboard or the mouse. */
static ui_context *
active_ui(const demo *d)
{
    return d->ui_shown ? d->ui : NULL;
}

/* Whether the cursor is over a window the UI drew in the last frame. By position, not by
 * ImGui's WantCaptureMouse: that is updated once a frame, and a frame on llvmpipe can take
 * longer than moving the cursor off a window and clicking. */
static bool
cursor_over_ui(const demo *d)
{
    if (!active_ui(d))
        return false;
    double x, y;
    glfwGetCursorPos(d->window, &x, &y);
    for (int i = 0; i < d->ui_window_count && i < MAX_UI_WINDOWS; i++) {
        const ui_rect *r = &d->ui_windows[i].rect;
        if (x >= r->x && x < r->x + r->w && y >= r->y && y < r->y + r->h)
            return true;
    }
    return false;
}

static void
on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    demo *d = glfwGetWindowUserPointer(window);
    ui_context *ui = active_ui(d);
    if (ui)
        ui_key_event(ui, key, scancode, action, mods);
    /* F1 always reaches the demo, so that the UI can be hidden whatever it holds. */
    if (ui && ui_wants_keyboard(ui) && key != GLFW_KEY_F1)
        return;
    if (action != GLFW_RELEASE)
        press(d, key, mods, action == GLFW_REPEAT);
}

static void
on_char(GLFWwindow *window, unsigned int codepoint)
{
    ui_context *ui = active_ui(glfwGetWindowUserPointer(window));
    if (ui)
        ui_char_event(ui, codepoint);
}

static void
on_focus(GLFWwindow *window, int focused)
{
    ui_context *ui = active_ui(glfwGetWindowUserPointer(window));
    if (ui)
        ui_focus_event(ui, focused);
}

static void
on_mouse_button(GLFWwindow *window, int button, int action, int mods)
{
    demo *d = glfwGetWindowUserPointer(window);
    ui_context *ui = active_ui(d);
    if (ui)
        ui_mouse_button_event(ui, button, action, mods);
    if (button != GLFW_MOUSE_BUTTON_LEFT)
        return;
    /* A press on a UI window is the UI's; a release always ends a look. */
    if (action == GLFW_PRESS && cursor_over_ui(d))
        return;
    d->dragging = action == GLFW_PRESS;
}

static void
start_flying(demo *d)
{
    if (d->flying)
        return;
    demo_camera_from_view(&d->s.frame.view, &d->cam);
    d->flying = true;
}

static void
on_cursor(GLFWwindow *window, double x, double y)
{
    demo *d = glfwGetWindowUserPointer(window);
    /* Deltas between cursor events: the first event after entering has none to go by. */
    double dx = d->have_cursor ? x - d->drag_x : 0, dy = d->have_cursor ? y - d->drag_y : 0;
    d->drag_x = x;
    d->drag_y = y;
    d->have_cursor = true;
    if (!d->dragging || (dx == 0 && dy == 0))
        return;
    start_flying(d);
    /* 0.004 rad per pixel: a 1280-pixel drag turns about 290 degrees. */
    demo_camera_look(&d->cam, (float)(dx * 0.004), (float)(-dy * 0.004));
}

static void
on_cursor_enter(GLFWwindow *window, int entered)
{
    demo *d = glfwGetWindowUserPointer(window);
    if (active_ui(d))
        ui_cursor_enter_event(d->ui, entered);
    /* Positions from before leaving say nothing about where the cursor comes back. */
    d->have_cursor = false;
}

static void
on_scroll(GLFWwindow *window, double xoffset, double yoffset)
{
    demo *d = glfwGetWindowUserPointer(window);
    ui_context *ui = active_ui(d);
    if (ui)
        ui_scroll_event(ui, xoffset, yoffset);
    if (cursor_over_ui(d))
        return;
    float speed = d->speed * powf(1.25f, (float)yoffset);
    /* Within 1/1000 to 1000 times the starting speed: a scroll never makes it 0 or infinite. */
    if (speed >= d->base_speed * 1e-3f && speed <= d->base_speed * 1e3f)
        d->speed = speed;
    printf("camera: speed %g m/s\n", d->speed);
    fflush(stdout);
}

/* A key held down in the window (unless it is typing into a text field of the UI) or the
 * scripted one. */
static bool
held(const demo *d, const scripted_key *script, int key)
{
    const ui_context *ui = active_ui(d);
    bool typing = ui && ui_wants_text(ui);
    return (!typing && glfwGetKey(d->window, key) == GLFW_PRESS) || (script && script->key == key);
}

/* Flies with the keys held down (or the scripted one, held for SCRIPTED_HOLD_SECONDS). */
static void
move_camera(demo *d, float seconds, const scripted_key *script)
{
    float forward = 0, right = 0, up = 0;
    forward += held(d, script, GLFW_KEY_W);
    forward -= held(d, script, GLFW_KEY_S);
    right += held(d, script, GLFW_KEY_D);
    right -= held(d, script, GLFW_KEY_A);
    up += held(d, script, GLFW_KEY_E);
    up -= held(d, script, GLFW_KEY_Q);
    if (forward == 0 && right == 0 && up == 0)
        return;
    if (script)
        seconds = SCRIPTED_HOLD_SECONDS;
    bool fast = held(d, NULL, GLFW_KEY_LEFT_SHIFT) || held(d, NULL, GLFW_KEY_RIGHT_SHIFT) ||
                (script && (script->mods & GLFW_MOD_SHIFT));
    float metres = d->speed * seconds * (fast ? 4.0f : 1.0f);
    start_flying(d);
    demo_camera_move(&d->cam, forward * metres, right * metres, up * metres);
}

/* Poses the scene at the clock's time through the session, as render does, with the sun
 * key's turn on top (demo_anim.h): the light stamp is bumped when the turn changed the lights,
 * so that passes caching on it (the path tracer) see the move, and the GPU scene gets them;
 * the shadow map, the voxels and the cones follow on this frame (nothing is baked). */
static bool
pose_scene(demo *d, cg_error *err)
{
    cg_scene_changes changes;
    demo_sun_unturn(&d->sun, &d->s.scene);
    if (!app_session_set_time(&d->s, demo_clock_time(&d->clock), &changes, err))
        return false;
    if (demo_sun_turn(&d->sun, &d->s.scene, changes.lights)) {
        cg_scene_lights_changed(&d->s.scene);
        if (d->s.uploaded && !cg_gpu_scene_update_lights(&d->s.gpu, err))
            return false;
    }
    return true;
}

/* ------------------------------------------------------------ frame */

static void
blit(demo *d)
{
    const char *source = d->shown[d->shown_index];
    const fg_resource_info *info = fg_graph_find_resource(d->graph, source);
    GLuint texture = fg_graph_texture(d->graph, source);
    /* The last writer may have used image stores (composite does). */
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    if (!info || !texture) {
        glClearNamedFramebufferfv(0, GL_COLOR, 0, (const GLfloat[4]){ 0, 0, 0, 1 });
        return;
    }
    glNamedFramebufferTexture(d->read_fbo, GL_COLOR_ATTACHMENT0, texture, 0);
    glNamedFramebufferReadBuffer(d->read_fbo, GL_COLOR_ATTACHMENT0);
    int sw = info->desc.width, sh = info->desc.height;
    bool same = sw == d->s.frame.width && sh == d->s.frame.height;
    /* Texture rows and the window both run bottom to top in GL: no flip is needed. */
    glBlitNamedFramebuffer(d->read_fbo, 0, 0, 0, sw, sh, 0, 0, d->s.frame.width, d->s.frame.height,
                           GL_COLOR_BUFFER_BIT, same ? GL_NEAREST : GL_LINEAR);
}

/* Reads the window's back buffer (what is shown) into a PNG, written atomically. */
static bool
write_screenshot(demo *d, const char *path, cg_error *err)
{
    int w = d->s.frame.width, h = d->s.frame.height;
    unsigned char *px = malloc((size_t)w * (size_t)h * 4);
    if (!px)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: %dx%d pixels", path, w, h);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    cg_image image = { 0 };
    if (!cg_image_alloc(&image, w, h, err)) {
        free(px);
        return false;
    }
    /* The window holds sRGB-encoded bytes; cg_image is linear and the PNG writer encodes.
     * Window rows go bottom to top, image rows top to bottom. */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const unsigned char *src = px + ((size_t)y * (size_t)w + (size_t)x) * 4;
            float *dst = image.rgba + ((size_t)(h - 1 - y) * (size_t)w + (size_t)x) * 4;
            for (int c = 0; c < 3; c++)
                dst[c] = cg_srgb_decode((float)src[c] / 255.0f);
            dst[3] = 1.0f;
        }
    free(px);
    bool ok = cg_image_write(path, &image, CG_EXR_HALF, err);
    cg_image_free(&image);
    return ok;
}

static double
frame_median_ms(const demo *d)
{
    if (!d->frame_ms_count)
        return 0;
    double sorted[FRAME_HISTORY];
    memcpy(sorted, d->frame_ms, (size_t)d->frame_ms_count * sizeof *sorted);
    return app_median(sorted, d->frame_ms_count);
}

/* stdout: what each pass that keeps work across frames redid in the frame just run
 * (fg_pass_rebuilt), one line, so that a parameter's change shows what it cost. */
static void
print_rebuilt(demo *d)
{
    const int *order;
    int live = fg_graph_order(d->graph, &order);
    printf("rebuilt:");
    int listed = 0;
    for (int k = 0; k < live; k++) {
        const fg_pass *pass = fg_graph_pass_at(d->graph, order[k]);
        const char *what = fg_pass_rebuilt(pass);
        if (what && *what)
            printf("%s %s: %s", listed++ ? " |" : "", fg_pass_name(pass), what);
    }
    printf("%s\n", listed ? "" : " (no pass keeps work across frames)");
    fflush(stdout);
}

/* Title and stdout: the selection, frame time, per-pass times and GI memory. */
static void
report_status(demo *d, bool force)
{
    double now = app_now_ms();
    if (!force && now - d->last_status < 1000.0)
        return;
    d->last_status = now;
    fg_memory_report mem;
    fg_graph_memory_report(d->graph, &mem);
    double frame = d->frame_median_ms;
    char passes[1536] = "";
    size_t len = 0;
    const int *order;
    int live = fg_graph_order(d->graph, &order);
    for (int k = 0; k < live && len < sizeof passes; k++) {
        const fg_pass *pass = fg_graph_pass_at(d->graph, order[k]);
        double ms = fg_pass_milliseconds(pass);
        int n = ms >= 0 ? snprintf(passes + len, sizeof passes - len, "%s%s %.1f", k ? " | " : "",
                                   fg_pass_name(pass), ms)
                        : snprintf(passes + len, sizeof passes - len, "%s%s -", k ? " | " : "",
                                   fg_pass_name(pass));
        if (n < 0)
            break;
        len += (size_t)n;
    }
    if (len >= sizeof passes)
        len = sizeof passes - 1;
    char when[112] = "";
    if (d->clock.animated) {
        memcpy(when, " | ", 4);
        format_time(d, when + 3, sizeof when - 3);
    }
    /* The texture reads of the passes that count them (fg_pass_reads): a cost the machine's load
     * does not change. */
    char reads[480], reads_part[512] = "";
    if (fg_graph_reads_text(d->graph, reads, sizeof reads)[0])
        snprintf(reads_part, sizeof reads_part, " | reads %s", reads);
    snprintf(d->status, sizeof d->status, "frame %.1f ms | %s ms%s | GI %.1f MiB | %dx%d | %s%s",
             frame, passes, reads_part, (double)mem.gi_bytes / (1024.0 * 1024.0), d->s.frame.width,
             d->s.frame.height, d->shown[d->shown_index], when);
    printf("%s\n", d->status);
    fflush(stdout);

    update_title(d);
}

/* Writes the window as it is now (with_ui: after the UI was drawn; else the image alone) to
 * --screenshot or --image-screenshot, or to a numbered file in the current directory. */
static bool
take_screenshot(demo *d, bool with_ui, cg_error *err)
{
    const char *given = with_ui ? d->o.screenshot : d->o.image_screenshot;
    char numbered[64];
    if (!given)
        snprintf(numbered, sizeof numbered, "conegraph-demo-%s%d.png", with_ui ? "" : "image-",
                 d->screenshot_serial++);
    const char *path = given ? given : numbered;
    cg_error why = { 0 };
    if (!write_screenshot(d, path, &why))
        return cg_fail(err, why.status, "%s: %s", path, why.message);
    snprintf(d->last_screenshot, sizeof d->last_screenshot, "%s", path);
    bool ui = with_ui && d->ui_shown;
    printf("screenshot: %s (%s)\n", path, ui ? "the window with the UI" : "the image without the UI");
    /* Where the UI covers the image, for tests and for anyone comparing the two kinds. */
    for (int i = 0; ui && i < d->ui_window_count && i < MAX_UI_WINDOWS; i++) {
        const ui_rect *r = &d->ui_windows[i].rect;
        printf("ui: window '%s' at %.0f,%.0f size %.0fx%.0f\n", d->ui_windows[i].title, r->x, r->y, r->w, r->h);
    }
    fflush(stdout);
    return true;
}

static bool
is_software(const char *renderer)
{
    return strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe") || strstr(renderer, "swrast");
}

/* Runs the window until it closes (or --frames). Returns the exit code. */
static int
run(demo *d)
{
    cg_error err = { 0 };
    int frames_run = 0;
    double last = app_now_ms();
    while (!glfwWindowShouldClose(d->window) && (!d->o.common.frames || frames_run < d->o.common.frames)) {
        glfwPollEvents();
        int w, h;
        glfwGetFramebufferSize(d->window, &w, &h);
        if (w <= 0 || h <= 0) {
            glfwWaitEvents(); /* minimised: nothing to draw */
            last = app_now_ms();
            continue;
        }
        const scripted_key *script = frames_run < d->o.key_count ? &d->o.keys[frames_run] : NULL;
        if (script && !is_movement_key(script->key)) {
            press(d, script->key, script->mods, false);
            script = NULL;
            if (glfwWindowShouldClose(d->window))
                break;
        }
        if (w != d->s.frame.width || h != d->s.frame.height) {
            d->s.frame.width = w;
            d->s.frame.height = h;
            d->recompile = true;
        }
        double now = app_now_ms();
        double seconds = (now - last) * 1e-3;
        last = now;
        /* A long compile or a stall must not throw the camera, the sun or the animation far. */
        float step = (float)(seconds < 0.25 ? seconds : 0.25);
        /* The scene moves on between frames, not before the first (which shows --time); with
         * --fps by exactly 1/F (frame k at T + k / F). */
        if (frames_run > 0) {
            double scene_step = d->o.fps > 0 ? 1.0 / d->o.fps : step;
            demo_clock_tick(&d->clock, scene_step);
            demo_sun_advance(&d->sun, scene_step);
        }
        if (d->recompile) {
            double t0 = app_now_ms();
            if (!apply_changes(d, &err))
                return app_fail(TOOL, NULL, &err);
            printf("graph: compiled and prepared for %dx%d in %.0f ms\n", d->s.frame.width, d->s.frame.height,
                   app_now_ms() - t0);
            fflush(stdout);
            report_status(d, true);
        }
        move_camera(d, step, script);
        if (!pose_scene(d, &err))
            return app_fail(TOOL, NULL, &err);
        update_view(d);

        d->s.frame.index = (uint64_t)frames_run;
        double t0 = app_now_ms();
        if (!fg_graph_execute(d->graph, &d->s.frame, d->timing, &err))
            return app_fail(TOOL, "frame", &err);
        blit(d);
        bool last_frame = d->o.common.frames && frames_run + 1 == d->o.common.frames;
        if (d->image_screenshot_requested || (last_frame && d->o.image_screenshot)) {
            d->image_screenshot_requested = false;
            if (!take_screenshot(d, false, &err))
                return app_fail(TOOL, NULL, &err);
        }
        d->ui_window_count = 0;
        if (d->ui_shown) {
            double u0 = app_now_ms();
            if (!demo_ui_frame(d, &err))
                return app_fail(TOOL, "UI", &err);
            /* As the passes are timed: the UI's GPU work included unless timed by queries. */
            if (d->timing != FG_TIMING_QUERIES)
                glFinish();
            d->ui_ms = app_now_ms() - u0;
        }
        if (d->screenshot_requested || (last_frame && d->o.screenshot)) {
            d->screenshot_requested = false;
            if (!take_screenshot(d, true, &err))
                return app_fail(TOOL, NULL, &err);
        }
        cg_context_swap(d->s.ctx);
        /* With sync or no timing, finish here so that the frame time is the frame's work,
         * not how far the driver queued ahead. */
        if (d->timing != FG_TIMING_QUERIES)
            glFinish();
        double ms = app_now_ms() - t0;
        if (d->frame_ms_count == FRAME_HISTORY)
            memmove(d->frame_ms, d->frame_ms + 1, (FRAME_HISTORY - 1) * sizeof *d->frame_ms);
        else
            d->frame_ms_count++;
        d->frame_ms[d->frame_ms_count - 1] = ms;
        d->frame_median_ms = frame_median_ms(d);
        if (d->all_frame_ms)
            d->all_frame_ms[frames_run] = ms;
        frames_run++;

        int errors = cg_context_gl_error_count(d->s.ctx);
        if (errors > 0) {
            fprintf(stderr, "conegraph-demo: %d GL error(s) in frame %d (logged above)\n", errors, frames_run);
            return 1;
        }
        if (d->report_rebuilt) {
            d->report_rebuilt = false;
            print_rebuilt(d);
        }
        if (d->print_report) {
            d->print_report = false;
            fg_graph_print_report(d->graph, stdout);
            fflush(stdout);
        }
        report_status(d, frames_run == 1);
    }
    report_status(d, true);
    fg_graph_print_report(d->graph, stdout);
    if (d->all_frame_ms && frames_run > 0) {
        printf("demo: %s %dx%d, graph %s, on %s: median frame %.1f ms over %d frame(s)\n", d->s.scene.name,
               d->s.frame.width, d->s.frame.height, d->s.graph_path, cg_context_renderer(d->s.ctx),
               app_median(d->all_frame_ms, frames_run), frames_run);
    }
    fflush(stdout);
    return 0;
}

/* --view: a texture this scene and graph produce (known from the compile without GL). */
static bool
check_view(const demo *d, const char *source, cg_error *err)
{
    const fg_resource_info *info = fg_graph_find_resource(d->graph, source);
    if (info && !info->absent && info->desc.kind != FG_BUFFER)
        return true;
    char textures[2048] = "";
    size_t len = 0;
    for (int i = 0; i < fg_graph_resource_count(d->graph) && len < sizeof textures; i++) {
        const fg_resource_info *r = fg_graph_resource_at(d->graph, i);
        if (!r->absent && r->desc.kind != FG_BUFFER) {
            int n = snprintf(textures + len, sizeof textures - len, "%s%s", len ? ", " : "", r->name);
            len += n > 0 ? (size_t)n : 0;
        }
    }
    return cg_fail(err, CG_ERR_USAGE, "--view %s: %s; the textures of this graph on this scene are: %s", source,
                   !info ? "no such resource" : info->absent ? "absent for this scene" : "a buffer, not a texture",
                   textures);
}

/* Loads and checks everything (bad input exits 2 before a window opens), opens the window,
 * runs, and tears down. */
static int
demo_main(demo *d)
{
    cg_error err = { 0 };
    int code = 1;
    app_session_desc desc = app_options_session(&d->o.common);
    app_graph_desc graph = app_options_graph(&d->o.common);
    graph.image = "ldr";
    graph.interactive = true;
    cg_context_desc context = { .backend = CG_CONTEXT_GLFW, .width = d->o.common.width, .height = d->o.common.height,
                                .title = "conegraph-demo", .debug = true };
    if (!app_session_open(&d->s, &desc, &err) || !app_session_load_graph(&d->s, &graph, &err) ||
        !app_session_check(&d->s, &err)) {
        code = app_fail(TOOL, NULL, &err);
        goto done;
    }
    d->graph = d->s.graph;
    if (d->s.interactive[0])
        printf("demo: %s (interactive value: the graph file and --set leave it unset; docs/demo.md)\n",
               d->s.interactive);
    /* The lights are settled now (a default sun is one of them): the sun key's base. */
    double start, end;
    cg_scene_animation_range(&d->s.scene, &start, &end);
    demo_clock_init(&d->clock, cg_scene_is_animated(&d->s.scene), start, end, d->o.time, d->o.fps, !d->o.no_play);
    if (!demo_sun_init(&d->sun, &d->s.scene, &err) || !pose_scene(d, &err)) {
        code = app_fail(TOOL, NULL, &err);
        goto done;
    }
    if (d->o.view && !check_view(d, d->o.view, &err)) {
        code = app_fail(TOOL, NULL, &err);
        goto done;
    }
    if (d->o.common.frames) {
        d->all_frame_ms = calloc((size_t)d->o.common.frames, sizeof *d->all_frame_ms);
        if (!d->all_frame_ms) {
            fprintf(stderr, "conegraph-demo: out of memory\n");
            goto done;
        }
    }
    if (!app_session_start_gl(&d->s, &context, &err)) {
        code = app_fail(TOOL, NULL, &err);
        goto done;
    }
    d->window = cg_context_window(d->s.ctx);
    glfwSetWindowUserPointer(d->window, d);
    glfwSetKeyCallback(d->window, on_key);
    glfwSetMouseButtonCallback(d->window, on_mouse_button);
    glfwSetCursorPosCallback(d->window, on_cursor);
    glfwSetCursorEnterCallback(d->window, on_cursor_enter);
    glfwSetScrollCallback(d->window, on_scroll);
    glfwSetCharCallback(d->window, on_char);
    glfwSetWindowFocusCallback(d->window, on_focus);
    if (!ui_create(d->window, &d->ui, &err)) {
        code = app_fail(TOOL, NULL, &err);
        goto done;
    }
    d->ui_shown = !d->o.no_ui;
    demo_view_create(&d->view);
    /* Frame times measure the frames, not the display's refresh. */
    glfwSwapInterval(0);
    d->editing_pass = -1;
    d->timing = d->o.common.timing_given ? d->o.common.timing
                                  : is_software(cg_context_renderer(d->s.ctx)) ? FG_TIMING_SYNC : FG_TIMING_QUERIES;
    glCreateFramebuffers(1, &d->read_fbo);
    glfwGetFramebufferSize(d->window, &d->s.frame.width, &d->s.frame.height);
    if (d->o.view)
        demo_view_resource(d, d->o.view);
    if (!compile_and_prepare(d, &err)) {
        code = app_fail(TOOL, NULL, &err);
        goto done;
    }
    d->recompile = false; /* what --view marked is in this compile already */
    float diagonal = 0;
    for (int k = 0; k < 3; k++)
        diagonal += (d->s.scene.bounds_max[k] - d->s.scene.bounds_min[k]) * (d->s.scene.bounds_max[k] - d->s.scene.bounds_min[k]);
    /* A tenth of the scene per second. */
    d->base_speed = d->speed = diagonal > 0 ? sqrtf(diagonal) * 0.1f : 1.0f;

    printf("conegraph-demo: %s, graph %s, %dx%d, %s on %s, timing %s\n", d->s.scene.name, d->s.graph_path,
           d->s.frame.width, d->s.frame.height, cg_context_version(d->s.ctx), cg_context_renderer(d->s.ctx),
           d->timing == FG_TIMING_SYNC ? "sync" : d->timing == FG_TIMING_QUERIES ? "queries" : "none");
    printf("keys: WASD/QE fly, drag look, scroll speed, R reset, Tab/Shift+Tab pass, Up/Down param, "
           "Left/Right value, 1..%d show, Space play/pause, [ ] step (Shift: x10), L sun (Shift: back), "
           "P report, F1 UI, F12 screenshot (Shift: without the UI), Esc quit\n", d->shown_count);
    if (d->clock.animated) {
        printf("animation: keys from %g to %g s, %s; ", d->clock.start, d->clock.end,
               d->o.fps > 0 ? "a fixed step a frame (--fps)" : "in real time");
        say_time(d);
    }
    demo_select_first(d->graph, &d->sel);
    print_selection(d);
    code = run(d);

done:
    free(d->all_frame_ms);
    demo_sun_free(&d->sun);
    /* The window's GL objects go before its context. */
    if (d->view.vao)
        demo_view_destroy(&d->view);
    ui_destroy(d->ui);
    if (d->read_fbo)
        glDeleteFramebuffers(1, &d->read_fbo);
    app_session_close(&d->s);
    return code;
}

int
main(int argc, char **argv)
{
    if (app_wants_help(argc, argv)) {
        usage(stdout);
        return 0;
    }
    demo *d = calloc(1, sizeof *d);
    if (!d) {
        fprintf(stderr, "conegraph-demo: out of memory\n");
        return 1;
    }
    d->actions = &actions;
    int code = parse_args(argc, argv, &d->o);
    if (!code)
        code = demo_main(d);
    free(d);
    return code;
}
