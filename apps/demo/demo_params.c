/* The demo's parameter controls: see demo_params.h. */
#include "demo_params.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Values read back through fg_param_float are floats: compare and snap with this slack. */
#define VALUE_SLACK 1e-5

static bool
doubles(const fg_param_desc *desc)
{
    return desc->type == FG_PARAM_INT && desc->min >= 1 && desc->max - desc->min > 64;
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
    if (desc->type == FG_PARAM_INT)
        return doubles(desc) ? 0 : 1;
    if (desc->type != FG_PARAM_FLOAT)
        return 0;
    double width = desc->max - desc->min;
    if (width <= 1000)
        return width > 0 ? nice_step_below(width / 50) : 0;
    double magnitude = fabs(value) > 1 ? fabs(value) : 1;
    return nice_step_below(magnitude / 4);
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
        if (doubles(desc))
            next = direction > 0 ? value * 2 : floor(value / 2);
        else
            next = value + (direction > 0 ? 1 : -1);
        break;
    case FG_PARAM_FLOAT: {
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
    char text[256], range[320];
    if (desc->type == FG_PARAM_STRING) {
        snprintf(text, sizeof text, "\"%s\"", fg_param_string(pass, desc->name));
        snprintf(range, sizeof range, "string, not steppable");
    } else if (desc->type == FG_PARAM_FLOAT) {
        /* Floats are stored as floats: %g shows 0.35, not 0.349999994. */
        snprintf(text, sizeof text, "%g", value);
        snprintf(range, sizeof range, "float %g..%g, step %g", desc->min, desc->max,
                 demo_param_step_size(desc, value));
    } else {
        demo_param_format(desc, value, text, sizeof text);
        if (desc->type == FG_PARAM_INT)
            snprintf(range, sizeof range, "int %g..%g, %s", desc->min, desc->max,
                     doubles(desc) ? "doubles/halves" : "step 1");
        else if (desc->type == FG_PARAM_BOOL)
            snprintf(range, sizeof range, "bool");
        else
            snprintf(range, sizeof range, "%s", desc->choices);
    }
    snprintf(out, size, "%s.%s = %s (%s): %s", fg_pass_name(pass), desc->name, text, range, desc->doc);
}

/* ------------------------------------------------------------ selection */

static int
param_count(const fg_graph *graph, int pass)
{
    return fg_pass_type_of(fg_graph_pass_at(graph, pass))->param_count;
}

void
demo_select_first(const fg_graph *graph, demo_selection *sel)
{
    sel->pass = -1;
    sel->param = -1;
    for (int p = 0; p < fg_graph_pass_count(graph); p++)
        if (param_count(graph, p) > 0) {
            sel->pass = p;
            sel->param = 0;
            return;
        }
}

void
demo_select_pass(const fg_graph *graph, demo_selection *sel, int direction)
{
    int n = fg_graph_pass_count(graph);
    if (sel->pass < 0) {
        demo_select_first(graph, sel);
        return;
    }
    int step = direction < 0 ? -1 : 1;
    for (int k = 1; k <= n; k++) {
        int p = ((sel->pass + step * k) % n + n) % n;
        if (param_count(graph, p) > 0) {
            sel->pass = p;
            sel->param = 0;
            return;
        }
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

bool
demo_adjust(fg_graph *graph, const demo_selection *sel, int direction, bool *changed, char *previous,
            size_t previous_size, cg_error *err)
{
    *changed = false;
    fg_pass *pass;
    const fg_param_desc *desc;
    if (!demo_selected(graph, sel, &pass, &desc))
        return true;
    double value = demo_param_value(pass, desc), next;
    if (!demo_param_step(desc, value, direction, &next))
        return true;
    char text[256];
    demo_param_format(desc, next, text, sizeof text);
    demo_param_format(desc, value, previous, previous_size);
    if (!fg_graph_set_param(graph, fg_pass_name(pass), desc->name, text, NULL, err))
        return false;
    *changed = true;
    return true;
}
