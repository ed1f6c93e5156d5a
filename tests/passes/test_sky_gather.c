/* The sky in the raster graphs (passes/sdk/sky.h, shaders/common/sky.glsl), small images:
 *   - the bake: a uniform sky is L in every texel of every layer, to the bit; layer 0 of a
 *     Preetham sky is cg_sky_model_radiance at the texel centres; its widest layer (a
 *     hemisphere, cosine-weighted) at the zenith is the sky's irradiance / pi by quadrature;
 *   - cgp_sky_update bakes once per change of the sky (and of the sun, for Preetham), not per frame;
 *   - a white plane under an unoccluded uniform sky: albedo x L in the path tracer (exactly),
 *     in graphs/vct.json and graphs/hybrid.json;
 *   - the background of vct.json and hybrid.json equals the path tracer's: a uniform sky to the
 *     bit, a Preetham sky to the bilinear filtering of the 128 x 64 texture;
 *   - a plane under the Preetham sky in both cone tracers against the path tracer. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdk/pass.h"
#include "sdk/sky.h"
#include "cg/gl.h"
#include "hybrid_fixture.h"
#include "test_support.h"

#define PI 3.14159265358979323846

static void
test_bake(void **state)
{
    (void)state;
    hf_scene s;
    hf_init(&s);
    hf_grid(&s, 1, -1, -1, 2, hf_flat, NULL);
    hf_finish(&s);
    cg_error err = {0};
    float *t = malloc(CGP_SKY_BYTES);
    assert_non_null(t);
    const size_t n = CGP_SKY_BYTES / sizeof(float) / 4;
    const size_t layer = (size_t)CGP_SKY_WIDTH * CGP_SKY_HEIGHT;

    cg_sky uniform = {.type = CG_SKY_UNIFORM, .radiance = {0.3f, 1.7f, 1e6f}};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &uniform, &err), &err);
    assert_cg_ok(cgp_sky_bake(&s.scene, t, &err), &err);
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            if (t[4 * i + c] != uniform.radiance[c])
                fail_msg("uniform sky: texel %zu channel %d is %.9g, not %.9g", i, c, t[4 * i + c],
                         uniform.radiance[c]);

    /* Preetham, the sun 35 degrees up. */
    const double elevation = 35.0 * PI / 180.0;
    const double sun_dir[3] = {-cos(elevation), -sin(elevation), 0.0};
    hf_sun(&s, sun_dir, 1.0f);
    cg_sky preetham = {.type = CG_SKY_PREETHAM, .turbidity = 3, .scale = 0.01f};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &preetham, &err), &err);
    assert_cg_ok(cgp_sky_bake(&s.scene, t, &err), &err);
    cg_sky_model m;
    assert_cg_ok(cg_sky_model_init(&s.scene, &m, &err), &err);
    for (int j = 0; j < CGP_SKY_HEIGHT; j++)
        for (int i = 0; i < CGP_SKY_WIDTH; i++) {
            double d[3];
            cgp_sky_direction(i, j, d);
            float dir[3] = {(float)d[0], (float)d[1], (float)d[2]}, rgb[3];
            cg_sky_model_radiance(&m, dir, rgb);
            const float *texel = t + 4 * ((size_t)j * CGP_SKY_WIDTH + i);
            for (int c = 0; c < 3; c++)
                assert_true(texel[c] == rgb[c]);
        }
    /* The irradiance of a horizontal plane by quadrature (1024 x 4096 midpoints), over pi, against
     * the widest layer's top row (2.8 degrees off the zenith: the mean of its 128 texels). */
    double e = 0.0;
    const int nt = 1024, np = 4096;
    for (int a = 0; a < nt; a++) {
        double theta = (a + 0.5) * 0.5 * PI / nt;
        for (int b = 0; b < np; b++) {
            double phi = (b + 0.5) * 2.0 * PI / np;
            float dir[3] = {(float)(sin(theta) * cos(phi)), (float)cos(theta), (float)(sin(theta) * sin(phi))}, rgb[3];
            cg_sky_model_radiance(&m, dir, rgb);
            e += (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]) * cos(theta) * sin(theta) *
                 (0.5 * PI / nt) * (2.0 * PI / np);
        }
    }
    double top = 0.0;
    const float *wide = t + (CGP_SKY_LAYERS - 1) * layer * 4;
    for (int i = 0; i < CGP_SKY_WIDTH; i++)
        top += (0.2126 * wide[4 * i] + 0.7152 * wide[4 * i + 1] + 0.0722 * wide[4 * i + 2]) / CGP_SKY_WIDTH;
    printf("# Preetham (T 3, sun 35 deg up): E/pi by quadrature %.6g, widest layer at the zenith %.6g (%+.3f%%)\n",
           e / PI, top, 100.0 * (top / (e / PI) - 1.0));
    assert_true(fabs(top / (e / PI) - 1.0) < 0.02);
    free(t);
    hf_free(&s);
}

static void
test_bakes_once_per_change(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    hf_scene s;
    hf_init(&s);
    hf_grid(&s, 1, -1, -1, 2, hf_flat, NULL);
    const double down[3] = {0.3, -1, 0.2};
    hf_sun(&s, down, 1.0f);
    hf_finish(&s);
    cg_error err = {0};
    void *owner = cgp_state_new(NULL, 16, &err);
    assert_non_null(owner);
    cgp_sky sky;
    cgp_sky_prepare(owner, &sky);
    assert_cg_ok(cgp_sky_update(owner, &sky, &s.scene, &err), &err);
    assert_true(sky.bakes == 0 && sky.texture == 0 && !sky.present);   /* no sky: nothing made */
    cg_sky uniform = {.type = CG_SKY_UNIFORM, .radiance = {1, 1, 1}};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &uniform, &err), &err);
    for (int frame = 0; frame < 3; frame++)
        assert_cg_ok(cgp_sky_update(owner, &sky, &s.scene, &err), &err);
    assert_true(sky.bakes == 1 && sky.texture != 0 && sky.present);
    cg_scene_lights_changed(&s.scene);      /* a uniform sky does not follow the sun */
    assert_cg_ok(cgp_sky_update(owner, &sky, &s.scene, &err), &err);
    assert_true(sky.bakes == 1);
    cg_sky preetham = {.type = CG_SKY_PREETHAM, .turbidity = 3, .scale = 0.01f};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &preetham, &err), &err);
    assert_cg_ok(cgp_sky_update(owner, &sky, &s.scene, &err), &err);
    assert_cg_ok(cgp_sky_update(owner, &sky, &s.scene, &err), &err);
    assert_true(sky.bakes == 2);
    cg_scene_lights_changed(&s.scene);      /* the sun moved: Preetham follows it */
    assert_cg_ok(cgp_sky_update(owner, &sky, &s.scene, &err), &err);
    assert_true(sky.bakes == 3);
    cg_sky none = {0};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &none, &err), &err);
    assert_cg_ok(cgp_sky_update(owner, &sky, &s.scene, &err), &err);
    assert_true(!sky.present && sky.bakes == 3);
    cgp_state_destroy(owner);
    assert_no_gl_errors(ctx);
    hf_free(&s);
}

/* A white-ish plane (albedo a) 40 m wide seen from 3 m up, the horizon in the upper part of the
 * image: plane pixels and background pixels. */
#define W 48
#define H 32
static void
plane_scene(hf_scene *s, float albedo)
{
    hf_init(s);
    hf_material(s, 1, albedo, 0.0f);
    hf_grid(s, 4, -20, -20, 40, hf_flat, NULL);
    const double eye[3] = {0, 3, 6}, forward[3] = {0, -0.25, -1}, up[3] = {0, 1, 0};
    hf_camera_looking(s, eye, forward, up, 1.0f);
}

static float *
render(const cg_scene *scene, const char *graph, const char *const *overrides, float **position)
{
    vf_runner r;
    vf_start_file(&r, scene, W, H, graph, overrides);
    vf_frame(&r);
    int w = 0, h = 0;
    float *hdr = hf_read_2d(&r, "final.hdr", 0, &w, &h);
    assert_true(w == W && h == H);
    if (position)
        *position = hf_read_2d(&r, "gbuf.position", 0, &w, &h);
    vf_stop(&r);
    return hdr;
}

typedef struct plane_figures {
    int plane, background;
    double mean, worst;         /* over plane pixels: mean of hdr / target, worst |hdr / target - 1| */
    double background_worst;    /* worst |hdr - pt| over background pixels / the mean of pt there */
} plane_figures;

/* Plane pixels against `target` (grey), background pixels against the path tracer's `pt`. */
static plane_figures
figures(const float *hdr, const float *position, const float *pt, const double target[3])
{
    plane_figures f = {0};
    double sky[3] = {0, 0, 0};
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++)
            if (position[4 * i + 3] <= 0.0f)
                sky[c] += pt[4 * i + c];
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            if (position[4 * i + 3] > 0.0f) {
                double q = hdr[4 * i + c] / target[c];
                f.plane += c == 0;
                f.mean += q / 3.0;
                f.worst = fmax(f.worst, fabs(q - 1.0));
            } else {
                f.background += c == 0;
                f.background_worst = fmax(f.background_worst, fabs(hdr[4 * i + c] - (double)pt[4 * i + c]));
            }
        }
    f.mean /= f.plane > 0 ? f.plane : 1;
    double mean_sky = (sky[0] + sky[1] + sky[2]) / 3.0 / (f.background > 0 ? f.background : 1);
    f.background_worst /= mean_sky > 0.0 ? mean_sky : 1.0;
    return f;
}

static const char *const pt_settings[] = {"trace.spp=64", "trace.progress=false", NULL};

static void
test_plane_under_uniform_sky(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const float albedo = 0.8f;
    hf_scene s;
    plane_scene(&s, albedo);
    hf_finish(&s);
    cg_error err = {0};
    cg_sky sky = {.type = CG_SKY_UNIFORM, .radiance = {0.5f, 1.0f, 2.0f}};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &sky, &err), &err);
    const double target[3] = {albedo * 0.5, albedo * 1.0, albedo * 2.0};
    float *position = NULL;
    free(render(&s.scene, "vct.json", NULL, &position));    /* where the plane is: its G-buffer */
    float *pt = render(&s.scene, "reference.json", pt_settings, NULL);
    /* The reference: exactly a L on the plane (the cosine-sampled sky, both MIS weights 1/2). */
    plane_figures p = figures(pt, position, pt, target);
    printf("# plane under a uniform sky, path tracer: %d plane pixels, mean %.7f of a L, worst %.2g\n", p.plane,
           p.mean, p.worst);
    assert_true(p.plane > W * H / 3 && p.background > W * H / 8);
    assert_true(p.worst < 1e-5);
    static const char *const graphs[] = {"vct.json", "hybrid.json"};
    for (int g = 0; g < 2; g++) {
        float *hdr = render(&s.scene, graphs[g], NULL, NULL);
        plane_figures f = figures(hdr, position, pt, target);
        printf("# plane under a uniform sky, %s: mean %.5f of a L, worst pixel %.4f off; background worst %.2g off "
               "the path tracer's\n", graphs[g], f.mean, f.worst, f.background_worst);
        /* Measured 2.4e-4 below a L in both: the cones' coverage of the plane's own voxels and
         * texels at grazing angles. 1e-3 allows that, and fails for any cone that misses the sky
         * (the smallest cone weight of the 6-cone set is 0.15) or a sky added twice. */
        if (f.worst > 1e-3)
            fail_msg("%s: a plane pixel is %.4f off a L (1e-3 allowed)", graphs[g], f.worst);
        /* The background is L itself in every texel: what the path tracer's escaping rays see. */
        assert_true(f.background_worst == 0.0);
        free(hdr);
    }
    free(pt);
    free(position);
    assert_no_gl_errors(ctx);
    hf_free(&s);
}

static void
test_plane_under_preetham(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const float albedo = 0.8f;
    hf_scene s;
    plane_scene(&s, albedo);
    /* The sun 35 degrees up, behind the camera's right: its light is the sky's only. */
    const double elevation = 35.0 * PI / 180.0;
    const double sun_dir[3] = {-0.5 * cos(elevation), -sin(elevation), -0.866 * cos(elevation)};
    hf_sun(&s, sun_dir, 0.0f);
    hf_finish(&s);
    cg_error err = {0};
    cg_sky sky = {.type = CG_SKY_PREETHAM, .turbidity = 3, .scale = 0.01f};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &sky, &err), &err);
    float *position = NULL;
    free(render(&s.scene, "vct.json", NULL, &position));
    const char *const settings[] = {"trace.spp=256", "trace.progress=false", NULL};
    float *pt = render(&s.scene, "reference.json", settings, NULL);
    double target[3] = {0, 0, 0};
    int n = 0;
    for (int i = 0; i < W * H; i++)
        if (position[4 * i + 3] > 0.0f) {
            n++;
            for (int c = 0; c < 3; c++)
                target[c] += pt[4 * i + c];
        }
    for (int c = 0; c < 3; c++)
        target[c] /= n;
    static const char *const graphs[] = {"vct.json", "hybrid.json"};
    for (int g = 0; g < 2; g++) {
        float *hdr = render(&s.scene, graphs[g], NULL, NULL);
        plane_figures f = figures(hdr, position, pt, target);
        printf("# plane under the Preetham sky, %s: mean %.5f of the path tracer's mean, worst pixel %.4f off; "
               "background worst %.4f off the path tracer's\n", graphs[g], f.mean, f.worst, f.background_worst);
        /* Measured: mean 0.986 in both (six cones sample a sky that is not uniform: the
         * cosine-weighted means of their apertures, not the lobe's integral), the worst channel
         * of a pixel 5.5% off; the background 1.6% of the sky's mean off, at the horizon rows
         * (bilinear filtering of 2.8-degree texels). Allowed: 3%, 8% and 3%. */
        assert_true(fabs(f.mean - 1.0) < 0.03);
        assert_true(f.worst < 0.08);
        assert_true(f.background_worst < 0.03);
        free(hdr);
    }
    free(pt);
    free(position);
    assert_no_gl_errors(ctx);
    hf_free(&s);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_bake),
             cmocka_unit_test(test_bakes_once_per_change),
             cmocka_unit_test(test_plane_under_uniform_sky),
             cmocka_unit_test(test_plane_under_preetham))
