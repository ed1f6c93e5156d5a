/* Reports of a compiled graph: resources, memory, the printed table, JSON and Graphviz DOT. */
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/fs.h"
#include "fg_internal.h"

int
fg_graph_resource_count(const fg_graph *graph)
{
    return graph->resource_count;
}

const fg_resource_info *
fg_graph_resource_at(const fg_graph *graph, int index)
{
    return index >= 0 && index < graph->resource_count ? &graph->resources[index].info : NULL;
}

int
fg_graph_find_resource_index(const fg_graph *graph, const char *source)
{
    for (int i = 0; i < graph->resource_count; i++)
        if (!strcmp(graph->resources[i].name, source))
            return i;
    return -1;
}

const fg_resource_info *
fg_graph_find_resource(const fg_graph *graph, const char *source)
{
    int index = fg_graph_find_resource_index(graph, source);
    return index >= 0 ? &graph->resources[index].info : NULL;
}

void
fg_graph_memory_report(const fg_graph *graph, fg_memory_report *out)
{
    memset(out, 0, sizeof *out);
    /* An in-place version shares its first version's storage by design, not by pooling:
     * count each chain once, and a double-buffered one twice. */
    for (int i = 0; i < graph->resource_count; i++) {
        const fg_res *r = &graph->resources[i];
        if (r->info.absent || r->version_of >= 0)
            continue;
        size_t copies = r->double_buffered ? 2 : 1;
        bool gi = false;
        for (int v = i; v >= 0; v = graph->resources[v].updated_by)
            gi |= graph->resources[v].info.desc.gi;
        out->resource_bytes += copies * r->info.bytes;
        if (gi)
            out->gi_bytes += copies * r->info.bytes;
    }
    for (int s = 0; s < graph->storage_count; s++)
        out->allocated_bytes += graph->storage[s].bytes;
    for (int k = 0; k < graph->order_count; k++) {
        size_t live = 0;
        for (int s = 0; s < graph->storage_count; s++)
            if (graph->storage[s].first_use <= k && k <= graph->storage[s].last_use)
                live += graph->storage[s].bytes;
        if (live > out->peak_bytes)
            out->peak_bytes = live;
    }
}

static void
describe_size(const fg_resource_desc *d, char *buf, size_t size)
{
    char fmt[32];
    if (d->kind == FG_BUFFER)
        snprintf(buf, size, "buffer");
    else if (d->kind == FG_TEXTURE_2D)
        snprintf(buf, size, "%s %dx%d", fg_format_name(d->format, fmt, sizeof fmt), d->width, d->height);
    else
        snprintf(buf, size, "%s %dx%dx%d%s", fg_format_name(d->format, fmt, sizeof fmt), d->width,
                 d->height, d->depth, d->kind == FG_TEXTURE_2D_ARRAY ? " layers" : "");
    if (d->levels > 1) {
        size_t len = strlen(buf);
        snprintf(buf + len, size - len, " %dL", d->levels);
    }
}

const char *
fg_pass_reads_text(const fg_pass *pass, char *buf, size_t size)
{
    double reads, items;
    const char *item;
    if (!fg_pass_reads(pass, &reads, &items, &item))
        snprintf(buf, size, "-");
    else if (items > 0)
        snprintf(buf, size, "%.4g M, %.4g a %s", reads * 1e-6, reads / items, item);
    else
        snprintf(buf, size, "%.4g M, no %s", reads * 1e-6, item);
    return buf;
}

const char *
fg_graph_reads_text(const fg_graph *graph, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (int k = 0; k < graph->order_count && len < size; k++) {
        const fg_pass *pass = graph->passes[graph->order[k]];
        char text[64];
        if (!fg_pass_reads(pass, NULL, NULL, NULL))
            continue;
        int n = snprintf(buf + len, size - len, "%s%s %s", len ? "; " : "", pass->name,
                         fg_pass_reads_text(pass, text, sizeof text));
        if (n < 0)
            break;
        len += (size_t)n;
    }
    return buf;
}

void
fg_graph_print_report(const fg_graph *graph, FILE *out)
{
    char a[64], b[64], c[64], d[64], e[64];
    fprintf(out, "%-4s %-20s %-16s %10s  %-26s %s\n", "#", "pass", "type", "ms", "texture reads", "barrier bits");
    double total = 0;
    bool timed = false;
    for (int k = 0; k < graph->order_count; k++) {
        const fg_pass *pass = graph->passes[graph->order[k]];
        if (pass->ms >= 0) {
            snprintf(a, sizeof a, "%.3f", pass->ms);
            total += pass->ms;
            timed = true;
        } else {
            snprintf(a, sizeof a, "-");
        }
        fg_pass_reads_text(pass, e, sizeof e);
        fprintf(out, "%-4d %-20s %-16s %10s  %-26s 0x%x%s%s\n", k, pass->name, pass->type->name, a, e,
                (unsigned)pass->barrier_bits, pass->rebuilt[0] ? "  rebuilt: " : "", pass->rebuilt);
    }
    if (timed)
        fprintf(out, "%-4s %-20s %-16s %10.3f\n", "", "total", "", total);
    for (int p = 0; p < graph->pass_count; p++) {
        const fg_pass *pass = graph->passes[p];
        if (pass->culled)
            fprintf(out, "culled %-20s %-16s %s\n", pass->name, pass->type->name, pass->cull_reason);
    }
    fprintf(out, "\n%-28s %-26s %12s %8s %10s\n", "resource", "format and size", "bytes", "storage",
            "lifetime");
    for (int i = 0; i < graph->resource_count; i++) {
        const fg_res *r = &graph->resources[i];
        if (r->info.absent)
            continue;
        describe_size(&r->info.desc, a, sizeof a);
        if (r->info.desc.kind == FG_BUFFER)
            snprintf(a, sizeof a, "buffer");
        if (r->double_buffered)
            snprintf(c, sizeof c, "%d+%d", r->info.storage, r->storage2);
        else
            snprintf(c, sizeof c, "%d", r->info.storage);
        snprintf(d, sizeof d, "%d-%d", r->info.first_use, r->info.last_use);
        fprintf(out, "%-28s %-26s %12s %8s %10s%s%s%s\n", r->name, a, fg_bytes_text(r->info.bytes, b, sizeof b),
                c, d, r->info.desc.persistent ? " persistent" : "", r->graph_output ? " output" : "",
                r->info.desc.gi ? " gi" : "");
    }
    fg_memory_report m;
    fg_graph_memory_report(graph, &m);
    fprintf(out, "\nmemory: resources %s, allocated %s (pool), peak %s, GI %s\n",
            fg_bytes_text(m.resource_bytes, a, sizeof a), fg_bytes_text(m.allocated_bytes, b, sizeof b),
            fg_bytes_text(m.peak_bytes, c, sizeof c), fg_bytes_text(m.gi_bytes, d, sizeof d));
}

static json_t *
report_json(const fg_graph *graph)
{
    json_t *root = json_object();
    json_t *passes = json_array();
    for (int p = 0; p < graph->pass_count; p++) {
        const fg_pass *pass = graph->passes[p];
        json_t *j = json_object();
        json_object_set_new(j, "name", json_string(pass->name));
        json_object_set_new(j, "type", json_string(pass->type->name));
        json_object_set_new(j, "position", json_integer(pass->position));
        json_object_set_new(j, "culled", json_boolean(pass->culled));
        if (pass->culled)
            json_object_set_new(j, "cull_reason", json_string(pass->cull_reason));
        json_object_set_new(j, "ms", pass->ms >= 0 ? json_real(pass->ms) : json_null());
        json_object_set_new(j, "barrier_bits", json_integer((json_int_t)pass->barrier_bits));
        json_object_set_new(j, "rebuilt", pass->rebuilt[0] ? json_string(pass->rebuilt) : json_null());
        double reads, items;
        const char *item;
        if (fg_pass_reads(pass, &reads, &items, &item)) {
            json_t *r = json_object();
            json_object_set_new(r, "reads", json_real(reads));
            json_object_set_new(r, "items", json_real(items));
            json_object_set_new(r, "item", json_string(item));
            json_object_set_new(j, "texture_reads", r);
        } else {
            json_object_set_new(j, "texture_reads", json_null());
        }
        json_array_append_new(passes, j);
    }
    json_object_set_new(root, "passes", passes);
    json_t *resources = json_array();
    for (int i = 0; i < graph->resource_count; i++) {
        const fg_res *r = &graph->resources[i];
        const fg_resource_desc *d = &r->info.desc;
        char fmt[32];
        json_t *j = json_object();
        json_object_set_new(j, "name", json_string(r->name));
        json_object_set_new(j, "kind", json_string(fg_kind_name(d->kind)));
        if (d->kind != FG_BUFFER) {
            json_object_set_new(j, "format", json_string(fg_format_name(d->format, fmt, sizeof fmt)));
            json_object_set_new(j, "width", json_integer(d->width));
            json_object_set_new(j, "height", json_integer(d->height));
            json_object_set_new(j, "depth", json_integer(d->depth));
            json_object_set_new(j, "levels", json_integer(d->levels));
        }
        json_object_set_new(j, "bytes", json_integer((json_int_t)r->info.bytes));
        json_object_set_new(j, "absent", json_boolean(r->info.absent));
        json_object_set_new(j, "persistent", json_boolean(d->persistent));
        json_object_set_new(j, "gi", json_boolean(d->gi));
        json_object_set_new(j, "output", json_boolean(r->graph_output));
        json_object_set_new(j, "storage", json_integer(r->info.storage));
        json_object_set_new(j, "first_use", json_integer(r->info.first_use));
        json_object_set_new(j, "last_use", json_integer(r->info.last_use));
        json_array_append_new(resources, j);
    }
    json_object_set_new(root, "resources", resources);
    fg_memory_report m;
    fg_graph_memory_report(graph, &m);
    json_t *memory = json_object();
    json_object_set_new(memory, "resource_bytes", json_integer((json_int_t)m.resource_bytes));
    json_object_set_new(memory, "allocated_bytes", json_integer((json_int_t)m.allocated_bytes));
    json_object_set_new(memory, "peak_bytes", json_integer((json_int_t)m.peak_bytes));
    json_object_set_new(memory, "gi_bytes", json_integer((json_int_t)m.gi_bytes));
    json_object_set_new(root, "memory", memory);
    json_object_set_new(root, "frames", json_integer((json_int_t)graph->frames_executed));
    return root;
}

bool
fg_graph_write_report_json(const fg_graph *graph, const char *path, cg_error *err)
{
    json_t *root = report_json(graph);
    cg_atomic_file f;
    if (!cg_atomic_open(&f, path, err)) {
        json_decref(root);
        return false;
    }
    int rc = json_dumpf(root, f.fp, JSON_INDENT(2) | JSON_PRESERVE_ORDER);
    json_decref(root);
    if (rc != 0 || fputc('\n', f.fp) == EOF) {
        cg_atomic_abort(&f);
        return cg_fail(err, CG_ERR_IO, "%s: cannot write the report", path);
    }
    return cg_atomic_commit(&f, err);
}

/* DOT strings are double-quoted: escape quotes and backslashes. */
static void
dot_text(FILE *out, const char *s)
{
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            fputc('\\', out);
        fputc(*s, out);
    }
}

void
fg_graph_write_dot(const fg_graph *graph, FILE *out)
{
    char a[64], b[64];
    fprintf(out, "digraph frame_graph {\n  rankdir=LR;\n  node [shape=box, fontname=\"Helvetica\"];\n"
                 "  edge [fontname=\"Helvetica\", fontsize=10];\n");
    for (int p = 0; p < graph->pass_count; p++) {
        const fg_pass *pass = graph->passes[p];
        fprintf(out, "  p%d [label=\"", p);
        dot_text(out, pass->name);
        fprintf(out, "\\n(");
        dot_text(out, pass->type->name);
        fprintf(out, ")");
        if (pass->culled) {
            fprintf(out, "\\nculled: ");
            dot_text(out, pass->cull_reason ? pass->cull_reason : "");
            fprintf(out, "\", style=dashed, color=grey, fontcolor=grey];\n");
        } else {
            if (pass->ms >= 0)
                fprintf(out, "\\n%.3f ms", pass->ms);
            fprintf(out, "\"%s];\n", pass->type->side_effect ? ", peripheries=2" : "");
        }
    }
    for (int p = 0; p < graph->pass_count; p++) {
        const fg_pass *pass = graph->passes[p];
        for (int c = 0; c < pass->connection_count; c++) {
            const fg_connection *conn = &pass->connections[c];
            if (conn->source_index < 0)
                continue;
            const fg_pass *source = graph->passes[conn->source_index];
            int in = -1;
            for (int i = 0; i < pass->input_count; i++)
                if (!strcmp(pass->inputs[i].name, conn->input))
                    in = i;
            fprintf(out, "  p%d -> p%d [label=\"", conn->source_index, p);
            if (in >= 0 && pass->inputs[in].source_output >= 0) {
                const fg_output *o = &source->outputs[pass->inputs[in].source_output];
                dot_text(out, o->name);
                describe_size(&o->desc, a, sizeof a);
                fprintf(out, "\\n%s\\n%s", o->desc.kind == FG_BUFFER ? "buffer" : a,
                        fg_bytes_text(fg_resource_bytes(&o->desc), b, sizeof b));
            } else {
                dot_text(out, conn->source_output ? conn->source_output : conn->input);
            }
            if (conn->previous)
                fprintf(out, "\\n@previous");
            fprintf(out, " -> ");
            dot_text(out, conn->input);
            fprintf(out, "\"");
            if (conn->previous)
                fprintf(out, ", style=dashed, constraint=false");
            if (pass->culled || source->culled)
                fprintf(out, ", color=grey, fontcolor=grey");
            fprintf(out, "];\n");
        }
    }
    for (int i = 0; i < graph->output_count; i++) {
        char pass_name[256];
        fg_split_source(graph->outputs[i].source, pass_name, sizeof pass_name);
        const fg_pass *pass = fg_graph_find_pass(graph, pass_name);
        fprintf(out, "  out%d [shape=ellipse, label=\"", i);
        dot_text(out, graph->outputs[i].source);
        fprintf(out, "\"];\n");
        if (pass)
            fprintf(out, "  p%d -> out%d;\n", pass->index, i);
    }
    fprintf(out, "}\n");
}
