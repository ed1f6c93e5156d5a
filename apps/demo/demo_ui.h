/* apps/demo/demo_ui.h: the demo's UI panels, drawn over the image every frame (apps/demo/ui.h):
 * - "conegraph": the scene and size, the frame times of the last frames as a graph with their
 *   median, the UI's own time, GI memory (and what the graph allocates), then the passes in
 *   execution order, each with a bar of its milliseconds against the frame time, and the
 *   culled ones greyed with the reason; the resource the window shows (keys 1..9) and the
 *   screenshot buttons (F12, Shift+F12) with the last path written;
 * - "parameters": every parameter of every pass as the control its table entry asks for
 *   (demo_param_control), with - and + buttons that step it as Left and Right do; inactive
 *   parameters (a dependency not met) greyed, the keys' selection marked, the table's line
 *   (demo_param_describe) as a tooltip, and why the last change was refused or undone;
 * - "resource viewer": any texture resource of the compiled graph, a level and a slice or
 *   layer of it, through demo_view.h.
 * Every change goes through d->actions (demo.h), the paths the keys take; the panels call
 * nothing of the main loop by name.
 *
 * Layout (demo_ui_layout): from 1120x560 up, the frame panel above the viewer on the left and
 * the parameters on the right; smaller (the README's 640x360), the frame panel alone on the
 * left, at most 42% of the width and as tall as its contents, its animation and image
 * sections folded (the frame graph lower, what a pass rebuilt in its bar's tooltip), the
 * parameters and the viewer folded to their title bars at the top right, so that most of the
 * image shows and every per-pass bar is in view. Every panel folds and unfolds with its title bar's arrow;
 * the panels are laid out again when the window changes size.
 *
 * Declares: demo_ui_places, demo_ui_layout, demo_ui_frame.
 */
#ifndef CONEGRAPH_DEMO_UI_H
#define CONEGRAPH_DEMO_UI_H

#include <stdbool.h>

#include "cg/error.h"
#include "demo.h"
#include "ui.h"

/* Where the three panels start. */
typedef struct demo_ui_places {
    bool roomy;                 /* the large layout; false: the small one */
    ui_window_place frame, params, viewer;
} demo_ui_places;

/* The panels' places for a window of width x height; `viewing`: the viewer has a resource (it
 * starts open). */
void demo_ui_layout(float width, float height, bool viewing, demo_ui_places *out);

/* Builds and draws this frame's UI into the window's back buffer, and records where its
 * windows are (d->ui_windows). Fails only when the viewer's shader does not build. */
bool demo_ui_frame(demo *d, cg_error *err);

#endif
