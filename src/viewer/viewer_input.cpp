// viewer_input.cpp - the mouse and keys over the 3D view (docs/VIEWER.md has
// the list) and the overlays of region selection.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "viewer/region_pick.h"
#include "viewer/viewer_ui.h"

namespace ff::viewer {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kOrbitRadiansPerPixel = 0.008f;

// World units per window pixel at the orbit target's depth, over the distance.
float panScale(const ViewerUi& ui) {
  return 2.0f * std::tan(0.5f * ui.camera.fov_y_deg * kPi / 180.0f) / float(std::max(ui.view_h, 1));
}

void handleKey(ViewerUi& ui, ViewerSession& session, const ViewerUi::KeyPress& k) {
  const bool shift = (k.mods & GLFW_MOD_SHIFT) != 0, ctrl = (k.mods & GLFW_MOD_CONTROL) != 0;
  // Held keys repeat only for stepping and zooming.
  if (k.repeat && k.key != GLFW_KEY_PERIOD && k.key != GLFW_KEY_RIGHT && k.key != GLFW_KEY_EQUAL &&
      k.key != GLFW_KEY_KP_ADD && k.key != GLFW_KEY_MINUS && k.key != GLFW_KEY_KP_SUBTRACT)
    return;
  if (ctrl) {
    if (k.key == GLFW_KEY_Q) ui.quit = true;
    return;
  }
  if (k.key >= GLFW_KEY_0 && k.key <= GLFW_KEY_9) return pickChoice(ui, session, k.key - GLFW_KEY_0);
  if (k.key >= GLFW_KEY_KP_0 && k.key <= GLFW_KEY_KP_9) return pickChoice(ui, session, k.key - GLFW_KEY_KP_0);
  switch (k.key) {
    case GLFW_KEY_SPACE:
      ui.playing = !ui.playing;
      break;
    case GLFW_KEY_PERIOD:
    case GLFW_KEY_RIGHT:
      ui.playing = false;
      ui.step_once = true;
      break;
    case GLFW_KEY_R:
      (shift ? ui.reset_to_scene_request : ui.reset_request) = true;
      break;
    case GLFW_KEY_C:
    case GLFW_KEY_HOME:
      ui.camera = homeCamera(ui, session);
      break;
    case GLFW_KEY_B:
      toggleMode(ui, PickMode::BoxSelect);
      break;
    case GLFW_KEY_S:
      toggleMode(ui, PickMode::SphereBrush);
      break;
    case GLFW_KEY_ESCAPE:  // back to the camera; a selection in progress is dropped
      ui.mode = PickMode::Camera;
      ui.drag_button = -1;
      ui.drag_selects = false;
      break;
    case GLFW_KEY_A:
      applyRegion(ui, session, RegionDesc());
      break;
    case GLFW_KEY_M:
      ui.render.mode = ui.render.mode == render::FluidMode::ScreenSpace ? render::FluidMode::Particles
                                                                        : render::FluidMode::ScreenSpace;
      break;
    case GLFW_KEY_O:
      ui.render.show_control = !ui.render.show_control;
      break;
    case GLFW_KEY_G:
      ui.render.show_ghost = !ui.render.show_ghost;
      break;
    case GLFW_KEY_W:
      ui.render.show_region = !ui.render.show_region;
      break;
    case GLFW_KEY_TAB:
      ui.show_panel = !ui.show_panel;
      break;
    case GLFW_KEY_H:
    case GLFW_KEY_F1:
      ui.show_help = !ui.show_help;
      break;
    case GLFW_KEY_P:
      ui.screenshot_request = true;
      break;
    case GLFW_KEY_E:
      ui.record_request = true;
      break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
      ui.camera.zoom(0.9f);
      break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
      ui.camera.zoom(1.0f / 0.9f);
      break;
    default:
      break;
  }
}

// The presses queued since the last frame, unless the panel is taking text.
void handleKeys(ViewerUi& ui, ViewerSession& session) {
  std::vector<ViewerUi::KeyPress> keys;
  keys.swap(ui.keys);
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput || io.WantCaptureKeyboard) return;
  for (const ViewerUi::KeyPress& k : keys) handleKey(ui, session, k);
}

void drawBrush(const ViewerUi& ui) {
  if (ui.hover_particle < 0) return;
  const size_t i = size_t(ui.hover_particle);
  const Vec3 c(ui.frame.x[i], ui.frame.y[i], ui.frame.z[i]);
  // The projected radius: the centre and a point one radius along the screen's right axis.
  const Vec3 right = ui.camera.view().block<1, 3>(0, 0).transpose();
  float cx, cy, ex, ey;
  if (!projectToPixel(ui.camera, ui.view_w, ui.view_h, c, cx, cy) ||
      !projectToPixel(ui.camera, ui.view_w, ui.view_h, c + ui.brush_radius * right, ex, ey))
    return;
  const float r = std::hypot(ex - cx, ey - cy);
  cx += float(ui.view_x);
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->AddCircleFilled(ImVec2(cx, cy), r, IM_COL32(255, 200, 60, 40), 48);
  dl->AddCircle(ImVec2(cx, cy), r, IM_COL32(255, 200, 60, 220), 48, 2.0f);
  dl->AddCircleFilled(ImVec2(cx, cy), 3.0f, IM_COL32(255, 200, 60, 255));
}

// The selection rectangle (view coordinates) and how many particles it holds.
void drawRubberBand(const ViewerUi& ui, float x1, float y1) {
  const ImVec2 a(std::min(ui.drag_x0, x1), std::min(ui.drag_y0, y1));
  const ImVec2 b(std::max(ui.drag_x0, x1), std::max(ui.drag_y0, y1));
  const std::vector<int> inside = particlesInRect(ui.camera, ui.view_w, ui.view_h, ui.frame.x, ui.frame.y,
                                                  ui.frame.z, {a.x, a.y, b.x, b.y});
  const ImVec2 off(float(ui.view_x), 0.0f);
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->AddRectFilled(ImVec2(a.x + off.x, a.y), ImVec2(b.x + off.x, b.y), IM_COL32(80, 180, 255, 40));
  dl->AddRect(ImVec2(a.x + off.x, a.y), ImVec2(b.x + off.x, b.y), IM_COL32(80, 180, 255, 230), 0.0f, 0, 1.5f);
  char label[64];
  std::snprintf(label, sizeof label, "%zu particles", inside.size());
  dl->AddText(ImVec2(b.x + off.x + 6.0f, b.y + 2.0f), IM_COL32(230, 240, 255, 255), label);
}

}  // namespace

void handleInput(ViewerUi& ui, ViewerSession& session) {
  handleKeys(ui, session);
  const ImGuiIO& io = ImGui::GetIO();
  const float mx = io.MousePos.x - float(ui.view_x), my = io.MousePos.y;  // view coordinates
  const bool over_view =
      !io.WantCaptureMouse && mx >= 0.0f && mx < float(ui.view_w) && my >= 0.0f && my < float(ui.view_h);

  // A drag starts over the 3D view and lasts until its button is released,
  // wherever the mouse goes meanwhile.
  if (ui.drag_button < 0 && over_view) {
    for (int b = 0; b < 3; ++b)
      if (ImGui::IsMouseClicked(b)) {
        ui.drag_button = b;
        ui.drag_x0 = mx, ui.drag_y0 = my;
        // The motion between the press and this frame still counts.
        ui.drag_last_x = ui.press_x[b] - float(ui.view_x), ui.drag_last_y = ui.press_y[b];
        ui.drag_selects = b == 0 && !io.KeyShift && ui.mode == PickMode::BoxSelect;
        if (b == 0 && !io.KeyShift && ui.mode == PickMode::SphereBrush) brushAt(ui, session, mx, my);
        break;
      }
  }
  if (ui.drag_button >= 0) {
    // Motion since the last frame of this drag (not io.MouseDelta, which in the
    // drag's first frame holds the move before the button went down).
    const float dx = mx - ui.drag_last_x, dy = my - ui.drag_last_y;
    ui.drag_last_x = mx, ui.drag_last_y = my;
    const bool pan = ui.drag_button != 0 || io.KeyShift;
    if (ui.drag_selects) {
      drawRubberBand(ui, mx, my);
    } else if (pan) {
      const float s = panScale(ui);
      ui.camera.pan(-dx * s, dy * s);
    } else if (ui.mode == PickMode::Camera) {
      ui.camera.orbit(-dx * kOrbitRadiansPerPixel, dy * kOrbitRadiansPerPixel);
    }
    if (ImGui::IsMouseReleased(ui.drag_button)) {
      if (ui.drag_selects) {
        if (std::abs(mx - ui.drag_x0) >= 3.0f && std::abs(my - ui.drag_y0) >= 3.0f)
          selectBox(ui, session, ui.drag_x0, ui.drag_y0, mx, my);
        else
          ui.report("drag a rectangle over the fluid to select the region", false);
      }
      ui.drag_button = -1;
      ui.drag_selects = false;
    }
  }

  if (over_view && io.MouseWheel != 0.0f) {
    if (ui.mode == PickMode::SphereBrush && !io.KeyCtrl)
      ui.brush_radius = std::clamp(ui.brush_radius * std::pow(1.1f, io.MouseWheel), 0.005f, 0.5f);
    else
      ui.camera.zoom(std::pow(0.9f, io.MouseWheel));
  }

  ui.hover_particle = -1;
  if (ui.mode == PickMode::SphereBrush && over_view && ui.drag_button < 0) {
    ui.hover_particle = particleUnder(ui, mx, my);
    drawBrush(ui);
  }
}

}  // namespace ff::viewer
