/* conegraph-demo in a window, as a user runs it with --frames: exit 0 (the demo exits 1
 * on any GL error the context counts), a screenshot of what the window shows that is
 * finite, not black, and the same image `conegraph render` writes for the same scene,
 * graph and size (so the blit is the right way up and nothing is lost on the way); the
 * UI drawn over it where it says its windows are and nowhere else, hidden by --ui off and
 * F1, and its resource viewer on every kind of texture; an animated glTF played, paused
 * and scrubbed showing render's image at the same time; the sun key seen by the path
 * tracer and adding to an animated sun; --camera, --from, --look-at and --fov as render's.
 * Needs an X display: .ci/test runs the suite under xvfb-run; without one the program
 * reports SKIP. $CONEGRAPH_DEMO_EXE and $CONEGRAPH_EXE name the executables; the argument
 * is tests/plugin/demo_test_plugin.so. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "cg/image.h"
#include "test_support.h"

static int
run(const char *exe_var, const char *args, const char *stdout_path)
{
    const char *exe = getenv(exe_var);
    if (!exe)
        fail_msg("%s is not set", exe_var);
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "'%s' %s >'%s' 2>&1", exe, args, stdout_path ? stdout_path : "/dev/null");
    int status = system(cmd);
    if (status == -1 || !WIFEXITED(status))
        fail_msg("could not run: %s", cmd);
    if (WEXITSTATUS(status) && stdout_path) {
        /* Show what the program said, for the log. */
        char show[4200];
        snprintf(show, sizeof show, "cat '%s' >&2", stdout_path);
        if (system(show) == -1)
            fail_msg("could not show %s", stdout_path);
    }
    return WEXITSTATUS(status);
}

/* Mean of RGB; fails on a non-finite or negative pixel or a wrong size. */
static double
check_image(const cg_image *img, int w, int h)
{
    assert_int_equal(img->width, w);
    assert_int_equal(img->height, h);
    double sum = 0;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        for (int c = 0; c < 3; c++) {
            float v = img->rgba[4 * i + c];
            if (!isfinite(v) || v < 0)
                fail_msg("pixel %zu channel %d is %g", i, c, (double)v);
            sum += v;
        }
    return sum / (3.0 * w * h);
}

static char *
read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Largest difference between two images of the same size, in 8-bit sRGB levels. */
static int
max_level_difference(const char *path_a, const char *path_b)
{
    cg_error err = { 0 };
    cg_image a = { 0 }, b = { 0 };
    assert_cg_ok(cg_image_read(path_a, &a, &err), &err);
    assert_cg_ok(cg_image_read(path_b, &b, &err), &err);
    assert_int_equal(a.width, b.width);
    assert_int_equal(a.height, b.height);
    int worst = 0;
    for (size_t i = 0; i < (size_t)a.width * (size_t)a.height * 4; i++) {
        if (i % 4 == 3)
            continue;
        int d = abs((int)lroundf(cg_srgb_encode(a.rgba[i]) * 255.0f) -
                    (int)lroundf(cg_srgb_encode(b.rgba[i]) * 255.0f));
        worst = d > worst ? d : worst;
    }
    cg_image_free(&a);
    cg_image_free(&b);
    return worst;
}

static void
test_direct_matches_render(void **state)
{
    (void)state;
    cg_error err = { 0 };
    const char *shot = cg_test_tmp_path("demo.png"), *ref = cg_test_tmp_path("render.png"), *log = cg_test_tmp_path("demo.txt");
    char args[8192];
    snprintf(args, sizeof args,
             "builtin:cornell --graph direct.json --size 64x64 --frames 3 --ui off --screenshot '%s'", shot);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    snprintf(args, sizeof args, "render builtin:cornell --graph direct.json --size 64x64 -o '%s'", ref);
    assert_int_equal(run("CONEGRAPH_EXE", args, NULL), 0);

    cg_image a = { 0 }, b = { 0 };
    assert_cg_ok(cg_image_read(shot, &a, &err), &err);
    assert_cg_ok(cg_image_read(ref, &b, &err), &err);
    double mean = check_image(&a, 64, 64);
    check_image(&b, 64, 64);
    assert_true(mean > 0.01);
    cg_image_free(&a);
    cg_image_free(&b);
    /* Both are 8-bit sRGB: compare the stored levels. */
    int worst = max_level_difference(shot, ref);
    if (worst > 1)
        fail_msg("the demo's screenshot differs from `conegraph render` by %d levels", worst);

    /* stdout: the selected parameter, per-pass times, the report and the median. */
    const char *out = read_text(log);
    assert_non_null(strstr(out, "param: shadow.light = -1"));
    assert_non_null(strstr(out, "| direct "));
    assert_non_null(strstr(out, "| final "));
    assert_non_null(strstr(out, "median frame"));
}

/* The VCT graph with a --set, at a size that is not square: runs clean, shows light,
 * reports the GI memory of its volume, and steps the cone count over the values the pass
 * refuses. */
static void
test_vct_runs(void **state)
{
    (void)state;
    cg_error err = { 0 };
    const char *shot = cg_test_tmp_path("vct.png"), *log = cg_test_tmp_path("vct.txt");
    char args[8192];
    snprintf(args, sizeof args,
             "builtin:cornell --graph vct.json --set vox.resolution=32 --size 48x32 --frames 3 "
             "--timing sync --ui off --keys shift+tab,shift+tab,left --screenshot '%s'", shot);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    cg_image a = { 0 };
    assert_cg_ok(cg_image_read(shot, &a, &err), &err);
    assert_true(check_image(&a, 48, 32) > 0.01);
    cg_image_free(&a);
    const char *out = read_text(log);
    assert_non_null(strstr(out, "| gather "));
    /* The gather's `temporal` takes its interactive value, unset in vct.json (fg_graph_apply_interactive). */
    assert_non_null(strstr(out, "demo: gather.temporal=4 (interactive value"));
    /* Shift+Tab twice from the first pass: gather (final, then gather). Left from 26 cones
     * steps past 25 .. 17, which the pass refuses, to 16. */
    assert_non_null(strstr(out, "param: gather.cones = 16 "));
    assert_null(strstr(out, "gather.cones = 17"));
    const char *gi = strstr(out, "| GI ");
    assert_non_null(gi);
    /* The geometry and the three 32^3 RGBA16F volumes with mips of voxel_light: about 1.6 MiB. */
    assert_true(atof(gi + 5) > 0.1);
}

/* Parameter stages: a change of a parameter that the gather reads every frame (step) or at its
 * prepare (cones) compiles nothing and keeps the voxels (the demo's rebuilt line after the change);
 * one that changes the graph's slots (specular: an output) compiles it again, which voxelizes
 * again. */
static void
test_param_stages(void **state)
{
    (void)state;
    static const struct {
        const char *keys, *applied;
        bool compiles;
    } cases[] = {
        {"shift+tab,shift+tab,down,down,right", "param: gather.step applied (read by the next frame", false},
        {"shift+tab,shift+tab,left", "param: gather.cones applied (the pass prepared again", false},
        {"shift+tab,shift+tab,down,down,down,down,down,down,right", "param: gather.specular = false", true},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *log = cg_test_tmp_path("stages.txt");
        char args[8192];
        snprintf(args, sizeof args,
                 "builtin:cornell --graph vct.json --set vox.resolution=32 --set gather.temporal=1 --size 48x32 "
                 "--frames %d --timing sync --ui off --keys %s", (int)strlen(cases[i].keys) / 4 + 4, cases[i].keys);
        assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
        const char *out = read_text(log);
        /* --set wins over the interactive value: nothing applied, nothing said. */
        assert_null(strstr(out, "interactive value"));
        if (!strstr(out, cases[i].applied))
            fail_msg("keys %s: no '%s' in:\n%s", cases[i].keys, cases[i].applied, out);
        const char *rebuilt = strstr(out, "rebuilt: ");
        assert_non_null(rebuilt);
        bool compiled = strstr(out, "graph: compiled") != NULL;
        bool kept = strncmp(strstr(rebuilt, "vox: ") ? strstr(rebuilt, "vox: ") + 5 : "", "geometry kept", 13) == 0;
        fprintf(stderr, "# keys %s: graph compiled again %s, voxels %s\n", cases[i].keys, compiled ? "yes" : "no",
                kept ? "kept" : "voxelized again");
        if (compiled != cases[i].compiles || kept == cases[i].compiles)
            fail_msg("keys %s: compiled %d, voxels kept %d:\n%s", cases[i].keys, compiled, kept, out);
    }
}

static double
mean_of(const char *path)
{
    cg_error err = { 0 };
    cg_image img = { 0 };
    assert_cg_ok(cg_image_read(path, &img, &err), &err);
    double mean = check_image(&img, img.width, img.height);
    cg_image_free(&img);
    return mean;
}

/* Keys typed through --keys take the same path as the window's: Shift+Tab from the first
 * pass wraps to the last (final, composite), whose first parameter is exposure; two steps
 * of Right raise it by 1 EV, read by the next frame, and the image brightens. Key 2 shows another resource. */
static void
test_keys(void **state)
{
    (void)state;
    const char *plain = cg_test_tmp_path("plain.png"), *bright = cg_test_tmp_path("bright.png"), *other = cg_test_tmp_path("other.png");
    const char *log = cg_test_tmp_path("keys.txt");
    char args[8192];
    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 48x32 --frames 1 --ui off "
             "--screenshot '%s'", plain);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, NULL), 0);
    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 48x32 --frames 4 --ui off "
             "--keys shift+tab,right,right --screenshot '%s'", bright);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    const char *out = read_text(log);
    assert_non_null(strstr(out, "param: final.exposure = 0.5 (float -20..20, step 0.5; a change redoes: frame)"));
    assert_non_null(strstr(out, "param: final.exposure = 1 (float -20..20, step 0.5; a change redoes: frame)"));
    /* exposure is read by composite's execute: nothing compiles again. */
    assert_non_null(strstr(out, "param: final.exposure applied (read by the next frame"));
    assert_null(strstr(out, "graph: compiled and prepared"));
    double m0 = mean_of(plain), m1 = mean_of(bright);
    if (!(m1 > m0 * 1.3))
        fail_msg("+1 EV: mean %g, before %g", m1, m0);

    /* Scripted flight: held for a fixed 0.25 s each, so the same distance on any machine.
     * Forward twice and right at 4x speed changes the view; R brings back the scene's. */
    const char *flown = cg_test_tmp_path("flown.png"), *back = cg_test_tmp_path("back.png");
    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 48x32 --frames 3 --ui off "
             "--keys shift+w,shift+w,shift+d --screenshot '%s'", flown);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, NULL), 0);
    int moved = max_level_difference(plain, flown);
    if (moved < 40)
        fail_msg("flying forward and right changed the image by %d levels at most", moved);
    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 48x32 --frames 4 --ui off "
             "--keys shift+w,shift+w,shift+d,r --screenshot '%s'", back);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    assert_non_null(strstr(read_text(log), "camera: reset to the scene's view"));
    assert_true(max_level_difference(plain, back) <= 1);

    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 48x32 --frames 2 --ui off "
             "--keys 2 --screenshot '%s'", other);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    assert_non_null(strstr(read_text(log), "show: 2 "));
    assert_true(fabs(mean_of(other) - m0) > 0.01);
}

/* A UI window as the demo reports it with a screenshot, in whole pixels, grown by a margin
 * for the antialiased edges. */
typedef struct drawn_window {
    char title[64];
    int x0, y0, x1, y1;         /* [x0, x1) x [y0, y1) */
} drawn_window;

#define MAX_WINDOWS 16

/* "ui: window 'TITLE' at X,Y size WxH" lines. */
static int
ui_windows(const char *out, drawn_window *w)
{
    int n = 0;
    for (const char *p = strstr(out, "ui: window '"); p && n < MAX_WINDOWS; p = strstr(p + 1, "ui: window '")) {
        const char *title = p + strlen("ui: window '"), *end = strchr(title, '\'');
        assert_non_null(end);
        float x, y, width, height;
        assert_int_equal(sscanf(end, "' at %f,%f size %fx%f", &x, &y, &width, &height), 4);
        snprintf(w[n].title, sizeof w[n].title, "%.*s", (int)(end - title), title);
        w[n].x0 = (int)floorf(x) - 2;
        w[n].y0 = (int)floorf(y) - 2;
        w[n].x1 = (int)ceilf(x + width) + 2;
        w[n].y1 = (int)ceilf(y + height) + 2;
        n++;
    }
    return n;
}

static const drawn_window *
find_window(const drawn_window *w, int n, const char *title)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i].title, title))
            return &w[i];
    fail_msg("no UI window '%s' reported", title);
    return NULL;
}

static bool
inside(const drawn_window *w, int n, int x, int y)
{
    for (int i = 0; i < n; i++)
        if (x >= w[i].x0 && x < w[i].x1 && y >= w[i].y0 && y < w[i].y1)
            return true;
    return false;
}

static int
level_difference(const cg_image *a, const cg_image *b, int x, int y)
{
    int worst = 0;
    for (int c = 0; c < 3; c++) {
        size_t i = ((size_t)y * (size_t)a->width + (size_t)x) * 4 + (size_t)c;
        int d = abs((int)lroundf(cg_srgb_encode(a->rgba[i]) * 255.0f) - (int)lroundf(cg_srgb_encode(b->rgba[i]) * 255.0f));
        worst = d > worst ? d : worst;
    }
    return worst;
}

static void
read_pair(const char *path_a, const char *path_b, cg_image *a, cg_image *b)
{
    cg_error err = { 0 };
    assert_cg_ok(cg_image_read(path_a, a, &err), &err);
    assert_cg_ok(cg_image_read(path_b, b, &err), &err);
    assert_int_equal(a->width, b->width);
    assert_int_equal(a->height, b->height);
}

#define UI_SIZE "800x450"

/* The UI is drawn over the image: the screenshot with it differs from the one without it
 * where the demo says its windows are, and is the same image everywhere else; the image
 * without the UI (Shift+F12's, --image-screenshot) is the image of --ui off, and so is the
 * window after F1. Keys still work with the UI shown. */
static void
test_ui_shown(void **state)
{
    (void)state;
    const char *shown = cg_test_tmp_path("ui.png"), *bare = cg_test_tmp_path("bare.png"), *off = cg_test_tmp_path("off.png"), *f1 = cg_test_tmp_path("f1.png");
    const char *log = cg_test_tmp_path("ui.txt");
    char args[8192];
    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size " UI_SIZE " --frames 3 "
             "--keys shift+tab,right --screenshot '%s' --image-screenshot '%s'", shown, bare);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    const char *out = read_text(log);
    assert_non_null(strstr(out, "param: final.exposure = 0.5 "));
    drawn_window windows[MAX_WINDOWS];
    int n = ui_windows(out, windows);
    find_window(windows, n, "conegraph");
    find_window(windows, n, "parameters");
    find_window(windows, n, "resource viewer");

    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size " UI_SIZE " --frames 3 --ui off "
             "--keys shift+tab,right --screenshot '%s'", off);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    assert_null(strstr(read_text(log), "ui: window"));
    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size " UI_SIZE " --frames 4 "
             "--keys shift+tab,right,f1 --screenshot '%s'", f1);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    out = read_text(log);
    assert_non_null(strstr(out, "ui: hidden"));
    assert_null(strstr(out, "ui: window"));
    assert_true(max_level_difference(bare, off) <= 1);
    assert_true(max_level_difference(f1, off) <= 1);

    cg_image a = { 0 }, b = { 0 };
    read_pair(shown, off, &a, &b);
    long covered = 0, changed = 0, outside_worst = 0;
    for (int y = 0; y < a.height; y++)
        for (int x = 0; x < a.width; x++) {
            int d = level_difference(&a, &b, x, y);
            if (inside(windows, n, x, y)) {
                covered++;
                changed += d > 2;
            } else if (d > outside_worst) {
                outside_worst = d;
            }
        }
    cg_image_free(&a);
    cg_image_free(&b);
    if (outside_worst > 1)
        fail_msg("outside the UI's windows the image differs by %ld levels", outside_worst);
    /* The panels cover a good part of the window, and nearly all of it visibly (their
     * backgrounds are nearly opaque; only black scene pixels under black can agree). */
    if (covered < (long)800 * 450 / 4 || changed < covered * 6 / 10)
        fail_msg("the UI covers %ld pixels of which %ld differ", covered, changed);
}

/* At the README's 640x360 the panels leave the image visible: the frame panel inside the
 * window and only as tall as its contents (so its per-pass bars are in it, not scrolled away),
 * the parameters and the viewer folded to their title bars, and more than half of the window
 * the image alone. At 1280x720 every panel starts open. */
static void
test_ui_small_window(void **state)
{
    (void)state;
    const char *shot = cg_test_tmp_path("small.png"), *log = cg_test_tmp_path("small.txt");
    char args[8192];
    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 640x360 --frames 3 --screenshot '%s'", shot);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    drawn_window w[MAX_WINDOWS];
    int n = ui_windows(read_text(log), w);
    const drawn_window *frame = find_window(w, n, "conegraph");
    /* Inside the window (the margin of ui_windows aside), and shorter than the room it has. */
    assert_true(frame->x0 >= -2 && frame->y0 >= -2 && frame->x1 <= 640 + 2 && frame->y1 <= 360 + 2);
    if (frame->y1 - frame->y0 >= 360 - 16)
        fail_msg("the frame panel takes the whole height (%d pixels): its contents do not fit", frame->y1 - frame->y0);
    if (frame->x1 - frame->x0 > 640 / 2)
        fail_msg("the frame panel is %d pixels wide of 640", frame->x1 - frame->x0);
    const char *folded[] = { "parameters", "resource viewer" };
    for (int i = 0; i < 2; i++) {
        const drawn_window *f = find_window(w, n, folded[i]);
        if (f->y1 - f->y0 > 30)
            fail_msg("'%s' is %d pixels high at 640x360: not folded", folded[i], f->y1 - f->y0);
    }
    long clear = 0;
    for (int y = 0; y < 360; y++)
        for (int x = 0; x < 640; x++)
            clear += !inside(w, n, x, y);
    if (clear < 640L * 360 / 2)
        fail_msg("only %ld of the 640x360 pixels are clear of the UI", clear);

    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 1280x720 --frames 2 --screenshot '%s'", shot);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    n = ui_windows(read_text(log), w);
    for (int i = 0; i < 2; i++) {
        const drawn_window *f = find_window(w, n, folded[i]);
        if (f->y1 - f->y0 < 200)
            fail_msg("'%s' is %d pixels high at 1280x720: folded", folded[i], f->y1 - f->y0);
    }
}

/* The viewer shows each kind of texture (2D float colour, depth, 3D float colour, 3D
 * unsigned integer) without a GL error, in its window: there the screenshot differs from
 * the viewer showing none. */
static void
test_viewer(void **state)
{
    (void)state;
    static const struct {
        const char *graph, *view;
    } cases[] = {
        { "direct.json", NULL },
        { "direct.json", "gbuf.normal" },
        { "direct.json", "shadow.depth" },
        { "vct.json", NULL },
        { "vct.json", "light.radiance" },
        { "vct.json", "vox.accumulation" },
    };
    const char *none = NULL;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char name[64], args[8192], view[128] = "";
        snprintf(name, sizeof name, "view%zu.png", k);
        const char *shot = cg_test_tmp_path(name), *log = cg_test_tmp_path("view.txt");
        if (cases[k].view)
            snprintf(view, sizeof view, "--view %s", cases[k].view);
        snprintf(args, sizeof args, "builtin:cornell --graph %s --set vox.resolution=32 --size 480x360 --frames 2 "
                 "%s --screenshot '%s'", cases[k].graph, view, shot);
        if (!strcmp(cases[k].graph, "direct.json"))
            snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 480x360 --frames 2 %s "
                     "--screenshot '%s'", view, shot);
        assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
        const char *out = read_text(log);
        if (!cases[k].view) {
            none = shot;
            continue;
        }
        char said[160];
        snprintf(said, sizeof said, "view: %s\n", cases[k].view);
        assert_non_null(strstr(out, said));
        /* Where the viewer is with --view (in a small window it starts folded without it). */
        drawn_window viewing[MAX_WINDOWS];
        const drawn_window *w = find_window(viewing, ui_windows(out, viewing), "resource viewer");
        cg_image a = { 0 }, b = { 0 };
        read_pair(shot, none, &a, &b);
        long area = 0, changed = 0;
        for (int y = w->y0 > 0 ? w->y0 : 0; y < w->y1 && y < a.height; y++)
            for (int x = w->x0 > 0 ? w->x0 : 0; x < w->x1 && x < a.width; x++) {
                area++;
                changed += level_difference(&a, &b, x, y) > 2;
            }
        cg_image_free(&a);
        cg_image_free(&b);
        if (changed < area / 20)
            fail_msg("--view %s: %ld of the viewer's %ld pixels changed", cases[k].view, changed, area);
    }
}

static const char *plugin_path;

static const char *
write_fill_graph(const char *name, int error_frame)
{
    char json[512];
    snprintf(json, sizeof json,
             "{ \"version\": 1, \"passes\": { \"fill\": { \"type\": \"demo_test_fill\", "
             "\"params\": { \"error_frame\": %d } } }, \"outputs\": [ \"fill.ldr\" ] }", error_frame);
    return cg_test_write_file(name, json, 0);
}

/* A pass plugin fills the ldr output with known 8-bit levels: the window shows exactly those
 * (the blit copies bytes: no sRGB conversion, no filtering), and a GL error the pass provokes
 * on frame 2 stops the demo there with exit 1. */
static void
test_plugin_levels_and_gl_error(void **state)
{
    (void)state;
    cg_error err = { 0 };
    const char *shot = cg_test_tmp_path("fill.png"), *log = cg_test_tmp_path("fill.txt");
    char args[8192];
    snprintf(args, sizeof args, "builtin:cornell --plugin '%s' --graph '%s' --size 40x24 --frames 3 --ui off "
             "--screenshot '%s'", plugin_path, write_fill_graph("fill.json", -1), shot);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    cg_image img = { 0 };
    assert_cg_ok(cg_image_read(shot, &img, &err), &err);
    check_image(&img, 40, 24);
    const int want[3] = { 200, 100, 50 };
    for (size_t i = 0; i < 40 * 24; i++)
        for (int c = 0; c < 3; c++) {
            int level = (int)lroundf(cg_srgb_encode(img.rgba[4 * i + c]) * 255.0f);
            if (abs(level - want[c]) > 1)
                fail_msg("pixel %zu channel %d: level %d, the pass stored %d", i, c, level, want[c]);
        }
    cg_image_free(&img);

    const char *broken = cg_test_tmp_path("broken.png");
    snprintf(args, sizeof args, "builtin:cornell --plugin '%s' --graph '%s' --size 40x24 --frames 5 "
             "--screenshot '%s'", plugin_path, write_fill_graph("error.json", 2), broken);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 1);
    assert_non_null(strstr(read_text(log), "GL error(s) in frame 3"));
    FILE *f = fopen(broken, "rb");
    if (f)
        fclose(f);
    assert_null(f); /* stopped before the last frame's screenshot */
}

/* `conegraph render SCENE --graph GRAPH --size SIZE EXTRA -o OUT`, which must succeed. */
static void
render_png(const char *scene, const char *graph, const char *size, const char *extra, const char *out)
{
    char args[8192];
    snprintf(args, sizeof args, "render '%s' --graph %s --size %s %s -o '%s'", scene, graph, size, extra, out);
    assert_int_equal(run("CONEGRAPH_EXE", args, NULL), 0);
}

/* The demo's image (Shift+F12's, without the UI) after `extra`, which must succeed; its
 * stdout in the returned text. */
static const char *
demo_png(const char *scene, const char *graph, const char *size, const char *extra, const char *out)
{
    const char *log = cg_test_tmp_path("demo-run.txt");
    char args[8192];
    snprintf(args, sizeof args, "'%s' --graph %s --size %s %s --image-screenshot '%s'", scene, graph, size, extra, out);
    assert_int_equal(run("CONEGRAPH_DEMO_EXE", args, log), 0);
    return read_text(log);
}

static void
expect_same(const char *what, const char *demo, const char *render)
{
    int worst = max_level_difference(demo, render);
    if (worst > 1)
        fail_msg("%s: the demo's image differs from render's by %d levels", what, worst);
}

static void
expect_different(const char *what, const char *a, const char *b)
{
    int worst = max_level_difference(a, b);
    if (worst < 20)
        fail_msg("%s: the images differ by %d levels at most", what, worst);
}

#define ANIM_SIZE "64x36"

/* An animated glTF (builtin:openworld's every moving object, exported) plays at a fixed step:
 * frame k at T + k / F shows render's image at that time and another than the first frame's;
 * paused it stays at the time it was paused at; [ and ] (Shift: ten frames) pause and scrub
 * to a time whose image is render's; with the UI shown (its time slider drawn) too. */
static void
test_animation(void **state)
{
    (void)state;
    const char *scene = cg_test_tmp_path("moving.glb");
    char args[8192];
    snprintf(args, sizeof args, "export 'builtin:openworld?motion=all&period=4&triangles=20000' '%s'", scene);
    assert_int_equal(run("CONEGRAPH_EXE", args, NULL), 0);
    const char *at0 = cg_test_tmp_path("anim-r0.png"), *at025 = cg_test_tmp_path("anim-r025.png"), *at1 = cg_test_tmp_path("anim-r1.png");
    const char *at325 = cg_test_tmp_path("anim-r325.png");
    render_png(scene, "direct.json", ANIM_SIZE, "--time 0", at0);
    render_png(scene, "direct.json", ANIM_SIZE, "--time 0.25", at025);
    render_png(scene, "direct.json", ANIM_SIZE, "--time 1", at1);
    render_png(scene, "direct.json", ANIM_SIZE, "--time 3.25", at325);
    expect_different("render at 0 and 1 s", at0, at1);

    /* Five frames at 4 per second: the last at 1 s. */
    const char *played = cg_test_tmp_path("anim-played.png");
    const char *out = demo_png(scene, "direct.json", ANIM_SIZE, "--fps 4 --frames 5 --ui off", played);
    assert_non_null(strstr(out, "animation: keys from 0 to 4 s"));
    assert_non_null(strstr(out, "t = 1 s (playing)"));
    expect_same("played to 1 s", played, at1);
    /* --play off: the first frame's time throughout. */
    const char *still = cg_test_tmp_path("anim-still.png");
    demo_png(scene, "direct.json", ANIM_SIZE, "--fps 4 --frames 3 --ui off --play off", still);
    expect_same("not played", still, at0);
    /* Space on the third frame: frames 2 to 4 stay at the second frame's 0.25 s. */
    const char *paused = cg_test_tmp_path("anim-paused.png");
    out = demo_png(scene, "direct.json", ANIM_SIZE, "--fps 4 --frames 5 --ui off --keys tab,tab,space", paused);
    assert_non_null(strstr(out, "animation: t = 0.25 s (paused)"));
    expect_same("paused at 0.25 s", paused, at025);
    /* From 0.5 s: 0.75, 1, 0.75, then ten frames on to 3.25 s; paused there, with the UI. */
    const char *scrubbed = cg_test_tmp_path("anim-scrubbed.png");
    out = demo_png(scene, "direct.json", ANIM_SIZE, "--time 0.5 --fps 4 --frames 6 --keys '],],[,shift+]'",
                   scrubbed);
    assert_non_null(strstr(out, "animation: t = 0.75 s (paused)"));
    assert_non_null(strstr(out, "animation: t = 3.25 s (paused)"));
    expect_same("scrubbed to 3.25 s", scrubbed, at325);
    /* The same in real time: a frame moves on by its wall time, so only that it moved. */
    const char *real = cg_test_tmp_path("anim-real.png");
    demo_png(scene, "direct.json", ANIM_SIZE, "--time 0.5 --frames 2 --ui off --keys tab,]", real);
    const char *at05_plus = cg_test_tmp_path("anim-r0533.png");
    render_png(scene, "direct.json", ANIM_SIZE, "--time 0.5 --fps 30 --frames 2", at05_plus);
    expect_same("a step of 1/30 s without --fps", real, at05_plus);
}

/* The sun key's turn reaches the path tracer (which caches on the scene's light stamp):
 * builtin:openworld's motion=sun turns the sun about +y once a period, with a period of 18 s
 * at 20 degrees a second, L's rate; so 1 s of L (two frames at --fps 2) on the still scene is
 * render's image of the animated one at 1 s, and on the animated scene playing, L adds to the
 * animation's turn (2 s). Shift+L gives the animation back its own sun. The raster graph too. */
static void
test_sun_key(void **state)
{
    (void)state;
    const char *still = "builtin:openworld", *moving = "builtin:openworld?motion=sun&period=18";
    const char *pt = "reference.json --set trace.spp=4 --set trace.progress=false";
    const char *r0 = cg_test_tmp_path("sun-r0.png"), *r1 = cg_test_tmp_path("sun-r1.png"), *r15 = cg_test_tmp_path("sun-r15.png"), *r2 = cg_test_tmp_path("sun-r2.png");
    render_png(still, pt, "48x27", "", r0);
    render_png(moving, pt, "48x27", "--time 1", r1);
    render_png(moving, pt, "48x27", "--time 1.5", r15);
    render_png(moving, pt, "48x27", "--time 2", r2);
    expect_different("the path tracer's sun at 0 and 20 degrees", r0, r1);

    const char *turned = cg_test_tmp_path("sun-turned.png");
    const char *out = demo_png(still, pt, "48x27", "--fps 2 --frames 3 --ui off --keys l", turned);
    assert_non_null(strstr(out, "sun: moving"));
    expect_same("the path tracer after 1 s of L", turned, r1);
    const char *both = cg_test_tmp_path("sun-both.png");
    demo_png(moving, pt, "48x27", "--fps 2 --frames 3 --ui off --keys l", both);
    expect_same("1 s of L on 1 s of the animated sun", both, r2);
    /* L on frame 0, Shift+L on frame 2 (turned 10 degrees by then): the animation's 1.5 s. */
    const char *back = cg_test_tmp_path("sun-back.png");
    out = demo_png(moving, pt, "48x27", "--fps 2 --frames 4 --ui off --keys l,tab,shift+l", back);
    assert_non_null(strstr(out, "sun: back where the scene's animation has it"));
    expect_same("L, then Shift+L", back, r15);

    const char *direct = cg_test_tmp_path("sun-direct.png"), *direct_ref = cg_test_tmp_path("sun-direct-r1.png");
    render_png(moving, "direct.json", "48x27", "--time 1", direct_ref);
    demo_png(still, "direct.json", "48x27", "--fps 2 --frames 3 --ui off --keys l", direct);
    expect_same("the raster graph after 1 s of L", direct, direct_ref);
}

/* A glTF of a grey floor seen by a camera that moves 1.5 m along +x in 2 s (translation
 * keys at 0 and 2 s), tilted 25 degrees down; no light (the default light is added). */
static const char *
write_moving_camera(void)
{
    static const float positions[4][3] = { { -1, 0, 1 }, { 1, 0, 1 }, { 1, 0, -1 }, { -1, 0, -1 } };
    static const float normals[4][3] = { { 0, 1, 0 }, { 0, 1, 0 }, { 0, 1, 0 }, { 0, 1, 0 } };
    static const uint16_t indices[6] = { 0, 1, 2, 0, 2, 3 };
    static const float times[2] = { 0, 2 };
    static const float path[2][3] = { { 0, 1.5f, 3 }, { 1.5f, 1.5f, 3 } };
    unsigned char bin[140] = { 0 };
    memcpy(bin, positions, 48);
    memcpy(bin + 48, normals, 48);
    memcpy(bin + 96, indices, 12);
    memcpy(bin + 108, times, 8);
    memcpy(bin + 116, path, 24);
    cg_test_write_file("camera_path.bin", bin, sizeof bin);
    const char *json =
        "{ \"asset\": { \"version\": \"2.0\" }, \"scene\": 0, \"scenes\": [ { \"nodes\": [ 0, 1 ] } ],\n"
        "  \"nodes\": [ { \"mesh\": 0, \"name\": \"floor\" },\n"
        "             { \"camera\": 0, \"name\": \"eye\", \"translation\": [ 0, 1.5, 3 ],\n"
        "               \"rotation\": [ -0.21644, 0, 0, 0.97630 ] } ],\n"
        "  \"cameras\": [ { \"type\": \"perspective\", \"perspective\": { \"yfov\": 0.8, \"znear\": 0.1 } } ],\n"
        "  \"meshes\": [ { \"primitives\": [ { \"attributes\": { \"POSITION\": 0, \"NORMAL\": 1 }, \"indices\": 2,\n"
        "                                    \"material\": 0 } ] } ],\n"
        "  \"materials\": [ { \"pbrMetallicRoughness\": { \"baseColorFactor\": [ 0.6, 0.6, 0.6, 1 ], "
        "\"metallicFactor\": 0 } } ],\n"
        "  \"animations\": [ { \"channels\": [ { \"sampler\": 0, \"target\": { \"node\": 1, \"path\": \"translation\" } } ],\n"
        "                    \"samplers\": [ { \"input\": 3, \"output\": 4 } ] } ],\n"
        "  \"buffers\": [ { \"uri\": \"camera_path.bin\", \"byteLength\": 140 } ],\n"
        "  \"bufferViews\": [ { \"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48 },\n"
        "                   { \"buffer\": 0, \"byteOffset\": 48, \"byteLength\": 48 },\n"
        "                   { \"buffer\": 0, \"byteOffset\": 96, \"byteLength\": 12 },\n"
        "                   { \"buffer\": 0, \"byteOffset\": 108, \"byteLength\": 8 },\n"
        "                   { \"buffer\": 0, \"byteOffset\": 116, \"byteLength\": 24 } ],\n"
        "  \"accessors\": [\n"
        "    { \"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"min\": [ -1, 0, -1 ], "
        "\"max\": [ 1, 0, 1 ] },\n"
        "    { \"bufferView\": 1, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\" },\n"
        "    { \"bufferView\": 2, \"componentType\": 5123, \"count\": 6, \"type\": \"SCALAR\" },\n"
        "    { \"bufferView\": 3, \"componentType\": 5126, \"count\": 2, \"type\": \"SCALAR\", \"min\": [ 0 ], "
        "\"max\": [ 2 ] },\n"
        "    { \"bufferView\": 4, \"componentType\": 5126, \"count\": 2, \"type\": \"VEC3\" } ] }\n";
    return cg_test_write_file("camera_path.gltf", json, 0);
}

/* --camera, --from, --look-at and --fov give the demo render's view; the fly camera starts
 * from it and R goes back to it. On an animated camera, --fov holds at every time. */
static void
test_camera_options(void **state)
{
    (void)state;
    const char *view = "--from 1,2.5,4 --look-at 0,0.5,0 --fov 60";
    const char *ref = cg_test_tmp_path("cam-r.png"), *plain = cg_test_tmp_path("cam-plain.png"), *flown = cg_test_tmp_path("cam-flown.png");
    const char *back = cg_test_tmp_path("cam-back.png");
    render_png("builtin:cornell", "direct.json", "48x32", view, ref);
    render_png("builtin:cornell", "direct.json", "48x32", "", plain);
    expect_different("--from, --look-at, --fov against the scene's camera", ref, plain);
    char extra[512];
    snprintf(extra, sizeof extra, "%s --frames 2 --ui off --keys shift+w", view);
    demo_png("builtin:cornell", "direct.json", "48x32", extra, flown);
    expect_different("flown from the view asked for", flown, ref);
    snprintf(extra, sizeof extra, "%s --frames 3 --ui off --keys shift+w,r", view);
    const char *out = demo_png("builtin:cornell", "direct.json", "48x32", extra, back);
    assert_non_null(strstr(out, "camera: reset to the view of --camera, --from, --look-at, --fov"));
    expect_same("--from, --look-at, --fov, flown and back", back, ref);

    const char *framed = cg_test_tmp_path("cam-auto.png"), *framed_ref = cg_test_tmp_path("cam-auto-r.png");
    render_png("builtin:cornell", "direct.json", "48x32", "--camera auto", framed_ref);
    demo_png("builtin:cornell", "direct.json", "48x32", "--camera auto --frames 1 --ui off", framed);
    expect_same("--camera auto", framed, framed_ref);

    const char *scene = write_moving_camera();
    const char *narrow0 = cg_test_tmp_path("cam-move-r0.png"), *narrow1 = cg_test_tmp_path("cam-move-r1.png"), *wide1 = cg_test_tmp_path("cam-move-w1.png");
    const char *shown = cg_test_tmp_path("cam-move.png");
    render_png(scene, "direct.json", "48x32", "--fov 30 --time 0", narrow0);
    render_png(scene, "direct.json", "48x32", "--fov 30 --time 1", narrow1);
    render_png(scene, "direct.json", "48x32", "--time 1", wide1);
    expect_different("the camera at 0 and 1 s", narrow0, narrow1);
    expect_different("--fov 30 against the camera's own", narrow1, wide1);
    demo_png(scene, "direct.json", "48x32", "--fov 30 --fps 2 --frames 3 --ui off", shown);
    expect_same("--fov 30 on the moving camera at 1 s", shown, narrow1);
}

int
main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DEMO_TEST_PLUGIN.so\n", argv[0]);
        return 2;
    }
    plugin_path = argv[1];
    const char *display = getenv("DISPLAY");
    if (!display || !*display)
        return cg_test_skip_program("no DISPLAY for the demo window (.ci/test runs it under xvfb-run)");
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_direct_matches_render),
        cmocka_unit_test(test_vct_runs),
        cmocka_unit_test(test_param_stages),
        cmocka_unit_test(test_keys),
        cmocka_unit_test(test_plugin_levels_and_gl_error),
        cmocka_unit_test(test_ui_shown),
        cmocka_unit_test(test_ui_small_window),
        cmocka_unit_test(test_viewer),
        cmocka_unit_test(test_animation),
        cmocka_unit_test(test_sun_key),
        cmocka_unit_test(test_camera_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
