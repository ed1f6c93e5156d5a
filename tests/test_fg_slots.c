/* Slot handles (cg/fg.h fg_slot): a pass finds its slots once in prepare and binds through them at
 * execute; a name it did not declare fails fg_graph_prepare (or fg_graph_execute, for a by-name
 * lookup there) with the pass and the slot named, while a declared optional input left
 * unconnected is a legitimate absent slot. The passes are defined here; `misspell` chooses where
 * the misspelt name is looked up. */
#include "test_support.h"

#include <stdlib.h>
#include <string.h>

#include "cg/fg.h"
#include "cg/gl.h"

typedef struct slot_state {
    fg_slot in, out, extra, maybe;
    int executed;
} slot_state;

enum { MISSPELL_NONE, MISSPELL_PREPARE, MISSPELL_EXECUTE };

static const fg_param_desc slot_params[] = {
    { .name = "misspell", .type = FG_PARAM_ENUM, .choices = "none|prepare|execute",
      .doc = "where the pass looks up 'outt', a slot it does not declare" },
    { .name = "reads", .type = FG_PARAM_BOOL, .doc = "declare the required input 'in'" },
};

static bool
slot_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    (void)err;
    if (fg_param_bool(pass, "reads"))
        fg_declare_input(decl, "in", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, true);
    fg_declare_input(decl, "extra", FG_TEXTURE_2D, FG_ACCESS_SAMPLED, false);
    fg_resource_desc out = { .kind = FG_TEXTURE_2D, .format = GL_RGBA16F, .width = 8, .height = 4 };
    fg_declare_output(decl, "out", &out, FG_ACCESS_TRANSFER);
    return true;
}

static bool
slot_prepare(fg_pass *pass, void **state, cg_error *err)
{
    slot_state *s = calloc(1, sizeof *s);
    if (!s)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    *state = s;
    s->in = fg_param_bool(pass, "reads") ? fg_pass_slot(pass, "in") : FG_NO_SLOT;
    s->extra = fg_pass_slot(pass, "extra");
    s->maybe = fg_pass_slot_if_declared(pass, "maybe");    /* never declared: no slot, no error */
    s->out = fg_pass_slot(pass, fg_param_enum(pass, "misspell") == MISSPELL_PREPARE ? "outt" : "out");
    return true;
}

static bool
slot_execute(fg_pass *pass, void *state, cg_error *err)
{
    slot_state *s = state;
    const fg_resource_desc *out = fg_slot_resource(pass, s->out);
    if (!out || !fg_slot_present(pass, s->out) || fg_slot_texture(pass, s->out) == 0 ||
        fg_slot_buffer(pass, s->out) != 0 || out->width != 8 || out->height != 4)
        return cg_fail(err, CG_ERR_PASS, "output 'out' not bound through its handle");
    if (fg_slot_present(pass, s->extra) || fg_slot_texture(pass, s->extra) != 0 || fg_slot_resource(pass, s->extra))
        return cg_fail(err, CG_ERR_PASS, "the unconnected optional input 'extra' is not absent");
    if (fg_slot_present(pass, s->maybe) || fg_slot_texture(pass, FG_NO_SLOT) != 0)
        return cg_fail(err, CG_ERR_PASS, "FG_NO_SLOT resolves to something");
    if (fg_param_bool(pass, "reads") && fg_slot_texture(pass, s->in) == 0)
        return cg_fail(err, CG_ERR_PASS, "input 'in' not bound through its handle");
    /* The by-name lookup finds what the handle does. */
    if (fg_texture(pass, "out") != fg_slot_texture(pass, s->out))
        return cg_fail(err, CG_ERR_PASS, "fg_texture and fg_slot_texture disagree");
    if (fg_param_enum(pass, "misspell") == MISSPELL_EXECUTE && fg_texture(pass, "outt") != 0)
        return cg_fail(err, CG_ERR_PASS, "an undeclared name gave a texture");
    const float value[4] = { 0.25f, 0.5f, 0.75f, 1.0f };
    glClearTexImage(fg_slot_texture(pass, s->out), 0, GL_RGBA, GL_FLOAT, value);
    s->executed++;
    return true;
}

static void
slot_destroy(void *state)
{
    free(state);
}

static const fg_pass_type slot_type = {
    .abi_version = FG_ABI_VERSION, .name = "slots",
    .doc = "Test pass: finds its slots by handle, or misspells one.",
    .params = slot_params, .param_count = (int)(sizeof slot_params / sizeof slot_params[0]),
    .declare = slot_declare, .prepare = slot_prepare, .execute = slot_execute, .destroy = slot_destroy,
};

typedef struct graph_fixture {
    fg_registry *registry;
    fg_graph *graph;
    fg_frame frame;
    cg_error err;
} graph_fixture;

/* "first" writes 'out'; "second" reads it as 'in', with `misspell` set as given. */
static void
build(graph_fixture *g, const char *misspell)
{
    memset(g, 0, sizeof *g);
    g->registry = fg_registry_create();
    assert_cg_ok(fg_registry_add(g->registry, &slot_type, &g->err), &g->err);
    g->graph = fg_graph_create(g->registry);
    assert_cg_ok(fg_graph_add_pass(g->graph, "first", "slots", NULL, &g->err), &g->err);
    assert_cg_ok(fg_graph_add_pass(g->graph, "second", "slots", NULL, &g->err), &g->err);
    assert_cg_ok(fg_graph_set_param(g->graph, "second", "reads", "true", NULL, &g->err), &g->err);
    assert_cg_ok(fg_graph_set_param(g->graph, "second", "misspell", misspell, NULL, &g->err), &g->err);
    assert_cg_ok(fg_graph_connect(g->graph, "second", "in", "first.out", NULL, &g->err), &g->err);
    assert_cg_ok(fg_graph_mark_output(g->graph, "second.out", NULL, &g->err), &g->err);
    g->frame = (fg_frame){ .width = 8, .height = 4 };
    assert_cg_ok(fg_graph_compile(g->graph, &g->frame, NULL, &g->err), &g->err);
}

static void
destroy(graph_fixture *g)
{
    fg_graph_destroy(g->graph);
    fg_registry_destroy(g->registry);
}

static void
handles_bind_declared_slots(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    graph_fixture g;
    build(&g, "none");
    assert_cg_ok(fg_graph_prepare(g.graph, &g.err), &g.err);
    for (int frame = 0; frame < 2; frame++)
        assert_cg_ok(fg_graph_execute(g.graph, &g.frame, FG_TIMING_NONE, &g.err), &g.err);
    GLuint out = fg_graph_texture(g.graph, "second.out");
    assert_true(out != 0);
    int w, h, d;
    float *texels = cg_test_read_texture(out, 0, &w, &h, &d);
    assert_int_equal(w * h * d, 32);
    assert_float_equal(texels[1], 0.5f, 1e-6f);
    free(texels);
    assert_no_gl_errors(ctx);
    destroy(&g);
}

static void
misspelt_slot_fails_prepare(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    graph_fixture g;
    build(&g, "prepare");
    assert_cg_status(fg_graph_prepare(g.graph, &g.err), &g.err, CG_ERR_PASS);
    assert_non_null(strstr(g.err.message, "pass 'second' (type slots)"));
    assert_non_null(strstr(g.err.message, "slot 'outt', which it does not declare"));
    assert_non_null(strstr(g.err.message, "its slots: in, extra, out"));
    assert_no_gl_errors(ctx);
    destroy(&g);   /* releases the state prepare made before the check failed */
}

static void
misspelt_name_fails_execute(void **state)
{
    cg_context *ctx = cg_test_gl_context(state);
    graph_fixture g;
    build(&g, "execute");
    assert_cg_ok(fg_graph_prepare(g.graph, &g.err), &g.err);
    assert_cg_status(fg_graph_execute(g.graph, &g.frame, FG_TIMING_NONE, &g.err), &g.err, CG_ERR_PASS);
    assert_non_null(strstr(g.err.message, "pass 'second' (type slots) looks up slot 'outt'"));
    /* The first pass ran; a lookup outside a callback (an application's) leaves nothing behind. */
    assert_int_equal(fg_texture(fg_graph_find_pass(g.graph, "first"), "nothing"), 0);
    assert_cg_ok(fg_graph_set_param(g.graph, "second", "misspell", "none", NULL, &g.err), &g.err);
    assert_cg_ok(fg_graph_compile(g.graph, &g.frame, NULL, &g.err), &g.err);
    assert_cg_ok(fg_graph_prepare(g.graph, &g.err), &g.err);
    assert_cg_ok(fg_graph_execute(g.graph, &g.frame, FG_TIMING_NONE, &g.err), &g.err);
    assert_no_gl_errors(ctx);
    destroy(&g);
}

CG_TEST_MAIN(cg_test_gl_setup, cg_test_gl_teardown,
             cmocka_unit_test(handles_bind_declared_slots),
             cmocka_unit_test(misspelt_slot_fails_prepare),
             cmocka_unit_test(misspelt_name_fails_execute))
