/* direct_light: outgoing radiance of the G-buffer's surfaces lit directly by every light
 * of the scene (the units of docs/architecture.md: shaders/common/lights.glsl), shadowed by the
 * optional shadow map (shaders/common/shadow.glsl) for the light it serves. Point lights
 * and lights without a map are unshadowed.
 *
 * The BSDF is glTF 2.0's (common/bsdf.glsl, Appendix B): f |n.l| E with f = rho/pi (1 - F) +
 * F D V, F by Schlick on v.h, v towards the camera, from the gbuffer's optional inputs specular
 * and material (and transmission: the ior). Without them, or where a pixel's material has no glossy
 * lobe (F0 = F90 = 0: the built-in scenes), the Lambertian albedo E cos/pi, the arithmetic as before.
 * Light from behind the surface (n.l < 0) is not used: through a solid it would have crossed its far
 * face first, a caustic, which the renderer's caustics-free light transport leaves out (the glass
 * shadows fully, docs/reference.md); a thin sheet's transmission lobe lit from behind is left out too, as
 * the path tracer's light sampling leaves it out (a shadow ray only towards the viewer's side), and
 * so is a BLEND layer's hole (ior 1), which passes light straight on to pixels that look at the
 * light itself. The diffuse lobe is reflection only (glTF has no diffuse transmission without
 * KHR_materials_diffuse_transmission): a thin sheet's side facing away from a light stays dark.
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
    /* The glossy lobe (gbuffer's outputs of the same names; transmission for its ior); Lambertian without. */
    fg_declare_input(decl, "specular", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    fg_declare_input(decl, "material", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    fg_declare_input(decl, "transmission", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
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
    bool glossy = fg_input_present(pass, "specular") && fg_input_present(pass, "material");
    bool transmission = glossy && fg_input_present(pass, "transmission");
    /* Absent inputs: the albedo stands in at their units, never read (u_glossy false). */
    glBindTextureUnit(6, glossy ? fg_texture(pass, "specular") : fg_texture(pass, "albedo"));
    glBindTextureUnit(7, glossy ? fg_texture(pass, "material") : fg_texture(pass, "albedo"));
    glBindTextureUnit(8, transmission ? fg_texture(pass, "transmission") : fg_texture(pass, "albedo"));
    glUniform1i(0, glossy);
    glUniform1i(1, transmission);
    /* v: towards the camera's position, or along its backward axis for an orthographic view. */
    glUniform3fv(2, 1, frame->view.position);
    glUniform3f(3, frame->view.inv_view[8], frame->view.inv_view[9], frame->view.inv_view[10]);
    glUniform1i(4, frame->view.orthographic);
    glBindImageTexture(0, fg_texture(pass, "radiance"), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    cgp_dispatch_2d(out->width, out->height);
    glUseProgram(0);
    return true;
}

CGP_PASS(direct_light, CGP_NO_PARAMS,
         "Outgoing radiance of the G-buffer's surfaces lit directly by every scene light: "
         "glTF 2.0's BSDF x cos x E (Lambertian albedo x E x cos / pi plus GGX highlights where the "
         "optional inputs specular and material are connected, transmission for the ior; light from "
         "behind a surface is not transmitted) with E from KHR_lights_punctual (directional: "
         "intensity x color; point: I/d^2; spot: I/d^2 with the smooth cone falloff). The light "
         "served by the optional shadow map (inputs shadow and shadow_matrix) is shadowed; "
         "the others, point lights included, are not.");
