// script.cpp - reads viewer scripts: {"actions": [{"at": t, ACTION: value}]}.
#include "viewer/script.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <optional>

#include "core/error.h"
#include "core/text_file.h"
#include "render/fluid_mode.h"
#include "scene/scene_json.h"

namespace ff::viewer {

namespace {

using json = nlohmann::json;

const char* const kActionKeys[] = {"target", "region",     "camera", "params", "render", "panel",
                                   "pause",  "screenshot", "save",   "play",   "quit"};

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

struct Reader {
  std::string source;

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw Error(source + ": " + (path.empty() ? std::string() : path + ": ") + problem);
  }

  void keys(const json& j, const std::string& path, std::initializer_list<const char*> known) const {
    if (!j.is_object()) fail(path, "must be an object");
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      for (const char* k : known) ok = ok || it.key() == k;
      if (ok) continue;
      std::string list;
      for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      fail(child(path, it.key()), "unknown key (expected one of: " + list + ")");
    }
    if (j.empty()) fail(path, "must not be empty");
  }

  double number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "must be a number");
    const double v = j.get<double>();
    if (!std::isfinite(v) || !std::isfinite(float(v))) fail(path, "must be a finite number");
    return v;
  }

  bool boolean(const json& j, const std::string& path) const {
    if (!j.is_boolean()) fail(path, "must be true or false");
    return j.get<bool>();
  }

  void isTrue(const json& j, const std::string& path) const {
    if (!j.is_boolean() || !j.get<bool>()) fail(path, "must be true");
  }

  std::string string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "must be a string");
    return j.get<std::string>();
  }
};

RenderAction readRender(const Reader& r, const json& j, const std::string& path) {
  r.keys(j, path, {"mode", "control", "ghost", "region"});
  RenderAction a;
  if (j.contains("mode")) {
    const std::string m = r.string(j["mode"], child(path, "mode"));
    const std::optional<render::FluidMode> mode = render::fluidModeByName(m);
    if (!mode)
      r.fail(child(path, "mode"), std::string("must be ") + render::kFluidModeNames + " (got '" + m + "')");
    a.particles = *mode == render::FluidMode::Particles;
  }
  if (j.contains("control")) a.control = r.boolean(j["control"], child(path, "control"));
  if (j.contains("ghost")) a.ghost = r.boolean(j["ghost"], child(path, "ghost"));
  if (j.contains("region")) a.region = r.boolean(j["region"], child(path, "region"));
  return a;
}

std::string lowerExtension(const std::string& file) {
  std::string ext = std::filesystem::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  return ext;
}

ScriptAction readAction(const Reader& r, const json& j, const std::string& path,
                        const std::string& base_dir) {
  if (!j.is_object()) r.fail(path, "must be an object {\"at\": seconds, ACTION: value}");
  std::string action_key;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() == "at") continue;
    bool known = false;
    for (const char* k : kActionKeys) known = known || it.key() == k;
    if (!known) {
      std::string list = "at";
      for (const char* k : kActionKeys) list += std::string(", ") + k;
      r.fail(child(path, it.key()), "unknown key (expected one of: " + list + ")");
    }
    if (!action_key.empty())
      r.fail(path, "holds two actions ('" + action_key + "' and '" + it.key() + "'); give one per entry");
    action_key = it.key();
  }
  if (!j.contains("at")) r.fail(child(path, "at"), "required key is missing");
  if (action_key.empty())
    r.fail(path,
           "has no action (one of: target, region, camera, params, render, panel, screenshot, save, "
           "pause, play, quit)");

  ScriptAction a;
  a.where = r.source + ": " + path;
  a.at = r.number(j["at"], child(path, "at"));
  if (!(a.at >= 0.0)) r.fail(child(path, "at"), "must be >= 0 seconds (got " + fmt(a.at) + ")");
  const json& v = j[action_key];
  const std::string vpath = child(path, action_key);
  if (action_key == "target") {
    if (v.is_string() && v.get<std::string>() == "none") {
      a.kind = ScriptAction::Kind::NoTarget;
    } else {
      a.kind = ScriptAction::Kind::Target;
      a.target = parseTargetSpec(v, r.source, vpath, base_dir);
    }
  } else if (action_key == "region") {
    a.kind = ScriptAction::Kind::Region;
    a.region = parseRegionDesc(v, r.source, vpath);
  } else if (action_key == "camera") {
    a.kind = ScriptAction::Kind::Camera;
    a.camera = parseCameraDesc(v, r.source, vpath);
  } else if (action_key == "params") {
    a.kind = ScriptAction::Kind::Params;
    Params check;  // ranges do not depend on each other: check the keys given over valid values
    parseParamsOverlay(v, r.source, vpath, check);
    if (v.empty()) r.fail(vpath, "must not be empty");
    try {
      validateParams(check, "");
    } catch (const Error& e) {
      // validateParams names fields "params.group.key"; put them under this entry.
      r.fail("", path + "." + e.what());
    }
    a.params = v;
  } else if (action_key == "render") {
    a.kind = ScriptAction::Kind::Render;
    a.render = readRender(r, v, vpath);
  } else if (action_key == "panel") {
    a.kind = ScriptAction::Kind::Panel;
    a.panel = r.boolean(v, vpath);
  } else if (action_key == "screenshot") {
    a.kind = ScriptAction::Kind::Screenshot;
    a.screenshot = r.string(v, vpath);
    if (a.screenshot.empty()) r.fail(vpath, "must not be empty");
    if (lowerExtension(a.screenshot) != ".png")
      r.fail(vpath, "must be a .png file name (got '" + a.screenshot + "')");
  } else if (action_key == "save") {
    a.kind = ScriptAction::Kind::Save;
    a.save = r.string(v, vpath);
    if (a.save.empty()) r.fail(vpath, "must not be empty");
    if (lowerExtension(a.save) != ".json") r.fail(vpath, "must be a .json file name (got '" + a.save + "')");
  } else if (action_key == "pause") {
    a.kind = ScriptAction::Kind::Pause;
    r.isTrue(v, vpath);
  } else if (action_key == "play") {
    a.kind = ScriptAction::Kind::Play;
    r.isTrue(v, vpath);
  } else {
    a.kind = ScriptAction::Kind::Quit;
    r.isTrue(v, vpath);
  }
  return a;
}

}  // namespace

Script parseScript(const std::string& text, const std::string& source, const std::string& base_dir) {
  const json root = parseJsonStrict(text, source);
  const Reader r{source};
  if (!root.is_object()) r.fail("", "a script must be a JSON object {\"actions\": [...]}");
  for (auto it = root.begin(); it != root.end(); ++it)
    if (it.key() != "actions") r.fail(it.key(), "unknown key (expected: actions)");
  if (!root.contains("actions")) r.fail("actions", "required key is missing");
  const json& list = root["actions"];
  if (!list.is_array()) r.fail("actions", "must be an array");
  Script script;
  script.source = source;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "actions[" + std::to_string(i) + "]";
    ScriptAction a = readAction(r, list[i], path, base_dir);
    if (!script.actions.empty() && a.at < script.actions.back().at)
      r.fail(child(path, "at"),
             "times must not decrease (got " + fmt(a.at) + " after " + fmt(script.actions.back().at) + ")");
    script.actions.push_back(std::move(a));
  }
  return script;
}

Script loadScript(const std::string& path) {
  const std::string text = readTextFile(path, "script");
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  return parseScript(text, path, dir);
}

void applyParamsAction(const ScriptAction& action, Params& params) {
  if (action.kind != ScriptAction::Kind::Params) return;
  parseParamsOverlay(action.params, action.where, "params", params);
}

const char* actionName(ScriptAction::Kind kind) {
  switch (kind) {
    case ScriptAction::Kind::Target:
      return "target";
    case ScriptAction::Kind::NoTarget:
      return "target none";
    case ScriptAction::Kind::Region:
      return "region";
    case ScriptAction::Kind::Camera:
      return "camera";
    case ScriptAction::Kind::Params:
      return "params";
    case ScriptAction::Kind::Render:
      return "render";
    case ScriptAction::Kind::Panel:
      return "panel";
    case ScriptAction::Kind::Screenshot:
      return "screenshot";
    case ScriptAction::Kind::Save:
      return "save";
    case ScriptAction::Kind::Pause:
      return "pause";
    case ScriptAction::Kind::Play:
      return "play";
    case ScriptAction::Kind::Quit:
      return "quit";
  }
  return "?";
}

}  // namespace ff::viewer
