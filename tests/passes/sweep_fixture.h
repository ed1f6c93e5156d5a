/* tests/passes/sweep_fixture.h: one graph file on one scene, rendered in this process, for the
 * tests that render the same scene many times over (test_scale_sweep.c, test_radiance_range.c).
 *
 * Declares: sf_render, sf_render_placed, sf_nonfinite, sf_compare, sf_level_runs.
 */
#ifndef CG_TEST_SWEEP_FIXTURE_H
#define CG_TEST_SWEEP_FIXTURE_H

#include <stdbool.h>
#include <stddef.h>

#include "cg/image.h"
#include "cg/metrics.h"

/* `final.hdr` of graphs/GRAPH.json on the scene `source` at width x height, one frame, with
 * `overrides` ("pass.param=value", NULL-terminated, may be NULL): linear RGBA, rows bottom to
 * top. Fails the test on any error. The caller frees with cg_image_free. */
cg_image sf_render(const char *source, const char *graph, const char *const *overrides, int width, int height);

/* The same with the scene scaled about the origin by `scale` after loading (cg_test_scale_scene:
 * lights keep their irradiance), for scenes without a scale parameter, then moved by `offset`
 * metres along each axis (geometry, lights and cameras). */
cg_image sf_render_placed(const char *source, double scale, double offset, const char *graph,
                          const char *const *overrides, int width, int height);

/* RGB values of the image that are NaN or infinite. */
size_t sf_nonfinite(const cg_image *img);

/* Whether level i of a sweep of `count` levels is rendered: every level, unless CONEGRAPH_SWEEP is
 * "extremes" (the sanitizer setup, tests/meson.build), which renders the first, the last and `unit`
 * (the one the others are compared with): under the sanitizers the sweeps' task is the C code each
 * graph runs, the same at every level; every level's image is compared in the plain suite. */
bool sf_level_runs(int i, int count, int unit);

/* The metrics of `test` against `ref`, `test` divided by `divide` first (1: as it is). */
cg_metrics sf_compare(const cg_image *test, const cg_image *ref, double divide);

#endif
