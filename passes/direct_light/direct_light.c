/* direct_light: outgoing radiance of the G-buffer's surfaces lit directly by every light
 * of the scene (Lambertian, DESIGN.md units: shaders/common/lights.glsl), shadowed by the
 * optional shadow map (shaders/common/shadow.glsl) for the light it serves. Point lights
 * and lights without a map are unshadowed.
 */
#include <stdlib.h>
#include <string.h>

#include "sdk/pass.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

typedef struct direct_state {
    GLuint program;
} direct_state;

static bool
direct_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    const fg_resource_desc *position =
        fg_declare_input(decl, "position", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    fg_declare_input(decl, "normal", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    fg_declare_input(decl, "albedo", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    const fg_resource_desc *shadow =
        fg_declare_input(decl, "shadow", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    const fg_resource_desc *matrix =
        fg_declare_input(decl, "shadow_matrix", FG_BUFFER, FG_ACCESS_UNIFORM, false);
    if (!shadow != !matrix)
        return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                       "pass '%s': inputs 'shadow' and 'shadow_matrix' go together (a shadow_map "
                       "pass's outputs 'depth' and 'matrix'); only one is present", fg_pass_name(pass));
    if (shadow && shadow->format != GL_DEPTH_COMPONENT32F)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'shadow' must be a GL_DEPTH_COMPONENT32F shadow map",
                       fg_pass_name(pass));
    if (matrix && matrix->buffer_bytes < CG_SHADOW_BLOCK_BYTES)
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                       "pass '%s': input 'shadow_matrix' holds %zu bytes; a shadow_map 'matrix' "
                       "holds %d", fg_pass_name(pass), matrix->buffer_bytes, CG_SHADOW_BLOCK_BYTES);
    fg_resource_desc out = cgp_image_like(pass, position, GL_RGBA16F);
    fg_declare_output(decl, "radiance", &out, FG_ACCESS_IMAGE_STORE);
    return true;
}

static bool
direct_prepare(fg_pass *pass, void **state, cg_error *err)
{
    direct_state *st = cgp_state_new(pass, sizeof *st, err);
    if (!st)
        return false;
    if (!cg_program_compute("direct_light/direct.comp", NULL, &st->program, err)) {
        free(st);
        return false;
    }
    *state = st;
    return true;
}

static bool
direct_execute(fg_pass *pass, void *state, cg_error *err)
{
    (void)err;
    direct_state *st = state;
    const fg_frame *frame = fg_pass_frame(pass);
    const fg_resource_desc *out = fg_resource(pass, "radiance");

    glUseProgram(st->program);
    cg_gpu_scene_bind_lights(frame->gpu_scene);
    cg_gpu_scene_bind_shadow(frame->gpu_scene, fg_texture(pass, "shadow"), fg_buffer(pass, "shadow_matrix"), 5);
    glBindTextureUnit(2, fg_texture(pass, "position"));
    glBindTextureUnit(3, fg_texture(pass, "normal"));
    glBindTextureUnit(4, fg_texture(pass, "albedo"));
    glBindImageTexture(0, fg_texture(pass, "radiance"), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    cgp_dispatch_2d(out->width, out->height);
    glUseProgram(0);
    return true;
}

static void
direct_destroy(void *state)
{
    direct_state *st = state;
    if (!st)
        return;
    glDeleteProgram(st->program);
    free(st);
}

static const fg_pass_type direct_light_type = {
    .abi_version = FG_ABI_VERSION,
    .name = "direct_light",
    .doc = "Outgoing radiance of the G-buffer's surfaces lit directly by every scene light: "
           "Lambertian, albedo x E x cos / pi with E from KHR_lights_punctual (directional: "
           "intensity x color; point: I/d^2; spot: I/d^2 with the smooth cone falloff). The light "
           "served by the optional shadow map (inputs shadow and shadow_matrix) is shadowed; "
           "the others, point lights included, are not.",
    CGP_NO_PARAMS,
    .declare = direct_declare,
    .prepare = direct_prepare,
    .execute = direct_execute,
    .destroy = direct_destroy,
};

CGP_REGISTER_PASS(direct_light, direct_light_type)
