/* `conegraph graph` and `conegraph passes` end to end: exit codes, what is printed, that a
 * bad graph writes nothing, plugins by --plugin and $CONEGRAPH_PLUGIN_PATH, and that
 * docs/pass-parameters.md is what `passes --markdown` prints.
 * argv[1]: the example plugin; argv[2]: graphs/direct.json; argv[3]: docs/pass-parameters.md;
 * the executable: $CONEGRAPH_EXE. */
#include "test_support.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static const char *plugin_path, *direct_graph, *parameters_doc;

/* Runs conegraph with `args`; returns the exit code. */
static int
run(const char *args, char *out, size_t size)
{
    return cg_test_run_conegraph(args, true, out, size);
}

static char out[1 << 16];

static void
graph_check_and_report(void **state)
{
    (void)state;
    char args[8192], report[4200];
    snprintf(report, sizeof report, "%s/report.json", cg_test_tmpdir());
    snprintf(args, sizeof args, "graph '%s' builtin:cornell --size 320x180 --report '%s'", direct_graph, report);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_non_null(strstr(out, "4 of 4 passes run"));
    assert_non_null(strstr(out, "final.hdr"));
    assert_non_null(strstr(out, "memory: resources"));
    assert_int_equal(access(report, R_OK), 0);

    snprintf(args, sizeof args, "graph '%s' builtin:cornell --dot", direct_graph);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_true(strncmp(out, "digraph", 7) == 0);

    /* A bare name is looked up in the graph directory, as render --graph does. */
    assert_int_equal(run("graph hybrid.json builtin:cornell --size 64x36", out, sizeof out), 0);
    assert_non_null(strstr(out, "hybrid.json: compiles for builtin:cornell"));

    /* The README's pipe through Graphviz (.ci/deps installs it). */
    if (system("command -v dot >/dev/null 2>&1") != 0) {
        fprintf(stderr, "# skipping the Graphviz pipe: no `dot` on PATH (.ci/deps installs graphviz)\n");
    } else {
        char svg[4200];
        snprintf(svg, sizeof svg, "%s/graph.svg", cg_test_tmpdir());
        snprintf(args, sizeof args, "'%s' graph hybrid.json builtin:cornell --dot | dot -Tsvg > '%s'",
                 getenv("CONEGRAPH_EXE"), svg);
        assert_int_equal(system(args), 0);
        struct stat st;
        assert_int_equal(stat(svg, &st), 0);
        assert_true(st.st_size > 1000);
    }

    assert_int_equal(run("graph --help", out, sizeof out), 0);
    assert_non_null(strstr(out, "--dot"));
    assert_int_equal(run("graph", out, sizeof out), 2);
    assert_int_equal(run("graph x.json --size 0x7", out, sizeof out), 2);
}

static void
bad_graphs_exit_2_and_write_nothing(void **state)
{
    (void)state;
    char args[8192], report[4200];
    snprintf(report, sizeof report, "%s/never.json", cg_test_tmpdir());
    snprintf(args, sizeof args, "graph '%s' builtin:cornell --set shadow.resolution=9 --report '%s'", direct_graph,
             report);
    assert_int_equal(run(args, out, sizeof out), 2);
    assert_non_null(strstr(out, "--set shadow.resolution=9: expected an integer in 16..16384"));
    assert_int_not_equal(access(report, F_OK), 0);

    const char *cycle = cg_test_write_file("cycle.json",
        "{ \"version\": 1,\n  \"passes\": {\n"
        "    \"g\": { \"type\": \"gbuffer\" },\n"
        "    \"d\": { \"type\": \"direct_light\", \"inputs\": { \"position\": \"g\", \"normal\": \"g\", \"albedo\": \"c\" } },\n"
        "    \"c\": { \"type\": \"composite\", \"inputs\": { \"direct\": \"d.radiance\", \"albedo\": \"g\", \"emissive\": \"g\" } } },\n"
        "  \"outputs\": [ \"c.hdr\" ] }\n", 0);
    snprintf(args, sizeof args, "graph '%s' builtin:cornell --report '%s'", cycle, report);
    assert_int_equal(run(args, out, sizeof out), 2);
    assert_non_null(strstr(out, "cycle.json:4:5: graph has a cycle: 'd' -> 'c' -> 'd'"));
    assert_int_not_equal(access(report, F_OK), 0);

    snprintf(args, sizeof args, "graph '%s' builtin:cornell --max-gpu-memory 1M", direct_graph);
    assert_int_equal(run(args, out, sizeof out), 2);
    assert_non_null(strstr(out, "more than the allowed 1.00 MiB"));
    /* One syntax with render: a number needs its unit. */
    snprintf(args, sizeof args, "graph '%s' builtin:cornell --max-gpu-memory 1", direct_graph);
    assert_int_equal(run(args, out, sizeof out), 2);
    assert_non_null(strstr(out, "--max-gpu-memory wants a size with its unit"));
    snprintf(args, sizeof args, "graph '%s' builtin:no_such_scene", direct_graph);
    assert_int_equal(run(args, out, sizeof out), 2);
}

static void
passes_lists_tables_and_plugins(void **state)
{
    (void)state;
    assert_int_equal(run("passes", out, sizeof out), 0);
    /* The passes, and the constraints of the tables: allowed values, powers of two, dependencies. */
    cg_test_expect_all(out, "conegraph passes", (const char *const[]){
        "shadow_map", "composite",
        "  cones            int    default 6        1, 6, 9, 16, 26 ",
        "  resolution       int    default 128      16..512, power of two ",
        "[only with region = explicit; greater than min_x]", NULL });
    assert_int_equal(run("passes --markdown", out, sizeof out), 0);
    cg_test_expect_all(out, "conegraph passes --markdown", (const char *const[]){
        "## `shadow_map`", "| `resolution` | int | `2048` | 16..16384 |",
        "| `cones` | int | `6` | 1, 6, 9, 16, 26 |", "| `resolution` | int | `1024` | 16..8192, power of two |",
        "(*less than 0.25 x resolution*)", NULL });
    assert_int_equal(run("passes --plugin /nonexistent/plugin.so", out, sizeof out), 2);
    assert_non_null(strstr(out, "/nonexistent/plugin.so"));

    char args[8192];
    snprintf(args, sizeof args, "passes --plugin '%s'", plugin_path);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_non_null(strstr(out, "example_fill"));

    /* A graph using the plugin's pass, the plugin found through $CONEGRAPH_PLUGIN_PATH. */
    char dir[4200], link[4300], target[PATH_MAX];
    snprintf(dir, sizeof dir, "%s/plugins", cg_test_tmpdir());
    mkdir(dir, 0700);
    snprintf(link, sizeof link, "%s/example.so", dir);
    assert_non_null(realpath(plugin_path, target));
    assert_int_equal(symlink(target, link), 0);
    const char *graph = cg_test_write_file("fill.json",
        "{ \"version\": 1, \"passes\": { \"fill\": { \"type\": \"example_fill\", \"params\": { \"red\": 0.5 } } },\n"
        "  \"outputs\": [ \"fill.color\" ] }\n", 0);
    snprintf(args, sizeof args, "graph '%s' builtin:cornell", graph);
    assert_int_equal(run(args, out, sizeof out), 2); /* not registered without the plugin */
    assert_non_null(strstr(out, "unknown type 'example_fill'"));
    setenv("CONEGRAPH_PLUGIN_PATH", dir, 1);
    assert_int_equal(run(args, out, sizeof out), 0);
    assert_non_null(strstr(out, "1 of 1 passes run"));
    unsetenv("CONEGRAPH_PLUGIN_PATH");
}

/* The document is generated; this keeps it from going stale when a table changes. */
static void
parameters_doc_is_generated(void **state)
{
    (void)state;
    unsetenv("CONEGRAPH_PLUGIN_PATH");
    assert_int_equal(cg_test_run_conegraph("passes --markdown", false, out, sizeof out), 0);
    assert_true(strlen(out) + 1 < sizeof out);
    FILE *f = fopen(parameters_doc, "rb");
    if (!f)
        fail_msg("cannot open %s", parameters_doc);
    static char doc[sizeof out];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    doc[n] = '\0';
    fclose(f);
    if (strcmp(doc, out)) {
        size_t at = 0;
        int line = 1;
        while (doc[at] && doc[at] == out[at]) {
            line += doc[at] == '\n';
            at++;
        }
        fail_msg("%s differs from `conegraph passes --markdown` from line %d on; regenerate it with\n"
                 "  build/apps/conegraph passes --markdown > docs/pass-parameters.md",
                 parameters_doc, line);
    }
}

int
main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: %s EXAMPLE_PLUGIN DIRECT_GRAPH PARAMETERS_DOC\n", argv[0]);
        return 2;
    }
    plugin_path = argv[1];
    direct_graph = argv[2];
    parameters_doc = argv[3];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(graph_check_and_report),
        cmocka_unit_test(bad_graphs_exit_2_and_write_nothing),
        cmocka_unit_test(passes_lists_tables_and_plugins),
        cmocka_unit_test(parameters_doc_is_generated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
