/* The demo without a window: parameter stepping from the tables (apps/demo/demo_params.c),
 * the UI's controls built from the same tables, the pass/parameter selection on a real
 * graph, the fly camera, the animation clock and the sun key's turn (apps/demo/demo_anim.c),
 * and the command line: --help and bad input (exit 2 before any window opens;
 * $CONEGRAPH_DEMO_EXE). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "../apps/demo/demo_anim.h"
#include "../apps/demo/demo_camera.h"
#include "../apps/demo/demo_params.h"
#include "sdk/builtin.h"
#include "cg/camera.h"
#include "cg/graphfile.h"
#include "test_support.h"

static const fg_param_desc cones = { .name = "cones", .type = FG_PARAM_INT, .default_value = 6, .min = 1,
                                     .max = 16, .allowed = FG_PARAM_VALUES(1, 6, 9, 16), .doc = "cones" };
static const fg_param_desc resolution = { .name = "resolution", .type = FG_PARAM_INT, .default_value = 128,
                                          .min = 16, .max = 512, .power_of_two = true, .doc = "voxels" };
static const fg_param_desc samples = { .name = "spp", .type = FG_PARAM_INT, .default_value = 64, .min = 1,
                                       .max = 65536, .step_doubles = true, .doc = "samples" };
static const fg_param_desc count = { .name = "threads", .type = FG_PARAM_INT, .min = 0, .max = 256,
                                     .doc = "threads" };
static const fg_param_desc light = { .name = "light", .type = FG_PARAM_INT, .default_value = -1, .min = -1,
                                     .max = 65535, .doc = "light index" };
static const fg_param_desc exposure = { .name = "exposure", .type = FG_PARAM_FLOAT, .min = -20, .max = 20,
                                        .doc = "EV" };
static const fg_param_desc aperture = { .name = "aperture", .type = FG_PARAM_FLOAT, .min = 0, .max = 150,
                                        .step = 5, .doc = "degrees" };
static const fg_param_desc step = { .name = "step", .type = FG_PARAM_FLOAT, .default_value = 0.25, .min = 0.05,
                                    .max = 4, .doc = "step" };
static const fg_param_desc distance = { .name = "max_distance", .type = FG_PARAM_FLOAT, .min = 0, .max = 1e9,
                                        .doc = "metres" };
static const fg_param_desc flag = { .name = "specular", .type = FG_PARAM_BOOL, .doc = "mirror cone" };
static const fg_param_desc tonemap = { .name = "tonemap", .type = FG_PARAM_ENUM, .default_value = 2,
                                       .choices = "none|reinhard|aces", .doc = "tonemap" };
static const fg_param_desc text = { .name = "name", .type = FG_PARAM_STRING, .choices = "x", .doc = "a string" };

/* One step from `value`; fails the test when there is none. */
static double
stepped(const fg_param_desc *desc, double value, int direction)
{
    double out = NAN;
    if (!demo_param_step(desc, value, direction, &out))
        fail_msg("%s: no step %+d from %g", desc->name, direction, value);
    return out;
}

static void
assert_no_step(const fg_param_desc *desc, double value, int direction)
{
    double out = NAN;
    if (demo_param_step(desc, value, direction, &out))
        fail_msg("%s: step %+d from %g gave %g; expected none", desc->name, direction, value, out);
}

static void
test_step_int(void **state)
{
    (void)state;
    /* Allowed values: exactly those, both ways; the ends stop the keys. */
    assert_true(stepped(&cones, 6, 1) == 9);
    assert_true(stepped(&cones, 9, 1) == 16);
    assert_true(stepped(&cones, 16, -1) == 9);
    assert_true(stepped(&cones, 9, -1) == 6);
    assert_true(stepped(&cones, 6, -1) == 1);
    assert_no_step(&cones, 16, 1);
    assert_no_step(&cones, 1, -1);
    /* A plain int range steps by one, also from below 1 (an index). */
    assert_true(stepped(&count, 0, 1) == 1);
    assert_true(stepped(&count, 7, -1) == 6);
    assert_no_step(&count, 256, 1);
    assert_true(stepped(&light, -1, 1) == 0);
    assert_no_step(&light, -1, -1);
    /* Powers of two: the next power of two in the range, from any value. */
    assert_true(stepped(&resolution, 128, 1) == 256);
    assert_true(stepped(&resolution, 256, 1) == 512);
    assert_true(stepped(&resolution, 128, -1) == 64);
    assert_true(stepped(&resolution, 300, 1) == 512);
    assert_true(stepped(&resolution, 300, -1) == 256);
    assert_true(stepped(&resolution, 17, -1) == 16);
    assert_true(stepped(&resolution, 17, 1) == 32);
    assert_no_step(&resolution, 512, 1);
    assert_no_step(&resolution, 16, -1);
    /* step_doubles: doubled and halved, the bounds stop it. */
    assert_true(stepped(&samples, 64, 1) == 128);
    assert_true(stepped(&samples, 64, -1) == 32);
    assert_true(stepped(&samples, 3, -1) == 1);
    assert_true(stepped(&samples, 40000, 1) == 65536);
    assert_no_step(&samples, 1, -1);
    assert_no_step(&samples, 65536, 1);
    assert_true(demo_param_step_size(&count, 6) == 1);
    assert_true(demo_param_step_size(&cones, 6) == 0);
    assert_true(demo_param_step_size(&resolution, 128) == 0);
    assert_true(demo_param_step_size(&samples, 64) == 0);
}

static void
test_step_float(void **state)
{
    (void)state;
    /* 1/50 of [-20, 20] is 0.8: the step is 0.5. */
    assert_true(demo_param_step_size(&exposure, 0) == 0.5);
    assert_true(stepped(&exposure, 0, 1) == 0.5);
    assert_true(stepped(&exposure, 0, -1) == -0.5);
    /* Off the grid, the step lands on it. */
    assert_true(stepped(&exposure, 0.3, 1) == 0.5);
    assert_true(stepped(&exposure, 0.3, -1) == 0.0);
    assert_no_step(&exposure, 20, 1);
    assert_true(stepped(&exposure, 19.8, 1) == 20);
    /* Values come back from the graph as floats: 0.3f is a hair above 0.3 and must still
     * step to 0.35 and 0.25, not skip or stall. */
    assert_true(demo_param_step_size(&step, 0.25) == 0.05);
    assert_true(fabs(stepped(&step, (float)0.25, 1) - 0.3) < 1e-12);
    assert_true(fabs(stepped(&step, (float)0.3, 1) - 0.35) < 1e-12);
    assert_true(fabs(stepped(&step, (float)0.3, -1) - 0.25) < 1e-12);
    assert_true(fabs(stepped(&step, (float)0.05, 1) - 0.1) < 1e-12);
    assert_no_step(&step, (float)0.05, -1);
    assert_no_step(&step, 4, 1);
    /* The table's step hint, on its grid. */
    assert_true(demo_param_step_size(&aperture, 0) == 5);
    assert_true(stepped(&aperture, 0, 1) == 5);
    assert_true(stepped(&aperture, 12, 1) == 15);
    assert_true(stepped(&aperture, 12, -1) == 10);
    assert_true(stepped(&aperture, 148, 1) == 150);
    assert_no_step(&aperture, 0, -1);
    /* A range wider than 1000: about a quarter of the value, at least 0.2. */
    assert_true(demo_param_step_size(&distance, 0) == 0.2);
    assert_true(fabs(stepped(&distance, 0, 1) - 0.2) < 1e-12);
    assert_true(stepped(&distance, 10, 1) == 12);
    assert_true(stepped(&distance, 10, -1) == 8);
    assert_true(stepped(&distance, 100, 1) == 120);
    assert_no_step(&distance, 0, -1);
}

static void
test_step_bool_enum_string(void **state)
{
    (void)state;
    assert_true(stepped(&flag, 0, 1) == 1);
    assert_true(stepped(&flag, 1, 1) == 0);
    assert_true(stepped(&flag, 0, -1) == 1);
    assert_true(stepped(&tonemap, 0, 1) == 1);
    assert_true(stepped(&tonemap, 2, 1) == 0);      /* wraps round */
    assert_true(stepped(&tonemap, 0, -1) == 2);
    assert_no_step(&text, 0, 1);
    assert_no_step(&text, 0, -1);
    assert_no_step(&cones, 6, 0);
}

static void
test_format(void **state)
{
    (void)state;
    char out[64];
    demo_param_format(&cones, 9, out, sizeof out);
    assert_string_equal(out, "9");
    demo_param_format(&step, 0.35000000000000003, out, sizeof out);
    assert_string_equal(out, "0.35");
    demo_param_format(&exposure, -0.5, out, sizeof out);
    assert_string_equal(out, "-0.5");
    demo_param_format(&flag, 1, out, sizeof out);
    assert_string_equal(out, "true");
    demo_param_format(&flag, 0, out, sizeof out);
    assert_string_equal(out, "false");
    demo_param_format(&tonemap, 1, out, sizeof out);
    assert_string_equal(out, "reinhard");
}

static fg_graph *
load_graph(const char *name, fg_registry **registry)
{
    cg_error err = { 0 };
    *registry = fg_registry_create();
    assert_non_null(*registry);
    assert_cg_ok(cg_builtin_passes_register(*registry, &err), &err);
    fg_graph *graph = fg_graph_create(*registry);
    assert_non_null(graph);
    assert_cg_ok(fg_graph_load_file(graph, cg_test_graph_path(name), &err), &err);
    return graph;
}

static int
params_of(const fg_graph *graph, int pass)
{
    return fg_pass_type_of(fg_graph_pass_at(graph, pass))->param_count;
}

/* Tab visits every pass that has parameters once per round, skipping those without. */
static void
test_selection(void **state)
{
    (void)state;
    fg_registry *registry;
    fg_graph *graph = load_graph("vct.json", &registry);
    int with_params = 0;
    for (int p = 0; p < fg_graph_pass_count(graph); p++)
        with_params += params_of(graph, p) > 0;
    assert_true(with_params >= 2);
    assert_true(with_params < fg_graph_pass_count(graph)); /* gbuffer has none */

    demo_selection sel;
    demo_select_first(graph, &sel);
    assert_int_equal(sel.param, 0);
    int first = sel.pass, visits = 0;
    do {
        assert_true(params_of(graph, sel.pass) > 0);
        demo_select_pass(graph, &sel, 1);
        visits++;
    } while (sel.pass != first && visits <= fg_graph_pass_count(graph));
    assert_int_equal(visits, with_params);
    demo_select_pass(graph, &sel, -1);
    demo_select_pass(graph, &sel, 1);
    assert_int_equal(sel.pass, first);

    /* Up from the first parameter wraps to the last. */
    demo_select_param(graph, &sel, -1);
    assert_int_equal(sel.param, params_of(graph, sel.pass) - 1);
    demo_select_param(graph, &sel, 1);
    assert_int_equal(sel.param, 0);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

static void
select_param(const fg_graph *graph, demo_selection *sel, const char *pass, const char *param)
{
    demo_select_first(graph, sel);
    for (int k = 0; k < fg_graph_pass_count(graph); k++) {
        fg_pass *p;
        const fg_param_desc *d;
        assert_true(demo_selected(graph, sel, &p, &d));
        if (!strcmp(fg_pass_name(p), pass))
            for (int i = 0; i < fg_pass_type_of(p)->param_count; i++) {
                if (!strcmp(d->name, param))
                    return;
                demo_select_param(graph, sel, 1);
                assert_true(demo_selected(graph, sel, &p, &d));
            }
        demo_select_pass(graph, sel, 1);
    }
    fail_msg("%s.%s not reached with Tab and Down", pass, param);
}

static const fg_param_desc *
desc_of(const fg_pass *pass, const char *name)
{
    const fg_pass_type *type = fg_pass_type_of(pass);
    for (int i = 0; i < type->param_count; i++)
        if (!strcmp(type->params[i].name, name))
            return &type->params[i];
    fail_msg("%s has no parameter %s", type->name, name);
    return NULL;
}

/* The selected parameter's line: the values as `conegraph passes` lists them, the stepping,
 * the dependencies and whether they hold now. */
static void
test_describe(void **state)
{
    (void)state;
    fg_registry *registry;
    fg_graph *graph = load_graph("vct-aniso.json", &registry);
    cg_error err = { 0 };
    fg_pass *gather = fg_graph_find_pass(graph, "gather"), *vox = fg_graph_find_pass(graph, "vox");
    char line[1024];
    demo_param_describe(gather, desc_of(gather, "cones"), line, sizeof line);
    assert_non_null(strstr(line, "gather.cones = 6 (int 1, 6, 9, 16, 26; a change redoes: prepare): diffuse cones"));
    demo_param_describe(vox, desc_of(vox, "resolution"), line, sizeof line);
    assert_non_null(strstr(line, "vox.resolution = 128 (int 16..512, power of two; a change redoes: graph): "));
    demo_param_describe(gather, desc_of(gather, "step"), line, sizeof line);
    assert_non_null(strstr(line, "; a change redoes: frame): "));
    demo_param_describe(gather, desc_of(gather, "roughness"), line, sizeof line);
    assert_non_null(strstr(line, "gather.roughness = 0.3 (float 0..1, step 0.05; only with specular = true: "
                                 "inactive now; a change redoes: frame): "));
    assert_cg_ok(fg_graph_set_param(graph, "gather", "specular", "true", NULL, &err), &err);
    demo_param_describe(gather, desc_of(gather, "roughness"), line, sizeof line);
    assert_non_null(strstr(line, "(float 0..1, step 0.05; only with specular = true; a change redoes: frame): "));
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

/* Left/Right go through fg_graph_set_param: the graph holds the new value, the old text
 * comes back for undoing, and the ends of the range stop the keys. */
static void
test_adjust(void **state)
{
    (void)state;
    fg_registry *registry;
    fg_graph *graph = load_graph("vct-aniso.json", &registry);
    cg_error err = { 0 };
    demo_selection sel;
    char previous[64];
    bool changed;
    select_param(graph, &sel, "gather", "cones");
    assert_cg_ok(demo_adjust(graph, &sel, 1, &changed, previous, sizeof previous, &err), &err);
    assert_true(changed);
    assert_string_equal(previous, "6");
    assert_int_equal(fg_param_int(fg_graph_find_pass(graph, "gather"), "cones"), 9);
    assert_cg_ok(demo_adjust(graph, &sel, 1, &changed, previous, sizeof previous, &err), &err);
    assert_int_equal(fg_param_int(fg_graph_find_pass(graph, "gather"), "cones"), 16);
    assert_cg_ok(demo_adjust(graph, &sel, 1, &changed, previous, sizeof previous, &err), &err);
    assert_int_equal(fg_param_int(fg_graph_find_pass(graph, "gather"), "cones"), 26);
    assert_cg_ok(demo_adjust(graph, &sel, 1, &changed, previous, sizeof previous, &err), &err);
    assert_false(changed);
    assert_int_equal(fg_param_int(fg_graph_find_pass(graph, "gather"), "cones"), 26);
    for (int i = 0; i < 3; i++)
        assert_cg_ok(demo_adjust(graph, &sel, -1, &changed, previous, sizeof previous, &err), &err);
    assert_int_equal(fg_param_int(fg_graph_find_pass(graph, "gather"), "cones"), 6);

    select_param(graph, &sel, "vox", "resolution");
    assert_cg_ok(demo_adjust(graph, &sel, 1, &changed, previous, sizeof previous, &err), &err);
    assert_string_equal(previous, "128");
    assert_int_equal(fg_param_int(fg_graph_find_pass(graph, "vox"), "resolution"), 256);

    /* A step that breaks a dependency (padding below a quarter of the resolution) is
     * refused by the table, without a compile, and leaves the value as it was. */
    assert_cg_ok(fg_graph_set_param(graph, "vox", "resolution", "16", NULL, &err), &err);
    assert_cg_ok(fg_graph_set_param(graph, "vox", "padding", "3.8", NULL, &err), &err);
    select_param(graph, &sel, "vox", "padding");
    assert_cg_status(demo_adjust(graph, &sel, 1, &changed, previous, sizeof previous, &err), &err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_false(changed);
    assert_non_null(strstr(err.message, "vox.padding = 4; expected less than 0.25 x resolution = 4"));
    assert_float_equal(fg_param_float(fg_graph_find_pass(graph, "vox"), "padding"), 3.8f, 1e-6);
    cg_error_clear(&err);
    assert_cg_ok(demo_adjust(graph, &sel, -1, &changed, previous, sizeof previous, &err), &err);
    assert_true(changed);

    select_param(graph, &sel, "final", "tonemap");
    assert_cg_ok(demo_adjust(graph, &sel, 1, &changed, previous, sizeof previous, &err), &err);
    assert_true(changed);
    assert_string_equal(previous, "aces");
    assert_int_equal(fg_param_enum(fg_graph_find_pass(graph, "final"), "tonemap"), 0);

    select_param(graph, &sel, "gather", "step");
    for (int i = 0; i < 3; i++)
        assert_cg_ok(demo_adjust(graph, &sel, 1, &changed, previous, sizeof previous, &err), &err);
    /* vct-aniso.json's step is 0.5: three steps of 0.05 up. */
    assert_float_equal(fg_param_float(fg_graph_find_pass(graph, "gather"), "step"), 0.65f, 1e-6);
    assert_string_equal(previous, "0.600000024");
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

/* Every parameter of every built-in pass type, stepped both ways from its default and from
 * each end of its range, gives text that the graph's validation accepts. */
static void
test_every_table_steps_validly(void **state)
{
    (void)state;
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_ok(cg_builtin_passes_register(registry, &err), &err);
    fg_graph *graph = fg_graph_create(registry);
    int checked = 0;
    for (int t = 0; t < fg_registry_count(registry); t++) {
        const fg_pass_type *type = fg_registry_at(registry, t);
        char name[64];
        snprintf(name, sizeof name, "p%d", t);
        assert_cg_ok(fg_graph_add_pass(graph, name, type->name, NULL, &err), &err);
        for (int i = 0; i < type->param_count; i++) {
            const fg_param_desc *desc = &type->params[i];
            if (desc->type == FG_PARAM_STRING)
                continue;
            double starts[3] = { desc->default_value, desc->min, desc->max };
            for (int s = 0; s < (desc->type == FG_PARAM_INT || desc->type == FG_PARAM_FLOAT ? 3 : 1); s++)
                for (int dir = -1; dir <= 1; dir += 2) {
                    double next;
                    if (!demo_param_step(desc, starts[s], dir, &next))
                        continue;
                    char value[256];
                    demo_param_format(desc, next, value, sizeof value);
                    cg_error_clear(&err);
                    if (!fg_graph_set_param(graph, name, desc->name, value, NULL, &err))
                        fail_msg("%s.%s: step %+d from %g gave '%s': %s", type->name, desc->name, dir,
                                 starts[s], value, err.message);
                    checked++;
                }
        }
    }
    assert_true(checked > 40);

    /* Walking up from the bottom of the range visits exactly the table's list: the allowed
     * values, or every power of two in the range; and walking down visits it backwards. */
    int walked = 0;
    for (int t = 0; t < fg_registry_count(registry); t++) {
        const fg_pass_type *type = fg_registry_at(registry, t);
        for (int i = 0; i < type->param_count; i++) {
            const fg_param_desc *desc = &type->params[i];
            if (desc->allowed.count == 0 && !desc->power_of_two)
                continue;
            double expected[64] = { 0 };
            int n = 0;
            if (desc->allowed.count > 0)
                for (int k = 0; k < desc->allowed.count && n < 64; k++)
                    expected[n++] = desc->allowed.values[k];
            else
                for (double v = desc->min; v <= desc->max && n < 64; v *= 2)
                    expected[n++] = v;
            double v = expected[0];
            for (int k = 1; k < n; k++) {
                assert_true(demo_param_step(desc, v, 1, &v));
                if (v != expected[k])
                    fail_msg("%s.%s: step up %d gave %g, expected %g", type->name, desc->name, k, v, expected[k]);
            }
            assert_no_step(desc, v, 1);
            for (int k = n - 2; k >= 0; k--) {
                assert_true(demo_param_step(desc, v, -1, &v));
                if (v != expected[k])
                    fail_msg("%s.%s: step down gave %g, expected %g", type->name, desc->name, v, expected[k]);
            }
            assert_no_step(desc, v, -1);
            walked++;
        }
    }
    assert_true(walked >= 4); /* cones of both gathers, voxelize and heightmap_raster resolutions */
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

static void
assert_list(const demo_control *c, const double *values, int count, int current)
{
    assert_int_equal(c->kind, DEMO_CONTROL_LIST);
    assert_int_equal(c->count, count);
    for (int i = 0; i < count; i++)
        if (c->values[i] != values[i])
            fail_msg("entry %d is %g, expected %g", i, c->values[i], values[i]);
    assert_int_equal(c->current, current);
}

/* Each table entry gets the control its constraints ask for: a list of exactly the values
 * Left/Right reach, a slider over a range up to 1000 wide, a drag over a wider one. */
static void
test_controls(void **state)
{
    (void)state;
    demo_control c;
    demo_param_control(&cones, 6, &c);
    assert_list(&c, (const double[]){ 1, 6, 9, 16 }, 4, 1);
    demo_param_control(&resolution, 128, &c);
    assert_list(&c, (const double[]){ 16, 32, 64, 128, 256, 512 }, 6, 3);
    /* Doubling: what Left reaches from the value, the value, what Right reaches (an int
     * halves rounding down, so 100 lists 12 and 200, not 12.5 or 128). */
    demo_param_control(&samples, 100, &c);
    assert_list(&c, (const double[]){ 1, 3, 6, 12, 25, 50, 100, 200, 400, 800, 1600, 3200, 6400, 12800,
                                      25600, 51200, 65536 }, 17, 6);
    demo_param_control(&samples, 64, &c);
    assert_int_equal(c.count, 17);
    assert_true(c.values[0] == 1 && c.values[6] == 64 && c.values[16] == 65536);
    assert_int_equal(c.current, 6);
    for (int i = 0; i + 1 < c.count; i++) {
        double next;
        assert_true(demo_param_step(&samples, c.values[i], 1, &next) && next == c.values[i + 1]);
    }
    /* A value off the list (only code can set one) is no entry. */
    demo_param_control(&cones, 7, &c);
    assert_list(&c, (const double[]){ 1, 6, 9, 16 }, 4, -1);
    demo_param_control(&tonemap, 2, &c);
    assert_list(&c, (const double[]){ 0, 1, 2 }, 3, 2);

    demo_param_control(&count, 7, &c);
    assert_int_equal(c.kind, DEMO_CONTROL_SLIDER);
    assert_true(c.min == 0 && c.max == 256 && c.step == 1);
    demo_param_control(&exposure, 0, &c);
    assert_int_equal(c.kind, DEMO_CONTROL_SLIDER);
    assert_true(c.min == -20 && c.max == 20 && c.step == 0.5);
    demo_param_control(&aperture, 30, &c);
    assert_int_equal(c.kind, DEMO_CONTROL_SLIDER);
    assert_true(c.step == 5);
    demo_param_control(&light, -1, &c);
    assert_int_equal(c.kind, DEMO_CONTROL_DRAG);
    assert_true(c.min == -1 && c.max == 65535 && c.step == 1);
    demo_param_control(&distance, 10, &c);
    assert_int_equal(c.kind, DEMO_CONTROL_DRAG);
    assert_true(c.step == 2);

    demo_param_control(&flag, 1, &c);
    assert_int_equal(c.kind, DEMO_CONTROL_CHECKBOX);
    demo_param_control(&text, 0, &c);
    assert_int_equal(c.kind, DEMO_CONTROL_TEXT);
}

/* Sliders and drags land on the step's grid, within the range. */
static void
test_snap(void **state)
{
    (void)state;
    assert_true(demo_param_snap(&exposure, 0.3) == 0.5);
    assert_true(demo_param_snap(&exposure, 0.2) == 0);
    assert_true(demo_param_snap(&exposure, -0.74) == -0.5);
    assert_true(demo_param_snap(&exposure, 25) == 20);
    assert_true(demo_param_snap(&aperture, 12) == 10);
    assert_true(demo_param_snap(&aperture, 13) == 15);
    assert_true(demo_param_snap(&aperture, 149) == 150);
    assert_true(demo_param_snap(&count, 3.6) == 4);
    assert_true(demo_param_snap(&light, -3) == -1);
    assert_true(fabs(demo_param_snap(&step, 0.07) - 0.05) < 1e-12);
    assert_true(fabs(demo_param_snap(&step, 0.33) - 0.35) < 1e-12);
    assert_true(demo_param_snap(&step, 0.01) == 0.05);
    /* A wide range's grid follows the value's magnitude: 2 at 10, 20 at 100. */
    assert_true(demo_param_snap(&distance, 10.9) == 10);
    assert_true(demo_param_snap(&distance, 109) == 100);
    /* Lists are clamped only: their entries are the control's. */
    assert_true(demo_param_snap(&samples, 100) == 100);
    assert_true(demo_param_snap(&samples, 1e6) == 65536);
}

/* Every built-in parameter's control, built at its default, offers only values the graph's
 * validation accepts: each entry of a list (and the default among them), a slider's or a
 * drag's ends, its middle and its default snapped to the grid. */
static void
test_every_control_valid(void **state)
{
    (void)state;
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_ok(cg_builtin_passes_register(registry, &err), &err);
    fg_graph *graph = fg_graph_create(registry);
    int lists = 0, numbers = 0;
    for (int t = 0; t < fg_registry_count(registry); t++) {
        const fg_pass_type *type = fg_registry_at(registry, t);
        char name[64];
        snprintf(name, sizeof name, "p%d", t);
        assert_cg_ok(fg_graph_add_pass(graph, name, type->name, NULL, &err), &err);
        for (int i = 0; i < type->param_count; i++) {
            const fg_param_desc *desc = &type->params[i];
            demo_control c;
            demo_param_control(desc, desc->default_value, &c);
            double tries[4];
            int n = 0;
            if (c.kind == DEMO_CONTROL_LIST) {
                if (c.current < 0)
                    fail_msg("%s.%s: the default %g is not among its control's entries", type->name, desc->name,
                             desc->default_value);
                for (int k = 0; k < c.count; k++) {
                    char value[256];
                    demo_param_format(desc, c.values[k], value, sizeof value);
                    cg_error_clear(&err);
                    if (!fg_graph_set_param(graph, name, desc->name, value, NULL, &err))
                        fail_msg("%s.%s: entry '%s': %s", type->name, desc->name, value, err.message);
                }
                if (desc->allowed.count > 0)
                    assert_int_equal(c.count, desc->allowed.count);
                lists++;
                continue;
            }
            if (c.kind != DEMO_CONTROL_SLIDER && c.kind != DEMO_CONTROL_DRAG)
                continue;
            assert_true(c.min == desc->min && c.max == desc->max);
            tries[n++] = c.min;
            tries[n++] = c.max;
            tries[n++] = (c.min + c.max) / 2;
            tries[n++] = desc->default_value;
            for (int k = 0; k < n; k++) {
                char value[256];
                demo_param_format(desc, demo_param_snap(desc, tries[k]), value, sizeof value);
                cg_error_clear(&err);
                if (!fg_graph_set_param(graph, name, desc->name, value, NULL, &err))
                    fail_msg("%s.%s: %g snapped to '%s': %s", type->name, desc->name, tries[k], value, err.message);
            }
            numbers++;
        }
    }
    assert_true(lists >= 10);
    assert_true(numbers >= 20);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

/* A control's value takes the keys' path: validated, dependencies checked, undone when one
 * breaks, the old text returned. */
static void
test_param_set(void **state)
{
    (void)state;
    fg_registry *registry;
    fg_graph *graph = load_graph("vct-aniso.json", &registry);
    cg_error err = { 0 };
    char previous[64];
    fg_pass *gather = fg_graph_find_pass(graph, "gather"), *vox = fg_graph_find_pass(graph, "vox");
    assert_cg_ok(demo_param_set(graph, gather, desc_of(gather, "cones"), "9", previous, sizeof previous, &err), &err);
    assert_string_equal(previous, "6");
    assert_int_equal(fg_param_int(gather, "cones"), 9);
    assert_cg_status(demo_param_set(graph, gather, desc_of(gather, "cones"), "7", previous, sizeof previous, &err),
                     &err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_int_equal(fg_param_int(gather, "cones"), 9);
    cg_error_clear(&err);
    assert_cg_ok(fg_graph_set_param(graph, "vox", "resolution", "16", NULL, &err), &err);
    assert_cg_status(demo_param_set(graph, vox, desc_of(vox, "padding"), "4", previous, sizeof previous, &err),
                     &err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_non_null(strstr(err.message, "expected less than 0.25 x resolution"));
    assert_string_equal(previous, "1");
    assert_float_equal(fg_param_float(vox, "padding"), 1.0f, 1e-6);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

/* The fly camera starts where the scene's view is and moves along its own axes. */
static void
test_camera(void **state)
{
    (void)state;
    cg_error err = { 0 };
    cg_scene scene = { 0 };
    assert_cg_ok(cg_scene_load("builtin:cornell", &scene, &err), &err);
    int index;
    assert_cg_ok(cg_camera_select(&scene, NULL, &index, &err), &err);
    cg_view base, flown;
    cg_view_from_scene(&scene, index, 64, 48, &base);
    demo_camera cam;
    demo_camera_from_view(&base, &cam);
    demo_camera_view(&cam, &scene, &base, &flown);
    /* The cornell camera has no roll: the same view, the same projection. */
    for (int k = 0; k < 16; k++) {
        assert_float_equal(flown.view[k], base.view[k], 1e-4);
        assert_float_equal(flown.view_proj[k], base.view_proj[k], 1e-4);
    }
    float f[3];
    demo_camera_forward(&cam, f);
    assert_float_equal(f[0], -base.inv_view[8], 1e-5);
    assert_float_equal(f[2], -base.inv_view[10], 1e-5);
    float p0[3] = { cam.position[0], cam.position[1], cam.position[2] };
    demo_camera_move(&cam, 2, 0, 0);
    for (int k = 0; k < 3; k++)
        assert_float_equal(cam.position[k], p0[k] + 2 * f[k], 1e-5);
    demo_camera_move(&cam, 0, 0, 1);
    assert_float_equal(cam.position[1], p0[1] + 2 * f[1] + 1, 1e-5);
    /* Right is perpendicular to forward and horizontal. */
    float before[3] = { cam.position[0], cam.position[1], cam.position[2] };
    demo_camera_move(&cam, 0, 1, 0);
    float r[3] = { cam.position[0] - before[0], cam.position[1] - before[1], cam.position[2] - before[2] };
    assert_float_equal(r[1], 0, 1e-6);
    assert_float_equal(r[0] * f[0] + r[2] * f[2], 0, 1e-5);
    /* Looking up stops short of straight up. */
    demo_camera_look(&cam, 0.5f, 10.0f);
    assert_true(cam.pitch < 1.5708f && cam.pitch > 1.55f);
    /* Far from the scene, the far plane moves out to keep it in view. */
    cam.position[2] += 1000;
    demo_camera_view(&cam, &scene, &base, &flown);
    assert_true(flown.zfar > 1000);
    for (int k = 0; k < 16; k++)
        assert_true(isfinite(flown.inv_view_proj[k]));
    cg_scene_free(&scene);
}

/* The clock with --fps: frame k at T + k / F as render computes it (the same double), paused
 * it stays, a step pauses and moves by a frame within the keys, past the end it loops. */
static void
test_clock_fixed_step(void **state)
{
    (void)state;
    demo_clock c;
    demo_clock_init(&c, true, 0, 4, 0.1, 3, true);
    assert_true(c.playing);
    assert_true(demo_clock_time(&c) == 0.1);
    for (int k = 1; k <= 5; k++) {
        assert_true(demo_clock_tick(&c, 123.0)); /* the wall time does not matter */
        double want = 0.1 + k / 3.0;
        if (demo_clock_time(&c) != want)
            fail_msg("frame %d at %.17g, render's at %.17g", k, demo_clock_time(&c), want);
    }
    assert_true(demo_clock_toggle(&c));
    assert_false(c.playing);
    double paused = demo_clock_time(&c);
    assert_false(demo_clock_tick(&c, 1.0));
    assert_true(demo_clock_time(&c) == paused);
    assert_true(demo_clock_toggle(&c));
    demo_clock_step(&c, -1);
    assert_false(c.playing);
    assert_true(demo_clock_time(&c) == 0.1 + 4 / 3.0);
    assert_float_equal(demo_clock_frame_seconds(&c), 1 / 3.0, 1e-12);
    demo_clock_step(&c, -100);
    assert_true(demo_clock_time(&c) == 0);
    demo_clock_step(&c, 100);
    assert_true(demo_clock_time(&c) == 4);
    demo_clock_seek(&c, 2.5);
    assert_true(demo_clock_time(&c) == 2.5);
    demo_clock_seek(&c, -1);
    assert_true(demo_clock_time(&c) == 0);
    demo_clock_seek(&c, NAN);
    assert_true(demo_clock_time(&c) == 0);

    /* Looping: 3.5 and 4 are shown, 4.5 is 0.5 again, and the frames go on from there. */
    demo_clock_init(&c, true, 0, 4, 3.5, 2, true);
    assert_true(demo_clock_tick(&c, 0));
    assert_true(demo_clock_time(&c) == 4);
    assert_true(demo_clock_tick(&c, 0));
    assert_float_equal(demo_clock_time(&c), 0.5, 1e-12);
    assert_true(demo_clock_tick(&c, 0));
    assert_float_equal(demo_clock_time(&c), 1.0, 1e-12);
    /* Keys from 1 s: a time before them plays on into them. */
    demo_clock_init(&c, true, 1, 2, 0, 2, true);
    assert_true(demo_clock_tick(&c, 0));
    assert_true(demo_clock_time(&c) == 0.5);
}

/* Without --fps the clock plays the wall time and steps 1/30 s; without animation it never
 * moves, never plays, and Space says it did nothing. */
static void
test_clock_wall_time(void **state)
{
    (void)state;
    demo_clock c;
    demo_clock_init(&c, true, 0, 10, 2, 0, true);
    assert_true(demo_clock_tick(&c, 0.25));
    assert_float_equal(demo_clock_time(&c), 2.25, 1e-12);
    assert_false(demo_clock_tick(&c, 0));
    demo_clock_step(&c, 3);
    assert_false(c.playing);
    assert_float_equal(demo_clock_time(&c), 2.35, 1e-12);
    assert_float_equal(demo_clock_frame_seconds(&c), 1 / DEMO_CLOCK_DEFAULT_FPS, 1e-12);
    demo_clock_init(&c, true, 0, 10, 9.5, 0, false);
    assert_false(c.playing);
    assert_false(demo_clock_tick(&c, 1));
    assert_true(demo_clock_toggle(&c));
    assert_true(demo_clock_tick(&c, 1.0));
    assert_float_equal(demo_clock_time(&c), 0.5, 1e-12);

    demo_clock_init(&c, false, 0, 0, 0, 0, true);
    assert_false(c.playing);
    assert_false(demo_clock_toggle(&c));
    assert_false(demo_clock_tick(&c, 1));
    demo_clock_step(&c, 1);
    demo_clock_seek(&c, 1);
    assert_true(demo_clock_time(&c) == 0);
}

/* The sun's direction, for comparisons. */
static void
sun_direction(const cg_scene *scene, float out[3])
{
    for (int i = 0; i < scene->light_count; i++)
        if (scene->lights[i].type == CG_LIGHT_DIRECTIONAL) {
            memcpy(out, scene->lights[i].direction, sizeof(float) * 3);
            return;
        }
    fail_msg("%s has no directional light", scene->name);
}

/* One frame's pose, as the demo does it: unturn, evaluate, turn. Returns demo_sun_turn's
 * answer (the GPU scene needs the lights). */
static bool
pose(demo_sun *sun, cg_scene *scene, double t, bool *posed)
{
    cg_scene_changes changes;
    demo_sun_unturn(sun, scene);
    cg_scene_evaluate(scene, t, &changes);
    if (posed)
        *posed = changes.lights;
    return demo_sun_turn(sun, scene, changes.lights);
}

static void
assert_same_direction(const float a[3], const float b[3])
{
    for (int k = 0; k < 3; k++)
        if (fabsf(a[k] - b[k]) > 1e-5f)
            fail_msg("direction [%g %g %g], expected [%g %g %g]", (double)a[0], (double)a[1], (double)a[2],
                     (double)b[0], (double)b[1], (double)b[2]);
}

/* builtin:openworld's motion=sun turns the sun about +y once a period: with a period of 18 s,
 * 20 degrees a second, L's rate. So L's turn on the still scene for 1 s is the animation at
 * 1 s, and on the animated scene it adds to the animation's turn. */
static void
test_sun_turn(void **state)
{
    (void)state;
    cg_error err = { 0 };
    cg_scene still = { 0 }, moving = { 0 }, reference = { 0 };
    assert_cg_ok(cg_scene_load("builtin:openworld", &still, &err), &err);
    assert_cg_ok(cg_scene_load("builtin:openworld?motion=sun&period=18", &moving, &err), &err);
    assert_cg_ok(cg_scene_load("builtin:openworld?motion=sun&period=18", &reference, &err), &err);
    float at1[3], at2[3], at1_5[3], got[3];
    cg_scene_evaluate(&reference, 1, NULL);
    sun_direction(&reference, at1);
    cg_scene_evaluate(&reference, 2, NULL);
    sun_direction(&reference, at2);
    cg_scene_evaluate(&reference, 1.5, NULL);
    sun_direction(&reference, at1_5);

    demo_sun sun;
    assert_cg_ok(demo_sun_init(&sun, &still, &err), &err);
    assert_true(sun.any);
    /* Still: nothing changes, nothing to upload. */
    assert_false(pose(&sun, &still, 0, NULL));
    demo_sun_advance(&sun, 1.0);
    assert_true(sun.angle == 0);
    sun.moving = true;
    demo_sun_advance(&sun, 0.5);
    demo_sun_advance(&sun, 0.5);
    assert_float_equal(sun.angle, 20 * M_PI / 180, 1e-12);
    uint64_t before = still.lights_revision;
    assert_true(pose(&sun, &still, 0, NULL));
    sun_direction(&still, got);
    assert_same_direction(got, at1);
    /* The same angle again: the lights as they were, no upload. */
    assert_false(pose(&sun, &still, 0, NULL));
    sun_direction(&still, got);
    assert_same_direction(got, at1);
    /* The demo bumps the stamp when demo_sun_turn says so; evaluate alone does not here. */
    assert_true(still.lights_revision == before);
    demo_sun_reset(&sun);
    assert_false(sun.moving);
    assert_true(pose(&sun, &still, 0, NULL));
    cg_scene_evaluate(&reference, 0, NULL);
    float at0[3];
    sun_direction(&reference, at0);
    sun_direction(&still, got);
    assert_same_direction(got, at0);
    demo_sun_free(&sun);

    /* Animated: the turn goes on top of the pose, and a pose at the same time is no change
     * (the animation sees its own last pose, not the turned one). */
    assert_cg_ok(demo_sun_init(&sun, &moving, &err), &err);
    sun.moving = true;
    demo_sun_advance(&sun, 1.0);
    bool posed;
    assert_true(pose(&sun, &moving, 1, &posed));
    assert_true(posed);
    sun_direction(&moving, got);
    assert_same_direction(got, at2);
    assert_false(pose(&sun, &moving, 1, &posed));
    assert_false(posed);
    sun_direction(&moving, got);
    assert_same_direction(got, at2);
    /* A new time with the same angle: the pose changed the lights, so they go up again. */
    demo_sun_advance(&sun, 0);
    assert_true(pose(&sun, &moving, 0.5, &posed));
    assert_true(posed);
    sun_direction(&moving, got);
    assert_same_direction(got, at1_5);
    /* Back: the animation's own sun; the pose at the same time changed nothing, the reset did. */
    demo_sun_reset(&sun);
    assert_true(pose(&sun, &moving, 0.5, &posed));
    assert_false(posed);
    cg_scene_evaluate(&reference, 0.5, NULL);
    float at0_5[3];
    sun_direction(&reference, at0_5);
    sun_direction(&moving, got);
    assert_same_direction(got, at0_5);
    demo_sun_free(&sun);

    /* No directional light (the Cornell box's spot): nothing to turn, nothing to upload. */
    cg_scene box = { 0 };
    assert_cg_ok(cg_scene_load("builtin:cornell", &box, &err), &err);
    assert_cg_ok(demo_sun_init(&sun, &box, &err), &err);
    assert_false(sun.any);
    sun.moving = true;
    demo_sun_advance(&sun, 1);
    float spot[3];
    memcpy(spot, box.lights[0].direction, sizeof spot);
    assert_false(pose(&sun, &box, 0, NULL));
    assert_same_direction(box.lights[0].direction, spot);
    demo_sun_free(&sun);
    cg_scene_free(&box);
    cg_scene_free(&still);
    cg_scene_free(&moving);
    cg_scene_free(&reference);
}

static int
run_demo(const char *args)
{
    return cg_test_run_program("CONEGRAPH_DEMO_EXE", args, false, NULL, 0);
}

/* Bad input exits 2 before a window is asked for, so these need no display: run them with
 * DISPLAY unset, where anything that got as far as the window would exit 1 instead. */
/* --help lists every option the demo takes: the camera's and the lighting's as render words
 * them, the animation's. */
static void
test_help(void **state)
{
    (void)state;
    static char text[1 << 16];
    assert_int_equal(cg_test_run_program("CONEGRAPH_DEMO_EXE", "--help", false, text, sizeof text), 0);
    const char *options[] = { "--graph FILE", "--size WxH", "--camera NAME|INDEX|auto", "--from X,Y,Z",
                              "--look-at X,Y,Z", "--fov DEG", "--sky none|", "--no-default-light", "--time T",
                              "--fps F", "--play on|off", "--set PASS.PARAM=VALUE", "--plugin PATH",
                              "--frames N", "--ui on|off", "--view PASS.OUTPUT", "--screenshot FILE.png",
                              "--image-screenshot FILE.png", "--timing", "--keys", "Space plays or pauses",
                              "[ and ]", "Shift+L" };
    for (size_t i = 0; i < sizeof options / sizeof options[0]; i++)
        if (!strstr(text, options[i]))
            fail_msg("conegraph-demo --help does not list '%s'", options[i]);
}

static void
test_bad_input(void **state)
{
    (void)state;
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    const char *cases[] = {
        "builtin:nosuchscene",
        "builtin:cornell builtin:furnace",
        "builtin:cornell --size 64",
        "builtin:cornell --size 0x64",
        "builtin:cornell --frames 0",
        "builtin:cornell --frames",
        "builtin:cornell --screenshot shot.jpg",
        "builtin:cornell --timing fast",
        "builtin:cornell --bogus 1",
        "builtin:cornell --graph no_such_graph.json",
        "builtin:cornell --set final.tonemap=filmic",
        "builtin:cornell --set gather.cones=99",
        "builtin:cornell --set nosuchpass.x=1",
        "builtin:cornell --plugin /nonexistent/plugin.so",
        "builtin:cornell --keys tab,bogus",
        "builtin:cornell --keys tab,",
        "builtin:cornell --keys ''",
        "builtin:cornell --keys shift+",
        "builtin:cornell --keys shift+x",
        "builtin:cornell --keys f2",
        "builtin:cornell --ui maybe",
        "builtin:cornell --image-screenshot shot.exr",
        "builtin:cornell --graph vct.json --view gather",
        "builtin:cornell --graph vct.json --view nosuch.output",
        "builtin:cornell --graph vct.json --view shadow.matrix",
        "builtin:cornell --time -1",
        "builtin:cornell --time soon",
        "builtin:cornell --fps 0",
        "builtin:cornell --fps -30",
        "builtin:cornell --play maybe",
        "builtin:cornell --keys 'space,[,],shift+],bogus'",
        "builtin:cornell --camera nosuch",
        "builtin:cornell --camera 3",
        "builtin:cornell --from 1,2",
        "builtin:cornell --look-at 0,0,x",
        "builtin:cornell --fov 180",
        "builtin:cornell --sky purple",
        /* Output paths, checked before the window (core's cg_output_path_check). */
        "builtin:cornell --screenshot /nonexistent-dir/shot.png",
        "builtin:cornell --image-screenshot /nonexistent-dir/shot.png",
        "builtin:cornell --screenshot /proc/version/shot.png",
        "builtin:cornell --screenshot /",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (run_demo(cases[i]) != 2)
            fail_msg("conegraph-demo %s: expected exit 2", cases[i]);
    /* Good input without a display fails while running: 1, not 2. */
    assert_int_equal(run_demo("builtin:cornell --graph direct.json --size 32x32 --frames 1"), 1);
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_step_int),
             cmocka_unit_test(test_step_float),
             cmocka_unit_test(test_step_bool_enum_string),
             cmocka_unit_test(test_format),
             cmocka_unit_test(test_selection),
             cmocka_unit_test(test_describe),
             cmocka_unit_test(test_adjust),
             cmocka_unit_test(test_every_table_steps_validly),
             cmocka_unit_test(test_controls),
             cmocka_unit_test(test_snap),
             cmocka_unit_test(test_every_control_valid),
             cmocka_unit_test(test_param_set),
             cmocka_unit_test(test_camera),
             cmocka_unit_test(test_clock_fixed_step),
             cmocka_unit_test(test_clock_wall_time),
             cmocka_unit_test(test_sun_turn),
             cmocka_unit_test(test_help),
             cmocka_unit_test(test_bad_input))
