/* example_plugin: a pass module built as a shared object and loaded at run time
 * (`conegraph --plugin build/tests/example_plugin.so`, or $CONEGRAPH_PLUGIN_PATH).
 *
 * It registers `example_fill`, which fills a 2D RGBA16F output with a colour. Built a second
 * time with EXAMPLE_PLUGIN_ABI set to another value, it stands for a plugin built against an
 * older or newer cg/fg.h, which the host must refuse with CG_ERR_PLUGIN_ABI. It uses the pass SDK
 * (sdk/pass.h) as the built-in passes do; docs/architecture.md walks through it. */
#include <stdbool.h>
#include <stdint.h>

#include "sdk/pass.h"

#ifndef EXAMPLE_PLUGIN_ABI
#define EXAMPLE_PLUGIN_ABI FG_ABI_VERSION
#endif

static const fg_param_desc fill_params[] = {
    { .name = "red", .type = FG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 65504,
      .doc = "red component of the fill colour (linear)" },
    { .name = "green", .type = FG_PARAM_FLOAT, .min = 0, .max = 65504,
      .doc = "green component of the fill colour (linear)" },
    { .name = "blue", .type = FG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 65504,
      .doc = "blue component of the fill colour (linear)" },
    { .name = "alpha", .type = FG_PARAM_FLOAT, .default_value = 1, .min = 0, .max = 65504,
      .doc = "alpha component of the fill colour" },
    { .name = "width", .type = FG_PARAM_INT, .min = 0, .max = 16384,
      .doc = "output width in texels; 0 = the output image's" },
    { .name = "height", .type = FG_PARAM_INT, .min = 0, .max = 16384,
      .doc = "output height in texels; 0 = the output image's" },
};

static bool
fill_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)err;
    const fg_frame *frame = fg_pass_frame(pass);
    int width = fg_param_int(pass, "width"), height = fg_param_int(pass, "height");
    /* A single-level 2D texture (sdk/pass.h); 0 means the output image's size. */
    fg_resource_desc desc = cgp_image_2d(GL_RGBA16F, width ? width : frame->width, height ? height : frame->height);
    fg_declare_output(decl, "color", &desc, FG_ACCESS_TRANSFER);
    return true;
}

static bool
fill_execute(fg_pass *pass, void *state, cg_error *err)
{
    (void)state;
    (void)err;
    const float rgba[4] = { fg_param_float(pass, "red"), fg_param_float(pass, "green"),
                            fg_param_float(pass, "blue"), fg_param_float(pass, "alpha") };
    glClearTexImage(fg_texture(pass, "color"), 0, GL_RGBA, GL_FLOAT, rgba);
    return true;
}

static const fg_pass_type fill_type = {
    .abi_version = EXAMPLE_PLUGIN_ABI,
    .name = "example_fill",
    .doc = "Example plugin pass: fills a 2D RGBA16F output ('color') with a constant colour "
           "(glClearTexImage). Shows how a pass module outside the tree is built and loaded.",
    CGP_PARAMS(fill_params),
    .declare = fill_declare,
    .execute = fill_execute,
};

/* conegraph_plugin_register(): refuses a host of another ABI (the bad-ABI build above), then
 * registers fill_type. */
CGP_PLUGIN(&fill_type);
