/* Tests of the CPU path tracer behind the path_trace pass (pt_render.c), on scenes built
 * here whose answers are known in closed form. No GL needed. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cg/metrics.h"
#include "cg/pt_render.h"
#include "path_trace_fixture.h"
#include "test_support.h"


/* ------------------------------------------------------------ analytic tests */

static void
directional_light_on_white_plane_gives_e_over_pi(void **state)
{
    (void)state;
    enum { W = 16, H = 16 };
    cg_scene s;
    ptf_scene_init(&s);
    ptf_add_quad_at(&s, 0, 0, 0, 0, 10, 10);
    cg_light *l = ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, 3.0f);
    l->direction[2] = -1.0f;
    cg_view v = ptf_view_top_ortho(W, H);
    for (int bounces = 0; bounces <= 2; bounces++) {
        pt_settings st = ptf_settings(2, bounces);
        float *img = ptf_render(&s, &v, st);
        for (int i = 0; i < W * H; i++)
            for (int c = 0; c < 3; c++)
                ptf_assert_rel(img[4 * i + c], 3.0 / PTF_PI, 1e-5, "E/pi", i % W, i / W);
        free(img);
    }
    /* Tilted 60 degrees, coloured, albedo 0.5: L = a E cos(theta) / pi per channel. */
    int grey = ptf_add_material(&s, 0.5f, 0.5f, 0.5f, 0.0f);
    s.meshes[0].material = grey;
    l->color[0] = 1.0f, l->color[1] = 0.5f, l->color[2] = 0.25f;
    l->direction[0] = 0.0f, l->direction[1] = -(float)sin(PTF_PI / 3), l->direction[2] = -(float)cos(PTF_PI / 3);
    pt_settings st = pt_settings_default();
    st.spp = 1;
    float *img = ptf_render(&s, &v, st);
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++)
            ptf_assert_rel(img[4 * i + c], 0.5 * 3.0 * l->color[c] * 0.5 / PTF_PI, 1e-5, "aE cos/pi", i % W, i / W);
    free(img);
    ptf_scene_release(&s);
}

/* L = albedo I cos(theta) / (pi d^2) x spot falloff, at each pixel's point of the plane. */
static void
check_punctual(const cg_light *l, float albedo, const float *img, int w, int h)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double px, py;
            ptf_pixel_on_plane(x, y, w, h, &px, &py);
            double dx = l->position[0] - px, dy = l->position[1] - py, dz = l->position[2];
            double d = sqrt(dx * dx + dy * dy + dz * dz);
            double cos_theta = dz / d;
            double want = albedo * l->intensity * cos_theta / (PTF_PI * d * d), unattenuated = want;
            if (l->type == CG_LIGHT_SPOT) {
                /* KHR_lights_punctual: saturate((cd - cos_outer) / (cos_inner - cos_outer))^2. */
                double cd = -(l->direction[0] * dx + l->direction[1] * dy + l->direction[2] * dz) / d;
                double co = cos(l->outer_cone_angle), ci = cos(l->inner_cone_angle);
                double att = (cd - co) / (ci - co);
                att = att < 0 ? 0 : (att > 1 ? 1 : att);
                want *= att * att;
            }
            /* Float rounding of the hit point (ulps of the quad's 10 m vertices, about 1e-6 m)
             * moves the cone cosine by about 1e-6, which the falloff's slope
             * 1 / (cos_inner - cos_outer) ~ 8 amplifies: near the outer cone, where the falloff
             * is nearly 0, that is a large fraction of a small value. Hence 1e-4 of the light's
             * unattenuated radiance rather than 1e-5 of the value. */
            for (int c = 0; c < 3; c++) {
                double got = img[4 * (y * w + x) + c];
                if (!(fabs(got - want) <= 1e-4 * unattenuated))
                    fail_msg("I cos / (pi d^2) at pixel (%d,%d): got %.7g, expected %.7g", x, y, got, want);
            }
        }
}

static void
point_light_gives_inverse_square_cosine(void **state)
{
    (void)state;
    enum { W = 24, H = 16 };
    cg_scene s;
    ptf_floor_scene(&s, 0.7f);
    cg_light *l = ptf_add_light(&s, CG_LIGHT_POINT, 10.0f);
    l->position[0] = 0.3f, l->position[1] = -0.2f, l->position[2] = 1.5f;
    cg_view v = ptf_view_top_ortho(W, H);
    pt_settings st = ptf_settings(1, 1);
    float *img = ptf_render(&s, &v, st);
    check_punctual(l, 0.7f, img, W, H);
    free(img);
    ptf_scene_release(&s);
}

static void
spot_light_follows_the_cone_falloff(void **state)
{
    (void)state;
    enum { W = 32, H = 32 };
    cg_scene s;
    ptf_scene_init(&s);
    ptf_add_quad_at(&s, 0, 0, 0, 0, 10, 10);
    cg_light *l = ptf_add_light(&s, CG_LIGHT_SPOT, 4.0f);
    l->position[0] = 0.1f, l->position[2] = 1.0f;
    l->direction[2] = -1.0f;
    l->inner_cone_angle = 0.3f;
    l->outer_cone_angle = 0.6f;
    cg_view v = ptf_view_top_ortho(W, H);
    pt_settings st = pt_settings_default();
    st.spp = 1;
    float *img = ptf_render(&s, &v, st);
    check_punctual(l, 1.0f, img, W, H);
    /* The corners are outside the outer cone: black. */
    assert_true(img[0] == 0.0f && img[4 * (W * H - 1)] == 0.0f);
    free(img);
    ptf_scene_release(&s);
}

/* A closed cube of albedo a and emission Le seen from inside: the camera sees Le, and each
 * vertex x1 ... x(n+1) of an n-bounce path receives Le from every direction, reflected
 * a Le: the pixel mean is Le sum_{k=0..n+1} a^k. Emitter sampling and cosine sampling are
 * combined per sample, so pixels are noisy: the mean over the image must be the closed form
 * within 5 standard errors, with a standard error small enough (below 0.3%) that an error of
 * 1% would fail. */
static void
furnace_gives_the_closed_form(void **state)
{
    (void)state;
    enum { W = 32, H = 24 };
    const float a = 0.6f, le = 0.5f;
    cg_scene s;
    ptf_scene_init(&s);
    int mat = ptf_add_material(&s, a, a, a, le);
    int quad = ptf_add_quad_mesh(&s, mat);
    /* Six faces of the cube [-1,1]^3, normals inwards and outwards mixed on purpose: the
     * tracer must not care which way a closed surface's triangles wind. */
    static const float rot[6][4] = { { 0, 1, 0, 0 }, { 180, 1, 0, 0 }, { 90, 1, 0, 0 },
                                     { -90, 1, 0, 0 }, { 90, 0, 1, 0 }, { -90, 0, 1, 0 } };
    for (int f = 0; f < 6; f++) {
        mat4 m;
        glm_mat4_identity(m);
        glm_rotate(m, glm_rad(rot[f][0]), (vec3){ rot[f][1], rot[f][2], rot[f][3] });
        glm_translate(m, (vec3){ 0, 0, 1 });
        ptf_add_instance(&s, quad, m);
    }
    cg_view v = ptf_view_perspective(W, H, (vec3){ 0.2f, -0.1f, 0.3f }, (vec3){ 1, 0.5f, -1 });
    for (int n = 0; n <= 3; n++) {
        double want = 0.0;
        for (int k = 0; k <= n + 1; k++)
            want += le * pow(a, k);
        pt_settings st = ptf_settings(16, n);
        st.jitter = true;
        float *img = ptf_render(&s, &v, st);
        double mean, se;
        ptf_residual_mean(img, NULL, W * H, &mean, &se);
        print_message("# furnace, %d bounces: mean %.5f, closed form Le sum_{k=0..%d} a^k = %.5f, standard "
                      "error %.2g\n", n, mean, n + 1, want, se);
        assert_true(se < 3e-3 * want);
        if (!(fabs(mean - want) <= 5.0 * se))
            fail_msg("furnace, %d bounces: mean %.6f, expected %.6f (standard error %.2g)", n, mean, want, se);
        free(img);
    }
    ptf_scene_release(&s);
}

/* A white floor under an emissive rectangle (radiance Le, outside the camera's view) at
 * height h: each floor point has radiance albedo x Le x F, F the view factor above, at
 * 0 bounces (the emitter's direct light, which the tracer used to leave to the first
 * bounce). The emitter is tested facing down and facing up: emission is two-sided. */
static void
emissive_rectangle_lights_the_floor_by_its_view_factor(void **state)
{
    (void)state;
    enum { W = 24, H = 24 };
    const double h = 0.8, x1 = 1.2, x2 = 2.2, y1 = -0.6, y2 = 0.9, le = 3.0, albedo = 0.7;
    for (int side = 0; side < 2; side++) {
        cg_scene s;
        ptf_scene_init(&s);
        ptf_add_quad_at(&s, ptf_add_material(&s, (float)albedo, (float)albedo, (float)albedo, 0.0f), 0, 0, 0, 10, 10);
        int lamp = ptf_add_material(&s, 0, 0, 0, (float)le);
        mat4 m;
        glm_mat4_identity(m);
        glm_translate(m, (vec3){ (float)(0.5 * (x1 + x2)), (float)(0.5 * (y1 + y2)), (float)h });
        if (side == 0)
            glm_rotate(m, glm_rad(180.0f), (vec3){ 1, 0, 0 }); /* facing down, towards the floor */
        glm_scale(m, (vec3){ (float)(0.5 * (x2 - x1)), (float)(0.5 * (y2 - y1)), 1.0f });
        ptf_add_instance(&s, ptf_add_quad_mesh(&s, lamp), m);
        cg_view v = ptf_view_top_ortho(W, H);
        pt_settings st = ptf_settings(256, 0);
        float *img = ptf_render(&s, &v, st);
        double want[W * H], total = 0.0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double px, py;
                ptf_pixel_on_plane(x, y, W, H, &px, &py);
                double f = ptf_corner_view_factor(x2 - px, y2 - py, h) - ptf_corner_view_factor(x1 - px, y2 - py, h) -
                           ptf_corner_view_factor(x2 - px, y1 - py, h) + ptf_corner_view_factor(x1 - px, y1 - py, h);
                want[y * W + x] = albedo * le * f;
                total += want[y * W + x];
            }
        double mean, se;
        ptf_residual_mean(img, want, W * H, &mean, &se);
        total /= W * H;
        print_message("# emitter facing %s: mean residual %.3g of a mean %.5f (standard error %.2g)\n",
                      side == 0 ? "down" : "up", mean, total, se);
        assert_true(se < 5e-3 * total);
        if (!(fabs(mean) <= 5.0 * se))
            fail_msg("emissive rectangle facing %s: mean residual %.4g, standard error %.2g, mean %.5f",
                     side == 0 ? "down" : "up", mean, se, total);
        /* And in each quadrant of the image (the view factor falls from 0.14 to 0.03 over
         * it), so that an error in the shape of the falloff cannot hide in the mean. */
        for (int q = 0; q < 4; q++) {
            double r = 0.0, r2 = 0.0;
            int count = 0;
            for (int y = (q / 2) * H / 2; y < (q / 2 + 1) * H / 2; y++)
                for (int x = (q % 2) * W / 2; x < (q % 2 + 1) * W / 2; x++, count++) {
                    double d = img[4 * (y * W + x)] - want[y * W + x];
                    r += d;
                    r2 += d * d;
                }
            r /= count;
            double qse = sqrt((r2 / count - r * r) / count);
            if (!(fabs(r) <= 5.0 * qse))
                fail_msg("emissive rectangle facing %s, quadrant %d: mean residual %.4g, standard error %.2g",
                         side == 0 ? "down" : "up", q, r, qse);
        }
        free(img);
        ptf_scene_release(&s);
    }
}

/* Rays go through pixel centres, row 0 at the top: an emissive rectangle over
 * x in [-1, -0.49], y in [0.24, 1] covers exactly pixel columns 0-1 and rows 0-2 of 8x8. */
static void
camera_rays_go_through_pixel_centres_top_row_first(void **state)
{
    (void)state;
    enum { W = 8, H = 8 };
    cg_scene s;
    ptf_scene_init(&s);
    ptf_add_quad_at(&s, ptf_add_material(&s, 0, 0, 0, 1.0f), -0.745f, 0.62f, 0.0f, 0.255f, 0.38f);
    cg_view v = ptf_view_top_ortho(W, H);
    pt_settings st = pt_settings_default();
    st.spp = 1;
    float *img = ptf_render(&s, &v, st);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float want = (x <= 1 && y <= 2) ? 1.0f : 0.0f;
            ptf_assert_rel(img[4 * (y * W + x)], want, 0.0, "coverage", x, y);
            ptf_assert_rel(img[4 * (y * W + x) + 3], 1.0, 0.0, "alpha", x, y);
        }
    free(img);
    ptf_scene_release(&s);
}

/* A plane lit at 85 degrees from its normal, at sizes from 1e-6 m to 1e6 m and far from the
 * origin (1000 times its size away): every pixel is exactly a E cos / pi. A shadow ray that
 * finds its own plane again (ray offsets too small for the coordinates' float precision)
 * would leave black pixels; an offset with an absolute floor would lift the rays of the
 * 1e-6 m plane off into nothing, which this test cannot see, but the furnace and Cornell
 * scale sweeps (test_path_trace_scale.c) do. */
static void
grazing_light_far_from_the_origin_casts_no_self_shadow(void **state)
{
    (void)state;
    enum { W = 32, H = 32 };
    const double sizes[] = { 1e-6, 1e-2, 1.0, 1e3, 1e6 };
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        double size = sizes[k];
        float x0 = (float)(1000.0 * size), y0 = (float)(-700.0 * size);
        cg_scene s;
        ptf_scene_init(&s);
        /* The plane through (x0, y0, 0), tilted 30 degrees about y: its normal has two
         * non-zero components, so no coordinate of the offset is exact. */
        mat4 m;
        glm_mat4_identity(m);
        glm_translate(m, (vec3){ x0, y0, 0.0f });
        glm_rotate(m, glm_rad(30.0f), (vec3){ 0, 1, 0 });
        glm_scale(m, (vec3){ (float)(10 * size), (float)(10 * size), 1.0f });
        int grey = ptf_add_material(&s, 0.8f, 0.8f, 0.8f, 0.0f);
        ptf_add_instance(&s, ptf_add_quad_mesh(&s, grey), m);
        /* The light 85 degrees off the normal n = (sin 30, 0, cos 30), tilted towards +x. */
        double t = glm_rad(30.0f) + glm_rad(85.0f);
        cg_light *l = ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, 2.0f);
        l->direction[0] = (float)-sin(t), l->direction[1] = 0.0f, l->direction[2] = (float)-cos(t);
        double n[3] = { sin(glm_rad(30.0f)), 0.0, cos(glm_rad(30.0f)) };
        double cos_theta = -(n[0] * l->direction[0] + n[2] * l->direction[2]);
        double want = 0.8 * 2.0 * cos_theta / PTF_PI;
        cg_view v = { .width = W, .height = H, .orthographic = true };
        mat4 view, proj;
        glm_lookat((vec3){ x0, y0, (float)(5 * size) }, (vec3){ x0, y0, 0 }, (vec3){ 0, 1, 0 }, view);
        glm_ortho((float)-size, (float)size, (float)-size, (float)size, (float)(0.1 * size), (float)(20 * size), proj);
        ptf_view_finish(&v, view, proj);
        pt_settings st = ptf_settings(1, 0);
        float *img = ptf_render(&s, &v, st);
        for (int i = 0; i < W * H; i++)
            for (int c = 0; c < 3; c++)
                if (!(fabs(img[4 * i + c] - want) <= 1e-4 * want))
                    fail_msg("plane of %g m at %g m from the origin, pixel (%d,%d): %.7g, expected a E cos / pi = %.7g",
                             size, 1000.0 * size, i % W, i / W, img[4 * i + c], want);
        free(img);
        ptf_scene_release(&s);
    }
}

static void
hard_shadows_block_punctual_light(void **state)
{
    (void)state;
    enum { W = 8, H = 8 };
    cg_scene s;
    ptf_scene_init(&s);
    ptf_add_quad_at(&s, 0, 0, 0, 0, 10, 10);
    /* An occluder over x < 0 at height 1, lit from straight above: the left half is black. */
    ptf_add_quad_at(&s, 0, -5.0f, 0, 1.0f, 5.0f, 10.0f);
    cg_light *l = ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, 2.0f);
    l->direction[2] = -1.0f;
    /* Looking from below the occluder: a camera at z = 0.5. */
    cg_view v = { .width = W, .height = H, .orthographic = true };
    mat4 view, proj;
    glm_lookat((vec3){ 0, 0, 0.5f }, (vec3){ 0, 0, 0 }, (vec3){ 0, 1, 0 }, view);
    glm_ortho(-1, 1, -1, 1, 0.1f, 10.0f, proj);
    ptf_view_finish(&v, view, proj);
    pt_settings st = ptf_settings(1, 0);
    float *img = ptf_render(&s, &v, st);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            ptf_assert_rel(img[4 * (y * W + x)], x < W / 2 ? 0.0 : 2.0 / PTF_PI, 1e-5, "shadow", x, y);
    free(img);
    ptf_scene_release(&s);
}

/* A 2x2 sRGB texture seen through a 2x2 image: pixel centres land on texel centres, so
 * the bilinear filter returns the decoded texels; the top image row is the top texel row
 * (rows are stored bottom to top as GL expects). */
static void
base_colour_texture_is_srgb_decoded(void **state)
{
    (void)state;
    cg_scene s;
    ptf_scene_init(&s);
    static const uint8_t texels[16] = { 255, 0, 0, 255, 0, 255, 0, 255,     /* bottom row */
                                        0, 0, 255, 255, 128, 128, 128, 255 }; /* top row */
    s.textures = ptf_grow(NULL, 0, sizeof *s.textures);
    s.texture_count = 1;
    s.textures[0].width = s.textures[0].height = 2;
    s.textures[0].srgb = true;
    s.textures[0].rgba = malloc(sizeof texels);
    memcpy(s.textures[0].rgba, texels, sizeof texels);
    int mat = ptf_add_material(&s, 1, 1, 1, 0);
    s.materials[mat].base_color_texture = 0;
    ptf_add_quad_at(&s, mat, 0, 0, 0, 1, 1);
    cg_light *l = ptf_add_light(&s, CG_LIGHT_DIRECTIONAL, (float)PTF_PI);
    l->direction[2] = -1.0f;
    cg_view v = ptf_view_top_ortho(2, 2);
    pt_settings st = pt_settings_default();
    st.spp = 1;
    float *img = ptf_render(&s, &v, st);
    double grey = pow((128.0 / 255.0 + 0.055) / 1.055, 2.4);
    const double want[4][3] = { { 0, 0, 1 }, { grey, grey, grey }, { 1, 0, 0 }, { 0, 1, 0 } };
    for (int i = 0; i < 4; i++)
        for (int c = 0; c < 3; c++)
            ptf_assert_rel(img[4 * i + c], want[i][c], 1e-5, "texel", i % 2, i / 2);
    free(img);
    ptf_scene_release(&s);
}

/* ------------------------------------------------------------ noise, convergence, determinism */

/* A box open towards the camera with a point light inside, a red wall and a small
 * emitter: every pixel has indirect light, so images are noisy at low sample counts. */
static void
noisy_scene(cg_scene *s)
{
    ptf_scene_init(s);
    int white = ptf_add_material(s, 0.8f, 0.8f, 0.8f, 0.0f);
    int red = ptf_add_material(s, 0.8f, 0.2f, 0.2f, 0.0f);
    int quad_w = ptf_add_quad_mesh(s, white), quad_r = ptf_add_quad_mesh(s, red);
    static const float rot[5][4] = { { 0, 1, 0, 0 }, { 90, 1, 0, 0 }, { -90, 1, 0, 0 },
                                     { 90, 0, 1, 0 }, { -90, 0, 1, 0 } };
    for (int f = 0; f < 5; f++) {
        mat4 m;
        glm_mat4_identity(m);
        glm_rotate(m, glm_rad(rot[f][0]), (vec3){ rot[f][1], rot[f][2], rot[f][3] });
        glm_translate(m, (vec3){ 0, 0, -1 });
        ptf_add_instance(s, f == 3 ? quad_r : quad_w, m);
    }
    ptf_add_quad_at(s, ptf_add_material(s, 0, 0, 0, 2.0f), 0.5f, 0.5f, -0.999f, 0.2f, 0.2f);
    cg_light *l = ptf_add_light(s, CG_LIGHT_POINT, 1.5f);
    l->position[0] = -0.3f, l->position[1] = 0.6f, l->position[2] = 0.2f;
}

static double
rel_mse(const float *a, const float *b, int w, int h)
{
    cg_image ia = { w, h, (float *)a }, ib = { w, h, (float *)b };
    cg_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_compute(&ia, &ib, &m, &err), &err);
    return m.rel_mse;
}

static void
error_falls_with_sample_count(void **state)
{
    (void)state;
    enum { W = 32, H = 32 };
    cg_scene s;
    noisy_scene(&s);
    cg_view v = ptf_view_perspective(W, H, (vec3){ 0, 0, 3.0f }, (vec3){ 0, 0, 0 });
    pt_settings st = ptf_settings(512, 2);
    st.seed = 99; /* independent of the images under test */
    float *ref = ptf_render(&s, &v, st);
    st.seed = 1;
    st.spp = 4;
    float *low = ptf_render(&s, &v, st);
    st.spp = 16;
    float *high = ptf_render(&s, &v, st);
    double e_low = rel_mse(low, ref, W, H), e_high = rel_mse(high, ref, W, H);
    /* Variance falls as 1/N; the reference's own variance adds V/512 to both, so the
     * expected ratio is (1/4 + 1/512) / (1/16 + 1/512) = 3.9. */
    double ratio = e_low / e_high;
    print_message("# relMSE 4 spp %.5f, 16 spp %.5f, ratio %.2f\n", e_low, e_high, ratio);
    assert_true(e_low > 0.0);
    assert_true(ratio > 3.0 && ratio < 5.0);
    free(ref);
    free(low);
    free(high);
    ptf_scene_release(&s);
}

static void
bit_identical_across_runs_and_thread_counts(void **state)
{
    (void)state;
    enum { W = 40, H = 24 };
    cg_scene s;
    noisy_scene(&s);
    cg_view v = ptf_view_perspective(W, H, (vec3){ 0, 0, 3.0f }, (vec3){ 0, 0, 0 });
    pt_settings st = ptf_settings(3, 2);
    st.jitter = true;
    st.threads = 1;
    float *one = ptf_render(&s, &v, st);
    const int counts[] = { 1, 2, 3, 7 };
    for (int k = 0; k < 4; k++) {
        st.threads = counts[k];
        float *other = ptf_render(&s, &v, st);
        if (memcmp(one, other, sizeof(float) * 4 * W * H) != 0)
            fail_msg("image with %d threads differs from the one with 1", counts[k]);
        free(other);
    }
    st.seed = 2;
    float *reseeded = ptf_render(&s, &v, st);
    assert_true(memcmp(one, reseeded, sizeof(float) * 4 * W * H) != 0);
    free(reseeded);
    free(one);
    ptf_scene_release(&s);
}

/* The parts of the image (pt_render_parts) on the open box with a point light, an emitter
 * and a uniform sky outside: they add up to the image (which is bit-identical with and
 * without parts), the indirect part is 0 at 0 bounces, and what does not depend on bounces
 * (what the camera sees, light reflected once) is bit-identical at 0 and 2 bounces. */
static void
parts_add_up_to_the_image(void **state)
{
    (void)state;
    enum { W = 24, H = 16, N = W * H };
    cg_scene s;
    noisy_scene(&s);
    cg_sky sky = { .type = CG_SKY_UNIFORM, .radiance = { 0.2f, 0.3f, 0.5f } };
    cg_error err = { 0 };
    assert_cg_ok(cg_scene_set_sky(&s, &sky, &err), &err);
    cg_view v = ptf_view_perspective(W, H, (vec3){ 0.3f, 0.2f, 2.5f }, (vec3){ 0, 0, 0 });
    pt_scene *pts;
    assert_cg_ok(pt_scene_create(&s, &pts, &err), &err);
    float *img[2], *parts[2][PT_PART_COUNT];
    for (int b = 0; b < 2; b++) {
        pt_settings st = ptf_settings(4, 2 * b);
        img[b] = malloc(sizeof(float) * 4 * N);
        assert_non_null(img[b]);
        for (int p = 0; p < PT_PART_COUNT; p++) {
            parts[b][p] = malloc(sizeof(float) * 4 * N);
            assert_non_null(parts[b][p]);
        }
        assert_cg_ok(pt_render_parts(pts, &v, &st, img[b], parts[b], NULL, &err), &err);
        float *plain = malloc(sizeof(float) * 4 * N);
        assert_non_null(plain);
        assert_cg_ok(pt_render(pts, &v, &st, plain, NULL, &err), &err);
        assert_memory_equal(plain, img[b], sizeof(float) * 4 * N);
        free(plain);
        double part_mean[PT_PART_COUNT] = { 0 };
        for (int i = 0; i < N; i++)
            for (int c = 0; c < 3; c++) {
                double sum = 0.0;
                for (int p = 0; p < PT_PART_COUNT; p++) {
                    sum += parts[b][p][4 * i + c];
                    part_mean[p] += parts[b][p][4 * i + c] / (3.0 * N);
                }
                if (!(fabs(sum - img[b][4 * i + c]) <= 1e-5 * fabs(img[b][4 * i + c]) + 1e-7))
                    fail_msg("%d bounces, pixel (%d,%d).%d: parts add up to %.7g, the image is %.7g", st.bounces,
                             i % W, i / W, c, sum, img[b][4 * i + c]);
            }
        print_message("# %d bounces: mean emitted %.4f, direct punctual %.4f, emitters %.4f, sky %.4f, indirect %.4f\n",
                      st.bounces, part_mean[0], part_mean[1], part_mean[2], part_mean[3], part_mean[4]);
        for (int p = 0; p < PT_PART_INDIRECT; p++)
            assert_true(part_mean[p] > 0.0); /* every source is in view or lights something */
        assert_true(b == 0 ? part_mean[PT_PART_INDIRECT] == 0.0 : part_mean[PT_PART_INDIRECT] > 0.0);
    }
    for (int p = 0; p < PT_PART_INDIRECT; p++)
        if (memcmp(parts[0][p], parts[1][p], sizeof(float) * 4 * N))
            fail_msg("part %s differs between 0 and 2 bounces", pt_part_name((pt_part)p));
    for (int b = 0; b < 2; b++) {
        free(img[b]);
        for (int p = 0; p < PT_PART_COUNT; p++)
            free(parts[b][p]);
    }
    pt_scene_destroy(pts);
    ptf_scene_release(&s);
}

static void
bad_settings_are_usage_errors(void **state)
{
    (void)state;
    cg_scene s;
    noisy_scene(&s);
    pt_scene *pts;
    cg_error err = { 0 };
    assert_cg_ok(pt_scene_create(&s, &pts, &err), &err);
    assert_int_equal(pt_scene_triangle_count(pts), 12);
    cg_view v = ptf_view_top_ortho(4, 4);
    float img[4 * 4 * 4];
    pt_settings st = pt_settings_default();
    st.spp = 0;
    assert_cg_status(pt_render(pts, &v, &st, img, NULL, &err), &err, CG_ERR_USAGE);
    st = pt_settings_default();
    st.bounces = -1;
    assert_cg_status(pt_render(pts, &v, &st, img, NULL, &err), &err, CG_ERR_USAGE);
    st = pt_settings_default();
    st.threads = -2;
    assert_cg_status(pt_render(pts, &v, &st, img, NULL, &err), &err, CG_ERR_USAGE);
    v.width = 0;
    st = pt_settings_default();
    assert_cg_status(pt_render(pts, &v, &st, img, NULL, &err), &err, CG_ERR_USAGE);
    pt_scene_destroy(pts);
    ptf_scene_release(&s);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(directional_light_on_white_plane_gives_e_over_pi),
             cmocka_unit_test(point_light_gives_inverse_square_cosine),
             cmocka_unit_test(spot_light_follows_the_cone_falloff),
             cmocka_unit_test(furnace_gives_the_closed_form),
             cmocka_unit_test(emissive_rectangle_lights_the_floor_by_its_view_factor),
             cmocka_unit_test(camera_rays_go_through_pixel_centres_top_row_first),
             cmocka_unit_test(hard_shadows_block_punctual_light),
             cmocka_unit_test(grazing_light_far_from_the_origin_casts_no_self_shadow),
             cmocka_unit_test(base_colour_texture_is_srgb_decoded),
             cmocka_unit_test(error_falls_with_sample_count),
             cmocka_unit_test(bit_identical_across_runs_and_thread_counts),
             cmocka_unit_test(parts_add_up_to_the_image),
             cmocka_unit_test(bad_settings_are_usage_errors))
