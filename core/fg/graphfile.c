/* Graph files: JSON (jansson) into an fg_graph, every error with file:line:column.
 *
 * jansson gives line and column for syntax errors only, not for the values it parsed, so a
 * small scanner walks the (already valid) text alongside and records where every key and
 * value starts. The scanner also finds duplicate keys, which jansson would silently merge. */
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/fs.h"
#include "cg/graphfile.h"
#include "fg_internal.h"

/* ---------------------------------------------------------------- where things are */

typedef struct jpos {
    int line, column;           /* where the value starts */
    int key_line, key_column;   /* where its key starts (object members) */
    char *key;                  /* decoded key (object members) */
    const char *text;           /* the value's source text */
    size_t length;
    struct jpos *children;
    int count, cap;
} jpos;

typedef struct scanner {
    const char *p, *end;
    int line, column;
    const char *name;
    cg_error *err;
} scanner;

static void
jpos_free(jpos *node)
{
    for (int i = 0; i < node->count; i++)
        jpos_free(&node->children[i]);
    free(node->children);
    free(node->key);
}

static void
advance(scanner *s)
{
    if (*s->p == '\n') {
        s->line++;
        s->column = 1;
    } else if (((unsigned char)*s->p & 0xC0) != 0x80) {
        s->column++; /* a UTF-8 continuation byte does not start a new column */
    }
    s->p++;
}

static void
skip_space(scanner *s)
{
    while (s->p < s->end && (*s->p == ' ' || *s->p == '\t' || *s->p == '\n' || *s->p == '\r'))
        advance(s);
}

static int
hex_value(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return 0;
}

static unsigned
read_hex4(scanner *s)
{
    unsigned v = 0;
    for (int i = 0; i < 4 && s->p < s->end; i++) {
        v = v * 16 + (unsigned)hex_value(*s->p);
        advance(s);
    }
    return v;
}

static size_t
put_utf8(char *out, unsigned cp)
{
    if (cp < 0x80) {
        out[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        out[0] = (char)(0xC0 | (cp >> 6));
        out[1] = (char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | (cp >> 12));
        out[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
        out[2] = (char)(0x80 | (cp & 0x3F));
        return 3;
    }
    out[0] = (char)(0xF0 | (cp >> 18));
    out[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
    out[2] = (char)(0x80 | ((cp >> 6) & 0x3F));
    out[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

/* At the opening quote; returns the decoded string (escapes resolved). */
static char *
scan_string(scanner *s)
{
    const char *start = s->p;
    advance(s);
    char *out = malloc((size_t)(s->end - start) + 1);
    size_t len = 0;
    while (s->p < s->end && *s->p != '"') {
        if (*s->p != '\\') {
            if (out)
                out[len++] = *s->p;
            advance(s);
            continue;
        }
        advance(s);
        char c = s->p < s->end ? *s->p : '\0';
        advance(s);
        unsigned cp = (unsigned char)c;
        switch (c) {
        case 'b': cp = '\b'; break;
        case 'f': cp = '\f'; break;
        case 'n': cp = '\n'; break;
        case 'r': cp = '\r'; break;
        case 't': cp = '\t'; break;
        case 'u':
            cp = read_hex4(s);
            if (cp >= 0xD800 && cp < 0xDC00 && s->p + 1 < s->end && s->p[0] == '\\' && s->p[1] == 'u') {
                advance(s);
                advance(s);
                unsigned low = read_hex4(s);
                cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
            }
            break;
        default: break;
        }
        if (out)
            len += put_utf8(out + len, cp);
    }
    if (s->p < s->end)
        advance(s);
    if (out)
        out[len] = '\0';
    return out;
}

static bool scan_value(scanner *s, jpos *node);

static bool
scan_container(scanner *s, jpos *node, bool object)
{
    char close = object ? '}' : ']';
    advance(s);
    skip_space(s);
    while (s->p < s->end && *s->p != close) {
        if (!fg_grow((void **)&node->children, &node->cap, node->count + 1, sizeof *node->children))
            return cg_fail(s->err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory", s->name);
        jpos *child = &node->children[node->count++];
        memset(child, 0, sizeof *child);
        if (object) {
            child->key_line = s->line;
            child->key_column = s->column;
            child->key = scan_string(s);
            if (!child->key)
                return cg_fail(s->err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory", s->name);
            for (int i = 0; i < node->count - 1; i++)
                if (!strcmp(node->children[i].key, child->key))
                    return cg_fail(s->err, CG_ERR_GRAPH_DUPLICATE,
                                   "%s:%d:%d: duplicate key \"%s\" (first at line %d, column %d)", s->name,
                                   child->key_line, child->key_column, child->key,
                                   node->children[i].key_line, node->children[i].key_column);
            skip_space(s);
            if (s->p < s->end) /* ':' */
                advance(s);
            skip_space(s);
        }
        if (!scan_value(s, child))
            return false;
        skip_space(s);
        if (s->p < s->end && *s->p == ',') {
            advance(s);
            skip_space(s);
        }
    }
    if (s->p < s->end)
        advance(s);
    return true;
}

static bool
scan_value(scanner *s, jpos *node)
{
    node->line = s->line;
    node->column = s->column;
    node->text = s->p;
    bool ok = true;
    if (s->p >= s->end)
        return cg_fail(s->err, CG_ERR_GRAPH_SYNTAX, "%s:%d:%d: unexpected end of text", s->name, s->line,
                       s->column);
    if (*s->p == '{' || *s->p == '[') {
        ok = scan_container(s, node, *s->p == '{');
    } else if (*s->p == '"') {
        free(scan_string(s));
    } else {
        while (s->p < s->end && strchr("+-.0123456789eEtruefalsn", *s->p))
            advance(s);
    }
    node->length = (size_t)(s->p - node->text);
    return ok;
}

static const jpos *
member(const jpos *object, const char *key)
{
    for (int i = 0; i < object->count; i++)
        if (!strcmp(object->children[i].key, key))
            return &object->children[i];
    return NULL;
}

static fg_source_loc
value_loc(const char *name, const jpos *node)
{
    fg_source_loc loc = { name, node ? node->line : 1, node ? node->column : 1 };
    return loc;
}

static fg_source_loc
key_loc(const char *name, const jpos *node)
{
    fg_source_loc loc = { name, node->key_line, node->key_column };
    return loc;
}

/* ---------------------------------------------------------------- reading */

static const char *
json_type_name(const json_t *v)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return "an object";
    case JSON_ARRAY: return "an array";
    case JSON_STRING: return "a string";
    case JSON_INTEGER:
    case JSON_REAL: return "a number";
    case JSON_TRUE:
    case JSON_FALSE: return "a bool";
    case JSON_NULL: return "null";
    }
    return "a value";
}

static bool
check_keys(const jpos *object, const char *const *allowed, const char *what, const char *name,
           cg_error *err)
{
    for (int i = 0; i < object->count; i++) {
        bool known = false;
        for (int k = 0; allowed[k] && !known; k++)
            known = !strcmp(object->children[i].key, allowed[k]);
        if (known)
            continue;
        char list[256];
        size_t len = 0;
        for (int k = 0; allowed[k]; k++) {
            int n = snprintf(list + len, sizeof list - len, "%s\"%s\"", k ? ", " : "", allowed[k]);
            if (n > 0 && (size_t)n < sizeof list - len)
                len += (size_t)n;
        }
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: %s: unknown key \"%s\" (expected one of %s)",
                       name, object->children[i].key_line, object->children[i].key_column, what,
                       object->children[i].key, list);
    }
    return true;
}

static bool
set_param_from_json(fg_graph *graph, const char *pass_name, const jpos *pos, json_t *value,
                    const char *name, cg_error *err)
{
    const char *param = pos->key;
    fg_source_loc at_key = key_loc(name, pos), at_value = value_loc(name, pos);
    const fg_pass *pass = fg_graph_find_pass(graph, pass_name);
    const fg_param_desc *p = fg_param_find(fg_pass_type_of(pass), param, NULL);
    if (!p) /* the same call reports the unknown parameter, with the list of known ones */
        return fg_graph_set_param(graph, pass_name, param, "", &at_key, err);
    char text[512];
    const char *expected = NULL;
    switch (p->type) {
    case FG_PARAM_INT:
    case FG_PARAM_FLOAT:
        if (!json_is_number(value))
            expected = p->type == FG_PARAM_INT ? "an integer" : "a number";
        break;
    case FG_PARAM_BOOL:
        if (!json_is_boolean(value))
            expected = "true or false";
        break;
    case FG_PARAM_ENUM:
        if (!json_is_string(value) && !json_is_number(value))
            expected = "a string naming a choice";
        break;
    case FG_PARAM_STRING:
        if (!json_is_string(value))
            expected = "a string";
        break;
    }
    if (expected) {
        char values[1024];
        if (p->type == FG_PARAM_STRING)
            snprintf(values, sizeof values, "%s", expected);
        else
            fg_param_expected(p, values, sizeof values);
        return cg_fail(err, CG_ERR_GRAPH_PARAM_TYPE, "%s:%d:%d: %s.%s: expected %s, got %s", name,
                       at_value.line, at_value.column, pass_name, param, values, json_type_name(value));
    }
    if (json_is_string(value)) {
        return fg_graph_set_param(graph, pass_name, param, json_string_value(value), &at_value, err);
    } else if (json_is_boolean(value)) {
        snprintf(text, sizeof text, "%s", json_is_true(value) ? "true" : "false");
    } else {
        /* Numbers as written, so that messages quote the file and no digits are invented. */
        snprintf(text, sizeof text, "%.*s", (int)pos->length, pos->text);
    }
    return fg_graph_set_param(graph, pass_name, param, text, &at_value, err);
}

static bool
read_pass(fg_graph *graph, const jpos *pos, json_t *value, const char *name, cg_error *err)
{
    const char *pass_name = pos->key;
    static const char *const pass_keys[] = { "type", "params", "inputs", NULL };
    char what[300];
    snprintf(what, sizeof what, "pass '%s'", pass_name);
    if (!check_keys(pos, pass_keys, what, name, err))
        return false;
    json_t *params = json_object_get(value, "params");
    const jpos *params_pos = member(pos, "params");
    if (params) {
        if (!json_is_object(params))
            return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: pass '%s' \"params\": expected an object, got %s",
                           name, params_pos->line, params_pos->column, pass_name, json_type_name(params));
        for (int i = 0; i < params_pos->count; i++) {
            const jpos *p = &params_pos->children[i];
            if (!set_param_from_json(graph, pass_name, p, json_object_get(params, p->key), name, err))
                return false;
        }
    }
    json_t *inputs = json_object_get(value, "inputs");
    const jpos *inputs_pos = member(pos, "inputs");
    if (inputs) {
        if (!json_is_object(inputs))
            return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: pass '%s' \"inputs\": expected an object, got %s",
                           name, inputs_pos->line, inputs_pos->column, pass_name, json_type_name(inputs));
        for (int i = 0; i < inputs_pos->count; i++) {
            const jpos *in = &inputs_pos->children[i];
            json_t *source = json_object_get(inputs, in->key);
            fg_source_loc loc = value_loc(name, in);
            if (!json_is_string(source))
                return cg_fail(err, CG_ERR_GRAPH_SCHEMA,
                               "%s:%d:%d: pass '%s' input '%s': expected a string \"pass.output\", got %s",
                               name, loc.line, loc.column, pass_name, in->key, json_type_name(source));
            if (!fg_graph_connect(graph, pass_name, in->key, json_string_value(source), &loc, err))
                return false;
        }
    }
    return true;
}

static bool
read_graph(fg_graph *graph, json_t *root, const jpos *top, const char *name, cg_error *err)
{
    static const char *const top_keys[] = { "version", "description", "sky", "passes", "outputs", NULL };
    if (!check_keys(top, top_keys, "graph", name, err))
        return false;

    json_t *version = json_object_get(root, "version");
    const jpos *version_pos = member(top, "version");
    if (!version)
        return cg_fail(err, CG_ERR_GRAPH_VERSION, "%s:%d:%d: no \"version\": expected \"version\": 1", name,
                       top->line, top->column);
    if (!json_is_integer(version) || json_integer_value(version) != 1)
        return cg_fail(err, CG_ERR_GRAPH_VERSION,
                       "%s:%d:%d: \"version\" is %.*s; this conegraph reads graph files of version 1", name,
                       version_pos->line, version_pos->column, (int)version_pos->length, version_pos->text);
    json_t *description = json_object_get(root, "description");
    if (description && !json_is_string(description)) {
        const jpos *d = member(top, "description");
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: \"description\": expected a string, got %s", name,
                       d->line, d->column, json_type_name(description));
    }

    /* The sky the graph asks of the scene: --sky's syntax, as a string, or a number for a
     * grey uniform sky. */
    json_t *sky = json_object_get(root, "sky");
    if (sky) {
        const jpos *sky_pos = member(top, "sky");
        char text[256];
        if (json_is_string(sky))
            snprintf(text, sizeof text, "%s", json_string_value(sky));
        else if (json_is_number(sky))
            snprintf(text, sizeof text, "%.*s", (int)sky_pos->length, sky_pos->text);
        else
            return cg_fail(err, CG_ERR_GRAPH_SCHEMA,
                           "%s:%d:%d: \"sky\": expected a string (\"none\", \"R,G,B\", \"L\" or "
                           "\"preetham[:TURBIDITY[,SCALE]]\") or a number, got %s",
                           name, sky_pos->line, sky_pos->column, json_type_name(sky));
        cg_error why = { 0 };
        if (!cg_sky_parse(text, &graph->sky, &why))
            return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: %s", name, sky_pos->line, sky_pos->column,
                           why.message);
        graph->has_sky = true;
    }

    json_t *passes = json_object_get(root, "passes");
    const jpos *passes_pos = member(top, "passes");
    if (!passes)
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: no \"passes\": expected an object of passes",
                       name, top->line, top->column);
    if (!json_is_object(passes))
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: \"passes\": expected an object, got %s", name,
                       passes_pos->line, passes_pos->column, json_type_name(passes));
    /* All passes first, so that inputs may name passes written further down. */
    for (int i = 0; i < passes_pos->count; i++) {
        const jpos *p = &passes_pos->children[i];
        json_t *value = json_object_get(passes, p->key);
        if (!json_is_object(value))
            return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: pass '%s': expected an object, got %s", name,
                           p->line, p->column, p->key, json_type_name(value));
        json_t *type = json_object_get(value, "type");
        const jpos *type_pos = member(p, "type");
        if (!json_is_string(type))
            return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: pass '%s': expected \"type\": \"TYPE\"%s", name,
                           type_pos ? type_pos->line : p->line, type_pos ? type_pos->column : p->column,
                           p->key, type ? ", a string" : "");
        /* An unknown type is reported where the type is written; the pass is located at its name. */
        fg_source_loc loc = fg_registry_find(graph->registry, json_string_value(type))
                                ? key_loc(name, p)
                                : value_loc(name, type_pos);
        if (!fg_graph_add_pass(graph, p->key, json_string_value(type), &loc, err))
            return false;
    }
    for (int i = 0; i < passes_pos->count; i++) {
        const jpos *p = &passes_pos->children[i];
        if (!read_pass(graph, p, json_object_get(passes, p->key), name, err))
            return false;
    }

    json_t *outputs = json_object_get(root, "outputs");
    const jpos *outputs_pos = member(top, "outputs");
    if (!outputs)
        return cg_fail(err, CG_ERR_GRAPH_NO_OUTPUT,
                       "%s:%d:%d: no \"outputs\": expected a list of \"pass.output\" to compute", name,
                       top->line, top->column);
    if (!json_is_array(outputs))
        return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: \"outputs\": expected an array, got %s", name,
                       outputs_pos->line, outputs_pos->column, json_type_name(outputs));
    if (json_array_size(outputs) == 0)
        return cg_fail(err, CG_ERR_GRAPH_NO_OUTPUT,
                       "%s:%d:%d: \"outputs\" is empty: expected at least one \"pass.output\"", name,
                       outputs_pos->line, outputs_pos->column);
    for (int i = 0; i < outputs_pos->count; i++) {
        const jpos *o = &outputs_pos->children[i];
        json_t *value = json_array_get(outputs, (size_t)i);
        fg_source_loc loc = value_loc(name, o);
        if (!json_is_string(value))
            return cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: output %d: expected \"pass.output\", got %s",
                           name, loc.line, loc.column, i, json_type_name(value));
        if (!fg_graph_mark_output(graph, json_string_value(value), &loc, err))
            return false;
    }
    return true;
}

bool
fg_graph_load_string(fg_graph *graph, const char *json, const char *name, cg_error *err)
{
    if (!name)
        name = "(graph)";
    json_error_t jerr;
    size_t length = strlen(json);
    json_t *root = json_loadb(json, length, 0, &jerr);
    if (!root)
        return cg_fail(err, CG_ERR_GRAPH_SYNTAX, "%s:%d:%d: %s", name, jerr.line > 0 ? jerr.line : 1,
                       jerr.column > 0 ? jerr.column : 1, jerr.text);
    scanner s = { json, json + length, 1, 1, name, err };
    skip_space(&s);
    jpos top;
    memset(&top, 0, sizeof top);
    bool ok = scan_value(&s, &top);
    if (ok && !json_is_object(root))
        ok = cg_fail(err, CG_ERR_GRAPH_SCHEMA, "%s:%d:%d: expected an object { \"version\": 1, ... }, got %s",
                     name, top.line, top.column, json_type_name(root));
    if (ok)
        ok = read_graph(graph, root, &top, name, err);
    jpos_free(&top);
    json_decref(root);
    return ok;
}

bool
fg_graph_load_file(fg_graph *graph, const char *path, cg_error *err)
{
    char *text;
    size_t size;
    if (!cg_read_file(path, &text, &size, err))
        return false;
    if (strlen(text) != size) {
        free(text);
        return cg_fail(err, CG_ERR_GRAPH_SYNTAX, "%s:1:1: the file contains a NUL byte", path);
    }
    bool ok = fg_graph_load_string(graph, text, path, err);
    free(text);
    return ok;
}

bool
fg_graph_file_sky(const fg_graph *graph, cg_sky *out)
{
    if (graph->has_sky)
        *out = graph->sky;
    return graph->has_sky;
}

bool
fg_graph_apply_override(fg_graph *graph, const char *assignment, cg_error *err)
{
    const char *eq = strchr(assignment, '=');
    const char *dot = strchr(assignment, '.');
    if (!eq || !dot || dot > eq || dot == assignment || dot + 1 == eq)
        return cg_fail(err, CG_ERR_USAGE, "--set %s: expected PASS.PARAM=VALUE", assignment);
    char pass[256], param[256];
    snprintf(pass, sizeof pass, "%.*s", (int)(dot - assignment), assignment);
    snprintf(param, sizeof param, "%.*s", (int)(eq - dot - 1), dot + 1);
    /* The place is the assignment itself: messages quote it instead of a file line, and a
     * dependency checked at compile points back at it. */
    char place[1200];
    snprintf(place, sizeof place, "--set %s", assignment);
    fg_source_loc loc = { place, 0, 0 };
    if (!fg_graph_find_pass(graph, pass)) {
        char names[1024] = "";
        size_t len = 0;
        for (int i = 0; i < fg_graph_pass_count(graph) && len < sizeof names; i++) {
            int n = snprintf(names + len, sizeof names - len, "%s%s", i ? ", " : "",
                             fg_pass_name(fg_graph_pass_at(graph, i)));
            len += n > 0 ? (size_t)n : 0;
        }
        return cg_fail(err, CG_ERR_GRAPH_DANGLING, "%s: the graph has no pass named '%s' (its passes: %s)", place,
                       pass, names);
    }
    return fg_graph_set_param(graph, pass, param, eq + 1, &loc, err);
}
