/* Frame-graph prepare and execute on a headless GL context: storage of every kind made
 * from descriptors, passes writing known values, previous-frame resources alternating,
 * timings in both modes, a pass's texture reads read back as its time is, the JSON report,
 * and no GL error anywhere. */
#include "test_support.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/fg.h"
#include "cg/gl.h"
#include "fg_test_pass.h"

static void
add(fg_graph *graph, const char *name, const char *inputs, const char *outputs, const char *value)
{
    cg_error err = { 0 };
    assert_cg_ok(fg_graph_add_pass(graph, name, "t", NULL, &err), &err);
    if (inputs)
        assert_cg_ok(fg_graph_set_param(graph, name, "inputs", inputs, NULL, &err), &err);
    assert_cg_ok(fg_graph_set_param(graph, name, "outputs", outputs, NULL, &err), &err);
    assert_cg_ok(fg_graph_set_param(graph, name, "value", value, NULL, &err), &err);
}

static void
connect(fg_graph *graph, const char *pass, const char *input, const char *source)
{
    cg_error err = { 0 };
    assert_cg_ok(fg_graph_connect(graph, pass, input, source, NULL, &err), &err);
}

static void
check_texture(GLuint texture, GLenum format, int width, int height, int levels, float value, float tolerance)
{
    GLint internal = 0, immutable_levels = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &internal);
    glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_LEVELS, &immutable_levels);
    assert_int_equal(internal, format);
    assert_int_equal(immutable_levels, levels);
    int w, h, d;
    float *texels = cg_test_read_texture(texture, 0, &w, &h, &d);
    assert_int_equal(w, width);
    assert_int_equal(h, height);
    for (int i = 0; i < w * h * d; i++)
        if (texels[4 * i] < value - tolerance || texels[4 * i] > value + tolerance)
            fail_msg("texel %d is %g, expected %g", i, texels[4 * i], value);
    free(texels);
}

static void
graph_runs_and_is_timed(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_ok(fg_test_register(registry, &err), &err);
    fg_graph *graph = fg_graph_create(registry);
    add(graph, "a", NULL, "x:2d:RGBA16F:16x8:store", "0.5");
    add(graph, "vol", NULL, "v:3d:RGBA8:8x8x8:store:gi:mips", "0.25");
    add(graph, "layers", NULL, "l:array:R32F:4x4x3:store", "3");
    add(graph, "buf", NULL, "b:buffer:-:256:storage", "0");
    add(graph, "acc", "cur:2d:sampled history:2d:sampled", "out:2d:RGBA32F:16x8:store", "1");
    add(graph, "final", "in:2d:sampled v:3d:sampled l:array:sampled b:buffer:storage a:2d:sampled",
        "hdr:2d:RGBA32F:frame:attach", "2");
    connect(graph, "acc", "cur", "a");
    connect(graph, "acc", "history", "acc.out@previous");
    connect(graph, "final", "in", "acc");
    connect(graph, "final", "v", "vol");
    connect(graph, "final", "l", "layers");
    connect(graph, "final", "b", "buf");
    connect(graph, "final", "a", "a.x");
    assert_cg_ok(fg_graph_mark_output(graph, "final.hdr", NULL, &err), &err);
    fg_frame frame = { 0 };
    frame.width = 32;
    frame.height = 16;
    /* GL is current: the limits come from GL (llvmpipe: 16384 and 2048). */
    assert_cg_ok(fg_graph_compile(graph, &frame, NULL, &err), &err);
    assert_cg_ok(fg_graph_prepare(graph, &err), &err);
    assert_no_gl_errors(ctx);

    GLuint acc_textures[2];
    for (int f = 0; f < 2; f++) {
        frame.index = (uint64_t)f;
        assert_cg_ok(fg_graph_execute(graph, &frame, FG_TIMING_SYNC, &err), &err);
        acc_textures[f] = fg_graph_texture(graph, "acc.out");
        /* What a pass rebuilt: its words of this frame, cleared before the next execute. */
        assert_string_equal(fg_pass_rebuilt(fg_graph_find_pass(graph, "a")), f == 0 ? "execute 1" : "");
    }
    /* Read as "@previous" after its writer ran: two textures, one per frame parity. */
    assert_int_not_equal(acc_textures[0], acc_textures[1]);
    assert_int_not_equal(acc_textures[0], 0);

    check_texture(fg_graph_texture(graph, "final.hdr"), GL_RGBA32F, 32, 16, 1, 2.0f, 0);
    check_texture(fg_graph_texture(graph, "a.x"), GL_RGBA16F, 16, 8, 1, 0.5f, 0);
    check_texture(fg_graph_texture(graph, "vol.v"), GL_RGBA8, 8, 8, 4, 0.25f, 0.5f / 255);
    check_texture(fg_graph_texture(graph, "layers.l"), GL_R32F, 4, 4, 1, 3.0f, 0);
    check_texture(acc_textures[1], GL_RGBA32F, 16, 8, 1, 1.0f, 0);
    /* fg_graph_texture gives "the GL object" of a resource: for a buffer, the buffer. */
    GLuint buffer = fg_graph_texture(graph, "buf.b");
    assert_true(glIsBuffer(buffer));
    GLint64 buffer_size = 0;
    glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &buffer_size);
    assert_int_equal(buffer_size, 256);
    const fg_resource_info *b = fg_graph_find_resource(graph, "buf.b");
    assert_non_null(b);
    assert_int_equal(b->bytes, 256);

    const int *order;
    int live = fg_graph_order(graph, &order);
    assert_int_equal(live, 6);
    for (int k = 0; k < live; k++)
        assert_true(fg_pass_milliseconds(fg_graph_pass_at(graph, order[k])) >= 0);

    /* Timestamp queries: results arrive a frame late. */
    assert_cg_ok(fg_graph_prepare(graph, &err), &err);
    for (int k = 0; k < live; k++)
        assert_true(fg_pass_milliseconds(fg_graph_pass_at(graph, order[k])) < 0);
    for (int f = 0; f < 3; f++)
        assert_cg_ok(fg_graph_execute(graph, &frame, FG_TIMING_QUERIES, &err), &err);
    for (int k = 0; k < live; k++)
        assert_true(fg_pass_milliseconds(fg_graph_pass_at(graph, order[k])) >= 0);

    char path[4200];
    snprintf(path, sizeof path, "%s/report.json", cg_test_tmpdir());
    assert_cg_ok(fg_graph_write_report_json(graph, path, &err), &err);
    json_error_t jerr;
    json_t *report = json_load_file(path, 0, &jerr);
    assert_non_null(report);
    assert_int_equal(json_array_size(json_object_get(report, "passes")), 6);
    assert_int_equal(json_integer_value(json_object_get(report, "frames")), 3);
    /* Three frames since the second prepare (a new state): the third call's words. */
    json_t *first = json_array_get(json_object_get(report, "passes"), 0);
    assert_string_equal(json_string_value(json_object_get(first, "name")), "a");
    assert_string_equal(json_string_value(json_object_get(first, "rebuilt")), "execute 3");
    json_t *memory = json_object_get(report, "memory");
    fg_memory_report m;
    fg_graph_memory_report(graph, &m);
    assert_int_equal(json_integer_value(json_object_get(memory, "allocated_bytes")), (json_int_t)m.allocated_bytes);
    assert_int_equal(json_integer_value(json_object_get(memory, "gi_bytes")),
                     (json_int_t)fg_graph_find_resource(graph, "vol.v")->bytes);
    json_decref(report);

    /* A frame of another size needs a new compile. */
    frame.width = 64;
    assert_cg_status(fg_graph_execute(graph, &frame, FG_TIMING_NONE, &err), &err, CG_ERR_USAGE);
    assert_no_gl_errors(ctx);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
    assert_no_gl_errors(ctx);
}

/* A pass that reports texture reads (fg_pass_report_reads): its counter holds, after frame k,
 * reads 2^32 + 100 + k (the high word's carry) for 7 items; every third frame it reports none. */
static bool
counting_prepare(fg_pass *pass, void **state, cg_error *err)
{
    (void)pass;
    GLuint *buffer = calloc(1, sizeof *buffer);
    if (!buffer)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    glCreateBuffers(1, buffer);
    glNamedBufferStorage(*buffer, FG_READS_COUNTER, NULL, GL_DYNAMIC_STORAGE_BIT);
    *state = buffer;
    return true;
}

static bool
counting_execute(fg_pass *pass, void *state, cg_error *err)
{
    (void)err;
    GLuint buffer = *(GLuint *)state;
    uint64_t k = fg_pass_frame(pass)->index;
    if (k % 3 == 2)
        return true;
    const GLuint counter[4] = { 100u + (GLuint)k, 1u, 7u, 0u };
    glNamedBufferSubData(buffer, 0, sizeof counter, counter);
    fg_pass_report_reads(pass, buffer, "texel");
    return true;
}

static void
counting_destroy(void *state)
{
    glDeleteBuffers(1, (GLuint *)state);
    free(state);
}

static bool
counting_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)pass;
    (void)err;
    const fg_resource_desc out = { .kind = FG_TEXTURE_2D, .format = GL_R32F, .width = 4, .height = 4, .depth = 1,
                                   .levels = 1 };
    fg_declare_output(decl, "out", &out, FG_ACCESS_IMAGE_STORE);
    return true;
}

static const fg_pass_type counting_type = {
    .abi_version = FG_ABI_VERSION,
    .name = "counting",
    .doc = "Reports known texture reads.",
    .declare = counting_declare,
    .prepare = counting_prepare,
    .execute = counting_execute,
    .destroy = counting_destroy,
};

static void
expect_reads(fg_graph *graph, bool known, double reads)
{
    const fg_pass *pass = fg_graph_find_pass(graph, "count");
    double r = -1.0, items = -1.0;
    const char *item = "";
    assert_int_equal(fg_pass_reads(pass, &r, &items, &item), known);
    if (!known) {
        assert_null(item);
        return;
    }
    assert_true(r == reads);
    assert_true(items == 7.0);
    assert_string_equal(item, "texel");
}

/* The counts of a frame: at once with sync timing and none, a frame late with queries (read with
 * the timestamps), none for a frame the pass did not count; in the report, the JSON report and
 * fg_graph_reads_text. */
static void
reads_are_read_back(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    cg_error err = { 0 };
    fg_registry *registry = fg_registry_create();
    assert_cg_ok(fg_registry_add(registry, &counting_type, &err), &err);
    fg_graph *graph = fg_graph_create(registry);
    assert_cg_ok(fg_graph_add_pass(graph, "count", "counting", NULL, &err), &err);
    assert_cg_ok(fg_graph_mark_output(graph, "count.out", NULL, &err), &err);
    fg_frame frame = { .width = 4, .height = 4 };
    assert_cg_ok(fg_graph_compile(graph, &frame, NULL, &err), &err);
    assert_cg_ok(fg_graph_prepare(graph, &err), &err);
    expect_reads(graph, false, 0);
    const double high = 4294967296.0;
    fg_timing_mode modes[2] = { FG_TIMING_SYNC, FG_TIMING_NONE };
    for (int m = 0; m < 2; m++)
        for (uint64_t k = 0; k < 3; k++) {
            frame.index = k;
            assert_cg_ok(fg_graph_execute(graph, &frame, modes[m], &err), &err);
            expect_reads(graph, k != 2, high + 100.0 + (double)k);
        }
    char text[256];
    frame.index = 1;
    assert_cg_ok(fg_graph_execute(graph, &frame, FG_TIMING_SYNC, &err), &err);
    assert_string_equal(fg_graph_reads_text(graph, text, sizeof text), "count 4295 M, 6.136e+08 a texel");
    char path[4200];
    snprintf(path, sizeof path, "%s/reads.json", cg_test_tmpdir());
    assert_cg_ok(fg_graph_write_report_json(graph, path, &err), &err);
    json_error_t jerr;
    json_t *report = json_load_file(path, 0, &jerr);
    assert_non_null(report);
    json_t *counted = json_object_get(json_array_get(json_object_get(report, "passes"), 0), "texture_reads");
    assert_true(json_real_value(json_object_get(counted, "reads")) == high + 101.0);
    assert_true(json_real_value(json_object_get(counted, "items")) == 7.0);
    assert_string_equal(json_string_value(json_object_get(counted, "item")), "texel");
    json_decref(report);

    /* Queries: frame k's counts arrive with frame k + 1. */
    assert_cg_ok(fg_graph_prepare(graph, &err), &err);
    expect_reads(graph, false, 0);
    for (uint64_t k = 0; k < 4; k++) {
        frame.index = k;
        assert_cg_ok(fg_graph_execute(graph, &frame, FG_TIMING_QUERIES, &err), &err);
        if (k == 0)
            expect_reads(graph, false, 0);
        else
            expect_reads(graph, k - 1 != 2, high + 100.0 + (double)(k - 1));
    }
    assert_no_gl_errors(ctx);
    fg_graph_destroy(graph);
    fg_registry_destroy(registry);
    assert_no_gl_errors(ctx);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(graph_runs_and_is_timed),
             cmocka_unit_test(reads_are_read_back))
