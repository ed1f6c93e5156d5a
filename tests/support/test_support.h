/* tests/support/test_support.h: helpers shared by the cmocka tests.
 *
 * Declares: cg_test_tmpdir, cg_test_tmp_path, cg_test_write_file, cg_test_data_path, cg_test_graph_path,
 *           cg_test_run_program, cg_test_run_conegraph, cg_test_run_conegraph_split, cg_test_expect_all,
 *           cg_test_list_graphs, cg_test_json_number, cg_test_load_scene, cg_test_material_default, cg_test_scale_scene,
 *           assert_cg_ok, assert_cg_status, cg_test_gl_setup, cg_test_gl_teardown,
 *           cg_test_gl_context, assert_no_gl_errors, cg_test_read_texture, cg_test_read_framebuffer,
 *           CG_TEST_MAIN, cg_test_skip_program.
 *
 * GL tests: use the setup/teardown pair as cmocka group fixtures so that one headless
 * context serves every test of the file:
 *
 *     static void test_x(void **state) {
 *         cg_context *ctx = cg_test_gl_context(state);
 *         ...GL calls...
 *         assert_no_gl_errors(ctx);
 *     }
 *     CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
 *                  cmocka_unit_test(test_x))
 *
 * With group fixtures, cmocka hands each test the pointer the group setup stored.
 */
#ifndef CG_TEST_SUPPORT_H
#define CG_TEST_SUPPORT_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdbool.h>

#include "cg/error.h"
#include "cg/gl.h"
#include "cg/scene.h"

/* A fresh directory under $TMPDIR for this test process, removed at exit. */
const char *cg_test_tmpdir(void);
/* The paths below are kept in one pool of CG_TEST_PATH_SLOTS slots used in turn: a test
 * holds fewer paths than that at once. */
#define CG_TEST_PATH_SLOTS 64
/* cg_test_tmpdir()/name. */
const char *cg_test_tmp_path(const char *name);
/* Writes `size` bytes (strlen when size is 0) to DIR/name and returns the full path. */
const char *cg_test_write_file(const char *name, const void *data, size_t size);
/* $CONEGRAPH_TEST_DATA/relative (tests/data); fails the test when the variable is not set. */
const char *cg_test_data_path(const char *relative);
/* $CONEGRAPH_GRAPH_DIR/file (graphs/, e.g. "vct.json"); fails the test when it is not set. */
const char *cg_test_graph_path(const char *file);

/* Runs the program that the environment variable exe_var names (CONEGRAPH_EXE,
 * CONEGRAPH_DEMO_EXE) with `args` (shell words) and returns its exit code; fails the test when
 * the variable is not set or the program did not exit. Its stdout, and its stderr too when
 * with_stderr, goes to out (NUL-terminated, cut at size - 1); with out NULL both are thrown
 * away. Without with_stderr, stderr is thrown away. */
int cg_test_run_program(const char *exe_var, const char *args, bool with_stderr, char *out, size_t size);
/* cg_test_run_program for $CONEGRAPH_EXE. */
int cg_test_run_conegraph(const char *args, bool with_stderr, char *out, size_t size);
/* Runs $CONEGRAPH_EXE with stdout and stderr kept apart: in out and err (NUL-terminated, cut
 * at their size - 1). Returns the exit code. */
int cg_test_run_conegraph_split(const char *args, char *out, size_t out_size, char *err, size_t err_size);

/* Fails the test, showing `text`, unless it contains every string of `wanted` (a list ended
 * by NULL); `what` names the text in the message (e.g. the command that printed it). */
void cg_test_expect_all(const char *text, const char *what, const char *const *wanted);

/* The graph files of $CONEGRAPH_GRAPH_DIR by name without ".json", sorted; fails the test when
 * the directory is not set or cannot be read. */
#define CG_TEST_MAX_GRAPHS 64
int cg_test_list_graphs(char names[CG_TEST_MAX_GRAPHS][256]);

/* The number after "KEY": in the object that follows "SECTION": of a JSON text (as conegraph
 * prints it); fails the test when either is missing. */
double cg_test_json_number(const char *json, const char *section, const char *key);

/* Loads a scene (a file, or builtin:NAME with its options); fails the test with the loader's
 * message when it cannot. The caller frees it (cg_scene_free). */
cg_scene cg_test_load_scene(const char *source);

/* The built-in scenes' default material (cg_material_default, which the library keeps to
 * itself), named "material INDEX": white albedo, Lambertian (specular 0), double-sided, no
 * texture, identity uv transforms, nothing emitted. The GPU scene uploads it field by field,
 * so a hand-built scene sets every field as the loaders do. */
void cg_test_material_default(cg_material *m, int index);

/* Scales a whole scene about the origin by k: geometry (instance transforms), cameras (position,
 * clip planes, orthographic extents), light positions and ranges, and the intensity of point and
 * spot lights by k^2 so that E = I / d^2 stays the same. Directional irradiance and emitted
 * radiance do not depend on size, so the image must not either. Recomputes the bounds. */
void cg_test_scale_scene(cg_scene *s, double k);

/* Fails the test with the error's message when a call did not succeed. */
#define assert_cg_ok(call, errp)                                                          \
    do {                                                                                  \
        if (!(call))                                                                      \
            fail_msg("%s failed: %s: %s", #call, cg_status_name((errp)->status),          \
                     (errp)->message);                                                    \
    } while (0)

/* Asserts that a call failed with the named status. */
#define assert_cg_status(call, errp, expected)                                            \
    do {                                                                                  \
        cg_error_clear(errp);                                                             \
        if (call)                                                                         \
            fail_msg("%s succeeded; expected %s", #call, cg_status_name(expected));       \
        if ((errp)->status != (expected))                                                 \
            fail_msg("%s failed with %s (%s); expected %s", #call,                        \
                     cg_status_name((errp)->status), (errp)->message,                     \
                     cg_status_name(expected));                                           \
    } while (0)

/* cmocka group setup: creates a headless GL 4.5 core context with KHR_debug output
 * (backend from $CONEGRAPH_CONTEXT: egl, osmesa or glfw; EGL when unset; no fallback, so
 * a broken backend fails loudly instead of silently testing another one) and stores
 * the cg_context * in *state. Returns -1 (the group fails) when no context can be made. */
int cg_test_gl_setup(void **state);
/* cmocka group teardown: destroys the context. Returns -1 (the group fails) when GL
 * errors were counted after the last reset, so an error no test asserted on still fails. */
int cg_test_gl_teardown(void **state);
/* The context stored by cg_test_gl_setup, from a test's `state`. */
cg_context *cg_test_gl_context(void **state);

/* Fails the test when the context counted any GL error (KHR_debug type ERROR) since it
 * was created or since cg_context_reset_gl_error_count; the messages are in the log.
 * A test that provokes errors on purpose resets the count afterwards. */
#define assert_no_gl_errors(ctx)                                                          \
    do {                                                                                  \
        int cg_gl_errors_ = cg_context_gl_error_count(ctx);                               \
        if (cg_gl_errors_ != 0)                                                           \
            fail_msg("%d GL error(s) reported through KHR_debug (messages logged above)", \
                     cg_gl_errors_);                                                      \
    } while (0)

/* The main of a test program that runs its tests (cmocka_unit_test(name), ...) as one group
 * with the group fixtures `setup` and `teardown` (cg_test_gl_setup and cg_test_gl_teardown for
 * GL tests, NULL for none):
 *
 *     CG_TEST_MAIN(NULL, NULL,
 *                  cmocka_unit_test(test_x),
 *                  cmocka_unit_test(test_y))
 *
 * A program that must do more first (read its arguments, set the environment) writes its own. */
#define CG_TEST_MAIN(setup, teardown, ...)                                                \
    int main(void)                                                                        \
    {                                                                                     \
        const struct CMUnitTest tests[] = { __VA_ARGS__ };                                \
        return cmocka_run_group_tests(tests, setup, teardown);                            \
    }

/* Skips a whole test program: prints the TAP plan "1..0 # SKIP reason" and returns 0
 * for main to return. Use it instead of cmocka's skip(): cmocka 1.1.5 prints a skipped
 * test as "not ok N # SKIP", which Meson 1.0's TAP parser counts as a failure. */
int cg_test_skip_program(const char *reason);

/* Reads back mip `level` of a texture (any target glGetTextureImage accepts: 2D, 2D
 * array, 3D, ...) as RGBA float, rows bottom to top as GL stores them, layers one after
 * another. Sizes go to w, h, d (each may be NULL). Returns malloc'd w*h*d*4 floats;
 * the caller frees. Fails the test on a bad texture or out of memory. */
float *cg_test_read_texture(GLuint texture, int level, int *w, int *h, int *d);
/* Reads back a w x h region at the origin of one colour attachment (GL_COLOR_ATTACHMENT0
 * + i) of a framebuffer object as RGBA float, rows bottom to top. Returns malloc'd
 * w*h*4 floats; the caller frees. Leaves GL_READ_FRAMEBUFFER bound to 0. */
float *cg_test_read_framebuffer(GLuint fbo, GLenum attachment, int w, int h);

#endif
