/* tests/context_checks.h: checks that every GL context backend must pass, shared by
 * test_context.c (headless backends) and test_context_window.c (GLFW). */
#ifndef CG_TEST_CONTEXT_CHECKS_H
#define CG_TEST_CONTEXT_CHECKS_H

#include "test_support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gl.h"
#include "cg/log.h"

/* Values exactly representable in 8-bit unorm (k/255) so the readback is exact. */
static const unsigned char clear_u8[4] = { 51, 102, 204, 255 };
static const float clear_f32[4] = { 0.25f, -1.5f, 1024.0f, 0.125f };

static inline void
check_version(cg_context *ctx)
{
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    assert_true(major * 10 + minor >= 45);
    assert_true(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    assert_non_null(strstr(cg_context_version(ctx), "4."));
    assert_non_null(strstr(cg_context_version(ctx), "Core Profile"));
    assert_true(strlen(cg_context_renderer(ctx)) > 0);
}

/* Clears a 4x4 FBO with an RGBA8 and an RGBA32F attachment and reads both back. */
static inline void
check_clear_readback(void)
{
    GLuint tex[2], fbo;
    glCreateTextures(GL_TEXTURE_2D, 2, tex);
    glTextureStorage2D(tex[0], 1, GL_RGBA8, 4, 4);
    glTextureStorage2D(tex[1], 1, GL_RGBA32F, 4, 4);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex[0], 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, tex[1], 0);
    const GLenum bufs[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
    glNamedFramebufferDrawBuffers(fbo, 2, bufs);
    assert_int_equal(glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);

    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, 4, 4);
    const float c8[4] = { clear_u8[0] / 255.0f, clear_u8[1] / 255.0f, clear_u8[2] / 255.0f, 1.0f };
    glClearColor(c8[0], c8[1], c8[2], c8[3]);
    glClear(GL_COLOR_BUFFER_BIT); /* clears both draw buffers */
    glClearNamedFramebufferfv(fbo, GL_COLOR, 1, clear_f32);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);

    unsigned char u8[4 * 4 * 4];
    glGetTextureImage(tex[0], 0, GL_RGBA, GL_UNSIGNED_BYTE, sizeof u8, u8);
    for (int i = 0; i < 16; i++)
        assert_memory_equal(u8 + 4 * i, clear_u8, 4);

    float *f32 = cg_test_read_framebuffer(fbo, GL_COLOR_ATTACHMENT1, 4, 4);
    for (int i = 0; i < 16; i++)
        assert_memory_equal(f32 + 4 * i, clear_f32, sizeof clear_f32);
    free(f32);

    int w, h, d;
    float *t = cg_test_read_texture(tex[0], 0, &w, &h, &d);
    assert_int_equal(w, 4);
    assert_int_equal(h, 4);
    assert_int_equal(d, 1);
    for (int i = 0; i < 16; i++)
        for (int c = 0; c < 4; c++)
            assert_true(fabsf(t[4 * i + c] - clear_u8[c] / 255.0f) <= 1e-6f);
    free(t);

    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(2, tex);
}

/* A deliberate error must reach the count through KHR_debug. */
static inline void
check_error_counted(cg_context *ctx)
{
    assert_int_equal(cg_context_gl_error_count(ctx), 0);
    cg_log_level level = cg_log_get_level();
    cg_log_set_level(CG_LOG_SILENT); /* the expected errors are not news */
    glBindTexture(GL_TEXTURE_2D, 0xdeadbeefu); /* core profile: unknown name is INVALID_OPERATION */
    int after_bind = cg_context_gl_error_count(ctx);
    glEnable(0); /* INVALID_ENUM */
    int after_enable = cg_context_gl_error_count(ctx);
    cg_log_set_level(level);
    /* Drain the error flags so that nothing lingers for later calls. */
    while (glGetError() != GL_NO_ERROR) {
    }
    assert_int_equal(after_bind, 1);
    assert_int_equal(after_enable, 2);
    cg_context_reset_gl_error_count(ctx);
    assert_int_equal(cg_context_gl_error_count(ctx), 0);
}

#endif
