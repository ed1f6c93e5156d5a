/* GL contexts: each headless backend makes a GL 4.5 core context that clears an FBO to
 * exact values, reports its version, and counts a deliberate GL error; bad backend
 * names are refused; GLFW fails cleanly without a display (test_context_window.c opens
 * a window where there is one). */
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cg/gl.h"
#include "cg/log.h"

#include "context_checks.h"

static void
check_backend(cg_context_backend backend)
{
    cg_context_desc desc = { .backend = backend, .debug = true };
    cg_context *ctx = NULL;
    cg_error err = { 0 };
    assert_cg_ok(cg_context_create(&desc, &ctx, &err), &err);
    assert_int_equal(cg_context_get_backend(ctx), backend);
    check_version(ctx);
    check_clear_readback();
    assert_no_gl_errors(ctx);
    check_error_counted(ctx);
    cg_context_destroy(ctx);
}

static void
test_egl(void **state)
{
    (void)state;
    check_backend(CG_CONTEXT_EGL);
}

static void
test_osmesa(void **state)
{
    (void)state;
    check_backend(CG_CONTEXT_OSMESA);
}

/* A context made without desc->debug still reports errors: output is enabled always. */
static void
test_non_debug_context_counts_errors(void **state)
{
    (void)state;
    cg_context_desc desc = { .backend = CG_CONTEXT_EGL };
    cg_context *ctx = NULL;
    cg_error err = { 0 };
    assert_cg_ok(cg_context_create(&desc, &ctx, &err), &err);
    check_error_counted(ctx);
    cg_context_destroy(ctx);
}

/* Two contexts one after the other: the second reloads the GL entry points. */
static void
test_sequential_contexts(void **state)
{
    (void)state;
    check_backend(CG_CONTEXT_OSMESA);
    check_backend(CG_CONTEXT_EGL);
    check_backend(CG_CONTEXT_EGL);
}

static void
test_backend_names(void **state)
{
    (void)state;
    cg_context_backend b = CG_CONTEXT_GLFW;
    assert_true(cg_context_backend_parse("egl", &b));
    assert_int_equal(b, CG_CONTEXT_EGL);
    assert_true(cg_context_backend_parse("osmesa", &b));
    assert_int_equal(b, CG_CONTEXT_OSMESA);
    assert_true(cg_context_backend_parse("glfw", &b));
    assert_int_equal(b, CG_CONTEXT_GLFW);
    assert_true(cg_context_backend_parse("auto", &b));
    assert_int_equal(b, CG_CONTEXT_AUTO);
    b = CG_CONTEXT_OSMESA;
    assert_false(cg_context_backend_parse("vulkan", &b));
    assert_false(cg_context_backend_parse("EGL ", &b));
    assert_false(cg_context_backend_parse("", &b));
    assert_false(cg_context_backend_parse(NULL, &b));
    assert_int_equal(b, CG_CONTEXT_OSMESA); /* untouched on failure */
    assert_string_equal(cg_context_backend_name(CG_CONTEXT_OSMESA), "osmesa");
}

/* Restores an environment variable to its value before the test. */
typedef struct saved_env {
    const char *name;
    char value[4096];
    bool was_set;
} saved_env;

static void
env_save(saved_env *s, const char *name)
{
    const char *v = getenv(name);
    s->name = name;
    s->was_set = v != NULL;
    snprintf(s->value, sizeof s->value, "%s", v ? v : "");
}

static void
env_restore(const saved_env *s)
{
    if (s->was_set)
        setenv(s->name, s->value, 1);
    else
        unsetenv(s->name);
}

static void
test_bogus_backend_rejected(void **state)
{
    (void)state;
    saved_env env;
    env_save(&env, "CONEGRAPH_CONTEXT");
    cg_context *ctx = NULL;
    cg_error err = { 0 };

    setenv("CONEGRAPH_CONTEXT", "vulkan", 1);
    cg_context_desc desc = { .backend = CG_CONTEXT_AUTO };
    assert_cg_status(cg_context_create(&desc, &ctx, &err), &err, CG_ERR_GL_CONTEXT);
    assert_null(ctx);
    assert_non_null(strstr(err.message, "vulkan"));
    env_restore(&env);

    desc.backend = (cg_context_backend)42;
    assert_cg_status(cg_context_create(&desc, &ctx, &err), &err, CG_ERR_GL_CONTEXT);
    assert_null(ctx);
}

/* CONEGRAPH_CONTEXT chooses the backend under AUTO. */
static void
test_env_selects_backend(void **state)
{
    (void)state;
    saved_env env;
    env_save(&env, "CONEGRAPH_CONTEXT");
    setenv("CONEGRAPH_CONTEXT", "osmesa", 1);
    cg_context *ctx = NULL;
    cg_error err = { 0 };
    bool ok = cg_context_create(NULL, &ctx, &err);
    env_restore(&env);
    assert_cg_ok(ok, &err);
    assert_int_equal(cg_context_get_backend(ctx), CG_CONTEXT_OSMESA);
    cg_context_destroy(ctx);
}

/* When every backend fails, the error names each one and why. Mesa's version override
 * makes both headless backends offer GL 4.1 only; Mesa reads it once per process, so
 * the check runs in a fresh process: this test program re-executed with a flag. */
static int
auto_failure_child(void)
{
    cg_context *ctx = NULL;
    cg_error err = { 0 };
    if (cg_context_create(NULL, &ctx, &err)) {
        fprintf(stderr, "a GL 4.5 context was created under MESA_GL_VERSION_OVERRIDE=4.1\n");
        return 1;
    }
    fprintf(stderr, "# expected failure: %s: %s\n", cg_status_name(err.status), err.message);
    bool ok = err.status == CG_ERR_GL_CONTEXT && strstr(err.message, "egl: ") &&
              strstr(err.message, "osmesa: ");
    return ok ? 0 : 1;
}

static void
test_auto_failure_names_each_backend(void **state)
{
    (void)state;
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        unsetenv("CONEGRAPH_CONTEXT");
        setenv("MESA_GL_VERSION_OVERRIDE", "4.1", 1);
        execl("/proc/self/exe", "test_context", "--auto-failure-child", (char *)NULL);
        _exit(127);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
}

static void
test_glfw_without_display_fails_cleanly(void **state)
{
    (void)state;
    saved_env display, wayland;
    env_save(&display, "DISPLAY");
    env_save(&wayland, "WAYLAND_DISPLAY");
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    cg_context_desc desc = { .backend = CG_CONTEXT_GLFW };
    cg_context *ctx = NULL;
    cg_error err = { 0 };
    cg_error_clear(&err);
    bool ok = cg_context_create(&desc, &ctx, &err);
    env_restore(&display);
    env_restore(&wayland);
    assert_false(ok);
    assert_int_equal(err.status, CG_ERR_GL_CONTEXT);
    assert_non_null(strstr(err.message, "glfw"));
    assert_non_null(strstr(err.message, "DISPLAY"));
}

int
main(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "--auto-failure-child"))
        return auto_failure_child();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_backend_names),
        cmocka_unit_test(test_egl),
        cmocka_unit_test(test_osmesa),
        cmocka_unit_test(test_non_debug_context_counts_errors),
        cmocka_unit_test(test_sequential_contexts),
        cmocka_unit_test(test_bogus_backend_rejected),
        cmocka_unit_test(test_env_selects_backend),
        cmocka_unit_test(test_auto_failure_names_each_backend),
        cmocka_unit_test(test_glfw_without_display_fails_cleanly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
