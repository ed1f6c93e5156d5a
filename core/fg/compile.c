/* Compile: declare in topological order, validate, cull, order, lifetimes, pooled storage,
 * barriers, limits. No GL is needed (GL limits are asked for only when GL is loaded). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fg_internal.h"

/* ---------------------------------------------------------------- resetting */

static void
free_saved(fg_pass *pass)
{
    for (int i = 0; i < pass->saved_output_count; i++)
        free(pass->saved_outputs[i].name);
    free(pass->saved_outputs);
    pass->saved_outputs = NULL;
    pass->saved_output_count = 0;
}

/* Forgets the last declare; with `save`, keeps its outputs for previous-frame inputs. */
static void
clear_declared(fg_pass *pass, bool save)
{
    for (int i = 0; i < pass->input_count; i++)
        free(pass->inputs[i].name);
    free_saved(pass);
    if (save && pass->declared) {
        pass->saved_outputs = pass->outputs;
        pass->saved_output_count = pass->output_count;
        pass->saved_absent = pass->nothing_to_do || pass->missing_input;
        pass->outputs = NULL;
        pass->output_cap = 0;
    } else {
        for (int i = 0; i < pass->output_count; i++)
            free(pass->outputs[i].name);
    }
    pass->input_count = 0;
    pass->output_count = 0;
    pass->declared = false;
    pass->nothing_to_do = false;
    pass->missing_input = false;
    free(pass->cull_reason);
    pass->cull_reason = NULL;
}

void
fg_graph_reset_compile(fg_graph *graph)
{
    for (int i = 0; i < graph->pass_count; i++) {
        fg_pass *pass = graph->passes[i];
        clear_declared(pass, false);
        free(pass->inputs);
        free(pass->outputs);
        pass->inputs = NULL;
        pass->outputs = NULL;
        pass->input_cap = pass->output_cap = 0;
        pass->culled = false;
        pass->position = -1;
        pass->barrier_bits = 0;
        pass->ms = -1;
        for (int c = 0; c < pass->connection_count; c++) {
            pass->connections[c].source_index = -1;
            pass->connections[c].matched = false;
        }
    }
    for (int i = 0; i < graph->resource_count; i++)
        free(graph->resources[i].name);
    free(graph->resources);
    graph->resources = NULL;
    graph->resource_count = graph->resource_cap = 0;
    free(graph->storage);
    graph->storage = NULL;
    graph->storage_count = graph->storage_cap = 0;
    free(graph->order);
    graph->order = NULL;
    graph->order_count = 0;
    for (int i = 0; i < graph->output_count; i++)
        graph->outputs[i].resource = -1;
    graph->compiled = false;
}

/* A graph ends as a recompile begins (GL state, then compile's products), and then its passes
 * and itself are freed (graph.c): here, so that graph.c, which builds graphs, needs neither
 * compile nor execute. */
void
fg_graph_destroy(fg_graph *graph)
{
    if (!graph)
        return;
    fg_graph_release_gl(graph);
    fg_graph_reset_compile(graph);
    fg_graph_free(graph);
}

/* ---------------------------------------------------------------- small helpers */

static char *
format_string(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

static char *
format_string(const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return fg_strdup(buf);
}

static void
describe(const fg_resource_desc *d, char *buf, size_t size)
{
    char fmt[32];
    switch (d->kind) {
    case FG_BUFFER:
        snprintf(buf, size, "buffer of %zu bytes", d->buffer_bytes);
        return;
    case FG_TEXTURE_2D:
        snprintf(buf, size, "2d %s %dx%d", fg_format_name(d->format, fmt, sizeof fmt), d->width,
                 d->height);
        break;
    case FG_TEXTURE_3D:
    case FG_TEXTURE_2D_ARRAY:
        snprintf(buf, size, "%s %s %dx%dx%d", fg_kind_name(d->kind),
                 fg_format_name(d->format, fmt, sizeof fmt), d->width, d->height, d->depth);
        break;
    }
    if (d->levels > 1) {
        size_t len = strlen(buf);
        snprintf(buf + len, size - len, " (%d levels)", d->levels);
    }
}

static bool
same_storage_desc(const fg_resource_desc *a, const fg_resource_desc *b)
{
    return a->kind == b->kind && a->format == b->format && a->width == b->width &&
           a->height == b->height && a->depth == b->depth && a->levels == b->levels &&
           a->buffer_bytes == b->buffer_bytes;
}

static int
find_in(const fg_output *outputs, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (!strcmp(outputs[i].name, name))
            return i;
    return -1;
}

static int
find_output(const fg_pass *pass, const char *name)
{
    return find_in(pass->outputs, pass->output_count, name);
}

static int
find_input(const fg_pass *pass, const char *name)
{
    for (int i = 0; i < pass->input_count; i++)
        if (!strcmp(pass->inputs[i].name, name))
            return i;
    return -1;
}

static void
list_outputs(const fg_pass *pass, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; i < pass->output_count && len < size; i++) {
        int n = snprintf(buf + len, size - len, "%s%s", i ? ", " : "", pass->outputs[i].name);
        if (n < 0)
            break;
        len += (size_t)n;
    }
    if (!pass->output_count)
        snprintf(buf, size, "it declares none");
}

/* The writer of an absent resource: it had nothing to do, or lost a required input. */
static bool
pass_is_absent(const fg_pass *pass)
{
    return pass->nothing_to_do || pass->missing_input;
}

/* ---------------------------------------------------------------- declare */

static bool
access_fits(fg_resource_kind kind, GLenum format, unsigned access, const char **why)
{
    const fg_format_info *info = kind == FG_BUFFER ? NULL : fg_format_find(format);
    if (kind == FG_BUFFER) {
        if (access & (FG_ACCESS_ATTACHMENT | FG_ACCESS_SAMPLED | FG_ACCESS_IMAGE_LOAD |
                      FG_ACCESS_IMAGE_STORE)) {
            *why = "a buffer is accessed as storage, uniform or transfer only";
            return false;
        }
        return true;
    }
    if (access & (FG_ACCESS_STORAGE | FG_ACCESS_UNIFORM)) {
        *why = "a texture cannot be bound as a storage or uniform buffer";
        return false;
    }
    if ((access & (FG_ACCESS_IMAGE_LOAD | FG_ACCESS_IMAGE_STORE)) && info && !info->image_unit) {
        *why = "its format cannot be bound to an image unit (GL 4.5 table 8.26)";
        return false;
    }
    return true;
}

const fg_resource_desc *
fg_declare_input(fg_declare *decl, const char *name, fg_resource_kind kind, unsigned access,
                 bool required)
{
    fg_pass *pass = decl->pass;
    char at[512], what[256];
    if (decl->failed)
        return NULL;
    if (!name || !*name || find_input(pass, name) >= 0) {
        decl->failed = true;
        cg_fail(decl->err, CG_ERR_PASS, "%spass '%s': its type '%s' declares input '%s' twice (or without a name)",
                fg_loc_prefix(&pass->loc, at, sizeof at), pass->name, pass->type->name, name ? name : "");
        return NULL;
    }
    if (!fg_grow((void **)&pass->inputs, &pass->input_cap, pass->input_count + 1, sizeof *pass->inputs)) {
        decl->failed = true;
        cg_fail(decl->err, CG_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    fg_input *in = &pass->inputs[pass->input_count++];
    memset(in, 0, sizeof *in);
    in->name = fg_strdup(name);
    in->kind = kind;
    in->access = access;
    in->required = required;
    in->connection = -1;
    in->source_pass = -1;
    in->source_output = -1;
    in->resource = -1;
    for (int c = 0; c < pass->connection_count; c++)
        if (!strcmp(pass->connections[c].input, name))
            in->connection = c;
    if (in->connection < 0)
        return NULL;

    fg_connection *conn = &pass->connections[in->connection];
    conn->matched = true;
    fg_source_loc *loc = &conn->loc;
    fg_loc_prefix(loc, at, sizeof at);
    fg_pass *source = decl->graph->passes[conn->source_index];
    in->previous = conn->previous;
    in->source_pass = source->index;
    const fg_output *outputs = source->outputs;
    int output_count = source->output_count;
    bool source_absent = pass_is_absent(source);
    if (!source->declared && source->saved_outputs) {
        outputs = source->saved_outputs;
        output_count = source->saved_output_count;
        source_absent = source->saved_absent;
    } else if (!source->declared) {
        /* Only a previous-frame edge can point at a pass not declared yet (a later one, or
         * this pass itself): the compiler declares every pass a second time once it is known. */
        in->pending = true;
        return NULL;
    }
    int out = -1;
    if (conn->source_output) {
        out = find_in(outputs, output_count, conn->source_output);
    } else {
        out = find_in(outputs, output_count, name);
        if (out < 0 && output_count == 1)
            out = 0;
    }
    if (out < 0 && source_absent) {
        /* It stopped declaring when it found nothing to do: its outputs are simply absent. */
        in->absent = true;
        return NULL;
    }
    if (out < 0) {
        char names[512];
        size_t len = 0;
        names[0] = '\0';
        for (int i = 0; i < output_count && len < sizeof names; i++) {
            int k = snprintf(names + len, sizeof names - len, "%s%s", i ? ", " : "", outputs[i].name);
            if (k > 0)
                len += (size_t)k;
        }
        decl->failed = true;
        if (conn->source_output)
            cg_fail(decl->err, CG_ERR_GRAPH_DANGLING,
                    "%spass '%s' input '%s': pass '%s' (type %s) has no output '%s' (outputs: %s)", at,
                    pass->name, name, source->name, source->type->name, conn->source_output,
                    len ? names : "none");
        else
            cg_fail(decl->err, CG_ERR_GRAPH_DANGLING,
                    "%spass '%s' input '%s': pass '%s' (type %s) has no output '%s' and not exactly one "
                    "output; name one as '%s.OUTPUT' (outputs: %s)", at, pass->name, name, source->name,
                    source->type->name, name, source->name, len ? names : "none");
        return NULL;
    }
    in->source_output = out;
    if (source_absent) {
        in->absent = true;
        return NULL;
    }
    const fg_output *o = &outputs[out];
    if (o->desc.kind != kind) {
        describe(&o->desc, what, sizeof what);
        decl->failed = true;
        cg_fail(decl->err, CG_ERR_GRAPH_INCOMPATIBLE,
                "%spass '%s' input '%s': expected a %s resource, but '%s.%s' is a %s", at, pass->name,
                name, fg_kind_name(kind), source->name, o->name, what);
        return NULL;
    }
    const char *why;
    if (!access_fits(kind, o->desc.format, access, &why)) {
        char acc[128];
        describe(&o->desc, what, sizeof what);
        decl->failed = true;
        cg_fail(decl->err, CG_ERR_GRAPH_INCOMPATIBLE,
                "%spass '%s' input '%s' reads '%s.%s' (%s) as %s: %s", at, pass->name, name,
                source->name, o->name, what, fg_access_names(access, acc, sizeof acc), why);
        return NULL;
    }
    return &o->desc;
}

void
fg_declare_output(fg_declare *decl, const char *name, const fg_resource_desc *desc, unsigned access)
{
    fg_pass *pass = decl->pass;
    if (decl->failed)
        return;
    if (!name || !*name || strchr(name, '.') || strchr(name, '@') || find_output(pass, name) >= 0) {
        char at[512];
        decl->failed = true;
        cg_fail(decl->err, CG_ERR_PASS,
                "%spass '%s': its type '%s' declares output '%s' twice or with '.' or '@' in its name",
                fg_loc_prefix(&pass->loc, at, sizeof at), pass->name, pass->type->name, name ? name : "");
        return;
    }
    if (!fg_grow((void **)&pass->outputs, &pass->output_cap, pass->output_count + 1,
                 sizeof *pass->outputs)) {
        decl->failed = true;
        cg_fail(decl->err, CG_ERR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    fg_output *out = &pass->outputs[pass->output_count++];
    memset(out, 0, sizeof *out);
    out->name = fg_strdup(name);
    out->desc = *desc;
    /* Zero means the default, as for every descriptor: one level, one layer. */
    if (out->desc.levels == 0)
        out->desc.levels = 1;
    if (out->desc.depth == 0)
        out->desc.depth = 1;
    out->access = access;
    out->resource = -1;
    out->in_place_input = -1;
}

void
fg_declare_nothing_to_do(fg_declare *decl, const char *why)
{
    fg_pass *pass = decl->pass;
    if (pass->nothing_to_do)
        return;
    pass->nothing_to_do = true;
    free(pass->cull_reason);
    pass->cull_reason = format_string("nothing to do: %s", why && *why ? why : "(no reason given)");
}

static bool
check_output_desc(const fg_pass *pass, const fg_output *out, cg_error *err)
{
    const fg_resource_desc *d = &out->desc;
    char at[512], acc[128];
    fg_loc_prefix(&pass->loc, at, sizeof at);
    if (d->kind == FG_BUFFER) {
        if (d->buffer_bytes == 0)
            return cg_fail(err, CG_ERR_PASS, "%spass '%s' (type %s) output '%s': a buffer of 0 bytes", at,
                           pass->name, pass->type->name, out->name);
    } else {
        if (!fg_format_find(d->format))
            return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                           "%spass '%s' (type %s) output '%s': format 0x%04x is not a sized internal "
                           "format conegraph knows", at, pass->name, pass->type->name, out->name,
                           (unsigned)d->format);
        if (d->width <= 0 || d->height <= 0 || d->depth <= 0 ||
            (d->kind == FG_TEXTURE_2D && d->depth != 1))
            return cg_fail(err, CG_ERR_PASS, "%spass '%s' (type %s) output '%s': bad size %dx%dx%d", at,
                           pass->name, pass->type->name, out->name, d->width, d->height, d->depth);
        int max_levels = fg_mip_levels(d->width, d->height, d->kind == FG_TEXTURE_3D ? d->depth : 1);
        if (d->levels < 1 || d->levels > max_levels)
            return cg_fail(err, CG_ERR_PASS,
                           "%spass '%s' (type %s) output '%s': %d mip levels; a %dx%dx%d texture has 1..%d",
                           at, pass->name, pass->type->name, out->name, d->levels, d->width, d->height,
                           d->depth, max_levels);
    }
    const char *why;
    if (!access_fits(d->kind, d->format, out->access, &why)) {
        char what[256];
        describe(d, what, sizeof what);
        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE, "%spass '%s' (type %s) writes output '%s' (%s) as %s: %s",
                       at, pass->name, pass->type->name, out->name, what,
                       fg_access_names(out->access, acc, sizeof acc), why);
    }
    return true;
}

/* Calls declare() and checks what it stated. `any_pending` is set when a previous-frame
 * input could not be resolved yet. */
static bool
declare_pass(fg_graph *graph, fg_pass *pass, bool *any_pending, cg_error *err)
{
    char at[512];
    clear_declared(pass, true);
    fg_loc_prefix(&pass->loc, at, sizeof at);
    /* Errors the graph raises inside fg_declare_* carry their own location; a failure the pass
     * reports itself gets the pass's. */
    cg_error local = { 0 };
    fg_declare decl = { graph, pass, &local, false };
    bool ok = pass->type->declare(pass, &decl, &local);
    pass->declared = true;
    if (decl.failed)
        return cg_fail(err, local.status, "%s", local.message);
    if (!ok) {
        if (local.status == CG_OK)
            return cg_fail(err, CG_ERR_PASS, "%spass '%s' (type %s): declare failed without a reason", at,
                           pass->name, pass->type->name);
        return cg_fail(err, local.status, "%spass '%s' (type %s): %s", at, pass->name, pass->type->name,
                       local.message);
    }
    for (int i = 0; i < pass->input_count; i++) {
        fg_input *in = &pass->inputs[i];
        *any_pending |= in->pending;
        if (find_output(pass, in->name) >= 0) {
            fg_output *out = &pass->outputs[find_output(pass, in->name)];
            out->in_place_input = i;
        }
    }
    if (pass->nothing_to_do)
        return true;
    for (int i = 0; i < pass->input_count; i++) {
        fg_input *in = &pass->inputs[i];
        if (in->required && in->connection < 0)
            return cg_fail(err, CG_ERR_GRAPH_MISSING_INPUT,
                           "%spass '%s' (type %s): required input '%s' is not connected", at, pass->name,
                           pass->type->name, in->name);
        if (in->required && in->absent && !pass->missing_input) {
            const fg_pass *source = graph->passes[in->source_pass];
            pass->missing_input = true;
            free(pass->cull_reason);
            pass->cull_reason = format_string("required input '%s' is absent: pass '%s' %s", in->name,
                                              source->name,
                                              source->cull_reason ? source->cull_reason : "is absent");
        }
    }
    for (int c = 0; c < pass->connection_count; c++) {
        const fg_connection *conn = &pass->connections[c];
        if (conn->matched)
            continue;
        char inputs[512];
        size_t len = 0;
        inputs[0] = '\0';
        for (int i = 0; i < pass->input_count && len < sizeof inputs; i++) {
            int n = snprintf(inputs + len, sizeof inputs - len, "%s%s", i ? ", " : "", pass->inputs[i].name);
            if (n > 0)
                len += (size_t)n;
        }
        char cat[512];
        fg_loc_prefix(&conn->loc, cat, sizeof cat);
        return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%spass '%s' (type %s) has no input '%s' (inputs: %s)",
                       cat, pass->name, pass->type->name, conn->input, len ? inputs : "none");
    }
    for (int i = 0; i < pass->output_count; i++)
        if (!check_output_desc(pass, &pass->outputs[i], err))
            return false;
    return true;
}

/* ---------------------------------------------------------------- order */

/* Topological order over the file's connections (previous-frame edges excluded), the
 * lowest file index first among the ready passes, so that the order is stable. */
static bool
topological_order(fg_graph *graph, int *topo, cg_error *err)
{
    int n = graph->pass_count;
    int *indegree = calloc((size_t)n + 1, sizeof *indegree);
    bool *done = calloc((size_t)n + 1, sizeof *done);
    if (!indegree || !done) {
        free(indegree);
        free(done);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    }
    for (int p = 0; p < n; p++)
        for (int c = 0; c < graph->passes[p]->connection_count; c++)
            if (!graph->passes[p]->connections[c].previous)
                indegree[p]++;
    int count = 0;
    while (count < n) {
        int next = -1;
        for (int p = 0; p < n && next < 0; p++)
            if (!done[p] && indegree[p] == 0)
                next = p;
        if (next < 0)
            break;
        done[next] = true;
        topo[count++] = next;
        for (int p = 0; p < n; p++)
            for (int c = 0; c < graph->passes[p]->connection_count; c++) {
                const fg_connection *conn = &graph->passes[p]->connections[c];
                if (!conn->previous && conn->source_index == next)
                    indegree[p]--;
            }
    }
    bool ok = true;
    if (count < n) {
        /* Every pass left has a predecessor that is left too: walk back until one repeats. */
        int start = -1;
        for (int p = 0; p < n && start < 0; p++)
            if (!done[p])
                start = p;
        int *seen_at = malloc((size_t)n * sizeof *seen_at);
        int *walk = malloc((size_t)(n + 1) * sizeof *walk);
        if (!seen_at || !walk) {
            free(seen_at);
            free(walk);
            free(indegree);
            free(done);
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
        }
        for (int p = 0; p < n; p++)
            seen_at[p] = -1;
        int len = 0, cur = start;
        while (seen_at[cur] < 0) {
            seen_at[cur] = len;
            walk[len++] = cur;
            int pred = -1;
            const fg_pass *pass = graph->passes[cur];
            for (int c = 0; c < pass->connection_count && pred < 0; c++) {
                const fg_connection *conn = &pass->connections[c];
                if (!conn->previous && !done[conn->source_index])
                    pred = conn->source_index;
            }
            cur = pred;
        }
        /* walk[first..len) follows edges backwards from walk[first]; print it forwards,
         * starting and ending at walk[first]. */
        char cycle[1024], at[512];
        int first = seen_at[cur];
        size_t used = 0;
        cycle[0] = '\0';
        for (int i = first; i < len + 1 && used < sizeof cycle; i++) {
            int node = i == first ? walk[first] : i == len ? walk[first] : walk[len - (i - first)];
            int k = snprintf(cycle + used, sizeof cycle - used, "%s'%s'", i == first ? "" : " -> ",
                             graph->passes[node]->name);
            if (k > 0)
                used += (size_t)k;
        }
        fg_loc_prefix(&graph->passes[walk[first]]->loc, at, sizeof at);
        ok = cg_fail(err, CG_ERR_GRAPH_CYCLE,
                     "%sgraph has a cycle: %s (an input may read the previous frame with "
                     "\"pass.output@previous\" to close a loop)", at, cycle);
        free(seen_at);
        free(walk);
    }
    free(indegree);
    free(done);
    return ok;
}

/* ---------------------------------------------------------------- culling */

static bool
cull(fg_graph *graph, cg_error *err)
{
    int n = graph->pass_count;
    bool *live = calloc((size_t)n + 1, sizeof *live);
    int *stack = malloc(((size_t)n + 1) * sizeof *stack);
    if (!live || !stack) {
        free(live);
        free(stack);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    }
    int top = 0;
    bool any_output_present = false;
    for (int i = 0; i < graph->output_count; i++) {
        fg_graph_output *o = &graph->outputs[i];
        char at[512], pass_name[256];
        fg_loc_prefix(&o->loc, at, sizeof at);
        const char *output = fg_split_source(o->source, pass_name, sizeof pass_name);
        fg_pass *pass = fg_graph_find_pass(graph, pass_name);
        if (!pass) {
            free(live);
            free(stack);
            return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%soutput '%s': no pass named '%s'", at, o->source,
                           pass_name);
        }
        if (pass_is_absent(pass))
            continue;
        if (find_output(pass, output) < 0) {
            char outputs[512];
            list_outputs(pass, outputs, sizeof outputs);
            free(live);
            free(stack);
            return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%soutput '%s': pass '%s' (type %s) has no output "
                           "'%s' (outputs: %s)", at, o->source, pass_name, pass->type->name, output,
                           outputs);
        }
        any_output_present = true;
        if (!live[pass->index]) {
            live[pass->index] = true;
            stack[top++] = pass->index;
        }
    }
    if (!any_output_present) {
        /* Every marked output is absent: name why, from the first one. */
        char pass_name[256], at[512];
        fg_split_source(graph->outputs[0].source, pass_name, sizeof pass_name);
        fg_loc_prefix(&graph->outputs[0].loc, at, sizeof at);
        const fg_pass *pass = fg_graph_find_pass(graph, pass_name);
        free(live);
        free(stack);
        return cg_fail(err, CG_ERR_GRAPH_NO_OUTPUT,
                       "%severy marked output is absent for this scene: pass '%s' %s", at, pass_name,
                       pass->cull_reason);
    }
    for (int p = 0; p < n; p++) {
        const fg_pass *pass = graph->passes[p];
        if (live[p] || pass_is_absent(pass))
            continue;
        bool keep = pass->type->side_effect;
        for (int o = 0; o < pass->output_count && !keep; o++)
            keep = pass->outputs[o].desc.persistent;
        if (keep) {
            live[p] = true;
            stack[top++] = p;
        }
    }
    /* Everything a kept pass reads (this frame or the last) is kept too. */
    while (top > 0) {
        const fg_pass *pass = graph->passes[stack[--top]];
        for (int i = 0; i < pass->input_count; i++) {
            const fg_input *in = &pass->inputs[i];
            if (in->source_pass < 0 || in->absent || live[in->source_pass])
                continue;
            live[in->source_pass] = true;
            stack[top++] = in->source_pass;
        }
    }
    for (int p = 0; p < n; p++) {
        fg_pass *pass = graph->passes[p];
        pass->culled = !live[p] || pass_is_absent(pass);
        if (pass->culled && !pass->cull_reason)
            pass->cull_reason = format_string("not needed: no marked output, side effect or persistent "
                                              "resource depends on it");
    }
    free(live);
    free(stack);
    return true;
}

/* ---------------------------------------------------------------- resources and storage */

static int
add_storage(fg_graph *graph, const fg_resource_desc *desc, int first, int last, bool clear)
{
    if (!fg_grow((void **)&graph->storage, &graph->storage_cap, graph->storage_count + 1,
                 sizeof *graph->storage))
        return -1;
    fg_storage *s = &graph->storage[graph->storage_count];
    memset(s, 0, sizeof *s);
    s->desc = *desc;
    s->bytes = fg_resource_bytes(desc);
    s->first_use = first;
    s->last_use = last;
    s->clear_on_create = clear;
    return graph->storage_count++;
}

static bool
build_resources(fg_graph *graph, cg_error *err)
{
    /* One resource per declared output, in file order; those of culled passes are absent. */
    for (int p = 0; p < graph->pass_count; p++) {
        fg_pass *pass = graph->passes[p];
        for (int o = 0; o < pass->output_count; o++) {
            if (!fg_grow((void **)&graph->resources, &graph->resource_cap, graph->resource_count + 1,
                         sizeof *graph->resources))
                return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
            fg_output *out = &pass->outputs[o];
            fg_res *r = &graph->resources[graph->resource_count];
            memset(r, 0, sizeof *r);
            r->name = format_string("%s.%s", pass->name, out->name);
            if (!r->name)
                return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
            r->info.name = r->name;
            r->info.desc = out->desc;
            r->info.absent = pass->culled;
            r->info.writer = p;
            r->info.first_use = r->info.last_use = pass->culled ? -1 : pass->position;
            r->info.storage = -1;
            r->info.bytes = fg_resource_bytes(&out->desc);
            r->output = o;
            r->writer_access = out->access;
            r->version_of = -1;
            r->updated_by = -1;
            r->storage2 = -1;
            out->resource = graph->resource_count++;
        }
    }
    /* Readers extend lifetimes and link inputs to resources. */
    for (int k = 0; k < graph->order_count; k++) {
        fg_pass *pass = graph->passes[graph->order[k]];
        for (int i = 0; i < pass->input_count; i++) {
            fg_input *in = &pass->inputs[i];
            if (in->source_output < 0 || in->absent)
                continue;
            const fg_pass *source = graph->passes[in->source_pass];
            const fg_connection *conn = &pass->connections[in->connection];
            /* A previous-frame input was matched against the source's first declare round:
             * the second must have stated the same output there. */
            if (in->source_output >= source->output_count ||
                (conn->source_output && strcmp(source->outputs[in->source_output].name, conn->source_output)))
                return cg_fail(err, CG_ERR_PASS,
                               "pass '%s' (type %s) declared different outputs in two declare rounds; "
                               "declare() must depend only on parameters, scene and inputs",
                               source->name, source->type->name);
            in->resource = source->outputs[in->source_output].resource;
            fg_res *r = &graph->resources[in->resource];
            if (in->previous)
                r->read_previous = true;
            else if (k > r->info.last_use)
                r->info.last_use = k;
        }
    }
    for (int i = 0; i < graph->output_count; i++) {
        char pass_name[256];
        const char *output = fg_split_source(graph->outputs[i].source, pass_name, sizeof pass_name);
        const fg_pass *pass = fg_graph_find_pass(graph, pass_name);
        int o = find_output(pass, output);
        if (o < 0 || pass->culled)
            continue;
        graph->outputs[i].resource = pass->outputs[o].resource;
        fg_res *r = &graph->resources[pass->outputs[o].resource];
        r->graph_output = true;
        r->info.last_use = graph->order_count - 1;
    }
    /* In-place updates: an output named like an input, of the same descriptor, is a new
     * version of that input's resource on the same storage (a mip chain built in place). */
    for (int k = 0; k < graph->order_count; k++) {
        fg_pass *pass = graph->passes[graph->order[k]];
        for (int o = 0; o < pass->output_count; o++) {
            fg_output *out = &pass->outputs[o];
            if (out->in_place_input < 0)
                continue;
            const fg_input *in = &pass->inputs[out->in_place_input];
            char at[512];
            fg_loc_prefix(&pass->loc, at, sizeof at);
            if (in->resource < 0 || in->previous)
                return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                               "%spass '%s' (type %s) updates input '%s' in place, but it is %s", at,
                               pass->name, pass->type->name, in->name,
                               in->previous ? "a previous-frame input" : "not connected or absent");
            fg_res *old = &graph->resources[in->resource];
            fg_res *r = &graph->resources[out->resource];
            if (!same_storage_desc(&old->info.desc, &out->desc))
                return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                               "%spass '%s' (type %s) updates '%s' in place as output '%s' with a "
                               "different descriptor", at, pass->name, pass->type->name, old->name,
                               out->name);
            if (old->graph_output || old->read_previous || old->updated_by >= 0 ||
                old->info.last_use != k)
                return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                               "%spass '%s' (type %s) updates '%s' in place, so no other pass may read "
                               "it (read '%s.%s' instead) and it cannot be a graph output", at,
                               pass->name, pass->type->name, old->name, pass->name, out->name);
            for (int j = 0; j < k; j++) {
                const fg_pass *other = graph->passes[graph->order[j]];
                for (int x = 0; x < other->input_count; x++)
                    if (other->inputs[x].resource == in->resource)
                        return cg_fail(err, CG_ERR_GRAPH_INCOMPATIBLE,
                                       "%spass '%s' (type %s) updates '%s' in place, but pass '%s' reads "
                                       "it too (let it read '%s.%s')", at, pass->name, pass->type->name,
                                       old->name, other->name, pass->name, out->name);
            }
            old->updated_by = out->resource;
            r->version_of = in->resource;
            r->info.desc.persistent |= old->info.desc.persistent;
        }
    }
    return true;
}

static bool
assign_storage(fg_graph *graph, bool no_pool, cg_error *err)
{
    int last = graph->order_count - 1;
    for (int k = 0; k < graph->order_count; k++) {
        fg_pass *pass = graph->passes[graph->order[k]];
        for (int o = 0; o < pass->output_count; o++) {
            int head = pass->outputs[o].resource;
            fg_res *r = &graph->resources[head];
            if (r->version_of >= 0) {
                r->info.storage = graph->resources[r->version_of].info.storage;
                r->storage2 = graph->resources[r->version_of].storage2;
                continue;
            }
            /* The storage lives from the first version's writer to the last version's last reader. */
            bool keep = false, previous_after_write = false;
            int end = r->info.last_use;
            for (int v = head; v >= 0; v = graph->resources[v].updated_by) {
                const fg_res *rv = &graph->resources[v];
                keep |= rv->info.desc.persistent || rv->graph_output || rv->read_previous;
                if (rv->info.last_use > end)
                    end = rv->info.last_use;
                if (rv->read_previous) {
                    /* A previous-frame reader that runs before the writer sees last frame's value
                     * on the one storage; one at or after the writer needs a second storage. */
                    const fg_pass *writer = graph->passes[rv->info.writer];
                    for (int j = 0; j < graph->order_count; j++) {
                        const fg_pass *reader = graph->passes[graph->order[j]];
                        for (int x = 0; x < reader->input_count; x++)
                            if (reader->inputs[x].previous && reader->inputs[x].resource == v &&
                                j >= writer->position)
                                previous_after_write = true;
                    }
                }
            }
            int s = -1;
            if (keep) {
                s = add_storage(graph, &r->info.desc, 0, last, true);
                if (s >= 0 && previous_after_write) {
                    r->double_buffered = true;
                    r->storage2 = add_storage(graph, &r->info.desc, 0, last, true);
                    if (r->storage2 < 0)
                        s = -1;
                }
            } else {
                if (!no_pool)
                    for (int c = 0; c < graph->storage_count && s < 0; c++) {
                        fg_storage *st = &graph->storage[c];
                        if (!st->clear_on_create && st->last_use < k && same_storage_desc(&st->desc, &r->info.desc))
                            s = c;
                    }
                if (s >= 0)
                    graph->storage[s].last_use = end;
                else
                    s = add_storage(graph, &r->info.desc, k, end, false);
            }
            if (s < 0)
                return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
            r->info.storage = s;
            for (int v = r->updated_by; v >= 0; v = graph->resources[v].updated_by)
                graph->resources[v].double_buffered = r->double_buffered;
        }
    }
    return true;
}

/* Barrier bits before each pass: from each input's writer access to this pass's access,
 * and, where the pool hands over storage, from the previous occupant's writer to this writer. */
static void
compute_barriers(fg_graph *graph)
{
    int *last_writer_access = calloc((size_t)graph->storage_count + 1, sizeof *last_writer_access);
    /* Storage kept across frames was last written in the previous frame. */
    for (int k = 0; last_writer_access && k < graph->order_count; k++) {
        const fg_pass *pass = graph->passes[graph->order[k]];
        for (int o = 0; o < pass->output_count; o++) {
            const fg_res *r = &graph->resources[pass->outputs[o].resource];
            if (r->info.storage >= 0 && graph->storage[r->info.storage].clear_on_create)
                last_writer_access[r->info.storage] = (int)r->writer_access;
        }
    }
    for (int k = 0; k < graph->order_count; k++) {
        fg_pass *pass = graph->passes[graph->order[k]];
        GLbitfield bits = 0;
        for (int i = 0; i < pass->input_count; i++) {
            const fg_input *in = &pass->inputs[i];
            if (in->resource < 0)
                continue;
            const fg_res *r = &graph->resources[in->resource];
            bits |= fg_barrier_bits_for(r->writer_access, in->access, r->info.desc.kind);
        }
        for (int o = 0; o < pass->output_count; o++) {
            const fg_res *r = &graph->resources[pass->outputs[o].resource];
            if (last_writer_access && r->info.storage >= 0) {
                bits |= fg_barrier_bits_for((unsigned)last_writer_access[r->info.storage], r->writer_access,
                                            r->info.desc.kind);
                last_writer_access[r->info.storage] = (int)r->writer_access;
            }
        }
        pass->barrier_bits = bits;
    }
    free(last_writer_access);
}

/* ---------------------------------------------------------------- limits */

static int
gl_limit(GLenum name)
{
    /* Only when a GL loader is in place; with no current context Mesa's no-op dispatch
     * leaves the value untouched. */
    if (!glad_glGetIntegerv)
        return 0;
    GLint value = 0;
    glGetIntegerv(name, &value);
    return value;
}

static bool
check_limits(fg_graph *graph, cg_error *err)
{
    int max2d = graph->options.max_texture_size_2d ? graph->options.max_texture_size_2d
                                                   : gl_limit(GL_MAX_TEXTURE_SIZE);
    int max3d = graph->options.max_texture_size_3d ? graph->options.max_texture_size_3d
                                                   : gl_limit(GL_MAX_3D_TEXTURE_SIZE);
    int max_layers = gl_limit(GL_MAX_ARRAY_TEXTURE_LAYERS);
    for (int i = 0; i < graph->resource_count; i++) {
        const fg_res *r = &graph->resources[i];
        const fg_resource_desc *d = &r->info.desc;
        const fg_pass *pass = graph->passes[r->info.writer];
        if (d->kind == FG_BUFFER || (pass->nothing_to_do))
            continue;
        char at[512], what[256];
        fg_loc_prefix(&pass->loc, at, sizeof at);
        describe(d, what, sizeof what);
        bool is3d = d->kind == FG_TEXTURE_3D;
        int limit = is3d ? max3d : max2d;
        int largest = d->width > d->height ? d->width : d->height;
        if (is3d && d->depth > largest)
            largest = d->depth;
        if (limit > 0 && largest > limit)
            return cg_fail(err, CG_ERR_GRAPH_TOO_LARGE,
                           "%spass '%s' output '%s': %s exceeds the largest %s texture, %d texels a side%s",
                           at, pass->name, pass->outputs[r->output].name, what, is3d ? "3D" : "2D", limit,
                           (is3d ? graph->options.max_texture_size_3d : graph->options.max_texture_size_2d)
                               ? " (set by the options)"
                               : is3d ? " (GL_MAX_3D_TEXTURE_SIZE)" : " (GL_MAX_TEXTURE_SIZE)");
        if (d->kind == FG_TEXTURE_2D_ARRAY && max_layers > 0 && d->depth > max_layers)
            return cg_fail(err, CG_ERR_GRAPH_TOO_LARGE,
                           "%spass '%s' output '%s': %s has more layers than GL_MAX_ARRAY_TEXTURE_LAYERS, %d",
                           at, pass->name, pass->outputs[r->output].name, what, max_layers);
    }
    if (graph->options.max_gpu_memory) {
        fg_memory_report report;
        fg_graph_memory_report(graph, &report);
        if (report.allocated_bytes > graph->options.max_gpu_memory) {
            int largest = -1;
            for (int i = 0; i < graph->resource_count; i++)
                if (!graph->resources[i].info.absent &&
                    (largest < 0 || graph->resources[i].info.bytes > graph->resources[largest].info.bytes))
                    largest = i;
            char at[512], need[32], allowed[32], largest_text[32];
            const fg_res *r = &graph->resources[largest];
            fg_loc_prefix(&graph->passes[r->info.writer]->loc, at, sizeof at);
            return cg_fail(err, CG_ERR_GRAPH_MEMORY_BUDGET,
                           "%sthe graph needs %s of GPU memory, more than the allowed %s "
                           "(largest resource: '%s', %s)", at,
                           fg_bytes_text(report.allocated_bytes, need, sizeof need),
                           fg_bytes_text(graph->options.max_gpu_memory, allowed, sizeof allowed),
                           r->info.name, fg_bytes_text(r->info.bytes, largest_text, sizeof largest_text));
        }
    }
    return true;
}

/* ---------------------------------------------------------------- compile */

bool
fg_graph_compile(fg_graph *graph, const fg_frame *frame, const fg_compile_options *options,
                 cg_error *err)
{
    fg_graph_release_gl(graph);
    fg_graph_reset_compile(graph);
    graph->frame = *frame;
    if (options)
        graph->options = *options;
    else
        memset(&graph->options, 0, sizeof graph->options);
    if (graph->output_count == 0)
        return cg_fail(err, CG_ERR_GRAPH_NO_OUTPUT,
                       "the graph marks no output: list at least one \"pass.output\" in \"outputs\"");
    for (int p = 0; p < graph->pass_count; p++) {
        fg_pass *pass = graph->passes[p];
        for (int c = 0; c < pass->connection_count; c++) {
            fg_connection *conn = &pass->connections[c];
            const fg_pass *source = fg_graph_find_pass(graph, conn->source_pass);
            if (!source) {
                char at[512];
                fg_loc_prefix(&conn->loc, at, sizeof at);
                return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%spass '%s' input '%s': no pass named '%s'", at,
                               pass->name, conn->input, conn->source_pass);
            }
            conn->source_index = source->index;
        }
    }
    /* Each value met its own table entry when it was set; what one value requires of another
     * (voxelize's max_x > min_x) is checked here, once, before any declare() reads them. */
    for (int p = 0; p < graph->pass_count; p++)
        if (!fg_pass_check_params(graph->passes[p], err))
            return false;
    int *topo = malloc(((size_t)graph->pass_count + 1) * sizeof *topo);
    if (!topo)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    if (!topological_order(graph, topo, err)) {
        free(topo);
        return false;
    }
    /* declare() sees its connected inputs' descriptors, so it runs in topological order. A
     * previous-frame input may come from a later pass: then a second round gives it that
     * pass's descriptor from the first (declare depends only on parameters, scene and inputs). */
    for (int round = 0; round < 2; round++) {
        bool pending = false;
        for (int k = 0; k < graph->pass_count; k++)
            if (!declare_pass(graph, graph->passes[topo[k]], &pending, err)) {
                free(topo);
                return false;
            }
        if (!pending)
            break;
    }
    if (!cull(graph, err)) {
        free(topo);
        return false;
    }
    graph->order = topo;
    graph->order_count = 0;
    for (int k = 0; k < graph->pass_count; k++) {
        fg_pass *pass = graph->passes[topo[k]];
        if (!pass->culled) {
            pass->position = graph->order_count;
            topo[graph->order_count++] = pass->index;
        }
    }
    if (!build_resources(graph, err) || !assign_storage(graph, graph->options.no_pool, err))
        return false;
    compute_barriers(graph);
    if (!check_limits(graph, err))
        return false;
    graph->compiled = true;
    return true;
}

int
fg_graph_order(const fg_graph *graph, const int **order)
{
    if (order)
        *order = graph->order;
    return graph->order_count;
}

bool
fg_pass_is_culled(const fg_pass *pass)
{
    return pass->culled;
}

const char *
fg_pass_cull_reason(const fg_pass *pass)
{
    return pass->culled ? pass->cull_reason : NULL;
}

const char *
fg_pass_input_source(const fg_pass *pass, const char *input)
{
    for (int i = 0; i < pass->input_count; i++)
        if (!strcmp(pass->inputs[i].name, input))
            return pass->inputs[i].resource >= 0 ? pass->graph->resources[pass->inputs[i].resource].name : NULL;
    return NULL;
}

GLbitfield
fg_pass_barrier_bits(const fg_pass *pass)
{
    return pass->barrier_bits;
}
