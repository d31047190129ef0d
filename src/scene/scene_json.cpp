// scene_json.cpp - reads scene files (scenes/README.md describes the format).
// The reader is strict: an unknown key, a wrong type or a bad value is an
// ff::Error "FILE: key.path: problem".
#include "scene/scene_json.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <utility>

#include "core/embedded.h"
#include "core/error.h"
#include "core/param_table.h"
#include "core/resource_limits.h"
#include "core/text_file.h"
#include "core/warning.h"
#include "scene/scene.h"

namespace ff {

long SceneDesc::fluidCount() const {
  long n = 0;
  for (const FluidBlockDesc& b : fluid) n += b.count();
  return n;
}

namespace {

using json = nlohmann::json;

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string fmtVec(const Vec3& v) {
  return "[" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + "]";
}

std::string child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
std::string element(const std::string& path, size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

// Reads typed values out of the JSON tree; every failure names the source and
// the key path.
struct Reader {
  std::string source;

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw Error(source + ": " + (path.empty() ? std::string() : path + ": ") + problem);
  }

  const json& object(const json& j, const std::string& path, std::initializer_list<const char*> keys) const {
    return object(j, path, std::vector<const char*>(keys));
  }
  const json& object(const json& j, const std::string& path, const std::vector<const char*>& keys) const {
    if (!j.is_object()) fail(path, "must be an object");
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool known = false;
      for (const char* k : keys) known = known || it.key() == k;
      if (known) continue;
      std::string list;
      for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
      fail(child(path, it.key()), "unknown key (expected one of: " + list + ")");
    }
    return j;
  }

  const json& required(const json& obj, const std::string& path, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(child(path, key), "required key is missing");
    return *it;
  }

  const json& array(const json& j, const std::string& path) const {
    if (!j.is_array()) fail(path, "must be an array");
    return j;
  }

  double number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "must be a number");
    double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "must be a finite number (got " + fmt(v) + ")");
    return v;
  }

  float real(const json& j, const std::string& path) const {
    double v = number(j, path);
    if (!std::isfinite(float(v))) fail(path, "is too large for a float (got " + fmt(v) + ")");
    return float(v);
  }

  int integer(const json& j, const std::string& path) const {
    constexpr double kMin = std::numeric_limits<int>::min(), kMax = std::numeric_limits<int>::max();
    bool ok = j.is_number_integer() || j.is_number_unsigned() ||
              (j.is_number_float() && std::isfinite(j.get<double>()) &&
               std::floor(j.get<double>()) == j.get<double>());
    double v = ok ? j.get<double>() : 0.0;
    if (!ok || v < kMin || v > kMax) fail(path, "must be an integer");
    return int(v);
  }

  std::string string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "must be a string");
    return j.get<std::string>();
  }

  Vec3 vec3(const json& j, const std::string& path) const {
    if (!j.is_array() || j.size() != 3) fail(path, "must be an array of 3 numbers");
    for (const json& e : j)
      if (!e.is_number()) fail(path, "must be an array of 3 numbers");
    return Vec3(real(j[0], element(path, 0)), real(j[1], element(path, 1)), real(j[2], element(path, 2)));
  }

  // Optional keys: leave `out` alone when the key is absent.
  void opt(const json& obj, const std::string& path, const char* key, float& out) const {
    if (obj.contains(key)) out = real(obj[key], child(path, key));
  }
  void opt(const json& obj, const std::string& path, const char* key, int& out) const {
    if (obj.contains(key)) out = integer(obj[key], child(path, key));
  }
  void opt(const json& obj, const std::string& path, const char* key, Vec3& out) const {
    if (obj.contains(key)) out = vec3(obj[key], child(path, key));
  }

  void positive(double v, const std::string& path) const {
    if (!(v > 0)) fail(path, "must be > 0 (got " + fmt(v) + ")");
  }
};

void readUnits(const Reader& r, const json& j, const std::string& path, ControlForceUnits& out) {
  std::string u = r.string(j, path);
  if (u == "acceleration")
    out = ControlForceUnits::Acceleration;
  else if (u == "force_density")
    out = ControlForceUnits::ForceDensity;
  else if (u == "force")
    out = ControlForceUnits::Force;
  else
    r.fail(path, "must be \"acceleration\", \"force_density\" or \"force\" (got '" + u + "')");
}

// Reads the keys given under "params" (the parameter table lists them); the
// ranges are checked afterwards by validateParams.
void readParams(const Reader& r, const json& j, const std::string& base, Params& p) {
  std::vector<const char*> groups;
  for (const std::string& g : paramGroups()) groups.push_back(g.c_str());
  r.object(j, base, groups);
  std::vector<const ParamInfo*> given;
  for (const std::string& group : paramGroups()) {
    if (!j.contains(group)) continue;
    const std::string path = child(base, group);
    std::vector<const char*> keys;
    for (const ParamInfo& info : paramTable())
      if (group == info.group) keys.push_back(info.key);
    const json& obj = r.object(j[group], path, keys);
    for (const ParamInfo& info : paramTable()) {
      if (group != info.group || !obj.contains(info.key)) continue;
      given.push_back(&info);
      const json& v = obj[info.key];
      const std::string key = child(path, info.key);
      void* field = info.field(p);
      switch (info.type) {
        case ParamInfo::Type::Real:
          setRealParam(info, p, r.real(v, key));  // a step in seconds turns its *_fall off
          break;
        case ParamInfo::Type::Integer:
          *static_cast<int*>(field) = r.integer(v, key);
          break;
        case ParamInfo::Type::Vector: {
          const Vec3 g = r.vec3(v, key);
          for (int i = 0; i < 3; ++i) static_cast<float*>(field)[i] = g[i];
          break;
        }
        case ParamInfo::Type::Units:
          readUnits(r, v, key, *static_cast<ControlForceUnits*>(field));
          break;
        case ParamInfo::Type::Solver: {
          const std::string name = r.string(v, key);
          try {
            *static_cast<PressureSolverKind*>(field) = solverByName(name);
          } catch (const Error&) {
            r.fail(key, "must be \"wcsph\" or \"dfsph\" (got '" + name + "')");
          }
          break;
        }
      }
    }
  }
  // A key given that another parameter's mode overrides does nothing: said once.
  for (const ParamInfo* info : given) {
    const std::string why = whyNoEffect(*info, p);
    if (!why.empty())
      warn(r.source + ": " + child(child(base, info->group), info->key) + ": has no effect " + why);
  }
}

ContainerDesc readContainer(const Reader& r, const json& j) {
  r.object(j, "container", {"min", "max"});
  ContainerDesc c;
  c.min = r.vec3(r.required(j, "container", "min"), "container.min");
  c.max = r.vec3(r.required(j, "container", "max"), "container.max");
  // Lengths and their squares stay finite in float (the grid, the wall terms).
  constexpr float kMaxCoordinate = 1.0e6f;
  for (const auto& [v, key] :
       {std::pair<const Vec3&, const char*>{c.min, "container.min"}, {c.max, "container.max"}})
    for (int i = 0; i < 3; ++i)
      if (!(std::fabs(v[i]) <= kMaxCoordinate))
        r.fail(element(key, size_t(i)), "must lie within -1e6 .. 1e6 m (got " + fmt(v[i]) + ")");
  for (int i = 0; i < 3; ++i)
    if (!(c.min[i] < c.max[i]))
      r.fail("container",
             "min must be < max on every axis (got min " + fmtVec(c.min) + ", max " + fmtVec(c.max) + ")");
  return c;
}

FluidBlockDesc readBlock(const Reader& r, const json& j, const std::string& path, const SceneDesc& scene) {
  r.object(j, path, {"origin", "dims", "spacing", "velocity"});
  FluidBlockDesc b;
  b.origin = r.vec3(r.required(j, path, "origin"), child(path, "origin"));
  const json& dims = r.required(j, path, "dims");
  if (!dims.is_array() || dims.size() != 3) r.fail(child(path, "dims"), "must be an array of 3 integers");
  for (int i = 0; i < 3; ++i) {
    b.dims[i] = r.integer(dims[i], element(child(path, "dims"), i));
    if (b.dims[i] < 1)
      r.fail(element(child(path, "dims"), i), "must be >= 1 (got " + std::to_string(b.dims[i]) + ")");
  }
  if (j.contains("spacing")) {
    b.spacing = r.real(j["spacing"], child(path, "spacing"));
    r.positive(b.spacing, child(path, "spacing"));
  }
  r.opt(j, path, "velocity", b.velocity);

  const double s = b.spacing > 0 ? b.spacing : scene.params.fluid.restSpacing();
  const ContainerDesc& c = scene.container;
  const double tol = 1e-5 * (c.max - c.min).maxCoeff();
  Vec3 hi;
  bool inside = true;
  for (int i = 0; i < 3; ++i) {
    double top = double(b.origin[i]) + double(b.dims[i]) * s;
    hi[i] = float(top);
    inside = inside && b.origin[i] >= c.min[i] - tol && top <= c.max[i] + tol;
  }
  if (!inside)
    r.fail(path, "block " + fmtVec(b.origin) + "-" + fmtVec(hi) + " (spacing " + fmt(s) +
                     ") is not inside the container " + fmtVec(c.min) + "-" + fmtVec(c.max));
  return b;
}

RegionDesc readRegion(const Reader& r, const json& j, const std::string& path) {
  RegionDesc g;
  const std::string box = child(path, "box"), sphere = child(path, "sphere");
  if (j.is_string()) {
    if (r.string(j, path) != "all") r.fail(path, "must be \"all\", {\"box\": ...} or {\"sphere\": ...}");
    return g;
  }
  if (!j.is_object()) r.fail(path, "must be \"all\", {\"box\": ...} or {\"sphere\": ...}");
  r.object(j, path, {"box", "sphere"});
  if (j.size() != 1) r.fail(path, "must hold exactly one of: box, sphere");
  if (j.contains("box")) {
    const json& b = r.object(j["box"], box, {"min", "max"});
    g.kind = RegionDesc::Kind::Box;
    g.min = r.vec3(r.required(b, box, "min"), child(box, "min"));
    g.max = r.vec3(r.required(b, box, "max"), child(box, "max"));
    for (int i = 0; i < 3; ++i)
      if (!(g.min[i] < g.max[i]))
        r.fail(box,
               "min must be < max on every axis (got min " + fmtVec(g.min) + ", max " + fmtVec(g.max) + ")");
  } else {
    const json& s = r.object(j["sphere"], sphere, {"center", "radius"});
    g.kind = RegionDesc::Kind::Sphere;
    g.center = r.vec3(r.required(s, sphere, "center"), child(sphere, "center"));
    g.radius = r.real(r.required(s, sphere, "radius"), child(sphere, "radius"));
    r.positive(g.radius, child(sphere, "radius"));
  }
  return g;
}

CameraDesc readCamera(const Reader& r, const json& j, const std::string& path) {
  r.object(j, path, {"yaw", "pitch", "distance", "fov", "target"});
  if (j.empty()) r.fail(path, "must not be empty");
  CameraDesc c;
  if (j.contains("yaw")) c.yaw_deg = r.real(j["yaw"], child(path, "yaw"));
  if (j.contains("pitch")) {
    const float p = r.real(j["pitch"], child(path, "pitch"));
    if (!(p >= -89.0f && p <= 89.0f))
      r.fail(child(path, "pitch"), "must be in [-89, 89] degrees (got " + fmt(p) + ")");
    c.pitch_deg = p;
  }
  if (j.contains("distance")) {
    const float d = r.real(j["distance"], child(path, "distance"));
    r.positive(d, child(path, "distance"));
    c.distance = d;
  }
  if (j.contains("fov")) {
    const float f = r.real(j["fov"], child(path, "fov"));
    if (!(f >= 5.0f && f <= 150.0f))
      r.fail(child(path, "fov"), "must be in [5, 150] degrees (got " + fmt(f) + ")");
    c.fov_deg = f;
  }
  if (j.contains("target")) c.target = r.vec3(j["target"], child(path, "target"));
  return c;
}

bool isMeshName(const std::string& s) {
  std::string ext = std::filesystem::path(s).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  return ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".off";
}

bool analyticKind(const std::string& s, TargetKind& kind) {
  if (s == "sphere")
    kind = TargetKind::Sphere;
  else if (s == "box")
    kind = TargetKind::Box;
  else if (s == "torus")
    kind = TargetKind::Torus;
  else if (s == "capsule")
    kind = TargetKind::Capsule;
  else
    return false;
  return true;
}

void resolveMesh(const Reader& r, TargetSpec& t, const std::string& path, const std::string& base_dir) {
  try {
    t.resolved_path = resolveMeshPath(t.mesh, base_dir);
  } catch (const Error& e) {
    r.fail(path, e.what());
  }
}

TargetSpec readTarget(const Reader& r, const json& j, const std::string& path, const std::string& base_dir) {
  TargetSpec t;
  t.origin = r.source + ": " + path;
  if (j.is_string()) {
    std::string s = j.get<std::string>();
    if (analyticKind(s, t.kind)) return t;
    if (!isMeshName(s))
      r.fail(path,
             "must be sphere, box, torus, capsule or a mesh file (.obj, .ply, .stl, .off) (got '" + s + "')");
    t.kind = TargetKind::Mesh;
    t.mesh = s;
    resolveMesh(r, t, path, base_dir);
    return t;
  }
  if (!j.is_object()) r.fail(path, "must be a string (shape name or mesh file) or an object");
  const std::string shape = r.string(r.required(j, path, "shape"), child(path, "shape"));
  if (shape == "mesh") {
    t.kind = TargetKind::Mesh;
    r.object(j, path, {"shape", "mesh", "rotation", "control_count", "voxel_size", "volume"});
  } else if (!analyticKind(shape, t.kind)) {
    r.fail(child(path, "shape"), "must be one of: sphere, box, torus, capsule, mesh (got '" + shape + "')");
  } else if (t.kind == TargetKind::Box) {
    r.object(j, path, {"shape", "size", "rotation", "control_count", "voxel_size", "volume"});
  } else if (t.kind == TargetKind::Torus) {
    r.object(j, path, {"shape", "major", "minor", "rotation", "control_count", "voxel_size", "volume"});
  } else if (t.kind == TargetKind::Capsule) {
    r.object(j, path, {"shape", "radius", "length", "rotation", "control_count", "voxel_size", "volume"});
  } else {
    r.object(j, path, {"shape", "rotation", "control_count", "voxel_size", "volume"});
  }

  if (t.kind == TargetKind::Mesh) {
    t.mesh = r.string(r.required(j, path, "mesh"), child(path, "mesh"));
    if (t.mesh.empty()) r.fail(child(path, "mesh"), "must not be empty");
  }
  r.opt(j, path, "size", t.box_size);
  for (int i = 0; i < 3; ++i) r.positive(t.box_size[i], element(child(path, "size"), i));
  r.opt(j, path, "major", t.torus_major);
  r.opt(j, path, "minor", t.torus_minor);
  r.positive(t.torus_major, child(path, "major"));
  r.positive(t.torus_minor, child(path, "minor"));
  if (!(t.torus_minor < t.torus_major))
    r.fail(child(path, "minor"),
           "must be < major (got minor " + fmt(t.torus_minor) + ", major " + fmt(t.torus_major) + ")");
  r.opt(j, path, "radius", t.capsule_radius);
  r.opt(j, path, "length", t.capsule_length);
  r.positive(t.capsule_radius, child(path, "radius"));
  if (!(t.capsule_length >= 0))
    r.fail(child(path, "length"), "must be >= 0 (got " + fmt(t.capsule_length) + ")");
  r.opt(j, path, "rotation", t.rotation_deg);
  if (j.contains("control_count") && j.contains("voxel_size"))
    r.fail(path, "give control_count or voxel_size, not both");
  if (j.contains("control_count")) {
    t.control_count = r.integer(j["control_count"], child(path, "control_count"));
    r.positive(t.control_count, child(path, "control_count"));
  }
  if (j.contains("voxel_size")) {
    t.voxel_size = r.real(j["voxel_size"], child(path, "voxel_size"));
    r.positive(t.voxel_size, child(path, "voxel_size"));
  }
  if (j.contains("volume")) {
    t.volume = r.real(j["volume"], child(path, "volume"));
    r.positive(t.volume, child(path, "volume"));
  }
  if (t.kind == TargetKind::Mesh) resolveMesh(r, t, child(path, "mesh"), base_dir);
  return t;
}

std::vector<ScheduleEntry> readSchedule(const Reader& r, const json& j, const std::string& base_dir) {
  std::vector<ScheduleEntry> out;
  r.array(j, "schedule");
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string path = element("schedule", i);
    r.object(j[i], path, {"time", "target"});
    ScheduleEntry e;
    const std::string tpath = child(path, "time");
    e.time = r.number(r.required(j[i], path, "time"), tpath);
    if (i == 0 && e.time != 0.0) r.fail(tpath, "the first entry must be at time 0 (got " + fmt(e.time) + ")");
    if (i > 0 && !(e.time > out.back().time))
      r.fail(tpath, "times must be strictly increasing (got " + fmt(e.time) + " after " +
                        fmt(out.back().time) + ")");
    e.target = readTarget(r, r.required(j[i], path, "target"), child(path, "target"), base_dir);
    out.push_back(e);
  }
  return out;
}

std::string lineColumn(const std::string& text, size_t byte) {
  // nlohmann reports how many bytes it had read; the last one is at fault.
  size_t pos = std::min(byte > 0 ? byte - 1 : 0, text.size());
  size_t line = 1, line_start = 0;
  for (size_t k = 0; k < pos; ++k)
    if (text[k] == '\n') {
      ++line;
      line_start = k + 1;
    }
  return std::to_string(line) + ":" + std::to_string(pos - line_start + 1);
}

// Builds the JSON tree like json::parse, but knows the key path of every value,
// so that a number overflow ("1e999") and a duplicate key name their key.
class TreeBuilder final : public nlohmann::json_sax<json> {
 public:
  TreeBuilder(const std::string& source, const std::string& text) : source_(source), text_(text) {}
  json root;

  bool null() override { return put(nullptr); }
  bool boolean(bool v) override { return put(v); }
  bool number_integer(number_integer_t v) override { return put(v); }
  bool number_unsigned(number_unsigned_t v) override { return put(v); }
  bool number_float(number_float_t v, const string_t&) override { return put(v); }
  bool string(string_t& v) override { return put(v); }
  bool binary(binary_t& v) override { return put(json::binary(v)); }
  bool start_object(std::size_t) override { return open(json::object()); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    key_ = k;
    if (frames_.back().node->contains(k)) throw Error(source_ + ": " + nextPath() + ": duplicate key");
    return true;
  }
  bool parse_error(std::size_t position, const std::string& token, const json::exception& e) override {
    std::string where = source_ + ":" + lineColumn(text_, position) + ": ";
    if (e.id == 406) throw Error(where + nextPath() + ": number out of range (" + token + ")");
    std::string detail = e.what();
    size_t at = detail.find("syntax error");
    if (at != std::string::npos) detail = detail.substr(at);
    throw Error(where + "invalid JSON: " + detail);
  }

 private:
  struct Frame {
    json* node;
    std::string path;
  };
  const std::string& source_;
  const std::string& text_;
  std::vector<Frame> frames_;
  std::string key_;

  std::string nextPath() const {
    if (frames_.empty()) return "(top level)";
    const Frame& f = frames_.back();
    return f.node->is_object() ? child(f.path, key_) : element(f.path, f.node->size());
  }
  // Pointers into the tree stay valid: only the innermost open container grows.
  json* place(json&& v) {
    if (frames_.empty()) {
      root = std::move(v);
      return &root;
    }
    json& c = *frames_.back().node;
    if (c.is_object()) return &(c[key_] = std::move(v));
    c.push_back(std::move(v));
    return &c.back();
  }
  bool put(json&& v) {
    place(std::move(v));
    return true;
  }
  bool open(json&& v) {
    std::string path = frames_.empty() ? std::string() : nextPath();
    frames_.push_back({place(std::move(v)), path});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }
};

SceneDesc parseSceneImpl(const std::string& text, const std::string& source, const std::string& base_dir,
                         const std::string& default_name) {
  TreeBuilder builder(source, text);
  if (!json::sax_parse(text, &builder)) throw Error(source + ": invalid JSON");
  const json& root = builder.root;
  const Reader r{source};
  if (!root.is_object()) r.fail("", "the scene must be a JSON object");
  r.object(root, "",
           {"name", "preset", "duration", "params", "container", "fluid", "region", "target", "schedule",
            "camera"});

  SceneDesc scene;
  scene.source = source;
  scene.name = default_name;
  if (root.contains("name")) {
    scene.name = r.string(root["name"], "name");
    if (scene.name.empty()) r.fail("name", "must not be empty");
  }
  // A scene that names no preset gets the engine's recommended one.
  scene.preset = root.contains("preset") ? r.string(root["preset"], "preset") : "default";
  try {
    scene.params = presetParams(scene.preset);
  } catch (const Error& e) {
    r.fail("preset", e.what());
  }
  if (root.contains("params")) readParams(r, root["params"], "params", scene.params);
  validateParams(scene.params, source);
  scene.params.fluid.setFrameStep();
  if (root.contains("duration")) {
    scene.duration = r.number(root["duration"], "duration");
    r.positive(scene.duration, "duration");
    checkRunLength(scene.duration, scene.params.fluid.time_step, source + ": duration");
  }
  if (root.contains("container")) scene.container = readContainer(r, root["container"]);

  if (!root.contains("fluid"))
    r.fail("fluid", "required key is missing (a scene needs at least one fluid block)");
  const json& fluid = r.array(root["fluid"], "fluid");
  if (fluid.empty()) r.fail("fluid", "must hold at least one fluid block");
  double particles = 0.0;
  for (size_t i = 0; i < fluid.size(); ++i) {
    scene.fluid.push_back(readBlock(r, fluid[i], element("fluid", i), scene));
    const FluidBlockDesc& b = scene.fluid.back();
    particles += double(b.dims[0]) * double(b.dims[1]) * double(b.dims[2]);
    checkFluidCount(particles, source, child(element("fluid", i), "dims"));
    // Particles much closer than the rest spacing start at many times the
    // rest density: the first steps blow them apart (junk, not a liquid).
    const double rest = scene.params.fluid.restSpacing();
    if (b.spacing > 0 && !(b.spacing >= 0.5 * rest && b.spacing <= 10.0 * rest))
      r.fail(child(element("fluid", i), "spacing"),
             "must be in [0.5, 10] times the rest spacing " + fmt(rest) + " m (got " + fmt(b.spacing) + ")");
  }

  if (root.contains("region")) scene.region = readRegion(r, root["region"], "region");
  if (root.contains("target") && root.contains("schedule"))
    r.fail("target", "give either 'target' or 'schedule', not both");
  if (root.contains("target"))
    scene.schedule.push_back({0.0, readTarget(r, root["target"], "target", base_dir)});
  if (root.contains("schedule")) scene.schedule = readSchedule(r, root["schedule"], base_dir);
  if (root.contains("camera")) scene.camera = readCamera(r, root["camera"], "camera");
  return scene;
}

}  // namespace

nlohmann::json parseJsonStrict(const std::string& text, const std::string& source) {
  TreeBuilder builder(source, text);
  if (!json::sax_parse(text, &builder)) throw Error(source + ": invalid JSON");
  return std::move(builder.root);
}

TargetSpec parseTargetSpec(const nlohmann::json& j, const std::string& source, const std::string& path,
                           const std::string& base_dir) {
  return readTarget(Reader{source}, j, path, base_dir);
}

RegionDesc parseRegionDesc(const nlohmann::json& j, const std::string& source, const std::string& path) {
  return readRegion(Reader{source}, j, path);
}

CameraDesc parseCameraDesc(const nlohmann::json& j, const std::string& source, const std::string& path) {
  return readCamera(Reader{source}, j, path);
}

void parseParamsOverlay(const nlohmann::json& j, const std::string& source, const std::string& path,
                        Params& params) {
  readParams(Reader{source}, j, path, params);
}

SceneDesc parseScene(const std::string& json_text, const std::string& source, const std::string& base_dir) {
  return parseSceneImpl(json_text, source, base_dir, "scene");
}

SceneDesc loadScene(const std::string& path) {
  const std::string text = readTextFile(path, "scene");

  const std::filesystem::path p(path);
  std::string dir = p.parent_path().string();
  if (dir.empty()) dir = ".";
  return parseSceneImpl(text, path, dir, p.stem().string());
}

SceneDesc defaultScene() {
  return parseScene(embeddedFile("scenes/default.json"), "<built-in default scene>", "");
}

}  // namespace ff
