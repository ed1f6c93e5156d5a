/* composite: the final image. hdr = direct + albedo.rgb x indirect x albedo.a + reflection +
 * refraction + emissive (linear radiance, RGBA32F, what .exr files hold); ldr = hdr x 2^exposure,
 * tonemapped, sRGB-encoded (RGBA8 holding sRGB-encoded values, what .png files hold).
 *
 * Convention with the gather passes (docs/passes.md): the `indirect` input holds the
 * gathered incident radiance integral divided by pi (x the diffuse lobe's Fresnel share where the
 * gather has the material), so that the outgoing diffuse radiance is albedo x indirect (VCT paper
 * 3.2: the diffuse cones' weighted sum), darkened by the G-buffer's occlusion (albedo.a: the glTF
 * occlusion texture darkens indirect light only; 1 = none). `reflection` and `refraction` (a cone
 * gather's specular and refracted cones, VCT paper 3.2.2) are radiance already weighted by the
 * BSDF, added as they are; both optional, so graphs without them are unchanged.
 */
#include <math.h>
#include <stdlib.h>

#include "sdk/pass.h"
#include "cg/fg.h"
#include "cg/shader.h"

enum { TONEMAP_NONE, TONEMAP_REINHARD, TONEMAP_ACES };

static const fg_param_desc composite_params[] = {
    { .name = "exposure", .type = FG_PARAM_FLOAT, .stage = FG_STAGE_FRAME, .min = -20.0, .max = 20.0,
      .step = 0.5,
      .doc = "exposure of the ldr output in EV: radiance is scaled by 2^exposure before the tonemap (hdr is not)" },
    { .name = "tonemap", .type = FG_PARAM_ENUM, .stage = FG_STAGE_FRAME, .default_value = TONEMAP_ACES, .choices = "none|reinhard|aces",
      .doc = "tonemap operator of the ldr output: clamp, Reinhard on luminance, or the Narkowicz ACES fit" },
};

/* The optional inputs, declared and found by these names. */
enum { INDIRECT, ALBEDO, EMISSIVE, REFLECTION, REFRACTION, OPTIONAL_INPUTS };
static const char *const optional_names[OPTIONAL_INPUTS] = { "indirect", "albedo", "emissive", "reflection",
                                                             "refraction" };

typedef struct composite_state {
    GLuint program;
    fg_slot direct, optional[OPTIONAL_INPUTS], hdr, ldr;
} composite_state;

static bool
same_size(const fg_resource_desc *a, const fg_resource_desc *b)
{
    return a->width == b->width && a->height == b->height;
}

static bool
composite_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *direct =
        fg_declare_input(decl, "direct", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    const fg_resource_desc *inputs[OPTIONAL_INPUTS];
    for (int i = 0; i < OPTIONAL_INPUTS; i++)
        inputs[i] = fg_declare_input(decl, optional_names[i], FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    if (inputs[INDIRECT] && !inputs[ALBEDO])
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': input 'indirect' needs 'albedo' (outgoing = albedo x indirect)",
                       fg_pass_name(pass));
    for (int i = 0; i < OPTIONAL_INPUTS; i++)
        if (direct && inputs[i] && !same_size(direct, inputs[i]))
            return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                           "pass '%s': input '%s' is %dx%d, input 'direct' %dx%d; composite reads "
                           "them pixel for pixel", fg_pass_name(pass), optional_names[i], inputs[i]->width,
                           inputs[i]->height, direct->width, direct->height);
    fg_resource_desc out = cgp_image_like(pass, direct, GL_RGBA32F);
    fg_declare_output(decl, "hdr", &out, FG_ACCESS_IMAGE_STORE);
    out.format = GL_RGBA8;
    fg_declare_output(decl, "ldr", &out, FG_ACCESS_IMAGE_STORE);
    return true;
}

static bool
composite_prepare(fg_pass *pass, composite_state *st, cg_error *err)
{
    CGP_SLOTS(pass, st, direct, hdr, ldr);
    for (int i = 0; i < OPTIONAL_INPUTS; i++)
        st->optional[i] = fg_pass_slot(pass, optional_names[i]);
    return cgp_compute_program(st, "composite/composite.comp", NULL, &st->program, err);
}

static bool
composite_execute(fg_pass *pass, composite_state *st, cg_error *err)
{
    (void)err;
    GLuint direct = fg_slot_texture(pass, st->direct);

    glUseProgram(st->program);
    /* Absent inputs are never read (the flags say so); the direct image stands in at their units,
     * input i at unit i + 1. */
    glBindTextureUnit(0, direct);
    bool present[OPTIONAL_INPUTS];
    for (int i = 0; i < OPTIONAL_INPUTS; i++)
        present[i] = cgp_bind_optional(pass, (GLuint)i + 1, st->optional[i], direct);
    glUniform1i(0, present[INDIRECT]);
    glUniform1i(1, present[EMISSIVE]);
    glUniform1i(4, present[REFLECTION]);
    glUniform1i(5, present[REFRACTION]);
    glUniform1f(2, exp2f(fg_param_float(pass, "exposure")));
    glUniform1i(3, fg_param_enum(pass, "tonemap"));
    glBindImageTexture(0, fg_slot_texture(pass, st->hdr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, fg_slot_texture(pass, st->ldr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    cgp_dispatch_over(pass, st->hdr);
    glUseProgram(0);
    return true;
}

CGP_PASS(composite, CGP_PARAMS(composite_params),
         "The final image: hdr = direct + albedo x indirect x occlusion + reflection + refraction + "
         "emissive, linear radiance (RGBA32F); ldr = hdr x 2^exposure, tonemapped and sRGB-encoded "
         "(RGBA8). The optional indirect input holds the gathered incident radiance integral over pi, "
         "so that outgoing = albedo x indirect (occlusion: albedo's alpha); the optional reflection and "
         "refraction inputs (a cone gather's specular and refracted cones) are weighted radiance.");
