/* GLFW window context: opens a GL 4.5 core window where there is an X display (.ci/test
 * runs the suite under xvfb-run); without one the whole program reports SKIP. */
#include "context_checks.h"

static void
test_glfw_window(void **state)
{
    (void)state;
    cg_context_desc desc = { .backend = CG_CONTEXT_GLFW, .width = 64, .height = 32,
                             .title = "conegraph test", .debug = true };
    cg_context *ctx = NULL;
    cg_error err = { 0 };
    assert_cg_ok(cg_context_create(&desc, &ctx, &err), &err);
    assert_int_equal(cg_context_get_backend(ctx), CG_CONTEXT_GLFW);
    assert_non_null(cg_context_window(ctx));
    check_version(ctx);
    check_clear_readback();

    /* The window's default framebuffer clears and reads back too. */
    glViewport(0, 0, 64, 32);
    glClearColor(clear_u8[0] / 255.0f, clear_u8[1] / 255.0f, clear_u8[2] / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    unsigned char px[4];
    glReadBuffer(GL_BACK);
    glReadPixels(10, 10, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    assert_memory_equal(px, clear_u8, 4);
    cg_context_swap(ctx);

    assert_no_gl_errors(ctx);
    check_error_counted(ctx);
    cg_context_destroy(ctx);
}

int
main(void)
{
    const char *display = getenv("DISPLAY");
    if (!display || !*display)
        return cg_test_skip_program("no DISPLAY for the GLFW window test (.ci/test runs it under xvfb-run)");
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_glfw_window),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
