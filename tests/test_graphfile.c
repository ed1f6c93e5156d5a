/* Graph files: a good file, --set overrides, the sky a file asks for, and the bad-graph corpus,
 * where every entry must fail with its named status and a message that points at
 * file:line:column. */
#include "test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/fg.h"
#include "cg/graphfile.h"
#include "fg_test_pass.h"

#define SRC "\"src\": { \"type\": \"t\", \"params\": { \"outputs\": \"out:2d:RGBA16F:frame:store\" } }"
#define USE_PARAMS "\"inputs\": \"in:2d:sampled\", \"outputs\": \"out:2d:RGBA16F:frame:attach\""

static const char good_graph[] =
    "{\n"
    "  \"version\": 1,\n"
    "  \"description\": \"two passes\",\n"
    "  \"passes\": {\n"
    "    \"use\": { \"type\": \"t\", \"params\": { " USE_PARAMS ", \"cones\": 6, \"scale\": 0.25,\n"
    "               \"nothing\": false, \"label\": \"caf\\u00e9\" },\n"
    "             \"inputs\": { \"in\": \"src.out\" } },\n"
    "    " SRC "\n"
    "  },\n"
    "  \"outputs\": [ \"use.out\" ]\n"
    "}\n";

typedef fg_test_fixture fixture;

static bool
compile(fixture *f, size_t budget)
{
    fg_frame frame = { 0 };
    frame.width = 64;
    frame.height = 64;
    fg_compile_options options = { false, budget, 16384, 2048 };
    return fg_graph_compile(f->graph, &frame, &options, &f->err);
}

static void
good_graph_loads(void **state)
{
    fixture *f = *state;
    const char *path = cg_test_write_file("good.json", good_graph, 0);
    assert_cg_ok(fg_graph_load_file(f->graph, path, &f->err), &f->err);
    assert_cg_ok(compile(f, 0), &f->err);
    /* Passes keep file order; execution follows the connections. */
    assert_string_equal(fg_pass_name(fg_graph_pass_at(f->graph, 0)), "use");
    const int *order;
    assert_int_equal(fg_graph_order(f->graph, &order), 2);
    assert_int_equal(order[0], 1);
    fg_pass *use = fg_graph_find_pass(f->graph, "use");
    assert_int_equal(fg_param_int(use, "cones"), 6);
    assert_true(fg_param_float(use, "scale") == 0.25f);
    assert_string_equal(fg_param_string(use, "label"), "caf\xc3\xa9");
    assert_int_equal(fg_graph_output_count(f->graph), 1);
    assert_string_equal(fg_graph_output_at(f->graph, 0), "use.out");

    assert_cg_ok(fg_graph_apply_override(f->graph, "use.cones=16", &f->err), &f->err);
    assert_int_equal(fg_param_int(use, "cones"), 16);
    /* A --set value's error quotes the assignment, names the pass once and no file line. */
    assert_cg_status(fg_graph_apply_override(f->graph, "use.cones=7", &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message, "--set use.cones=7: expected one of 1, 6, 9, 16");
    assert_cg_status(fg_graph_apply_override(f->graph, "use.resolution=48", &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message, "--set use.resolution=48: expected a power of two in 1..4096");
    assert_cg_status(fg_graph_apply_override(f->graph, "use.scale=x", &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_TYPE);
    assert_string_equal(f->err.message, "--set use.scale=x: expected a number in 0..1");
    assert_cg_status(fg_graph_apply_override(f->graph, "use.rays=7", &f->err), &f->err,
                     CG_ERR_GRAPH_UNKNOWN_PARAM);
    assert_non_null(strstr(f->err.message, "--set use.rays=7: pass type t has no parameter 'rays' (parameters: "));
    assert_cg_status(fg_graph_apply_override(f->graph, "ghost.rays=7", &f->err), &f->err,
                     CG_ERR_GRAPH_DANGLING);
    assert_non_null(strstr(f->err.message, "--set ghost.rays=7: the graph has no pass named 'ghost' (its passes: "));
    /* A --set value that breaks a dependency is found at compile, and still quoted. */
    assert_cg_ok(fg_graph_apply_override(f->graph, "use.margin=20", &f->err), &f->err);
    assert_cg_status(compile(f, 0), &f->err, CG_ERR_GRAPH_PARAM_RANGE);
    assert_string_equal(f->err.message,
                        "--set use.margin=20: expected less than 0.25 x resolution = 16 (resolution = 64, its default)");
    assert_cg_ok(fg_graph_apply_override(f->graph, "use.resolution=128", &f->err), &f->err);
    assert_cg_ok(compile(f, 0), &f->err);
    assert_cg_status(fg_graph_apply_override(f->graph, "use.cones", &f->err), &f->err, CG_ERR_USAGE);
    assert_cg_status(fg_graph_apply_override(f->graph, "use.resolution=1e9", &f->err), &f->err,
                     CG_ERR_GRAPH_PARAM_RANGE);
    assert_cg_status(fg_graph_load_file(f->graph, "/nonexistent/graph.json", &f->err), &f->err,
                     CG_ERR_FILE_NOT_FOUND);
    /* The file asks for no sky. */
    cg_sky sky;
    assert_false(fg_graph_file_sky(f->graph, &sky));
}

/* "sky": --sky's text, or a number for a grey uniform sky. */
static void
sky_entry(void **state)
{
    fixture *f = *state;
    const struct { const char *value; cg_sky_type type; float first; } cases[] = {
        { "\"0.5,0.6,0.8\"", CG_SKY_UNIFORM, 0.5f },
        { "0.25", CG_SKY_UNIFORM, 0.25f },
        { "\"preetham:4\"", CG_SKY_PREETHAM, 4.0f },
        { "\"none\"", CG_SKY_NONE, 0.0f },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[1024];
        snprintf(text, sizeof text, "{ \"version\": 1, \"sky\": %s, \"passes\": { " SRC " }, \"outputs\": [ \"src.out\" ] }",
                 cases[i].value);
        fg_graph_destroy(f->graph);
        f->graph = fg_graph_create(f->registry);
        assert_cg_ok(fg_graph_load_string(f->graph, text, "sky.json", &f->err), &f->err);
        cg_sky sky;
        assert_true(fg_graph_file_sky(f->graph, &sky));
        assert_int_equal(sky.type, cases[i].type);
        if (sky.type == CG_SKY_UNIFORM)
            assert_true(sky.radiance[0] == cases[i].first);
        if (sky.type == CG_SKY_PREETHAM)
            assert_true(sky.turbidity == cases[i].first);
    }
}

/* ---------------------------------------------------------------- the bad-graph corpus */

typedef struct bad_graph {
    const char *name;
    const char *text;
    cg_status status;
    const char *anchor;     /* the error points at this text (its `nth` occurrence, from 1) */
    int nth;
    size_t budget;
    const char *message;    /* a part of the message that must appear */
} bad_graph;

#define HEAD "{\n  \"version\": 1,\n  \"passes\": {\n    " SRC ",\n    "
#define TAIL "\n  },\n  \"outputs\": [ \"use.out\" ]\n}\n"
#define USE(params, inputs) \
    "\"use\": { \"type\": \"t\", \"params\": { " USE_PARAMS params " }, \"inputs\": { " inputs " } }"
#define USE_OK USE("", "\"in\": \"src.out\"")

static const bad_graph corpus[] = {
    { "syntax", "{\n  \"version\": 1,\n  \"passes\": { \"a\": { \"type\": \"t\" },, }\n}\n",
      CG_ERR_GRAPH_SYNTAX, NULL, 0, 0, "syntax.json:3:" },
    { "version", "{\n  \"version\": 2,\n  \"passes\": {},\n  \"outputs\": [ \"a.b\" ]\n}\n",
      CG_ERR_GRAPH_VERSION, "2", 1, 0, "version 1" },
    { "no_version", "{\n  \"passes\": {},\n  \"outputs\": [ \"a.b\" ]\n}\n",
      CG_ERR_GRAPH_VERSION, "{", 1, 0, "\"version\": 1" },
    { "top_key", "{\n  \"version\": 1,\n  \"pases\": {}\n}\n", CG_ERR_GRAPH_SCHEMA, "\"pases\"", 1, 0,
      "unknown key \"pases\"" },
    { "pass_key", HEAD "\"use\": { \"type\": \"t\", \"param\": {} }" TAIL, CG_ERR_GRAPH_SCHEMA, "\"param\"", 1,
      0, "pass 'use': unknown key \"param\"" },
    { "unknown_type", HEAD "\"use\": { \"type\": \"cone_magic\" }" TAIL, CG_ERR_GRAPH_UNKNOWN_TYPE,
      "\"cone_magic\"", 1, 0, "known types: t, t_side" },
    { "unknown_param", HEAD USE(", \"rays\": 4", "\"in\": \"src.out\"") TAIL, CG_ERR_GRAPH_UNKNOWN_PARAM,
      "\"rays\"", 1, 0, "has no parameter 'rays'" },
    { "param_type", HEAD USE(", \"resolution\": \"high\"", "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_PARAM_TYPE, "\"high\"", 1, 0, "use.resolution: expected a power of two in 1..4096, got a string" },
    { "param_fraction", HEAD USE(", \"resolution\": 2.5", "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_PARAM_TYPE, "2.5", 1, 0, "use.resolution = 2.5; expected a power of two in 1..4096" },
    { "param_bool", HEAD USE(", \"nothing\": 1", "\"in\": \"src.out\"") TAIL, CG_ERR_GRAPH_PARAM_TYPE,
      "1 }", 1, 0, "expected true or false" },
    { "param_range", HEAD USE(", \"cones\": 7", "\"in\": \"src.out\"") TAIL, CG_ERR_GRAPH_PARAM_RANGE,
      "7 }", 1, 0, ": use.cones = 7; expected one of 1, 6, 9, 16" },
    { "param_range_int", HEAD USE(", \"resolution\": 5000", "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_PARAM_RANGE, "5000", 1, 0, "use.resolution = 5000; expected a power of two in 1..4096" },
    { "param_range_float", HEAD USE(", \"scale\": 1.5", "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_PARAM_RANGE, "1.5", 1, 0, "use.scale = 1.5; expected a number in 0..1" },
    { "param_power_of_two", HEAD USE(", \"resolution\": 100", "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_PARAM_RANGE, "100", 1, 0, "use.resolution = 100; expected a power of two in 1..4096" },
    { "param_bool_text", HEAD USE(", \"label\": \"x\", \"nothing\": \"maybe\"", "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_PARAM_TYPE, "\"maybe\"", 1, 0, "use.nothing: expected true or false, got a string" },
    /* Dependencies, checked at compile: at the value written, naming where the other came from. */
    { "param_dependency", HEAD USE(", \"bounded\": true, \"low\": 2,\n              \"high\": 1.5",
                                   "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_PARAM_RANGE, "1.5", 1, 0, "use.high = 1.5; expected greater than low = 2 (set at " },
    { "param_dependency_default", HEAD USE(", \"bounded\": true, \"low\": 3", "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_PARAM_RANGE, "3 }", 1, 0, "use.low = 3; expected less than high = 1 (its default)" },
    { "cycle", HEAD "\"a\": { \"type\": \"t\", \"params\": { " USE_PARAMS " }, \"inputs\": { \"in\": \"use\" } },\n    "
               USE("", "\"in\": \"a\"") TAIL, CG_ERR_GRAPH_CYCLE, "\"a\"", 1, 0, "'a' -> 'use' -> 'a'" },
    { "dangling_pass", HEAD USE("", "\"in\": \"ghost.out\"") TAIL, CG_ERR_GRAPH_DANGLING, "\"ghost.out\"", 1,
      0, "no pass named 'ghost'" },
    { "dangling_output", HEAD USE("", "\"in\": \"src.color\"") TAIL, CG_ERR_GRAPH_DANGLING, "\"src.color\"",
      1, 0, "has no output 'color' (outputs: out)" },
    { "dangling_graph_output", HEAD USE_OK "\n  },\n  \"outputs\": [ \"use.hdr\" ]\n}\n",
      CG_ERR_GRAPH_DANGLING, "\"use.hdr\"", 1, 0, NULL },
    { "duplicate_pass", HEAD USE_OK ",\n    " USE_OK TAIL, CG_ERR_GRAPH_DUPLICATE, "\"use\"", 2, 0,
      "duplicate key \"use\"" },
    { "duplicate_param", HEAD USE(", \"cones\": 6, \"cones\": 9", "\"in\": \"src.out\"") TAIL,
      CG_ERR_GRAPH_DUPLICATE, "\"cones\"", 2, 0, NULL },
    { "no_outputs", HEAD USE_OK "\n  }\n}\n", CG_ERR_GRAPH_NO_OUTPUT, "{", 1, 0, NULL },
    { "empty_outputs", HEAD USE_OK "\n  },\n  \"outputs\": []\n}\n", CG_ERR_GRAPH_NO_OUTPUT, "[]", 1, 0, NULL },
    { "output_not_string", HEAD USE_OK "\n  },\n  \"outputs\": [ 3 ]\n}\n", CG_ERR_GRAPH_SCHEMA, "3 ]", 1, 0,
      NULL },
    { "missing_input", HEAD "\"use\": { \"type\": \"t\", \"params\": { " USE_PARAMS " } }" TAIL,
      CG_ERR_GRAPH_MISSING_INPUT, "\"use\"", 1, 0, "required input 'in' is not connected" },
    { "incompatible", "{\n  \"version\": 1,\n  \"passes\": {\n    \"src\": { \"type\": \"t\", \"params\": "
                      "{ \"outputs\": \"out:3d:RGBA8:16x16x16:store\" } },\n    " USE_OK TAIL,
      CG_ERR_GRAPH_INCOMPATIBLE, "\"src.out\"", 1, 0, "expected a 2d resource" },
    { "too_large", "{\n  \"version\": 1,\n  \"passes\": {\n    \"src\": { \"type\": \"t\", \"params\": "
                   "{ \"outputs\": \"out:2d:RGBA16F:20000x8:store\" } },\n    " USE_OK TAIL,
      CG_ERR_GRAPH_TOO_LARGE, "\"src\"", 1, 0, "16384" },
    { "too_large_3d", "{\n  \"version\": 1,\n  \"passes\": {\n    \"vox\": { \"type\": \"t\", \"params\": "
                      "{ \"outputs\": \"v:3d:RGBA8:4096x4096x4096:store\" } },\n    " SRC ",\n    "
                      "\"use\": { \"type\": \"t\", \"params\": { \"inputs\": \"in:2d:sampled v:3d:sampled\", "
                      "\"outputs\": \"out:2d:RGBA16F:frame:attach\" }, \"inputs\": { \"in\": \"src\", \"v\": \"vox\" } }"
                      TAIL, CG_ERR_GRAPH_TOO_LARGE, "\"vox\"", 1, 0, "2048" },
    { "budget", HEAD USE_OK TAIL, CG_ERR_GRAPH_MEMORY_BUDGET, "\"src\"", 1, 1000, "more than the allowed" },
    { "not_object", "[ 1, 2 ]\n", CG_ERR_GRAPH_SCHEMA, "[", 1, 0, NULL },
    { "sky_not_text", "{\n  \"version\": 1,\n  \"sky\": [ 1, 2, 3 ],\n  \"passes\": {\n    " SRC ",\n    " USE_OK TAIL,
      CG_ERR_GRAPH_SCHEMA, "[ 1, 2, 3 ]", 1, 0, "\"sky\": expected a string" },
    { "sky_bad_value", "{\n  \"version\": 1,\n  \"sky\": \"preetham:20\",\n  \"passes\": {\n    " SRC ",\n    " USE_OK
      TAIL, CG_ERR_GRAPH_SCHEMA, "\"preetham:20\"", 1, 0, "turbidity 1.7 to 10" },
    { "sky_negative", "{\n  \"version\": 1,\n  \"sky\": -1,\n  \"passes\": {\n    " SRC ",\n    " USE_OK TAIL,
      CG_ERR_GRAPH_SCHEMA, "-1", 1, 0, ">= 0" },
    { "inputs_not_string", HEAD USE("", "\"in\": 5") TAIL, CG_ERR_GRAPH_SCHEMA, "5 }", 1, 0, NULL },
    { "bad_source", HEAD USE("", "\"in\": \"src.out@next\"") TAIL, CG_ERR_GRAPH_SCHEMA, "\"src.out@next\"", 1,
      0, "@previous" },
};

/* "name.json:LINE:COLUMN" of the nth occurrence of anchor in text. */
static void
location_of(const char *name, const char *text, const char *anchor, int nth, char *out, size_t size)
{
    const char *at = text;
    for (int i = 0; i < nth; i++) {
        at = strstr(i ? at + 1 : at, anchor);
        assert_non_null(at);
    }
    int line = 1, column = 1;
    for (const char *c = text; c < at; c++) {
        if (*c == '\n') {
            line++;
            column = 1;
        } else {
            column++;
        }
    }
    snprintf(out, size, "%s.json:%d:%d: ", name, line, column);
}

static void
bad_graph_corpus(void **state)
{
    fixture *f = *state;
    for (size_t i = 0; i < sizeof corpus / sizeof corpus[0]; i++) {
        const bad_graph *b = &corpus[i];
        fg_graph_destroy(f->graph);
        f->graph = fg_graph_create(f->registry);
        char file[64];
        snprintf(file, sizeof file, "%s.json", b->name);
        const char *path = cg_test_write_file(file, b->text, 0);
        cg_error_clear(&f->err);
        bool ok = fg_graph_load_file(f->graph, path, &f->err) && compile(f, b->budget);
        if (ok)
            fail_msg("%s: loaded and compiled; expected %s", b->name, cg_status_name(b->status));
        if (f->err.status != b->status)
            fail_msg("%s: %s (%s); expected %s", b->name, cg_status_name(f->err.status), f->err.message,
                     cg_status_name(b->status));
        /* The message starts with the path as given, then line and column. */
        char expected[512];
        if (b->anchor) {
            location_of(b->name, b->text, b->anchor, b->nth, expected, sizeof expected);
            if (!strstr(f->err.message, expected))
                fail_msg("%s: message '%s' does not point at %s", b->name, f->err.message, expected);
        }
        if (b->message && !strstr(f->err.message, b->message))
            fail_msg("%s: message '%s' lacks '%s'", b->name, f->err.message, b->message);
        if (strncmp(f->err.message, path, strlen(path)))
            fail_msg("%s: message '%s' does not start with the file", b->name, f->err.message);
    }
}

/* Random edits of a good file (deterministic): whatever they break, loading and compiling
 * either succeeds or fails with a named status and a message located in the file. */
static void
mutated_graphs_fail_with_locations(void **state)
{
    fixture *f = *state;
    static const char alphabet[] = "{}[]\",:.@\\u0123456789abcdefxtrunl \n-+eE";
    unsigned seed = 7;
    char text[sizeof good_graph + 16];
    int compiled = 0;
    for (int i = 0; i < 3000; i++) {
        strcpy(text, good_graph);
        size_t n = strlen(text);
        for (int m = 1 + rand_r(&seed) % 3; m > 0; m--) {
            size_t at = (size_t)rand_r(&seed) % n;
            char c = alphabet[rand_r(&seed) % (sizeof alphabet - 1)];
            switch (rand_r(&seed) % 3) {
            case 0: text[at] = c; break;
            case 1: memmove(text + at, text + at + 1, n - at); n--; break;
            default:
                if (n + 1 < sizeof text) {
                    memmove(text + at + 1, text + at, n - at + 1);
                    text[at] = c;
                    n++;
                }
            }
        }
        fg_graph_destroy(f->graph);
        f->graph = fg_graph_create(f->registry);
        cg_error_clear(&f->err);
        if (fg_graph_load_string(f->graph, text, "m.json", &f->err) && compile(f, 0)) {
            compiled++;
            continue;
        }
        if (f->err.status == CG_OK || strncmp(f->err.message, "m.json:", 7))
            fail_msg("mutant %d: %s: '%s' is not located in m.json:\n%s", i, cg_status_name(f->err.status),
                     f->err.message, text);
    }
    /* Some edits are harmless (inside a description or a label), most are not. */
    assert_true(compiled > 0 && compiled < 3000);
}

CG_TEST_MAIN(NULL, NULL,
             fg_test_unit(good_graph_loads),
             fg_test_unit(bad_graph_corpus),
             fg_test_unit(sky_entry),
             fg_test_unit(mutated_graphs_fail_with_locations))
