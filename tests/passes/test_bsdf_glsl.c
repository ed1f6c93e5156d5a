/* The GLSL BSDF (shaders/common/bsdf.glsl, cg_bsdf_from_material of common/scene.glsl) against the
 * C one (cg/bsdf.h) on the same inputs: materials uploaded by cg_gpu_scene (so the upload's packing
 * is checked too), a grid of view and light directions around a tilted normal, reflection and
 * transmission, both sides of a solid's interface; every function the GLSL side mirrors (D, V, G1,
 * Schlick, the dielectric Fresnel, the surface's parameters, f |n.l| per lobe and all together, the
 * diffuse lobe's hemispherical albedo whose constants the C albedo terms give)
 * evaluated by a compute shader (tests/data/shaders/bsdf/bsdf_eval.comp) on the headless context's
 * software GL and compared with the C functions, value by value. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/bsdf.h"
#include "cg/shader.h"
#include "pass_fixtures.h"
#include "test_support.h"

#define TEST_VEC4 12    /* vec4s a case writes: bsdf_eval.comp's CG_BSDF_TEST_VEC4 */
#define MAX_CASES 4096

typedef struct bsdf_case {
    float n[4], v[4], l[4], params[4];
    float dots[4];  /* n.h, n.l, n.v, v.h (h = normalize(v + l); 0 where v + l = 0): bsdf_eval.comp */
} bsdf_case;

static void
normalize3(float a[3])
{
    float len = sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++)
        a[k] /= len;
}

/* A unit direction at cosine c from n and azimuth phi about it. */
static void
direction(const float n[3], const float t[3], const float s[3], float c, float phi, float out[3])
{
    float sn = sqrtf(fmaxf(0.0f, 1.0f - c * c));
    for (int k = 0; k < 3; k++)
        out[k] = sn * cosf(phi) * t[k] + sn * sinf(phi) * s[k] + c * n[k];
    normalize3(out);
}

/* Materials the GLSL side reads from the SSBO and the C side from cg_material: one of each kind. */
static void
build_materials(fx_scene *s)
{
    fx_scene_init(s);   /* material 0: white, Lambertian (specular 0) */
    int m;
    m = fx_add_material(s, 0.8f, 0.5f, 0.3f);   /* dielectric, KHR_materials_specular colour */
    s->materials[m].roughness = 0.5f;
    s->materials[m].specular = 1.0f;
    s->materials[m].specular_color[1] = 0.9f;
    s->materials[m].specular_color[2] = 0.8f;
    m = fx_add_material(s, 1.0f, 0.78f, 0.34f);  /* gold */
    s->materials[m].metallic = 1.0f;
    s->materials[m].roughness = 0.3f;
    s->materials[m].specular = 1.0f;
    m = fx_add_material(s, 0.3f, 0.6f, 0.9f);    /* metallic 0.4: the spec's mix */
    s->materials[m].metallic = 0.4f;
    s->materials[m].roughness = 0.7f;
    s->materials[m].specular = 0.7f;
    s->materials[m].ior = 1.33f;
    m = fx_add_material(s, 0.9f, 1.0f, 0.95f);   /* thin-walled glass */
    s->materials[m].transmission = 1.0f;
    s->materials[m].roughness = 0.2f;
    s->materials[m].specular = 1.0f;
    m = fx_add_material(s, 1.0f, 1.0f, 1.0f);    /* solid glass with attenuation */
    s->materials[m].transmission = 0.9f;
    s->materials[m].roughness = 0.35f;
    s->materials[m].specular = 1.0f;
    s->materials[m].ior = 1.45f;
    s->materials[m].thickness = 0.1f;
    s->materials[m].attenuation_distance = 2.0f;
    s->materials[m].attenuation_color[0] = 0.5f;
    s->materials[m].attenuation_color[1] = 0.8f;
    s->materials[m].attenuation_color[2] = 0.9f;
    m = fx_add_material(s, 0.95f, 0.95f, 0.95f); /* smooth metal: delta lobes, eval 0 */
    s->materials[m].metallic = 1.0f;
    s->materials[m].roughness = 0.02f;
    s->materials[m].specular = 1.0f;
    m = fx_add_material(s, 0.2f, 0.7f, 0.3f);    /* rough dielectric */
    s->materials[m].roughness = 1.0f;
    s->materials[m].specular = 1.0f;
    fx_add_quad(s, 1, 0.0f, -1.0f, 1.0f, -1.0f, 1.0f, 0);
    fx_scene_finish(s);
}

/* The grid: four view angles, light directions on both sides (near the mirror direction, the
 * straight-through one and elsewhere), eta = ior and, for solids, 1/ior (from inside). */
static int
build_cases(const fx_scene *s, bsdf_case *cases)
{
    float n[3] = { 0.3f, 0.8f, -0.2f };
    normalize3(n);
    float t[3] = { n[1], -n[0], 0.0f };
    normalize3(t);
    float b[3] = { n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0] };
    static const float view_cos[] = { 0.08f, 0.35f, 0.7f, 0.98f };
    static const float light_cos[] = { 0.15f, 0.5f, 0.9f, -0.2f, -0.6f, -0.95f };
    static const float light_phi[] = { 0.4f + 3.14159265f, 1.5f, 3.0f };
    const float phi_v = 0.4f;
    int count = 0;
    for (int m = 0; m < s->scene.material_count; m++) {
        const cg_material *mat = &s->materials[m];
        float etas[2] = { mat->ior, 1.0f / mat->ior };
        int eta_count = mat->thickness > 0.0f ? 2 : 1;
        for (int e = 0; e < eta_count; e++)
            for (size_t iv = 0; iv < sizeof view_cos / sizeof view_cos[0]; iv++) {
                float v[3];
                direction(n, t, b, view_cos[iv], phi_v, v);
                float ls[32][3];
                int lc = 0;
                for (size_t ic = 0; ic < sizeof light_cos / sizeof light_cos[0]; ic++)
                    for (size_t ip = 0; ip < sizeof light_phi / sizeof light_phi[0]; ip++)
                        direction(n, t, b, light_cos[ic], light_phi[ip], ls[lc++]);
                /* The mirror direction (the glossy peak) and straight through (a thin sheet's peak). */
                float nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
                for (int k = 0; k < 3; k++) {
                    ls[lc][k] = 2.0f * nv * n[k] - v[k];
                    ls[lc + 1][k] = -v[k];
                }
                normalize3(ls[lc]);
                lc += 2;
                for (int il = 0; il < lc; il++) {
                    assert_true(count < MAX_CASES);
                    bsdf_case *c = &cases[count++];
                    memcpy(c->n, n, sizeof n);
                    memcpy(c->v, v, sizeof v);
                    memcpy(c->l, ls[il], sizeof ls[il]);
                    c->n[3] = c->v[3] = c->l[3] = 0.0f;
                    c->params[0] = (float)m;
                    c->params[1] = etas[e];
                    c->params[2] = c->params[3] = 0.0f;
                    float h[3] = { v[0] + ls[il][0], v[1] + ls[il][1], v[2] + ls[il][2] };
                    float hh = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                    for (int k = 0; k < 3; k++)
                        h[k] = hh > 1e-6f ? h[k] / hh : 0.0f;
                    c->dots[0] = n[0] * h[0] + n[1] * h[1] + n[2] * h[2];
                    c->dots[1] = n[0] * ls[il][0] + n[1] * ls[il][1] + n[2] * ls[il][2];
                    c->dots[2] = nv;
                    c->dots[3] = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
                }
            }
    }
    return count;
}

/* cg_bsdf_diffuse_albedo_terms' a and b averaged over n.v, cosine-weighted (n.v = sqrt(u), u uniform,
 * a 256-point midpoint rule): what bsdf.glsl's CG_BSDF_DIFFUSE_HEMISPHERICAL_A and _B hold. */
static void
hemispherical_terms(double *a_mean, double *b_mean)
{
    static double a_sum = -1.0, b_sum;
    if (a_sum < 0.0) {
        a_sum = b_sum = 0.0;
        for (int i = 0; i < 256; i++) {
            float a, b;
            cg_bsdf_diffuse_albedo_terms(sqrtf(((float)i + 0.5f) / 256.0f), &a, &b);
            a_sum += a / 256.0;
            b_sum += b / 256.0;
        }
    }
    *a_mean = a_sum;
    *b_mean = b_sum;
}

/* The C side's values of one case, in bsdf_eval.comp's order. */
static void
c_values(const fx_scene *s, const bsdf_case *c, float out[TEST_VEC4][4])
{
    memset(out, 0, sizeof(float) * TEST_VEC4 * 4);
    const cg_material *m = &s->materials[(int)c->params[0]];
    float eta = c->params[1];
    cg_bsdf b;
    cg_bsdf_from_material(m, m->base_color, m->metallic, m->roughness, m->transmission, &b);
    float nh = c->dots[0], nl = c->dots[1], nv = c->dots[2], vh = c->dots[3];
    out[0][0] = cg_bsdf_ggx_d(b.alpha, nh);
    out[0][1] = cg_bsdf_smith_v(b.alpha, nl, nv);
    out[0][2] = cg_bsdf_smith_g1(b.alpha, nv);
    out[0][3] = cg_bsdf_is_smooth(&b) ? 1.0f : 0.0f;
    cg_bsdf_fresnel(b.f0, b.f90, vh, out[1]);
    cg_bsdf_fresnel_dielectric(&b, vh, eta, out[2]);
    cg_bsdf_eval(&b, c->n, c->v, c->l, eta, CG_BSDF_ALL_LOBES, out[3]);
    cg_bsdf_eval(&b, c->n, c->v, c->l, eta, CG_BSDF_DIFFUSE, out[4]);
    cg_bsdf_eval(&b, c->n, c->v, c->l, eta, CG_BSDF_GLOSSY, out[5]);
    cg_bsdf_eval(&b, c->n, c->v, c->l, eta, CG_BSDF_TRANSMISSION, out[6]);
    memcpy(out[7], b.diffuse, sizeof b.diffuse);
    out[7][3] = b.f90;
    memcpy(out[8], b.f0, sizeof b.f0);
    out[8][3] = b.alpha;
    memcpy(out[9], b.transmission, sizeof b.transmission);
    out[9][3] = b.ior;
    memcpy(out[10], b.sigma, sizeof b.sigma);
    out[10][3] = b.thickness;
    double ha, hb;
    hemispherical_terms(&ha, &hb);
    for (int k = 0; k < 3; k++)
        out[11][k] = (float)(b.diffuse[k] * (1.0 - b.f0[k] * ha - b.f90 * hb));
}

static const char *const value_names[TEST_VEC4] = {
    "D, V, G1, smooth", "fresnel", "fresnel_dielectric", "eval(all)", "eval(diffuse)", "eval(glossy)",
    "eval(transmission)", "diffuse, f90", "f0, alpha", "transmission, ior", "sigma, thickness",
    "diffuse_hemispherical",
};

/* Relative error, with values below 1e-3 of the largest of their kind compared absolutely at that
 * scale: a lobe that is 1e-7 of its peak may differ in every digit between two float orders. */
static void
test_glsl_matches_c(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    static fx_scene s;
    build_materials(&s);
    static bsdf_case cases[MAX_CASES];
    int count = build_cases(&s, cases);

    cg_error err = { 0 };
    cg_gpu_scene gpu;
    assert_cg_ok(cg_gpu_scene_upload(&s.scene, &gpu, &err), &err);
    GLuint program = 0;
    assert_cg_ok(cg_program_compute(cg_test_data_path("shaders/bsdf/bsdf_eval.comp"), NULL, &program, &err), &err);
    GLuint buffers[2];
    glCreateBuffers(2, buffers);
    size_t result_bytes = (size_t)count * TEST_VEC4 * 4 * sizeof(float);
    glNamedBufferStorage(buffers[0], (GLsizeiptr)((size_t)count * sizeof *cases), cases, 0);
    glNamedBufferStorage(buffers[1], (GLsizeiptr)result_bytes, NULL, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CG_BINDING_MATERIALS, gpu.material_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers[1]);
    glUseProgram(program);
    glUniform1ui(8, (GLuint)count);
    glDispatchCompute((GLuint)(count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    float *gpu_values = malloc(result_bytes);
    assert_non_null(gpu_values);
    glGetNamedBufferSubData(buffers[1], 0, (GLsizeiptr)result_bytes, gpu_values);

    /* The scale of each kind of value: its largest magnitude over the grid. */
    double scale[TEST_VEC4] = { 0 };
    float (*expected)[TEST_VEC4][4] = malloc((size_t)count * sizeof *expected);
    assert_non_null(expected);
    for (int i = 0; i < count; i++) {
        c_values(&s, &cases[i], expected[i]);
        for (int q = 0; q < TEST_VEC4; q++)
            for (int k = 0; k < 4; k++)
                if (!(q == 0 && k == 0 && expected[i][0][3] > 0.5f))   /* a smooth D: see below */
                    scale[q] = fmax(scale[q], fabs(expected[i][q][k]));
    }
    double worst[TEST_VEC4] = { 0 };
    int nonzero_transmission = 0, nonzero_glossy = 0;
    for (int i = 0; i < count; i++)
        for (int q = 0; q < TEST_VEC4; q++)
            for (int k = 0; k < 4; k++) {
                double c = expected[i][q][k], g = gpu_values[((size_t)i * TEST_VEC4 + (size_t)q) * 4 + (size_t)k];
                /* D of a smooth surface (alpha < CG_BSDF_ALPHA_MIN) at its peak is 1 - (1 - alpha^2) n.h^2
                 * cancelled to 1e-7: its float value follows the order (and fusing) of the operations,
                 * 25% apart here. No function evaluates it: such lobes are deltas. */
                if (q == 0 && k == 0 && expected[i][0][3] > 0.5f)
                    continue;
                double floor = 1e-3 * scale[q];
                double rel = fabs(g - c) / fmax(fabs(c), floor > 0.0 ? floor : 1e-30);
                if (!(rel <= worst[q]))
                    worst[q] = isnan(rel) ? INFINITY : rel;
                if (rel > 1e-4)
                    print_message("# case %d (material %d, eta %g) %s[%d]: GLSL %.9g, C %.9g\n", i,
                                  (int)cases[i].params[0], cases[i].params[1], value_names[q], k, g, c);
                if (q == 6 && k == 0 && c > 0.0)
                    nonzero_transmission++;
                if (q == 5 && k == 0 && c > 0.0)
                    nonzero_glossy++;
            }
    for (int q = 0; q < TEST_VEC4; q++)
        print_message("# %-20s largest relative difference %.2e (scale %.3g)\n", value_names[q], worst[q], scale[q]);
    print_message("# %d cases, %d with a glossy and %d with a transmission value\n", count, nonzero_glossy,
                  nonzero_transmission);
    /* The grid reaches every lobe: a comparison of zeros would prove nothing. */
    assert_true(nonzero_glossy > count / 4);
    assert_true(nonzero_transmission > 20);
    for (int q = 0; q < TEST_VEC4; q++)
        assert_true(worst[q] <= 1e-4);

    free(expected);
    free(gpu_values);
    glUseProgram(0);
    glDeleteBuffers(2, buffers);
    glDeleteProgram(program);
    cg_gpu_scene_destroy(&gpu);
    assert_no_gl_errors(ctx);
}

int
main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_glsl_matches_c),
    };
    if (!getenv("CONEGRAPH_TEST_DATA")) {
        fprintf(stderr, "CONEGRAPH_TEST_DATA is not set: run through meson test\n");
        return 1;
    }
    return cmocka_run_group_tests(tests, cg_test_gl_setup, cg_test_gl_teardown);
}
