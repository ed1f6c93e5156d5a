/* Frame-graph compile without GL: registry checks, parameters, order, cycles, culling,
 * absent inputs, previous-frame edges, in-place updates, the pool and barrier bits. */
#include "test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/fg.h"
#include "fg_test_pass.h"

typedef fg_test_fixture fixture;

/* Adds a test pass with its slot specs. */
static void
add(fixture *f, const char *name, const char *type, const char *inputs, const char *outputs)
{
    assert_cg_ok(fg_graph_add_pass(f->graph, name, type, NULL, &f->err), &f->err);
    if (inputs)
        assert_cg_ok(fg_graph_set_param(f->graph, name, "inputs", inputs, NULL, &f->err), &f->err);
    if (outputs)
        assert_cg_ok(fg_graph_set_param(f->graph, name, "outputs", outputs, NULL, &f->err), &f->err);
}

static void
connect(fixture *f, const char *pass, const char *input, const char *source)
{
    assert_cg_ok(fg_graph_connect(f->graph, pass, input, source, NULL, &f->err), &f->err);
}

static void
output(fixture *f, const char *source)
{
    assert_cg_ok(fg_graph_mark_output(f->graph, source, NULL, &f->err), &f->err);
}

static bool
compile(fixture *f)
{
    cg_error_clear(&f->err);
    return fg_graph_compile(f->graph, &f->frame, &f->options, &f->err);
}

static const char *
order_names(fixture *f)
{
    static char buf[512];
    const int *order;
    int n = fg_graph_order(f->graph, &order);
    buf[0] = '\0';
    for (int i = 0; i < n; i++) {
        strcat(buf, i ? " " : "");
        strcat(buf, fg_pass_name(fg_graph_pass_at(f->graph, order[i])));
    }
    return buf;
}

#define IMG "RGBA16F:frame"

/* ---------------------------------------------------------------- registry */

static bool noop_declare(fg_pass *p, fg_declare *d, cg_error *e) { (void)p; (void)d; (void)e; return true; }
static bool noop_execute(fg_pass *p, void *s, cg_error *e) { (void)p; (void)s; (void)e; return true; }

/* Tables whose constraints fg_registry_add must refuse, one fault each. */
static const fg_param_desc bad_constraints[][2] = {
    /* default not among the allowed values */
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 2, .max = 16, .allowed = FG_PARAM_VALUES(1, 6),
        .doc = "n" } },
    /* an allowed value outside the range, or not increasing, or fractional for an int */
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 16, .allowed = FG_PARAM_VALUES(1, 32),
        .doc = "n" } },
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 16, .allowed = FG_PARAM_VALUES(6, 1),
        .doc = "n" } },
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 16, .allowed = FG_PARAM_VALUES(1, 1.5),
        .doc = "n" } },
    /* a list without a count */
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 16,
        .allowed = { (const double[]){ 1 }, 0 }, .doc = "n" } },
    /* power of two: bounds, default, type */
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 16, .min = 10, .max = 512, .power_of_two = true,
        .doc = "n" } },
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 24, .min = 16, .max = 512, .power_of_two = true,
        .doc = "n" } },
    { { .name = "n", .type = FG_PARAM_FLOAT, .default_value = 16, .min = 16, .max = 512, .power_of_two = true,
        .doc = "n" } },
    /* step hints: on a bool, negative, wider than the range, with a list, doubling from 0 */
    { { .name = "b", .type = FG_PARAM_BOOL, .step = 1, .doc = "b" } },
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .step = -0.1, .doc = "x" } },
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .step = 2, .doc = "x" } },
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 16, .allowed = FG_PARAM_VALUES(1, 6),
        .step = 5, .doc = "n" } },
    { { .name = "n", .type = FG_PARAM_INT, .max = 16, .step_doubles = true, .doc = "n" } },
    /* active_when: naming nothing, itself, a non-bool bare, a value the other does not take */
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .active_when = "ghost", .doc = "x" } },
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .active_when = "x", .doc = "x" } },
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .active_when = "m", .doc = "x" },
      { .name = "m", .type = FG_PARAM_ENUM, .choices = "a|b", .doc = "m" } },
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .active_when = "m=a|c", .doc = "x" },
      { .name = "m", .type = FG_PARAM_ENUM, .choices = "a|b", .doc = "m" } },
    /* bounds: naming nothing, a non-number, a negative scale, a default that breaks them */
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .less_than = { .param = "ghost" }, .doc = "x" } },
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .less_than = { .param = "m" }, .doc = "x" },
      { .name = "m", .type = FG_PARAM_ENUM, .choices = "a|b", .doc = "m" } },
    { { .name = "x", .type = FG_PARAM_FLOAT, .max = 1, .less_than = { .param = "y", .scale = -1 }, .doc = "x" },
      { .name = "y", .type = FG_PARAM_FLOAT, .default_value = 1, .max = 1, .doc = "y" } },
    { { .name = "x", .type = FG_PARAM_FLOAT, .default_value = 1, .max = 1, .less_than = { .param = "y" },
        .doc = "x" },
      { .name = "y", .type = FG_PARAM_FLOAT, .default_value = 1, .max = 1, .doc = "y" } },
    /* interactive values: out of range, not allowed, not a number */
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 5, .interactive = "9", .doc = "n" } },
    { { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 16, .allowed = FG_PARAM_VALUES(1, 6),
        .interactive = "4", .doc = "n" } },
    { { .name = "b", .type = FG_PARAM_BOOL, .interactive = "yes", .doc = "b" } },
};

/* And tables that use every constraint correctly. */
static const fg_param_desc good_constraints[] = {
    { .name = "n", .type = FG_PARAM_INT, .default_value = 6, .min = 1, .max = 16,
      .allowed = FG_PARAM_VALUES(1, 6, 9, 16), .doc = "n" },
    { .name = "size", .type = FG_PARAM_INT, .default_value = 64, .min = 16, .max = 512, .power_of_two = true,
      .doc = "size" },
    { .name = "spp", .type = FG_PARAM_INT, .default_value = 3, .min = 1, .max = 100, .step_doubles = true,
      .doc = "spp" },
    { .name = "m", .type = FG_PARAM_ENUM, .choices = "a|b|c", .doc = "m" },
    { .name = "x", .type = FG_PARAM_FLOAT, .max = 10, .step = 0.5, .active_when = "m=b|c",
      .less_than = { .param = "size", .scale = 0.25 }, .doc = "x" },
    { .name = "y", .type = FG_PARAM_FLOAT, .default_value = 1, .max = 10, .active_when = "m=b",
      .greater_than = { .param = "x" }, .doc = "y" },
};

static void
registry_checks_descriptors(void **state)
{
    fixture *f = *state;
    static const fg_param_desc out_of_range[] = {
        { .name = "n", .type = FG_PARAM_INT, .default_value = 10, .min = 0, .max = 5, .doc = "n" } };
    static const fg_param_desc bad_enum[] = {
        { .name = "mode", .type = FG_PARAM_ENUM, .default_value = 3, .choices = "a|b|c", .doc = "mode" } };
    static const fg_param_desc fractional[] = {
        { .name = "n", .type = FG_PARAM_INT, .default_value = 1.5, .min = 0, .max = 5, .doc = "n" } };
    static const fg_param_desc no_doc[] = { { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 5 } };
    static const fg_param_desc twice[] = {
        { .name = "n", .type = FG_PARAM_INT, .default_value = 1, .max = 5, .doc = "n" },
        { .name = "n", .type = FG_PARAM_FLOAT, .default_value = 1, .max = 5, .doc = "n" } };
    fg_pass_type good = { FG_ABI_VERSION, "good", "doc", NULL, 0, false, noop_declare, NULL, noop_execute, NULL };
    assert_cg_ok(fg_registry_add(f->registry, &good, &f->err), &f->err);
    assert_cg_status(fg_registry_add(f->registry, &good, &f->err), &f->err, CG_ERR_PLUGIN_LOAD);
    assert_non_null(strstr(f->err.message, "already registered"));

    fg_pass_type t = good;
    t.name = "abi";
    t.abi_version = FG_ABI_VERSION + 1;
    assert_cg_status(fg_registry_add(f->registry, &t, &f->err), &f->err, CG_ERR_PLUGIN_ABI);
    t = good;
    t.name = "no_execute";
    t.execute = NULL;
    assert_cg_status(fg_registry_add(f->registry, &t, &f->err), &f->err, CG_ERR_PLUGIN_LOAD);
    t = good;
    t.name = "bad.name";
    assert_cg_status(fg_registry_add(f->registry, &t, &f->err), &f->err, CG_ERR_PLUGIN_LOAD);
    const fg_param_desc *tables[] = { out_of_range, bad_enum, fractional, no_doc, twice };
    const int counts[] = { 1, 1, 1, 1, 2 };
    for (int i = 0; i < 5; i++) {
        t = good;
        t.name = "table";
        t.params = tables[i];
        t.param_count = counts[i];
        assert_cg_status(fg_registry_add(f->registry, &t, &f->err), &f->err, CG_ERR_PLUGIN_LOAD);
        assert_non_null(strstr(f->err.message, "'table'"));
    }
    for (size_t i = 0; i < sizeof bad_constraints / sizeof bad_constraints[0]; i++) {
        t = good;
        t.name = "constrained";
        t.params = bad_constraints[i];
        t.param_count = bad_constraints[i][1].name ? 2 : 1;
        cg_error_clear(&f->err);
        if (fg_registry_add(f->registry, &t, &f->err))
            fail_msg("bad constraint table %zu was registered", i);
        assert_int_equal(f->err.status, CG_ERR_PLUGIN_LOAD);
        assert_non_null(strstr(f->err.message, "'constrained'"));
    }
    t = good;
    t.name = "constrained";
    t.params = good_constraints;
    t.param_count = (int)(sizeof good_constraints / sizeof good_constraints[0]);
    assert_cg_ok(fg_registry_add(f->registry, &t, &f->err), &f->err);
    assert_int_equal(fg_registry_count(f->registry), 4); /* t, t_side, good, constrained */
    assert_ptr_equal(fg_registry_find(f->registry, "good"), fg_registry_at(f->registry, 2));
    assert_null(fg_registry_find(f->registry, "table"));
}

/* ---------------------------------------------------------------- parameters */

static void
parameters_are_validated(void **state)
{
    fixture *f = *state;
    add(f, "p", "t", NULL, NULL);
    fg_source_loc loc = { "vct.json", 7, 24 };
    /* Allowed values and powers of two are the table's, checked where the value is set; the
     * message says where, names the pass once and says what was expected. */
    assert_cg_status(fg_graph_set_param(f->graph, "p", "cones", "7", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message, "vct.json:7:24: p.cones = 7; expected one of 1, 6, 9, 16");
    assert_cg_status(fg_graph_set_param(f->graph, "p", "resolution", "100", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message, "vct.json:7:24: p.resolution = 100; expected a power of two in 1..4096");
    assert_cg_status(fg_graph_set_param(f->graph, "p", "resolution", "2.5", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_TYPE);
    assert_cg_status(fg_graph_set_param(f->graph, "p", "resolution", "12abc", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_TYPE);
    assert_cg_status(fg_graph_set_param(f->graph, "p", "resolution", "8192", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_cg_status(fg_graph_set_param(f->graph, "p", "resolution", "0", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_cg_status(fg_graph_set_param(f->graph, "p", "scale", "1.01", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message, "vct.json:7:24: p.scale = 1.01; expected a number in 0..1");
    assert_cg_status(fg_graph_set_param(f->graph, "p", "scale", "nan", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_TYPE);
    assert_cg_status(fg_graph_set_param(f->graph, "p", "scale", "1e-400", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_TYPE);
    assert_cg_status(fg_graph_set_param(f->graph, "p", "nothing", "1", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_TYPE);
    assert_string_equal(f->err.message, "vct.json:7:24: p.nothing = 1; expected true or false");
    assert_cg_status(fg_graph_set_param(f->graph, "p", "rays", "1", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_UNKNOWN_PARAM);
    assert_non_null(strstr(f->err.message, "resolution"));
    /* Without a location: the same message without its start. */
    assert_cg_status(fg_graph_set_param(f->graph, "p", "cones", "8", NULL, &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message, "p.cones = 8; expected one of 1, 6, 9, 16");
    /* Inclusive ranges, integral values written as reals, allowed values, powers of two. */
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "resolution", "4096", NULL, &f->err), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "scale", "0", NULL, &f->err), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "cones", "9.0", NULL, &f->err), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "nothing", "true", NULL, &f->err), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "label", "x y", NULL, &f->err), &f->err);
    fg_pass *p = fg_graph_find_pass(f->graph, "p");
    assert_int_equal(fg_param_int(p, "resolution"), 4096);
    assert_int_equal(fg_param_int(p, "cones"), 9);
    assert_true(fg_param_bool(p, "nothing"));
    assert_true(fg_param_float(p, "scale") == 0.0f);
    assert_string_equal(fg_param_string(p, "label"), "x y");
    assert_true(fg_param_float(p, "resolution") == 4096.0f);
}

/* What one value requires of another is checked once, at compile, before declare(); only
 * while the parameter is active; the message starts where a value was written. */
static void
parameter_dependencies_are_checked_at_compile(void **state)
{
    fixture *f = *state;
    add(f, "p", "t", NULL, "out:2d:RGBA16F:frame:store");
    assert_cg_ok(fg_graph_mark_output(f->graph, "p.out", NULL, &f->err), &f->err);
    fg_pass *p = fg_graph_find_pass(f->graph, "p");
    const fg_param_desc *high = NULL, *margin = NULL;
    for (int i = 0; i < fg_pass_type_of(p)->param_count; i++) {
        if (!strcmp(fg_pass_type_of(p)->params[i].name, "high"))
            high = &fg_pass_type_of(p)->params[i];
        if (!strcmp(fg_pass_type_of(p)->params[i].name, "margin"))
            margin = &fg_pass_type_of(p)->params[i];
    }
    assert_non_null(high);
    assert_non_null(margin);

    /* high <= low does not matter while 'bounded' is false. */
    fg_source_loc low_at = { "g.json", 4, 30 }, high_at = { "g.json", 5, 31 }, bounded_at = { "g.json", 6, 20 };
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "low", "5", &low_at, &f->err), &f->err);
    assert_false(fg_param_active(p, high));
    assert_true(fg_param_active(p, margin));
    assert_cg_ok(compile(f), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "bounded", "true", &bounded_at, &f->err), &f->err);
    assert_true(fg_param_active(p, high));
    /* Only low was written: the message starts at low and reads the bound its way round. */
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message, "g.json:4:30: p.low = 5; expected less than high = 1 (its default)");
    assert_cg_status(fg_pass_check_params(p, &f->err), &f->err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "high", "5", &high_at, &f->err), &f->err);
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message,
                        "g.json:5:31: p.high = 5; expected greater than low = 5 (set at g.json:4:30)");
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "high", "5.5", &high_at, &f->err), &f->err);
    assert_cg_ok(compile(f), &f->err);
    assert_cg_ok(fg_pass_check_params(p, &f->err), &f->err);

    /* A scaled bound: margin < 0.25 x resolution; a --set value is quoted as it was given. */
    fg_source_loc set_at = { "--set p.margin=16", 0, 0 };
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "margin", "16", &set_at, &f->err), &f->err);
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message,
                        "--set p.margin=16: expected less than 0.25 x resolution = 16 (resolution = 64, its default)");
    fg_source_loc res_at = { "g.json", 9, 22 };
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "resolution", "128", &res_at, &f->err), &f->err);
    assert_cg_ok(compile(f), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "resolution", "32", &res_at, &f->err), &f->err);
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message, "--set p.margin=16: expected less than 0.25 x resolution = 8 "
                                        "(resolution = 32, set at g.json:9:22)");
}

/* The table's constraints as text: what `conegraph passes`, the docs and the demo print. */
static void
parameter_constraints_as_text(void **state)
{
    fixture *f = *state;
    const fg_pass_type *t = fg_registry_find(f->registry, "t");
    static const struct { const char *name, *values, *depends; } expected[] = {
        { "cones", "1, 6, 9, 16", "" },
        { "resolution", "1..4096, power of two", "" },
        { "scale", "0..1", "" },
        { "nothing", "true|false", "" },
        { "label", "any text", "" },
        { "high", "-100..100", "only with bounded = true; greater than low" },
        { "margin", "0..100", "less than 0.25 x resolution" },
        { "value", "-1e+06..1e+06", "0.25 in interactive applications unless set" },
        { "low", "-100..100", "only with bounded = true; -1 in interactive applications unless set" },
    };
    for (size_t i = 0; i < sizeof expected / sizeof expected[0]; i++) {
        const fg_param_desc *p = NULL;
        for (int k = 0; k < t->param_count; k++)
            if (!strcmp(t->params[k].name, expected[i].name))
                p = &t->params[k];
        assert_non_null(p);
        char values[256], depends[256];
        fg_param_values_text(p, values, sizeof values);
        fg_param_dependency_text(p, depends, sizeof depends);
        assert_string_equal(values, expected[i].values);
        assert_string_equal(depends, expected[i].depends);
    }
}

/* An interactive application's values (fg_graph_apply_interactive): set only where neither the
 * file nor an override set the parameter and where it matters; listed; the others untouched. */
static void
interactive_values_fill_what_is_unset(void **state)
{
    fixture *f = *state;
    add(f, "a", "t", NULL, NULL);
    add(f, "b", "t", NULL, NULL);
    fg_source_loc file_at = { "g.json", 3, 12 }, set_at = { "--set b.bounded=true", 0, 0 };
    assert_cg_ok(fg_graph_set_param(f->graph, "a", "value", "7", &file_at, &f->err), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "b", "bounded", "true", &set_at, &f->err), &f->err);
    char applied[256];
    assert_cg_ok(fg_graph_apply_interactive(f->graph, applied, sizeof applied, &f->err), &f->err);
    /* a.value was set; a.low does not matter while a.bounded is false. */
    assert_string_equal(applied, "b.value=0.25, b.low=-1");
    fg_pass *a = fg_graph_find_pass(f->graph, "a"), *b = fg_graph_find_pass(f->graph, "b");
    assert_true(fg_param_float(a, "value") == 7.0f);
    assert_true(fg_param_float(a, "low") == 0.0f);
    assert_true(fg_param_float(b, "value") == 0.25f);
    assert_true(fg_param_float(b, "low") == -1.0f);
    /* Applied values count as set: a second call changes nothing; a small buffer truncates. */
    assert_cg_ok(fg_graph_apply_interactive(f->graph, applied, sizeof applied, &f->err), &f->err);
    assert_string_equal(applied, "");
    add(f, "c", "t", NULL, NULL);
    char small[8];
    assert_cg_ok(fg_graph_apply_interactive(f->graph, small, sizeof small, &f->err), &f->err);
    assert_string_equal(small, "c.value");
    assert_true(fg_param_float(fg_graph_find_pass(f->graph, "c"), "value") == 0.25f);
}

static void
building_errors_are_named(void **state)
{
    fixture *f = *state;
    add(f, "a", "t", NULL, "out:2d:" IMG ":attach");
    fg_source_loc loc = { "g.json", 3, 5 };
    assert_cg_status(fg_graph_add_pass(f->graph, "a", "t", &loc, &f->err), &f->err, CG_ERR_GRAPH_DUPLICATE);
    assert_cg_status(fg_graph_add_pass(f->graph, "b", "nope", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_UNKNOWN_TYPE);
    assert_non_null(strstr(f->err.message, "g.json:3:5:"));
    assert_non_null(strstr(f->err.message, "known types: t, t_side"));
    assert_cg_status(fg_graph_connect(f->graph, "zz", "x", "a.out", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_DANGLING);
    assert_cg_status(fg_graph_connect(f->graph, "a", "x", "b.out@later", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_SCHEMA);
    assert_cg_status(fg_graph_mark_output(f->graph, "a", &loc, &f->err), &f->err, CG_ERR_GRAPH_SCHEMA);
    /* No output marked. */
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_NO_OUTPUT);
    output(f, "a.out");
    assert_cg_status(fg_graph_mark_output(f->graph, "a.out", &loc, &f->err), &f->err,
                     CG_ERR_GRAPH_DUPLICATE);
    output(f, "a.nope");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_DANGLING);
    assert_non_null(strstr(f->err.message, "outputs: out"));
}

/* ---------------------------------------------------------------- order and cycles */

static void
order_is_topological_and_stable(void **state)
{
    fixture *f = *state;
    /* File order: c (reads b), a, b (reads a), d (independent), e (reads c and d). */
    add(f, "c", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    add(f, "a", "t", NULL, "out:2d:" IMG ":attach");
    add(f, "b", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    add(f, "d", "t", NULL, "out:2d:" IMG ":attach");
    add(f, "e", "t", "x:2d:sampled y:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "c", "in", "b");
    connect(f, "b", "in", "a.out");
    connect(f, "e", "x", "c");
    connect(f, "e", "y", "d.out");
    output(f, "e.out");
    assert_cg_ok(compile(f), &f->err);
    assert_string_equal(order_names(f), "a b c d e");
    /* Compiling again gives the same order. */
    assert_cg_ok(compile(f), &f->err);
    assert_string_equal(order_names(f), "a b c d e");
}

static void
cycles_are_named(void **state)
{
    fixture *f = *state;
    add(f, "src", "t", NULL, "out:2d:" IMG ":attach");
    add(f, "x", "t", "a:2d:sampled b:2d:sampled", "out:2d:" IMG ":attach");
    add(f, "y", "t", "a:2d:sampled", "out:2d:" IMG ":attach");
    add(f, "z", "t", "a:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "x", "a", "src");
    connect(f, "x", "b", "z");
    connect(f, "y", "a", "x");
    connect(f, "z", "a", "y");
    output(f, "z.out");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_CYCLE);
    assert_non_null(strstr(f->err.message, "'x' -> 'y' -> 'z' -> 'x'"));
}

static void
self_cycle_is_a_cycle(void **state)
{
    fixture *f = *state;
    add(f, "x", "t", "a:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "x", "a", "x.out");
    output(f, "x.out");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_CYCLE);
    assert_non_null(strstr(f->err.message, "'x' -> 'x'"));
}

/* A loop closed by "@previous": accumulation reads its own last-frame value. */
static void
previous_frame_edges_close_loops(void **state)
{
    fixture *f = *state;
    add(f, "src", "t", NULL, "out:2d:" IMG ":store");
    add(f, "acc", "t", "cur:2d:load history:2d:sampled", "out:2d:" IMG ":store");
    add(f, "use", "t", "a:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "acc", "cur", "src");
    connect(f, "acc", "history", "acc.out@previous");
    connect(f, "use", "a", "acc");
    output(f, "use.out");
    assert_cg_ok(compile(f), &f->err);
    assert_string_equal(order_names(f), "src acc use");
    const fg_resource_info *acc = fg_graph_find_resource(f->graph, "acc.out");
    /* Read last frame by its own writer: two storages alternate; never pooled. */
    fg_memory_report m;
    fg_graph_memory_report(f->graph, &m);
    size_t image = (size_t)64 * 32 * 8;
    assert_int_equal(acc->bytes, image);
    assert_int_equal(m.resource_bytes, 4 * image); /* src, acc twice, use */
    for (int i = 0; i < fg_graph_resource_count(f->graph); i++) {
        const fg_resource_info *r = fg_graph_resource_at(f->graph, i);
        if (r != acc)
            assert_int_not_equal(r->storage, acc->storage);
    }
    /* The history input is read after an image store: a texture fetch barrier. */
    assert_true(fg_pass_barrier_bits(fg_graph_find_pass(f->graph, "acc")) & GL_TEXTURE_FETCH_BARRIER_BIT);
}

/* A pass that reads last frame's value of a later pass needs only one storage. */
static void
previous_edge_to_a_later_pass(void **state)
{
    fixture *f = *state;
    add(f, "early", "t", "last:2d:sampled", "out:2d:" IMG ":attach");
    add(f, "late", "t", "a:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "early", "last", "late.out@previous");
    connect(f, "late", "a", "early");
    output(f, "late.out");
    assert_cg_ok(compile(f), &f->err);
    assert_string_equal(order_names(f), "early late");
    fg_memory_report m;
    fg_graph_memory_report(f->graph, &m);
    assert_int_equal(m.allocated_bytes, 2 * (size_t)64 * 32 * 8);
    assert_int_equal(m.resource_bytes, m.allocated_bytes);
}

/* ---------------------------------------------------------------- inputs and culling */

static void
missing_required_input(void **state)
{
    fixture *f = *state;
    fg_source_loc loc = { "g.json", 4, 6 };
    assert_cg_ok(fg_graph_add_pass(f->graph, "p", "t", &loc, &f->err), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "inputs", "gbuffer:2d:sampled", NULL, &f->err), &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "p", "outputs", "out:2d:" IMG ":attach", NULL, &f->err), &f->err);
    output(f, "p.out");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_MISSING_INPUT);
    assert_string_equal(f->err.message, "g.json:4:6: pass 'p' (type t): required input 'gbuffer' is not connected");
}

static void
connection_to_unknown_slot_or_pass(void **state)
{
    fixture *f = *state;
    add(f, "a", "t", NULL, "out:2d:" IMG ":attach second:2d:" IMG ":attach");
    add(f, "b", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    output(f, "b.out");
    fg_source_loc loc = { "g.json", 9, 20 };
    assert_cg_ok(fg_graph_connect(f->graph, "b", "in", "a", &loc, &f->err), &f->err);
    /* "a" has two outputs, neither named "in". */
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_DANGLING);
    assert_non_null(strstr(f->err.message, "g.json:9:20:"));
    fg_graph_destroy(f->graph);
    f->graph = fg_graph_create(f->registry);
    add(f, "a", "t", NULL, "out:2d:" IMG ":attach");
    add(f, "b", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "b", "in", "a");
    connect(f, "b", "extra", "a");
    output(f, "b.out");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_DANGLING);
    assert_non_null(strstr(f->err.message, "has no input 'extra' (inputs: in)"));
    fg_graph_destroy(f->graph);
    f->graph = fg_graph_create(f->registry);
    add(f, "b", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "b", "in", "ghost.out");
    output(f, "b.out");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_DANGLING);
    assert_non_null(strstr(f->err.message, "no pass named 'ghost'"));
}

static void
culling_keeps_what_outputs_and_side_effects_need(void **state)
{
    fixture *f = *state;
    add(f, "a", "t", NULL, "out:2d:" IMG ":attach");
    add(f, "unused", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    add(f, "feeds_side", "t", NULL, "out:2d:" IMG ":attach");
    add(f, "writer", "t_side", "in:2d:sampled", NULL);
    add(f, "feeds_persistent", "t", NULL, "out:2d:" IMG ":attach");
    add(f, "history", "t", "in:2d:sampled", "out:2d:" IMG ":attach:persistent");
    add(f, "final", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "unused", "in", "a");
    connect(f, "writer", "in", "feeds_side");
    connect(f, "history", "in", "feeds_persistent");
    connect(f, "final", "in", "a");
    output(f, "final.out");
    assert_cg_ok(compile(f), &f->err);
    assert_string_equal(order_names(f), "a feeds_side writer feeds_persistent history final");
    fg_pass *unused = fg_graph_find_pass(f->graph, "unused");
    assert_true(fg_pass_is_culled(unused));
    assert_non_null(strstr(fg_pass_cull_reason(unused), "not needed"));
    assert_null(fg_pass_cull_reason(fg_graph_find_pass(f->graph, "a")));
    assert_true(fg_graph_find_resource(f->graph, "unused.out")->absent);
    assert_false(fg_graph_find_resource(f->graph, "history.out")->absent);
}

static void
absent_inputs_adapt_or_cull(void **state)
{
    fixture *f = *state;
    add(f, "terrain", "t", NULL, "lightmap:2d:RGBA16F:256x256:store:gi");
    assert_cg_ok(fg_graph_set_param(f->graph, "terrain", "nothing", "true", NULL, &f->err), &f->err);
    add(f, "hsat", "t", "lightmap:2d:sampled", "table:2d:R32F:256x256:store");
    add(f, "gather", "t", "table:2d:sampled:opt lightmap:2d:sampled:opt", "out:2d:" IMG ":store");
    add(f, "final", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "hsat", "lightmap", "terrain");
    connect(f, "gather", "table", "hsat.table");
    connect(f, "gather", "lightmap", "terrain.lightmap");
    connect(f, "final", "in", "gather");
    output(f, "final.out");
    assert_cg_ok(compile(f), &f->err);
    assert_string_equal(order_names(f), "gather final");
    fg_pass *terrain = fg_graph_find_pass(f->graph, "terrain");
    fg_pass *hsat = fg_graph_find_pass(f->graph, "hsat");
    fg_pass *gather = fg_graph_find_pass(f->graph, "gather");
    assert_true(fg_pass_is_culled(terrain));
    assert_string_equal(fg_pass_cull_reason(terrain), "nothing to do: the test said so");
    assert_true(fg_pass_is_culled(hsat));
    assert_non_null(strstr(fg_pass_cull_reason(hsat), "required input 'lightmap' is absent"));
    assert_false(fg_pass_is_culled(gather));
    assert_false(fg_input_present(gather, "table"));
    assert_false(fg_input_present(gather, "lightmap"));
    assert_true(fg_input_present(fg_graph_find_pass(f->graph, "final"), "in"));
    /* The source an input reads: the shorthand resolved; NULL when absent or not a slot. */
    assert_string_equal(fg_pass_input_source(fg_graph_find_pass(f->graph, "final"), "in"), "gather.out");
    assert_null(fg_pass_input_source(gather, "table"));
    assert_null(fg_pass_input_source(gather, "no_such_slot"));
    assert_true(fg_graph_find_resource(f->graph, "hsat.table")->absent);
    fg_memory_report m;
    fg_graph_memory_report(f->graph, &m);
    assert_int_equal(m.gi_bytes, 0);

    /* When the terrain has work, everything runs and the lightmap counts as GI memory. */
    assert_cg_ok(fg_graph_set_param(f->graph, "terrain", "nothing", "false", NULL, &f->err), &f->err);
    assert_cg_ok(compile(f), &f->err);
    assert_string_equal(order_names(f), "terrain hsat gather final");
    assert_true(fg_input_present(gather, "table"));
    assert_string_equal(fg_pass_input_source(gather, "table"), "hsat.table");
    fg_graph_memory_report(f->graph, &m);
    assert_int_equal(m.gi_bytes, (size_t)256 * 256 * 8);
}

static void
all_outputs_absent_is_an_error(void **state)
{
    fixture *f = *state;
    add(f, "a", "t", NULL, "out:2d:" IMG ":attach");
    assert_cg_ok(fg_graph_set_param(f->graph, "a", "nothing", "true", NULL, &f->err), &f->err);
    output(f, "a.out");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_NO_OUTPUT);
    assert_non_null(strstr(f->err.message, "nothing to do"));
}

/* ---------------------------------------------------------------- validation */

static void
incompatible_kinds_and_formats(void **state)
{
    fixture *f = *state;
    add(f, "vol", "t", NULL, "v:3d:RGBA8:32x32x32:store");
    add(f, "use", "t", "v:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "use", "v", "vol");
    output(f, "use.out");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_INCOMPATIBLE);
    assert_non_null(strstr(f->err.message, "expected a 2d resource, but 'vol.v' is a 3d RGBA8 32x32x32"));

    /* imageLoad of a depth texture. */
    assert_cg_ok(fg_graph_set_param(f->graph, "vol", "outputs", "v:2d:DEPTH32F:64x64:attach", NULL, &f->err),
                 &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "use", "inputs", "v:2d:load", NULL, &f->err), &f->err);
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_INCOMPATIBLE);
    assert_non_null(strstr(f->err.message, "image unit"));
    /* imageStore into sRGB. */
    assert_cg_ok(fg_graph_set_param(f->graph, "vol", "outputs", "v:2d:SRGB8_ALPHA8:64x64:store", NULL, &f->err),
                 &f->err);
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_INCOMPATIBLE);
    /* A texture read as an SSBO. */
    assert_cg_ok(fg_graph_set_param(f->graph, "vol", "outputs", "v:2d:RGBA8:64x64:attach", NULL, &f->err),
                 &f->err);
    assert_cg_ok(fg_graph_set_param(f->graph, "use", "inputs", "v:2d:storage", NULL, &f->err), &f->err);
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_INCOMPATIBLE);
    assert_cg_ok(fg_graph_set_param(f->graph, "use", "inputs", "v:2d:sampled+load", NULL, &f->err), &f->err);
    assert_cg_ok(compile(f), &f->err);
}

static void
limits_and_budget(void **state)
{
    fixture *f = *state;
    add(f, "vol", "t", NULL, "v:3d:RGBA8:256x256x256:store:gi");
    add(f, "img", "t", "v:3d:sampled", "out:2d:RGBA16F:4096x4096:attach");
    connect(f, "img", "v", "vol");
    output(f, "img.out");
    f->options.max_texture_size_3d = 128;
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_TOO_LARGE);
    assert_non_null(strstr(f->err.message, "pass 'vol' output 'v'"));
    f->options.max_texture_size_3d = 256;
    f->options.max_texture_size_2d = 2048;
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_TOO_LARGE);
    assert_non_null(strstr(f->err.message, "pass 'img' output 'out'"));
    f->options.max_texture_size_2d = 4096;
    /* 64 MiB + 128 MiB. */
    f->options.max_gpu_memory = (size_t)150 << 20;
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_MEMORY_BUDGET);
    assert_non_null(strstr(f->err.message, "192.00 MiB"));
    f->options.max_gpu_memory = (size_t)192 << 20;
    assert_cg_ok(compile(f), &f->err);
    fg_memory_report m;
    fg_graph_memory_report(f->graph, &m);
    assert_int_equal(m.gi_bytes, (size_t)64 << 20);
}

/* ---------------------------------------------------------------- in-place updates */

static void
in_place_update_shares_storage(void **state)
{
    fixture *f = *state;
    add(f, "vox", "t", NULL, "volume:3d:RGBA16F:32x32x32:store:gi:mips");
    add(f, "mip", "t", "volume:3d:sampled+load", "volume:3d:RGBA16F:32x32x32:store:gi:mips");
    add(f, "gather", "t", "volume:3d:sampled", "out:2d:" IMG ":store");
    connect(f, "mip", "volume", "vox");
    connect(f, "gather", "volume", "mip");
    output(f, "gather.out");
    assert_cg_ok(compile(f), &f->err);
    const fg_resource_info *a = fg_graph_find_resource(f->graph, "vox.volume");
    const fg_resource_info *b = fg_graph_find_resource(f->graph, "mip.volume");
    assert_int_equal(a->storage, b->storage);
    /* A reader of the updated volume reads the update's version. */
    assert_string_equal(fg_pass_input_source(fg_graph_find_pass(f->graph, "gather"), "volume"), "mip.volume");
    assert_string_equal(fg_pass_input_source(fg_graph_find_pass(f->graph, "mip"), "volume"), "vox.volume");
    fg_memory_report m;
    fg_graph_memory_report(f->graph, &m);
    assert_int_equal(m.gi_bytes, a->bytes);
    assert_int_equal(m.allocated_bytes, a->bytes + (size_t)64 * 32 * 8);
    /* A second reader of the version being updated would see it change under it. */
    add(f, "peek", "t", "v:3d:sampled", "out:2d:" IMG ":store");
    connect(f, "peek", "v", "vox");
    output(f, "peek.out");
    assert_cg_status(compile(f), &f->err, CG_ERR_GRAPH_INCOMPATIBLE);
    assert_non_null(strstr(f->err.message, "in place"));
}

/* ---------------------------------------------------------------- pool */

static void
pool_reuses_identical_descriptors(void **state)
{
    fixture *f = *state;
    /* A chain of five: each output dies once the next pass has read it. */
    const char *names[] = { "p0", "p1", "p2", "p3", "p4" };
    for (int i = 0; i < 5; i++) {
        add(f, names[i], "t", i ? "in:2d:sampled" : NULL, "out:2d:" IMG ":store");
        if (i)
            connect(f, names[i], "in", names[i - 1]);
    }
    output(f, "p4.out");
    assert_cg_ok(compile(f), &f->err);
    fg_memory_report m;
    fg_graph_memory_report(f->graph, &m);
    size_t image = (size_t)64 * 32 * 8;
    assert_int_equal(m.resource_bytes, 5 * image);
    /* p4.out is a graph output (its own storage); p0..p3 alternate between two. */
    assert_int_equal(m.allocated_bytes, 3 * image);
    /* A pass's input and output, and the graph output, which is kept all frame long (it is
     * read after the frame and must survive until the next frame writes it). */
    assert_int_equal(m.peak_bytes, 3 * image);
    f->options.no_pool = true;
    assert_cg_ok(compile(f), &f->err);
    fg_graph_memory_report(f->graph, &m);
    assert_int_equal(m.allocated_bytes, 5 * image);
    assert_int_equal(m.peak_bytes, 3 * image);
}

/* Deterministic xorshift so that failures reproduce. */
static uint32_t
next_random(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static void
pool_never_shares_live_storage(void **state)
{
    fixture *f = *state;
    static const char *const outs[] = { "RGBA16F:16x16", "RGBA16F:32x32", "R32F:16x16" };
    uint32_t seed = 12345;
    int shared = 0;
    for (int trial = 0; trial < 200; trial++) {
        fg_graph_destroy(f->graph);
        f->graph = fg_graph_create(f->registry);
        int n = 3 + (int)(next_random(&seed) % 20);
        for (int p = 0; p < n; p++) {
            char name[16], inputs[256] = "", outputs[64];
            snprintf(name, sizeof name, "p%d", p);
            snprintf(outputs, sizeof outputs, "out:2d:%s:store", outs[next_random(&seed) % 3]);
            int reads = p ? (int)(next_random(&seed) % 3) : 0;
            int src[3];
            for (int r = 0; r < reads; r++) {
                src[r] = (int)(next_random(&seed) % (unsigned)p);
                char slot[32];
                snprintf(slot, sizeof slot, "%si%d:2d:sampled", r ? " " : "", r);
                strcat(inputs, slot);
            }
            add(f, name, next_random(&seed) % 10 == 0 ? "t_side" : "t", reads ? inputs : NULL, outputs);
            for (int r = 0; r < reads; r++) {
                char slot[8], source[16];
                snprintf(slot, sizeof slot, "i%d", r);
                snprintf(source, sizeof source, "p%d.out", src[r]);
                connect(f, name, slot, source);
            }
        }
        char last[16];
        snprintf(last, sizeof last, "p%d.out", n - 1);
        output(f, last);
        assert_cg_ok(compile(f), &f->err);
        int count = fg_graph_resource_count(f->graph);
        for (int i = 0; i < count; i++) {
            const fg_resource_info *a = fg_graph_resource_at(f->graph, i);
            if (a->absent)
                continue;
            assert_true(a->storage >= 0);
            assert_true(a->first_use <= a->last_use);
            for (int j = i + 1; j < count; j++) {
                const fg_resource_info *b = fg_graph_resource_at(f->graph, j);
                if (b->absent || a->storage != b->storage)
                    continue;
                shared++;
                /* One storage, two resources: same descriptor, lifetimes apart. */
                assert_int_equal(a->desc.format, b->desc.format);
                assert_int_equal(a->desc.width, b->desc.width);
                assert_true(a->last_use < b->first_use || b->last_use < a->first_use);
            }
        }
        fg_memory_report m;
        fg_graph_memory_report(f->graph, &m);
        assert_true(m.allocated_bytes <= m.resource_bytes);
        assert_true(m.peak_bytes <= m.allocated_bytes);
    }
    /* The pool did hand storage over in these graphs, so the check above was exercised. */
    assert_true(shared > 100);
}

/* ---------------------------------------------------------------- barriers */

static void
barrier_bits_from_writer_and_reader_access(void **state)
{
    fixture *f = *state;
    static const struct {
        const char *output, *input;
        GLbitfield bits;
    } table[] = {
        { "x:2d:RGBA16F:8x8:store", "x:2d:sampled", GL_TEXTURE_FETCH_BARRIER_BIT },
        { "x:2d:RGBA16F:8x8:store", "x:2d:load", GL_SHADER_IMAGE_ACCESS_BARRIER_BIT },
        { "x:2d:RGBA16F:8x8:store", "x:2d:attach", GL_FRAMEBUFFER_BARRIER_BIT },
        { "x:2d:RGBA16F:8x8:store", "x:2d:transfer", GL_TEXTURE_UPDATE_BARRIER_BIT },
        { "x:2d:RGBA16F:8x8:store", "x:2d:sampled+load", GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT },
        { "x:buffer:-:1024:storage", "x:buffer:storage", GL_SHADER_STORAGE_BARRIER_BIT },
        { "x:buffer:-:1024:storage", "x:buffer:uniform", GL_UNIFORM_BARRIER_BIT },
        { "x:buffer:-:1024:storage", "x:buffer:transfer", GL_BUFFER_UPDATE_BARRIER_BIT },
        { "x:2d:RGBA16F:8x8:attach", "x:2d:sampled", 0 },
        { "x:2d:RGBA16F:8x8:transfer", "x:2d:sampled", 0 },
        { "x:2d:RGBA16F:8x8:attach", "x:2d:load", 0 },
    };
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++) {
        fg_graph_destroy(f->graph);
        f->graph = fg_graph_create(f->registry);
        add(f, "w", "t", NULL, table[i].output);
        add(f, "r", "t", table[i].input, "out:2d:" IMG ":attach");
        connect(f, "r", "x", "w");
        output(f, "r.out");
        assert_cg_ok(compile(f), &f->err);
        if (fg_pass_barrier_bits(fg_graph_find_pass(f->graph, "r")) != table[i].bits)
            fail_msg("row %zu (%s -> %s): bits 0x%x, expected 0x%x", i, table[i].output, table[i].input,
                     fg_pass_barrier_bits(fg_graph_find_pass(f->graph, "r")), table[i].bits);
        assert_int_equal(fg_pass_barrier_bits(fg_graph_find_pass(f->graph, "w")), 0);
    }
}

/* A pooled texture handed from one image-store writer to the next needs a barrier
 * between the two writes (write after write), even with no reader in between. */
static void
pool_handover_orders_writes(void **state)
{
    fixture *f = *state;
    add(f, "a", "t", NULL, "x:2d:RGBA16F:8x8:store");
    add(f, "b", "t", "in:2d:sampled", "y:2d:RGBA16F:8x8:store");
    add(f, "c", "t", "in:2d:sampled", "z:2d:RGBA16F:8x8:store");
    add(f, "d", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "b", "in", "a");
    connect(f, "c", "in", "b");
    connect(f, "d", "in", "c");
    output(f, "d.out");
    assert_cg_ok(compile(f), &f->err);
    assert_int_equal(fg_graph_find_resource(f->graph, "a.x")->storage,
                     fg_graph_find_resource(f->graph, "c.z")->storage);
    assert_true(fg_pass_barrier_bits(fg_graph_find_pass(f->graph, "c")) & GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

static void
resource_bytes_and_levels(void **state)
{
    (void)state;
    fg_resource_desc d = { FG_TEXTURE_3D, GL_RGBA8, 4, 4, 4, 3, 0, false, false };
    assert_int_equal(fg_resource_bytes(&d), (64 + 8 + 1) * 4);
    d.kind = FG_TEXTURE_2D_ARRAY;
    assert_int_equal(fg_resource_bytes(&d), (64 + 16 + 4) * 4);
    fg_resource_desc b = { FG_BUFFER, 0, 0, 0, 0, 0, 1000, false, false };
    assert_int_equal(fg_resource_bytes(&b), 1000);
    assert_int_equal(fg_mip_levels(1, 1, 1), 1);
    assert_int_equal(fg_mip_levels(640, 360, 1), 10);
    assert_int_equal(fg_mip_levels(16, 4, 128), 8);
}

static void
report_and_dot_mention_everything(void **state)
{
    fixture *f = *state;
    add(f, "a", "t", NULL, "out:2d:" IMG ":store");
    add(f, "spare", "t", NULL, "out:2d:" IMG ":store");
    add(f, "b", "t", "in:2d:sampled", "out:2d:" IMG ":attach");
    connect(f, "b", "in", "a");
    output(f, "b.out");
    assert_cg_ok(compile(f), &f->err);
    char *text = NULL;
    size_t size = 0;
    FILE *mem = open_memstream(&text, &size);
    fg_graph_write_dot(f->graph, mem);
    fclose(mem);
    assert_non_null(strstr(text, "digraph"));
    assert_non_null(strstr(text, "style=dashed, color=grey"));
    assert_non_null(strstr(text, "out\\nRGBA16F 64x32\\n16.0 KiB -> in"));
    free(text);
    mem = open_memstream(&text, &size);
    fg_graph_print_report(f->graph, mem);
    fclose(mem);
    assert_non_null(strstr(text, "culled spare"));
    assert_non_null(strstr(text, "a.out"));
    free(text);
}

CG_TEST_MAIN(NULL, NULL,
             fg_test_unit(registry_checks_descriptors),
             fg_test_unit(parameters_are_validated),
             fg_test_unit(parameter_dependencies_are_checked_at_compile),
             fg_test_unit(parameter_constraints_as_text),
             fg_test_unit(building_errors_are_named),
             fg_test_unit(order_is_topological_and_stable),
             fg_test_unit(cycles_are_named),
             fg_test_unit(self_cycle_is_a_cycle),
             fg_test_unit(previous_frame_edges_close_loops),
             fg_test_unit(previous_edge_to_a_later_pass),
             fg_test_unit(missing_required_input),
             fg_test_unit(connection_to_unknown_slot_or_pass),
             fg_test_unit(culling_keeps_what_outputs_and_side_effects_need),
             fg_test_unit(absent_inputs_adapt_or_cull),
             fg_test_unit(all_outputs_absent_is_an_error),
             fg_test_unit(incompatible_kinds_and_formats),
             fg_test_unit(limits_and_budget),
             fg_test_unit(in_place_update_shares_storage),
             fg_test_unit(pool_reuses_identical_descriptors),
             fg_test_unit(pool_never_shares_live_storage),
             fg_test_unit(barrier_bits_from_writer_and_reader_access),
             fg_test_unit(pool_handover_orders_writes),
             cmocka_unit_test(resource_bytes_and_levels),
             fg_test_unit(report_and_dot_mention_everything),
             fg_test_unit(interactive_values_fill_what_is_unset))
