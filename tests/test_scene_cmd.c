/* `conegraph info` and `conegraph export` end to end: output, exit codes, errors on stderr,
 * no output file for a bad scene. The executable comes from $CONEGRAPH_EXE (tests/meson.build). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_support.h"

static char out_text[1 << 16], err_text[1 << 14];

/* Runs conegraph with `args`; returns the exit code, stdout and stderr in out_text, err_text. */
static int
run(const char *args)
{
    return cg_test_run_conegraph_split(args, out_text, sizeof out_text, err_text, sizeof err_text);
}

static void
info_prints_the_scene(void **state)
{
    (void)state;
    assert_int_equal(run("info builtin:cornell"), 0);
    assert_non_null(strstr(out_text, "triangles 34"));
    assert_non_null(strstr(out_text, "'left_wall' complex"));
    assert_non_null(strstr(out_text, "spot"));
    assert_non_null(strstr(out_text, "cameras 1"));
    assert_non_null(strstr(out_text, "bounds [-0.5 0 -0.5] .. [0.5 1 0.5]"));
    assert_int_equal(run("info builtin:openworld?triangles=10000"), 0);
    assert_non_null(strstr(out_text, "'terrain' heightfield"));
    assert_non_null(strstr(out_text, "directional"));
    assert_int_equal(run("info --help"), 0);
    assert_non_null(strstr(out_text, "usage: conegraph info SCENE"));
    assert_non_null(strstr(out_text, "builtin:furnace"));
}

static void
info_gl_reports_the_context(void **state)
{
    (void)state;
    const char *backends[] = { "egl", "osmesa" };
    for (int i = 0; i < 2; i++) {
        char args[128];
        snprintf(args, sizeof args, "info builtin:cornell --gl --context %s", backends[i]);
        if (run(args) != 0)
            fail_msg("%s: %s", args, err_text);
        assert_non_null(strstr(out_text, "gl version 4."));
        assert_non_null(strstr(out_text, "Core Profile"));
        assert_non_null(strstr(out_text, "gl renderer "));
        char line[64];
        snprintf(line, sizeof line, "gl context %s", backends[i]);
        assert_non_null(strstr(out_text, line));
    }
    assert_int_equal(run("info builtin:cornell --gl --context nothing"), 2);
    /* --context alone asks for the GL report too. */
    assert_int_equal(run("info builtin:cornell --context osmesa"), 0);
    assert_non_null(strstr(out_text, "gl context osmesa"));
}

static void
info_bad_input(void **state)
{
    (void)state;
    assert_int_equal(run("info builtin:nowhere"), 2);
    assert_string_equal(out_text, "");
    assert_non_null(strstr(err_text, "unknown built-in scene"));
    assert_int_equal(run("info /nonexistent/scene.gltf"), 2);
    assert_non_null(strstr(err_text, "/nonexistent/scene.gltf"));
    assert_int_equal(run("info"), 2);
    assert_int_equal(run("info builtin:cornell --bogus"), 2);
    assert_int_equal(run("info builtin:cornell builtin:furnace"), 2);
}

static void
export_writes_and_refuses(void **state)
{
    (void)state;
    char args[8400], out[4200];
    snprintf(out, sizeof out, "%s/cornell.glb", cg_test_tmpdir());
    snprintf(args, sizeof args, "export builtin:cornell '%s'", out);
    assert_int_equal(run(args), 0);
    snprintf(args, sizeof args, "info '%s'", out);
    assert_int_equal(run(args), 0);
    assert_non_null(strstr(out_text, "triangles 34"));
    assert_non_null(strstr(out_text, "ceiling_spot"));
    assert_int_equal(run("export --help"), 0);
    assert_non_null(strstr(out_text, "usage: conegraph export"));

    /* A bad scene: message on stderr, exit 2, no output file. */
    const char *bad = cg_test_write_file("bad.gltf", "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"children\":[0]}]}", 0);
    snprintf(out, sizeof out, "%s/never.gltf", cg_test_tmpdir());
    snprintf(args, sizeof args, "export '%s' '%s'", bad, out);
    assert_int_equal(run(args), 2);
    assert_non_null(strstr(err_text, "bad.gltf"));
    assert_non_null(strstr(err_text, "cycle"));
    assert_int_not_equal(access(out, F_OK), 0);
    snprintf(args, sizeof args, "export builtin:openworld?triangles=3 '%s'", out);
    assert_int_equal(run(args), 2);
    assert_int_not_equal(access(out, F_OK), 0);
    snprintf(out, sizeof out, "%s/scene.obj", cg_test_tmpdir());
    snprintf(args, sizeof args, "export builtin:cornell '%s'", out);
    assert_int_equal(run(args), 2);
    assert_int_not_equal(access(out, F_OK), 0);
    assert_int_equal(run("export builtin:cornell"), 2);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(info_prints_the_scene),
             cmocka_unit_test(info_gl_reports_the_context),
             cmocka_unit_test(info_bad_input),
             cmocka_unit_test(export_writes_and_refuses))
