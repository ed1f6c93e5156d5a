/* The path tracer at every scale (no GL needed): the same scene scaled from 1e-6 m to 1e6 m
 * (lights scaled to give the same irradiance) gives the same image, the white furnace keeps
 * its closed form at every scale, and a kilometre-sized scene seen through a 5 cm near plane
 * gives the image of the same scene at 1 m. Epsilons that do not follow the scene's size
 * (a ray offset of at least 1e-4 m, a near-plane ray built as the difference of two world
 * points) fail here. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/camera.h"
#include "cg/metrics.h"
#include "cg/pt_render.h"
#include "cg/scene.h"
#include "test_support.h"
#include "path_trace_fixture.h"

static float *
render_scene(const cg_scene *scene, int w, int h, const pt_settings *st)
{
    cg_view view;
    cg_view_from_scene(scene, 0, w, h, &view);
    float *img = malloc(sizeof(float) * 4 * (size_t)w * (size_t)h);
    assert_non_null(img);
    pt_scene *pts;
    cg_error err = { 0 };
    assert_cg_ok(pt_scene_create(scene, &pts, &err), &err);
    assert_cg_ok(pt_render(pts, &view, st, img, NULL, &err), &err);
    pt_scene_destroy(pts);
    return img;
}

static cg_metrics
compare(const float *test, const float *ref, int w, int h)
{
    cg_image it = { w, h, (float *)test }, ir = { w, h, (float *)ref };
    cg_metrics m;
    cg_error err = { 0 };
    assert_cg_ok(cg_metrics_compute(&it, &ir, &m, &err), &err);
    return m;
}

/* Mean of the RGB channels over the image, and the standard error of that mean from the
 * spread of the pixels (pixels are independent: each has its own random numbers). */
static void
image_mean(const float *img, int n, double *mean, double *std_error)
{
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            s += img[4 * i + c];
            s2 += (double)img[4 * i + c] * img[4 * i + c];
        }
    double count = 3.0 * n;
    *mean = s / count;
    double var = s2 / count - *mean * *mean;
    *std_error = sqrt(var > 0.0 ? var / n : 0.0);
}

static const double scales[] = { 1e-6, 1e-5, 1e-3, 1.0, 1e3, 1e6 };
#define SCALE_COUNT ((int)(sizeof scales / sizeof scales[0]))

/* builtin:furnace?scale=S (albedo 0.5, emission 1, one bounce): the mean is the closed form
 * 1 + 0.5 + 0.25 at every scale (within 5 standard errors of the pixel spread), and the image
 * is that of scale 1. */
static void
furnace_at_every_scale(void **state)
{
    (void)state;
    enum { W = 24, H = 16 };
    pt_settings st = ptf_settings(16, 1);
    st.jitter = true;
    st.threads = 2;
    const double a = 0.5, le = 1.0;
    double want = 0.0;
    for (int k = 0; k <= st.bounces + 1; k++) /* emission, direct light of it, one bounce */
        want += le * pow(a, k);
    float *images[SCALE_COUNT];
    int unit = -1;
    for (int i = 0; i < SCALE_COUNT; i++) {
        char source[128];
        snprintf(source, sizeof source, "builtin:furnace?scale=%g", scales[i]);
        cg_scene scene;
        cg_error err = { 0 };
        assert_cg_ok(cg_scene_load(source, &scene, &err), &err);
        images[i] = render_scene(&scene, W, H, &st);
        cg_scene_free(&scene);
        if (scales[i] == 1.0)
            unit = i;
        double mean, se;
        image_mean(images[i], W * H, &mean, &se);
        print_message("# furnace scale %g: mean %.6f (closed form %.6f, standard error %.2g)\n", scales[i],
                      mean, want, se);
        /* Five standard errors, and float rounding when the estimate has no variance. */
        if (!(fabs(mean - want) <= 5.0 * se + 1e-5 * want))
            fail_msg("furnace at scale %g: mean %.6f, expected %.6f", scales[i], mean, want);
    }
    for (int i = 0; i < SCALE_COUNT; i++) {
        cg_metrics m = compare(images[i], images[unit], W, H);
        print_message("# furnace scale %g against scale 1: relMSE %.3g\n", scales[i], m.rel_mse);
        if (!(m.rel_mse < 1e-3))
            fail_msg("furnace at scale %g: relMSE %.3g against scale 1", scales[i], m.rel_mse);
    }
    for (int i = 0; i < SCALE_COUNT; i++)
        free(images[i]);
}

/* builtin:cornell scaled from 1e-6 to 1e6 with its spot light scaled to match: the image of
 * scale 1, to relMSE 1e-3 and mean luminance to 0.2%. By powers of two the scaled scene is
 * exactly the same scene (float scaling by 2^k is exact), so rays through pixel centres must
 * give the same image. By powers of ten the vertices round differently and a pixel centre
 * that lies on an edge (the box is symmetric about the camera's axis) may fall on either
 * side: samples spread over the pixel (jitter) keep such edges from counting. */
static void
cornell_at_every_scale(void **state)
{
    (void)state;
    enum { W = 40, H = 40 };
    static const struct {
        double scale;
        bool jitter;
    } cases[] = { { 0x1p-20, false }, { 0x1p-10, false }, { 0x1p10, false }, { 0x1p20, false },
                  { 1e-6, true },     { 1e-3, true },     { 1e3, true },     { 1e6, true } };
    pt_settings st = ptf_settings(8, 1);
    st.threads = 2;
    cg_error err = { 0 };
    cg_scene scene = cg_test_load_scene("builtin:cornell");
    float *ref[2];
    for (int j = 0; j < 2; j++) {
        st.jitter = j;
        ref[j] = render_scene(&scene, W, H, &st);
    }
    cg_scene_free(&scene);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        assert_cg_ok(cg_scene_load("builtin:cornell", &scene, &err), &err);
        cg_test_scale_scene(&scene, cases[i].scale);
        st.jitter = cases[i].jitter;
        float *img = render_scene(&scene, W, H, &st);
        cg_scene_free(&scene);
        cg_metrics m = compare(img, ref[st.jitter], W, H);
        print_message("# cornell scale %g (%s) against scale 1: relMSE %.3g, mean luminance ratio %.5f\n",
                      cases[i].scale, st.jitter ? "jitter" : "pixel centres", m.rel_mse, m.mean_luminance_ratio);
        if (!(m.rel_mse < 1e-3 && fabs(m.mean_luminance_ratio - 1.0) < 2e-3))
            fail_msg("cornell at scale %g: relMSE %.3g, luminance ratio %.5f against scale 1", cases[i].scale,
                     m.rel_mse, m.mean_luminance_ratio);
        free(img);
    }
    free(ref[0]);
    free(ref[1]);
}

/* The Cornell box scaled to 1 km (by 1024: exactly the same scene; its camera 1.9 km from the
 * box, 512 m above the origin) seen through a 5 cm near plane, against the 1 m box, both
 * through pixel centres: the same image. A ray built from two world points 5 cm apart
 * (what the tracer did before) moves edges by whole pixels there. */
static void
kilometre_scene_through_a_5cm_near_plane(void **state)
{
    (void)state;
    enum { W = 40, H = 40 };
    pt_settings st = ptf_settings(8, 1);
    st.threads = 2;
    cg_scene scene = cg_test_load_scene("builtin:cornell");
    float *ref = render_scene(&scene, W, H, &st);
    cg_test_scale_scene(&scene, 1024.0);
    scene.cameras[0].znear = 0.05f;
    float *img = render_scene(&scene, W, H, &st);
    cg_scene_free(&scene);
    cg_metrics m = compare(img, ref, W, H);
    print_message("# cornell at 1 km through a 5 cm near plane: relMSE %.3g, mean luminance ratio %.5f\n",
                  m.rel_mse, m.mean_luminance_ratio);
    if (!(m.rel_mse < 1e-3 && fabs(m.mean_luminance_ratio - 1.0) < 2e-3))
        fail_msg("1 km through a 5 cm near plane: relMSE %.3g, luminance ratio %.5f against 1 m", m.rel_mse,
                 m.mean_luminance_ratio);
    free(img);
    free(ref);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(furnace_at_every_scale),
             cmocka_unit_test(cornell_at_every_scale),
             cmocka_unit_test(kilometre_scene_through_a_5cm_near_plane))
