// panel: the thin C++ adapter over Dear ImGui behind app/panel.h. One ImGui call per
// function; no state of its own beyond the ImGui context.
#include "app/panel.h"

#include <cstdarg>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

struct panel {
  ImGuiContext *context;
};

extern "C" panel *panel_create(void *glfw_window) {
  IMGUI_CHECKVERSION();
  panel *p = new panel;
  p->context = ImGui::CreateContext();
  ImGuiIO &io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini beside the user's files
  ImGui::StyleColorsDark();
  ImGui::GetStyle().Alpha = 0.92f;
  if (!ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow *>(glfw_window), true) ||
      !ImGui_ImplOpenGL3_Init("#version 430 core")) {
    ImGui::DestroyContext(p->context);
    delete p;
    return nullptr;
  }
  return p;
}

extern "C" void panel_destroy(panel *p) {
  if (!p) return;
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext(p->context);
  delete p;
}

extern "C" void panel_begin_frame(panel *) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

extern "C" void panel_end_frame(panel *) {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

extern "C" bool panel_wants_mouse(const panel *) { return ImGui::GetIO().WantCaptureMouse; }
extern "C" bool panel_wants_keyboard(const panel *) {
  return ImGui::GetIO().WantCaptureKeyboard;
}

extern "C" bool panel_window_begin(panel *, const char *title, float x, float y, float w) {
  ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(w, 0.0f), ImGuiCond_FirstUseEver);
  return ImGui::Begin(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize);
}
extern "C" void panel_window_end(panel *) { ImGui::End(); }

extern "C" bool panel_header(panel *, const char *label, bool open_by_default) {
  return ImGui::CollapsingHeader(label, open_by_default ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

extern "C" void panel_text(panel *, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  ImGui::TextV(fmt, ap);
  va_end(ap);
}
extern "C" void panel_separator(panel *) { ImGui::Separator(); }
extern "C" void panel_same_line(panel *) { ImGui::SameLine(); }

extern "C" bool panel_button(panel *, const char *label) { return ImGui::Button(label); }
extern "C" bool panel_checkbox(panel *, const char *label, bool *value) {
  return ImGui::Checkbox(label, value);
}
extern "C" bool panel_slider_float(panel *, const char *label, float *value, float min,
                                   float max, const char *format, bool logarithmic) {
  /* AlwaysClamp: a value typed with Ctrl+click stays in [min, max] too */
  return ImGui::SliderFloat(label, value, min, max, format ? format : "%.3f",
                            ImGuiSliderFlags_AlwaysClamp |
                                (logarithmic ? ImGuiSliderFlags_Logarithmic : 0));
}
extern "C" bool panel_slider_int(panel *, const char *label, int *value, int min, int max) {
  return ImGui::SliderInt(label, value, min, max, "%d", ImGuiSliderFlags_AlwaysClamp);
}
extern "C" bool panel_combo(panel *, const char *label, int *current, const char *const *items,
                            int count) {
  return ImGui::Combo(label, current, items, count);
}
extern "C" bool panel_color3(panel *, const char *label, float rgb[3]) {
  // ImGui (1.86) leaves a channel typed after Ctrl+click unclamped: -100 made negative
  // light, and a config the brush's Ctrl+S refused. Held to [0, 1e4], the configs' colour
  // range (SCENE_CONFIG_MAX_RADIANCE).
  const bool changed = ImGui::ColorEdit3(label, rgb);
  for (int c = 0; c < 3; c++) rgb[c] = rgb[c] >= 0.0f ? (rgb[c] <= 1e4f ? rgb[c] : 1e4f) : 0.0f;
  return changed;
}
extern "C" void panel_plot(panel *, const char *label, const float *values, int count,
                           float max) {
  ImGui::PlotLines(label, values, count, 0, nullptr, 0.0f, max, ImVec2(0, 40));
}
