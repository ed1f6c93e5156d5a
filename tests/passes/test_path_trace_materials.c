/* The path tracer with glTF materials (no GL), on unit scenes with closed forms:
 *   - white furnace: a plane under a uniform sky L returns L x the BSDF's directional albedo
 *     (cg_bsdf_albedo, numerical) for rough and smooth metals, a glossy dielectric, a thin glass;
 *   - a mirror (metal, roughness 0) under a uniform sky returns L x F0;
 *   - a glass slab over an emitter: L_e (1 - F0)^2 exp(-sigma d) (thick), L_e (1 - F0) (thin sheet);
 *   - a mirror seeing a lit ceiling: F0 x the ceiling's radiance; black with glossy_bounces 0;
 *     the ceiling single-sided, so the camera sees through its back;
 *   - alpha MASK holes let light and view through; BLEND lets 1 - alpha through;
 *   - caustics false: no light through glass onto a diffuse floor; caustics true: some;
 *   - a sun with an angular diameter gives the same irradiance as a point sun.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/bsdf.h"
#include "path_trace_fixture.h"
#include "test_support.h"

enum { W = 8, H = 8 };

static cg_material *
mat(cg_scene *s, int index)
{
    return &s->materials[index];
}

/* A glTF-style material: specular 1 (F0 from the ior), the given metallic, roughness, transmission. */
static int
add_gltf_material(cg_scene *s, float r, float g, float b, float metallic, float roughness, float transmission)
{
    int m = ptf_add_material(s, r, g, b, 0.0f);
    mat(s, m)->metallic = metallic;
    mat(s, m)->roughness = roughness;
    mat(s, m)->transmission = transmission;
    mat(s, m)->specular = 1.0f;
    return m;
}

/* A quad of half extents h at height z facing -z (the quad mesh turned over about x). */
static void
add_quad_down(cg_scene *s, int material, float z, float h)
{
    mat4 m;
    glm_mat4_identity(m);
    glm_translate(m, (vec3){ 0, 0, z });
    glm_rotate(m, (float)PTF_PI, (vec3){ 1, 0, 0 });
    glm_scale(m, (vec3){ h, h, 1.0f });
    ptf_add_instance(s, ptf_add_quad_mesh(s, material), m);
}

static void
set_sky(cg_scene *s, float l)
{
    cg_sky sky = { .type = CG_SKY_UNIFORM, .radiance = { l, l, l } };
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_set_sky(s, &sky, &err), &err);
}

/* The mean of the image's channel c over all pixels. */
static double
image_mean(const float *img, int c)
{
    double sum = 0.0;
    for (int i = 0; i < W * H; i++)
        sum += img[4 * i + c];
    return sum / (W * H);
}

static void
furnace_returns_the_directional_albedo(void **state)
{
    (void)state;
    struct {
        const char *name;
        float base[3], metallic, roughness, transmission;
    } cases[] = {
        { "rough gold", { 1.0f, 0.78f, 0.34f }, 1, 0.5f, 0 },
        { "smooth chrome", { 0.55f, 0.55f, 0.55f }, 1, 0.0f, 0 },
        { "glossy plastic", { 0.2f, 0.4f, 0.8f }, 0, 0.3f, 0 },
        { "rough thin glass", { 0.9f, 0.9f, 0.9f }, 0, 0.4f, 1 },
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        cg_scene s;
        ptf_scene_init(&s);
        int m = add_gltf_material(&s, cases[k].base[0], cases[k].base[1], cases[k].base[2], cases[k].metallic,
                                  cases[k].roughness, cases[k].transmission);
        ptf_add_quad_at(&s, m, 0, 0, 0, 10, 10);
        set_sky(&s, 2.0f);
        cg_view v = ptf_view_top_ortho(W, H);
        pt_settings st = pt_settings_default();
        st.spp = 1024;
        float *img = ptf_render(&s, &v, st);
        cg_bsdf b;
        float bc[4] = { cases[k].base[0], cases[k].base[1], cases[k].base[2], 1 };
        cg_bsdf_from_material(mat(&s, m), bc, cases[k].metallic, cases[k].roughness, cases[k].transmission, &b);
        float ad[3], ag[3], at[3];
        cg_bsdf_albedo(&b, 1.0f, ad, ag, at);
        for (int c = 0; c < 3; c++) {
            double want = 2.0 * (ad[c] + ag[c] + at[c]), got = image_mean(img, c);
            print_message("# furnace %s channel %d: %.4f, albedo x L %.4f\n", cases[k].name, c, got, want);
            if (fabs(got - want) > 0.01 * want + 1e-4)
                fail_msg("furnace %s channel %d: %.4f, want %.4f", cases[k].name, c, got, want);
        }
        free(img);
        ptf_scene_release(&s);
    }
}

static void
glass_slab_transmits_its_fresnel_and_beer_lambert(void **state)
{
    (void)state;
    for (int thick = 0; thick <= 1; thick++) {
        cg_scene s;
        ptf_scene_init(&s);
        int emitter = ptf_add_material(&s, 0, 0, 0, 3.0f);
        ptf_add_quad_at(&s, emitter, 0, 0, -1.0f, 10, 10);
        int glass = add_gltf_material(&s, 1, 1, 1, 0, 0, 1);
        double want = 3.0 * (1.0 - 0.04);
        if (thick) {
            /* A slab 0.5 thick: its top faces +z at 0.25, its bottom -z at -0.25; sigma = ln 2. */
            mat(&s, glass)->thickness = 0.5f;
            mat(&s, glass)->attenuation_distance = 1.0f;
            for (int c = 0; c < 3; c++)
                mat(&s, glass)->attenuation_color[c] = 0.5f;
            ptf_add_quad_at(&s, glass, 0, 0, 0.25f, 10, 10);
            add_quad_down(&s, glass, -0.25f, 10);
            want = 3.0 * (1.0 - 0.04) * (1.0 - 0.04) * exp(-log(2.0) * 0.5);
        } else {
            ptf_add_quad_at(&s, glass, 0, 0, 0, 10, 10);
        }
        cg_view v = ptf_view_top_ortho(W, H);
        pt_settings st = pt_settings_default();
        st.spp = 4096;
        float *img = ptf_render(&s, &v, st);
        double got = image_mean(img, 0);
        print_message("# glass %s: %.4f, closed form %.4f\n", thick ? "slab" : "sheet", got, want);
        /* The two internal reflections (F0^2 = 0.0016 of it) are left out of the closed form. */
        if (fabs(got - want) > 0.01 * want)
            fail_msg("glass %s: %.4f, want %.4f", thick ? "slab" : "sheet", got, want);
        free(img);
        ptf_scene_release(&s);
    }
}

static void
mirror_reflects_the_sky_times_f0(void **state)
{
    (void)state;
    cg_scene s;
    ptf_scene_init(&s);
    int m = add_gltf_material(&s, 0.9f, 0.6f, 0.3f, 1, 0, 0);
    ptf_add_quad_at(&s, m, 0, 0, 0, 10, 10);
    set_sky(&s, 1.5f);
    cg_view v = ptf_view_top_ortho(W, H);
    for (int glossy = 0; glossy <= 1; glossy++) {
        pt_settings st = pt_settings_default();
        st.spp = 4;
        st.glossy_bounces = glossy; /* the sky seen in the mirror is one scattering: there either way */
        float *img = ptf_render(&s, &v, st);
        for (int i = 0; i < W * H; i++)
            for (int c = 0; c < 3; c++)
                ptf_assert_rel(img[4 * i + c], 1.5 * mat(&s, m)->base_color[c], 1e-5, "L F0", i % W, i / W);
        free(img);
    }
    ptf_scene_release(&s);
}

static void
mirror_sees_a_lit_ceiling_within_its_glossy_bounces(void **state)
{
    (void)state;
    cg_scene s;
    ptf_scene_init(&s);
    int mirror = add_gltf_material(&s, 0.8f, 0.8f, 0.8f, 1, 0, 0);
    ptf_add_quad_at(&s, mirror, 0, 0, 0, 10, 10);
    int ceiling = ptf_add_material(&s, 0.5f, 0.5f, 0.5f, 0.0f);
    mat(&s, ceiling)->double_sided = false; /* the camera above sees through its back */
    add_quad_down(&s, ceiling, 0.5f, 10);
    cg_light *l = ptf_add_light(&s, CG_LIGHT_POINT, 2.0f);
    l->position[2] = 0.25f;
    cg_view v = ptf_view_top_ortho(W, H);
    for (int glossy = 0; glossy <= 1; glossy++) {
        pt_settings st = pt_settings_default();
        st.spp = 4;
        st.glossy_bounces = glossy;
        float *img = ptf_render(&s, &v, st);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double px, py;
                ptf_pixel_on_plane(x, y, W, H, &px, &py);
                /* The mirror sees the ceiling point above it: 0.8 x (0.5/pi) I cos / d^2, with
                 * d^2 = px^2 + py^2 + 0.25^2 and cos = 0.25/d. Without caustics, the ceiling's
                 * bounce sees a black mirror, and nothing else lights it. */
                double d2 = px * px + py * py + 0.0625;
                double want = glossy ? 0.8 * (0.5 / PTF_PI) * 2.0 * (0.25 / sqrt(d2)) / d2 : 0.0;
                ptf_assert_rel(img[4 * (y * W + x)], want, 1e-4, "mirror of the ceiling", x, y);
            }
        free(img);
    }
    ptf_scene_release(&s);
}

static void
mask_holes_and_blend_let_light_through(void **state)
{
    (void)state;
    for (int mode = 0; mode < 2; mode++) {
        cg_scene s;
        ptf_scene_init(&s);
        int floor = ptf_add_material(&s, 0.6f, 0.6f, 0.6f, 0.0f);
        ptf_add_quad_at(&s, floor, 0, 0, 0, 10, 10);
        int cover = ptf_add_material(&s, 0.0f, 0.0f, 0.0f, 0.0f);
        mat(&s, cover)->alpha_mode = mode == 0 ? CG_ALPHA_MASK : CG_ALPHA_BLEND;
        mat(&s, cover)->base_color[3] = 0.25f; /* below MASK's cutoff 0.5; BLEND lets 0.75 through */
        mat(&s, cover)->alpha_cutoff = 0.5f;
        ptf_add_quad_at(&s, cover, 0, 0, 0.5f, 10, 10);
        cg_light *l = ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, 3.0f);
        l->direction[2] = -1.0f;
        cg_view v = ptf_view_top_ortho(W, H);
        pt_settings st = pt_settings_default();
        st.spp = mode == 0 ? 1 : 2048;
        float *img = ptf_render(&s, &v, st);
        /* The camera sees the floor through the cover (MASK: always; BLEND: 0.75 of the time,
         * else the black cover), and the light reaches it the same way. */
        double lit = 0.6 / PTF_PI * 3.0;
        double want = mode == 0 ? lit : 0.75 * 0.75 * lit;
        double got = image_mean(img, 0);
        print_message("# %s cover: %.4f, closed form %.4f\n", mode == 0 ? "MASK" : "BLEND", got, want);
        if (fabs(got - want) > (mode == 0 ? 1e-5 : 0.02) * want)
            fail_msg("%s: %.4f, want %.4f", mode == 0 ? "MASK" : "BLEND", got, want);
        free(img);
        ptf_scene_release(&s);
    }
}

static void
caustics_false_keeps_light_through_glass_off_a_diffuse_floor(void **state)
{
    (void)state;
    cg_scene s;
    ptf_scene_init(&s);
    int floor = ptf_add_material(&s, 0.8f, 0.8f, 0.8f, 0.0f);
    ptf_add_quad_at(&s, floor, 0, 0, 0, 10, 10);
    int glass = add_gltf_material(&s, 1, 1, 1, 0, 0, 1); /* a thin, smooth sheet */
    ptf_add_quad_at(&s, glass, 0, 0, 0.5f, 10, 10);
    int lamp = ptf_add_material(&s, 0, 0, 0, 4.0f);
    mat(&s, lamp)->double_sided = false; /* the camera above sees through its back */
    add_quad_down(&s, lamp, 1.0f, 10);
    cg_view v = ptf_view_top_ortho(W, H);
    double got[2];
    for (int caustics = 0; caustics <= 1; caustics++) {
        pt_settings st = pt_settings_default();
        st.spp = 256;
        st.caustics = caustics;
        float *img = ptf_render(&s, &v, st);
        got[caustics] = image_mean(img, 0);
        free(img);
    }
    /* Without caustics the camera sees the lamp in the sheet's reflection, F0 L = 0.16 (a
     * Bernoulli draw of probability F0: 0.008 of noise), and a black floor. With caustics the
     * floor under an infinite lamp of L through the sheet twice adds about 0.8 L (1 - F)^2,
     * less what the sheet's Fresnel turns away at grazing angles. */
    print_message("# floor under glass: caustics off %.4f, on %.4f (0.8 L (1-F0)^2 = %.4f)\n", got[0], got[1],
                  0.8 * 4.0 * 0.96 * 0.96);
    assert_true(fabs(got[0] - 0.16) < 0.03);
    assert_true(got[1] - got[0] > 0.5 * 0.8 * 4.0 * 0.96 * 0.96 && got[1] - got[0] < 0.8 * 4.0 * 0.96 * 0.96 * 1.02);
    ptf_scene_release(&s);
}

static void
sun_disc_keeps_the_irradiance(void **state)
{
    (void)state;
    cg_scene s;
    ptf_floor_scene(&s, 0.5f);
    cg_light *l = ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, 2.0f);
    l->direction[2] = -1.0f;
    l->angular_diameter = 0.2f; /* a large disc: the mean cosine over it is (1 + cos 0.1)/2 */
    cg_view v = ptf_view_top_ortho(W, H);
    pt_settings st = pt_settings_default();
    st.spp = 16;
    float *img = ptf_render(&s, &v, st);
    double want = 0.5 / PTF_PI * 2.0 * 0.5 * (1.0 + cos(0.1));
    double got = image_mean(img, 0);
    assert_true(fabs(got - want) < 1e-3 * want);
    free(img);
    ptf_scene_release(&s);
}

static void
new_settings_are_checked(void **state)
{
    (void)state;
    cg_scene s;
    ptf_scene_init(&s);
    ptf_add_quad_at(&s, 0, 0, 0, 0, 1, 1);
    pt_scene *pts;
    cg_error err = { 0 };
    assert_cg_ok(pt_scene_create(&s, &pts, &err), &err);
    cg_view v = ptf_view_top_ortho(W, H);
    float img[W * H * 4];
    pt_settings st = pt_settings_default();
    assert_int_equal(st.glossy_bounces, 1);
    assert_int_equal(st.transmission_bounces, 4);
    assert_false(st.caustics);
    st.glossy_bounces = -1;
    assert_cg_status(pt_render(pts, &v, &st, img, NULL, &err), &err, CG_ERR_USAGE);
    assert_non_null(strstr(err.message, "glossy_bounces"));
    st = pt_settings_default();
    st.transmission_bounces = 1000;
    assert_cg_status(pt_render(pts, &v, &st, img, NULL, &err), &err, CG_ERR_USAGE);
    assert_non_null(strstr(err.message, "transmission_bounces"));
    pt_scene_destroy(pts);
    ptf_scene_release(&s);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(furnace_returns_the_directional_albedo),
             cmocka_unit_test(glass_slab_transmits_its_fresnel_and_beer_lambert),
             cmocka_unit_test(mirror_reflects_the_sky_times_f0),
             cmocka_unit_test(mirror_sees_a_lit_ceiling_within_its_glossy_bounces),
             cmocka_unit_test(mask_holes_and_blend_let_light_through),
             cmocka_unit_test(caustics_false_keeps_light_through_glass_off_a_diffuse_floor),
             cmocka_unit_test(sun_disc_keeps_the_irradiance),
             cmocka_unit_test(new_settings_are_checked))
