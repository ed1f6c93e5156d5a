/* apps/demo/ui.h: the demo's immediate-mode UI toolkit, a C face on Dear ImGui (its GLFW and
 * OpenGL 3 backends) so that the demo stays C; apps/demo/ui_imgui.cpp is the one C++ file.
 * Only what the demo draws is here; apps/demo/demo_ui.c lays the panels out with it.
 *
 * Declares: ui_context, ui_rect, ui_create, ui_destroy, ui_begin_frame, ui_end_frame,
 *           ui_key_event, ui_char_event, ui_mouse_button_event, ui_scroll_event,
 *           ui_cursor_enter_event, ui_focus_event, ui_wants_keyboard,
 *           ui_wants_text, ui_drawn, ui_drawn_windows; windows ui_window_place, ui_window_begin,
 *           ui_window_end; layout ui_same_line, ui_separator, ui_push_id, ui_pop_id,
 *           ui_push_dim, ui_pop_dim, ui_set_next_item_width, ui_available_width,
 *           ui_available_height,
 *           ui_collapsing_header; output ui_text, ui_text_disabled, ui_text_wrapped, ui_bar,
 *           ui_plot, ui_image, ui_tooltip; controls ui_button, ui_small_button, ui_checkbox,
 *           ui_combo, ui_slider_double, ui_drag_double, ui_input_text,
 *           ui_last_item_activated, ui_last_item_active, ui_last_item_edited.
 *
 * One frame: ui_begin_frame, windows (ui_window_begin ... ui_window_end, always paired),
 * ui_end_frame, which draws into the current framebuffer (the window's). Between
 * ui_begin_frame and ui_end_frame only; the widget functions act on the frame begun.
 * A control returns true on the frame its value changed (a combo: another entry chosen; a
 * slider or drag: moved; a text field: Enter pressed).
 *
 * Input: no GLFW callback is installed; the demo's callbacks hand every event to the
 * ui_*_event functions first, and skip their own action for keys while ui_wants_* says the UI
 * has them and for clicks and scrolls over the windows the UI drew (ui_drawn_windows).
 * Coordinates are window pixels, origin top left, y down. Labels identify their widget within
 * its window: "name##key" shows "name" and is told apart by the whole text; "shown###key" is
 * known by "key" alone, so its shown part may change from frame to frame.
 */
#ifndef CONEGRAPH_UI_H
#define CONEGRAPH_UI_H

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "cg/error.h"

typedef struct ui_context ui_context;

typedef struct ui_rect {
    float x, y, w, h;
} ui_rect;

/* A window as drawn: its title (up to the first "##") and where it was. */
typedef struct ui_drawn {
    char title[64];
    ui_rect rect;
} ui_drawn;

/* Makes the UI for a GLFWwindow whose GL 4.5 core context is current; nothing is saved to
 * disk (no imgui.ini): every run starts with the demo's layout. */
bool ui_create(void *glfw_window, ui_context **out, cg_error *err);
/* With the window's context current. NULL is fine. */
void ui_destroy(ui_context *ui);
void ui_begin_frame(ui_context *ui);
/* Renders the frame's windows into the bound draw framebuffer; GL state is restored. */
void ui_end_frame(ui_context *ui);

/* GLFW events, as the GLFW callbacks receive them. */
void ui_key_event(ui_context *ui, int key, int scancode, int action, int mods);
void ui_char_event(ui_context *ui, unsigned int codepoint);
void ui_mouse_button_event(ui_context *ui, int button, int action, int mods);
void ui_scroll_event(ui_context *ui, double x, double y);
void ui_cursor_enter_event(ui_context *ui, int entered);
void ui_focus_event(ui_context *ui, int focused);
/* A control has the keyboard (a text field, a held slider): keys are the UI's. */
bool ui_wants_keyboard(const ui_context *ui);
/* A text field is being typed into: held keys are text, not flight. */
bool ui_wants_text(const ui_context *ui);

/* After ui_end_frame: every window drawn in that frame (tooltips and popups included, child
 * windows inside their parents left out), at most `max`; returns how many there were. */
int ui_drawn_windows(const ui_context *ui, ui_drawn *out, int max);

/* Where a window goes, and how. */
typedef struct ui_window_place {
    ui_rect rect;           /* its place and size; with fit_height, rect.h is the most it takes */
    bool fit_height;        /* as tall as its contents on every frame (at most rect.h), so that a
                             * small demo window keeps the image visible below it */
    bool folded;            /* folded to its title bar */
    bool relayout;          /* apply the place now (the demo's window was resized) */
} ui_window_place;

/* A window placed, sized and folded as `place` says the first time it appears and again
 * whenever place->relayout is true; in between the user moves, resizes, folds and unfolds it
 * (the arrow of its title bar), and its contents scroll when they do not fit. Returns whether
 * its contents are visible (false when folded); ui_window_end must follow either way. */
bool ui_window_begin(const char *title, const ui_window_place *place);
void ui_window_end(void);

void ui_same_line(void);
void ui_separator(void);
void ui_push_id(int id);
void ui_pop_id(void);
/* Draws what follows at half opacity (greyed) while it stays usable. */
void ui_push_dim(bool dim);
void ui_pop_dim(void);
void ui_set_next_item_width(float width);
/* What is left of the window's contents region from the current position. */
float ui_available_width(void);
float ui_available_height(void);
/* A header that folds what follows; true while open. */
bool ui_collapsing_header(const char *label, bool default_open);

void ui_text(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void ui_text_disabled(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void ui_text_wrapped(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* A horizontal bar filled to `fraction` (0..1) with `overlay` written on it. */
void ui_bar(float fraction, const char *overlay);
/* A line graph of `count` values between min and max, as wide as the window, `height`
 * pixels high, `overlay` on top. */
void ui_plot(const char *id, const float *values, int count, float min, float max, float height,
             const char *overlay);
/* A GL_TEXTURE_2D shown at w x h pixels, its row 0 at the bottom (GL's convention). */
void ui_image(unsigned int texture, float w, float h);
/* Shows `text` in a tooltip while the cursor is over the last item. */
void ui_tooltip(const char *text);

bool ui_button(const char *label);
bool ui_small_button(const char *label);
bool ui_checkbox(const char *label, bool *value);
/* A drop-down list of `count` items; *current is the chosen index (-1: none). */
bool ui_combo(const char *label, int *current, const char *const *items, int count);
/* `format` is printf's for one double ("%.0f", "%.3g"); logarithmic needs min > 0. */
bool ui_slider_double(const char *label, double *value, double min, double max, const char *format,
                      bool logarithmic);
/* Changes by `speed` per pixel of drag; Ctrl+click types a value. Kept within min..max. */
bool ui_drag_double(const char *label, double *value, double speed, double min, double max,
                    const char *format);
/* Edits buf in place; true when Enter was pressed. */
bool ui_input_text(const char *label, char *buf, size_t size);
/* The last item was clicked or started being dragged this frame. */
bool ui_last_item_activated(void);
/* The last item is held (a slider being dragged, a field being typed into). */
bool ui_last_item_active(void);
/* The last item was let go this frame after its value changed (the end of a drag). */
bool ui_last_item_edited(void);

#ifdef __cplusplus
}
#endif

#endif
