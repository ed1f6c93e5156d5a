/* cone_gather's specular and refracted cones (VCT paper 3.2.2) and composite's sum, through the
 * shipped vct.json and vct-paper.json on a software context, against closed forms:
 *   - a white furnace with GGX materials: a plate under a uniform sky of radiance L, every cone sees
 *     L, so the image less the emission is L x the BSDF's directional albedo at the pixel's n.v
 *     (cg_bsdf_albedo: diffuse + glossy), for rough and smooth metals and dielectrics;
 *   - a mirror (metal, base colour 1, roughness 0) under the uniform sky returns L;
 *   - a glass slab (solid, thickness d, smooth) seen at normal incidence against the uniform sky:
 *     the refracted cone returns (1 - F0)^2 exp(-sigma d) L and the reflected one F0 L;
 *   - a Lambertian plate (the built-in scenes' material) gets no specular or refracted light;
 *   - the shadow cone of a sun with an angular diameter against the path tracer's soft shadow;
 *   - voxel_light's `glossy`, which the lobes' cones read, is the light of one bounce more: the
 *     `radiance` of the same pass with bounces + 1; both gathers' lobes read it; a metal's voxels hold
 *     its specular albedo's light there (the sky's, and a rough lobe's share of the sun's). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/bsdf.h"
#include "cg/fs.h"
#include "cg/gl.h"
#include "cg/scene.h"
#include "sdk/cone.h"
#include "test_support.h"
#include "hybrid_fixture.h"
#include "vct_fixture.h"

#define SIZE 32

/* A 20 m plate at y = 0 facing up (material 2) under a uniform sky of radiance L, seen from above
 * at about 40 degrees off the normal, so that the pixels span a range of n.v. */
static void
plate_scene(hf_scene *s, float radiance)
{
    hf_init(s);
    const double corner[3] = {-10, 0, 10}, e1[3] = {20, 0, 0}, e2[3] = {0, 0, -20};
    hf_quad(s, corner, e1, e2);
    const double eye[3] = {0, 6, 6}, forward[3] = {0, -1, -0.85}, up[3] = {0, 1, 0};
    hf_camera_looking(s, eye, forward, up, 0.6f);
    hf_finish(s);
    cg_sky sky = {.type = CG_SKY_UNIFORM, .radiance = {radiance, radiance, radiance}};
    cg_error err = {0};
    assert_cg_ok(cg_scene_set_sky(&s->scene, &sky, &err), &err);
}

typedef struct furnace_result {
    int pixels;
    double mean_ratio;  /* mean over the pixels of (hdr - emissive) / (L x albedo) */
    double worst;       /* largest |ratio - 1| */
} furnace_result;


/* Runs `graph` on s (no lights: direct is 0) and compares each covered pixel's hdr - emissive with
 * L x (diffuse + glossy directional albedo of the material at its n.v). */
static furnace_result
furnace(cg_context *ctx, hf_scene *s, int material, const char *graph, const char *const *overrides, double radiance)
{
    const cg_material *m = &s->materials[material];
    cg_bsdf b;
    cg_bsdf_from_material(m, m->base_color, m->metallic, m->roughness, m->transmission, &b);
    vf_runner r;
    vf_start_file(&r, &s->scene, SIZE, SIZE, graph, overrides);
    vf_frame(&r);
    float *hdr = hf_read_2d_sized(&r, "final.hdr", SIZE, SIZE);
    float *emissive = hf_read_2d_sized(&r, "gbuf.emissive", SIZE, SIZE);
    float *position = hf_read_2d_sized(&r, "gbuf.position", SIZE, SIZE);
    float *normal = hf_read_2d_sized(&r, "gbuf.normal", SIZE, SIZE);
    const float *eye = r.frame.view.position;
    furnace_result f = {0};
    for (int i = 0; i < SIZE * SIZE; i++) {
        const float *p = &position[4 * i];
        if (p[3] <= 0.0f)
            continue;
        float v[3] = {eye[0] - p[0], eye[1] - p[1], eye[2] - p[2]};
        float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        float nv = (v[0] * normal[4 * i] + v[1] * normal[4 * i + 1] + v[2] * normal[4 * i + 2]) / len;
        float diffuse[3], glossy[3], transmission[3];
        cg_bsdf_albedo(&b, nv, diffuse, glossy, transmission);
        for (int k = 0; k < 3; k++) {
            double expect = radiance * (diffuse[k] + glossy[k]);
            double got = hdr[4 * i + k] - emissive[4 * i + k];
            if (!isfinite(got))
                fail_msg("pixel %d channel %d is %g", i, k, got);
            double ratio = got / expect;
            f.mean_ratio += ratio / 3.0;
            f.worst = fmax(f.worst, fabs(ratio - 1.0));
        }
        f.pixels++;
    }
    f.mean_ratio /= f.pixels > 0 ? f.pixels : 1;
    free(hdr);
    free(emissive);
    free(position);
    free(normal);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    return f;
}

static void
set_material(cg_material *m, float base, float metallic, float roughness)
{
    m->base_color[0] = m->base_color[1] = m->base_color[2] = base;
    m->metallic = metallic;
    m->roughness = roughness;
    m->specular = 1.0f;
    m->ior = 1.5f;
}

/* The white furnace with GGX materials: within 2% at every pixel, 1% in the mean, through both
 * shipped graphs (vct.json at 0 bounces: its volume holds what the voxels emit and reflect of the
 * lights, none here). */
static void
test_furnace_ggx(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const double radiance = 2.0;
    static const struct { const char *name; float base, metallic, roughness; } materials[] = {
        {"rough metal", 0.9f, 1.0f, 0.8f},
        {"glossy metal", 0.7f, 1.0f, 0.3f},
        {"smooth metal", 0.95f, 1.0f, 0.05f},
        {"rough dielectric", 0.5f, 0.0f, 0.7f},
        {"smooth dielectric", 0.5f, 0.0f, 0.1f},
        {"half metal", 0.6f, 0.5f, 0.4f},
    };
    static const char *const graphs[] = {"vct.json", "vct-paper.json"};
    static const char *const no_bounce[] = {"light.bounces=0", NULL};
    for (size_t i = 0; i < sizeof materials / sizeof materials[0]; i++)
        for (int g = 0; g < 2; g++) {
            hf_scene s;
            plate_scene(&s, (float)radiance);
            set_material(&s.materials[2], materials[i].base, materials[i].metallic, materials[i].roughness);
            furnace_result f = furnace(ctx, &s, 2, graphs[g], g == 0 ? no_bounce : NULL, radiance);
            fprintf(stderr, "# furnace, %s (base %.2f, metallic %.1f, roughness %.2f), %s: mean ratio %.4f, "
                    "worst pixel %.2f%% (%d pixels)\n", materials[i].name, materials[i].base, materials[i].metallic,
                    materials[i].roughness, graphs[g], f.mean_ratio, 100.0 * f.worst, f.pixels);
            assert_true(f.pixels > SIZE * SIZE / 2);
            if (fabs(f.mean_ratio - 1.0) > 0.01 || f.worst > 0.02)
                fail_msg("furnace, %s through %s: mean ratio %.4f, worst pixel %.2f%% off", materials[i].name,
                         graphs[g], f.mean_ratio, 100.0 * f.worst);
            hf_free(&s);
        }
}

static double
dome(double x, double z, const void *user)
{
    (void)user;
    return 1.5 - 2.0 * (x * x + z * z);
}

/* A rough metal on a curved surface in the furnace: a dome (a convex paraboloid, so that no point of it
 * sees another and every direction above a point's plane sees the sky), roughness 1: the single cone
 * would be 60 degrees wide and read the dome's own voxels beside the pixel (it returned 0.6 of the
 * sky on a rough white metal sphere); the diffuse cone set weighted by the lobe (common/gather.glsl,
 * cg_gather_reflection) returns L x the directional albedo. */
static void
test_furnace_rough_dome(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const double radiance = 2.0;
    hf_scene s;
    hf_init(&s);
    hf_grid(&s, 48, -1.0, -1.0, 2.0, dome, NULL);
    const double eye[3] = {0, 4, 3.5}, forward[3] = {0, -1.1, -1}, up[3] = {0, 1, 0};
    hf_camera_looking(&s, eye, forward, up, 0.55f);
    hf_finish(&s);
    set_material(&s.materials[1], 0.9f, 1.0f, 1.0f);
    cg_sky sky = {.type = CG_SKY_UNIFORM, .radiance = {radiance, radiance, radiance}};
    cg_error err = {0};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &sky, &err), &err);
    static const char *const no_bounce[] = {"light.bounces=0", NULL};
    furnace_result f = furnace(ctx, &s, 1, "vct.json", no_bounce, radiance);
    fprintf(stderr, "# furnace, rough metal dome (roughness 1), vct.json: mean ratio %.4f, worst pixel %.2f%% (%d pixels)\n",
            f.mean_ratio, 100.0 * f.worst, f.pixels);
    assert_true(f.pixels > SIZE * SIZE / 4);
    if (fabs(f.mean_ratio - 1.0) > 0.01 || f.worst > 0.02)
        fail_msg("furnace, rough metal dome: mean ratio %.4f, worst pixel %.2f%% off", f.mean_ratio, 100.0 * f.worst);
    hf_free(&s);
}

/* The same furnace through hybrid.json on a height field (material 1, the terrain): the specular
 * cone through the horizon march (common/gather.glsl's cones, hybrid_gather's trace). */
static void
test_furnace_hybrid(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const double radiance = 2.0;
    static const struct { const char *name; float base, metallic, roughness; } materials[] = {
        {"glossy metal", 0.7f, 1.0f, 0.3f},
        {"smooth dielectric", 0.5f, 0.0f, 0.1f},
    };
    static const char *const no_bounce[] = {"light.bounces=0", NULL};
    for (size_t i = 0; i < sizeof materials / sizeof materials[0]; i++) {
        hf_scene s;
        hf_init(&s);
        hf_grid(&s, 8, -10.0, -10.0, 20.0, hf_flat, NULL);
        const double eye[3] = {0, 6, 6}, forward[3] = {0, -1, -0.85}, up[3] = {0, 1, 0};
        hf_camera_looking(&s, eye, forward, up, 0.6f);
        hf_finish(&s);
        cg_sky sky = {.type = CG_SKY_UNIFORM, .radiance = {(float)radiance, (float)radiance, (float)radiance}};
        cg_error err = {0};
        assert_cg_ok(cg_scene_set_sky(&s.scene, &sky, &err), &err);
        set_material(&s.materials[1], materials[i].base, materials[i].metallic, materials[i].roughness);
        furnace_result f = furnace(ctx, &s, 1, "hybrid.json", no_bounce, radiance);
        fprintf(stderr, "# furnace on a height field, %s, hybrid.json: mean ratio %.4f, worst pixel %.2f%% (%d pixels)\n",
                materials[i].name, f.mean_ratio, 100.0 * f.worst, f.pixels);
        assert_true(f.pixels > SIZE * SIZE / 2);
        if (fabs(f.mean_ratio - 1.0) > 0.01 || f.worst > 0.02)
            fail_msg("furnace on a height field, %s through hybrid.json: mean ratio %.4f, worst pixel %.2f%% off",
                     materials[i].name, f.mean_ratio, 100.0 * f.worst);
        hf_free(&s);
    }
}

/* A mirror (metal, base colour 1, roughness 0) under a uniform sky returns the sky's radiance, at
 * every angle (F0 = F90 = 1). */
static void
test_mirror(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const double radiance = 3.0;
    hf_scene s;
    plate_scene(&s, (float)radiance);
    set_material(&s.materials[2], 1.0f, 1.0f, 0.0f);
    vf_runner r;
    static const char *const no_bounce[] = {"light.bounces=0", NULL};
    vf_start_file(&r, &s.scene, SIZE, SIZE, "vct.json", no_bounce);
    vf_frame(&r);
    float *hdr = hf_read_2d_sized(&r, "final.hdr", SIZE, SIZE);
    float *position = hf_read_2d_sized(&r, "gbuf.position", SIZE, SIZE);
    double worst = 0.0;
    int pixels = 0;
    for (int i = 0; i < SIZE * SIZE; i++)
        if (position[4 * i + 3] > 0.0f) {
            for (int k = 0; k < 3; k++)
                worst = fmax(worst, fabs(hdr[4 * i + k] / radiance - 1.0));
            pixels++;
        }
    fprintf(stderr, "# mirror under a uniform sky L = %.1f: worst pixel %.3f%% off L (%d pixels)\n", radiance,
            100.0 * worst, pixels);
    assert_true(pixels > SIZE * SIZE / 2);
    if (worst > 0.01)
        fail_msg("mirror: a pixel is %.2f%% off the sky's radiance", 100.0 * worst);
    free(hdr);
    free(position);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    hf_free(&s);
}

/* A glass slab, two 4 m squares d = 0.5 m apart (materials 2 and 3: smooth, ior 1.5, thickness d,
 * attenuation colour 0.5 at 1 m: sigma = ln 2), seen face on from 5 m against a uniform sky: the
 * refracted cone (Snell in and out, parallel faces) returns (1 - F0)^2 exp(-sigma d) L with F0 =
 * 0.04, the reflected one F0 L, composite their sum (rho = 0: no diffuse). */
static void
test_glass_slab(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const double radiance = 2.0, d = 0.5, sigma = log(2.0);
    hf_scene s;
    hf_init(&s);
    const double front[3] = {-2, -2, 0}, back[3] = {-2, -2, -d}, ex[3] = {4, 0, 0}, ey[3] = {0, 4, 0};
    const double minus_ey[3] = {0, -4, 0}, back_top[3] = {-2, 2, -d};
    hf_quad(&s, front, ex, ey);
    hf_quad(&s, back_top, ex, minus_ey);
    (void)back;
    for (int m = 2; m <= 3; m++) {
        set_material(&s.materials[m], 1.0f, 0.0f, 0.0f);
        s.materials[m].transmission = 1.0f;
        s.materials[m].thickness = (float)d;
        s.materials[m].attenuation_distance = 1.0f;
        for (int k = 0; k < 3; k++)
            s.materials[m].attenuation_color[k] = 0.5f;
    }
    const double eye[3] = {0, 0, 5}, forward[3] = {0, 0, -1}, up[3] = {0, 1, 0};
    hf_camera_looking(&s, eye, forward, up, 0.3f);
    hf_finish(&s);
    cg_sky sky = {.type = CG_SKY_UNIFORM, .radiance = {(float)radiance, (float)radiance, (float)radiance}};
    cg_error err = {0};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &sky, &err), &err);
    vf_runner r;
    static const char *const no_bounce[] = {"light.bounces=0", NULL};
    vf_start_file(&r, &s.scene, SIZE, SIZE, "vct.json", no_bounce);
    vf_frame(&r);
    float *refraction = hf_read_2d_sized(&r, "gather.refraction", SIZE, SIZE);
    float *reflection = hf_read_2d_sized(&r, "gather.reflection", SIZE, SIZE);
    float *hdr = hf_read_2d_sized(&r, "final.hdr", SIZE, SIZE);
    float *position = hf_read_2d_sized(&r, "gbuf.position", SIZE, SIZE);
    const double f0 = 0.04;
    const double through = (1.0 - f0) * (1.0 - f0) * exp(-sigma * d) * radiance, back_out = f0 * radiance;
    double worst_t = 0.0, worst_r = 0.0, worst_sum = 0.0, mean_t = 0.0;
    int pixels = 0;
    for (int y = SIZE / 4; y < 3 * SIZE / 4; y++)
        for (int x = SIZE / 4; x < 3 * SIZE / 4; x++) {
            int i = y * SIZE + x;
            if (position[4 * i + 3] <= 0.0f || position[4 * i + 2] < -0.01f)
                continue;
            for (int k = 0; k < 3; k++) {
                worst_t = fmax(worst_t, fabs(refraction[4 * i + k] / through - 1.0));
                worst_r = fmax(worst_r, fabs(reflection[4 * i + k] / back_out - 1.0));
                worst_sum = fmax(worst_sum, fabs(hdr[4 * i + k] / (through + back_out) - 1.0));
            }
            mean_t += refraction[4 * i] / through;
            pixels++;
        }
    mean_t /= pixels > 0 ? pixels : 1;
    fprintf(stderr, "# glass slab d = %.2f m, sigma = %.3f /m, face on: refraction / (1-F0)^2 exp(-sigma d) L mean "
            "%.4f, worst %.3f%%; reflection worst %.3f%% off F0 L; hdr worst %.3f%% off the sum (%d pixels)\n", d,
            sigma, mean_t, 100.0 * worst_t, 100.0 * worst_r, 100.0 * worst_sum, pixels);
    assert_true(pixels > 20);
    if (worst_t > 0.02 || worst_r > 0.02 || worst_sum > 0.02)
        fail_msg("glass slab: refraction %.2f%%, reflection %.2f%%, hdr %.2f%% off", 100.0 * worst_t, 100.0 * worst_r,
                 100.0 * worst_sum);
    free(refraction);
    free(reflection);
    free(hdr);
    free(position);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    hf_free(&s);
}

/* A Lambertian plate (specular 0, the built-in scenes' material) under a sun and a sky: the
 * specular and refracted cones have no weight and are not traced (both outputs 0 to the bit), and
 * the diffuse share is 1, so the image is what it was before these terms. */
static void
test_lambertian_unchanged(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    hf_scene s;
    plate_scene(&s, 1.5f);
    hf_material(&s, 2, 0.6f, 0.0f);
    const double down[3] = {0.3, -1, 0.2};
    hf_sun(&s, down, 3.0f);
    vf_runner r;
    vf_start_file(&r, &s.scene, SIZE, SIZE, "vct.json", NULL);
    vf_frame(&r);
    float *reflection = hf_read_2d_sized(&r, "gather.reflection", SIZE, SIZE);
    float *refraction = hf_read_2d_sized(&r, "gather.refraction", SIZE, SIZE);
    float *position = hf_read_2d_sized(&r, "gbuf.position", SIZE, SIZE);
    int pixels = 0;
    for (int i = 0; i < SIZE * SIZE; i++) {
        pixels += position[4 * i + 3] > 0.0f;
        for (int k = 0; k < 4; k++)
            if (reflection[4 * i + k] != 0.0f || refraction[4 * i + k] != 0.0f)
                fail_msg("Lambertian plate: pixel %d channel %d reflects %g, transmits %g", i, k, reflection[4 * i + k],
                         refraction[4 * i + k]);
    }
    assert_true(pixels > SIZE * SIZE / 2);
    free(reflection);
    free(refraction);
    free(position);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    hf_free(&s);
}

/* The shadow cone (VCT paper 3.2.3) of a sun with an angular diameter (cone_gather takes the sun's
 * disc as the cone's aperture) against the path tracer's soft shadow: a ground under a plate 10 m
 * up (test_cone_gather's scene), the sun's disc 0.2 rad wide (a penumbra 2 m wide under the plate's
 * edge). The path tracer's visibility is its direct radiance at 0 bounces over the unshadowed
 * albedo E cos / pi; the cone's is the `visibility` output. Over the ground pixels: the mean and
 * the penumbra's (0.05 < path-traced visibility < 0.95) absolute difference. */
static const char shadow_cone_graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"gbuf\": { \"type\": \"gbuffer\" },"
    " \"trace\": { \"type\": \"path_trace\", \"params\": { \"spp\": 64, \"bounces\": 0 } },"
    " \"vox\": { \"type\": \"voxelize\", \"params\": { \"resolution\": 128 } },"
    " \"mip\": { \"type\": \"mip3d\", \"inputs\": { \"volume\": \"vox.radiance\" } },"
    " \"gather\": { \"type\": \"cone_gather\", \"params\": { \"shadow_cone\": true, \"shadow_light\": 0 },"
    "   \"inputs\": { \"position\": \"gbuf\", \"normal\": \"gbuf\", \"volume\": \"mip.volume\", \"region\": \"vox.region\" } } },"
    " \"outputs\": [ \"gather.visibility\", \"trace.radiance\", \"gbuf.position\" ] }";

static void
test_shadow_cone_sun_disc(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    hf_scene s;
    const float irradiance = 3.0f;
    hf_plate_under_sun(&s, irradiance, 0.2f);
    const double eye[3] = {30, 25, 0}, forward[3] = {-1, -1.2, 0}, up[3] = {0, 1, 0};
    hf_camera_looking(&s, eye, forward, up, 0.9f);
    hf_finish(&s);
    vf_runner r;
    vf_start(&r, &s.scene, SIZE, SIZE, shadow_cone_graph, NULL);
    vf_frame(&r);
    float *vis = hf_read_2d_sized(&r, "gather.visibility", SIZE, SIZE);
    float *pt = hf_read_2d_sized(&r, "trace.radiance", SIZE, SIZE);
    float *pos = hf_read_2d_sized(&r, "gbuf.position", SIZE, SIZE);
    double cos_sun = -s.light.direction[1], unshadowed = 0.5 * irradiance * cos_sun / M_PI;
    double sum = 0.0, sum_pen = 0.0, mean_pt = 0.0, mean_cone = 0.0;
    int n = 0, n_pen = 0;
    for (int i = 0; i < SIZE * SIZE; i++) {
        const float *p = &pos[4 * i];
        if (p[3] <= 0.0f || p[1] > 1.0f || fabsf(p[2]) > 30.0f)
            continue;   /* the ground only, away from the plate's far ends */
        double v_pt = pt[4 * i + 1] / unshadowed, v_cone = vis[4 * i];
        assert_true(isfinite(v_cone));
        sum += fabs(v_cone - v_pt);
        mean_pt += v_pt;
        mean_cone += v_cone;
        n++;
        if (v_pt > 0.05 && v_pt < 0.95) {
            sum_pen += fabs(v_cone - v_pt);
            n_pen++;
        }
    }
    fprintf(stderr, "# shadow cone of a 0.2 rad sun against the path tracer (64 spp): ground mean visibility %.3f "
            "(path tracer %.3f), mean |difference| %.3f over %d pixels, %.3f over the %d penumbra pixels\n",
            mean_cone / n, mean_pt / n, sum / n, n, n_pen ? sum_pen / n_pen : 0.0, n_pen);
    /* Measured: 0.006 over the ground, 0.130 over the penumbra (its profile is the voxels' and the
     * mip levels', not the disc's). */
    assert_true(n > 100 && n_pen > 10);
    if (sum / n > 0.03 || sum_pen / n_pen > 0.2)
        fail_msg("shadow cone: mean |visibility - path tracer's| %.3f, %.3f in the penumbra", sum / n, sum_pen / n_pen);
    free(vis);
    free(pt);
    free(pos);
    assert_no_gl_errors(ctx);
    vf_stop(&r);
    hf_free(&s);
}

/* voxel_light's `glossy` (the light one diffuse bounce further, for the lobes' cones) against the
 * `radiance` of a second voxel_light pass with one bounce more: the same recursion V_(N+1), so the same
 * values at every occupied voxel of level 0 whose lit side the extra bounce leaves where it was (glossy
 * keeps radiance's sides and normals; the others are counted, not compared: an emitter's two sides are
 * equal at V_0, and the bounce picks one). The town of the voxelize tests under a sun, no sky, its roof
 * a dielectric with a specular lobe: at bounces 1 (V_2) and at bounces 0 with an emitting wall (V_1). */
static const char glossy_graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"shadow\": { \"type\": \"shadow_map\", \"params\": { \"resolution\": 512 } },"
    " \"vox\": { \"type\": \"voxelize\", \"params\": { \"model\": \"surface\", \"resolution\": 32 } },"
    " \"light\": { \"type\": \"voxel_light\", \"params\": { \"bounces\": %d, \"glossy\": true }, \"inputs\": {"
    "   \"albedo\": \"vox.albedo\", \"coverage\": \"vox.coverage\", \"normal\": \"vox.normal\", \"emission\": \"vox.emission\","
    "   \"region\": \"vox.region\", \"shadow\": \"shadow.depth\", \"shadow_matrix\": \"shadow.matrix\" } },"
    " \"next\": { \"type\": \"voxel_light\", \"params\": { \"bounces\": %d }, \"inputs\": {"
    "   \"albedo\": \"vox.albedo\", \"coverage\": \"vox.coverage\", \"normal\": \"vox.normal\", \"emission\": \"vox.emission\","
    "   \"region\": \"vox.region\", \"shadow\": \"shadow.depth\", \"shadow_matrix\": \"shadow.matrix\" } } },"
    " \"outputs\": [ \"light.glossy\", \"light.radiance\", \"light.normals\", \"next.radiance\", \"next.normals\" ] }";

static void
test_glossy_is_one_bounce_more(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    for (int bounces = 0; bounces <= 1; bounces++) {
        hf_scene s;
        hf_town(&s, 4, bounces == 0 ? 2.0f : 0.0f);
        /* A specular lobe on the roof: voxel_light lights `glossy` only where a material has one. */
        s.materials[3].specular = 1.0f;
        const double down[3] = {0.4, -1, 0.3};
        hf_sun(&s, down, 3.0f);
        hf_finish(&s);
        char json[2048];
        snprintf(json, sizeof json, glossy_graph, bounces, bounces + 1);
        vf_runner r;
        vf_start(&r, &s.scene, SIZE, SIZE, json, NULL);
        vf_frame(&r);
        int n = 0, n2 = 0, n3 = 0;
        float *glossy = vf_read_volume(&r, "light.glossy", 0, &n);
        float *radiance = vf_read_volume(&r, "light.radiance", 0, &n3);
        float *next = vf_read_volume(&r, "next.radiance", 0, &n2);
        float *sides = vf_read_volume(&r, "light.normals", 0, &n3);
        float *next_sides = vf_read_volume(&r, "next.normals", 0, &n3);
        assert_int_equal(n, n2);
        int occupied = 0, off = 0, brighter = 0, turned = 0;
        double worst = 0.0;
        for (size_t i = 0; i < (size_t)n * n * n; i++) {
            const float *g = &glossy[4 * i], *x = &next[4 * i], *v = &radiance[4 * i];
            if (x[3] <= 0.0f)
                continue;
            occupied++;
            const float *a = &sides[4 * i], *b = &next_sides[4 * i];
            if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.0f) {
                turned++;
                continue;
            }
            double y = 0.2126 * x[0] + 0.7152 * x[1] + 0.0722 * x[2];
            double e = fabs(0.2126 * (g[0] - x[0]) + 0.7152 * (g[1] - x[1]) + 0.0722 * (g[2] - x[2])) / fmax(y, 1e-6);
            worst = fmax(worst, e);
            off += e > 2e-3;
            brighter += 0.2126 * g[0] + 0.7152 * g[1] + 0.0722 * g[2] > 1.001 * (0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2]);
        }
        fprintf(stderr, "# voxel_light glossy at bounces %d against radiance at bounces %d: %d occupied voxels, %d off by "
                "more than 0.2%% (worst %.4f), %d brighter than radiance, %d lit on the other side\n", bounces, bounces + 1,
                occupied, off, worst, brighter, turned);
        assert_true(occupied > 100 && turned < occupied / 4);
        /* The bounce adds light somewhere: glossy is not radiance again. */
        assert_true(brighter > occupied / 10);
        if (off > occupied / 100)
            fail_msg("glossy differs from the next bounce's radiance at %d of %d voxels", off, occupied);
        free(glossy);
        free(radiance);
        free(next);
        free(sides);
        free(next_sides);
        assert_no_gl_errors(ctx);
        vf_stop(&r);
        hf_free(&s);
    }
}

/* The gathers' lobes read `glossy` in every march: a metal ground (material 1, roughness 0.2: a
 * height field, in hybrid.json the 2D lightmap's) reflecting two sunlit Lambertian walls that light
 * each other (the 3D part). Through each shipped graph (light.bounces 1: the lobes read V_2) the
 * ground's `gather.reflection` equals that of the same graph with light.bounces 2 and no `glossy`
 * input (its `volume`, V_2, read by the lobes), and differs from the graph at bounces 1 without it
 * (V_1): the walls' light on each other is the bounce glossy adds. vct.json tests cone_gather's
 * march, hybrid.json the horizon march over the 2D lightmap. */
/* json with its one `what` replaced by `with` (freed and reallocated); fails when the shipped graph no
 * longer holds `what`. */
static char *
replace_once(char *json, const char *file, const char *what, const char *with)
{
    char *at = strstr(json, what);
    if (!at)
        fail_msg("%s no longer has %s: update this test", file, what);
    size_t before = (size_t)(at - json), cut = strlen(what), add = strlen(with);
    char *out = malloc(strlen(json) - cut + add + 1);
    assert_non_null(out);
    memcpy(out, json, before);
    memcpy(out + before, with, add);
    strcpy(out + before + add, at + cut);
    free(json);
    return out;
}

/* The shipped graph `file` with voxel_light's bounces set, and without `glossy` (the pass's and the
 * gather's input) unless asked. */
static char *
graph_variant(const char *file, int bounces, bool glossy)
{
    char *json = NULL;
    size_t size = 0;
    cg_error err = {0};
    assert_cg_ok(cg_read_file(cg_test_graph_path(file), &json, &size, &err), &err);
    char light[64];
    snprintf(light, sizeof light, glossy ? "\"bounces\": %d, \"glossy\": true" : "\"bounces\": %d", bounces);
    json = replace_once(json, file, "\"bounces\": 1, \"glossy\": true", light);
    if (!glossy)
        json = replace_once(json, file, "\"glossy\": \"light.glossy\", ", "");
    return json;
}

static float *
mirror_reflection(const hf_scene *s, const char *file, int bounces, bool glossy, float **position)
{
    static const char *const sets[] = {"vox.resolution=64", NULL};
    char *json = graph_variant(file, bounces, glossy);
    vf_runner r;
    vf_start(&r, &s->scene, SIZE, SIZE, json, sets);
    free(json);
    vf_frame(&r);
    float *reflection = hf_read_2d_sized(&r, "gather.reflection", SIZE, SIZE);
    if (position)
        *position = hf_read_2d_sized(&r, "gbuf.position", SIZE, SIZE);
    vf_stop(&r);
    return reflection;
}

static void
test_lobes_read_glossy(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    static const char *const graphs[] = {"vct.json", "hybrid.json"};
    for (int g = 0; g < 2; g++) {
        hf_scene s;
        hf_init(&s);
        hf_grid(&s, 8, -4.0, -4.0, 8.0, hf_flat, NULL);
        const double back[3] = {-4, 0, -2}, back_u[3] = {8, 0, 0}, back_v[3] = {0, 3, 0};
        const double side[3] = {3, 0, -2}, side_u[3] = {0, 0, 5}, side_v[3] = {0, 3, 0};
        hf_quad(&s, back, back_u, back_v);   /* faces +z */
        hf_quad(&s, side, side_u, side_v);   /* faces -x */
        hf_material(&s, 2, 0.8f, 0.0f);
        hf_material(&s, 3, 0.8f, 0.0f);
        const double down[3] = {0.5, -1, -0.6};
        hf_sun(&s, down, 3.0f);
        const double eye[3] = {-1, 2.5, 5}, forward[3] = {0.25, -0.4, -1}, up[3] = {0, 1, 0};
        hf_camera_looking(&s, eye, forward, up, 0.9f);
        hf_finish(&s);
        set_material(&s.materials[1], 1.0f, 1.0f, 0.2f);
        float *position = NULL;
        float *shipped = mirror_reflection(&s, graphs[g], 1, true, &position);
        float *next = mirror_reflection(&s, graphs[g], 2, false, NULL);
        float *plain = mirror_reflection(&s, graphs[g], 1, false, NULL);
        double sum = 0.0, off_next = 0.0, off_plain = 0.0;
        int pixels = 0;
        for (int i = 0; i < SIZE * SIZE; i++) {
            /* the ground's pixels */
            if (!(position[4 * i + 3] > 0.0f && fabsf(position[4 * i + 1]) < 1e-3f))
                continue;
            pixels++;
            for (int k = 0; k < 3; k++) {
                sum += shipped[4 * i + k];
                off_next += fabs(shipped[4 * i + k] - next[4 * i + k]);
                off_plain += fabs(shipped[4 * i + k] - plain[4 * i + k]);
            }
        }
        fprintf(stderr, "# %s, metal ground's reflection (%d pixels): mean |glossy - V_2| / mean %.4f, "
                "|glossy - V_1| / mean %.4f\n", graphs[g], pixels, off_next / sum, off_plain / sum);
        assert_true(pixels > SIZE * SIZE / 4);
        assert_true(sum > 0.0);
        if (off_next / sum > 0.01)
            fail_msg("%s: the lobes' light is %.2f%% off the volume one bounce further", graphs[g], 100.0 * off_next / sum);
        if (off_plain / sum < 0.02)
            fail_msg("%s: the lobes' light is within %.2f%% of the diffuse cones' volume: glossy not read?", graphs[g],
                     100.0 * off_plain / sum);
        free(shipped);
        free(next);
        free(plain);
        free(position);
        assert_no_gl_errors(ctx);
        hf_free(&s);
    }
}

/* voxelize's `transmissive`: a Lambertian floor under a thin glass pane (transmission 1, ior 1.5)
 * that covers its whole sky (20 m each way, 1.5 m up) under a uniform sky L, seen from under the
 * pane, through vct.json at 0 bounces (the floor's light is its gather alone). With the option the
 * cones see the sky through the pane: the floor's image / its albedo is L (1 - F), F the
 * hemispherical Fresnel of ior 1.5 (1 - 0.956), as path_trace with caustics sees it; without it
 * the pane is opaque and black, as with caustics off. */
static void
test_transmissive_voxels(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const double radiance = 2.0, albedo = 0.5;
    double seen[2] = {0.0, 0.0};
    for (int on = 0; on < 2; on++) {
        hf_scene s;
        hf_init(&s);
        hf_grid(&s, 8, -20.0, -20.0, 40.0, hf_flat, NULL);
        const double corner[3] = {-20, 1.5, 20}, e1[3] = {40, 0, 0}, e2[3] = {0, 0, -40};
        hf_quad(&s, corner, e1, e2);    /* material 2 */
        hf_material(&s, 1, (float)albedo, 0.0f);
        const double eye[3] = {0, 0.8, 2}, forward[3] = {0, -1, -1.2}, up[3] = {0, 1, 0};
        hf_camera_looking(&s, eye, forward, up, 0.8f);
        hf_finish(&s);
        set_material(&s.materials[2], 1.0f, 0.0f, 0.0f);
        s.materials[2].transmission = 1.0f;
        cg_sky sky = {.type = CG_SKY_UNIFORM, .radiance = {radiance, radiance, radiance}};
        cg_error err = {0};
        assert_cg_ok(cg_scene_set_sky(&s.scene, &sky, &err), &err);
        const char *const set[] = {"light.bounces=0", "gather.downsample=1",
                                   on ? "vox.transmissive=true" : "vox.transmissive=false", NULL};
        vf_runner r;
        vf_start_file(&r, &s.scene, SIZE, SIZE, "vct.json", set);
        vf_frame(&r);
        float *hdr = hf_read_2d_sized(&r, "final.hdr", SIZE, SIZE);
        float *position = hf_read_2d_sized(&r, "gbuf.position", SIZE, SIZE);
        int pixels = 0;
        for (int i = 0; i < SIZE * SIZE; i++) {
            const float *p = &position[4 * i];
            if (p[3] <= 0.0f || fabsf(p[1]) > 1e-3f || fabsf(p[0]) > 6.0f || fabsf(p[2]) > 6.0f)
                continue;
            seen[on] += (hdr[4 * i] + hdr[4 * i + 1] + hdr[4 * i + 2]) / (3.0 * albedo * radiance);
            pixels++;
        }
        assert_true(pixels > SIZE * SIZE / 4);
        seen[on] /= pixels;
        free(hdr);
        free(position);
        assert_no_gl_errors(ctx);
        vf_stop(&r);
        hf_free(&s);
    }
    const double through = 0.956;   /* 1 - F, common/bsdf.glsl's CG_BSDF_DIFFUSE_HEMISPHERICAL_* */
    fprintf(stderr, "# floor under a glass pane, image / (albedo L): transmissive voxels %.4f (1 - F %.3f), "
            "opaque %.4f\n", seen[1], through, seen[0]);
    if (fabs(seen[1] / through - 1.0) > 0.03)
        fail_msg("through transmissive voxels the floor sees %.4f of the sky, 1 - F = %.3f", seen[1], through);
    if (seen[0] > 0.1)
        fail_msg("an opaque pane lets %.4f of the sky through", seen[0]);
}

/* voxel_light's `glossy` holds a metal's light (voxelize's `specular`): two coplanar plates under a
 * uniform sky L and a sun, a Lambertian one (albedo a) and a white metal (base F0, roughness r). In
 * glossy the metal's voxels return rho_s (alpha S + L), rho_s = F0 Abar(r) + Bbar(r) (the lobe's
 * hemispherical albedo, sdk/cone.h), alpha = r^2, S the sun's E cos / pi, against the Lambertian's
 * a (S + L) in radiance (the same coverage and scale: the ratio is the closed form); in radiance the
 * metal is black (no diffuse lobe), and the Lambertian's glossy is its radiance (the plates do not see
 * each other). */
static const char metal_graph[] =
    "{ \"version\": 1, \"passes\": {"
    " \"shadow\": { \"type\": \"shadow_map\", \"params\": { \"resolution\": 512 } },"
    " \"vox\": { \"type\": \"voxelize\", \"params\": { \"model\": \"surface\", \"resolution\": 32 } },"
    " \"light\": { \"type\": \"voxel_light\", \"params\": { \"bounces\": 1, \"glossy\": true }, \"inputs\": {"
    "   \"albedo\": \"vox.albedo\", \"coverage\": \"vox.coverage\", \"normal\": \"vox.normal\", \"emission\": \"vox.emission\","
    "   \"specular\": \"vox.specular\", \"region\": \"vox.region\", \"shadow\": \"shadow.depth\","
    "   \"shadow_matrix\": \"shadow.matrix\" } } },"
    " \"outputs\": [ \"light.glossy\", \"light.radiance\", \"vox.albedo\", \"vox.specular\" ] }";

static void
test_metal_voxels_in_glossy(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    const float a = 0.5f, f0 = 0.9f, r = 0.6f, sky = 1.0f, sun = 3.0f;
    hf_scene s;
    hf_init(&s);
    const double lambert[3] = {-8, 0, -4}, metal[3] = {1, 0, -4}, e1[3] = {0, 0, 8}, e2[3] = {7, 0, 0};
    hf_quad(&s, lambert, e1, e2);   /* material 2, faces +y */
    hf_quad(&s, metal, e1, e2);     /* material 3 */
    hf_material(&s, 2, a, 0.0f);
    const double down[3] = {0.3, -1, 0.2};
    hf_sun(&s, down, sun);
    hf_finish(&s);
    set_material(&s.materials[3], f0, 1.0f, r);
    cg_sky uniform = {.type = CG_SKY_UNIFORM, .radiance = {sky, sky, sky}};
    cg_error err = {0};
    assert_cg_ok(cg_scene_set_sky(&s.scene, &uniform, &err), &err);
    vf_runner run;
    vf_start(&run, &s.scene, SIZE, SIZE, metal_graph, NULL);
    vf_frame(&run);
    int n = 0, m = 0;
    float *glossy = vf_read_volume(&run, "light.glossy", 0, &n);
    float *radiance = vf_read_volume(&run, "light.radiance", 0, &m);
    float *albedo = vf_read_volume(&run, "vox.albedo", 0, &m);
    float *specular = vf_read_volume(&run, "vox.specular", 0, &m);
    assert_int_equal(n, m);
    float rg[2 * CGP_BRDF_TABLE_SIZE];
    cgp_brdf_hemispherical_fill(CGP_BRDF_TABLE_SIZE, rg);
    float at = r * (CGP_BRDF_TABLE_SIZE - 1);   /* texel j at roughness j / (size - 1) */
    int j = (int)floorf(at);
    float t = at - (float)j;
    double rho_s = f0 * ((1.0f - t) * rg[2 * j] + t * rg[2 * j + 2]) + ((1.0f - t) * rg[2 * j + 1] + t * rg[2 * j + 3]);
    double len = sqrt(0.3 * 0.3 + 1.0 + 0.2 * 0.2), cosine = 1.0 / len, direct = sun * cosine / M_PI;
    double expect = rho_s * (r * r * direct + sky) / (a * (direct + sky));
    /* Means over each plate's voxels, per coverage w (alpha): the planes are alike, so w is too. */
    double lit[2] = {0.0, 0.0}, black = 0.0, same = 0.0, held = 0.0, weight[2] = {0.0, 0.0};
    int voxels[2] = {0, 0}, off_alpha = 0;
    for (size_t i = 0; i < (size_t)n * n * n; i++) {
        const float *g = &glossy[4 * i], *v = &radiance[4 * i];
        if (v[3] <= 0.0f)
            continue;
        bool is_metal = specular[4 * i] > 0.0f && albedo[4 * i] == 0.0f;
        bool is_lambert = specular[4 * i] == 0.0f && albedo[4 * i] > 0.0f;
        if (is_metal) {
            lit[1] += g[1];
            weight[1] += v[3];
            black = fmax(black, v[1]);
            held += specular[4 * i + 1];
            off_alpha += fabsf(specular[4 * i + 3] - r * r) > 1.5f / 255.0f;
            voxels[1]++;
        } else if (is_lambert) {
            lit[0] += v[1];
            weight[0] += v[3];
            same = fmax(same, fabs(g[1] - v[1]) / fmax(v[1], 1e-6));
            voxels[0]++;
        }
    }
    double ratio = (lit[1] / weight[1]) / (lit[0] / weight[0]);
    fprintf(stderr, "# metal plate in glossy / Lambertian plate in radiance: %.4f, closed form %.4f (rho_s %.4f, "
            "voxelized %.4f); %d and %d voxels; metal in radiance at most %.2g; Lambertian glossy off its radiance "
            "by at most %.4f; %d voxels with another alpha\n", ratio, expect, rho_s, held / fmax(voxels[1], 1),
            voxels[1], voxels[0], black, same, off_alpha);
    assert_true(voxels[0] > 100 && voxels[1] > 100);
    assert_true(fabs(held / voxels[1] - rho_s) < 2.0 / 255.0);
    assert_int_equal(off_alpha, 0);
    assert_true(black == 0.0);
    assert_true(same < 1e-3);
    if (fabs(ratio / expect - 1.0) > 0.02)
        fail_msg("the metal's glossy light is %.4f of the Lambertian's, the closed form %.4f", ratio, expect);
    free(glossy);
    free(radiance);
    free(albedo);
    free(specular);
    assert_no_gl_errors(ctx);
    vf_stop(&run);
    hf_free(&s);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_furnace_ggx),
             cmocka_unit_test(test_furnace_hybrid),
             cmocka_unit_test(test_furnace_rough_dome),
             cmocka_unit_test(test_mirror),
             cmocka_unit_test(test_glass_slab),
             cmocka_unit_test(test_lambertian_unchanged),
             cmocka_unit_test(test_shadow_cone_sun_disc),
             cmocka_unit_test(test_glossy_is_one_bounce_more),
             cmocka_unit_test(test_lobes_read_glossy),
             cmocka_unit_test(test_metal_voxels_in_glossy),
             cmocka_unit_test(test_transmissive_voxels))
