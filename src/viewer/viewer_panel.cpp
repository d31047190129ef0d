// viewer_panel.cpp - the ImGui control panel: run controls, target list,
// region selection, render options, every parameter, timings, metrics, help.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/param_table.h"
#include "render/scene_renderer.h"
#include "viewer/viewer_ui.h"

namespace ff::viewer {

namespace {

const ImVec4 kErrorColour(1.0f, 0.45f, 0.4f, 1.0f);
const ImVec4 kDimColour(0.65f, 0.7f, 0.75f, 1.0f);

void errorText(const std::string& text) {
  if (text.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

// A small colour square and a wrapped text beside it.
void legendLine(const char* id, const float* rgb, float alpha, const char* text) {
  const float size = ImGui::GetTextLineHeight();
  ImGui::ColorButton(id, ImVec4(rgb[0], rgb[1], rgb[2], alpha),
                     ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoDragDrop, ImVec2(size, size));
  ImGui::SameLine();
  ImGui::TextWrapped("%s", text);
}

// A plot of values in [lo, hi] with its y values: the top and bottom of the
// scale at the left edge, the last value in the title.
void plotWithScale(const char* id, const char* title, const History& b, float lo, float hi, float height) {
  char overlay[96];
  const float last = b.latest();
  std::snprintf(overlay, sizeof overlay, "%s  now %.3f", title, double(last));
  ImGui::PlotLines(id, b.data(), int(b.count()), int(b.offset()), overlay, lo, hi,
                   ImVec2(ImGui::GetContentRegionAvail().x, height));
  const ImVec2 a = ImGui::GetItemRectMin(), z = ImGui::GetItemRectMax();
  ImDrawList* d = ImGui::GetWindowDrawList();
  const ImU32 c = ImGui::GetColorU32(kDimColour);
  char label[32];
  std::snprintf(label, sizeof label, "%.2g", double(hi));
  d->AddText(ImVec2(a.x + 3.0f, a.y + 1.0f), c, label);
  std::snprintf(label, sizeof label, "%.2g", double(lo));
  d->AddText(ImVec2(a.x + 3.0f, z.y - ImGui::GetTextLineHeight() - 1.0f), c, label);
}

void runSection(ViewerUi& ui, ViewerSession& session) {
  if (ImGui::Button(ui.playing ? "Pause (space)" : "Play (space)")) ui.playing = !ui.playing;
  ImGui::SameLine();
  if (ImGui::Button("Step (.)")) {
    ui.playing = false;
    ui.step_once = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Reset (R)")) ui.reset_request = true;
  ImGui::SameLine();
  if (ImGui::Button("Scene (shift R)")) ui.reset_to_scene_request = true;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Reset to the scene as loaded: its parameters, region and target schedule");
  ImGui::SliderInt("steps / frame", &ui.steps_per_frame, 1, 32);
  ImGui::SliderFloat("frame budget ms", &ui.frame_budget_ms, 5.0f, 200.0f, "%.0f");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Stop stepping in a frame after this long (at least one step), so the view stays live");
  const Simulation& sim = session.sim();
  ImGui::Text("t = %.3f s   step %ld   substeps %d", sim.time(), sim.stepCount(), sim.metrics().substeps);
  if (ImGui::Button(ui.recording.active() ? "Stop recording (E)" : "Record (E)")) ui.record_request = true;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Export frames at %g fps of simulated time into a new take_NNN folder of %s",
                      ui.recording.options().fps, ui.recording.options().dir.c_str());
  ImGui::SameLine();
  if (ui.recording.active())
    ImGui::TextColored(kErrorColour, "REC %ld frames: %s", ui.recording.frames(),
                       ui.recording.folder().c_str());
  else
    ImGui::TextColored(kDimColour, "into %s", ui.recording.options().dir.c_str());
  // Save scene...: the file name, then the button. An existing file is kept:
  // the scene then goes to the next free name, and the message says which.
  ImGui::SetNextItemWidth(-110.0f);
  const bool enter = ImGui::InputText("##save_path", ui.save_path, sizeof ui.save_path,
                                      ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if (ImGui::Button("Save scene...") || enter) {
    try {
      saveScene(ui, session, ui.save_path, true);
    } catch (const Error& e) {
      ui.report(std::string("scene not saved: ") + e.what(), true);
    }
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Write the container, fluid, parameters, region, target and camera to this scene file\n"
        "(flowform run and flowform view read it); an existing file is never replaced");
}

void targetSection(ViewerUi& ui, ViewerSession& session) {
  ImGui::Text("current: %s%s", session.targetLabel().c_str(),
              session.followsSchedule() && !session.scene().schedule.empty() ? "  (scene schedule)" : "");
  const float list_h =
      ImGui::GetTextLineHeightWithSpacing() * float(std::min<size_t>(ui.choices.size(), 9) + 0.5f);
  if (ImGui::BeginListBox("##targets", ImVec2(-1.0f, list_h))) {
    for (size_t i = 0; i < ui.choices.size(); ++i) {
      char label[600];
      if (i <= 9)
        std::snprintf(label, sizeof label, "%zu  %s", i, ui.choices[i].label.c_str());
      else
        std::snprintf(label, sizeof label, "   %s", ui.choices[i].label.c_str());
      ImGui::PushID(int(i));
      if (ImGui::Selectable(label, ui.chosen == int(i))) pickChoice(ui, session, int(i));
      if (ImGui::IsItemHovered() && !ui.choices[i].spec.resolved_path.empty())
        ImGui::SetTooltip("%s", ui.choices[i].spec.resolved_path.c_str());
      ImGui::PopID();
    }
    ImGui::EndListBox();
  }
  ImGui::SetNextItemWidth(-60.0f);
  const bool enter = ImGui::InputTextWithHint("##typed", "mesh path, shape or {\"shape\": ...}", ui.typed,
                                              sizeof ui.typed, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if (ImGui::Button("Apply") || enter) pickTypedTarget(ui, session);
  errorText(ui.target_error);
}

void regionSection(ViewerUi& ui, ViewerSession& session) {
  int mode = int(ui.mode);
  ImGui::RadioButton("camera", &mode, int(PickMode::Camera));
  ImGui::SameLine();
  ImGui::RadioButton("box select (B)", &mode, int(PickMode::BoxSelect));
  ImGui::SameLine();
  ImGui::RadioButton("sphere (S)", &mode, int(PickMode::SphereBrush));
  if (mode != int(ui.mode)) toggleMode(ui, PickMode(mode));
  ImGui::SliderFloat("brush radius", &ui.brush_radius, 0.005f, 0.5f, "%.3f m", ImGuiSliderFlags_Logarithmic);
  if (ImGui::Button("All fluid (A)")) applyRegion(ui, session, RegionDesc());
  ImGui::SameLine();
  if (ImGui::Button("Scene's region")) applyRegion(ui, session, session.scene().region);
  ImGui::TextWrapped("region: %s", describeRegion(session.region()).c_str());
  ImGui::TextWrapped("controlled fluid: %ld of %ld particles", session.sim().controlledCount(),
                     session.scene().fluidCount());
  // Legend: which liquid is controlled, and what the overlays mean.
  legendLine("##legend_region", render::kRegionColor, 1.0f,
             session.region().kind == RegionDesc::Kind::All
                 ? "controlled: all the liquid (no region box); it flows into the target"
                 : "controlled: the liquid inside the orange region when the target was set; the rest flows "
                   "freely");
  legendLine("##legend_ghost", render::kGhostColor, 0.8f, "target shape (ghost)");
  legendLine("##legend_filled", render::kControlFilledColor, 1.0f,
             "control particle with liquid around (s = 0)");
  legendLine("##legend_empty", render::kControlEmptyColor, 1.0f, "control particle still empty (s = 1)");
  switch (ui.mode) {
    case PickMode::BoxSelect:
      ImGui::TextColored(kDimColour, "Drag a rectangle over the fluid (Esc: back to camera)");
      break;
    case PickMode::SphereBrush:
      ImGui::TextColored(kDimColour, "Click the fluid; the wheel sizes the brush (ctrl+wheel zooms)");
      break;
    case PickMode::Camera:
      break;
  }
  errorText(ui.region_error);
}

void renderSection(ViewerUi& ui, const ViewerSession& session) {
  int mode = ui.render.mode == render::FluidMode::ScreenSpace ? 0 : 1;
  ImGui::RadioButton("screen-space fluid", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("particles (M)", &mode, 1);
  ui.render.mode = mode == 0 ? render::FluidMode::ScreenSpace : render::FluidMode::Particles;
  ImGui::Checkbox("control s_i (O)", &ui.render.show_control);
  ImGui::SameLine();
  ImGui::Checkbox("ghost (G)", &ui.render.show_ghost);
  ImGui::Checkbox("region (W)", &ui.render.show_region);
  ImGui::SameLine();
  ImGui::Checkbox("container", &ui.render.show_container);
  ImGui::SliderInt("smoothing passes", &ui.render.smoothing_iterations, 0, 10);
  ImGui::SliderFloat("smoothing scale", &ui.render.smoothing_scale, 0.25f, 4.0f, "%.2f");
  ImGui::ColorEdit3("fluid colour", ui.render.fluid_color);
  ImGui::SliderFloat("absorption 1/m", &ui.render.absorption, 0.0f, 300.0f, "%.1f");
  ImGui::Checkbox("time render passes", &ui.render.profile_passes);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("A glFinish after each pass: the split costs some speed");
  if (ui.render.profile_passes) {
    const render::RenderTimings& t = ui.render_timings;
    ImGui::Text("background %.1f  depth %.1f  smoothing %.1f ms", t.background_ms, t.depth_ms,
                t.smoothing_ms);
    ImGui::Text("thickness %.1f  composite %.1f  overlays %.1f ms", t.thickness_ms, t.composite_ms,
                t.overlay_ms);
  }
  if (ImGui::Button("Reset camera (C)")) ui.camera = homeCamera(ui, session);
}

// One parameter widget; true when the user changed it this frame.
bool floatParam(const char* label, float& v, float lo, float hi, bool log, const char* help) {
  const bool changed =
      ImGui::SliderFloat(label, &v, lo, hi, "%.5g",
                         log ? ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoRoundToFormat
                             : ImGuiSliderFlags_NoRoundToFormat);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\n(ctrl+click to type a value)", help);
  return changed;
}

bool intParam(const char* label, int& v, int lo, int hi, const char* help) {
  const bool changed = ImGui::SliderInt(label, &v, lo, hi);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\n(ctrl+click to type a value)", help);
  return changed;
}

// A mode that is on (1) or off (0), as a checkbox.
bool modeParam(const char* label, int& v, const char* help) {
  bool on = v != 0;
  const bool changed = ImGui::Checkbox(label, &on);
  if (changed) v = on ? 1 : 0;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", help);
  return changed;
}

// Whether GROUP.KEY acts with parameters p (paramActs).
bool acts(const Params& p, const char* group, const char* key) {
  for (const ParamInfo& info : paramTable())
    if (std::string(info.group) == group && std::string(info.key) == key) return paramActs(info, p);
  return true;
}

void paramsSection(ViewerUi& ui, ViewerSession& session) {
  // Show the session's values unless an edit is waiting to be fixed.
  if (ui.params_error.empty()) ui.edit = session.params();
  Params& p = ui.edit;
  bool changed = false;
  ImGui::PushItemWidth(-150.0f);
  if (ImGui::TreeNodeEx("Fluid", ImGuiTreeNodeFlags_DefaultOpen)) {
    FluidParams& f = p.fluid;
    changed |= floatParam("particle mass kg", f.particle_mass, 1e-5f, 1e-2f, true, "mass of one particle");
    changed |= floatParam("particle radius m", f.particle_radius, 1e-3f, 0.05f, true,
                          "drawn radius (rendering and export only)");
    changed |= floatParam("smoothing radius h", f.smoothing_radius, 2e-3f, 0.1f, true, "SPH kernel support");
    changed |= floatParam("rest density", f.rest_density, 100.0f, 3000.0f, true, "kg/m^3");
    changed |= floatParam("gas constant k", f.gas_constant, 0.0f, 20.0f, true, "p = k (rho - rho0)");
    changed |= floatParam("viscosity mu", f.viscosity, 0.0f, 1.0f, true, "viscosity coefficient");
    float frame = f.time_step;
    if (floatParam("time step s", frame, 5e-4f, 0.02f, true, "one step of simulated time")) {
      f.setTimeStep(frame);  // a step in seconds: the frame step no longer follows h
      changed = true;
    }
    changed |= ImGui::SliderFloat3("gravity m/s^2", f.gravity, -20.0f, 20.0f, "%.2f");
    changed |= floatParam("cfl", f.cfl, 0.05f, 1.0f, false, "substeps: dt <= cfl h / (c + v_max)");
    changed |= intParam("max substeps", f.max_substeps, 1, 64, "upper bound on CFL substeps per step");
    changed |= modeParam("carry substeps", f.substep_carry,
                         "fluid.substep_carry: substeps as long as the CFL conditions allow, the last one "
                         "ending past the step (the fluid's clock leads by less than a substep), or equal "
                         "substeps that end on it");
    changed |= floatParam("max step fraction", f.max_step_fraction, 0.05f, 1.0f, false,
                          "no particle moves more than this fraction of h per substep");
    ImGui::TreePop();
  }
  if (ImGui::TreeNodeEx("Control", ImGuiTreeNodeFlags_DefaultOpen)) {
    ControlParams& c = p.control;
    // The sliders of the parameters that act (paramActs): the radius in
    // control spacings or in metres, the normalised pull or the paper's.
    if (acts(p, "control", "radius"))
      changed |= floatParam("control radius m", c.radius, 5e-3f, 0.1f, true,
                            "influence radius of a control particle");
    else
      changed |= floatParam("radius spacings", c.radius_spacings, 0.5f, 10.0f, true,
                            "control.radius_spacings: the influence radius in control particle spacings, set "
                            "at every target");
    changed |= modeParam("normalised pull", c.normalise,
                         "control.normalise: eq. 4 and 6 normalised by the local control weight "
                         "(attraction_g, velocity_rate), or as the paper writes them (w_a, w_v, units)");
    if (acts(p, "control", "attraction_g")) {
      changed |= floatParam("attraction g", c.attraction_g, 0.0f, 50.0f, false,
                            "control.attraction_g: the most attraction, in units of gravity");
      changed |= floatParam("velocity rate", c.velocity_rate, 0.0f, 10.0f, false,
                            "control.velocity_rate: the velocity force's rate, in units of sqrt(g / radius)");
    } else {
      changed |= floatParam("attraction w_a", c.attraction, 0.0f, 1e-2f, true, "eq. 4 weight");
      changed |= floatParam("velocity w_v", c.velocity, 0.0f, 1e-2f, true, "eq. 6 weight");
      int units = int(c.units);
      const char* names[] = {"acceleration", "force_density", "force"};
      if (ImGui::Combo("force units", &units, names, 3)) {
        c.units = ControlForceUnits(units);
        changed = true;
      }
    }
    changed |=
        floatParam("feedback", c.feedback, 0.0f, 1.0f, false, "fluid feedback on the control particles");
    changed |= floatParam("gravity compensation", c.gravity_compensation, 0.0f, 1.0f, false,
                          "share of gravity the control carries inside the target");
    changed |= floatParam("recapture", c.recapture, 0.0f, 10.0f, false,
                          "control.recapture: fluid out of the control's reach flies back at this many "
                          "sqrt(g radius) (0 = off)");
    ImGui::TreePop();
  }
  if (ImGui::TreeNodeEx("Shape matching", ImGuiTreeNodeFlags_DefaultOpen)) {
    ShapeMatchParams& s = p.shape;
    changed |= floatParam("stiffness alpha", s.stiffness, 0.0f, 1.0f, false, "eq. 7");
    // The step the shape matching takes: with time_step_fall > 0 the scene's
    // fall time sets it; dragging gives it in seconds and turns that off.
    float step = s.timeStepFor(p.control.radius, p.fluid.gravity);
    char step_help[256] = "the shape-matching clock";
    if (s.time_step_fall > 0.0f)
      std::snprintf(
          step_help, sizeof step_help,
          "the shape-matching clock, set by shape_matching.time_step_fall: %.4g fall times "
          "sqrt(r / g) of the control radius r = %.4g m; dragging gives it in seconds (time_step_fall 0)",
          double(s.time_step_fall), double(p.control.radius));
    if (floatParam("sm time step s", step, 1e-3f, 0.05f, true, step_help)) {
      s.setTimeStep(step);
      changed = true;
    }
    changed |= intParam("cluster stride", s.cluster_stride, 1, 8, "a cluster on every n-th reference voxel");
    changed |= intParam("cluster half width", s.cluster_half_width, 1, 6, "cluster size in voxels");
    changed |=
        intParam("rotation iterations", s.rotation_iterations, 1, 32, "quaternion iterations per step");
    changed |= floatParam("damping", s.damping, 0.0f, 1.0f, false, "deformation damping per step");
    ImGui::TreePop();
  }
  ImGui::PopItemWidth();
  if (changed) applyParams(ui, session, p);
  errorText(ui.params_error);
  if (!ui.params_error.empty() && ImGui::Button("Discard the rejected edit")) ui.params_error.clear();
  if (ImGui::Button("Scene's parameters")) applyParams(ui, session, session.scene().params);
}

void timingSection(ViewerUi& ui, ViewerSession& session) {
  Simulation& sim = session.sim();
  // The device names can be long: the backend on one line, its device wrapped below.
  ImGui::Text("backend: %s", sim.backend().name().c_str());
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextColored(kDimColour, "%s", sim.backend().device().c_str());
  ImGui::PopTextWrapPos();
  if (!session.backendNote().empty()) ImGui::TextColored(kDimColour, "%s", session.backendNote().c_str());
  const double fps = ui.frame_ms.value > 0.0 ? 1000.0 / ui.frame_ms.value : 0.0;
  ImGui::Text("FPS %.1f   frame %.1f ms", fps, ui.frame_ms.value);
  ImGui::Text("simulation %.1f ms/frame (%d steps)   render %.1f ms", ui.sim_ms_per_frame.value,
              ui.steps_last_frame, ui.render_ms.value);
  ImGui::Checkbox("profile phases and stages", &ui.profile_phases);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("each phase waits for the device: OpenCL's phases, forces and solver stages are timed");
  sim.setProfiling(ui.profile_phases);
  if (ImGui::BeginTable("phases", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("phase");
    ImGui::TableSetupColumn("last ms");
    ImGui::TableSetupColumn("smoothed");
    ImGui::TableHeadersRow();
    double last_total = 0.0;
    for (size_t p = 0; p < size_t(Phase::Count); ++p) {
      last_total += sim.lastStepMs()[p];
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(phaseName(Phase(p)));
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", sim.lastStepMs()[p]);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", ui.phase_ms[p].value);
      for (const StageTime& s : sim.lastStepStageMs()) {  // the phase's named stages (run mean)
        if (s.phase != phaseName(Phase(p))) continue;
        double mean = 0.0;
        for (const StageTime& t : sim.stageMs())
          if (t.phase == s.phase && t.name == s.name) mean = t.ms / double(std::max(1L, sim.stepCount()));
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::Text("  %s", s.name.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", s.ms);
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", mean);
      }
    }
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted("step");
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", last_total);
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", ui.step_ms.value);
    ImGui::EndTable();
  }
}

void metricsSection(ViewerUi& ui, ViewerSession& session) {
  const Simulation& sim = session.sim();
  const StepMetrics& m = sim.metrics();
  ImGui::Text("fluid particles %ld   control particles %ld", session.scene().fluidCount(), m.control_count);
  ImGui::Text("iou %.3f   coverage %.3f", m.iou, m.coverage);
  ImGui::Text("filled %.3f (thin parts %.3f)   captured %.3f   stray %.3f", m.filled, m.filled_thin,
              m.captured, m.stray);
  ImGui::Text("max speed %.3f m/s   density error %.3f", m.max_speed, m.density_error);
  const float seconds = float(ui.iou.count()) * session.params().fluid.time_step;
  char title[64];
  std::snprintf(title, sizeof title, "iou, last %.1f s", double(seconds));
  plotWithScale("##iou", title, ui.iou, 0.0f, 1.0f, 70.0f);
  std::snprintf(title, sizeof title, "coverage, last %.1f s", double(seconds));
  plotWithScale("##coverage", title, ui.coverage, 0.0f, 1.0f, 50.0f);
  std::snprintf(title, sizeof title, "filled, last %.1f s", double(seconds));
  plotWithScale("##filled", title, ui.filled, 0.0f, 1.0f, 50.0f);
  std::snprintf(title, sizeof title, "stray (out of the control's reach), last %.1f s", double(seconds));
  plotWithScale("##stray", title, ui.stray, 0.0f, 1.0f, 50.0f);
}

void messagesSection(const ViewerUi& ui) {
  for (const ViewerUi::Message& m : ui.messages) {
    if (m.error)
      errorText(m.text);
    else
      ImGui::TextWrapped("%s", m.text.c_str());
  }
}

void drawHelp(bool* open, float x) {
  ImGui::SetNextWindowPos(ImVec2(x + 16.0f, 16.0f), ImGuiCond_Appearing);
  if (!ImGui::Begin("Help (H)", open, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return;
  }
  static const char* const kRows[][2] = {
      {"left drag", "orbit (camera mode)"},
      {"right / middle drag, shift+left", "pan"},
      {"wheel, + / -", "zoom (sphere brush: wheel sizes the brush)"},
      {"C, Home", "reset the camera"},
      {"space", "play / pause"},
      {". or right arrow", "single step (pauses)"},
      {"R", "reset: fluid back to time 0, edits kept"},
      {"shift+R", "reset to the scene as loaded"},
      {"B", "box select: drag a rectangle over the fluid"},
      {"S", "sphere brush: click the fluid"},
      {"Esc", "back to camera mode"},
      {"A", "region: all fluid"},
      {"0", "no control"},
      {"1 .. 9", "target list entries 1 .. 9"},
      {"M", "screen-space fluid / particles"},
      {"O, G, W", "control particles (s_i), target ghost, region"},
      {"P", "screenshot (flowform_NNNN.png, current folder)"},
      {"E", "start / stop recording frames (a new take_NNN folder each time)"},
      {"Tab", "hide / show the panel"},
      {"H, F1", "this help"},
      {"ctrl+Q", "quit"},
  };
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    for (const auto& row : kRows) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(row[0]);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(row[1]);
    }
    ImGui::EndTable();
  }
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 520.0f);
  ImGui::TextWrapped(
      "Reset (R) keeps the edited parameters, the region and the picked target (or No control); when no "
      "target was picked, the scene's schedule plays again. Sliders take effect at once; ctrl+click a "
      "slider to type a value. Values the engine rejects are shown in red and not applied.");
  ImGui::PopTextWrapPos();
  ImGui::End();
}

void drawPanelWindow(ViewerUi& ui, ViewerSession& session) {
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(float(ui.view_x), float(ui.win_h)), ImGuiCond_Always);
  const std::string title = "flowform: " + session.scene().name + "###panel";
  if (!ImGui::Begin(title.c_str(), nullptr,
                    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    return;
  }
  if (ImGui::CollapsingHeader("Run", ImGuiTreeNodeFlags_DefaultOpen)) runSection(ui, session);
  if (ImGui::CollapsingHeader("Target", ImGuiTreeNodeFlags_DefaultOpen)) targetSection(ui, session);
  if (ImGui::CollapsingHeader("Region", ImGuiTreeNodeFlags_DefaultOpen)) regionSection(ui, session);
  if (ImGui::CollapsingHeader("Metrics", ImGuiTreeNodeFlags_DefaultOpen)) metricsSection(ui, session);
  if (ImGui::CollapsingHeader("Timings", ImGuiTreeNodeFlags_DefaultOpen)) timingSection(ui, session);
  if (ImGui::CollapsingHeader("Render")) renderSection(ui, session);
  if (ImGui::CollapsingHeader("Parameters")) paramsSection(ui, session);
  if (ImGui::CollapsingHeader("Messages", ImGuiTreeNodeFlags_DefaultOpen)) messagesSection(ui);
  ImGui::Separator();
  ImGui::TextColored(kDimColour, "H: help, keys and mouse   Tab: hide panel");
  ImGui::End();
}

}  // namespace

void drawPanel(ViewerUi& ui, ViewerSession& session) {
  if (ui.show_panel) drawPanelWindow(ui, session);
  if (ui.show_help) drawHelp(&ui.show_help, float(ui.view_x));
}

}  // namespace ff::viewer
