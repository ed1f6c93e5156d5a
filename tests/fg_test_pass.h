/* tests/fg_test_pass.h: pass types for frame-graph tests whose slots come from parameters.
 *
 * Declares: fg_test_register, fg_test_fixture, fg_test_fixture_setup,
 *           fg_test_fixture_teardown, fg_test_unit.
 *
 * Registers two types, "t" and "t_side" (a side-effect pass), with the parameters
 *   inputs   "NAME:KIND:ACCESS[:opt] ..."   KIND 2d|3d|array|buffer, ACCESS sampled|load|store|
 *                                          attach|storage|uniform|transfer joined by '+'
 *   outputs  "NAME:KIND:FORMAT:SIZE:ACCESS[:persistent][:gi][:mips] ..."  FORMAT as in the
 *            report (RGBA16F, R32F, DEPTH32F, RGBA8, ...; "-" for buffers), SIZE WxH, WxHxD,
 *            "frame" (the output image), or BYTES for buffers; mips = full chain
 *   nothing  declare nothing to do
 *   value    what execute() clears every 2D/3D colour output to (RGBA)
 *   for parameter validation tests only:
 *   cones    int 1, 6, 9 or 16 (allowed values); resolution int 1..4096, a power of two;
 *   scale    float [0, 1]; label string;
 *   bounded  bool; low, high floats [-100, 100] that matter only while bounded, high > low;
 *   margin   float [0, 100], below 0.25 x resolution
 * execute() clears each colour texture output to `value` with glClearTexImage and counts
 * its calls in the pass state (an int); on odd calls since prepare it reports "execute N"
 * (fg_pass_report_rebuilt), on even ones nothing.
 */
#ifndef CG_TEST_FG_TEST_PASS_H
#define CG_TEST_FG_TEST_PASS_H

#include <stdbool.h>

#include "cg/fg.h"

bool fg_test_register(fg_registry *registry, cg_error *err);

/* A frame graph over a registry of these types, with a 64x32 frame (no scene) and default
 * compile options: what the frame-graph tests start each test from. */
typedef struct fg_test_fixture {
    fg_registry *registry;
    fg_graph *graph;
    cg_error err;
    fg_frame frame;
    fg_compile_options options;
} fg_test_fixture;

/* cmocka per-test setup and teardown: a fresh fg_test_fixture in *state, freed after. */
int fg_test_fixture_setup(void **state);
int fg_test_fixture_teardown(void **state);
/* A cmocka test entry run on a fresh fg_test_fixture. */
#define fg_test_unit(test) cmocka_unit_test_setup_teardown(test, fg_test_fixture_setup, fg_test_fixture_teardown)

#endif
