/* End to end on builtin:cornell with the shipped graphs (graphs/direct.json, vct.json,
 * vct-paper.json, vct-aniso.json, reference.json) at 64x64: VCT adds colour bleeding that direct light alone
 * cannot have (red on the white surfaces of the left half, green on the right half, as the
 * path tracer shows too; direct light alone is white there), and its mean luminance is closer to the path-traced
 * reference than the direct-only image's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cg/gl.h"
#include "cg/scene.h"
#include "test_support.h"
#include "vct_fixture.h"

#define SIZE 64

typedef struct cornell_image {
    float *hdr;         /* SIZE x SIZE RGBA, rows bottom to top */
    double luminance;   /* mean over the image */
    double bleed[2];    /* mean (R - G) / (R + G + B) over white surfaces, left and right halves */
} cornell_image;

/* White surfaces: where the G-buffer albedo is grey (the walls, floor, ceiling and blocks
 * of material "white"), from a run of graphs/direct.json. */
static void
measure(cornell_image *img, const float *albedo)
{
    double lum = 0, bleed[2] = {0, 0};
    int count[2] = {0, 0};
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++) {
            const float *p = &img->hdr[4 * (y * SIZE + x)], *a = &albedo[4 * (y * SIZE + x)];
            assert_true(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]));
            lum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            bool white = a[0] > 0.5f && fabsf(a[0] - a[1]) < 0.01f && fabsf(a[1] - a[2]) < 0.01f;
            double sum = (double)p[0] + p[1] + p[2];
            if (!white || sum <= 1e-6)
                continue;
            int side = x < SIZE / 2 ? 0 : 1;
            bleed[side] += (p[0] - p[1]) / sum;
            count[side]++;
        }
    assert_true(count[0] > 50 && count[1] > 50);
    img->luminance = lum / (SIZE * SIZE);
    img->bleed[0] = bleed[0] / count[0];
    img->bleed[1] = bleed[1] / count[1];
}

static void
render(const cg_scene *scene, const char *graph, const char *const *overrides, cornell_image *img,
       float **albedo)
{
    vf_runner r;
    vf_start_file(&r, scene, SIZE, SIZE, graph, overrides);
    vf_frame(&r);
    img->hdr = vf_read_image(&r, "final.hdr", SIZE, SIZE);
    if (albedo)
        *albedo = vf_read_image(&r, "gbuf.albedo", SIZE, SIZE);
    vf_stop(&r);
}

static void
test_cornell_bleeding_and_energy(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_scene scene = cg_test_load_scene("builtin:cornell");
    float *albedo = NULL;
    cornell_image direct = {0}, vct = {0}, paper = {0}, aniso = {0}, ref = {0};
    const char *const direct_set[] = {"final.exposure=0", NULL};
    const char *const ref_set[] = {"trace.spp=64", NULL};
    const char *const ref0_set[] = {"trace.spp=16", "trace.bounces=0", NULL};
    cornell_image ref0 = {0};
    render(&scene, "direct.json", direct_set, &direct, &albedo);
    render(&scene, "vct.json", NULL, &vct, NULL);
    render(&scene, "vct-paper.json", NULL, &paper, NULL);
    render(&scene, "vct-aniso.json", NULL, &aniso, NULL);
    render(&scene, "reference.json", ref_set, &ref, NULL);
    render(&scene, "reference.json", ref0_set, &ref0, NULL);
    measure(&direct, albedo);
    measure(&vct, albedo);
    measure(&paper, albedo);
    measure(&aniso, albedo);
    measure(&ref, albedo);
    measure(&ref0, albedo);
    const cornell_image *all[5] = {&direct, &vct, &paper, &aniso, &ref};
    const char *names[5] = {"direct", "vct", "vct-paper", "vct-aniso", "path traced"};
    for (int i = 0; i < 5; i++)
        fprintf(stderr, "# %-12s mean luminance %.5f, (R-G)/(R+G+B) on white: left %+.4f right %+.4f\n",
                names[i], all[i]->luminance, all[i]->bleed[0], all[i]->bleed[1]);
    /* Direct light is white: no bleeding at all. The path tracer has red on the left and
     * green (R < G) on the right; VCT must show the same signs, clearly. */
    assert_true(fabs(direct.bleed[0]) < 0.01 && fabs(direct.bleed[1]) < 0.01);
    assert_true(ref.bleed[0] > 0.01 && ref.bleed[1] < -0.01);
    for (int i = 1; i <= 3; i++) {
        if (!(all[i]->bleed[0] > 0.01 && all[i]->bleed[1] < -0.01))
            fail_msg("%s: no colour bleeding (left %+.4f, right %+.4f)", names[i], all[i]->bleed[0], all[i]->bleed[1]);
        if (!(fabs(all[i]->luminance - ref.luminance) < fabs(direct.luminance - ref.luminance)))
            fail_msg("%s: mean luminance %.5f is not closer to the reference %.5f than direct's %.5f",
                     names[i], all[i]->luminance, ref.luminance, direct.luminance);
    }
    /* The indirect light alone (image minus the path tracer's direct light, against the
     * path tracer's one bounce minus the same): its mean luminance within 15% of the path
     * tracer's for vct.json (measured 1.10 at 160x90 against 256 spp, docs/vct.md) and the
     * anisotropic graph. Before the samples were kept off the cone's own surface and the
     * coverage made exact, the ratio rested on two errors cancelling (a leak of 10% and an
     * over-estimate of 14%). vct-paper.json (64^3 RGBA8, 9 cones) gathers more (1.4 at
     * 160x90): printed, and bounded only by the energy test above. */
    double ref_indirect = ref.luminance - ref0.luminance;
    assert_true(ref_indirect > 0.0);
    for (int i = 1; i <= 3; i++) {
        double ratio = (all[i]->luminance - ref0.luminance) / ref_indirect;
        fprintf(stderr, "# %-12s indirect luminance / path tracer's: %.4f\n", names[i], ratio);
        if (i != 2 && fabs(ratio - 1.0) > 0.15)
            fail_msg("%s: indirect luminance %.4f of the path tracer's, expected within 15%%", names[i], ratio);
    }
    free(ref0.hdr);
    for (int i = 0; i < 5; i++)
        free(all[i]->hdr);
    free(albedo);
    assert_no_gl_errors(ctx);
    cg_scene_free(&scene);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(test_cornell_bleeding_and_energy))
