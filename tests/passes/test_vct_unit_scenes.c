/* graphs/vct.json's indirect light on the unit scenes whose answer is known (docs/scenes.md,
 * docs/vct.md "Accuracy"), at 64x36:
 *   - builtin:plates: the receiver's light is the closed-form view factor of the source plate
 *     (Lambert's polygon formula), straight and turned against the voxel axes, and the same
 *     wherever the plate falls within the mip levels' texels;
 *   - builtin:wallfloor: floor and wall light each other by the form factor between perpendicular
 *     rectangles (the same formula per pixel);
 *   - builtin:thinwall: the dark side of a wall lit on one side gets nothing;
 *   - builtin:boxplane and builtin:terrain: the path tracer's one bounce is the truth;
 *   - builtin:openworld through vct.json and hybrid.json (whose 3D part is the same surface
 *     voxels, of the buildings' box at 128) against the path tracer.
 * The estimate is what compare's --direct measures (apps/compare, core/metrics' cg_metrics_part):
 * the final image minus the graph's own direct light and emission; the figures are its mean
 * luminance over the truth's (energy) and rmse(estimate - truth) / rms(truth) (nrmse). Each
 * tolerance says what it rests on. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/gl.h"
#include "cg/scene.h"
#include "test_support.h"
#include "vct_fixture.h"

#define W 64
#define H 36
#define PI 3.14159265358979323846

/* One render of vct.json: the indirect estimate (final.hdr - direct.radiance - gbuf.emissive) and the
 * G-buffer's positions and normals. */
typedef struct unit_render {
    float *estimate, *position, *normal;
} unit_render;

static unit_render
render_graph(const cg_scene *scene, const char *graph, const char *const *overrides)
{
    vf_runner r;
    vf_start_file(&r, scene, W, H, graph, overrides);
    vf_frame(&r);
    unit_render u = {vf_read_image(&r, "final.hdr", W, H), vf_read_image(&r, "gbuf.position", W, H),
                     vf_read_image(&r, "gbuf.normal", W, H)};
    float *direct = vf_read_image(&r, "direct.radiance", W, H);
    float *emissive = vf_read_image(&r, "gbuf.emissive", W, H);
    for (int i = 0; i < W * H * 4; i++)
        u.estimate[i] -= direct[i] + emissive[i];
    free(direct);
    free(emissive);
    vf_stop(&r);
    return u;
}

static unit_render
render_vct(const cg_scene *scene, const char *const *overrides)
{
    return render_graph(scene, "vct.json", overrides);
}

static void
unit_render_free(unit_render *u)
{
    free(u->estimate);
    free(u->position);
    free(u->normal);
}

/* The path tracer's light off surfaces: its image minus its parts emitted and direct_punctual, as
 * bench's and compare's truth of the GI part. 1024 samples: its own noise is nrmse 0.03-0.06 at
 * this size (measured against a second seed), small beside the tolerances. */
static float *
path_traced_indirect(const cg_scene *scene)
{
    static const char *const set[] = {"trace.spp=1024", "trace.bounces=1", "trace.parts=true", NULL};
    vf_runner r;
    vf_start_file(&r, scene, W, H, "reference.json", set);
    vf_frame(&r);
    float *all = vf_read_image(&r, "trace.radiance", W, H);
    float *emitted = vf_read_image(&r, "trace.emitted", W, H);
    float *punctual = vf_read_image(&r, "trace.direct_punctual", W, H);
    for (int i = 0; i < W * H * 4; i++)
        all[i] -= emitted[i] + punctual[i];
    free(emitted);
    free(punctual);
    vf_stop(&r);
    return all;
}

static double
luminance(const float *p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

typedef struct part_figures {
    double energy, nrmse, mean_estimate, mean_truth;
    int pixels;
} part_figures;

/* Over the pixels where mask is nonzero (all covered pixels when mask is NULL). */
static part_figures
figures(const float *estimate, const float *truth, const float *position, const unsigned char *mask)
{
    double se = 0, st = 0, le = 0, lt = 0;
    int n = 0;
    for (int i = 0; i < W * H; i++) {
        if (position[4 * i + 3] <= 0.0f || (mask && !mask[i]))
            continue;
        for (int k = 0; k < 3; k++) {
            assert_true(isfinite(estimate[4 * i + k]));
            double d = (double)estimate[4 * i + k] - truth[4 * i + k];
            se += d * d;
            st += (double)truth[4 * i + k] * truth[4 * i + k];
        }
        le += luminance(&estimate[4 * i]);
        lt += luminance(&truth[4 * i]);
        n++;
    }
    assert_true(n > 0);
    part_figures f = {lt > 0 ? le / lt : INFINITY, st > 0 ? sqrt(se / st) : INFINITY, le / n, lt / n, n};
    return f;
}

/* Lambert's formula for the form factor from a point x with unit normal n to the polygon v[0..3]
 * wholly in front of it: F = 1 / (2 pi) sum_i gamma_i n . (r_i x r_(i+1)) / |r_i x r_(i+1)|, gamma_i
 * the angle between the directions r_i, r_(i+1) to consecutive vertices. */
static double
form_factor(const double x[3], const double n[3], const double v[4][3])
{
    double r[4][3], sum = 0;
    for (int i = 0; i < 4; i++) {
        double len = 0;
        for (int k = 0; k < 3; k++) {
            r[i][k] = v[i][k] - x[k];
            len += r[i][k] * r[i][k];
        }
        for (int k = 0; k < 3; k++)
            r[i][k] /= sqrt(len);
    }
    for (int i = 0; i < 4; i++) {
        const double *a = r[i], *b = r[(i + 1) % 4];
        double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        double cl = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double dot = fmin(1.0, fmax(-1.0, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
        if (cl > 0)
            sum += acos(dot) * (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / cl;
    }
    return fabs(sum) / (2.0 * PI);
}

/* World to the scene's local frame: the unit scenes turn everything by one rotation (their
 * instances' matrix, no translation). */
static void
to_local(const cg_scene *scene, const float *p, double out[3])
{
    const float *m = scene->instances[0].world;
    for (int r = 0; r < 3; r++)
        out[r] = m[4 * r + 0] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2];
}

static void
load(const char *source, cg_scene *scene)
{
    cg_error err = {0};
    assert_cg_ok(cg_scene_load(source, scene, &err), &err);
}

static void
check(const char *what, part_figures f, double lo, double hi, double max_nrmse)
{
    fprintf(stderr, "# %-36s energy %.4f nrmse %.4f (mean estimate %.5g, truth %.5g, %d pixels)\n", what, f.energy,
            f.nrmse, f.mean_estimate, f.mean_truth, f.pixels);
    if (!(f.energy >= lo && f.energy <= hi) || !(f.nrmse <= max_nrmse))
        fail_msg("%s: energy %.4f (expected %.2f..%.2f), nrmse %.4f (expected at most %.2f)", what, f.energy, lo, hi,
                 f.nrmse, max_nrmse);
}

/* Parallel plates, w = 1, source at h, the sun E = 3 from below at beta = atan(1.2 w / h) lighting
 * the source's underside (radiance L_s = rho E cos beta / pi) and not the receiver's top, whose
 * light is then rho L_s F(x -> source); the source's underside sees only the dark top: 0.
 * vct.json's figures on `source` against that closed form, with `overrides`. */
static part_figures
plates_figures(const char *source, double h, const char *const *overrides)
{
    cg_scene scene;
    load(source, &scene);
    double rho = 0.8, E = 3.0, beta = atan(1.2 / h);
    double ls = rho * E * cos(beta) / PI;
    const double plate[4][3] = {{-0.5, h, -0.5}, {0.5, h, -0.5}, {0.5, h, 0.5}, {-0.5, h, 0.5}};
    unit_render u = render_vct(&scene, overrides);
    float *truth = calloc((size_t)W * H * 4, sizeof(float));
    assert_non_null(truth);
    for (int i = 0; i < W * H; i++) {
        if (u.position[4 * i + 3] <= 0.0f)
            continue;
        double x[3], n[3];
        to_local(&scene, &u.position[4 * i], x);
        to_local(&scene, &u.normal[4 * i], n);
        if (n[1] > 0.9 && fabs(x[1]) < 1e-3) {
            const double up[3] = {0, 1, 0};
            double v = rho * ls * form_factor(x, up, plate);
            for (int k = 0; k < 3; k++)
                truth[4 * i + k] = (float)v;
        }
    }
    part_figures f = figures(u.estimate, truth, u.position, NULL);
    free(truth);
    unit_render_free(&u);
    cg_scene_free(&scene);
    return f;
}

/* Tolerance: energy 0.90..1.10 and nrmse 0.30, the target (10%) with the nrmse these
 * compact sources reach. The closed form is exact; vct.json's 26 cones measure 1.02, 1.09 and 1.05
 * here at 64x36 in 4x4 blocks as shipped (1.03, 1.07 and 1.01 at every pixel; 1.00-1.09 over
 * h = 0.25..2 at 160x90, docs/vct.md). With 16 cones the outer
 * ring's wide cones over-gather where they cross the source obliquely, 1.17 at h = 0.5; the old
 * two-sided volume gathered 1.37 at h = 1 and 1.94 at h = 0.5 (docs/vct.md, cause 1). */
static void
test_plates_view_factor(void **state)
{
    (void)cg_test_gl_context(state);
    static const char *const sources[] = {"builtin:plates", "builtin:plates?h=0.5", "builtin:plates?yaw=30&tilt=20"};
    static const double heights[] = {1.0, 0.5, 1.0};
    for (int s = 0; s < 3; s++)
        check(sources[s], plates_figures(sources[s], heights[s], NULL), 0.90, 1.10, 0.30);
}

/* Where the surfaces fall in the voxel grid must not change their light: the plates (h = 1) with the
 * volume's padding at 1, 4, 8 and 12 voxels, which moves the source plate within its mip texels (the
 * cube spans the bounds and the padding in 128 voxels, so the plate lies at voxel 128 - padding: 7,
 * 4, 0 and -4 voxels from the centre of its level-4 texel, the level the outer cones cross it at).
 * Asserted: the energies within 0.05 of each other. A level keeps a surface's coverage at its
 * texel's centre, up to half a cell off the surface; crossings are read centred on the surface's
 * plane (common/cone_trace.glsl, cg_cone_surface_recentre). Measured at this size: 0.039 (1.023..1.063)
 * in 4x4 blocks as shipped, 0.025 (1.011..1.036) at every pixel; with the crossings read on the axis
 * (before, at every pixel): 0.114 (0.988..1.102), which fails. */
static void
test_plates_alignment(void **state)
{
    (void)cg_test_gl_context(state);
    static const char *const paddings[] = {"vox.padding=1", "vox.padding=4", "vox.padding=8", "vox.padding=12"};
    double lo = INFINITY, hi = -INFINITY;
    for (int p = 0; p < 4; p++) {
        const char *const overrides[] = {paddings[p], NULL};
        part_figures f = plates_figures("builtin:plates", 1.0, overrides);
        fprintf(stderr, "# plates, %s: energy %.4f nrmse %.4f\n", paddings[p], f.energy, f.nrmse);
        lo = fmin(lo, f.energy);
        hi = fmax(hi, f.energy);
    }
    fprintf(stderr, "# plates: energy %.4f..%.4f over the paddings, spread %.4f\n", lo, hi, hi - lo);
    if (!(hi - lo <= 0.05))
        fail_msg("plates: the energy moves by %.4f (%.4f..%.4f) with the grid's alignment", hi - lo, lo, hi);
}

/* Floor (y = 0, x in [-1, 1], z in [0, 1]) and wall (z = 0, y in [0, 1]) lit by the sun E = 3 at 45
 * degrees: the floor's light is rho L_wall F(x -> wall), the wall's rho L_floor F(x -> floor), with
 * L = rho E cos / pi of each one's angle to the sun. Tolerance: energy 0.90..1.10, nrmse 0.30, as
 * the plates'; measured 1.01 and 1.03 (turned) at 64x36 in 4x4 blocks as shipped, 1.02 and 1.05 at
 * every pixel, 1.01 and 1.05 at 160x90 (docs/vct.md);
 * with 16 cones 1.10 and 1.12, the old volume 1.56. */
static void
test_wallfloor_form_factor(void **state)
{
    (void)cg_test_gl_context(state);
    static const char *const sources[] = {"builtin:wallfloor", "builtin:wallfloor?yaw=30&tilt=20"};
    for (int s = 0; s < 2; s++) {
        cg_scene scene;
        load(sources[s], &scene);
        double rho = 0.8, E = 3.0, g = 45.0 * PI / 180.0;
        double l_wall = rho * E * cos(g) / PI, l_floor = rho * E * sin(g) / PI;
        const double wall[4][3] = {{-1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 1, 0}};
        const double floor_[4][3] = {{-1, 0, 0}, {1, 0, 0}, {1, 0, 1}, {-1, 0, 1}};
        unit_render u = render_vct(&scene, NULL);
        float *truth = calloc((size_t)W * H * 4, sizeof(float));
        assert_non_null(truth);
        for (int i = 0; i < W * H; i++) {
            if (u.position[4 * i + 3] <= 0.0f)
                continue;
            double x[3], n[3], v = 0;
            to_local(&scene, &u.position[4 * i], x);
            to_local(&scene, &u.normal[4 * i], n);
            const double up[3] = {0, 1, 0}, front[3] = {0, 0, 1};
            if (n[1] > 0.9)
                v = rho * l_wall * form_factor(x, up, wall);
            else if (n[2] > 0.9)
                v = rho * l_floor * form_factor(x, front, floor_);
            for (int k = 0; k < 3; k++)
                truth[4 * i + k] = (float)v;
        }
        check(sources[s], figures(u.estimate, truth, u.position, NULL), 0.90, 1.10, 0.30);
        free(truth);
        unit_render_free(&u);
        cg_scene_free(&scene);
    }
}

/* A wall lit on its front only, the back floor wholly in its shadow: on the dark side (view=0) no
 * surface in sight is lit, so the indirect light there is exactly 0. Asserted: its mean luminance
 * below 2% of the lit side's true mean indirect light (view=1). One-sided voxels leave a residue
 * where a cell holds the wall and the lit front floor (one mean plane for both, the lit side blended
 * over half a cell): 1.0% at 160x90, 0.69% here; the old two-sided volume showed the dark side as much light
 * as the lit side gets (0.039 against 0.038, docs/vct.md, cause 1). */
static void
test_thinwall_dark_side(void **state)
{
    (void)cg_test_gl_context(state);
    cg_scene dark, lit;
    load("builtin:thinwall?view=0", &dark);
    load("builtin:thinwall?view=1", &lit);
    unit_render d = render_vct(&dark, NULL);
    float *zero = calloc((size_t)W * H * 4, sizeof(float));
    assert_non_null(zero);
    part_figures fd = figures(d.estimate, zero, d.position, NULL);
    float *truth = path_traced_indirect(&lit);
    unit_render l = render_vct(&lit, NULL);
    part_figures fl = figures(l.estimate, truth, l.position, NULL);
    fprintf(stderr, "# thinwall: dark side mean %.3g, lit side's truth %.4g (ratio %.4f); lit side energy %.4f "
            "nrmse %.4f\n", fd.mean_estimate, fl.mean_truth, fd.mean_estimate / fl.mean_truth, fl.energy, fl.nrmse);
    if (!(fd.mean_estimate < 0.02 * fl.mean_truth))
        fail_msg("thinwall: the dark side gathers %.3g, %.2f%% of the lit side's light", fd.mean_estimate,
                 100.0 * fd.mean_estimate / fl.mean_truth);
    check("builtin:thinwall?view=1 (lit side)", fl, 0.90, 1.10, 0.30);
    free(zero);
    free(truth);
    unit_render_free(&d);
    unit_render_free(&l);
    cg_scene_free(&dark);
    cg_scene_free(&lit);
}

/* A box on a sunlit plane and a sunlit sinusoidal terrain against the path tracer. Tolerance:
 * energy 0.90..1.10, nrmse 0.40, the target: measured 1.01 / 0.16 and 1.04 / 0.31 at 64x36
 * in 4x4 blocks as shipped, 0.99 / 0.17 and 1.06 / 0.20 at every pixel (at 160x90 0.99 / 0.18 and
 * 1.05 / 0.21, docs/vct.md; with 16 cones 1.10 / 0.18 and 1.07 / 0.34);
 * the old volume gathered 1.84 and 2.06. A flat sunlit plane (terrain A = 0) gathers nothing: below 1e-4 of the
 * terrain's light (the cone's own plane left out, cg_cone_sample_surface). */
static void
test_boxplane_and_terrain(void **state)
{
    (void)cg_test_gl_context(state);
    static const char *const sources[] = {"builtin:boxplane", "builtin:terrain?n=64"};
    double terrain_truth = 0;
    for (int s = 0; s < 2; s++) {
        cg_scene scene;
        load(sources[s], &scene);
        float *truth = path_traced_indirect(&scene);
        unit_render u = render_vct(&scene, NULL);
        part_figures f = figures(u.estimate, truth, u.position, NULL);
        check(sources[s], f, 0.90, 1.10, 0.40);
        terrain_truth = f.mean_truth;
        free(truth);
        unit_render_free(&u);
        cg_scene_free(&scene);
    }
    cg_scene flat;
    load("builtin:terrain?A=0&n=8", &flat);
    unit_render u = render_vct(&flat, NULL);
    float *zero = calloc((size_t)W * H * 4, sizeof(float));
    assert_non_null(zero);
    part_figures f = figures(u.estimate, zero, u.position, NULL);
    fprintf(stderr, "# flat sunlit plane: mean gathered %.3g (terrain's truth %.4g)\n", f.mean_estimate, terrain_truth);
    assert_true(f.mean_estimate < 1e-4 * terrain_truth);
    free(zero);
    unit_render_free(&u);
    cg_scene_free(&flat);
}

/* builtin:openworld (a 400 m terrain of 200 000 triangles and its town) through both cone-traced
 * graphs against the path tracer. Tolerance: energy 0.90..1.10, nrmse 0.40, the target;
 * measured here at 64x36 with 26 cones in 4x4 blocks as shipped: vct.json 0.904 / 0.347, hybrid.json
 * 0.925 / 0.309; at every pixel 0.920 / 0.333 and 0.956 / 0.267 (at 160x90: docs/vct.md,
 * docs/hybrid.md). Both stop a little short of the light near the horizon.
 * Before the hybrid read the surface voxels with 16 cones its energy was 1.46 / 0.78, and the
 * radiance-voxel vct.json's 1.62 / 0.85: both fail. */
static void
test_openworld(void **state)
{
    (void)cg_test_gl_context(state);
    cg_scene scene;
    load("builtin:openworld", &scene);
    float *truth = path_traced_indirect(&scene);
    static const char *const graphs[] = {"vct.json", "hybrid.json"};
    for (int g = 0; g < 2; g++) {
        unit_render u = render_graph(&scene, graphs[g], NULL);
        char what[64];
        snprintf(what, sizeof what, "builtin:openworld, %s", graphs[g]);
        check(what, figures(u.estimate, truth, u.position, NULL), 0.90, 1.10, 0.40);
        unit_render_free(&u);
    }
    free(truth);
    cg_scene_free(&scene);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_plates_view_factor),
             cmocka_unit_test(test_plates_alignment),
             cmocka_unit_test(test_openworld),
             cmocka_unit_test(test_wallfloor_form_factor),
             cmocka_unit_test(test_thinwall_dark_side),
             cmocka_unit_test(test_boxplane_and_terrain))
