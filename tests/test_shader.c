/* Shaders: #include expansion with #line, once-only and nested includes, errors that name
 * the original file and line, and programs that run (compute and graphics).
 * The shaders are in tests/data/shaders (CONEGRAPH_SHADER_DIR is pointed there). */
#include "test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gl.h"
#include "cg/log.h"
#include "cg/shader.h"

static void
test_shader_dir_from_env(void **state)
{
    (void)state;
    assert_string_equal(cg_shader_dir(), getenv("CONEGRAPH_SHADER_DIR"));
}

/* The whole expansion, line for line: #line resumes each file at the right line, the
 * define follows #version, one.glsl appears once though included twice, and the
 * #include inside a block comment is left alone. */
static void
test_include_expansion(void **state)
{
    (void)state;
    static const char expected[] =
        "#version 450 core\n"
        "#define VALUE 40\n"
        "#line 2 0\n"
        "/* Includes two.glsl, which includes one.glsl; the second include of one.glsl expands to nothing.\n"
        "#include \"common/does_not_exist.glsl\" is inside this comment and left alone. */\n"
        "#line 100001 1\n" /* file i counts lines from i * 100000 (Mesa drops i in some logs) */
        "#line 200001 2\n"
        "\n" /* #pragma once */
        "// one(): the constant 1, reached through a nested include.\n"
        "float one() { return 1.0; }\n"
        "#line 100002 1\n"
        "float two() { return one() + one(); }\n"
        "#line 5 0\n"
        "\n" /* the second #include "common/one.glsl" */
        "layout(local_size_x = 1) in;\n"
        "layout(std430, binding = 0) buffer Out { float value[]; };\n"
        "void main() { value[gl_GlobalInvocationID.x] = two() + float(VALUE) + float(gl_GlobalInvocationID.x); }\n";
    char *src = NULL;
    cg_error err = { 0 };
    assert_cg_ok(cg_shader_source_load("test/include_top.comp", "#define VALUE 40", &src, &err), &err);
    assert_string_equal(src, expected);
    free(src);
}

static void
test_version_prepended_when_missing(void **state)
{
    (void)state;
    char *src = NULL;
    cg_error err = { 0 };
    assert_cg_ok(cg_shader_source_load("test/no_version.comp", "#define X 1\n", &src, &err), &err);
    assert_string_equal(src, "#version 450 core\n#define X 1\n#line 1 0\n"
                             "layout(local_size_x = 1) in;\nvoid main() {}\n");
    free(src);
}

static void
test_absolute_path(void **state)
{
    (void)state;
    char path[4096], *src = NULL;
    snprintf(path, sizeof path, "%s/test/no_version.comp", getenv("CONEGRAPH_SHADER_DIR"));
    cg_error err = { 0 };
    assert_cg_ok(cg_shader_source_load(path, NULL, &src, &err), &err);
    assert_non_null(strstr(src, "void main() {}"));
    free(src);
}

static void
test_missing_file(void **state)
{
    (void)state;
    char *src = NULL;
    cg_error err;
    assert_cg_status(cg_shader_source_load("test/nope.comp", NULL, &src, &err), &err, CG_ERR_SHADER_NOT_FOUND);
    assert_null(src);
    assert_non_null(strstr(err.message, "test/nope.comp"));
}

static void
test_missing_include_names_includer_and_line(void **state)
{
    (void)state;
    char *src = NULL;
    cg_error err;
    assert_cg_status(cg_shader_source_load("test/missing_include.comp", NULL, &src, &err), &err,
                     CG_ERR_SHADER_NOT_FOUND);
    assert_non_null(strstr(err.message, "test/missing_include.comp:4: #include \"common/does_not_exist.glsl\""));

    assert_cg_status(cg_shader_source_load("test/nested_missing_include.comp", NULL, &src, &err), &err,
                     CG_ERR_SHADER_NOT_FOUND);
    assert_non_null(strstr(err.message, "common/includes_missing.glsl:2: #include \"common/does_not_exist.glsl\""));
    assert_non_null(strstr(err.message, "included from test/nested_missing_include.comp:2"));
}

static void
test_include_cycle(void **state)
{
    (void)state;
    char *src = NULL;
    cg_error err;
    assert_cg_status(cg_shader_source_load("test/cycle.comp", NULL, &src, &err), &err, CG_ERR_SHADER_COMPILE);
    assert_non_null(strstr(err.message, "common/cycle_b.glsl:2"));
    assert_non_null(strstr(err.message, "cycle"));
}

/* The driver's "2:200004(2): error" (source string 2 = broken.glsl), and Mesa's
 * "0:200004(9)" for the same file, are reported as "common/broken.glsl:4(...)". */
static void
test_compile_error_in_include(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    GLuint program = 1234;
    cg_error err;
    cg_log_level level = cg_log_get_level();
    cg_log_set_level(CG_LOG_SILENT);
    assert_cg_status(cg_program_compute("test/error_in_include.comp", NULL, &program, &err), &err,
                     CG_ERR_SHADER_COMPILE);
    cg_log_set_level(level);
    assert_int_equal(program, 0);
    assert_non_null(strstr(err.message, "test/error_in_include.comp"));
    assert_non_null(strstr(err.message, "common/broken.glsl:4("));
    assert_non_null(strstr(err.message, "undeclared_variable"));
    assert_null(strstr(err.message, "200004"));
    /* A failed compile is not a GL API error. */
    assert_no_gl_errors(ctx);
}

/* An error in the top file after an include: the #line after the include is right. */
static void
test_compile_error_after_include(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    GLuint program = 0;
    cg_error err;
    cg_log_level level = cg_log_get_level();
    cg_log_set_level(CG_LOG_SILENT);
    assert_cg_status(cg_program_compute("test/error_after_include.comp", NULL, &program, &err), &err,
                     CG_ERR_SHADER_COMPILE);
    cg_log_set_level(level);
    assert_non_null(strstr(err.message, "test/error_after_include.comp:5("));
    assert_non_null(strstr(err.message, "not_declared_here"));
    assert_no_gl_errors(ctx);
}

static void
test_link_error(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    GLuint program = 0;
    cg_error err;
    cg_log_level level = cg_log_get_level();
    cg_log_set_level(CG_LOG_SILENT);
    assert_cg_status(cg_program_graphics("test/fullscreen.vert", NULL, "test/needs_input.frag", NULL, &program,
                                         &err),
                     &err, CG_ERR_SHADER_COMPILE);
    cg_log_set_level(level);
    assert_non_null(strstr(err.message, "link"));
    assert_non_null(strstr(err.message, "never_written"));
    assert_no_gl_errors(ctx);
}

/* The include-expanded compute program runs: value[i] = two() + VALUE + i. */
static void
test_compute_program_runs(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    GLuint program = 0;
    cg_error err = { 0 };
    assert_cg_ok(cg_program_compute("test/include_top.comp", "#define VALUE 40\n", &program, &err), &err);
    GLuint buffer;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, 4 * sizeof(float), NULL, GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    glUseProgram(program);
    glDispatchCompute(4, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    float values[4] = { 0 };
    glGetNamedBufferSubData(buffer, 0, sizeof values, values);
    for (int i = 0; i < 4; i++)
        assert_true(values[i] == 42.0f + (float)i);
    glUseProgram(0);
    glDeleteBuffers(1, &buffer);
    glDeleteProgram(program);
    assert_no_gl_errors(ctx);
}

/* A graphics program with an include in its fragment stage draws a known colour. */
static void
test_graphics_program_draws(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    GLuint program = 0;
    cg_error err = { 0 };
    assert_cg_ok(cg_program_graphics("test/fullscreen.vert", NULL, "test/solid.frag", "#define RED 0.75\n",
                                     &program, &err),
                 &err);
    GLuint tex, fbo, vao;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, 8, 8);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    glCreateVertexArrays(1, &vao);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, 8, 8);
    glBindVertexArray(vao);
    glUseProgram(program);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glUseProgram(0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    float *px = cg_test_read_texture(tex, 0, NULL, NULL, NULL);
    const float expected[4] = { 0.25f, 0.5f, 0.75f, 1.0f };
    for (int i = 0; i < 64; i++)
        assert_memory_equal(px + 4 * i, expected, sizeof expected);
    free(px);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glDeleteProgram(program);
    assert_no_gl_errors(ctx);
}

/* Vertex + geometry stages and no fragment stage: a depth-only program writes the
 * geometry shader's depth into a depth attachment. */
static void
test_depth_only_program_with_geometry_stage(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    GLuint program = 0;
    cg_error err = { 0 };
    assert_cg_ok(cg_program_graphics("test/fullscreen.vert", "test/passthrough.geom", NULL, "#define DEPTH 0.5\n",
                                     &program, &err),
                 &err);
    GLuint depth, fbo, vao;
    glCreateTextures(GL_TEXTURE_2D, 1, &depth);
    glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 8, 8);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    glNamedFramebufferReadBuffer(fbo, GL_NONE);
    assert_int_equal(glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &far);
    glCreateVertexArrays(1, &vao);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, 8, 8);
    glEnable(GL_DEPTH_TEST);
    glBindVertexArray(vao);
    glUseProgram(program);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    float values[64];
    glGetTextureImage(depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, sizeof values, values);
    for (int i = 0; i < 64; i++) /* NDC z 0.5 -> window depth 0.75 */
        assert_true(values[i] == 0.75f);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &depth);
    glDeleteProgram(program);
    assert_no_gl_errors(ctx);
}

int
main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shader_dir_from_env),
        cmocka_unit_test(test_include_expansion),
        cmocka_unit_test(test_version_prepended_when_missing),
        cmocka_unit_test(test_absolute_path),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_missing_include_names_includer_and_line),
        cmocka_unit_test(test_include_cycle),
        cmocka_unit_test(test_compile_error_in_include),
        cmocka_unit_test(test_compile_error_after_include),
        cmocka_unit_test(test_link_error),
        cmocka_unit_test(test_compute_program_runs),
        cmocka_unit_test(test_graphics_program_draws),
        cmocka_unit_test(test_depth_only_program_with_geometry_stage),
    };
    /* The shaders of these tests live with the tests, not in shaders/. */
    char dir[4096];
    const char *data = getenv("CONEGRAPH_TEST_DATA");
    if (!data) {
        fprintf(stderr, "CONEGRAPH_TEST_DATA is not set: run through meson test\n");
        return 1;
    }
    snprintf(dir, sizeof dir, "%s/shaders", data);
    setenv("CONEGRAPH_SHADER_DIR", dir, 1);
    return cmocka_run_group_tests(tests, cg_test_gl_setup, cg_test_gl_teardown);
}
