// The demo's UI toolkit (apps/demo/ui.h) on Dear ImGui 1.86 and its GLFW and OpenGL 3 backends,
// which Debian's libimgui-dev compiles into libimgui.a. The one C++ file of the demo: each
// function forwards to ImGui, so the panels themselves stay C (apps/demo/demo_ui.c).
#include "ui.h"

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <new>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h> // the window list, for ui_drawn_windows

struct ui_context {
    GLFWwindow *window;
    ImGuiContext *imgui;
    bool glfw_ready, gl_ready;
};

bool
ui_create(void *glfw_window, ui_context **out, cg_error *err)
{
    *out = nullptr;
    IMGUI_CHECKVERSION();
    ui_context *ui = new (std::nothrow) ui_context{};
    if (!ui)
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "UI: out of memory");
    ui->window = static_cast<GLFWwindow *>(glfw_window);
    ui->imgui = ImGui::CreateContext();
    ImGuiIO &io = ImGui::GetIO();
    // The layout is the demo's on every run, and nothing is written to the current directory.
    io.IniFilename = nullptr;
    io.LogFilename = nullptr;
    // A drag on a window's contents (the viewer's picture) must not carry the window off.
    io.ConfigWindowsMoveFromTitleBarOnly = true;
    ImGui::StyleColorsDark();
    // The demo's own callbacks forward events (ui_*_event), so that they decide who gets each.
    ui->glfw_ready = ImGui_ImplGlfw_InitForOpenGL(ui->window, false);
    // GLSL 4.10 core and later take the backend's core-profile shaders.
    ui->gl_ready = ui->glfw_ready && ImGui_ImplOpenGL3_Init("#version 450 core");
    if (!ui->gl_ready) {
        const char *backend = ui->glfw_ready ? "OpenGL 3" : "GLFW";
        ui_destroy(ui);
        return cg_fail(err, CG_ERR_GL, "UI: Dear ImGui's %s backend failed to start", backend);
    }
    *out = ui;
    return true;
}

void
ui_destroy(ui_context *ui)
{
    if (!ui)
        return;
    ImGui::SetCurrentContext(ui->imgui);
    if (ui->gl_ready)
        ImGui_ImplOpenGL3_Shutdown();
    if (ui->glfw_ready)
        ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext(ui->imgui);
    delete ui;
}

void
ui_begin_frame(ui_context *ui)
{
    ImGui::SetCurrentContext(ui->imgui);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void
ui_end_frame(ui_context *ui)
{
    ImGui::SetCurrentContext(ui->imgui);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void
ui_key_event(ui_context *ui, int key, int scancode, int action, int mods)
{
    ImGui::SetCurrentContext(ui->imgui);
    ImGui_ImplGlfw_KeyCallback(ui->window, key, scancode, action, mods);
}

void
ui_char_event(ui_context *ui, unsigned int codepoint)
{
    ImGui::SetCurrentContext(ui->imgui);
    ImGui_ImplGlfw_CharCallback(ui->window, codepoint);
}

void
ui_mouse_button_event(ui_context *ui, int button, int action, int mods)
{
    ImGui::SetCurrentContext(ui->imgui);
    ImGui_ImplGlfw_MouseButtonCallback(ui->window, button, action, mods);
}

void
ui_scroll_event(ui_context *ui, double x, double y)
{
    ImGui::SetCurrentContext(ui->imgui);
    ImGui_ImplGlfw_ScrollCallback(ui->window, x, y);
}

void
ui_cursor_enter_event(ui_context *ui, int entered)
{
    ImGui::SetCurrentContext(ui->imgui);
    ImGui_ImplGlfw_CursorEnterCallback(ui->window, entered);
}

void
ui_focus_event(ui_context *ui, int focused)
{
    ImGui::SetCurrentContext(ui->imgui);
    ImGui_ImplGlfw_WindowFocusCallback(ui->window, focused);
}

bool
ui_wants_keyboard(const ui_context *ui)
{
    ImGui::SetCurrentContext(ui->imgui);
    return ImGui::GetIO().WantCaptureKeyboard;
}

bool
ui_wants_text(const ui_context *ui)
{
    ImGui::SetCurrentContext(ui->imgui);
    return ImGui::GetIO().WantTextInput;
}

int
ui_drawn_windows(const ui_context *ui, ui_drawn *out, int max)
{
    ImGuiContext &g = *ui->imgui;
    int n = 0;
    for (ImGuiWindow *w : g.Windows) {
        // Active: begun in the frame just rendered; a collapsed window's size is its title bar.
        if (!w->Active || w->Hidden || (w->Flags & ImGuiWindowFlags_ChildWindow))
            continue;
        if (n < max) {
            const char *end = ImGui::FindRenderedTextEnd(w->Name);
            snprintf(out[n].title, sizeof out[n].title, "%.*s", static_cast<int>(end - w->Name), w->Name);
            out[n].rect = ui_rect{ w->Pos.x, w->Pos.y, w->Size.x, w->Size.y };
        }
        n++;
    }
    return n;
}

bool
ui_window_begin(const char *title, const ui_window_place *place)
{
    const ui_rect &r = place->rect;
    ImGuiCond when = place->relayout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y), when);
    ImGui::SetNextWindowCollapsed(place->folded, when);
    ImGuiWindowFlags flags = 0;
    if (place->fit_height) {
        // The width as given, the height what the contents take up to r.h (then it scrolls);
        // a fixed width also keeps the bars' "all that is left" widths from feeding the fit.
        ImGui::SetNextWindowSizeConstraints(ImVec2(r.w, 0), ImVec2(r.w, r.h));
        flags |= ImGuiWindowFlags_AlwaysAutoResize;
    } else {
        ImGui::SetNextWindowSize(ImVec2(r.w, r.h), when);
    }
    return ImGui::Begin(title, nullptr, flags);
}

void
ui_window_end(void)
{
    ImGui::End();
}

void
ui_same_line(void)
{
    ImGui::SameLine();
}

void
ui_separator(void)
{
    ImGui::Separator();
}

void
ui_push_id(int id)
{
    ImGui::PushID(id);
}

void
ui_pop_id(void)
{
    ImGui::PopID();
}

void
ui_push_dim(bool dim)
{
    ImGui::PushStyleVar(ImGuiStyleVar_Alpha, ImGui::GetStyle().Alpha * (dim ? 0.5f : 1.0f));
}

void
ui_pop_dim(void)
{
    ImGui::PopStyleVar();
}

void
ui_set_next_item_width(float width)
{
    ImGui::SetNextItemWidth(width);
}

float
ui_available_width(void)
{
    return ImGui::GetContentRegionAvail().x;
}

float
ui_available_height(void)
{
    return ImGui::GetContentRegionAvail().y;
}

bool
ui_collapsing_header(const char *label, bool default_open)
{
    return ImGui::CollapsingHeader(label, default_open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

void
ui_text(const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    ImGui::TextV(fmt, args);
    va_end(args);
}

void
ui_text_disabled(const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    ImGui::TextDisabledV(fmt, args);
    va_end(args);
}

void
ui_text_wrapped(const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    ImGui::TextWrappedV(fmt, args);
    va_end(args);
}

void
ui_bar(float fraction, const char *overlay)
{
    ImGui::ProgressBar(fraction, ImVec2(-1, 0), overlay);
}

void
ui_plot(const char *id, const float *values, int count, float min, float max, float height, const char *overlay)
{
    // 1.86's plots take no negative width for "all that is left".
    ImGui::PlotLines(id, values, count, 0, overlay, min, max, ImVec2(ImGui::GetContentRegionAvail().x, height));
}

void
ui_image(unsigned int texture, float w, float h)
{
    // ImGui's rows run top to bottom, GL textures' bottom to top.
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(texture)), ImVec2(w, h), ImVec2(0, 1),
                 ImVec2(1, 0));
}

void
ui_tooltip(const char *text)
{
    if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
        ImGui::TextUnformatted(text);
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

bool
ui_button(const char *label)
{
    return ImGui::Button(label);
}

bool
ui_small_button(const char *label)
{
    return ImGui::SmallButton(label);
}

bool
ui_checkbox(const char *label, bool *value)
{
    return ImGui::Checkbox(label, value);
}

static bool
combo_item(void *data, int index, const char **text)
{
    *text = static_cast<const char *const *>(data)[index];
    return true;
}

bool
ui_combo(const char *label, int *current, const char *const *items, int count)
{
    return ImGui::Combo(label, current, combo_item, const_cast<void *>(static_cast<const void *>(items)), count);
}

bool
ui_slider_double(const char *label, double *value, double min, double max, const char *format, bool logarithmic)
{
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
    return ImGui::SliderScalar(label, ImGuiDataType_Double, value, &min, &max, format, flags);
}

bool
ui_drag_double(const char *label, double *value, double speed, double min, double max, const char *format)
{
    return ImGui::DragScalar(label, ImGuiDataType_Double, value, static_cast<float>(speed), &min, &max, format,
                             ImGuiSliderFlags_AlwaysClamp);
}

bool
ui_input_text(const char *label, char *buf, size_t size)
{
    return ImGui::InputText(label, buf, size, ImGuiInputTextFlags_EnterReturnsTrue);
}

bool
ui_last_item_activated(void)
{
    return ImGui::IsItemActivated();
}

bool
ui_last_item_active(void)
{
    return ImGui::IsItemActive();
}

bool
ui_last_item_edited(void)
{
    return ImGui::IsItemDeactivatedAfterEdit();
}
