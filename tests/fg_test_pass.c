/* Configurable pass types for frame-graph tests (see fg_test_pass.h). */
#include "fg_test_pass.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const fg_param_desc test_params[] = {
    { .name = "inputs", .type = FG_PARAM_STRING, .choices = "",
      .doc = "input slots: NAME:KIND:ACCESS[:opt] ..." },
    { .name = "outputs", .type = FG_PARAM_STRING, .choices = "",
      .doc = "outputs: NAME:KIND:FORMAT:SIZE:ACCESS[:persistent][:gi][:mips] ..." },
    { .name = "nothing", .type = FG_PARAM_BOOL, .doc = "declare that there is nothing to do" },
    { .name = "value", .type = FG_PARAM_FLOAT, .min = -1e6, .max = 1e6, .interactive = "0.25",
      .doc = "value execute() clears colour outputs to" },
    /* For the validation tests only: */
    { .name = "cones", .type = FG_PARAM_INT, .default_value = 6, .min = 1, .max = 16,
      .allowed = FG_PARAM_VALUES(1, 6, 9, 16), .doc = "number of cones" },
    { .name = "resolution", .type = FG_PARAM_INT, .default_value = 64, .min = 1, .max = 4096,
      .power_of_two = true, .doc = "a resolution" },
    { .name = "scale", .type = FG_PARAM_FLOAT, .default_value = 0.5, .min = 0, .max = 1, .doc = "a fraction" },
    { .name = "label", .type = FG_PARAM_STRING, .choices = "none", .doc = "a label" },
    { .name = "bounded", .type = FG_PARAM_BOOL, .doc = "whether low and high apply" },
    { .name = "low", .type = FG_PARAM_FLOAT, .min = -100, .max = 100, .active_when = "bounded",
      .interactive = "-1", .doc = "lower end" },
    { .name = "high", .type = FG_PARAM_FLOAT, .default_value = 1, .min = -100, .max = 100,
      .active_when = "bounded", .greater_than = { .param = "low" }, .doc = "upper end, above low" },
    { .name = "margin", .type = FG_PARAM_FLOAT, .min = 0, .max = 100,
      .less_than = { .param = "resolution", .scale = 0.25 }, .doc = "below a quarter of the resolution" },
};

static const struct {
    const char *name;
    GLenum format;
} formats[] = {
    { "RGBA16F", GL_RGBA16F }, { "RGBA32F", GL_RGBA32F }, { "R32F", GL_R32F }, { "RGBA8", GL_RGBA8 },
    { "R8", GL_R8 }, { "DEPTH32F", GL_DEPTH_COMPONENT32F }, { "SRGB8_ALPHA8", GL_SRGB8_ALPHA8 },
    { "R32UI", GL_R32UI }, { "-", 0 },
};

static bool
parse_kind(const char *s, fg_resource_kind *kind)
{
    static const char *const names[] = { "2d", "3d", "array", "buffer" };
    for (int i = 0; i < 4; i++)
        if (!strcmp(s, names[i])) {
            *kind = (fg_resource_kind)i;
            return true;
        }
    return false;
}

static bool
parse_access(char *s, unsigned *access)
{
    static const char *const names[] = { "sampled", "load", "store", "attach", "storage", "uniform",
                                         "transfer" };
    *access = 0;
    for (char *save = NULL, *tok = strtok_r(s, "+", &save); tok; tok = strtok_r(NULL, "+", &save)) {
        bool found = false;
        for (unsigned i = 0; i < 7; i++)
            if (!strcmp(tok, names[i])) {
                *access |= 1u << i;
                found = true;
            }
        if (!found)
            return false;
    }
    return true;
}

/* Splits "a:b:c" in place into at most `max` fields. */
static int
split_fields(char *s, char **fields, int max)
{
    int n = 0;
    for (char *save = NULL, *tok = strtok_r(s, ":", &save); tok && n < max; tok = strtok_r(NULL, ":", &save))
        fields[n++] = tok;
    return n;
}

static bool
declare_inputs(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    char *spec = strdup(fg_param_string(pass, "inputs"));
    bool ok = true;
    for (char *save = NULL, *item = strtok_r(spec, " ", &save); item && ok;
         item = strtok_r(NULL, " ", &save)) {
        char *f[4];
        int n = split_fields(item, f, 4);
        fg_resource_kind kind;
        unsigned access;
        if (n < 3 || !parse_kind(f[1], &kind) || !parse_access(f[2], &access)) {
            ok = cg_fail(err, CG_ERR_PASS, "test pass '%s': bad input spec", fg_pass_name(pass));
            break;
        }
        fg_declare_input(decl, f[0], kind, access, !(n == 4 && !strcmp(f[3], "opt")));
    }
    free(spec);
    return ok;
}

static bool
declare_outputs(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    char *spec = strdup(fg_param_string(pass, "outputs"));
    const fg_frame *frame = fg_pass_frame(pass);
    bool ok = true;
    for (char *save = NULL, *item = strtok_r(spec, " ", &save); item && ok;
         item = strtok_r(NULL, " ", &save)) {
        char *f[8];
        int n = split_fields(item, f, 8);
        fg_resource_desc desc = { 0 };
        unsigned access;
        int format = -1;
        for (int i = 0; n >= 5 && i < (int)(sizeof formats / sizeof formats[0]); i++)
            if (!strcmp(formats[i].name, f[2]))
                format = i;
        if (n < 5 || !parse_kind(f[1], &desc.kind) || format < 0 || !parse_access(f[4], &access)) {
            ok = cg_fail(err, CG_ERR_PASS, "test pass '%s': bad output spec", fg_pass_name(pass));
            break;
        }
        desc.format = formats[format].format;
        desc.depth = 1;
        desc.levels = 1;
        if (desc.kind == FG_BUFFER) {
            desc.buffer_bytes = (size_t)strtoull(f[3], NULL, 10);
        } else if (!strcmp(f[3], "frame")) {
            desc.width = frame->width;
            desc.height = frame->height;
        } else if (sscanf(f[3], "%dx%dx%d", &desc.width, &desc.height, &desc.depth) < 2) {
            ok = cg_fail(err, CG_ERR_PASS, "test pass '%s': bad size '%s'", fg_pass_name(pass), f[3]);
            break;
        }
        for (int i = 5; i < n; i++) {
            if (!strcmp(f[i], "persistent"))
                desc.persistent = true;
            else if (!strcmp(f[i], "gi"))
                desc.gi = true;
            else if (!strcmp(f[i], "mips"))
                desc.levels = fg_mip_levels(desc.width, desc.height,
                                            desc.kind == FG_TEXTURE_3D ? desc.depth : 1);
        }
        fg_declare_output(decl, f[0], &desc, access);
    }
    free(spec);
    return ok;
}

static bool
test_declare(fg_pass *pass, fg_declare *decl, cg_error *err)
{
    if (!declare_inputs(pass, decl, err))
        return false;
    if (fg_param_bool(pass, "nothing")) {
        fg_declare_nothing_to_do(decl, "the test said so");
        return true;
    }
    return declare_outputs(pass, decl, err);
}

static bool
test_prepare(fg_pass *pass, void **state, cg_error *err)
{
    (void)pass;
    *state = calloc(1, sizeof(int));
    return *state ? true : cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
}

static bool
test_execute(fg_pass *pass, void *state, cg_error *err)
{
    (void)err;
    int calls = ++*(int *)state;
    /* Odd calls say what they "rebuilt"; even calls say nothing, which must read "". */
    if (calls % 2)
        fg_pass_report_rebuilt(pass, "execute %d", calls);
    char *spec = strdup(fg_param_string(pass, "outputs"));
    float v = fg_param_float(pass, "value");
    const float rgba[4] = { v, v, v, v };
    for (char *save = NULL, *item = strtok_r(spec, " ", &save); item; item = strtok_r(NULL, " ", &save)) {
        char *f[2];
        if (split_fields(item, f, 2) < 1)
            continue;
        const fg_resource_desc *d = fg_resource(pass, f[0]);
        GLuint tex = fg_texture(pass, f[0]);
        if (!d || !tex || d->format == GL_DEPTH_COMPONENT32F || d->format == GL_R32UI)
            continue;
        for (int level = 0; level < d->levels; level++)
            glClearTexImage(tex, level, GL_RGBA, GL_FLOAT, rgba);
    }
    free(spec);
    return true;
}

static void
test_destroy(void *state)
{
    free(state);
}

static const fg_pass_type test_type = {
    .abi_version = FG_ABI_VERSION,
    .name = "t",
    .doc = "A test pass whose inputs and outputs are given by its parameters.",
    .params = test_params,
    .param_count = (int)(sizeof test_params / sizeof test_params[0]),
    .declare = test_declare,
    .prepare = test_prepare,
    .execute = test_execute,
    .destroy = test_destroy,
};

static const fg_pass_type test_side_type = {
    .abi_version = FG_ABI_VERSION,
    .name = "t_side",
    .doc = "The same test pass, marked as having a side effect (never culled).",
    .params = test_params,
    .param_count = (int)(sizeof test_params / sizeof test_params[0]),
    .side_effect = true,
    .declare = test_declare,
    .prepare = test_prepare,
    .execute = test_execute,
    .destroy = test_destroy,
};

bool
fg_test_register(fg_registry *registry, cg_error *err)
{
    return fg_registry_add(registry, &test_type, err) && fg_registry_add(registry, &test_side_type, err);
}

int
fg_test_fixture_setup(void **state)
{
    fg_test_fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    f->registry = fg_registry_create();
    if (!fg_test_register(f->registry, &f->err))
        return -1;
    f->graph = fg_graph_create(f->registry);
    f->frame.width = 64;
    f->frame.height = 32;
    *state = f;
    return 0;
}

int
fg_test_fixture_teardown(void **state)
{
    fg_test_fixture *f = *state;
    fg_graph_destroy(f->graph);
    fg_registry_destroy(f->registry);
    free(f);
    return 0;
}
