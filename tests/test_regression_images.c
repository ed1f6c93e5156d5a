/* Image regression: every graph in graphs/ on every built-in scene, rendered by the built
 * `conegraph render` at 64x36, equals the image kept in tests/data/regression/.
 *
 * The kept images were rendered before a refactoring, so a change that must not alter any
 * image (moving code into the pass SDK, say) proves it here: the comparison is bit for bit
 * (llvmpipe is deterministic for one build; the voxelizer's atomic sums are fixed point, so
 * the order of fragments does not matter). A change that alters images on purpose renders
 * the new ones with CONEGRAPH_REGRESSION_UPDATE=1 (the test then writes instead of
 * comparing) and says in its commit what changed and by how much.
 *
 * A graph or scene without a kept image fails: a new one is added to the set on purpose.
 *
 * With CONEGRAPH_REGRESSION_PAIRS=cover (the sanitizer setup, tests/meson.build) only a
 * covering set of pairs is rendered: scene k with graph k, cycling the shorter list, so that
 * every graph and every scene runs once under the sanitizers. Their task there is the C code
 * each graph's passes and each scene's builder run, which the other pairs repeat; every pair's
 * image is compared in the plain suite.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/image.h"
#include "cg/metrics.h"
#include "cg/scene.h"
#include "test_support.h"

/* Largest |a - b| over all channels; -1 when the sizes differ. */
static double
max_difference(const cg_image *a, const cg_image *b)
{
    if (a->width != b->width || a->height != b->height)
        return -1.0;
    double worst = 0.0;
    for (size_t i = 0; i < (size_t)a->width * (size_t)a->height * 4; i++) {
        double d = fabs((double)a->rgba[i] - (double)b->rgba[i]);
        if (isnan(d))
            d = INFINITY;
        worst = fmax(worst, d);
    }
    return worst;
}

static void
test_every_graph_on_every_builtin_scene(void **state)
{
    (void)state;
    char kept_dir[4200]; /* a copy: the support's path slots are reused */
    snprintf(kept_dir, sizeof kept_dir, "%s", cg_test_data_path("regression"));
    const char *update = getenv("CONEGRAPH_REGRESSION_UPDATE");
    bool updating = update && *update && strcmp(update, "0");
    static char graphs[CG_TEST_MAX_GRAPHS][256];
    int graph_count = cg_test_list_graphs(graphs);
    assert_true(graph_count > 0);
    const char *pairs = getenv("CONEGRAPH_REGRESSION_PAIRS");
    bool cover = pairs && !strcmp(pairs, "cover");
    if (pairs && *pairs && !cover && strcmp(pairs, "all"))
        fail_msg("CONEGRAPH_REGRESSION_PAIRS is '%s'; expected 'all' or 'cover'", pairs);
    if (cover && updating)
        fail_msg("CONEGRAPH_REGRESSION_UPDATE renders every pair: unset CONEGRAPH_REGRESSION_PAIRS");
    int scene_count = 0;
    while (cg_scene_builtin_names()[scene_count])
        scene_count++;
    /* Pair k of the cover is scene k % S with graph k % G, k < max(S, G); all pairs run in order. */
    int pair_count = cover ? (scene_count > graph_count ? scene_count : graph_count) : scene_count * graph_count;
    int failures = 0;
    for (int k = 0; k < pair_count; k++) {
        const char *const *scene = cg_scene_builtin_names() + (cover ? k % scene_count : k / graph_count);
        int g = k % graph_count;
        static char out[1 << 16];
        static char kept[1 << 15], fresh[1 << 15], args[1 << 17];
        snprintf(kept, sizeof kept, "%s/%s-%s.exr", kept_dir, *scene, graphs[g]);
        snprintf(fresh, sizeof fresh, "%s/%s-%s.exr", cg_test_tmpdir(), *scene, graphs[g]);
        snprintf(args, sizeof args, "render builtin:%s --graph %s.json --size 64x36 -o '%s'", *scene,
                 graphs[g], updating ? kept : fresh);
        int code = cg_test_run_conegraph(args, true, out, sizeof out);
        if (code != 0) {
            print_error("%s exited %d:\n%s\n", args, code, out);
            failures++;
            continue;
        }
        if (updating) {
            print_message("# wrote %s\n", kept);
            continue;
        }
        cg_image a = {0}, b = {0};
        cg_error err = {0};
        if (!cg_image_read(kept, &a, &err)) {
            print_error("builtin:%s with %s.json: no kept image (%s); render it with "
                        "CONEGRAPH_REGRESSION_UPDATE=1\n", *scene, graphs[g], err.message);
            failures++;
            continue;
        }
        assert_cg_ok(cg_image_read(fresh, &b, &err), &err);
        double diff = max_difference(&a, &b);
        if (diff != 0.0) {
            cg_metrics m;
            bool sized = cg_metrics_compute(&b, &a, &m, &err);
            print_error("builtin:%s with %s.json differs from %s: max |difference| %g, relMSE %g, "
                        "mean luminance ratio %.6f\n", *scene, graphs[g], kept, diff,
                        sized ? m.rel_mse : -1.0, sized ? m.mean_luminance_ratio : -1.0);
            failures++;
        }
        cg_image_free(&a);
        cg_image_free(&b);
    }
    print_message("# %d of %d pairs rendered (%s)\n", pair_count, scene_count * graph_count, cover ? "cover" : "all");
    assert_int_equal(failures, 0);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_every_graph_on_every_builtin_scene))
