/* Parameter tables: a value parsed and checked against its table entry, the checks that
 * fg_registry_add makes on a table, the dependencies between a pass's values, and the text
 * that `conegraph passes`, the docs and the error messages show. One reading of the table
 * for all of them, so that what is listed is what is accepted. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fg_internal.h"

/* ---------------------------------------------------------------- text helpers */

/* Appends to a NUL-terminated buffer, truncating at its end. */
static void
appendf(char *buf, size_t size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static void
appendf(char *buf, size_t size, const char *fmt, ...)
{
    size_t len = strlen(buf);
    if (len + 1 >= size)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf + len, size - len, fmt, ap);
    va_end(ap);
}

/* A number as a graph file would write it for this parameter. */
static void
append_number(char *buf, size_t size, const fg_param_desc *p, double v)
{
    if (p->type == FG_PARAM_INT)
        appendf(buf, size, "%.0f", v);
    else
        appendf(buf, size, "%g", v);
}

/* ---------------------------------------------------------------- choices */

int
fg_param_choice_count(const char *choices)
{
    if (!choices || !*choices)
        return 0;
    int n = 1;
    for (const char *c = choices; *c; c++)
        n += *c == '|';
    return n;
}

bool
fg_param_choice(const char *choices, int index, char *buf, size_t size)
{
    if (!choices || index < 0)
        return false;
    const char *start = choices;
    for (int i = 0; i < index; i++) {
        start = strchr(start, '|');
        if (!start)
            return false;
        start++;
    }
    const char *end = strchr(start, '|');
    size_t len = end ? (size_t)(end - start) : strlen(start);
    if (len >= size)
        len = size - 1;
    memcpy(buf, start, len);
    buf[len] = '\0';
    return true;
}

const fg_param_desc *
fg_param_find(const fg_pass_type *type, const char *name, int *index)
{
    for (int i = 0; i < type->param_count; i++) {
        if (type->params[i].name && !strcmp(type->params[i].name, name)) {
            if (index)
                *index = i;
            return &type->params[i];
        }
    }
    return NULL;
}

/* ---------------------------------------------------------------- values */

static bool
is_integral(double v)
{
    return isfinite(v) && v == floor(v);
}

static bool
is_power_of_two(double v)
{
    int exponent;
    return v >= 1 && isfinite(v) && frexp(v, &exponent) == 0.5;
}

static bool
is_numeric(const fg_param_desc *p)
{
    return p->type == FG_PARAM_INT || p->type == FG_PARAM_FLOAT;
}

/* Parses all of `text` as a finite decimal number. */
static bool
parse_number(const char *text, double *out)
{
    if (!*text)
        return false;
    /* strtod also takes "nan", "inf" and hex floats; a parameter is a plain decimal number. */
    for (const char *c = text; *c; c++)
        if (!strchr("0123456789+-.eE", *c))
            return false;
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (*end || errno == ERANGE || !isfinite(v))
        return false;
    *out = v;
    return true;
}

bool
fg_param_parse(const fg_param_desc *p, const char *text, double *out)
{
    switch (p->type) {
    case FG_PARAM_INT:
        return parse_number(text, out) && is_integral(*out);
    case FG_PARAM_FLOAT:
        return parse_number(text, out);
    case FG_PARAM_BOOL:
        if (!strcmp(text, "true") || !strcmp(text, "false")) {
            *out = !strcmp(text, "true");
            return true;
        }
        return false;
    case FG_PARAM_ENUM: {
        char choice[256];
        for (int c = 0; fg_param_choice(p->choices, c, choice, sizeof choice); c++)
            if (!strcmp(choice, text)) {
                *out = c;
                return true;
            }
        return false;
    }
    case FG_PARAM_STRING:
        *out = 0;
        return true;
    }
    return false;
}

bool
fg_param_accepts(const fg_param_desc *p, double v)
{
    if (!is_numeric(p))
        return true;
    if (!(v >= p->min && v <= p->max))
        return false;
    if (p->power_of_two && !is_power_of_two(v))
        return false;
    if (p->allowed.count > 0) {
        for (int i = 0; i < p->allowed.count; i++)
            if (p->allowed.values[i] == v)
                return true;
        return false;
    }
    return true;
}

const char *
fg_param_stage_name(fg_param_stage stage)
{
    switch (stage) {
    case FG_STAGE_PREPARE:
        return "prepare";
    case FG_STAGE_FRAME:
        return "frame";
    case FG_STAGE_GRAPH:
    default:
        return "graph";
    }
}

void
fg_param_values_text(const fg_param_desc *p, char *buf, size_t size)
{
    if (!size)
        return;
    buf[0] = '\0';
    switch (p->type) {
    case FG_PARAM_INT:
    case FG_PARAM_FLOAT:
        if (p->allowed.count > 0) {
            for (int i = 0; i < p->allowed.count; i++) {
                appendf(buf, size, "%s", i ? ", " : "");
                append_number(buf, size, p, p->allowed.values[i]);
            }
            return;
        }
        append_number(buf, size, p, p->min);
        appendf(buf, size, "..");
        append_number(buf, size, p, p->max);
        if (p->power_of_two)
            appendf(buf, size, ", power of two");
        return;
    case FG_PARAM_BOOL:
        snprintf(buf, size, "true|false");
        return;
    case FG_PARAM_ENUM:
        snprintf(buf, size, "%s", p->choices ? p->choices : "");
        return;
    case FG_PARAM_STRING:
        snprintf(buf, size, "any text");
        return;
    }
}

void
fg_param_expected(const fg_param_desc *p, char *buf, size_t size)
{
    char values[512];
    fg_param_values_text(p, values, sizeof values);
    switch (p->type) {
    case FG_PARAM_INT:
    case FG_PARAM_FLOAT:
        if (p->allowed.count > 0) {
            snprintf(buf, size, "one of %s", values);
        } else if (p->power_of_two) {
            buf[0] = '\0';
            appendf(buf, size, "a power of two in ");
            append_number(buf, size, p, p->min);
            appendf(buf, size, "..");
            append_number(buf, size, p, p->max);
        } else {
            snprintf(buf, size, "%s in %s", p->type == FG_PARAM_INT ? "an integer" : "a number", values);
        }
        return;
    case FG_PARAM_BOOL:
        snprintf(buf, size, "true or false");
        return;
    case FG_PARAM_ENUM: {
        buf[0] = '\0';
        appendf(buf, size, "one of ");
        char choice[256];
        for (int c = 0; fg_param_choice(p->choices, c, choice, sizeof choice); c++)
            appendf(buf, size, "%s%s", c ? ", " : "", choice);
        return;
    }
    case FG_PARAM_STRING:
        snprintf(buf, size, "text");
        return;
    }
}

/* ---------------------------------------------------------------- dependencies */

/* Splits active_when "PARAM" or "PARAM=A|B": the name into `name`, *alternatives at "A|B"
 * (NULL for a bare name). False when the name does not fit. */
static bool
split_when(const char *when, char *name, size_t size, const char **alternatives)
{
    const char *eq = strchr(when, '=');
    size_t len = eq ? (size_t)(eq - when) : strlen(when);
    if (len >= size)
        return false;
    memcpy(name, when, len);
    name[len] = '\0';
    *alternatives = eq ? eq + 1 : NULL;
    return true;
}

/* Whether `number` is one of "A|B" read as values of `target`. */
static bool
when_matches(const fg_param_desc *target, const char *alternatives, double number)
{
    if (!alternatives)
        return number != 0;
    const char *start = alternatives;
    for (;;) {
        const char *end = strchr(start, '|');
        size_t len = end ? (size_t)(end - start) : strlen(start);
        char token[256];
        if (len < sizeof token) {
            memcpy(token, start, len);
            token[len] = '\0';
            double v;
            if (fg_param_parse(target, token, &v) && v == number)
                return true;
        }
        if (!end)
            return false;
        start = end + 1;
    }
}

bool
fg_param_active_in(const fg_pass_type *type, const fg_param_desc *p, const fg_param_value *values)
{
    if (!p->active_when)
        return true;
    char name[256];
    const char *alternatives;
    int index;
    if (!split_when(p->active_when, name, sizeof name, &alternatives) || !fg_param_find(type, name, &index))
        return true; /* fg_registry_add refused such tables */
    return when_matches(&type->params[index], alternatives, values[index].number);
}

void
fg_param_dependency_text(const fg_param_desc *p, char *buf, size_t size)
{
    if (!size)
        return;
    buf[0] = '\0';
    if (p->active_when) {
        char name[256];
        const char *alternatives;
        if (split_when(p->active_when, name, sizeof name, &alternatives)) {
            appendf(buf, size, "only with %s = ", name);
            if (!alternatives) {
                appendf(buf, size, "true");
            } else {
                /* "A|B" as "A or B". */
                for (const char *c = alternatives; *c; c++) {
                    if (*c == '|')
                        appendf(buf, size, " or ");
                    else
                        appendf(buf, size, "%c", *c);
                }
            }
        }
    }
    const fg_param_bound *bounds[2] = { &p->greater_than, &p->less_than };
    for (int b = 0; b < 2; b++) {
        if (!bounds[b]->param)
            continue;
        appendf(buf, size, "%s%s than ", buf[0] ? "; " : "", b ? "less" : "greater");
        if (bounds[b]->scale != 0 && bounds[b]->scale != 1)
            appendf(buf, size, "%g x ", bounds[b]->scale);
        appendf(buf, size, "%s", bounds[b]->param);
    }
    if (p->interactive)
        appendf(buf, size, "%s%s in interactive applications unless set", buf[0] ? "; " : "", p->interactive);
}

/* ---------------------------------------------------------------- messages */

bool
fg_loc_is_assignment(const fg_source_loc *loc)
{
    return loc && loc->file && loc->line <= 0;
}

void
fg_param_lead(const fg_source_loc *loc, const char *pass, const char *param, const char *value,
              char *buf, size_t size)
{
    if (fg_loc_is_assignment(loc)) {
        snprintf(buf, size, "%s: ", loc->file);
        return;
    }
    char at[512];
    fg_loc_prefix(loc, at, sizeof at);
    snprintf(buf, size, "%s%s.%s = %s; ", at, pass, param, value);
}

/* Where a value came from: "set at g.json:3:5", "set by --set p.n=1", "its default", or ""
 * (set in code, without a location). */
static void
origin_text(const fg_param_value *v, char *buf, size_t size)
{
    if (!v->set)
        snprintf(buf, size, "its default");
    else if (fg_loc_is_assignment(&v->loc))
        snprintf(buf, size, "set by %s", v->loc.file);
    else if (v->loc.file)
        snprintf(buf, size, "set at %s:%d:%d", v->loc.file, v->loc.line, v->loc.column);
    else
        buf[0] = '\0';
}

/* p's value against bound b (greater: p > scale x other; else p < scale x other). */
static bool
check_bound(const fg_pass *pass, int index, const fg_param_bound *b, bool greater, cg_error *err)
{
    const fg_param_desc *p = &pass->type->params[index];
    int other;
    if (!b->param || !fg_param_find(pass->type, b->param, &other))
        return true;
    double scale = b->scale != 0 ? b->scale : 1;
    const fg_param_value *pv = &pass->values[index], *ov = &pass->values[other];
    double bound = scale * ov->number;
    if (greater ? pv->number > bound : pv->number < bound)
        return true;

    /* Reported where a value was written: this parameter's, else the other one's, read the
     * other way round (p > s x o is o < p / s), so that the message starts at what to fix. */
    bool flip = !pv->set && ov->set;
    const fg_param_desc *subject = flip ? &pass->type->params[other] : p;
    const fg_param_desc *against = flip ? p : &pass->type->params[other];
    const fg_param_value *sv = flip ? ov : pv, *av = flip ? pv : ov;
    double factor = flip ? 1 / scale : scale;
    const char *relation = (flip ? !greater : greater) ? "greater" : "less";
    char value[64] = "", lead[1200], limit[64] = "", against_value[64] = "", origin[600], expected[1024];
    append_number(value, sizeof value, subject, sv->number);
    fg_param_lead(sv->set ? &sv->loc : &pass->loc, pass->name, subject->name, value, lead, sizeof lead);
    append_number(limit, sizeof limit, against, factor * av->number);
    append_number(against_value, sizeof against_value, against, av->number);
    origin_text(av, origin, sizeof origin);
    if (factor == 1)
        snprintf(expected, sizeof expected, "%s than %s = %s%s%s%s", relation, against->name, limit,
                 origin[0] ? " (" : "", origin, origin[0] ? ")" : "");
    else
        snprintf(expected, sizeof expected, "%s than %g x %s = %s (%s = %s%s%s)", relation, factor,
                 against->name, limit, against->name, against_value, origin[0] ? ", " : "", origin);
    return cg_fail(err, CG_ERR_GRAPH_PARAM_RANGE, "%sexpected %s", lead, expected);
}

bool
fg_pass_check_params(const fg_pass *pass, cg_error *err)
{
    const fg_pass_type *type = pass->type;
    for (int i = 0; i < type->param_count; i++) {
        const fg_param_desc *p = &type->params[i];
        if (!p->greater_than.param && !p->less_than.param)
            continue;
        if (!fg_param_active_in(type, p, pass->values))
            continue;
        if (!check_bound(pass, i, &p->greater_than, true, err) || !check_bound(pass, i, &p->less_than, false, err))
            return false;
    }
    return true;
}

bool
fg_param_active(const fg_pass *pass, const fg_param_desc *desc)
{
    return fg_param_active_in(pass->type, desc, pass->values);
}

/* ---------------------------------------------------------------- table checks */

bool
fg_is_identifier(const char *s)
{
    if (!s || !*s)
        return false;
    for (const char *c = s; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
              *c == '_' || *c == '-'))
            return false;
    return true;
}

/* Allowed values, power of two and step hints of an int or float entry (range already sane). */
static bool
check_values(const fg_pass_type *type, const fg_param_desc *p, cg_error *err)
{
    bool numeric = is_numeric(p), integral = p->type == FG_PARAM_INT;
    if (!numeric && (p->allowed.count || p->allowed.values || p->power_of_two || p->step != 0 ||
                     p->step_doubles || p->greater_than.param || p->less_than.param))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter '%s': allowed values, power_of_two, step hints and "
                       "bounds by other parameters are for int and float parameters",
                       type->name, p->name);
    if (!numeric)
        return true;
    const fg_param_values *a = &p->allowed;
    if (a->count < 0 || (a->count > 0 && !a->values) || (a->count == 0 && a->values))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter '%s': allowed values %s (count %d)", type->name, p->name,
                       a->values ? "listed without a count" : "counted without a list", a->count);
    for (int i = 0; i < a->count; i++) {
        double v = a->values[i];
        if (!isfinite(v) || (integral && !is_integral(v)) || v < p->min || v > p->max)
            return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                           "pass type '%s': parameter '%s': allowed value %g is not %s within [%g, %g]",
                           type->name, p->name, v, integral ? "an integer" : "a number", p->min, p->max);
        if (i > 0 && !(v > a->values[i - 1]))
            return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                           "pass type '%s': parameter '%s': allowed values must increase (%g after %g)",
                           type->name, p->name, v, a->values[i - 1]);
    }
    if (p->power_of_two) {
        if (!integral)
            return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                           "pass type '%s': parameter '%s': power_of_two is for int parameters",
                           type->name, p->name);
        if (!is_power_of_two(p->min) || !is_power_of_two(p->max))
            return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                           "pass type '%s': parameter '%s': power_of_two needs a range whose bounds are "
                           "powers of two, not [%g, %g]", type->name, p->name, p->min, p->max);
        for (int i = 0; i < a->count; i++)
            if (!is_power_of_two(a->values[i]))
                return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                               "pass type '%s': parameter '%s': allowed value %g is not a power of two",
                               type->name, p->name, a->values[i]);
    }
    if (!fg_param_accepts(p, p->default_value))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter '%s': default %g is not %s", type->name, p->name,
                       p->default_value, a->count ? "one of the allowed values" : "a power of two");
    if (!isfinite(p->step) || p->step < 0 || (integral && !is_integral(p->step)) ||
        (p->step > 0 && p->step > p->max - p->min))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter '%s': step %g is not %s in (0, %g], nor 0 (the default)",
                       type->name, p->name, p->step, integral ? "an integer" : "a number", p->max - p->min);
    if ((p->step > 0 || p->step_doubles) && (a->count || p->power_of_two))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter '%s': a step hint has no use with allowed values or "
                       "power_of_two (they step to the next value)", type->name, p->name);
    if (p->step > 0 && p->step_doubles)
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter '%s': step and step_doubles exclude each other",
                       type->name, p->name);
    if (p->step_doubles && !(p->min > 0))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter '%s': step_doubles needs a range above 0, not [%g, %g]",
                       type->name, p->name, p->min, p->max);
    return true;
}

static bool
check_param(const fg_pass_type *type, int i, cg_error *err)
{
    const fg_param_desc *p = &type->params[i];
    if (!fg_is_identifier(p->name))
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter %d: name '%s' is not an identifier "
                       "(letters, digits, '_' and '-')", type->name, i, p->name ? p->name : "(null)");
    for (int j = 0; j < i; j++)
        if (!strcmp(type->params[j].name, p->name))
            return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type '%s': parameter '%s' is declared twice",
                           type->name, p->name);
    if (!p->doc || !*p->doc)
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type '%s': parameter '%s' has no doc line",
                       type->name, p->name);
    switch (p->type) {
    case FG_PARAM_INT:
    case FG_PARAM_FLOAT: {
        bool integral = p->type == FG_PARAM_INT;
        if (!isfinite(p->min) || !isfinite(p->max) || !isfinite(p->default_value) ||
            (integral && (!is_integral(p->min) || !is_integral(p->max) ||
                          !is_integral(p->default_value))))
            return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                           "pass type '%s': parameter '%s': default and range must be finite%s",
                           type->name, p->name, integral ? " integers" : " numbers");
        if (p->min > p->max || p->default_value < p->min || p->default_value > p->max)
            return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                           "pass type '%s': parameter '%s': default %g is not within [%g, %g]",
                           type->name, p->name, p->default_value, p->min, p->max);
        break;
    }
    case FG_PARAM_BOOL:
        if (p->default_value != 0 && p->default_value != 1)
            return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                           "pass type '%s': parameter '%s': a bool default is 0 or 1, not %g",
                           type->name, p->name, p->default_value);
        break;
    case FG_PARAM_ENUM: {
        int n = fg_param_choice_count(p->choices);
        if (!n)
            return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type '%s': parameter '%s': enum without choices",
                           type->name, p->name);
        char a[128], b[128];
        for (int c = 0; c < n; c++) {
            fg_param_choice(p->choices, c, a, sizeof a);
            if (!fg_is_identifier(a))
                return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                               "pass type '%s': parameter '%s': choice %d '%s' is not an identifier",
                               type->name, p->name, c, a);
            for (int d = 0; d < c; d++) {
                fg_param_choice(p->choices, d, b, sizeof b);
                if (!strcmp(a, b))
                    return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                                   "pass type '%s': parameter '%s': choice '%s' appears twice",
                                   type->name, p->name, a);
            }
        }
        if (!is_integral(p->default_value) || p->default_value < 0 || p->default_value >= n)
            return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                           "pass type '%s': parameter '%s': default index %g is not one of 0..%d (%s)",
                           type->name, p->name, p->default_value, n - 1, p->choices);
        break;
    }
    case FG_PARAM_STRING:
        break;
    default:
        return cg_fail(err, CG_ERR_PLUGIN_LOAD, "pass type '%s': parameter '%s': unknown type %d",
                       type->name, p->name, (int)p->type);
    }
    if (!check_values(type, p, err))
        return false;
    double v;
    if (p->interactive && (!fg_param_parse(p, p->interactive, &v) || !fg_param_accepts(p, v))) {
        char expected[1024];
        fg_param_expected(p, expected, sizeof expected);
        return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                       "pass type '%s': parameter '%s': interactive value \"%s\"; expected %s", type->name,
                       p->name, p->interactive, expected);
    }
    return true;
}

/* active_when and the bounds name other entries of the table (all entries checked singly). */
static bool
check_dependencies(const fg_pass_type *type, const fg_param_value *defaults, cg_error *err)
{
    for (int i = 0; i < type->param_count; i++) {
        const fg_param_desc *p = &type->params[i];
        if (p->active_when) {
            char name[256];
            const char *alternatives;
            int target;
            if (!split_when(p->active_when, name, sizeof name, &alternatives) ||
                !fg_param_find(type, name, &target) || target == i)
                return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                               "pass type '%s': parameter '%s': active_when \"%s\" does not name another "
                               "parameter (expected \"PARAM\" or \"PARAM=VALUE|VALUE\")",
                               type->name, p->name, p->active_when);
            const fg_param_desc *t = &type->params[target];
            if (!alternatives && t->type != FG_PARAM_BOOL)
                return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                               "pass type '%s': parameter '%s': active_when \"%s\": a bare name must be a "
                               "bool parameter; write \"%s=VALUE\"", type->name, p->name, p->active_when, name);
            if (alternatives && t->type != FG_PARAM_BOOL && t->type != FG_PARAM_ENUM && t->type != FG_PARAM_INT)
                return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                               "pass type '%s': parameter '%s': active_when \"%s\": '%s' must be an enum, "
                               "bool or int parameter", type->name, p->name, p->active_when, name);
            for (const char *start = alternatives; start;) {
                const char *end = strchr(start, '|');
                char token[256];
                size_t len = end ? (size_t)(end - start) : strlen(start);
                snprintf(token, sizeof token, "%.*s", (int)len, start);
                double v;
                if (!fg_param_parse(t, token, &v) || !fg_param_accepts(t, v))
                    return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                                   "pass type '%s': parameter '%s': active_when \"%s\": '%s' is not a value "
                                   "of '%s'", type->name, p->name, p->active_when, token, name);
                start = end ? end + 1 : NULL;
            }
        }
        const fg_param_bound *bounds[2] = { &p->greater_than, &p->less_than };
        for (int b = 0; b < 2; b++) {
            if (!bounds[b]->param)
                continue;
            int other;
            if (!fg_param_find(type, bounds[b]->param, &other) || other == i ||
                !is_numeric(&type->params[other]))
                return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                               "pass type '%s': parameter '%s': %s \"%s\" is not another int or float "
                               "parameter", type->name, p->name, b ? "less_than" : "greater_than",
                               bounds[b]->param);
            if (!isfinite(bounds[b]->scale) || bounds[b]->scale < 0)
                return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                               "pass type '%s': parameter '%s': %s scale %g is not a number above 0 "
                               "(or 0 for 1)", type->name, p->name, b ? "less_than" : "greater_than",
                               bounds[b]->scale);
            double bound = (bounds[b]->scale != 0 ? bounds[b]->scale : 1) * defaults[other].number;
            if (b ? !(p->default_value < bound) : !(p->default_value > bound))
                return cg_fail(err, CG_ERR_PLUGIN_LOAD,
                               "pass type '%s': parameter '%s': default %g is not %s than %g (from '%s')",
                               type->name, p->name, p->default_value, b ? "less" : "greater", bound,
                               bounds[b]->param);
        }
    }
    return true;
}

bool
fg_param_table_check(const fg_pass_type *type, cg_error *err)
{
    for (int i = 0; i < type->param_count; i++)
        if (!check_param(type, i, err))
            return false;
    fg_param_value *defaults = calloc((size_t)type->param_count + 1, sizeof *defaults);
    if (!defaults)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "out of memory checking pass type '%s'", type->name);
    for (int i = 0; i < type->param_count; i++)
        defaults[i].number = type->params[i].default_value;
    bool ok = check_dependencies(type, defaults, err);
    free(defaults);
    return ok;
}
