/* Unit tests of cg/bsdf.h against what the glTF BSDF must satisfy: normalisation of D, Fresnel
 * values, reciprocity, energy (no lobe reflects more than it receives), sampling that agrees with
 * eval and pdf (the estimator of the integral of f cos equals a quadrature of eval), and the
 * albedo helpers against brute-force quadrature. No GL. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "cg/bsdf.h"
#include "test_support.h"

#define PI 3.14159265358979323846

/* A glTF material as the loader starts it (glTF defaults), with the given factors. */
static cg_material
material(float metallic, float roughness, float transmission, float thickness)
{
    cg_material m;
    memset(&m, 0, sizeof m);
    m.base_color[0] = m.base_color[1] = m.base_color[2] = m.base_color[3] = 1.0f;
    m.metallic = metallic;
    m.roughness = roughness;
    m.ior = 1.5f;
    m.specular = 1.0f;
    m.specular_color[0] = m.specular_color[1] = m.specular_color[2] = 1.0f;
    m.transmission = transmission;
    m.thickness = thickness;
    m.attenuation_distance = INFINITY;
    m.attenuation_color[0] = m.attenuation_color[1] = m.attenuation_color[2] = 1.0f;
    return m;
}

static cg_bsdf
bsdf_of(float metallic, float roughness, float transmission, float thickness, const float base[3])
{
    cg_material m = material(metallic, roughness, transmission, thickness);
    float bc[4] = { base[0], base[1], base[2], 1.0f };
    cg_bsdf b;
    cg_bsdf_from_material(&m, bc, metallic, roughness, transmission, &b);
    return b;
}

static uint64_t
next_u64(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static float
uniform(uint64_t *s)
{
    return (float)(next_u64(s) >> 40) * (1.0f / 16777216.0f);
}

static const float N[3] = { 0.0f, 0.0f, 1.0f };

static void
dir_of(float cos_theta, float phi, float out[3])
{
    float s = sqrtf(fmaxf(0.0f, 1.0f - cos_theta * cos_theta));
    out[0] = s * cosf(phi);
    out[1] = s * sinf(phi);
    out[2] = cos_theta;
}

/* The integral over the sphere of eval (per channel mean) and of pdf, by a midpoint rule in
 * (cos theta, phi) on each hemisphere: fine enough for alpha >= 0.2. */
static void
quadrature(const cg_bsdf *b, const float v[3], float eta, int lobes, double *f_int, double *pdf_int)
{
    const int nt = 512, np = 512;
    double sf = 0.0, sp = 0.0;
    for (int i = 0; i < 2 * nt; i++)
        for (int j = 0; j < np; j++) {
            float c = -1.0f + 2.0f * ((float)i + 0.5f) / (2.0f * nt);
            float l[3], f[3];
            dir_of(c, 2.0f * (float)PI * ((float)j + 0.5f) / np, l);
            cg_bsdf_eval(b, N, v, l, eta, lobes, f);
            sf += (f[0] + f[1] + f[2]) / 3.0;
            sp += cg_bsdf_pdf(b, N, v, l, eta, lobes);
        }
    double dw = (2.0 / (2.0 * nt)) * (2.0 * PI / np);
    *f_int = sf * dw;
    *pdf_int = sp * dw;
}

/* The estimator of the integral of f cos, the mean of cg_bsdf_sample's weight (channel mean),
 * and checks on every sample: its pdf is cg_bsdf_pdf's, its weight eval / pdf. */
static double
sampled_integral(const cg_bsdf *b, const float v[3], float eta, int lobes, int count, int only_lobe)
{
    uint64_t seed = 12345;
    double sum = 0.0;
    for (int k = 0; k < count; k++) {
        float u[3] = { uniform(&seed), uniform(&seed), uniform(&seed) };
        cg_bsdf_sample_result r;
        if (!cg_bsdf_sample(b, N, v, eta, lobes, u, &r))
            continue;
        if (only_lobe && r.lobe != only_lobe)
            continue;
        if (!r.delta && k % 97 == 0) {
            float p = cg_bsdf_pdf(b, N, v, r.l, eta, lobes), f[3];
            assert_true(fabsf(p - r.pdf) <= 1e-4f * p);
            cg_bsdf_eval(b, N, v, r.l, eta, lobes, f);
            for (int c = 0; c < 3; c++)
                assert_true(fabsf(f[c] / p - r.weight[c]) <= 1e-3f * fmaxf(1.0f, r.weight[c]));
        }
        sum += (r.weight[0] + r.weight[1] + r.weight[2]) / 3.0;
    }
    return sum / count;
}

static void
ggx_d_is_normalised(void **state)
{
    (void)state;
    /* The integral of D(h) (n.h) over the hemisphere is 1 (the projected microfacet area). */
    const float alphas[] = { 0.05f, 0.2f, 0.5f, 1.0f };
    for (size_t a = 0; a < sizeof alphas / sizeof *alphas; a++) {
        double sum = 0.0;
        const int n = 200000;
        /* In u = cos^2 theta the integrand D(h) (n.h) dw is pi D du: a midpoint rule in u. */
        for (int i = 0; i < n; i++) {
            double u = ((double)i + 0.5) / n;
            sum += PI * cg_bsdf_ggx_d(alphas[a], (float)sqrt(u)) / n;
        }
        assert_true(fabs(sum - 1.0) < 2e-3);
    }
}

static void
fresnel_of_a_glass_and_total_internal_reflection(void **state)
{
    (void)state;
    const float white[3] = { 1, 1, 1 };
    cg_bsdf g = bsdf_of(0, 0, 1, 0.1f, white);
    assert_true(fabsf(g.f0[0] - 0.04f) < 1e-6f);
    assert_true(fabsf(g.f90 - 1.0f) < 1e-6f);
    float f[3];
    cg_bsdf_fresnel_dielectric(&g, 1.0f, 1.5f, f);
    assert_true(fabsf(f[0] - 0.04f) < 1e-6f);
    /* From inside at 60 degrees: past the critical angle asin(1/1.5) = 41.8 degrees. */
    cg_bsdf_fresnel_dielectric(&g, cosf(60.0f * (float)PI / 180.0f), 1.0f / 1.5f, f);
    assert_true(f[0] == 1.0f);
    /* Inside at 20 degrees the transmitted angle is 30.9 degrees: Schlick on its cosine. */
    cg_bsdf_fresnel_dielectric(&g, cosf(20.0f * (float)PI / 180.0f), 1.0f / 1.5f, f);
    float ct = cosf(asinf(1.5f * sinf(20.0f * (float)PI / 180.0f)));
    assert_true(fabsf(f[0] - (0.04f + 0.96f * powf(1.0f - ct, 5.0f))) < 1e-5f);
    /* A metal's F0 is its base colour; a Lambertian (specular 0) has none. */
    const float gold[3] = { 1.0f, 0.78f, 0.34f };
    cg_bsdf m = bsdf_of(1, 0.3f, 0, 0, gold);
    for (int k = 0; k < 3; k++) {
        assert_true(m.f0[k] == gold[k]);
        assert_true(m.diffuse[k] == 0.0f && m.transmission[k] == 0.0f);
    }
}

static void
reflection_is_reciprocal(void **state)
{
    (void)state;
    const float base[3] = { 0.8f, 0.5f, 0.2f };
    cg_bsdf mats[] = { bsdf_of(0, 0.5f, 0, 0, base), bsdf_of(1, 0.3f, 0, 0, base), bsdf_of(0.5f, 0.8f, 0, 0, base),
                       bsdf_of(0, 0.2f, 0.5f, 0, base) };
    uint64_t seed = 7;
    for (size_t m = 0; m < sizeof mats / sizeof *mats; m++)
        for (int k = 0; k < 200; k++) {
            float v[3], l[3];
            dir_of(0.05f + 0.95f * uniform(&seed), 2.0f * (float)PI * uniform(&seed), v);
            dir_of(0.05f + 0.95f * uniform(&seed), 2.0f * (float)PI * uniform(&seed), l);
            float a[3], b[3];
            cg_bsdf_eval(&mats[m], N, v, l, 1.5f, CG_BSDF_ALL_LOBES, a);
            cg_bsdf_eval(&mats[m], N, l, v, 1.5f, CG_BSDF_ALL_LOBES, b);
            for (int c = 0; c < 3; c++) {
                double fa = a[c] / l[2], fb = b[c] / v[2];
                assert_true(fabs(fa - fb) <= 1e-4 * fmax(1.0, fabs(fa)));
            }
        }
}

static void
albedo_terms_match_quadrature(void **state)
{
    (void)state;
    const float alphas[] = { 0.04f, 0.25f, 0.64f, 1.0f };
    const float cosines[] = { 0.2f, 0.5f, 0.9f, 1.0f };
    for (size_t a = 0; a < 4; a++)
        for (size_t c = 0; c < 4; c++) {
            /* A white metal (F0 = 1): the glossy lobe alone, its albedo scale + bias. */
            const float white[3] = { 1, 1, 1 };
            cg_bsdf b = bsdf_of(1, sqrtf(alphas[a]), 0, 0, white);
            float v[3];
            dir_of(cosines[c], 0.0f, v);
            float scale, bias;
            cg_bsdf_specular_albedo_terms(b.alpha, cosines[c], &scale, &bias);
            assert_true(scale + bias <= 1.0f + 1e-3f);
            if (alphas[a] >= 0.2f) {
                double fi, pi_;
                quadrature(&b, v, 1.5f, CG_BSDF_ALL_LOBES, &fi, &pi_);
                assert_true(fabs(fi - (scale + bias)) < 0.01);
            }
        }
    /* The diffuse factor: for F0 = F90 = 0 the Lambertian albedo is 1; the terms lie in [0, 1]. */
    float da, db;
    cg_bsdf_diffuse_albedo_terms(0.7f, &da, &db);
    assert_true(da > 0.5f && da <= 1.0f && db >= 0.0f && da + db < 1.0f + 1e-4f);
    const float white[3] = { 1, 1, 1 };
    cg_bsdf d = bsdf_of(0, 1.0f, 0, 0, white);
    float v[3];
    dir_of(0.7f, 0.0f, v);
    double fi, pi_;
    quadrature(&d, v, 1.5f, CG_BSDF_ALL_LOBES, &fi, &pi_);
    float ad[3], ag[3], at[3];
    cg_bsdf_albedo(&d, 0.7f, ad, ag, at);
    assert_true(fabs(fi - (ad[0] + ag[0])) < 0.01);
}

static void
no_lobe_reflects_more_than_it_receives(void **state)
{
    (void)state;
    const float white[3] = { 1, 1, 1 };
    float worst = 0.0f;
    for (int r = 0; r <= 10; r++)
        for (int c = 1; c <= 10; c++) {
            float nv = (float)c / 10.0f;
            const float ms[][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 1, 0.01f }, { 0.5f, 0.5f, 0 } };
            for (size_t m = 0; m < sizeof ms / sizeof *ms; m++) {
                cg_bsdf b = bsdf_of(ms[m][0], (float)r / 10.0f, ms[m][1], ms[m][2], white);
                float ad[3], ag[3], at[3];
                cg_bsdf_albedo(&b, nv, ad, ag, at);
                for (int k = 0; k < 3; k++) {
                    assert_true(ad[k] >= 0.0f && ag[k] >= 0.0f && at[k] >= 0.0f);
                    assert_true(ad[k] <= 1.0f && ag[k] <= 1.0f + 1e-3f && at[k] <= 1.0f + 1e-3f);
                    /* Without a diffuse lobe the sum holds too (glossy + transmission = the GGX
                     * albedo). With one it does not: glTF's diffuse weight 1 - F(v.h) ignores the
                     * light the glossy lobe took at n.v (spec Appendix B.3.5's approximation), so a
                     * white smooth plastic at grazing angles sums above 1 (below, the largest). */
                    if (ad[k] == 0.0f)
                        assert_true(ad[k] + ag[k] + at[k] <= 1.0f + 2e-3f);
                    else
                        worst = fmaxf(worst, ad[k] + ag[k] + at[k]);
                }
            }
        }
    print_message("# largest albedo of a white dielectric with its diffuse lobe: %.3f\n", (double)worst);
    assert_true(worst < 1.6f);
}

static void
sampling_agrees_with_eval_and_pdf(void **state)
{
    (void)state;
    const float base[3] = { 0.9f, 0.6f, 0.3f };
    struct {
        float metallic, roughness, transmission, thickness;
    } cases[] = { { 0, 0.5f, 0, 0 }, { 1, 0.3f, 0, 0 }, { 1, 0.8f, 0, 0 }, { 0.5f, 0.6f, 0, 0 },
                  { 0, 0.5f, 1, 0 }, { 0, 0.5f, 1, 0.2f }, { 0, 0.7f, 0.5f, 0.2f } };
    const float cosines[] = { 0.3f, 0.8f };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++)
        for (size_t c = 0; c < 2; c++) {
            cg_bsdf b = bsdf_of(cases[k].metallic, cases[k].roughness, cases[k].transmission, cases[k].thickness, base);
            float v[3];
            dir_of(cosines[c], 0.4f, v);
            double fi, pi_;
            quadrature(&b, v, 1.5f, CG_BSDF_ALL_LOBES, &fi, &pi_);
            double est = sampled_integral(&b, v, 1.5f, CG_BSDF_ALL_LOBES, 400000, 0);
            /* pdf integrates to at most 1 (samples can fall below the surface and be lost). */
            assert_true(pi_ <= 1.0 + 5e-3 && pi_ > 0.5);
            if (fabs(est - fi) > 0.01 * fmax(fi, 0.1))
                fail_msg("case %zu cos %.1f: sampled %.4f, quadrature %.4f", k, (double)cosines[c], est, fi);
        }
}

static void
smooth_lobes_are_deltas(void **state)
{
    (void)state;
    const float white[3] = { 1, 1, 1 };
    float v[3];
    dir_of(1.0f, 0.0f, v);
    /* A perfect mirror: its only sample is the mirror direction with weight F. */
    cg_bsdf mirror = bsdf_of(1, 0, 0, 0, white);
    cg_bsdf_sample_result r;
    float u[3] = { 0.5f, 0.3f, 0.7f };
    assert_true(cg_bsdf_sample(&mirror, N, v, 1.5f, CG_BSDF_ALL_LOBES, u, &r));
    assert_true(r.delta && r.lobe == CG_BSDF_GLOSSY && fabsf(r.l[2] - 1.0f) < 1e-6f);
    assert_true(fabsf(r.weight[0] - 1.0f) < 1e-6f);
    float f[3];
    cg_bsdf_eval(&mirror, N, v, v, 1.5f, CG_BSDF_ALL_LOBES, f);
    assert_true(f[0] == 0.0f && cg_bsdf_pdf(&mirror, N, v, v, 1.5f, CG_BSDF_ALL_LOBES) == 0.0f);
    /* A smooth glass at normal incidence: reflect with probability F0, else refract straight on;
     * the expected weight is F0 (reflection) and 1 - F0 (transmission). */
    cg_bsdf glass = bsdf_of(0, 0, 1, 0.1f, white);
    uint64_t seed = 3;
    double refl = 0.0, trans = 0.0;
    const int n = 100000;
    for (int k = 0; k < n; k++) {
        float uu[3] = { uniform(&seed), uniform(&seed), uniform(&seed) };
        assert_true(cg_bsdf_sample(&glass, N, v, 1.5f, CG_BSDF_ALL_LOBES, uu, &r));
        assert_true(r.delta);
        if (r.lobe == CG_BSDF_GLOSSY)
            refl += r.weight[0];
        else {
            assert_true(r.lobe == CG_BSDF_TRANSMISSION && r.refracted && fabsf(r.l[2] + 1.0f) < 1e-5f);
            trans += r.weight[0];
        }
    }
    assert_true(fabs(refl / n - 0.04) < 0.003);
    assert_true(fabs(trans / n - 0.96) < 0.003);
    /* With the glossy lobe removed (caustics off after a diffuse bounce), a glass is black and
     * a mirror too: nothing can be drawn. */
    assert_false(cg_bsdf_sample(&mirror, N, v, 1.5f, CG_BSDF_DIFFUSE, u, &r));
    assert_false(cg_bsdf_sample(&glass, N, v, 1.5f, CG_BSDF_DIFFUSE, u, &r));
}

static void
refraction_obeys_snell(void **state)
{
    (void)state;
    const float white[3] = { 1, 1, 1 };
    cg_bsdf glass = bsdf_of(0, 0, 1, 0.1f, white);
    float v[3];
    dir_of(cosf(0.7f), 0.0f, v);
    cg_bsdf_sample_result r;
    /* u[0] near 1 picks the refraction (its probability is 1 - F). */
    float u[3] = { 0.999f, 0.5f, 0.5f };
    assert_true(cg_bsdf_sample(&glass, N, v, 1.5f, CG_BSDF_ALL_LOBES, u, &r));
    assert_true(r.lobe == CG_BSDF_TRANSMISSION);
    float sin_i = sinf(0.7f), sin_t = sqrtf(r.l[0] * r.l[0] + r.l[1] * r.l[1]);
    assert_true(fabsf(sin_t - sin_i / 1.5f) < 1e-5f);
    assert_true(r.l[0] < 0.0f && r.l[2] < 0.0f); /* on through the surface, away from v's side */
    /* A thin sheet: straight on, not bent. */
    cg_bsdf sheet = bsdf_of(0, 0, 1, 0, white);
    assert_true(cg_bsdf_sample(&sheet, N, v, 1.5f, CG_BSDF_ALL_LOBES, u, &r));
    assert_true(r.lobe == CG_BSDF_TRANSMISSION && !r.refracted);
    for (int k = 0; k < 3; k++)
        assert_true(fabsf(r.l[k] + v[k]) < 1e-5f);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(ggx_d_is_normalised),
             cmocka_unit_test(fresnel_of_a_glass_and_total_internal_reflection),
             cmocka_unit_test(reflection_is_reciprocal),
             cmocka_unit_test(albedo_terms_match_quadrature),
             cmocka_unit_test(no_lobe_reflects_more_than_it_receives),
             cmocka_unit_test(sampling_agrees_with_eval_and_pdf),
             cmocka_unit_test(smooth_lobes_are_deltas),
             cmocka_unit_test(refraction_obeys_snell))
