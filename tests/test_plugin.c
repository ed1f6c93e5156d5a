/* Pass plugins: the example plugin loads and runs on GL; a plugin built for another ABI,
 * a shared object without the entry point and a missing file are refused with named
 * errors that name the file. Paths come from the command line (tests/meson.build):
 * argv[1] example_plugin, argv[2] the same built for another ABI, argv[3] not a plugin. */
#include "test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cg/fg.h"
#include "cg/gl.h"

static const char *plugin_path, *bad_abi_path, *not_plugin_path;

static void
plugin_registers_its_pass(void **state)
{
    (void)state;
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_ok(fg_registry_load_plugin(registry, plugin_path, &err), &err);
    const fg_pass_type *fill = fg_registry_find(registry, "example_fill");
    assert_non_null(fill);
    assert_int_equal(fill->abi_version, FG_ABI_VERSION);
    assert_int_equal(fill->param_count, 6);
    /* Loading it again would register the name twice. */
    assert_cg_status(fg_registry_load_plugin(registry, plugin_path, &err), &err, CG_ERR_PLUGIN_LOAD);
    assert_non_null(strstr(err.message, plugin_path));
    assert_int_equal(fg_registry_count(registry), 1);
    fg_registry_destroy(registry);
}

static void
wrong_abi_is_refused(void **state)
{
    (void)state;
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_status(fg_registry_load_plugin(registry, bad_abi_path, &err), &err, CG_ERR_PLUGIN_ABI);
    assert_true(strncmp(err.message, bad_abi_path, strlen(bad_abi_path)) == 0);
    assert_non_null(strstr(err.message, "ABI"));
    assert_int_equal(fg_registry_count(registry), 0);
    fg_registry_destroy(registry);
}

static void
not_a_plugin_or_missing(void **state)
{
    (void)state;
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_status(fg_registry_load_plugin(registry, not_plugin_path, &err), &err, CG_ERR_PLUGIN_LOAD);
    assert_non_null(strstr(err.message, not_plugin_path));
    assert_non_null(strstr(err.message, FG_PLUGIN_ENTRY));
    assert_cg_status(fg_registry_load_plugin(registry, "/nonexistent/plugin.so", &err), &err,
                     CG_ERR_PLUGIN_LOAD);
    assert_non_null(strstr(err.message, "/nonexistent/plugin.so"));
    assert_cg_status(fg_registry_load_plugin_dirs(registry, "/nonexistent-dir", &err), &err,
                     CG_ERR_PLUGIN_LOAD);
    assert_int_equal(fg_registry_count(registry), 0);
    fg_registry_destroy(registry);
}

static void
plugin_dirs_load_every_shared_object(void **state)
{
    (void)state;
    cg_error err = { 0 };
    char dir[4200], link[4300];
    snprintf(dir, sizeof dir, "%s/plugins", cg_test_tmpdir());
    mkdir(dir, 0700);
    snprintf(link, sizeof link, "%s/example.so", dir);
    char target[4096];
    assert_non_null(realpath(plugin_path, target));
    assert_int_equal(symlink(target, link), 0);
    cg_test_write_file("plugins/readme.txt", "not loaded: not a .so", 0);
    fg_registry *registry = fg_registry_create();
    char list[8600];
    snprintf(list, sizeof list, "::%s:", dir); /* empty entries are skipped */
    assert_cg_ok(fg_registry_load_plugin_dirs(registry, list, &err), &err);
    assert_non_null(fg_registry_find(registry, "example_fill"));
    assert_cg_ok(fg_registry_load_plugin_dirs(registry, NULL, &err), &err);
    fg_registry_destroy(registry);
}

static void
plugin_pass_runs(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_ok(fg_registry_load_plugin(registry, plugin_path, &err), &err);
    fg_graph *graph = fg_graph_create(registry);
    assert_cg_ok(fg_graph_add_pass(graph, "fill", "example_fill", NULL, &err), &err);
    assert_cg_ok(fg_graph_set_param(graph, "fill", "red", "0.25", NULL, &err), &err);
    assert_cg_ok(fg_graph_set_param(graph, "fill", "green", "2", NULL, &err), &err);
    assert_cg_ok(fg_graph_set_param(graph, "fill", "width", "8", NULL, &err), &err);
    assert_cg_ok(fg_graph_mark_output(graph, "fill.color", NULL, &err), &err);
    fg_frame frame = { 0 };
    frame.width = 16;
    frame.height = 4;
    assert_cg_ok(fg_graph_compile(graph, &frame, NULL, &err), &err);
    assert_cg_ok(fg_graph_prepare(graph, &err), &err);
    assert_cg_ok(fg_graph_execute(graph, &frame, FG_TIMING_SYNC, &err), &err);
    int w, h, d;
    float *texels = cg_test_read_texture(fg_graph_texture(graph, "fill.color"), 0, &w, &h, &d);
    assert_int_equal(w, 8);
    assert_int_equal(h, 4);
    for (int i = 0; i < w * h; i++) {
        assert_float_equal(texels[4 * i + 0], 0.25f, 0);
        assert_float_equal(texels[4 * i + 1], 2.0f, 0);
        assert_float_equal(texels[4 * i + 2], 1.0f, 0);
        assert_float_equal(texels[4 * i + 3], 1.0f, 0);
    }
    free(texels);
    assert_true(fg_pass_milliseconds(fg_graph_find_pass(graph, "fill")) >= 0);
    assert_no_gl_errors(ctx);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
}

int
main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: %s EXAMPLE_PLUGIN BAD_ABI_PLUGIN NOT_A_PLUGIN\n", argv[0]);
        return 2;
    }
    plugin_path = argv[1];
    bad_abi_path = argv[2];
    not_plugin_path = argv[3];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(plugin_registers_its_pass),
        cmocka_unit_test(wrong_abi_is_refused),
        cmocka_unit_test(not_a_plugin_or_missing),
        cmocka_unit_test(plugin_dirs_load_every_shared_object),
        cmocka_unit_test(plugin_pass_runs),
    };
    return cmocka_run_group_tests(tests, cg_test_gl_setup, cg_test_gl_teardown);
}
