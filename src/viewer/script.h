// script.h - timed actions for `flowform view --script FILE` (format:
// docs/VIEWER.md). A script is read whole and checked strictly before the
// window opens; every error names the file and the key path.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/params.h"
#include "scene/scene.h"
#include "target/target_shape.h"

namespace ff::viewer {

using CameraAction = CameraDesc;  // the scene's camera block (scene/scene.h)

struct RenderAction {
  std::optional<bool> particles;  // true: plain particles, false: screen-space fluid
  std::optional<bool> control, ghost, region;
};

struct ScriptAction {
  enum class Kind {
    Target,
    NoTarget,
    Region,
    Camera,
    Params,
    Render,
    Panel,
    Screenshot,
    Save,
    Pause,
    Play,
    Quit
  };
  Kind kind = Kind::Quit;
  double at = 0.0;         // simulated seconds
  std::string where;       // "FILE: actions[i]", for messages while it runs
  TargetSpec target;       // Target
  RegionDesc region;       // Region
  CameraAction camera;     // Camera
  nlohmann::json params;   // Params: the "params" object, scene syntax
  RenderAction render;     // Render
  bool panel = true;       // Panel: show (true) or hide the panel
  std::string screenshot;  // Screenshot: PNG path (relative: to the current directory)
  std::string save;        // Save: scene file path (relative: to the current directory)
};

struct Script {
  std::string source;
  std::vector<ScriptAction> actions;  // sorted by `at` (file order for equal times)
};

// Reads a script file. Mesh paths in targets resolve relative to the script's
// folder, then along FLOWFORM_MESH_PATH (as in scene files).
Script loadScript(const std::string& path);
// Parses script text; `source` names it in messages, `base_dir` anchors mesh paths.
Script parseScript(const std::string& text, const std::string& source, const std::string& base_dir);

// Walks a script as the simulated time grows: an action is due once the
// simulated time has reached its `at` (within 1e-9 s), in file order.
class ScriptCursor {
 public:
  explicit ScriptCursor(Script script) : script_(std::move(script)) {}
  bool due(double sim_time) const {
    return next_ < script_.actions.size() && script_.actions[next_].at <= sim_time + 1e-9;
  }
  // The next due action (call only when due()); moves past it.
  const ScriptAction& take() { return script_.actions[next_++]; }
  bool done() const { return next_ >= script_.actions.size(); }
  const Script& script() const { return script_; }

 private:
  Script script_;
  size_t next_ = 0;
};

// Writes a Params action's keys over `params` (ranges were checked when the
// script was read).
void applyParamsAction(const ScriptAction& action, Params& params);

const char* actionName(ScriptAction::Kind kind);

}  // namespace ff::viewer
