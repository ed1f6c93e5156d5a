/* The demo's parameter controls: see demo_params.h. */
#include "demo_params.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Values read back through fg_param_float are floats: compare and snap with this slack. */
#define VALUE_SLACK 1e-5

/* Steps that move along a list rather than by an amount. */
static bool
lists_values(const fg_param_desc *desc)
{
    return desc->allowed.count > 0 || (desc->type == FG_PARAM_INT && desc->power_of_two);
}

static bool
doubles(const fg_param_desc *desc)
{
    return desc->step_doubles && !lists_values(desc);
}

/* The largest 1, 2 or 5 x 10^k not above x (x > 0). */
static double
nice_step_below(double x)
{
    double power = pow(10.0, floor(log10(x)));
    /* log10 rounding may put x just under `power`. */
    if (power > x * (1 + 1e-12))
        power /= 10;
    double mantissa = x / power;
    if (mantissa >= 5 - 1e-9)
        return 5 * power;
    if (mantissa >= 2 - 1e-9)
        return 2 * power;
    return power;
}

double
demo_param_step_size(const fg_param_desc *desc, double value)
{
    if (desc->type != FG_PARAM_INT && desc->type != FG_PARAM_FLOAT)
        return 0;
    if (lists_values(desc) || doubles(desc))
        return 0;
    if (desc->step > 0)
        return desc->step;
    if (desc->type == FG_PARAM_INT)
        return 1;
    double width = desc->max - desc->min;
    if (width <= 1000)
        return width > 0 ? nice_step_below(width / 50) : 0;
    double magnitude = fabs(value) > 1 ? fabs(value) : 1;
    return nice_step_below(magnitude / 4);
}

/* The next value of the table's list (allowed values, or the powers of two in the range)
 * above `value` (direction > 0) or below it; false at the end of the list. */
static bool
next_listed(const fg_param_desc *desc, double value, int direction, double *out)
{
    double slack = VALUE_SLACK * (fabs(value) > 1 ? fabs(value) : 1);
    if (desc->allowed.count > 0) {
        const fg_param_values *a = &desc->allowed;
        if (direction > 0) {
            for (int i = 0; i < a->count; i++)
                if (a->values[i] > value + slack) {
                    *out = a->values[i];
                    return true;
                }
        } else {
            for (int i = a->count - 1; i >= 0; i--)
                if (a->values[i] < value - slack) {
                    *out = a->values[i];
                    return true;
                }
        }
        return false;
    }
    /* Powers of two: the range's bounds are powers of two too (fg_registry_add checks). */
    if (direction > 0) {
        double p = desc->min;
        while (p <= value + slack && p < desc->max)
            p *= 2;
        if (p > desc->max || p <= value + slack)
            return false;
        *out = p;
    } else {
        double p = desc->max;
        while (p >= value - slack && p > desc->min)
            p /= 2;
        if (p < desc->min || p >= value - slack)
            return false;
        *out = p;
    }
    return true;
}

static int
choice_count(const char *choices)
{
    int n = choices && *choices ? 1 : 0;
    for (const char *c = choices; c && *c; c++)
        n += *c == '|';
    return n;
}

/* Copies choice `index` of "a|b|c"; false when there is no such choice. */
static bool
choice_at(const char *choices, int index, char *out, size_t size)
{
    const char *start = choices;
    for (int i = 0; i < index && start; i++) {
        start = strchr(start, '|');
        if (start)
            start++;
    }
    if (!start || !size)
        return false;
    size_t len = strcspn(start, "|");
    if (len >= size)
        len = size - 1;
    memcpy(out, start, len);
    out[len] = '\0';
    return true;
}

bool
demo_param_step(const fg_param_desc *desc, double value, int direction, double *out)
{
    if (direction == 0)
        return false;
    double next = value;
    switch (desc->type) {
    case FG_PARAM_BOOL:
        next = value != 0 ? 0 : 1;
        break;
    case FG_PARAM_ENUM: {
        int n = choice_count(desc->choices);
        if (n < 2)
            return false;
        int index = (int)value;
        next = (double)(((index + (direction > 0 ? 1 : -1)) % n + n) % n);
        break;
    }
    case FG_PARAM_INT:
    case FG_PARAM_FLOAT: {
        if (lists_values(desc))
            return next_listed(desc, value, direction, out);
        if (doubles(desc)) {
            next = direction > 0 ? value * 2 : value / 2;
            if (desc->type == FG_PARAM_INT)
                next = floor(next);
            break;
        }
        double step = demo_param_step_size(desc, value);
        if (step <= 0)
            return false;
        /* Land on a multiple of the step, so that 0.25 + 0.05 is 0.3 and stays on the grid. */
        double units = value / step;
        next = direction > 0 ? (floor(units + VALUE_SLACK) + 1) * step
                             : (ceil(units - VALUE_SLACK) - 1) * step;
        break;
    }
    case FG_PARAM_STRING:
        return false;
    }
    if (desc->type == FG_PARAM_INT || desc->type == FG_PARAM_FLOAT) {
        /* The range stops the step: the last one lands on the bound. */
        if (next > desc->max)
            next = desc->max;
        if (next < desc->min)
            next = desc->min;
        double slack = VALUE_SLACK * (fabs(value) > 1 ? fabs(value) : 1);
        if (fabs(next - value) <= slack)
            return false;
    }
    *out = next;
    return true;
}

void
demo_param_format(const fg_param_desc *desc, double value, char *out, size_t size)
{
    switch (desc->type) {
    case FG_PARAM_INT:
        snprintf(out, size, "%.0f", value);
        break;
    case FG_PARAM_FLOAT: {
        /* Short text when it parses back inside the range, else every digit. */
        snprintf(out, size, "%.9g", value);
        double back = strtod(out, NULL);
        if (back < desc->min || back > desc->max)
            snprintf(out, size, "%.17g", value);
        break;
    }
    case FG_PARAM_BOOL:
        snprintf(out, size, "%s", value != 0 ? "true" : "false");
        break;
    case FG_PARAM_ENUM:
        if (!choice_at(desc->choices, (int)value, out, size))
            snprintf(out, size, "%d", (int)value);
        break;
    case FG_PARAM_STRING:
        snprintf(out, size, "%s", "");
        break;
    }
}

double
demo_param_snap(const fg_param_desc *desc, double value)
{
    if (desc->type != FG_PARAM_INT && desc->type != FG_PARAM_FLOAT)
        return value;
    if (value < desc->min)
        value = desc->min;
    if (value > desc->max)
        value = desc->max;
    double step = demo_param_step_size(desc, value);
    if (step > 0)
        value = round(value / step) * step;
    if (desc->type == FG_PARAM_INT)
        value = round(value);
    /* A bound off the grid (a range of -1..65535 stepped by 2) stays reachable. */
    if (value < desc->min)
        value = desc->min;
    if (value > desc->max)
        value = desc->max;
    return value;
}

/* Appends the values Left/Right reach from out->values[out->count - 1] upwards; false when
 * there are more than fit. */
static bool
walk_up(const fg_param_desc *desc, demo_control *out)
{
    for (double next; demo_param_step(desc, out->values[out->count - 1], 1, &next);) {
        if (out->count == DEMO_CONTROL_MAX_ENTRIES)
            return false;
        out->values[out->count++] = next;
    }
    return true;
}

/* The entries of a parameter that steps along a list: the allowed values, the powers of two
 * from the range's lower bound (a power of two), or the doublings and halvings of `value`;
 * false when there are more than fit. */
static bool
list_entries(const fg_param_desc *desc, double value, demo_control *out)
{
    out->count = 0;
    if (desc->allowed.count > 0) {
        if (desc->allowed.count > DEMO_CONTROL_MAX_ENTRIES)
            return false;
        for (int i = 0; i < desc->allowed.count; i++)
            out->values[out->count++] = desc->allowed.values[i];
        return true;
    }
    if (doubles(desc)) {
        /* Halving and doubling do not retrace each other (an int halves with rounding down:
         * 100, 50, 25, 12), so the list is what Left reaches from the value, the value, and
         * what Right reaches. */
        double below[DEMO_CONTROL_MAX_ENTRIES];
        int n = 0;
        for (double v = value, next; demo_param_step(desc, v, -1, &next); v = next) {
            if (n == DEMO_CONTROL_MAX_ENTRIES - 1)
                return false;
            below[n++] = next;
        }
        while (n > 0)
            out->values[out->count++] = below[--n];
        out->values[out->count++] = value;
        return walk_up(desc, out);
    }
    /* Powers of two: from the range's lower bound, itself a power of two (fg_registry_add). */
    out->values[out->count++] = desc->min;
    return walk_up(desc, out);
}

void
demo_param_control(const fg_param_desc *desc, double value, demo_control *out)
{
    memset(out, 0, sizeof *out);
    out->current = -1;
    out->min = desc->min;
    out->max = desc->max;
    switch (desc->type) {
    case FG_PARAM_BOOL:
        out->kind = DEMO_CONTROL_CHECKBOX;
        return;
    case FG_PARAM_STRING:
        out->kind = DEMO_CONTROL_TEXT;
        return;
    case FG_PARAM_ENUM:
        out->kind = DEMO_CONTROL_LIST;
        out->count = choice_count(desc->choices);
        if (out->count > DEMO_CONTROL_MAX_ENTRIES)
            out->count = DEMO_CONTROL_MAX_ENTRIES;
        for (int i = 0; i < out->count; i++)
            out->values[i] = i;
        out->current = (int)value < out->count ? (int)value : -1;
        return;
    case FG_PARAM_INT:
    case FG_PARAM_FLOAT:
        break;
    }
    if ((lists_values(desc) || doubles(desc)) && list_entries(desc, value, out)) {
        out->kind = DEMO_CONTROL_LIST;
        double slack = VALUE_SLACK * (fabs(value) > 1 ? fabs(value) : 1);
        for (int i = 0; i < out->count; i++)
            if (fabs(out->values[i] - value) <= slack)
                out->current = i;
        return;
    }
    out->kind = desc->max - desc->min <= 1000 ? DEMO_CONTROL_SLIDER : DEMO_CONTROL_DRAG;
    out->count = 0;
    out->step = demo_param_step_size(desc, value);
}

double
demo_param_value(const fg_pass *pass, const fg_param_desc *desc)
{
    switch (desc->type) {
    case FG_PARAM_INT: return fg_param_int(pass, desc->name);
    case FG_PARAM_FLOAT: return fg_param_float(pass, desc->name);
    case FG_PARAM_BOOL: return fg_param_bool(pass, desc->name) ? 1 : 0;
    case FG_PARAM_ENUM: return fg_param_enum(pass, desc->name);
    case FG_PARAM_STRING: return 0;
    }
    return 0;
}

void
demo_param_describe(const fg_pass *pass, const fg_param_desc *desc, char *out, size_t size)
{
    double value = demo_param_value(pass, desc);
    /* The values as `conegraph passes` lists them, then how the keys step them. */
    char text[256], values[512], range[768], depends[512], state[640] = "";
    fg_param_values_text(desc, values, sizeof values);
    if (desc->type == FG_PARAM_STRING) {
        snprintf(text, sizeof text, "\"%s\"", fg_param_string(pass, desc->name));
        snprintf(range, sizeof range, "string, not steppable");
    } else if (desc->type == FG_PARAM_INT || desc->type == FG_PARAM_FLOAT) {
        if (desc->type == FG_PARAM_FLOAT)
            snprintf(text, sizeof text, "%g", value); /* stored as floats: 0.35, not 0.349999994 */
        else
            demo_param_format(desc, value, text, sizeof text);
        const char *type = desc->type == FG_PARAM_INT ? "int" : "float";
        if (lists_values(desc))
            snprintf(range, sizeof range, "%s %s", type, values);
        else if (doubles(desc))
            snprintf(range, sizeof range, "%s %s, doubles/halves", type, values);
        else
            snprintf(range, sizeof range, "%s %s, step %g", type, values, demo_param_step_size(desc, value));
    } else {
        demo_param_format(desc, value, text, sizeof text);
        snprintf(range, sizeof range, "%s", desc->type == FG_PARAM_BOOL ? "bool" : desc->choices);
    }
    fg_param_dependency_text(desc, depends, sizeof depends);
    if (depends[0])
        snprintf(state, sizeof state, "; %s%s", depends, fg_param_active(pass, desc) ? "" : ": inactive now");
    snprintf(out, size, "%s.%s = %s (%s%s; a change redoes: %s): %s", fg_pass_name(pass), desc->name, text, range,
             state, fg_param_stage_name(desc->stage), desc->doc);
}

/* ------------------------------------------------------------ selection */

static int
param_count(const fg_graph *graph, int pass)
{
    return fg_pass_type_of(fg_graph_pass_at(graph, pass))->param_count;
}

/* The first pass with parameters from `start` on, going `step` (+1 or -1) and wrapping round, or
 * -1 where no pass has any. */
static int
pass_with_params(const fg_graph *graph, int start, int step)
{
    int n = fg_graph_pass_count(graph);
    for (int k = 0; k < n; k++) {
        int p = ((start + step * k) % n + n) % n;
        if (param_count(graph, p) > 0)
            return p;
    }
    return -1;
}

void
demo_select_first(const fg_graph *graph, demo_selection *sel)
{
    sel->pass = pass_with_params(graph, 0, 1);
    sel->param = sel->pass < 0 ? -1 : 0;
}

void
demo_select_pass(const fg_graph *graph, demo_selection *sel, int direction)
{
    if (sel->pass < 0) {
        demo_select_first(graph, sel);
        return;
    }
    int step = direction < 0 ? -1 : 1;
    int p = pass_with_params(graph, sel->pass + step, step);
    if (p >= 0) {
        sel->pass = p;
        sel->param = 0;
    }
}

void
demo_select_param(const fg_graph *graph, demo_selection *sel, int direction)
{
    if (sel->pass < 0)
        return;
    int n = param_count(graph, sel->pass);
    sel->param = ((sel->param + (direction < 0 ? -1 : 1)) % n + n) % n;
}

bool
demo_selected(const fg_graph *graph, const demo_selection *sel, fg_pass **pass, const fg_param_desc **desc)
{
    if (sel->pass < 0 || sel->pass >= fg_graph_pass_count(graph))
        return false;
    fg_pass *p = fg_graph_pass_at(graph, sel->pass);
    const fg_pass_type *type = fg_pass_type_of(p);
    if (sel->param < 0 || sel->param >= type->param_count)
        return false;
    *pass = p;
    *desc = &type->params[sel->param];
    return true;
}

/* The current value as text fg_graph_set_param takes back. */
static void
current_text(const fg_pass *pass, const fg_param_desc *desc, char *out, size_t size)
{
    if (desc->type == FG_PARAM_STRING)
        snprintf(out, size, "%s", fg_param_string(pass, desc->name));
    else
        demo_param_format(desc, demo_param_value(pass, desc), out, size);
}

bool
demo_param_set(fg_graph *graph, fg_pass *pass, const fg_param_desc *desc, const char *text, char *previous,
               size_t previous_size, cg_error *err)
{
    current_text(pass, desc, previous, previous_size);
    if (!fg_graph_set_param(graph, fg_pass_name(pass), desc->name, text, NULL, err))
        return false;
    /* What this value requires of the others (voxelize: padding below a quarter of the
     * resolution) is in the table too: refuse the value here rather than by compiling. */
    if (!fg_pass_check_params(pass, err)) {
        cg_error undo = { 0 };
        if (!fg_graph_set_param(graph, fg_pass_name(pass), desc->name, previous, NULL, &undo))
            snprintf(err->message + strlen(err->message), sizeof err->message - strlen(err->message),
                     " (and undoing it failed: %s)", undo.message);
        return false;
    }
    return true;
}

bool
demo_adjust(fg_graph *graph, const demo_selection *sel, int direction, bool *changed, char *previous,
            size_t previous_size, cg_error *err)
{
    *changed = false;
    fg_pass *pass;
    const fg_param_desc *desc;
    if (!demo_selected(graph, sel, &pass, &desc))
        return true;
    double next;
    if (!demo_param_step(desc, demo_param_value(pass, desc), direction, &next))
        return true;
    char text[256];
    demo_param_format(desc, next, text, sizeof text);
    if (!demo_param_set(graph, pass, desc, text, previous, previous_size, err))
        return false;
    *changed = true;
    return true;
}
