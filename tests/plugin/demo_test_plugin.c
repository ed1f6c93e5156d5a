/* demo_test_plugin: a pass for tests/test_demo_window.c, loaded with --plugin. It fills an
 * RGBA8 output named `ldr` (so the demo shows it) with a colour given as 8-bit levels, and on
 * frame `error_frame` provokes a GL error on purpose, so that the test sees the demo stop
 * with exit 1 on a GL error counted by the context. */
#include <stdbool.h>
#include <stdint.h>

#include "sdk/pass.h"

static const fg_param_desc params[] = {
    { .name = "red", .type = FG_PARAM_INT, .default_value = 200, .min = 0, .max = 255,
      .doc = "red level stored in the ldr output" },
    { .name = "green", .type = FG_PARAM_INT, .default_value = 100, .min = 0, .max = 255,
      .doc = "green level stored in the ldr output" },
    { .name = "blue", .type = FG_PARAM_INT, .default_value = 50, .min = 0, .max = 255,
      .doc = "blue level stored in the ldr output" },
    { .name = "error_frame", .type = FG_PARAM_INT, .default_value = -1, .min = -1, .max = 1000000,
      .doc = "frame index on which to provoke GL_INVALID_ENUM; -1 = never" },
};

static bool
declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)err;
    const fg_frame *frame = fg_pass_frame(pass);
    fg_resource_desc desc = { .kind = FG_TEXTURE_2D, .format = GL_RGBA8, .width = frame->width,
                              .height = frame->height, .depth = 1, .levels = 1 };
    fg_declare_output(decl, "ldr", &desc, FG_ACCESS_TRANSFER);
    return true;
}

static bool
execute(fg_pass *pass, void *state, cg_error *err)
{
    (void)state;
    (void)err;
    const GLubyte rgba[4] = { (GLubyte)fg_param_int(pass, "red"), (GLubyte)fg_param_int(pass, "green"),
                              (GLubyte)fg_param_int(pass, "blue"), 255 };
    glClearTexImage(fg_texture(pass, "ldr"), 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    if ((int64_t)fg_pass_frame(pass)->index == fg_param_int(pass, "error_frame"))
        glEnable(0x7fff); /* no such capability: GL_INVALID_ENUM */
    return true;
}

static const fg_pass_type fill_type = {
    .abi_version = FG_ABI_VERSION,
    .name = "demo_test_fill",
    .doc = "Test pass for the demo: fills an RGBA8 'ldr' output with given 8-bit levels and "
           "provokes a GL error on a chosen frame.",
    CGP_PARAMS(params),
    .declare = declare,
    .execute = execute,
};

CGP_PLUGIN(&fill_type);
