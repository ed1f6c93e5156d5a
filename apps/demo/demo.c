/* conegraph-demo: renders a graph file on a scene in a GLFW window every frame, with a fly
 * camera, the pass parameters on the keyboard (driven by the parameter tables), per-pass
 * times and GI memory in the title and on stdout. docs/demo.md describes it. */
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
#include "cg/gl.h"
#include "cg/gpu_scene.h"
#include "cg/image.h"
#include "cg/scene.h"
#include "demo_camera.h"
#include "demo_params.h"

#define MAX_LIST 64
#define MAX_SHOWN 9
#define FRAME_HISTORY 64
#define SUN_DEGREES_PER_SECOND 20.0

/* A key press given on the command line (--keys). */
typedef struct scripted_key {
    int key;                    /* GLFW_KEY_* */
    int mods;                   /* GLFW_MOD_SHIFT or 0 */
} scripted_key;

typedef struct demo_options {
    app_options common;         /* scene, graph, size, sets, plugins, timing; frames 0: until the
                                 * window closes */
    const char *screenshot;
    scripted_key keys[MAX_LIST];  /* --keys: pressed one per frame from the first */
    int key_count;
} demo_options;

/* A parameter changed by a key since the last compile, with its old text for undoing it. */
typedef struct pending_change {
    char pass[128];
    char param[128];
    char previous[256];
} pending_change;

typedef struct demo {
    demo_options o;
    /* Scene, registry, graph, context, GPU scene and the frame (view, size) it renders. */
    app_session s;
    fg_graph *graph;            /* s.graph: loaded once, compiled again after every change */
    GLFWwindow *window;
    fg_timing_mode timing;
    GLuint read_fbo;

    /* Camera: the scene's view until the first move or look. */
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

    bool sun_moving;
    bool screenshot_requested;
    int screenshot_serial;
    bool print_report;

    double frame_ms[FRAME_HISTORY];
    int frame_ms_count;
    double *all_frame_ms;       /* --frames N: every frame, for the median */
    double last_status;
    char status[2048];          /* frame time, per-pass times, GI memory, size, shown resource */
    char selection[1536];       /* the selected parameter: value, type, range, doc */
} demo;

static void
usage(FILE *out)
{
    fprintf(out,
        "usage: conegraph-demo [SCENE] [options]\n"
        "\n"
        "Opens a window and renders SCENE through a frame graph every frame, showing the\n"
        "graph's ldr output, with a fly camera and the pass parameters on the keyboard.\n"
        "\n"
        "  SCENE                   a .gltf/.glb file or builtin:NAME[?key=value&...]\n"
        "                          (default builtin:openworld)\n"
        "  --graph FILE            graph file (default: vct.json if it exists, else direct.json,\n"
        "                          from the graph directory); it must mark an output *.ldr\n"
        "  --size WxH              window size in pixels (default 1280x720); the graph renders\n"
        "                          at the window's framebuffer size and recompiles on resize\n"
        "  --set PASS.PARAM=VALUE  override a parameter, validated like the file; repeatable\n"
        "  --plugin PATH           load a pass plugin (.so); repeatable. Directories in\n"
        "                          $CONEGRAPH_PLUGIN_PATH are loaded too\n"
        "  --frames N              run N frames, then exit (default: until the window closes)\n"
        "  --screenshot FILE.png   where F12 writes (default conegraph-demo-N.png); with\n"
        "                          --frames, the last frame is written there too\n"
        "  --timing sync|queries|none  per-pass timing: glFinish + CPU clock, GL_TIMESTAMP\n"
        "                          queries read a frame late, or none (default: sync on a\n"
        "                          software renderer such as llvmpipe, queries on a GPU)\n"
        "  --keys K1,K2,...        press these keys, one per frame from the first, as if typed\n"
        "                          (for recordings and tests): tab, shift+tab, up, down, left,\n"
        "                          right, 1..9, r, l, p, f12, esc; w, a, s, d, q, e (optionally\n"
        "                          shift+) are held for 0.25 s of flight\n"
        "\n"
        "Keys: WASD fly, E/Q up/down, Shift x4 speed, left mouse drag to look, scroll for\n"
        "speed, R resets the camera; Tab/Shift+Tab pass, Up/Down parameter, Left/Right\n"
        "decrease/increase it; 1..9 shown resource; L moves the sun; P prints the per-pass\n"
        "report; F12 screenshot; Esc quits. docs/demo.md has the details.\n"
        "\n"
        "The selected parameter, per-pass milliseconds, frame time and GI memory are shown in\n"
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
    { "l", GLFW_KEY_L }, { "p", GLFW_KEY_P }, { "f12", GLFW_KEY_F12 }, { "esc", GLFW_KEY_ESCAPE },
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

/* --screenshot, --keys: the demo's own options. */
static int
own_option(void *user, const char *a, const char *v)
{
    demo_options *o = user;
    if (!strcmp(a, "--screenshot")) {
        if (!app_has_extension(v, ".png"))
            return usage_error("--screenshot writes .png files only, not '%s'", v);
        o->screenshot = v;
    } else if (!strcmp(a, "--keys")) {
        if (!parse_keys(v, o))
            return usage_error("--keys wants a comma-separated list of tab, shift+tab, up, down, "
                               "left, right, 1..9, r, l, p, f12, esc, w, a, s, d, q, e "
                               "(at most 64), not '%s'", v);
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
                                 APP_OPT_GRAPH | APP_OPT_SIZE | APP_OPT_SET | APP_OPT_PLUGIN | APP_OPT_FRAMES |
                                 APP_OPT_TIMING, &o->common, own_option, o);
    if (!code && !o->common.scene)
        o->common.scene = "builtin:openworld";
    return code;
}

/* ------------------------------------------------------------ view and graph */

static void
update_view(demo *d)
{
    cg_view base;
    cg_view_from_scene(&d->s.scene, d->s.camera, d->s.frame.width, d->s.frame.height, &base);
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
        return true;
    }
    fprintf(stderr, "conegraph-demo: %s; change undone\n", why.message);
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

/* Left/Right. The step lands on a value the table allows (demo_params.h), so nothing is
 * compiled to find it; a value whose dependencies fail is refused at once. The graph is
 * compiled before the next frame, and a value that still fails there (a resolution past the
 * GL limits) is undone by apply_changes. */
static void
adjust(demo *d, int direction)
{
    if (d->change_count == MAX_LIST) {
        /* Compile what is pending first so that every change can still be undone. */
        d->recompile = true;
        return;
    }
    pending_change *c = &d->changes[d->change_count];
    fg_pass *pass;
    const fg_param_desc *desc;
    if (!demo_selected(d->graph, &d->sel, &pass, &desc))
        return;
    cg_error err = { 0 };
    bool changed = false;
    if (!demo_adjust(d->graph, &d->sel, direction, &changed, c->previous, sizeof c->previous, &err)) {
        fprintf(stderr, "conegraph-demo: %s; not changed\n", err.message);
        return;
    }
    if (!changed) {
        printf("param: %s.%s: no step %s from here\n", fg_pass_name(pass), desc->name,
               desc->type == FG_PARAM_STRING ? "(a string)" : direction > 0 ? "up" : "down");
        fflush(stdout);
        return;
    }
    snprintf(c->pass, sizeof c->pass, "%s", fg_pass_name(pass));
    snprintf(c->param, sizeof c->param, "%s", desc->name);
    d->change_count++;
    d->recompile = true;
    print_selection(d);
}

static void
show(demo *d, int index)
{
    if (index >= d->shown_count) {
        printf("show: no resource %d (1..%d: ", index + 1, d->shown_count);
        for (int i = 0; i < d->shown_count; i++)
            printf("%s%s", i ? ", " : "", d->shown[i]);
        printf(")\n");
        fflush(stdout);
        return;
    }
    d->shown_index = index;
    /* Marked as an output so that it is kept and not pooled away before the blit. */
    cg_error err = { 0 };
    bool added = false;
    if (!app_session_mark_output(&d->s, d->shown[index], &added, &err)) {
        fprintf(stderr, "conegraph-demo: %s\n", err.message);
        d->shown_index = 0;
        return;
    }
    d->recompile |= added;
    printf("show: %d %s%s\n", index + 1, d->shown[index],
           index ? " (raw values, clamped to [0,1] by the blit)" : "");
    fflush(stdout);
}

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
            printf("camera: reset to the scene's view\n");
            fflush(stdout);
        }
        break;
    case GLFW_KEY_L:
        if (!repeat) {
            d->sun_moving = !d->sun_moving;
            printf("sun: %s\n", d->sun_moving ? "moving" : "still");
            fflush(stdout);
        }
        break;
    case GLFW_KEY_P:
        if (!repeat)
            d->print_report = true;
        break;
    case GLFW_KEY_F12:
        if (!repeat)
            d->screenshot_requested = true;
        break;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && !repeat)
            show(d, key - GLFW_KEY_1);
        break;
    }
}

static void
on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode;
    if (action != GLFW_RELEASE)
        press(glfwGetWindowUserPointer(window), key, mods, action == GLFW_REPEAT);
}

static void
on_mouse_button(GLFWwindow *window, int button, int action, int mods)
{
    (void)mods;
    demo *d = glfwGetWindowUserPointer(window);
    if (button != GLFW_MOUSE_BUTTON_LEFT)
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
    (void)entered;
    /* Positions from before leaving say nothing about where the cursor comes back. */
    ((demo *)glfwGetWindowUserPointer(window))->have_cursor = false;
}

static void
on_scroll(GLFWwindow *window, double xoffset, double yoffset)
{
    (void)xoffset;
    demo *d = glfwGetWindowUserPointer(window);
    float speed = d->speed * powf(1.25f, (float)yoffset);
    /* Within 1/1000 to 1000 times the starting speed: a scroll never makes it 0 or infinite. */
    if (speed >= d->base_speed * 1e-3f && speed <= d->base_speed * 1e3f)
        d->speed = speed;
    printf("camera: speed %g m/s\n", d->speed);
    fflush(stdout);
}

static bool
held(const demo *d, const scripted_key *script, int key)
{
    return glfwGetKey(d->window, key) == GLFW_PRESS || (script && script->key == key);
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

/* Turns every directional light about world +y: the sun circles at its elevation, and
 * the shadow map, voxels and cones all follow on the next frame (nothing is baked). */
static bool
move_sun(demo *d, double seconds, cg_error *err)
{
    float angle = (float)(seconds * SUN_DEGREES_PER_SECOND * 3.14159265358979 / 180.0);
    float c = cosf(angle), s = sinf(angle);
    bool any = false;
    for (int i = 0; i < d->s.scene.light_count; i++) {
        cg_light *l = &d->s.scene.lights[i];
        if (l->type != CG_LIGHT_DIRECTIONAL)
            continue;
        float x = l->direction[0], z = l->direction[2];
        l->direction[0] = c * x + s * z;
        l->direction[2] = -s * x + c * z;
        any = true;
    }
    return !any || cg_gpu_scene_update_lights(&d->s.gpu, err);
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
median_ms(const double *values, int count)
{
    double sorted[FRAME_HISTORY];
    memcpy(sorted, values, (size_t)count * sizeof *sorted);
    return app_median(sorted, count);
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
    double frame = d->frame_ms_count ? median_ms(d->frame_ms, d->frame_ms_count) : 0;
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
    snprintf(d->status, sizeof d->status, "frame %.1f ms | %s ms | GI %.1f MiB | %dx%d | %s",
             frame, passes, (double)mem.gi_bytes / (1024.0 * 1024.0), d->s.frame.width,
             d->s.frame.height, d->shown[d->shown_index]);
    printf("%s\n", d->status);
    fflush(stdout);

    update_title(d);
}

static const char *
screenshot_path(demo *d, char *buf, size_t size)
{
    if (d->o.screenshot)
        return d->o.screenshot;
    snprintf(buf, size, "conegraph-demo-%d.png", d->screenshot_serial++);
    return buf;
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
        if (d->recompile) {
            double t0 = app_now_ms();
            if (!apply_changes(d, &err))
                return app_fail(TOOL, NULL, &err);
            printf("graph: compiled and prepared for %dx%d in %.0f ms\n", d->s.frame.width, d->s.frame.height,
                   app_now_ms() - t0);
            fflush(stdout);
            report_status(d, true);
        }
        /* A long compile or a stall must not throw the camera or the sun across the scene. */
        float step = (float)(seconds < 0.25 ? seconds : 0.25);
        move_camera(d, step, script);
        if (d->sun_moving && !move_sun(d, step, &err))
            return app_fail(TOOL, "sun", &err);
        update_view(d);

        d->s.frame.index = (uint64_t)frames_run;
        double t0 = app_now_ms();
        if (!fg_graph_execute(d->graph, &d->s.frame, d->timing, &err))
            return app_fail(TOOL, "frame", &err);
        blit(d);
        bool last_frame = d->o.common.frames && frames_run + 1 == d->o.common.frames;
        if (d->screenshot_requested || (last_frame && d->o.screenshot)) {
            char buf[64];
            const char *path = screenshot_path(d, buf, sizeof buf);
            d->screenshot_requested = false;
            if (!write_screenshot(d, path, &err))
                return app_fail(TOOL, path, &err);
            printf("screenshot: %s\n", path);
            fflush(stdout);
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
        if (d->all_frame_ms)
            d->all_frame_ms[frames_run] = ms;
        frames_run++;

        int errors = cg_context_gl_error_count(d->s.ctx);
        if (errors > 0) {
            fprintf(stderr, "conegraph-demo: %d GL error(s) in frame %d (logged above)\n", errors, frames_run);
            return 1;
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
    cg_context_desc context = { .backend = CG_CONTEXT_GLFW, .width = d->o.common.width, .height = d->o.common.height,
                                .title = "conegraph-demo", .debug = true };
    if (!app_session_open(&d->s, &desc, &err) || !app_session_load_graph(&d->s, &graph, &err) ||
        !app_session_check(&d->s, &err)) {
        code = app_fail(TOOL, NULL, &err);
        goto done;
    }
    d->graph = d->s.graph;
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
    /* Frame times measure the frames, not the display's refresh. */
    glfwSwapInterval(0);
    d->timing = d->o.common.timing_given ? d->o.common.timing
                                  : is_software(cg_context_renderer(d->s.ctx)) ? FG_TIMING_SYNC : FG_TIMING_QUERIES;
    glCreateFramebuffers(1, &d->read_fbo);
    glfwGetFramebufferSize(d->window, &d->s.frame.width, &d->s.frame.height);
    if (!compile_and_prepare(d, &err)) {
        code = app_fail(TOOL, NULL, &err);
        goto done;
    }
    float diagonal = 0;
    for (int k = 0; k < 3; k++)
        diagonal += (d->s.scene.bounds_max[k] - d->s.scene.bounds_min[k]) * (d->s.scene.bounds_max[k] - d->s.scene.bounds_min[k]);
    /* A tenth of the scene per second. */
    d->base_speed = d->speed = diagonal > 0 ? sqrtf(diagonal) * 0.1f : 1.0f;

    printf("conegraph-demo: %s, graph %s, %dx%d, %s on %s, timing %s\n", d->s.scene.name, d->s.graph_path,
           d->s.frame.width, d->s.frame.height, cg_context_version(d->s.ctx), cg_context_renderer(d->s.ctx),
           d->timing == FG_TIMING_SYNC ? "sync" : d->timing == FG_TIMING_QUERIES ? "queries" : "none");
    printf("keys: WASD/QE fly, drag look, scroll speed, R reset, Tab/Shift+Tab pass, Up/Down param, "
           "Left/Right value, 1..%d show, L sun, P report, F12 screenshot, Esc quit\n", d->shown_count);
    demo_select_first(d->graph, &d->sel);
    print_selection(d);
    code = run(d);

done:
    free(d->all_frame_ms);
    /* The window's framebuffer object goes before its context. */
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
    int code = parse_args(argc, argv, &d->o);
    if (!code)
        code = demo_main(d);
    free(d);
    return code;
}
