/* The demo's UI panels: see demo_ui.h. */
#include "demo_ui.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cg/fg.h"
#include "demo_params.h"
#include "demo_view.h"
#include "ui.h"

#define MARGIN 8.0f
#define PANEL_WIDTH 360.0f
/* The left column: the frame panel above this fraction of the height, the viewer below. */
#define SPLIT 0.5f
#define MAX_VIEWABLE 128
/* Below this window size the panels are laid out small (demo_ui_layout). */
#define ROOMY_WIDTH 1120.0f
#define ROOMY_HEIGHT 560.0f
/* A folded window's title bar (Dear ImGui's default font, 13 px, and its frame padding). */
#define TITLE_BAR 20.0f

static const double MIB = 1024.0 * 1024.0;

/* ------------------------------------------------------------ frame, passes, screenshots */

/* `small`: the small layout's panel, where every line counts (demo_ui_layout). */
static void
frame_times(demo *d, bool small)
{
    float history[FRAME_HISTORY], highest = 0;
    for (int i = 0; i < d->frame_ms_count; i++) {
        history[i] = (float)d->frame_ms[i];
        highest = history[i] > highest ? history[i] : highest;
    }
    char overlay[96];
    snprintf(overlay, sizeof overlay, "frame %.1f ms (median of %d)", d->frame_median_ms, d->frame_ms_count);
    ui_plot("##frames", history, d->frame_ms_count, 0, highest * 1.1f, small ? 22 : 40, overlay);
    ui_tooltip("Each frame from the start of the graph's execution to the end of the buffer swap, "
               "the UI included; the last 64 frames.");
    fg_memory_report mem;
    fg_graph_memory_report(d->graph, &mem);
    ui_text("GI memory %.1f MiB", (double)mem.gi_bytes / MIB);
    char why[256];
    snprintf(why, sizeof why, "The resources flagged gi (volumes, maps, tables): the papers' memory metric. "
             "The graph allocates %.1f MiB in all, at most %.1f MiB live at once.",
             (double)mem.allocated_bytes / MIB, (double)mem.peak_bytes / MIB);
    ui_tooltip(why);
    ui_same_line();
    ui_text_disabled("  UI %.1f ms", d->ui_ms);
    ui_tooltip("What the UI itself took of the last frame: building, the viewer and drawing.");
}

/* Live passes in execution order with their times as bars of the frame time (and, greyed, what
 * a pass said it rebuilt), then the culled ones, greyed, with the reason. */
static void
passes(demo *d, bool small)
{
    if (!small)
        ui_text("passes, in execution order");
    const int *order;
    int live = fg_graph_order(d->graph, &order);
    double frame = d->frame_median_ms, total = 0;
    for (int k = 0; k < live; k++) {
        double ms = fg_pass_milliseconds(fg_graph_pass_at(d->graph, order[k]));
        total += ms > 0 ? ms : 0;
    }
    /* Against the frame time, or the passes' sum where that is larger (the latest frame's
     * times against a median). */
    double whole = frame > total ? frame : total;
    for (int k = 0; k < live; k++) {
        const fg_pass *pass = fg_graph_pass_at(d->graph, order[k]);
        double ms = fg_pass_milliseconds(pass);
        char label[192], reads[64];
        if (ms >= 0 && fg_pass_reads(pass, NULL, NULL, NULL))
            snprintf(label, sizeof label, "%s  %.1f ms, reads %s", fg_pass_name(pass), ms,
                     fg_pass_reads_text(pass, reads, sizeof reads));
        else if (ms >= 0)
            snprintf(label, sizeof label, "%s  %.1f ms", fg_pass_name(pass), ms);
        else
            snprintf(label, sizeof label, "%s  (not measured yet)", fg_pass_name(pass));
        ui_bar(ms > 0 && whole > 0 ? (float)(ms / whole) : 0.0f, label);
        const fg_pass_type *type = fg_pass_type_of(pass);
        const char *doc = type->doc ? type->doc : type->name;
        /* What a caching pass redid this frame (fg_pass_report_rebuilt): under its bar, or in a
         * small panel in its tooltip, so that every bar stays in view. */
        if (small && fg_pass_rebuilt(pass)[0]) {
            char tip[2048];
            snprintf(tip, sizeof tip, "%s\n\nThis frame: %s", doc, fg_pass_rebuilt(pass));
            ui_tooltip(tip);
        } else {
            ui_tooltip(doc);
        }
        if (!small && fg_pass_rebuilt(pass)[0]) {
            ui_push_dim(true);
            ui_text_wrapped("  %s", fg_pass_rebuilt(pass));
            ui_pop_dim();
        }
    }
    for (int p = 0; p < fg_graph_pass_count(d->graph); p++) {
        const fg_pass *pass = fg_graph_pass_at(d->graph, p);
        const char *why = fg_pass_cull_reason(pass);
        if (why) {
            /* Greyed, and wrapped: a reason names the chain of absent inputs that led to it. */
            ui_push_dim(true);
            ui_text_wrapped("%s  culled: %s", fg_pass_name(pass), why);
            ui_pop_dim();
        }
    }
}

/* Play and pause, a frame back and forward, the time as a slider over the animation's keys
 * (held: the scene follows it; let go: the time is said on stdout), and the sun key's turn. */
static void
animation(demo *d)
{
    demo_clock *c = &d->clock;
    if (c->animated) {
        if (ui_button(c->playing ? "Pause (Space)###play" : "Play (Space)###play"))
            d->actions->toggle_play(d);
        ui_same_line();
        if (ui_small_button("<"))
            d->actions->step_time(d, -1);
        ui_tooltip("One frame back and pause, as [ (Shift+[: ten frames).");
        ui_same_line();
        if (ui_small_button(">"))
            d->actions->step_time(d, 1);
        ui_tooltip("One frame forward and pause, as ] (Shift+]: ten frames).");
        ui_same_line();
        ui_text("t = %.3f s", demo_clock_time(c));
        if (c->end > c->start) {
            double t = demo_clock_time(c);
            ui_set_next_item_width(ui_available_width() * 0.7f);
            if (ui_slider_double("time", &t, c->start, c->end, "%.3f s", false))
                d->actions->seek_time(d, t, false);
            if (ui_last_item_edited())
                d->actions->seek_time(d, t, true);
            ui_tooltip("Scrub the animation (it pauses): the scene is posed at this time, as "
                       "conegraph render --time poses it.");
        }
        if (c->fps > 0)
            ui_text_disabled("keys %g..%g s, looping; 1/%g s a frame", c->start, c->end, c->fps);
        else
            ui_text_disabled("keys %g..%g s, looping; real time", c->start, c->end);
    } else {
        ui_text_disabled("no animation");
    }
    if (d->sun.any) {
        if (ui_small_button(d->sun.moving ? "Stop sun (L)###sun" : "Turn sun (L)###sun"))
            d->actions->sun_key(d, false);
        ui_same_line();
        if (ui_small_button("Back (Shift+L)"))
            d->actions->sun_key(d, true);
        ui_same_line();
        ui_text_disabled("+%.1f deg", d->sun.angle * 180.0 / M_PI);
        ui_tooltip("L turns every directional light about world +y at 20 degrees a second, on top of "
                   "what the animation does; Shift+L puts them back where the scene has them.");
    }
}

static void
shown_and_screenshots(demo *d)
{
    const char *items[MAX_SHOWN];
    char labels[MAX_SHOWN][272];
    for (int i = 0; i < d->shown_count; i++) {
        snprintf(labels[i], sizeof labels[i], "%d  %s", i + 1, d->shown[i]);
        items[i] = labels[i];
    }
    int current = d->shown_index;
    ui_set_next_item_width(ui_available_width() * 0.7f);
    if (ui_combo("shown", &current, items, d->shown_count) && current != d->shown_index)
        d->actions->show(d, current);
    ui_tooltip("What the window shows (keys 1..9): the ldr output, or another 2D colour texture "
               "copied raw (clamped to 0..1).");
    if (ui_button("Screenshot (F12)"))
        d->screenshot_requested = true;
    ui_tooltip("The window as shown, the UI included, to a PNG.");
    ui_same_line();
    if (ui_button("Image only (Shift+F12)"))
        d->image_screenshot_requested = true;
    ui_tooltip("The image without the UI, to a PNG.");
    if (d->last_screenshot[0])
        ui_text_wrapped("saved %s", d->last_screenshot);
    ui_text_disabled("F1 hides the UI");
}

/* The frame panel: what runs, the frame times, the per-pass bars (near the top, so that they
 * show in a small panel), then the animation and the image shown, each a section that folds
 * (folded at first in a small window). */
static void
frame_panel(demo *d, const ui_window_place *place, bool sections_open)
{
    if (ui_window_begin("conegraph", place)) {
        bool small = !sections_open;
        ui_text("%s  %dx%d", d->s.scene.name, d->s.frame.width, d->s.frame.height);
        const char *slash = strrchr(d->s.graph_path, '/');
        ui_text_disabled("%s, timing %s", slash ? slash + 1 : d->s.graph_path,
                         d->timing == FG_TIMING_SYNC ? "sync" : d->timing == FG_TIMING_QUERIES ? "queries" : "none");
        frame_times(d, small);
        ui_separator();
        passes(d, small);
        if (ui_collapsing_header("Animation and sun###animation", sections_open))
            animation(d);
        if (ui_collapsing_header("Image shown, screenshots###shown", sections_open))
            shown_and_screenshots(d);
    }
    ui_window_end();
}

/* ------------------------------------------------------------ parameters */

/* printf format for a value on a grid of `step`: as many decimals as the step has. */
static void
value_format(const fg_param_desc *desc, double step, char *out, size_t size)
{
    if (desc->type == FG_PARAM_INT) {
        snprintf(out, size, "%%.0f");
        return;
    }
    if (step <= 0) {
        snprintf(out, size, "%%.6g");
        return;
    }
    int decimals = (int)ceil(-log10(step) - 1e-9);
    decimals = decimals < 0 ? 0 : decimals > 6 ? 6 : decimals;
    snprintf(out, size, "%%.%df", decimals);
}

static void
set_number(demo *d, int p, int i, const fg_param_desc *desc, double value)
{
    char text[256];
    demo_param_format(desc, value, text, sizeof text);
    d->actions->set_param(d, p, i, text);
}

static bool
editing(const demo *d, int p, int i)
{
    return d->editing_pass == p && d->editing_param == i;
}

/* A slider or a drag: the value follows the mouse on the step's grid while held, and is set
 * once, when let go (each set compiles the graph). */
static void
number_control(demo *d, int p, int i, const fg_param_desc *desc, double value, const demo_control *c)
{
    double shown = editing(d, p, i) ? d->editing_value : value;
    char format[16];
    value_format(desc, c->step, format, sizeof format);
    if (c->kind == DEMO_CONTROL_SLIDER)
        ui_slider_double("##value", &shown, c->min, c->max, format, false);
    else
        /* Four pixels a step. */
        ui_drag_double("##value", &shown, c->step > 0 ? c->step / 4 : 0.25, c->min, c->max, format);
    if (ui_last_item_active()) {
        d->editing_pass = p;
        d->editing_param = i;
        d->editing_value = demo_param_snap(desc, shown);
    }
    if (ui_last_item_edited()) {
        d->editing_pass = -1;
        set_number(d, p, i, desc, demo_param_snap(desc, shown));
    } else if (editing(d, p, i) && !ui_last_item_active()) {
        d->editing_pass = -1;
    }
}

/* A text field: edited in d->editing_text while it has the keyboard, set on Enter. */
static void
text_control(demo *d, int p, int i, const fg_pass *pass, const fg_param_desc *desc)
{
    char local[sizeof d->editing_text];
    char *buf = editing(d, p, i) ? d->editing_text : local;
    if (buf == local)
        snprintf(local, sizeof local, "%s", fg_param_string(pass, desc->name));
    bool enter = ui_input_text("##value", buf, sizeof d->editing_text);
    if (ui_last_item_active() && buf == local) {
        memcpy(d->editing_text, local, sizeof local);
        d->editing_pass = p;
        d->editing_param = i;
    }
    if (enter) {
        d->editing_pass = -1;
        d->actions->set_param(d, p, i, buf);
    } else if (editing(d, p, i) && !ui_last_item_active()) {
        d->editing_pass = -1;
    }
}

static void
list_control(demo *d, int p, int i, const fg_param_desc *desc, const demo_control *c)
{
    char labels[DEMO_CONTROL_MAX_ENTRIES][64];
    const char *items[DEMO_CONTROL_MAX_ENTRIES];
    for (int k = 0; k < c->count; k++) {
        demo_param_format(desc, c->values[k], labels[k], sizeof labels[k]);
        items[k] = labels[k];
    }
    int current = c->current;
    if (ui_combo("##value", &current, items, c->count) && current != c->current && current >= 0)
        set_number(d, p, i, desc, c->values[current]);
}

static void
param_control(demo *d, int p, int i, fg_pass *pass, const fg_param_desc *desc)
{
    double value = demo_param_value(pass, desc);
    demo_control c;
    demo_param_control(desc, value, &c);
    char line[1024];
    demo_param_describe(pass, desc, line, sizeof line);
    bool selected = d->sel.pass == p && d->sel.param == i;
    bool activated = false;

    ui_push_id(i);
    ui_push_dim(!fg_param_active(pass, desc));
    ui_set_next_item_width(ui_available_width() * 0.5f);
    switch (c.kind) {
    case DEMO_CONTROL_CHECKBOX: {
        bool on = value != 0;
        if (ui_checkbox("##value", &on))
            d->actions->set_param(d, p, i, on ? "true" : "false");
        break;
    }
    case DEMO_CONTROL_LIST:
        list_control(d, p, i, desc, &c);
        break;
    case DEMO_CONTROL_SLIDER:
    case DEMO_CONTROL_DRAG:
        number_control(d, p, i, desc, value, &c);
        break;
    case DEMO_CONTROL_TEXT:
        text_control(d, p, i, pass, desc);
        break;
    }
    activated |= ui_last_item_activated();
    ui_tooltip(line);
    if (c.kind != DEMO_CONTROL_CHECKBOX && c.kind != DEMO_CONTROL_TEXT) {
        ui_same_line();
        if (ui_small_button("-"))
            d->actions->step_param(d, p, i, -1);
        ui_tooltip("one step down, as Left");
        ui_same_line();
        if (ui_small_button("+"))
            d->actions->step_param(d, p, i, 1);
        ui_tooltip("one step up, as Right");
    }
    ui_same_line();
    ui_text("%s%s", selected ? "> " : "", desc->name);
    ui_tooltip(line);
    ui_pop_dim();
    ui_pop_id();
    /* The keys go on from the control last used. */
    if (activated)
        d->actions->select(d, p, i);
}

static void
params_panel(demo *d, const ui_window_place *place)
{
    if (ui_window_begin("parameters", place)) {
        if (d->notice[0])
            ui_text_wrapped("%s", d->notice);
        ui_text_disabled("hover for the table's line; > marks the keys' selection");
        for (int p = 0; p < fg_graph_pass_count(d->graph); p++) {
            fg_pass *pass = fg_graph_pass_at(d->graph, p);
            const fg_pass_type *type = fg_pass_type_of(pass);
            if (type->param_count == 0)
                continue;
            const char *culled = fg_pass_cull_reason(pass);
            char header[320];
            snprintf(header, sizeof header, "%s (%s)%s###pass%d", fg_pass_name(pass), type->name,
                     culled ? ", culled" : "", p);
            ui_push_dim(culled != NULL);
            bool open = ui_collapsing_header(header, true);
            ui_pop_dim();
            if (culled)
                ui_tooltip(culled);
            if (!open)
                continue;
            ui_push_id(p);
            for (int i = 0; i < type->param_count; i++)
                param_control(d, p, i, pass, &type->params[i]);
            ui_pop_id();
        }
    }
    ui_window_end();
}

/* ------------------------------------------------------------ resource viewer */

static const char *
kind_text(fg_resource_kind kind)
{
    switch (kind) {
    case FG_TEXTURE_2D: return "2D";
    case FG_TEXTURE_3D: return "3D";
    case FG_TEXTURE_2D_ARRAY: return "2D array";
    case FG_BUFFER: return "buffer";
    }
    return "?";
}

static const char *
class_text(demo_view_class cls)
{
    switch (cls) {
    case DEMO_VIEW_COLOUR: return "colour";
    case DEMO_VIEW_DEPTH: return "depth";
    case DEMO_VIEW_UINT: return "uint";
    case DEMO_VIEW_INT: return "int";
    case DEMO_VIEW_CLASS_COUNT: break;
    }
    return "?";
}

static void
int_slider(const char *label, int *value, int max)
{
    double v = *value;
    if (ui_slider_double(label, &v, 0, max, "%.0f", false))
        *value = (int)lround(v);
}

/* A fit that cannot read the level back leaves the mapping as it was and says why. */
static void
fit(demo *d, GLuint texture, const fg_resource_desc *desc, demo_view_class cls)
{
    cg_error why = { 0 };
    if (!demo_view_fit(texture, desc, cls, &d->view_settings, &why)) {
        fprintf(stderr, "conegraph-demo: viewer: %s\n", why.message);
        snprintf(d->view_notice, sizeof d->view_notice, "%s", why.message);
    } else {
        d->view_notice[0] = '\0';
    }
}

/* The settings, the picture and what it is of. */
static bool
view_resource(demo *d, cg_error *err)
{
    const fg_resource_info *info = fg_graph_find_resource(d->graph, d->view_source);
    GLuint texture = info && !info->absent ? fg_graph_texture(d->graph, d->view_source) : 0;
    if (!texture) {
        ui_text_disabled("%s is absent in this compile", d->view_source);
        return true;
    }
    if (d->recompile) {
        /* Just marked to be kept: until the compile its texels may be another resource's. */
        ui_text_disabled("compiling...");
        return true;
    }
    const fg_resource_desc *desc = &info->desc;
    demo_view_class cls = demo_view_class_of(texture);
    demo_view_settings *s = &d->view_settings;
    if (d->view_fresh) {
        d->view_fresh = false;
        demo_view_defaults(texture, desc, cls, s);
        /* Depth and integers have no range of their own to show: fit them to what is there. */
        if (cls != DEMO_VIEW_COLOUR)
            fit(d, texture, desc, cls);
    }
    /* Two controls a line, so that the picture keeps most of the window. */
    float width = ui_available_width() * 0.3f;
    bool first = true;
    if (desc->levels > 1) {
        ui_set_next_item_width(width);
        int_slider("level", &s->level, desc->levels - 1);
        first = false;
    }
    int w, h, slices;
    demo_view_level_size(desc, s->level < desc->levels ? s->level : desc->levels - 1, &w, &h, &slices);
    if (desc->kind != FG_TEXTURE_2D) {
        if (!first)
            ui_same_line();
        ui_set_next_item_width(width);
        int_slider(desc->kind == FG_TEXTURE_3D ? "slice" : "layer", &s->layer, slices - 1);
    }
    if (cls != DEMO_VIEW_DEPTH) {
        static const char *const channels[] = { "RGB", "R", "G", "B", "A" };
        ui_set_next_item_width(width);
        ui_combo("channels", &s->channel, channels, 5);
        ui_same_line();
    }
    if (cls == DEMO_VIEW_COLOUR) {
        ui_set_next_item_width(width);
        ui_slider_double("EV", &s->exposure, -16, 16, "%.1f", false);
        ui_tooltip("exposure: values x 2^EV");
        ui_checkbox("sRGB", &s->srgb);
        ui_tooltip("sRGB-encode, for linear values; off shows them as stored (8-bit display values)");
    } else {
        /* A 24-bit depth or a 32-bit count spans more than a drag's pixels: a step of a
         * hundredth of the range shown. */
        double speed = fabs(s->hi - s->lo) / 100;
        double top = cls == DEMO_VIEW_DEPTH ? 1 : 4294967295.0, bottom = cls == DEMO_VIEW_INT ? -2147483648.0 : 0;
        ui_set_next_item_width(width);
        ui_drag_double("black", &s->lo, speed > 0 ? speed : 0.01, bottom, top, "%.6g");
        ui_tooltip("the value shown black");
        if (cls == DEMO_VIEW_DEPTH)
            ui_same_line();
        ui_set_next_item_width(width);
        ui_drag_double("white", &s->hi, speed > 0 ? speed : 0.01, bottom, top, "%.6g");
        ui_tooltip("the value shown white");
    }
    if (cls != DEMO_VIEW_DEPTH)
        ui_same_line();
    if (ui_small_button("Fit"))
        fit(d, texture, desc, cls);
    ui_tooltip(cls == DEMO_VIEW_COLOUR ? "The exposure that makes the largest value shown white."
                                       : "Black and white at the smallest and largest value shown.");
    if (!demo_view_draw(&d->view, texture, desc, cls, s, err))
        return false;
    ui_same_line();
    if (desc->kind == FG_TEXTURE_2D)
        ui_text_disabled("2D %s %dx%d, level %d/%d", class_text(cls), w, h, s->level, desc->levels);
    else
        ui_text_disabled("%s %s %dx%dx%d, level %d/%d", kind_text(desc->kind), class_text(cls), w, h, slices,
                         s->level, desc->levels);
    /* As large as the window leaves room for, at least 64 pixels high (the window scrolls). */
    float aspect = (float)d->view.height / (float)d->view.width;
    float shown_w = ui_available_width(), room = ui_available_height();
    if (shown_w * aspect > room)
        shown_w = (room > 64 ? room : 64) / aspect;
    ui_image(d->view.shown, shown_w, shown_w * aspect);
    return true;
}

static bool
viewer_panel(demo *d, const ui_window_place *place, cg_error *err)
{
    bool ok = true;
    if (ui_window_begin("resource viewer", place)) {
        const char *items[MAX_VIEWABLE + 1];
        const char *names[MAX_VIEWABLE + 1];
        char labels[MAX_VIEWABLE + 1][320];
        int count = 0, current = 0;
        items[count] = "none";
        names[count++] = "";
        for (int r = 0; r < fg_graph_resource_count(d->graph) && count <= MAX_VIEWABLE; r++) {
            const fg_resource_info *info = fg_graph_resource_at(d->graph, r);
            if (info->absent || info->desc.kind == FG_BUFFER)
                continue;
            const fg_resource_desc *desc = &info->desc;
            if (desc->kind == FG_TEXTURE_2D)
                snprintf(labels[count], sizeof labels[count], "%s  (2D %dx%d)", info->name, desc->width, desc->height);
            else
                snprintf(labels[count], sizeof labels[count], "%s  (%s %dx%dx%d)", info->name, kind_text(desc->kind),
                         desc->width, desc->height, desc->depth);
            if (!strcmp(info->name, d->view_source))
                current = count;
            items[count] = labels[count];
            names[count++] = info->name;
        }
        ui_set_next_item_width(ui_available_width());
        if (ui_combo("##resource", &current, items, count))
            d->actions->view_resource(d, names[current]);
        ui_tooltip("Any texture of the compiled graph; kept (never pooled) once chosen.");
        if (d->view_source[0])
            ok = view_resource(d, err);
        if (d->view_source[0] && d->view_notice[0])
            ui_text_wrapped("Fit: %s", d->view_notice);
    }
    ui_window_end();
    return ok;
}

/* ------------------------------------------------------------ the frame */

void
demo_ui_layout(float width, float height, bool viewing, demo_ui_places *out)
{
    memset(out, 0, sizeof *out);
    out->roomy = width >= ROOMY_WIDTH && height >= ROOMY_HEIGHT;
    if (out->roomy) {
        /* Frame panel above the viewer on the left, parameters on the right: the middle of
         * the image stays clear. */
        out->frame.rect = (ui_rect){ MARGIN, MARGIN, PANEL_WIDTH, height * SPLIT - 1.5f * MARGIN };
        out->viewer.rect = (ui_rect){ MARGIN, height * SPLIT + 0.5f * MARGIN, PANEL_WIDTH,
                                      height * (1 - SPLIT) - 1.5f * MARGIN };
        out->params.rect = (ui_rect){ width - PANEL_WIDTH - 40 - MARGIN, MARGIN, PANEL_WIDTH + 40, height - 2 * MARGIN };
        return;
    }
    /* Small (the README's 640x360): the frame panel on the left, at most 42% of the width and
     * only as tall as its contents (its sections folded); the parameters and the viewer folded
     * to their title bars at the top right (the viewer open when --view asked for it). Unfolded
     * they take the right column's height. */
    float panel = width * 0.42f;
    panel = panel > PANEL_WIDTH ? PANEL_WIDTH : panel < 200.0f ? 200.0f : panel;
    float right = width - panel - 40 * (width >= 2 * panel + 200) - MARGIN;
    float side = width - right - MARGIN;
    out->frame = (ui_window_place){ .rect = { MARGIN, MARGIN, panel, height - 2 * MARGIN }, .fit_height = true };
    out->params = (ui_window_place){ .rect = { right, MARGIN, side, height - 2 * MARGIN }, .folded = true };
    float below = MARGIN + TITLE_BAR + 4;
    out->viewer = (ui_window_place){ .rect = { right, below, side, height - below - MARGIN }, .folded = !viewing };
}

bool
demo_ui_frame(demo *d, cg_error *err)
{
    ui_begin_frame(d->ui);
    int width = d->s.frame.width, height = d->s.frame.height;
    demo_ui_places places;
    demo_ui_layout((float)width, (float)height, d->view_source[0] != '\0', &places);
    /* Laid out again when the window changes size (the first frame places them anyway). */
    bool relayout = d->ui_layout_width && (width != d->ui_layout_width || height != d->ui_layout_height);
    d->ui_layout_width = width;
    d->ui_layout_height = height;
    places.frame.relayout = places.params.relayout = places.viewer.relayout = relayout;
    frame_panel(d, &places.frame, places.roomy);
    params_panel(d, &places.params);
    bool ok = viewer_panel(d, &places.viewer, err);
    ui_end_frame(d->ui);
    d->ui_window_count = ui_drawn_windows(d->ui, d->ui_windows, MAX_UI_WINDOWS);
    return ok;
}
