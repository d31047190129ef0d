// target_catalog.cpp - lists target choices and reads typed targets.
#include "viewer/target_catalog.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include "core/error.h"
#include "scene/scene_json.h"

namespace ff::viewer {

namespace fs = std::filesystem;

namespace {

bool isMeshFile(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  return ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".off";
}

std::string trim(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

}  // namespace

std::vector<std::string> meshFilesOnPath(const std::string& mesh_path) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= mesh_path.size()) {
    size_t end = mesh_path.find(':', start);
    if (end == std::string::npos) end = mesh_path.size();
    const std::string folder = mesh_path.substr(start, end - start);
    start = end + 1;
    if (folder.empty()) continue;
    std::error_code ec;
    std::vector<std::string> here;
    fs::directory_iterator it(folder, ec), stop;
    for (; !ec && it != stop; it.increment(ec)) {
      std::error_code ec2;
      if (it->is_regular_file(ec2) && isMeshFile(it->path())) here.push_back(it->path().string());
    }
    std::sort(here.begin(), here.end());
    for (const std::string& f : here)
      if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
  }
  return out;
}

std::vector<TargetChoice> targetChoices(const std::string& mesh_path) {
  std::vector<TargetChoice> out;
  TargetChoice none;
  none.label = "No control";
  none.none = true;
  out.push_back(none);
  const std::pair<const char*, TargetKind> builtins[] = {{"sphere", TargetKind::Sphere},
                                                         {"box", TargetKind::Box},
                                                         {"torus", TargetKind::Torus},
                                                         {"capsule", TargetKind::Capsule}};
  for (const auto& [name, kind] : builtins) {
    TargetChoice c;
    c.label = name;
    c.spec.kind = kind;
    out.push_back(c);
  }
  const std::vector<std::string> files = meshFilesOnPath(mesh_path);
  std::map<std::string, int> name_count;
  for (const std::string& f : files) ++name_count[fs::path(f).filename().string()];
  for (const std::string& f : files) {
    TargetChoice c;
    const std::string name = fs::path(f).filename().string();
    c.label = name_count[name] > 1 ? name + " (" + fs::path(f).parent_path().string() + ")" : name;
    c.spec.kind = TargetKind::Mesh;
    c.spec.mesh = f;
    c.spec.resolved_path = f;
    out.push_back(c);
  }
  return out;
}

TargetSpec parseTypedTarget(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty())
    throw Error("typed target: empty (type sphere, box, torus, capsule, a mesh path or {\"shape\": ...})");
  const nlohmann::json j =
      (t.front() == '{' || t.front() == '"') ? parseJsonStrict(t, "typed target") : nlohmann::json(t);
  return parseTargetSpec(j, "typed target", "", ".");
}

}  // namespace ff::viewer
