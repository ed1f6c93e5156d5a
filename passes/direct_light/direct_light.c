/* direct_light: outgoing radiance of the G-buffer's surfaces lit directly by every light
 * of the scene (Lambertian, the units of docs/architecture.md: shaders/common/lights.glsl), shadowed by the
 * optional shadow map (shaders/common/shadow.glsl) for the light it serves. Point lights
 * and lights without a map are unshadowed.
 *
 * Output `radiance` is RGBA32F: a half float clips at 65504 W/sr/m^2 (a white surface under
 * 2e5 W/m^2; 1e9 W/m^2 gives 3e8) and loses precision below 6e-5 (starlight's 1e-6 W/m^2 lights
 * a white surface at 3e-7); fp32 holds 1e-38 to 3e38 at full precision for 8 more bytes a pixel
 * (docs/architecture.md, "Radiance range").
 */
#include <stdlib.h>
#include <string.h>

#include "sdk/pass.h"
#include "sdk/shadow.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

typedef struct direct_light_state {
    GLuint program;
    cgp_no_shadow no_shadow;
} direct_light_state;

static bool
direct_light_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *position =
        fg_declare_input(decl, "position", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    fg_declare_input(decl, "normal", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    fg_declare_input(decl, "albedo", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    if (!cgp_declare_shadow_inputs(pass, decl, err))
        return false;
    fg_resource_desc out = cgp_image_like(pass, position, GL_RGBA32F);
    fg_declare_output(decl, "radiance", &out, FG_ACCESS_IMAGE_STORE);
    return true;
}

static bool
direct_light_prepare(fg_pass *pass, direct_light_state *st, cg_error *err)
{
    (void)pass;
    cgp_no_shadow_create(st, &st->no_shadow);
    return cgp_compute_program(st, "direct_light/direct.comp", NULL, &st->program, err);
}

static bool
direct_light_execute(fg_pass *pass, direct_light_state *st, cg_error *err)
{
    (void)err;
    const fg_frame *frame = fg_pass_frame(pass);
    const fg_resource_desc *out = fg_resource(pass, "radiance");

    glUseProgram(st->program);
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &st->no_shadow, 5);
    glBindTextureUnit(2, fg_texture(pass, "position"));
    glBindTextureUnit(3, fg_texture(pass, "normal"));
    glBindTextureUnit(4, fg_texture(pass, "albedo"));
    glBindImageTexture(0, fg_texture(pass, "radiance"), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    cgp_dispatch_2d(out->width, out->height);
    glUseProgram(0);
    return true;
}

CGP_PASS(direct_light, CGP_NO_PARAMS,
         "Outgoing radiance of the G-buffer's surfaces lit directly by every scene light: "
         "Lambertian, albedo x E x cos / pi with E from KHR_lights_punctual (directional: "
         "intensity x color; point: I/d^2; spot: I/d^2 with the smooth cone falloff). The light "
         "served by the optional shadow map (inputs shadow and shadow_matrix) is shadowed; "
         "the others, point lights included, are not.");
