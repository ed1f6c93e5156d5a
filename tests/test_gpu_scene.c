/* cg_gpu_scene: what the upload holds (the light SSBO's layout that lights.glsl reads, byte
 * accounting), mesh filters, light updates, and draws with a program. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gpu_scene.h"
#include "cg/shader.h"
#include "passes/pass_fixtures.h"
#include "test_support.h"

static void
test_light_buffer_layout(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    fx_scene_init(&s);
    fx_add_quad(&s, 1, 0.0f, -1.0f, 1.0f, -1.0f, 1.0f, 0);
    cg_light *sun = fx_add_light(&s, CG_LIGHT_DIRECTIONAL, 2.0f);
    sun->color[1] = 0.5f;
    sun->direction[0] = 3.0f;   /* not unit length: the upload normalises */
    sun->direction[1] = -4.0f;
    cg_light *spot = fx_add_light(&s, CG_LIGHT_SPOT, 8.0f);
    spot->position[0] = 1.0f;
    spot->position[1] = 2.0f;
    spot->position[2] = 3.0f;
    spot->range = 5.0f;
    spot->inner_cone_angle = 0.2f;
    spot->outer_cone_angle = 0.5f;
    fx_scene_finish(&s);
    cg_error err = { 0 };
    cg_gpu_scene gpu;
    assert_cg_ok(cg_gpu_scene_upload(&s.scene, &gpu, &err), &err);

    float data[4 + 2 * 16];
    glGetNamedBufferSubData(gpu.light_buffer, 0, sizeof data, data);
    uint32_t count;
    memcpy(&count, data, sizeof count);
    assert_int_equal(count, 2);
    const float *l0 = data + 4, *l1 = data + 4 + 16;
    assert_float_equal(l0[3], 0.0, 0.0);                /* type directional */
    assert_float_equal(l0[4], 0.6, 1e-6);               /* direction normalised */
    assert_float_equal(l0[5], -0.8, 1e-6);
    assert_float_equal(l0[8], 2.0, 1e-6);               /* color x intensity */
    assert_float_equal(l0[9], 1.0, 1e-6);
    assert_float_equal(l1[0], 1.0, 0.0);                /* position */
    assert_float_equal(l1[2], 3.0, 0.0);
    assert_float_equal(l1[3], 2.0, 0.0);                /* type spot */
    assert_float_equal(l1[7], 5.0, 0.0);                /* range */
    assert_float_equal(l1[8], 8.0, 1e-6);
    double scale = 1.0 / (cos(0.2) - cos(0.5));
    assert_float_equal(l1[12], scale, 1e-3 * scale);
    assert_float_equal(l1[13], -cos(0.5) * scale, 1e-3 * scale);

    /* Moving the sun and updating keeps the buffer; changing the light count is refused. */
    sun->intensity = 4.0f;
    assert_cg_ok(cg_gpu_scene_update_lights(&gpu, &err), &err);
    glGetNamedBufferSubData(gpu.light_buffer, 0, sizeof data, data);
    assert_float_equal(l0[8], 4.0, 1e-6);
    s.scene.light_count = 1;
    assert_cg_status(cg_gpu_scene_update_lights(&gpu, &err), &err, CG_ERR_USAGE);
    s.scene.light_count = 2;
    cg_gpu_scene_destroy(&gpu);
    assert_no_gl_errors(ctx);
}

static void
test_filters_bytes_and_draw(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    fx_scene_init(&s);
    fx_add_quad(&s, 1, 0.0f, -1.0f, 1.0f, -1.0f, 1.0f, 0);
    fx_add_quad(&s, 2, 0.0f, -1.0f, 1.0f, -1.0f, 1.0f, 0);
    static uint8_t texels[4 * 4 * 4];
    s.textures[0] = (cg_texture){ .name = "t", .width = 4, .height = 4, .rgba = texels, .srgb = true };
    s.scene.texture_count = 1;
    fx_scene_finish(&s);
    cg_error err = { 0 };
    cg_gpu_scene gpu;
    assert_cg_ok(cg_gpu_scene_upload(&s.scene, &gpu, &err), &err);
    assert_true(cg_gpu_scene_has(&gpu, CG_MESHES_ALL));
    assert_true(cg_gpu_scene_has(&gpu, CG_MESHES_COMPLEX));
    assert_false(cg_gpu_scene_has(&gpu, CG_MESHES_HEIGHTFIELD));
    /* Two quads (4 vertices x 48 bytes: position, normal, texcoord, tangent; + 6 indices x 4), one
     * material (320), a 4x4 texture with its mips (64 + 16 + 4 texels x 4 bytes), the white texture
     * (4), no lights (16-byte header). */
    size_t expected = 2 * (4 * 48 + 6 * 4) + 320 + (16 + 4 + 1) * 4 + 4 + 16;
    assert_int_equal(gpu.bytes, expected);

    GLuint program;
    assert_cg_ok(cg_program_graphics("shadow_map/depth.vert", NULL, NULL, NULL, &program, &err), &err);
    GLuint fbo, depth;
    glCreateTextures(GL_TEXTURE_2D, 1, &depth);
    glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 8, 8);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, 8, 8);
    glUseProgram(program);
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    glUniformMatrix4fv(8, 1, GL_FALSE, identity);
    assert_int_equal(cg_gpu_scene_draw(&gpu, CG_MESHES_ALL), 4);
    assert_int_equal(cg_gpu_scene_draw(&gpu, CG_MESHES_COMPLEX), 4);
    assert_int_equal(cg_gpu_scene_draw(&gpu, CG_MESHES_HEIGHTFIELD), 0);
    s.meshes[1].kind = CG_MESH_HEIGHTFIELD;
    cg_gpu_scene_destroy(&gpu);
    assert_cg_ok(cg_gpu_scene_upload(&s.scene, &gpu, &err), &err);
    assert_true(cg_gpu_scene_has(&gpu, CG_MESHES_HEIGHTFIELD));
    assert_int_equal(cg_gpu_scene_draw(&gpu, CG_MESHES_HEIGHTFIELD), 2);
    assert_int_equal(cg_gpu_scene_draw(&gpu, CG_MESHES_COMPLEX), 2);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &depth);
    glDeleteProgram(program);
    cg_gpu_scene_destroy(&gpu);
    assert_no_gl_errors(ctx);
}

/* The material SSBO holds every field scene.glsl's CgMaterial names, where it names it: textures
 * the scene lacks read as none (-1), sigma = -ln(attenuation colour) / distance, the uv transforms
 * two vec4s each; and the vertex buffer carries the tangents (zero where the mesh has none). */
static void
test_material_buffer_layout(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    fx_scene s;
    fx_scene_init(&s);
    int m = fx_add_material(&s, 0.1f, 0.2f, 0.3f);
    cg_material *mat = &s.materials[m];
    mat->base_color[3] = 0.4f;
    mat->emissive[0] = 2.0f;
    mat->emissive_strength = 3.0f;
    mat->alpha_cutoff = 0.25f;
    mat->alpha_mode = CG_ALPHA_MASK;
    mat->double_sided = false;
    mat->base_color_texture = 0;
    mat->metallic_roughness_texture = 0;
    mat->normal_texture = 7;             /* the scene has one texture: none */
    mat->occlusion_texture = 0;
    mat->transmission_texture = -1;
    mat->metallic = 0.6f;
    mat->roughness = 0.7f;
    mat->normal_scale = 0.8f;
    mat->occlusion_strength = 0.9f;
    mat->specular = 0.5f;
    mat->specular_color[2] = 0.25f;
    mat->ior = 1.33f;
    mat->transmission = 0.75f;
    mat->thickness = 0.125f;
    mat->attenuation_distance = 2.0f;
    mat->attenuation_color[0] = 0.5f;
    mat->uv[CG_TEX_NORMAL] = (cg_uv_transform){ { 1, 2, 3, 4, 5, 6 } };
    static uint8_t texels[4] = { 255, 255, 255, 255 };
    s.textures[0] = (cg_texture){ .name = "t", .width = 1, .height = 1, .rgba = texels };
    s.scene.texture_count = 1;
    fx_add_quad(&s, 1, 0.0f, -1.0f, 1.0f, -1.0f, 1.0f, m);
    static float tangents[16] = { 1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1 };
    s.meshes[0].tangents = tangents;
    fx_add_quad(&s, 1, 1.0f, -1.0f, 1.0f, -1.0f, 1.0f, 0);
    fx_scene_finish(&s);
    cg_error err = { 0 };
    cg_gpu_scene gpu;
    assert_cg_ok(cg_gpu_scene_upload(&s.scene, &gpu, &err), &err);

    float f[80];
    int32_t i[80];
    glGetNamedBufferSubData(gpu.material_buffer, 320 * m, sizeof f, f);
    memcpy(i, f, sizeof i);
    assert_float_equal(f[0], 0.1, 1e-7);
    assert_float_equal(f[3], 0.4, 1e-7);
    assert_float_equal(f[4], 6.0, 1e-6);                /* emissive x strength */
    assert_float_equal(f[7], 0.25, 0.0);                /* alpha cutoff */
    assert_int_equal(i[8], 0);                          /* base colour texture */
    assert_int_equal(i[9], -1);                         /* emissive: none */
    assert_int_equal(i[10], 0);                         /* metallicRoughness */
    assert_int_equal(i[11], -1);                        /* normal: index 7 is not in the scene */
    assert_int_equal(i[12], 0);                         /* occlusion */
    assert_int_equal(i[13], -1);                        /* transmission */
    assert_int_equal(i[14], CG_ALPHA_MASK);
    assert_int_equal(i[15], 0);                         /* single-sided */
    assert_float_equal(f[16], 0.6, 1e-7);
    assert_float_equal(f[17], 0.7, 1e-7);
    assert_float_equal(f[18], 0.8, 1e-7);
    assert_float_equal(f[19], 0.9, 1e-7);
    assert_float_equal(f[22], 0.25, 0.0);               /* specular colour b */
    assert_float_equal(f[23], 0.5, 0.0);                /* specular factor */
    assert_float_equal(f[24], 1.33, 1e-6);              /* ior */
    assert_float_equal(f[25], 0.75, 0.0);
    assert_float_equal(f[26], 0.125, 0.0);
    assert_float_equal(f[28], -log(0.5) / 2.0, 1e-6);   /* sigma, 1/m */
    assert_float_equal(f[29], 0.0, 0.0);
    for (int k = 0; k < 4; k++)                         /* uv[2 x CG_TEX_NORMAL]: m0..m3 */
        assert_float_equal(f[32 + 8 * CG_TEX_NORMAL + k], 1.0 + k, 0.0);
    assert_float_equal(f[32 + 8 * CG_TEX_NORMAL + 4], 5.0, 0.0);
    assert_float_equal(f[32 + 8 * CG_TEX_NORMAL + 5], 6.0, 0.0);
    assert_float_equal(f[32 + 8 * CG_TEX_BASE_COLOR + 0], 1.0, 0.0);   /* identity elsewhere */
    assert_float_equal(f[32 + 8 * CG_TEX_BASE_COLOR + 4], 0.0, 0.0);

    /* Material 0 is double-sided. */
    glGetNamedBufferSubData(gpu.material_buffer, 0, 16 * sizeof(float), f);
    memcpy(i, f, sizeof i);
    assert_int_equal(i[15], CG_GPU_MATERIAL_DOUBLE_SIDED);

    float vertex[2][CG_GPU_VERTEX_FLOATS];
    glGetNamedBufferSubData(gpu.meshes[0].vertex_buffer, 0, sizeof vertex[0], vertex[0]);
    glGetNamedBufferSubData(gpu.meshes[1].vertex_buffer, 0, sizeof vertex[1], vertex[1]);
    assert_float_equal(vertex[0][8], 1.0, 0.0);
    assert_float_equal(vertex[0][11], -1.0, 0.0);
    for (int k = 8; k < 12; k++)
        assert_float_equal(vertex[1][k], 0.0, 0.0);
    cg_gpu_scene_destroy(&gpu);
    assert_no_gl_errors(ctx);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_light_buffer_layout),
             cmocka_unit_test(test_material_buffer_layout),
             cmocka_unit_test(test_filters_bytes_and_draw))
