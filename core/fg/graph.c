/* Building a graph: pass instances, parameter values, connections, marked outputs;
 * and what a pass reads of itself (parameters, name, frame). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fg_internal.h"

fg_graph *
fg_graph_create(const fg_registry *registry)
{
    fg_graph *graph = calloc(1, sizeof *graph);
    if (graph) {
        graph->registry = registry;
        graph->query_frame = -1;
    }
    return graph;
}

static void
free_pass(fg_pass *pass)
{
    for (int i = 0; i < pass->type->param_count; i++)
        free(pass->values[i].text);
    free(pass->values);
    for (int i = 0; i < pass->connection_count; i++) {
        fg_connection *c = &pass->connections[i];
        free(c->input);
        free(c->source_pass);
        free(c->source_output);
    }
    free(pass->connections);
    free(pass->inputs);
    free(pass->outputs);
    free(pass->name);
    free(pass);
}

void
fg_graph_free(fg_graph *graph)
{
    for (int i = 0; i < graph->pass_count; i++)
        free_pass(graph->passes[i]);
    free(graph->passes);
    for (int i = 0; i < graph->file_count; i++)
        free(graph->files[i]);
    free(graph->files);
    for (int i = 0; i < graph->output_count; i++)
        free(graph->outputs[i].source);
    free(graph->outputs);
    free(graph);
}

/* Locations outlive the caller's strings: keep one copy of each file name in the graph. */
static fg_source_loc
keep_loc(fg_graph *graph, const fg_source_loc *loc)
{
    fg_source_loc kept = { 0 };
    if (!loc)
        return kept;
    kept = *loc;
    if (!loc->file)
        return kept;
    for (int i = 0; i < graph->file_count; i++) {
        if (!strcmp(graph->files[i], loc->file)) {
            kept.file = graph->files[i];
            return kept;
        }
    }
    char *copy = fg_strdup(loc->file);
    if (!copy || !fg_grow((void **)&graph->files, &graph->file_cap, graph->file_count + 1,
                          sizeof *graph->files)) {
        free(copy);
        kept.file = "(out of memory)";
        return kept;
    }
    graph->files[graph->file_count++] = copy;
    kept.file = copy;
    return kept;
}

static void
list_type_names(const fg_registry *registry, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; i < registry->count && len < size; i++) {
        int n = snprintf(buf + len, size - len, "%s%s", i ? ", " : "", registry->types[i]->name);
        if (n < 0)
            break;
        len += (size_t)n;
    }
    if (!registry->count)
        snprintf(buf, size, "none registered");
}

bool
fg_graph_add_pass(fg_graph *graph, const char *name, const char *type, const fg_source_loc *loc,
                  cg_error *err)
{
    char at[512];
    fg_loc_prefix(loc, at, sizeof at);
    if (!name || !*name || strchr(name, '.') || strchr(name, '@') || strchr(name, '='))
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA,
                       "%spass name '%s': expected a name without '.', '@' or '='", at, name ? name : "");
    if (fg_graph_find_pass(graph, name))
        return cg_fail(err, CG_ERR_GRAPH_DUPLICATE, "%sa pass named '%s' already exists", at, name);
    const fg_pass_type *pass_type = fg_registry_find(graph->registry, type);
    if (!pass_type) {
        char known[1536];
        list_type_names(graph->registry, known, sizeof known);
        return cg_fail(err, CG_ERR_GRAPH_UNKNOWN_TYPE, "%spass '%s': unknown type '%s' (known types: %s)",
                       at, name, type, known);
    }
    fg_pass *pass = calloc(1, sizeof *pass);
    if (!pass || !fg_grow((void **)&graph->passes, &graph->pass_cap, graph->pass_count + 1,
                          sizeof *graph->passes)) {
        free(pass);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory adding pass '%s'", name);
    }
    pass->graph = graph;
    pass->index = graph->pass_count;
    pass->type = pass_type;
    pass->name = fg_strdup(name);
    pass->loc = keep_loc(graph, loc);
    pass->position = -1;
    pass->ms = -1;
    pass->values = calloc((size_t)(pass_type->param_count ? pass_type->param_count : 1),
                          sizeof *pass->values);
    if (!pass->name || !pass->values) {
        free(pass->name);
        free(pass->values);
        free(pass);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory adding pass '%s'", name);
    }
    for (int i = 0; i < pass_type->param_count; i++) {
        const fg_param_desc *p = &pass_type->params[i];
        pass->values[i].number = p->default_value;
        if (p->type == FG_PARAM_STRING)
            pass->values[i].text = fg_strdup(p->choices ? p->choices : "");
    }
    graph->passes[graph->pass_count++] = pass;
    graph->compiled = false;
    return true;
}

static void
list_param_names(const fg_pass_type *type, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int i = 0; i < type->param_count && len < size; i++) {
        int n = snprintf(buf + len, size - len, "%s%s", i ? ", " : "", type->params[i].name);
        if (n < 0)
            break;
        len += (size_t)n;
    }
    if (!type->param_count)
        snprintf(buf, size, "it has none");
}

bool
fg_graph_set_param(fg_graph *graph, const char *pass_name, const char *param, const char *value,
                   const fg_source_loc *loc, cg_error *err)
{
    char at[1200];
    fg_loc_prefix(loc, at, sizeof at);
    fg_pass *pass = fg_graph_find_pass(graph, pass_name);
    if (!pass)
        return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%sno pass named '%s'", at, pass_name);
    int index;
    const fg_param_desc *p = fg_param_find(pass->type, param, &index);
    if (!p) {
        char names[1024];
        list_param_names(pass->type, names, sizeof names);
        if (fg_loc_is_assignment(loc))
            return cg_fail(err, CG_ERR_GRAPH_UNKNOWN_PARAM, "%spass type %s has no parameter '%s' (parameters: %s)",
                           at, pass->type->name, param, names);
        return cg_fail(err, CG_ERR_GRAPH_UNKNOWN_PARAM,
                       "%spass '%s' (type %s) has no parameter '%s' (parameters: %s)", at, pass_name,
                       pass->type->name, param, names);
    }
    fg_param_value *v = &pass->values[index];
    double number = 0;
    bool parsed = fg_param_parse(p, value, &number);
    if (!parsed || !fg_param_accepts(p, number)) {
        /* One message for both: "g.json:7:24: gather.cones = 7; expected one of 1, 6, 9, 16". */
        char lead[1400], expected[1024];
        fg_param_lead(loc, pass_name, param, value, lead, sizeof lead);
        fg_param_expected(p, expected, sizeof expected);
        return cg_fail(err, parsed || p->type == FG_PARAM_ENUM ? CG_ERR_GRAPH_PARAM_RANGE : CG_ERR_GRAPH_PARAM_TYPE,
                       "%sexpected %s", lead, expected);
    }
    if (p->type == FG_PARAM_STRING) {
        char *copy = fg_strdup(value);
        if (!copy)
            return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
        free(v->text);
        v->text = copy;
    }
    v->number = number;
    v->set = true;
    v->loc = keep_loc(graph, loc);
    graph->compiled = false;
    return true;
}

bool
fg_graph_apply_interactive(fg_graph *graph, char *applied, size_t size, cg_error *err)
{
    if (size)
        applied[0] = '\0';
    static const fg_source_loc interactive = { "the pass's interactive value", 0, 0 };
    for (int i = 0; i < graph->pass_count; i++) {
        fg_pass *pass = graph->passes[i];
        for (int k = 0; k < pass->type->param_count; k++) {
            const fg_param_desc *p = &pass->type->params[k];
            if (!p->interactive || pass->values[k].set || !fg_param_active(pass, p))
                continue;
            if (!fg_graph_set_param(graph, pass->name, p->name, p->interactive, &interactive, err))
                return false;
            size_t used = size ? strlen(applied) : 0;
            if (used < size)
                snprintf(applied + used, size - used, "%s%s.%s=%s", used ? ", " : "", pass->name, p->name,
                         p->interactive);
        }
    }
    return true;
}

bool
fg_graph_connect(fg_graph *graph, const char *pass_name, const char *input, const char *source,
                 const fg_source_loc *loc, cg_error *err)
{
    char at[512];
    fg_loc_prefix(loc, at, sizeof at);
    fg_pass *pass = fg_graph_find_pass(graph, pass_name);
    if (!pass)
        return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%sno pass named '%s'", at, pass_name);
    for (int i = 0; i < pass->connection_count; i++)
        if (!strcmp(pass->connections[i].input, input))
            return cg_fail(err, CG_ERR_GRAPH_DUPLICATE, "%spass '%s': input '%s' is connected twice",
                           at, pass_name, input);
    /* "pass", "pass.output", each optionally followed by "@previous". */
    char buf[512];
    if (strlen(source) >= sizeof buf)
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%spass '%s' input '%s': source too long", at,
                       pass_name, input);
    strcpy(buf, source);
    bool previous = false;
    char *suffix = strchr(buf, '@');
    if (suffix) {
        if (strcmp(suffix, "@previous"))
            return cg_fail(err, CG_ERR_GRAPH_SCHEMA,
                           "%spass '%s' input '%s': '%s': expected 'pass.output' or "
                           "'pass.output@previous'", at, pass_name, input, source);
        previous = true;
        *suffix = '\0';
    }
    char source_pass[sizeof buf];
    const char *output = fg_split_source(buf, source_pass, sizeof source_pass);
    if (!*source_pass || (output && (!*output || strchr(output, '.'))))
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA,
                       "%spass '%s' input '%s': '%s': expected 'pass.output' or 'pass'", at, pass_name,
                       input, source);
    if (!fg_grow((void **)&pass->connections, &pass->connection_cap, pass->connection_count + 1,
                 sizeof *pass->connections))
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    fg_connection *c = &pass->connections[pass->connection_count];
    memset(c, 0, sizeof *c);
    c->input = fg_strdup(input);
    c->source_pass = fg_strdup(source_pass);
    c->source_output = output ? fg_strdup(output) : NULL;
    c->previous = previous;
    c->loc = keep_loc(graph, loc);
    c->source_index = -1;
    if (!c->input || !c->source_pass || (output && !c->source_output)) {
        free(c->input);
        free(c->source_pass);
        free(c->source_output);
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    }
    pass->connection_count++;
    graph->compiled = false;
    return true;
}

bool
fg_graph_mark_output(fg_graph *graph, const char *source, const fg_source_loc *loc, cg_error *err)
{
    char at[512];
    fg_loc_prefix(loc, at, sizeof at);
    char pass_name[256];
    const char *output = fg_split_source(source, pass_name, sizeof pass_name);
    if (!output || !*pass_name || !*output || strchr(output, '.') || strchr(source, '@'))
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%soutput '%s': expected 'pass.output'", at, source);
    for (int i = 0; i < graph->output_count; i++)
        if (!strcmp(graph->outputs[i].source, source))
            return cg_fail(err, CG_ERR_GRAPH_DUPLICATE, "%soutput '%s' is marked twice", at, source);
    if (!fg_grow((void **)&graph->outputs, &graph->output_cap, graph->output_count + 1,
                 sizeof *graph->outputs))
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    fg_graph_output *out = &graph->outputs[graph->output_count];
    out->source = fg_strdup(source);
    if (!out->source)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory");
    out->loc = keep_loc(graph, loc);
    out->resource = -1;
    graph->output_count++;
    graph->compiled = false;
    return true;
}

/* ---------------------------------------------------------------- what a pass reads of itself */

const char *
fg_pass_name(const fg_pass *pass)
{
    return pass->name;
}

const fg_pass_type *
fg_pass_type_of(const fg_pass *pass)
{
    return pass->type;
}

const fg_frame *
fg_pass_frame(const fg_pass *pass)
{
    return &pass->graph->frame;
}

void
fg_pass_report_rebuilt(fg_pass *pass, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(pass->rebuilt, sizeof pass->rebuilt, format, args);
    va_end(args);
}

const char *
fg_pass_rebuilt(const fg_pass *pass)
{
    return pass->rebuilt;
}

void
fg_pass_report_reads(fg_pass *pass, GLuint buffer, const char *item)
{
    pass->reads_source = buffer;
    pass->reads_source_item = item ? item : "item";
}

bool
fg_pass_reads(const fg_pass *pass, double *reads, double *items, const char **item)
{
    if (reads)
        *reads = pass->reads_known ? pass->reads : 0.0;
    if (items)
        *items = pass->reads_known ? pass->reads_items : 0.0;
    if (item)
        *item = pass->reads_known ? pass->reads_item : NULL;
    return pass->reads_known;
}

static const char *
param_type_name(fg_param_type type)
{
    static const char *const names[] = { "int", "float", "bool", "enum", "string" };
    return (unsigned)type < 5 ? names[type] : "?";
}

/* A pass asking for a parameter its table lacks, or as the wrong type, is a bug in the pass,
 * not bad input: stop at once with a message that names it. */
static const fg_param_value *
param_value(const fg_pass *pass, const char *name, fg_param_type want, bool int_as_float)
{
    int index;
    const fg_param_desc *p = fg_param_find(pass->type, name, &index);
    if (!p) {
        fprintf(stderr, "conegraph: bug in pass type '%s': it reads parameter '%s' that its table "
                        "does not declare\n", pass->type->name, name);
        abort();
    }
    if (p->type != want && !(int_as_float && p->type == FG_PARAM_INT)) {
        fprintf(stderr, "conegraph: bug in pass type '%s': parameter '%s' is %s, read as %s\n",
                pass->type->name, name, param_type_name(p->type), param_type_name(want));
        abort();
    }
    return &pass->values[index];
}

int
fg_param_int(const fg_pass *pass, const char *name)
{
    return (int)param_value(pass, name, FG_PARAM_INT, false)->number;
}

float
fg_param_float(const fg_pass *pass, const char *name)
{
    return (float)param_value(pass, name, FG_PARAM_FLOAT, true)->number;
}

bool
fg_param_bool(const fg_pass *pass, const char *name)
{
    return param_value(pass, name, FG_PARAM_BOOL, false)->number != 0;
}

int
fg_param_enum(const fg_pass *pass, const char *name)
{
    return (int)param_value(pass, name, FG_PARAM_ENUM, false)->number;
}

const char *
fg_param_string(const fg_pass *pass, const char *name)
{
    return param_value(pass, name, FG_PARAM_STRING, false)->text;
}

/* ---------------------------------------------------------------- introspection */

int
fg_graph_pass_count(const fg_graph *graph)
{
    return graph->pass_count;
}

fg_pass *
fg_graph_pass_at(const fg_graph *graph, int index)
{
    return index >= 0 && index < graph->pass_count ? graph->passes[index] : NULL;
}

fg_pass *
fg_graph_find_pass(const fg_graph *graph, const char *name)
{
    for (int i = 0; i < graph->pass_count; i++)
        if (!strcmp(graph->passes[i]->name, name))
            return graph->passes[i];
    return NULL;
}

int
fg_graph_output_count(const fg_graph *graph)
{
    return graph->output_count;
}

const char *
fg_graph_output_at(const fg_graph *graph, int index)
{
    return index >= 0 && index < graph->output_count ? graph->outputs[index].source : NULL;
}
