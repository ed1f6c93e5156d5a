/* apps/demo/demo_params.h: the demo's parameter controls, driven by the pass parameter tables
 * (fg_param_desc) exactly as validation, `conegraph passes` and the docs are.
 *
 * Declares: demo_param_step, demo_param_step_size, demo_param_snap, demo_param_format,
 *           demo_param_value, demo_param_describe, demo_control_kind, demo_control,
 *           demo_param_control, demo_selection, demo_select_first, demo_select_pass,
 *           demo_select_param, demo_selected, demo_param_set, demo_adjust.
 *
 * Stepping (Left/Right in the demo), a pure function of the table entry and the value:
 * - bool toggles; enum moves to the next or previous choice, wrapping round;
 * - int or float with allowed values: the next or previous of them (cones 1, 6, 9, 16);
 * - int that is a power of two: the next or previous power of two in the range
 *   (resolutions 128 -> 256 -> 512);
 * - step_doubles: doubled or halved (sample counts, shadow-map sizes);
 * - otherwise +- the table's step; without one, 1 for an int, and for a float the largest
 *   1, 2 or 5 x 10^k not above 1/50 of the range, or, when the range is wider than 1000
 *   (unbounded-like: distances, region corners), not above a quarter of max(|value|, 1);
 *   the value lands on a multiple of the step;
 * - the range bounds stop the step (there is no step beyond them); strings do not step.
 * So every step lands on a value that fg_graph_set_param accepts: nothing is tried and
 * refused. What a value requires of another parameter (greater_than, less_than) is checked
 * by demo_adjust through fg_pass_check_params, again without compiling.
 *
 * The window's controls (demo_param_control) follow from the same table and the same steps:
 * a checkbox for a bool; a list for an enum and for every value that steps along a list (the
 * allowed values, the powers of two, the doublings from the current value): exactly the
 * values Left/Right reach; a slider over the range when it is at most 1000 wide, else a drag;
 * both land on the step's grid (demo_param_snap); a text field for a string.
 */
#ifndef CONEGRAPH_DEMO_PARAMS_H
#define CONEGRAPH_DEMO_PARAMS_H

#include <stdbool.h>
#include <stddef.h>

#include "cg/error.h"
#include "cg/fg.h"

/* The value one step up (direction > 0) or down (direction < 0) from `value`. False when
 * there is none: a string parameter, or the value is already at that end of the range. */
bool demo_param_step(const fg_param_desc *desc, double value, int direction, double *out);
/* The step of an int or float parameter at `value`; 0 when it steps along a list (allowed
 * values, powers of two) or doubles, and for the other types. */
double demo_param_step_size(const fg_param_desc *desc, double value);
/* `value` within the range, on the grid of the step at `value` (an int: a whole number); a
 * value that steps along a list is only clamped. */
double demo_param_snap(const fg_param_desc *desc, double value);
/* `value` as the text fg_graph_set_param takes ("7", "0.35", "true", "aces"). */
void demo_param_format(const fg_param_desc *desc, double value, char *out, size_t size);
/* The current value of a pass's parameter as a number (enum: its index; string: 0). */
double demo_param_value(const fg_pass *pass, const fg_param_desc *desc);
/* One line: "pass.param = value (type values, stepping[; dependencies]): doc", e.g.
 * "gather.cones = 6 (int 1, 6, 9, 16): ...", "vox.min_x = -1 (float -1e+09..1e+09, step 0.2;
 * only with region = explicit: inactive now): ...". */
void demo_param_describe(const fg_pass *pass, const fg_param_desc *desc, char *out, size_t size);

typedef enum demo_control_kind {
    DEMO_CONTROL_CHECKBOX,      /* bool */
    DEMO_CONTROL_LIST,          /* a combo: enum choices, or the values an int or float steps along */
    DEMO_CONTROL_SLIDER,        /* int or float over a range at most 1000 wide */
    DEMO_CONTROL_DRAG,          /* int or float over a wider range (indices, distances, corners) */
    DEMO_CONTROL_TEXT           /* string */
} demo_control_kind;

/* A list longer than this (doubling over a huge range) becomes a slider or drag instead. */
#define DEMO_CONTROL_MAX_ENTRIES 64

typedef struct demo_control {
    demo_control_kind kind;
    int count;                  /* LIST: entries, in increasing order (enum: choice order) */
    double values[DEMO_CONTROL_MAX_ENTRIES]; /* LIST: each entry's value (enum: its index) */
    int current;                /* LIST: the entry holding the current value; -1: none */
    double min, max;            /* SLIDER, DRAG: the table's range */
    double step;                /* SLIDER, DRAG: the step at the current value (demo_param_step_size) */
} demo_control;

/* The control for a parameter whose current value is `value` (demo_param_value). */
void demo_param_control(const fg_param_desc *desc, double value, demo_control *out);

/* Which pass (file order) and which of its parameters the keys act on; -1 when the graph
 * has no pass with parameters. */
typedef struct demo_selection {
    int pass;
    int param;
} demo_selection;

/* The first pass with parameters, its first parameter. */
void demo_select_first(const fg_graph *graph, demo_selection *sel);
/* The next (direction > 0) or previous pass that has parameters, wrapping round; its first parameter. */
void demo_select_pass(const fg_graph *graph, demo_selection *sel, int direction);
/* The next or previous parameter of the selected pass, wrapping round. */
void demo_select_param(const fg_graph *graph, demo_selection *sel, int direction);
/* The selected pass and parameter; false when nothing is selected. */
bool demo_selected(const fg_graph *graph, const demo_selection *sel, fg_pass **pass,
                   const fg_param_desc **desc);

/* Sets a parameter from text through fg_graph_set_param (the same validation as graph files
 * and --set), then checks the pass's dependencies (fg_pass_check_params): a value that breaks
 * one is undone and the error says why. `previous` receives the old value's text (for undoing
 * the change if the graph then fails to compile, e.g. past the GL limits). */
bool demo_param_set(fg_graph *graph, fg_pass *pass, const fg_param_desc *desc, const char *text,
                    char *previous, size_t previous_size, cg_error *err);
/* Steps the selected parameter through fg_graph_set_param (the same validation as graph
 * files and --set), then checks the pass's dependencies (fg_pass_check_params): a value that
 * breaks one is undone and the error says why. *changed is false when there was no step to
 * take; `previous` receives the old value's text (for undoing the change if the graph then
 * fails to compile, e.g. past the GL limits). */
bool demo_adjust(fg_graph *graph, const demo_selection *sel, int direction, bool *changed,
                 char *previous, size_t previous_size, cg_error *err);

#endif
