/* The sky through the cone tracers against the path tracer, as a user measures it: `conegraph
 * render` of graphs/vct.json and graphs/hybrid.json with their direct parts dumped, the
 * reference with its parts, `conegraph compare --direct ... --ref-direct ... --json`. 64x36.
 *   - a box under the sky, the sky its only light (builtin:cornell?light_scale=0, open at +z):
 *     the graphs' GI part against the path tracer's sky light reflected once and twice
 *     (direct_sky + indirect: the reference, 1 bounce, minus emitted and direct_punctual). The
 *     screen's cones see the sky (the path tracer's direct_sky), and the gathers at the voxels
 *     see it too, so the voxels' one bounce holds it reflected once more (its indirect), as the
 *     bounce convention says (docs/vct.md, "Bounces");
 *     the sky the camera sees (gbuffer's emissive) equals the reference's `emitted` part to the bit;
 *   - builtin:openworld (sun) under a uniform sky: the image's mean luminance within 7% of the
 *     path tracer's, and the GI energy. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

#define SIZE "--size 64x36"

static void
run_ok(const char *args)
{
    static char out[1 << 16];
    int rc = cg_test_run_conegraph(args, true, out, sizeof out);
    if (rc != 0)
        fail_msg("conegraph %s: exit %d\n%s", args, rc, out);
}

typedef struct sky_figures {
    double full_lum_ratio, gi_energy, gi_nrmse, direct_energy, direct_nrmse;
} sky_figures;

/* Renders `graph` on `scene` under `sky` and compares it with the reference `ref` (whose parts
 * `ref_direct` are already rendered). */
static sky_figures
measure(const char *scene, const char *sky, const char *graph, const char *ref, const char *ref_direct)
{
    char args[8192];
    const char *img = cg_test_tmp_path("gi.exr"), *d = cg_test_tmp_path("gi-direct.exr"), *e = cg_test_tmp_path("gi-emissive.exr");
    snprintf(args, sizeof args, "render '%s' --sky %s --graph %s " SIZE " -o '%s' --dump direct.radiance='%s' "
             "--dump gbuf.emissive='%s'", scene, sky, graph, img, d, e);
    run_ok(args);
    char out[1 << 14];
    snprintf(args, sizeof args, "compare '%s' '%s' --direct '%s' --direct '%s' %s --json", img, ref, d, e, ref_direct);
    int rc = cg_test_run_conegraph(args, false, out, sizeof out);
    if (rc != 0)
        fail_msg("conegraph %s: exit %d", args, rc);
    sky_figures f = {
        .full_lum_ratio = cg_test_json_number(out, "\"full\"", "lum_ratio"),
        .gi_energy = cg_test_json_number(out, "\"indirect\"", "energy"),
        .gi_nrmse = cg_test_json_number(out, "\"indirect\"", "nrmse"),
        .direct_energy = cg_test_json_number(out, "\"direct\"", "energy"),
        .direct_nrmse = cg_test_json_number(out, "\"direct\"", "nrmse"),
    };
    printf("# %s --sky %s, %s: full lum ratio %.4f, GI energy %.4f nrmse %.4f, direct energy %.6f nrmse %.2g\n",
           scene, sky, graph, f.full_lum_ratio, f.gi_energy, f.gi_nrmse, f.direct_energy, f.direct_nrmse);
    return f;
}

/* The reference of `scene` under `sky` with the parts named in `parts` dumped; fills the
 * compare options naming them as REF_DIRECT. */
static const char *
reference(const char *scene, const char *sky, int spp, const char *const *parts, char *ref_direct, size_t size)
{
    const char *ref = cg_test_tmp_path("ref.exr");
    char args[8192];
    int n = snprintf(args, sizeof args, "render '%s' --sky %s --graph reference.json " SIZE " --set trace.parts=true "
                     "--set trace.spp=%d --set trace.progress=false -o '%s'", scene, sky, spp, ref);
    ref_direct[0] = '\0';
    for (int i = 0; parts[i]; i++) {
        char name[64];
        snprintf(name, sizeof name, "ref-%s.exr", parts[i]);
        const char *path = cg_test_tmp_path(name);
        n += snprintf(args + n, sizeof args - (size_t)n, " --dump trace.%s='%s'", parts[i], path);
        size_t used = strlen(ref_direct);
        snprintf(ref_direct + used, size - used, " --ref-direct '%s'", path);
    }
    run_ok(args);
    return ref;
}

static void
box_under_the_sky(void **state)
{
    (void)state;
    const char *scene = "builtin:cornell?light_scale=0";
    static const char *const parts[] = {"emitted", "direct_punctual", NULL};
    char ref_direct[4096];
    const char *ref = reference(scene, "0.5", 256, parts, ref_direct, sizeof ref_direct);
    static const char *const graphs[] = {"vct.json", "hybrid.json"};
    for (int g = 0; g < 2; g++) {
        sky_figures f = measure(scene, "0.5", graphs[g], ref, ref_direct);
        /* The background (gbuffer's emissive there) is the sky the path tracer's escaping camera
         * rays see (its `emitted` part), and nothing else emits: equal to the bit. */
        char args[8192], out[1 << 14];
        snprintf(args, sizeof args, "compare '%s' '%s' --json", cg_test_tmp_path("gi-emissive.exr"), cg_test_tmp_path("ref-emitted.exr"));
        assert_int_equal(cg_test_run_conegraph(args, false, out, sizeof out), 0);
        assert_true(cg_test_json_number(out, "\"full\"", "rmse") == 0.0);
        assert_true(cg_test_json_number(out, "\"full\"", "mean_luminance_ref") > 0.1);
        /* Measured at 64x36, 256 spp, 26 cones, the diffuse cones at one pixel in 4x4 (downsample 4,
         * as shipped) and voxel_light's gathers at one voxel in 4^3 (bounce_spacing 4, as shipped):
         * vct.json 0.916, hybrid.json 0.916 (0.920 with bounce_spacing 1); at every pixel (downsample 1) 0.946 and
         * 0.944 (no height field here: the hybrid's march is cone_gather's on the same surface
         * voxels, in a box at 128 where vct.json's cube is 128^3: the same voxels; its start offset
         * 0.75 voxel against 1). The sky enters through the open front only; at every pixel the 5%
         * short are the cones that pass the opening's edges; the 4x4 blocks (16x9 of them at this
         * size) lose 3% more. Against direct_sky alone, as this test read it until the gathers at
         * the voxels saw the sky, the figures were 1.15-1.18: the twice-reflected sky light counted
         * as an excess.
         * The bounds hold the measured figures with a margin of 0.1 for the noise of the truth and
         * the platform, and fail for a sky left out (0), for voxels that do not see it
         * (`light.bounces=0`: 0.75 at 160x90) or for a sky gathered through the walls. */
        const double measured = 0.916;
        if (fabs(f.gi_energy - measured) > 0.1)
            fail_msg("%s: GI energy %.4f, measured %.3f (0.1 allowed)", graphs[g], f.gi_energy, measured);
    }
}

static void
open_world_under_the_sky(void **state)
{
    (void)state;
    const char *scene = "builtin:openworld";
    static const char *const parts[] = {"emitted", "direct_punctual", NULL};
    char ref_direct[4096];
    const char *ref = reference(scene, "0.3", 128, parts, ref_direct, sizeof ref_direct);
    static const char *const graphs[] = {"vct.json", "hybrid.json"};
    for (int g = 0; g < 2; g++) {
        sky_figures f = measure(scene, "0.3", graphs[g], ref, ref_direct);
        /* Issue 11's bar: within 7% of the path tracer's mean luminance (measured 0.988 and 0.986). */
        assert_true(fabs(f.full_lum_ratio - 1.0) < 0.07);
        /* GI energy against the reference's bounces plus its once-reflected sky light, measured
         * 0.949 (vct.json) and 0.938 (hybrid.json): the cone tracers miss the sky light
         * reflected twice; 0.1 allowed around 0.93. */
        assert_true(fabs(f.gi_energy - 0.93) < 0.1);
    }
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(box_under_the_sky),
             cmocka_unit_test(open_world_under_the_sky))
