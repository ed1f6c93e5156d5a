/* The sky in the path tracer (no GL needed): parsing and checking a sky, the Preetham
 * model's zenith against the paper's formulas worked by hand, a white plane under a uniform
 * sky (exactly albedo x L), the floor of an open box (albedo x L x the view factor of its
 * opening), a plane under the Preetham sky (albedo / pi x the sky's irradiance, integrated
 * here by quadrature), and the sky seen as the background. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/pt_render.h"
#include "cg/scene.h"
#include "path_trace_fixture.h"
#include "test_support.h"

static void
sky_is_parsed_and_checked(void **state)
{
    (void)state;
    cg_sky sky;
    cg_error err = { 0 };
    assert_cg_ok(cg_sky_parse("none", &sky, &err), &err);
    assert_int_equal(sky.type, CG_SKY_NONE);
    assert_cg_ok(cg_sky_parse("0.5,1,2.25", &sky, &err), &err);
    assert_int_equal(sky.type, CG_SKY_UNIFORM);
    assert_true(sky.radiance[0] == 0.5f && sky.radiance[1] == 1.0f && sky.radiance[2] == 2.25f);
    assert_cg_ok(cg_sky_parse("3", &sky, &err), &err);
    assert_true(sky.type == CG_SKY_UNIFORM && sky.radiance[0] == 3.0f && sky.radiance[2] == 3.0f);
    assert_cg_ok(cg_sky_parse("preetham", &sky, &err), &err);
    assert_true(sky.type == CG_SKY_PREETHAM && sky.turbidity == 3.0f && sky.scale == 1.0f);
    assert_cg_ok(cg_sky_parse("preetham:2.5,0.01", &sky, &err), &err);
    assert_true(sky.turbidity == 2.5f && sky.scale == 0.01f);
    const char *bad[] = { "", "1,2", "1,2,3,4", "-1", "1,,2", "1,2,", "nan", "inf,1,1", "preetham:", "preetham:1",
                          "preetham:11", "preetham:3,-1", "preetham:3,1,2", "preethamX", "sun" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cg_error e = { 0 };
        if (cg_sky_parse(bad[i], &sky, &e) || e.status != CG_ERR_USAGE)
            fail_msg("cg_sky_parse(\"%s\") should fail with a usage error", bad[i]);
    }
    cg_scene s;
    ptf_scene_init(&s);
    cg_sky uniform = { .type = CG_SKY_UNIFORM, .radiance = { 1, -0.5f, 1 } };
    assert_cg_status(cg_scene_set_sky(&s, &uniform, &err), &err, CG_ERR_USAGE);
    assert_int_equal(s.sky.type, CG_SKY_NONE);
    cg_sky preetham = { .type = CG_SKY_PREETHAM, .turbidity = 3, .scale = 1 };
    assert_cg_status(cg_scene_set_sky(&s, &preetham, &err), &err, CG_ERR_USAGE); /* no sun */
    assert_non_null(strstr(err.message, "directional"));
    ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, 1.0f)->direction[1] = -1.0f;
    assert_cg_ok(cg_scene_set_sky(&s, &preetham, &err), &err);
    assert_int_equal(s.sky.type, CG_SKY_PREETHAM);
    ptf_scene_release(&s);
}

/* Linear sRGB back to CIE XYZ (the inverse of IEC 61966-2-1's matrix). */
static void
rgb_to_xyz(const float rgb[3], double xyz[3])
{
    xyz[0] = 0.4124564 * rgb[0] + 0.3575761 * rgb[1] + 0.1804375 * rgb[2];
    xyz[1] = 0.2126729 * rgb[0] + 0.7151522 * rgb[1] + 0.0721750 * rgb[2];
    xyz[2] = 0.0193339 * rgb[0] + 0.1191920 * rgb[1] + 0.9503041 * rgb[2];
}

/* Turbidity 2, the sun at the zenith: Preetham et al., appendix A.2, by hand:
 *   chi = (4/9 - 2/120) pi = 1.343904, tan chi = 4.331476,
 *   Y_z = (4.0453 x 2 - 4.9710) x 4.331476 - 0.2155 x 2 + 2.4192 = 15.50067 kcd/m^2,
 *   x_z = 2 x 0.00394 + 0.25886 = 0.26674, y_z = 2 x 0.00516 + 0.26688 = 0.27720
 * (theta_s = 0 leaves the last column of each matrix). Looking at the zenith, gamma =
 * theta_s, so the Perez ratio is 1 and the sky there is exactly the zenith value. */
static void
preetham_zenith_is_the_papers(void **state)
{
    (void)state;
    cg_scene s;
    ptf_scene_init(&s);
    ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, 1.0f)->direction[1] = -1.0f;
    cg_sky sky = { .type = CG_SKY_PREETHAM, .turbidity = 2, .scale = 0.5f };
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_set_sky(&s, &sky, &err), &err);
    cg_sky_model m;
    assert_cg_ok(cg_sky_model_init(&s, &m, &err), &err);
    float up[3] = { 0, 1, 0 }, rgb[3];
    cg_sky_model_radiance(&m, up, rgb);
    double xyz[3];
    rgb_to_xyz(rgb, xyz);
    double sum = xyz[0] + xyz[1] + xyz[2];
    print_message("# zenith: Y %.5f (x 1/scale), x %.5f, y %.5f; rgb %.4f %.4f %.4f\n", xyz[1] / 0.5, xyz[0] / sum,
                  xyz[1] / sum, rgb[0], rgb[1], rgb[2]);
    ptf_assert_rel(xyz[1] / 0.5, 15.50067, 1e-4, "zenith luminance", 0, 0);
    ptf_assert_rel(xyz[0] / sum, 0.26674, 1e-4, "zenith x", 0, 0);
    ptf_assert_rel(xyz[1] / sum, 0.27720, 1e-4, "zenith y", 0, 0);
    assert_true(rgb[2] > rgb[1] && rgb[1] > rgb[0]); /* a clear sky is blue */
    /* Black below the horizon, brighter towards the sun than away from it. */
    float down[3] = { 0.3f, -0.1f, 0.2f };
    cg_sky_model_radiance(&m, down, rgb);
    assert_true(rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f);
    ptf_scene_release(&s);
}

/* A 20 m white plane of albedo a under a uniform sky L, seen from above: the sky sample and
 * the cosine-sampled continuation both see L with weights 1/2, so every pixel is a L,
 * exactly, at any bounce count. A camera looking away from the plane sees L. */
static void
uniform_sky_on_a_white_plane_gives_albedo_times_l(void **state)
{
    (void)state;
    enum { W = 16, H = 16 };
    cg_scene s;
    ptf_floor_scene(&s, 0.7f);
    cg_sky sky = { .type = CG_SKY_UNIFORM, .radiance = { 0.3f, 0.5f, 0.9f } };
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_set_sky(&s, &sky, &err), &err);
    cg_view v = ptf_view_top_ortho(W, H);
    for (int bounces = 0; bounces <= 2; bounces++) {
        pt_settings st = ptf_settings(2, bounces);
        float *img = ptf_render(&s, &v, st);
        for (int i = 0; i < W * H; i++)
            for (int c = 0; c < 3; c++)
                ptf_assert_rel(img[4 * i + c], 0.7 * sky.radiance[c], 1e-5, "a L", i % W, i / W);
        free(img);
    }
    cg_view up = ptf_view_perspective(W, H, (vec3){ 0, 0, 1 }, (vec3){ 0.2f, 0.1f, 5 });
    float *img = ptf_render(&s, &up, pt_settings_default());
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++)
            ptf_assert_rel(img[4 * i + c], sky.radiance[c], 0.0, "the sky as background", i % W, i / W);
    free(img);
    ptf_scene_release(&s);
}

/* The floor [-1,1]^2 of an open box with black walls of height h under a uniform sky L: a
 * floor point sees the sky through the opening only, so its radiance is a L F, F the view
 * factor of the square opening at height h (four corners), whatever the bounce count (the
 * walls reflect nothing). Image mean and each quadrant's within 5 standard errors. */
static void
open_box_floor_sees_the_sky_through_its_opening(void **state)
{
    (void)state;
    enum { W = 24, H = 24 };
    const double h = 0.6, albedo = 0.8, l = 1.5;
    cg_scene s;
    ptf_scene_init(&s);
    ptf_add_quad_at(&s, ptf_add_material(&s, (float)albedo, (float)albedo, (float)albedo, 0.0f), 0, 0, 0, 1, 1);
    int black = ptf_add_material(&s, 0, 0, 0, 0);
    int wall = ptf_add_quad_mesh(&s, black);
    for (int k = 0; k < 4; k++) {
        /* The quad turned upright (facing -y), moved to y = -1, turned about z by k x 90 degrees. */
        mat4 m;
        glm_mat4_identity(m);
        glm_rotate(m, glm_rad(90.0f * k), (vec3){ 0, 0, 1 });
        glm_translate(m, (vec3){ 0, -1, (float)(0.5 * h) });
        glm_rotate(m, glm_rad(90.0f), (vec3){ 1, 0, 0 });
        glm_scale(m, (vec3){ 1.0f, (float)(0.5 * h), 1.0f });
        ptf_add_instance(&s, wall, m);
    }
    cg_sky sky = { .type = CG_SKY_UNIFORM, .radiance = { (float)l, (float)l, (float)l } };
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_set_sky(&s, &sky, &err), &err);
    /* Looking down from above the opening: only the floor is in view (the walls edge-on). */
    cg_view v = ptf_view_top_ortho(W, H);
    double want[W * H], mean_want = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double px, py;
            ptf_pixel_on_plane(x, y, W, H, &px, &py);
            double f = ptf_corner_view_factor(1 - px, 1 - py, h) - ptf_corner_view_factor(-1 - px, 1 - py, h) -
                       ptf_corner_view_factor(1 - px, -1 - py, h) + ptf_corner_view_factor(-1 - px, -1 - py, h);
            want[y * W + x] = albedo * l * f;
            mean_want += want[y * W + x] / (W * H);
        }
    for (int bounces = 0; bounces <= 1; bounces++) {
        pt_settings st = ptf_settings(128, bounces);
        float *img = ptf_render(&s, &v, st);
        double mean, se;
        ptf_residual_mean(img, want, W * H, &mean, &se);
        print_message("# open box, %d bounces: mean residual %.3g of a mean %.5f (standard error %.2g)\n", bounces,
                      mean, mean_want, se);
        assert_true(se < 5e-3 * mean_want);
        if (!(fabs(mean) <= 5.0 * se))
            fail_msg("open box, %d bounces: mean residual %.4g, standard error %.2g", bounces, mean, se);
        for (int q = 0; q < 4; q++) {
            double wq[W * H / 4];
            float sub[4 * W * H / 4];
            int n = 0;
            for (int y = (q / 2) * H / 2; y < (q / 2 + 1) * H / 2; y++)
                for (int x = (q % 2) * W / 2; x < (q % 2 + 1) * W / 2; x++, n++) {
                    memcpy(&sub[4 * n], &img[4 * (y * W + x)], 4 * sizeof(float));
                    wq[n] = want[y * W + x];
                }
            double qm, qse;
            ptf_residual_mean(sub, wq, n, &qm, &qse);
            if (!(fabs(qm) <= 5.0 * qse))
                fail_msg("open box, quadrant %d: mean residual %.4g, standard error %.2g", q, qm, qse);
        }
        free(img);
    }
    ptf_scene_release(&s);
}

/* Irradiance of the sky on a horizontal surface, E = integral of L(w) cos(theta) dw over the
 * upper hemisphere, by the midpoint rule on a fine (theta, phi) grid. */
static void
sky_irradiance(const cg_sky_model *m, double e[3])
{
    enum { NT = 512, NP = 1024 };
    e[0] = e[1] = e[2] = 0.0;
    for (int i = 0; i < NT; i++) {
        double theta = (i + 0.5) * (0.5 * PTF_PI) / NT;
        double w = cos(theta) * sin(theta) * (0.5 * PTF_PI / NT) * (2.0 * PTF_PI / NP);
        for (int j = 0; j < NP; j++) {
            double phi = (j + 0.5) * 2.0 * PTF_PI / NP;
            float d[3] = { (float)(sin(theta) * cos(phi)), (float)cos(theta), (float)(sin(theta) * sin(phi)) }, rgb[3];
            cg_sky_model_radiance(m, d, rgb);
            for (int c = 0; c < 3; c++)
                e[c] += rgb[c] * w;
        }
    }
}

/* A horizontal white plane (facing +y) under the Preetham sky, its sun 35 degrees above the
 * horizon (the directional light of intensity 0 only places the sun): each pixel is
 * a E_sky / pi, E_sky integrated by quadrature. The sky samples come from the importance
 * table, the continuation from the cosine: a wrong density in either, or wrong MIS weights,
 * moves the mean. Also: a camera looking straight up sees the zenith's radiance. */
static void
preetham_sky_on_a_white_plane(void **state)
{
    (void)state;
    enum { W = 16, H = 16 };
    const double albedo = 0.6;
    cg_scene s;
    ptf_scene_init(&s);
    mat4 m;
    glm_mat4_identity(m);
    glm_rotate(m, glm_rad(-90.0f), (vec3){ 1, 0, 0 }); /* +z onto +y */
    glm_scale(m, (vec3){ 50, 50, 1 });
    ptf_add_instance(&s, ptf_add_quad_mesh(&s, ptf_add_material(&s, (float)albedo, (float)albedo, (float)albedo, 0)), m);
    cg_light *sun = ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, 0.0f);
    double elevation = glm_rad(35.0f), azimuth = glm_rad(40.0f);
    sun->direction[0] = (float)(-cos(elevation) * cos(azimuth));
    sun->direction[1] = (float)-sin(elevation);
    sun->direction[2] = (float)(-cos(elevation) * sin(azimuth));
    cg_sky sky = { .type = CG_SKY_PREETHAM, .turbidity = 3, .scale = 0.1f };
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_set_sky(&s, &sky, &err), &err);
    cg_sky_model model;
    assert_cg_ok(cg_sky_model_init(&s, &model, &err), &err);
    double e[3];
    sky_irradiance(&model, e);
    cg_view v = { .width = W, .height = H, .orthographic = true };
    mat4 view, proj;
    glm_lookat((vec3){ 0, 5, 0 }, (vec3){ 0, 0, 0 }, (vec3){ 0, 0, -1 }, view);
    glm_ortho(-1, 1, -1, 1, 0.1f, 10.0f, proj);
    ptf_view_finish(&v, view, proj);
    pt_settings st = ptf_settings(64, 0);
    float *img = ptf_render(&s, &v, st);
    for (int c = 0; c < 3; c++) {
        double sum = 0.0, sum2 = 0.0;
        for (int i = 0; i < W * H; i++) {
            sum += img[4 * i + c];
            sum2 += (double)img[4 * i + c] * img[4 * i + c];
        }
        double mean = sum / (W * H), se = sqrt((sum2 / (W * H) - mean * mean) / (W * H));
        double want = albedo * e[c] / PTF_PI;
        print_message("# Preetham sky, channel %d: mean %.6f, a E_sky / pi = %.6f (standard error %.2g)\n", c, mean,
                      want, se);
        assert_true(se < 3e-3 * want);
        if (!(fabs(mean - want) <= 5.0 * se + 1e-4 * want)) /* 1e-4: the quadrature's own error */
            fail_msg("Preetham sky, channel %d: mean %.6f, expected %.6f (standard error %.2g)", c, mean, want, se);
    }
    free(img);
    /* An orthographic camera looking straight up: every ray goes to the zenith. */
    cg_view up = { .width = 4, .height = 4, .orthographic = true };
    glm_lookat((vec3){ 0, 1, 0 }, (vec3){ 0, 2, 0 }, (vec3){ 0, 0, 1 }, view);
    ptf_view_finish(&up, view, proj);
    img = ptf_render(&s, &up, pt_settings_default());
    float zenith[3] = { 0, 1, 0 }, rgb[3];
    cg_sky_model_radiance(&model, zenith, rgb);
    for (int i = 0; i < 16; i++)
        for (int c = 0; c < 3; c++)
            ptf_assert_rel(img[4 * i + c], rgb[c], 1e-5, "the zenith as background", i % 4, i / 4);
    free(img);
    ptf_scene_release(&s);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(sky_is_parsed_and_checked),
             cmocka_unit_test(preetham_zenith_is_the_papers),
             cmocka_unit_test(uniform_sky_on_a_white_plane_gives_albedo_times_l),
             cmocka_unit_test(open_box_floor_sees_the_sky_through_its_opening),
             cmocka_unit_test(preetham_sky_on_a_white_plane))
