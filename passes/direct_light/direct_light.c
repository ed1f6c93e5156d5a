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
 *
 * Shadow cones (VCT paper 3.2.3, "soft shadows"): the optional input `visibility` (a cone_gather's
 * output of that name, with shadow_cone = true) is the transmittance of a cone from each pixel
 * towards one light, `visibility_light` (the gather's shadow_light); where it is connected it
 * darkens that light in place of the shadow map (which keeps serving its own light if that is
 * another one). A sun with an angular diameter is the gather's cone, so its penumbra widens with
 * the occluder's distance as the path tracer's does (docs/passes.md, "Shadow cones").
 */
#include <stdlib.h>
#include <string.h>

#include "sdk/pass.h"
#include "sdk/shadow.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

static const fg_param_desc direct_light_params[] = {
    { .name = "visibility_light", .type = FG_PARAM_INT, .min = 0, .max = 65535,
      .doc = "index of the scene light that the optional input 'visibility' (cone_gather's shadow cone) shadows "
             "in place of the shadow map; the gather's shadow_light" },
};

typedef struct direct_light_state {
    GLuint program;
    cgp_no_shadow no_shadow;
    fg_slot position, normal, albedo, specular, material, transmission, visibility, radiance;
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
    /* The shadow cone's transmittance, per pixel of the same image (its red channel is read). */
    const fg_resource_desc *visibility =
        fg_declare_input(decl, "visibility", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    if (visibility && position && (visibility->width != position->width || visibility->height != position->height))
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'visibility' is %dx%d, the G-buffer %dx%d: the shadow cone's "
                       "visibility must be a gather's output at the image's size", fg_pass_name(pass),
                       visibility->width, visibility->height, position->width, position->height);
    fg_resource_desc out = cgp_image_like(pass, position, GL_RGBA32F);
    fg_declare_output(decl, "radiance", &out, FG_ACCESS_IMAGE_STORE);
    return true;
}

static bool
direct_light_prepare(fg_pass *pass, direct_light_state *st, cg_error *err)
{
    CGP_SLOTS(pass, st, position, normal, albedo, specular, material, transmission, visibility, radiance);
    cgp_no_shadow_create(st, pass, &st->no_shadow);
    return cgp_compute_program(st, "direct_light/direct.comp", NULL, &st->program, err);
}

static bool
direct_light_execute(fg_pass *pass, direct_light_state *st, cg_error *err)
{
    (void)err;
    const fg_frame *frame = fg_pass_frame(pass);
    GLuint albedo = fg_slot_texture(pass, st->albedo);

    glUseProgram(st->program);
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cgp_bind_shadow(pass, &st->no_shadow, 5);
    glBindTextureUnit(2, fg_slot_texture(pass, st->position));
    glBindTextureUnit(3, fg_slot_texture(pass, st->normal));
    glBindTextureUnit(4, albedo);
    /* Absent inputs: the albedo stands in at their units, never read (u_glossy false). */
    bool specular = cgp_bind_optional(pass, 6, st->specular, albedo);
    bool glossy = cgp_bind_optional(pass, 7, st->material, albedo) && specular;
    bool transmission = cgp_bind_optional(pass, 8, st->transmission, albedo) && glossy;
    glUniform1i(0, glossy);
    glUniform1i(1, transmission);
    /* v: towards the camera's position, or along its backward axis for an orthographic view. */
    glUniform3fv(2, 1, frame->view.position);
    glUniform3f(3, frame->view.inv_view[8], frame->view.inv_view[9], frame->view.inv_view[10]);
    glUniform1i(4, frame->view.orthographic);
    /* Without the input no light index matches (-1), and the albedo stands in at unit 9, never read. */
    bool cone = cgp_bind_optional(pass, 9, st->visibility, albedo);
    glUniform1i(5, cone ? fg_param_int(pass, "visibility_light") : -1);
    glBindImageTexture(0, fg_slot_texture(pass, st->radiance), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    cgp_dispatch_over(pass, st->radiance);
    glUseProgram(0);
    return true;
}

CGP_PASS(direct_light, CGP_PARAMS(direct_light_params),
         "Outgoing radiance of the G-buffer's surfaces lit directly by every scene light: "
         "glTF 2.0's BSDF x cos x E (Lambertian albedo x E x cos / pi plus GGX highlights where the "
         "optional inputs specular and material are connected, transmission for the ior; light from "
         "behind a surface is not transmitted) with E from KHR_lights_punctual (directional: "
         "intensity x color; point: I/d^2; spot: I/d^2 with the smooth cone falloff). The light "
         "served by the optional shadow map (inputs shadow and shadow_matrix) is shadowed; "
         "the others, point lights included, are not. The optional input visibility (cone_gather's "
         "shadow cone, VCT paper 3.2.3) shadows the light visibility_light instead of the shadow map.");
