/* `conegraph render` as a user runs it: exit codes (0 done, 2 bad input before anything is
 * written), the image, dumps and the JSON report on disk. Runs the built binary
 * ($CONEGRAPH_EXE) on builtin:cornell at 32x32. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cg/image.h"
#include "cg/metrics.h"
#include "test_support.h"

/* `conegraph render ARGS`, its output thrown away; returns the exit code. */
static int
run(const char *args)
{
    char words[8400];
    snprintf(words, sizeof words, "render %s", args);
    return cg_test_run_program("CONEGRAPH_EXE", words, false, NULL, 0);
}

static double
now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static bool
exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static void
test_help_and_usage(void **state)
{
    (void)state;
    assert_int_equal(run("--help"), 0);
    assert_int_equal(run("builtin:cornell"), 2);                        /* no -o */
    assert_int_equal(run("builtin:cornell -o x.jpg"), 2);               /* not .exr or .png */
    assert_int_equal(run("builtin:cornell -o x.png --size 64"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --frames 0"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --context vulkan"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --bogus"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --dump gbuf.normal"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --fps 0"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --fps -30"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --fps 30fps"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --fps inf"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --time -1"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --time nan"), 2);
    assert_int_equal(run("builtin:cornell -o x.png --time"), 2);
}

/* Every kind of bad input exits 2 and writes nothing. */
static void
test_bad_input_writes_nothing(void **state)
{
    (void)state;
    const char *out = cg_test_tmp_path("bad.png");
    char args[8192];
    const char *cases[] = {
        "builtin:nosuchscene",
        "builtin:cornell --set final.tonemap=filmic",
        "builtin:cornell --set final.exposure=99",
        "builtin:cornell --set nosuchpass.x=1",
        "builtin:cornell --set shadow.resolution=1.5",
        "builtin:cornell --graph no_such_graph.json",
        "builtin:cornell --camera nosuchcamera",
        "builtin:cornell --max-gpu-memory 1K",
        "builtin:cornell --dump gbuf.nosuchoutput=x.exr",
        "builtin:cornell --plugin /nonexistent/plugin.so",
        "builtin:cornell --graph direct.json --dump shadow.matrix=x.exr",     /* a buffer */
        "builtin:furnace --graph direct.json --dump shadow.depth=x.exr",      /* no light to shadow */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(args, sizeof args, "%s --size 32x32 -o '%s'", cases[i], out);
        int code = run(args);
        if (code != 2)
            fail_msg("'%s' exited with %d, expected 2", cases[i], code);
        assert_false(exists(out));
    }
}

/* A parameter value the table refuses is reported where it was given: a --set value quotes
 * the assignment (no graph-file line), names the pass once and says what was expected. */
static void
test_refused_parameter_points_at_its_source(void **state)
{
    (void)state;
    const char *out_png = cg_test_tmp_path("refused.png");
    static char out[1 << 14];
    char args[8192];
    snprintf(args, sizeof args, "render builtin:cornell --size 32x32 --set gather.cones=7 -o '%s'", out_png);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 2);
    assert_false(exists(out_png));
    const char *message = strstr(out, "--set gather.cones=7: expected one of 1, 6, 9, 16");
    if (!message)
        fail_msg("unexpected error text: %s", out);
    int passes_named = 0;
    for (const char *at = strstr(out, "gather"); at; at = strstr(at + 1, "gather"))
        passes_named++;
    assert_int_equal(passes_named, 1);
    assert_null(strstr(out, ".json:"));

    /* A file value points at the file, its line and the column of the value itself. */
    const char *graph = cg_test_write_file("bad_resolution.json",
        "{ \"version\": 1,\n"
        "  \"passes\": {\n"
        "    \"gbuf\": { \"type\": \"gbuffer\" },\n"
        "    \"vox\": { \"type\": \"voxelize\",\n"
        "             \"params\": { \"resolution\": 100 } },\n"
        "    \"final\": { \"type\": \"composite\", \"inputs\": { \"albedo\": \"gbuf\", \"emissive\": \"gbuf\" } }\n"
        "  },\n"
        "  \"outputs\": [ \"final.hdr\", \"final.ldr\" ] }\n", 0);
    snprintf(args, sizeof args, "render builtin:cornell --size 32x32 --graph '%s' -o '%s'", graph, out_png);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 2);
    char expected[4300];
    snprintf(expected, sizeof expected, "%s:5:40: vox.resolution = 100; expected a power of two in 16..512", graph);
    if (!strstr(out, expected))
        fail_msg("expected '%s' in: %s", expected, out);
    assert_false(exists(out_png));
}

static void
test_render_png_exr_dump_report(void **state)
{
    (void)state;
    const char *png = cg_test_tmp_path("cornell.png"), *exr = cg_test_tmp_path("cornell.exr");
    const char *dump = cg_test_tmp_path("normal.exr"), *report = cg_test_tmp_path("report.json");
    char args[8192];
    snprintf(args, sizeof args,
             "builtin:cornell --graph direct.json --size 32x24 --frames 2 -o '%s' --dump gbuf.normal='%s' "
             "--report '%s' --set shadow.resolution=256", png, dump, report);
    assert_int_equal(run(args), 0);
    snprintf(args, sizeof args, "builtin:cornell --graph direct.json --size 32x24 -o '%s'", exr);
    assert_int_equal(run(args), 0);

    cg_error err = { 0 };
    cg_image img;
    assert_cg_ok(cg_image_read(png, &img, &err), &err);
    assert_int_equal(img.width, 32);
    assert_int_equal(img.height, 24);
    cg_image_free(&img);
    assert_cg_ok(cg_image_read(exr, &img, &err), &err);
    assert_int_equal(img.width, 32);
    double sum = 0.0;
    for (int i = 0; i < 32 * 24 * 4; i++)
        sum += img.rgba[i];
    assert_true(sum > 0.0);
    cg_image_free(&img);
    assert_cg_ok(cg_image_read(dump, &img, &err), &err);
    assert_int_equal(img.height, 24);
    cg_image_free(&img);
    assert_true(exists(report));
}

static double
rel_mse(const char *test, const char *reference)
{
    cg_error err = { 0 };
    cg_image a, b;
    cg_metrics m;
    assert_cg_ok(cg_image_read(test, &a, &err), &err);
    assert_cg_ok(cg_image_read(reference, &b, &err), &err);
    assert_cg_ok(cg_metrics_compute(&a, &b, &m, &err), &err);
    cg_image_free(&a);
    cg_image_free(&b);
    return m.rel_mse;
}

/* Frame k of --frames N --fps F --time T is posed at T + k/F: the last of 4 frames from 0.5 s
 * at 10 fps is the frame at 0.8 s. Every pass rebuilds what it needs from the frame's scene, so
 * the two agree to the bit today; the bound guards the caching a later change may add. The
 * frames say so on stderr (--verbose), and the motion (buildings turning once in 2 s: 54 degrees between
 * the first frame and the last) changes the image ten times more than the bound allows. */
#define MOVING "'builtin:openworld?triangles=5000&motion=all&period=2'"

static void
test_frames_end_at_the_last_time(void **state)
{
    (void)state;
    const char *last = cg_test_tmp_path("frames.exr"), *at = cg_test_tmp_path("at.exr"), *first = cg_test_tmp_path("first.exr");
    static char out[1 << 16];
    char args[8192];
    snprintf(args, sizeof args, "render " MOVING " --size 64x36 --frames 4 --fps 10 --time 0.5 --verbose -o '%s'",
             last);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 0);
    for (int k = 1; k <= 4; k++) {
        char line[64];
        snprintf(line, sizeof line, "render: frame %d/4 ", k);
        if (!strstr(out, line))
            fail_msg("no '%s' line in: %s", line, out);
    }
    assert_non_null(strstr(out, "the last at t = 0.8 s"));
    snprintf(args, sizeof args, MOVING " --size 64x36 --time 0.8 -o '%s'", at);
    assert_int_equal(run(args), 0);
    snprintf(args, sizeof args, MOVING " --size 64x36 --time 0.5 -o '%s'", first);
    assert_int_equal(run(args), 0);
    double same = rel_mse(last, at), moved = rel_mse(first, at);
    if (!(same < 1e-3))
        fail_msg("frame 4 of 4 from 0.5 s at 10 fps against the frame at 0.8 s: relMSE %g", same);
    if (!(moved > 1e-2))
        fail_msg("the frames at 0.5 s and 0.8 s hardly differ (relMSE %g): the motion is not seen", moved);
}

/* OpenImageIO (260 shared libraries, half a second to load) is loaded on the first image, not
 * at start-up; and a render whose image module is missing fails before it renders, with the
 * file it looked for, and writes nothing. */
static void
test_images_load_their_library_on_use(void **state)
{
    (void)state;
    const char *exe = getenv("CONEGRAPH_EXE");
    assert_non_null(exe);
    char cmd[8192], out[65536];
    const struct { const char *args; bool loads; } runs[] = {
        { "info builtin:cornell", false },
        { "passes", false },
        { "render builtin:cornell --graph direct.json --size 16x16 -o '%s'", true },
    };
    /* A sanitizer build links the module into every program (core/image/meson.build): this one
     * has OpenImageIO mapped from the start too, then, and there is nothing to check. */
    bool linked = false;
    FILE *maps = fopen("/proc/self/maps", "r");
    assert_non_null(maps);
    while (fgets(out, sizeof out, maps))
        linked = linked || strstr(out, "libOpenImageIO") != NULL;
    fclose(maps);
    if (linked) {
        print_message("# the module is linked (a sanitizer build): not checked\n");
        return;
    }
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        char args[4096];
        snprintf(args, sizeof args, runs[i].args, cg_test_tmp_path("lazy.exr"));
        snprintf(cmd, sizeof cmd, "LD_DEBUG=files '%s' %s 2>&1 >/dev/null", exe, args);
        FILE *p = popen(cmd, "r");
        assert_non_null(p);
        bool loaded = false; /* the loader's trace, line by line to its end */
        while (fgets(out, sizeof out, p))
            loaded = loaded || strstr(out, "libOpenImageIO") != NULL;
        assert_int_equal(pclose(p), 0);
        if (loaded != runs[i].loads)
            fail_msg("conegraph %s: OpenImageIO %s, expected %s", args, loaded ? "loaded" : "not loaded",
                     runs[i].loads ? "loaded" : "not loaded");
    }

    const char *missing = cg_test_tmp_path("missing.exr");
    char args[4096];
    snprintf(args, sizeof args, "render builtin:cornell --size 16x16 -o '%s'", missing);
    setenv("CONEGRAPH_OIIO_MODULE", "/nonexistent/libcg-oiio.so", 1);
    int code = cg_test_run_conegraph(args, true, out, sizeof out);
    unsetenv("CONEGRAPH_OIIO_MODULE");
    assert_int_equal(code, 1);
    assert_non_null(strstr(out, "/nonexistent/libcg-oiio.so"));
    assert_null(strstr(out, "median frame")); /* refused before the first frame */
    assert_false(exists(missing));
}

/* An animated scene exported to glTF renders as the built-in does at the same time: the
 * animation goes through the file. */
static void
test_exported_animation_renders(void **state)
{
    (void)state;
    const char *glb = cg_test_tmp_path("moving.glb"), *from_file = cg_test_tmp_path("from_file.exr"), *builtin = cg_test_tmp_path("builtin.exr");
    static char out[1 << 16];
    char args[8192];
    snprintf(args, sizeof args, "export " MOVING " '%s'", glb);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 0);
    snprintf(args, sizeof args, "'%s' --size 64x36 --time 7 -o '%s'", glb, from_file);
    assert_int_equal(run(args), 0);
    snprintf(args, sizeof args, MOVING " --size 64x36 --time 7 -o '%s'", builtin);
    assert_int_equal(run(args), 0);
    double e = rel_mse(from_file, builtin);
    if (!(e < 1e-3))
        fail_msg("the exported scene at 7 s against the built-in at 7 s: relMSE %g", e);
}

/* Output paths are checked before any work: a missing directory, a directory where a file is
 * asked for, a wrong extension of -o, --dump, --pass-costs: exit 2 at once, naming the path as
 * written, and nothing is written. */
static void
test_output_paths_refused_before_work(void **state)
{
    (void)state;
    const char *written = cg_test_tmp_path("written.png"), *costs = cg_test_tmp_path("costs.csv");
    static char out[1 << 14];
    char args[8192];
    struct { const char *options, *named; } cases[] = {
        { "-o /nonexistent-dir/x.png", "/nonexistent-dir" },
        { "-o %s/adir.png", "is a directory, expected a file" },
        { "-o %s/x.png --dump gbuf.albedo=/nonexistent-dir/a.exr", "/nonexistent-dir" },
        { "-o %s/x.png --pass-costs /nonexistent-dir/c.csv", "/nonexistent-dir" },
        { "-o %s/x.png --report /nonexistent-dir/r.json", "/nonexistent-dir" },
        { "-o %s/written.png/x.png", "is not a directory" },
        { "-o %s/x-%s.png", "%d conversion" },
    };
    FILE *f = fopen(written, "w"); /* a file where a case wants a directory */
    assert_non_null(f);
    fclose(f);
    assert_int_equal(mkdir(cg_test_tmp_path("adir.png"), 0755), 0); /* a directory where a case wants a file */
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char options[1024];
        snprintf(options, sizeof options, cases[i].options, cg_test_tmpdir(), "%s");
        snprintf(args, sizeof args, "render builtin:cornell --graph vct.json --size 32x32 %s", options);
        double t0 = now_ms();
        int code = cg_test_run_conegraph(args, true, out, sizeof out);
        double ms = now_ms() - t0;
        if (code != 2 || !strstr(out, cases[i].named))
            fail_msg("'%s' exited %d, expected 2 naming '%s': %s", options, code, cases[i].named, out);
        /* Refused before the scene and the graph's GL work: a render of vct.json takes seconds. */
        if (ms > 3000.0)
            fail_msg("'%s' took %.0f ms to be refused", options, ms);
    }
    assert_false(exists(costs));
    assert_false(exists(cg_test_tmp_path("x.png")));
}

/* -o with %d writes every frame of --frames N; the default run says one line, --quiet none,
 * --verbose adds the tables on stdout. */
static void
test_sequence_and_verbosity(void **state)
{
    (void)state;
    static char out[1 << 16];
    char args[8192];
    snprintf(args, sizeof args, "render builtin:cornell --graph direct.json --size 32x32 --frames 3 -o '%s/f-%%04d.png'",
             cg_test_tmpdir());
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 0);
    for (int k = 0; k < 3; k++) {
        char name[64];
        snprintf(name, sizeof name, "f-%04d.png", k);
        if (!exists(cg_test_tmp_path(name)))
            fail_msg("no %s after --frames 3: %s", name, out);
    }
    assert_false(exists(cg_test_tmp_path("f-0003.png")));
    snprintf(args, sizeof args, "render builtin:cornell --graph direct.json --size 32x32 -o '%s'", cg_test_tmp_path("one.png"));
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 0);
    int lines = 0;
    for (const char *p = out; *p; p++)
        lines += *p == '\n';
    if (lines > 3)
        fail_msg("a default render printed %d lines: %s", lines, out);
    if (!strstr(out, "wrote ") || !strstr(out, "one.png"))
        fail_msg("the summary does not name the image: %s", out);
    char quiet[8300];
    snprintf(quiet, sizeof quiet, "%s --quiet", args);
    assert_int_equal(cg_test_run_conegraph(quiet, true, out, sizeof out), 0);
    if (out[0])
        fail_msg("--quiet printed: %s", out);
    snprintf(quiet, sizeof quiet, "%s --verbose", args);
    assert_int_equal(cg_test_run_conegraph(quiet, true, out, sizeof out), 0);
    if (!strstr(out, "gbuf"))
        fail_msg("--verbose printed no pass table: %s", out);
}

/* A graph file is looked for in the working directory, then in the graph directory, and a
 * missing one names both places; an unknown pass in --set lists the graph's passes. */
static void
test_graph_lookup_and_unknown_pass(void **state)
{
    (void)state;
    static char out[1 << 14];
    assert_int_equal(cg_test_run_conegraph("graph no_such_dir/vct.json", true, out, sizeof out), 2);
    if (!strstr(out, "working directory") || !strstr(out, "graph directory") || strstr(out, ": graph: "))
        fail_msg("the missing graph's message: %s", out);
    char args[8192];
    snprintf(args, sizeof args, "render builtin:cornell --graph vct.json --size 32x32 -o '%s' --set nosuch.x=1",
             cg_test_tmp_path("unknown.png"));
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 2);
    if (!strstr(out, "its passes: shadow, gbuf, direct"))
        fail_msg("the unknown pass's message does not list the passes: %s", out);
}

/* ------------------------------------------------------------------ skins and progress */

/* A skinned mesh is posed by its joints (tests/data/gltf/skin/bend.gltf: the strip's top turns a
 * quarter turn over 1 s): the images at 0 and 1 s differ, and the last of three frames of
 * vct.json from 0 to 1 s (its voxels kept from frame to frame where nothing changed) is the
 * image of a fresh render at 1 s: the bent mesh reached the GPU and the voxel cache. Debian's
 * assimp-testmodels simple_skin.gltf, where installed, differs at 0 and 1.5 s too. */
static void
test_skins_pose_at_two_times(void **state)
{
    (void)state;
    const char *bend = cg_test_data_path("gltf/skin/bend.gltf");
    const char *at0 = cg_test_tmp_path("bend0.exr"), *at1 = cg_test_tmp_path("bend1.exr"), *frames = cg_test_tmp_path("bend_frames.exr");
    char args[8192];
    snprintf(args, sizeof args, "'%s' --graph direct.json --size 48x48 --time 0 -o '%s'", bend, at0);
    assert_int_equal(run(args), 0);
    snprintf(args, sizeof args, "'%s' --graph direct.json --size 48x48 --time 1 -o '%s'", bend, at1);
    assert_int_equal(run(args), 0);
    double bent = rel_mse(at0, at1);
    if (!(bent > 1e-2))
        fail_msg("bend.gltf at 0 s and at 1 s hardly differ (relMSE %g): the skin is not applied", bent);

    snprintf(args, sizeof args, "'%s' --graph vct.json --set vox.resolution=64 --size 48x48 --time 1 -o '%s'", bend, at1);
    assert_int_equal(run(args), 0);
    snprintf(args, sizeof args, "'%s' --graph vct.json --set vox.resolution=64 --size 48x48 --frames 3 --fps 2 --time 0 "
             "-o '%s'", bend, frames);
    assert_int_equal(run(args), 0);
    double cached = rel_mse(frames, at1);
    if (!(cached < 1e-4))
        fail_msg("frame 3 of 3 (t = 1 s) against a fresh render at 1 s: relMSE %g", cached);

    const char *simple = "/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf";
    if (!exists(simple)) {
        printf("# %s is not installed (Debian assimp-testmodels): only bend.gltf checked\n", simple);
        return;
    }
    /* Its plane faces +z: looked at from the front (unskinned, the two images are equal). */
    snprintf(args, sizeof args, "'%s' --graph direct.json --size 48x48 --from 0.5,1,4 --look-at 0.5,1,0 --time 0 -o '%s'",
             simple, at0);
    assert_int_equal(run(args), 0);
    snprintf(args, sizeof args, "'%s' --graph direct.json --size 48x48 --from 0.5,1,4 --look-at 0.5,1,0 --time 1.5 -o '%s'",
             simple, at1);
    assert_int_equal(run(args), 0);
    bent = rel_mse(at0, at1);
    if (!(bent > 1e-3))
        fail_msg("simple_skin.gltf at 0 s and 1.5 s hardly differ (relMSE %g)", bent);
}

/* What a render writes on stderr into a file (`extra` options appended), with progress shown
 * from the start ($CONEGRAPH_PROGRESS_DELAY=0 stands for work long enough) and the log at info,
 * as a user's shell has it (the tests run with CONEGRAPH_LOG=warn). */
static const char *
stderr_of(const char *args)
{
    const char *exe = getenv("CONEGRAPH_EXE");
    const char *err_path = cg_test_tmp_path("stderr.txt");
    static char text[1 << 16];
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "CONEGRAPH_LOG=info CONEGRAPH_PROGRESS_DELAY=0 '%s' render %s 2>'%s' >/dev/null", exe,
             args, err_path);
    int status = system(cmd);
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        fail_msg("could not run: %s", cmd);
    FILE *f = fopen(err_path, "rb");
    assert_non_null(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
    return text;
}

/* Progress with the time left on the long steps (here all of them: no delay): the scene load, the
 * path tracer, the frames; into a file a line per 10% or per frame and never a carriage return;
 * nothing at all with --quiet. */
static void
test_progress_into_a_file(void **state)
{
    (void)state;
    char args[8192];
    snprintf(args, sizeof args, "builtin:cornell --graph reference.json --size 32x32 --set trace.spp=4 --frames 2 -o '%s'",
             cg_test_tmp_path("pt.png"));
    const char *err = stderr_of(args);
    if (strchr(err, '\r'))
        fail_msg("a carriage return in stderr sent to a file: %s", err);
    const char *want[] = { "conegraph: loading builtin:cornell: 100%", "conegraph: path tracing 32x32 at 4 spp: 100%",
                           "left\n",
                           "conegraph: rendering 2 frames: 50% (1/2 frames)",
                           "conegraph: rendering 2 frames: 100% (2/2 frames)" };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        if (!strstr(err, want[i]))
            fail_msg("no '%s' in stderr: %s", want[i], err);
    char quiet[8300];
    snprintf(quiet, sizeof quiet, "%s --quiet", args);
    err = stderr_of(quiet);
    if (err[0])
        fail_msg("--quiet wrote: %s", err);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_help_and_usage),
             cmocka_unit_test(test_bad_input_writes_nothing),
             cmocka_unit_test(test_output_paths_refused_before_work),
             cmocka_unit_test(test_sequence_and_verbosity),
             cmocka_unit_test(test_graph_lookup_and_unknown_pass),
             cmocka_unit_test(test_refused_parameter_points_at_its_source),
             cmocka_unit_test(test_render_png_exr_dump_report),
             cmocka_unit_test(test_frames_end_at_the_last_time),
             cmocka_unit_test(test_exported_animation_renders),
             cmocka_unit_test(test_images_load_their_library_on_use),
             cmocka_unit_test(test_skins_pose_at_two_times),
             cmocka_unit_test(test_progress_into_a_file))
