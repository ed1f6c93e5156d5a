/* gbuffer: the visible surface of every pixel of the output image, in world space.
 *
 * Outputs (all the output image's size): depth (GL_DEPTH_COMPONENT32F), position
 * (RGBA32F world position, w = 1 where a surface covers the pixel, 0 on the background),
 * normal (RGBA16F shading normal, the normal map applied, turned towards the camera; a height
 * field's upper side, see gbuffer.frag), emissive (RGBA32F emitted radiance) and the material
 * of glTF 2.0's BSDF (common/bsdf.glsl, cg/bsdf.h) in RGBA16F:
 *   albedo        rgb = the diffuse weight rho = (1-m)(1-T) baseColor (x coverage for BLEND),
 *                 a = occlusion 1 + strength (occ - 1) (1 = none; it darkens indirect light only)
 *   specular      rgb = F0 (metal and dielectric mixed by metallic), a = F90
 *   transmission  rgb = tau = (1-m) T baseColor (BLEND: alpha tau + (1 - alpha)), a = ior
 *   material      x = perceptual roughness, y = metallic, z = thickness in world metres (0 thin), w = 1
 *   attenuation   rgb = Beer-Lambert sigma (1/m, 0 = none), a = 1
 * A Lambertian material (cg_material_default) gives albedo = baseColor, specular 0,
 * transmission (0, 0, 0, ior): what direct_light and composite read is what it was before.
 * alphaMode MASK discards below the cutoff; a single-sided material's back faces are not seen
 * (glTF doubleSided false: discarded by gl_FrontFacing, which cg_gpu_scene_draw sets per instance).
 *
 * The world position is stored rather than reconstructed from depth: a perspective fp32
 * depth buffer loses ~z^2/near x 6e-8 metres, about half a metre at 1 km with a 10 cm
 * near plane, which shadow lookups and cone origins in an open world cannot afford.
 * Albedo is 16-bit float because 8-bit linear values band in dark albedos (1/255 is 8%
 * of an albedo of 0.05), and the indirect light is multiplied by it. Normal and albedo lie in
 * [-1, 1] and [0, 1], where half floats keep 11 bits; emitted radiance has no such bound (the
 * sun's disc is 2e7 W/sr/m^2) and goes in fp32, as direct_light's output.
 *
 * The background: where no surface covers the pixel, `emissive` holds the scene's sky in the
 * pixel's view direction (alpha stays 0), the emission the camera sees there, as the path
 * tracer's `emitted` part holds it; so composite shows it, and a graph's own direct image
 * (composite's direct + emissive, what `compare --direct` and bench take) holds it as the
 * reference's does. It is the pass SDK's baked sky (sdk/sky.h, layer 0), the texture the cone
 * tracers gather; with no sky nothing is dispatched.
 */
#include <stdlib.h>

#include "sdk/pass.h"
#include "sdk/sky.h"
#include "cg/fg.h"
#include "cg/gpu_scene.h"
#include "cg/shader.h"

static const char *const color_outputs[] = { "position", "normal", "albedo", "emissive",
                                            "specular", "transmission", "material", "attenuation" };
static const GLenum color_formats[] = { GL_RGBA32F, GL_RGBA16F, GL_RGBA16F, GL_RGBA32F,
                                        GL_RGBA16F, GL_RGBA16F, GL_RGBA16F, GL_RGBA16F };
/* GL 4.5 guarantees GL_MAX_DRAW_BUFFERS >= 8: the material takes every one of them. */
#define COLOR_OUTPUTS 8
#define EMISSIVE 3          /* color_outputs[EMISSIVE] */

typedef struct gbuffer_state {
    GLuint program;
    GLuint fbo;
    GLuint sky_program;     /* 0 until a frame has a sky */
    cgp_sky sky;
    fg_slot depth, color[COLOR_OUTPUTS];
} gbuffer_state;

static bool
gbuffer_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)err;
    fg_resource_desc desc = cgp_image_like(pass, NULL, GL_DEPTH_COMPONENT32F);
    fg_declare_output(decl, "depth", &desc, FG_ACCESS_ATTACHMENT);
    for (int i = 0; i < COLOR_OUTPUTS; i++) {
        desc.format = color_formats[i];
        fg_declare_output(decl, color_outputs[i], &desc, FG_ACCESS_ATTACHMENT);
    }
    return true;
}

static bool
gbuffer_prepare(fg_pass *pass, gbuffer_state *st, cg_error *err)
{
    st->depth = fg_pass_slot(pass, "depth");
    for (int i = 0; i < COLOR_OUTPUTS; i++)
        st->color[i] = fg_pass_slot(pass, color_outputs[i]);
    st->fbo = cgp_framebuffer(st);
    static const GLenum draw_buffers[COLOR_OUTPUTS] = {
        GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3,
        GL_COLOR_ATTACHMENT4, GL_COLOR_ATTACHMENT5, GL_COLOR_ATTACHMENT6, GL_COLOR_ATTACHMENT7,
    };
    glNamedFramebufferDrawBuffers(st->fbo, COLOR_OUTPUTS, draw_buffers);
    cgp_sky_prepare(st, &st->sky);
    return cgp_graphics_program(st, "gbuffer/gbuffer.vert", NULL, "gbuffer/gbuffer.frag", NULL, &st->program, err);
}

/* The sky where no surface is (see the top of this file). */
static bool
background_sky(fg_pass *pass, gbuffer_state *st, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    if (!cgp_sky_update(st, &st->sky, frame->scene, err))
        return false;
    if (!st->sky.present)
        return true;
    if (!st->sky_program &&
        !cgp_compute_program(st, "gbuffer/sky.comp", NULL, &st->sky_program, err))
        return false;
    /* The draw's writes reach the image loads below. */
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(st->sky_program);
    cgp_sky_bind(&st->sky);
    glUniformMatrix4fv(0, 1, GL_FALSE, frame->view.inv_proj);
    glUniformMatrix4fv(1, 1, GL_FALSE, frame->view.inv_view);
    glUniform1i(2, frame->view.orthographic);
    glBindImageTexture(0, fg_slot_texture(pass, st->color[EMISSIVE]), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    cgp_dispatch_2d(frame->width, frame->height);
    cgp_sky_unbind();
    glUseProgram(0);
    /* Readers sample the attachment the frame graph knows as written by rendering. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    return true;
}

static bool
gbuffer_execute(fg_pass *pass, gbuffer_state *st, cg_error *err)
{
    const fg_frame *frame = fg_pass_frame(pass);
    /* Pooled storage may hand this pass other textures from frame to frame: attach each time. */
    glNamedFramebufferTexture(st->fbo, GL_DEPTH_ATTACHMENT, fg_slot_texture(pass, st->depth), 0);
    for (int i = 0; i < COLOR_OUTPUTS; i++)
        glNamedFramebufferTexture(st->fbo, GL_COLOR_ATTACHMENT0 + (GLenum)i,
                                  fg_slot_texture(pass, st->color[i]), 0);
    GLenum status = glCheckNamedFramebufferStatus(st->fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return cg_fail(err, CG_ERR_GL, "pass '%s': G-buffer framebuffer incomplete (0x%x)",
                       fg_pass_name(pass), status);

    cgp_depth_draw_begin(st->fbo, frame->width, frame->height);
    glDisable(GL_BLEND);
    static const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
    const float far_depth = 1.0f;
    for (int i = 0; i < COLOR_OUTPUTS; i++)
        glClearNamedFramebufferfv(st->fbo, GL_COLOR, i, zero);
    glClearNamedFramebufferfv(st->fbo, GL_DEPTH, 0, &far_depth);
    glUseProgram(st->program);
    glUniformMatrix4fv(8, 1, GL_FALSE, frame->view.view_proj);
    /* Height fields apart: their normals are turned up where a silhouette shows a back face
     * (gbuffer.frag). */
    glUniform1i(9, 0);
    cg_gpu_scene_draw(frame->gpu_scene, CG_MESHES_COMPLEX);
    glUniform1i(9, 1);
    cg_gpu_scene_draw(frame->gpu_scene, CG_MESHES_HEIGHTFIELD);
    glUseProgram(0);
    cgp_depth_draw_end();
    return background_sky(pass, st, err);
}

CGP_PASS(gbuffer, CGP_NO_PARAMS,
         "The visible surface of each pixel of the output image: depth, world position "
         "(w = 1 where covered), shading normal facing the camera, emitted radiance and glTF 2.0's "
         "BSDF (albedo = diffuse weight and occlusion, specular = F0 and F90, transmission = "
         "tint and ior, material = roughness, metallic, thickness, attenuation = sigma), and on "
         "the background the scene's sky as the emission the camera sees. "
         "Deferred shading's G-buffer; the VCT paper's cones start from it.");
