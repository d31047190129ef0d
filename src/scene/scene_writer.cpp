// scene_writer.cpp - a SceneDesc as scene JSON (the reader's syntax).
#include "scene/scene_writer.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/param_table.h"

namespace ff {

namespace {

using json = nlohmann::ordered_json;
namespace fs = std::filesystem;

// The double with the fewest significant digits that reads back (as the
// reader does: double, then float) to exactly `v`.
double tidy(float v) {
  for (int digits = 6; digits < 9; ++digits) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, double(v));
    const double d = std::strtod(buf, nullptr);
    if (float(d) == v) return d;
  }
  return double(v);  // 9 significant digits always round-trip a float
}

json vec(const Vec3& v) {
  return json::array({tidy(v.x()), tidy(v.y()), tidy(v.z())});
}

const char* unitsName(ControlForceUnits u) {
  switch (u) {
    case ControlForceUnits::Acceleration:
      return "acceleration";
    case ControlForceUnits::ForceDensity:
      return "force_density";
    case ControlForceUnits::Force:
      return "force";
  }
  return "acceleration";
}

// The keys of `p` whose values differ from the preset's, by group.
json paramsOverlay(const Params& p, const Params& preset) {
  json out = json::object();
  Params a = p, b = preset;  // ParamInfo::field takes a mutable Params
  for (const ParamInfo& info : paramTable()) {
    const void* fa = info.field(a);
    const void* fb = info.field(b);
    json value;
    switch (info.type) {
      case ParamInfo::Type::Real: {
        const float v = *static_cast<const float*>(fa);
        if (v != *static_cast<const float*>(fb)) value = tidy(v);
        break;
      }
      case ParamInfo::Type::Integer: {
        const int v = *static_cast<const int*>(fa);
        if (v != *static_cast<const int*>(fb)) value = v;
        break;
      }
      case ParamInfo::Type::Vector: {
        const float* v = static_cast<const float*>(fa);
        const float* w = static_cast<const float*>(fb);
        if (v[0] != w[0] || v[1] != w[1] || v[2] != w[2]) value = vec(Vec3(v[0], v[1], v[2]));
        break;
      }
      case ParamInfo::Type::Units: {
        const auto v = *static_cast<const ControlForceUnits*>(fa);
        if (v != *static_cast<const ControlForceUnits*>(fb)) value = unitsName(v);
        break;
      }
      case ParamInfo::Type::Solver: {
        const auto v = *static_cast<const PressureSolverKind*>(fa);
        if (v != *static_cast<const PressureSolverKind*>(fb)) value = solverName(v);
        break;
      }
    }
    // A value another parameter sets (overrideRules' `sets`) is not written:
    // it follows the scene (a step given in seconds would turn its *_fall
    // off; a radius in metres has no effect while radius_spacings is on).
    // A value a mode leaves unused (attraction while normalise is 1) is the
    // user's and is written.
    if (setByAnother(info, a)) continue;
    if (!value.is_null()) out[info.group][info.key] = value;
  }
  return out;
}

json blockJson(const FluidBlockDesc& b) {
  json j = {{"origin", vec(b.origin)}, {"dims", {b.dims[0], b.dims[1], b.dims[2]}}};
  if (b.spacing > 0.0f) j["spacing"] = tidy(b.spacing);
  if (b.velocity != Vec3::Zero()) j["velocity"] = vec(b.velocity);
  return j;
}

json regionJson(const RegionDesc& r) {
  switch (r.kind) {
    case RegionDesc::Kind::All:
      break;
    case RegionDesc::Kind::Box:
      return {{"box", {{"min", vec(r.min)}, {"max", vec(r.max)}}}};
    case RegionDesc::Kind::Sphere:
      return {{"sphere", {{"center", vec(r.center)}, {"radius", tidy(r.radius)}}}};
  }
  return "all";
}

// The mesh as the user wrote it if that still finds the same file from
// base_dir, else the absolute path of the file read.
std::string meshPath(const TargetSpec& t, const std::string& base_dir) {
  if (t.resolved_path.empty()) return t.mesh;
  try {
    std::error_code ec;
    if (fs::equivalent(resolveMeshPath(t.mesh, base_dir), t.resolved_path, ec) && !ec) return t.mesh;
  } catch (const Error&) {
    // not found from the new folder: the absolute path below
  }
  std::error_code ec;
  const fs::path abs = fs::absolute(t.resolved_path, ec);
  return ec ? t.resolved_path : abs.lexically_normal().string();
}

json targetJson(const TargetSpec& t, const std::string& base_dir) {
  json j;
  switch (t.kind) {
    case TargetKind::Sphere:
      j["shape"] = "sphere";
      break;
    case TargetKind::Box:
      j["shape"] = "box";
      j["size"] = vec(t.box_size);
      break;
    case TargetKind::Torus:
      j["shape"] = "torus";
      j["major"] = tidy(t.torus_major);
      j["minor"] = tidy(t.torus_minor);
      break;
    case TargetKind::Capsule:
      j["shape"] = "capsule";
      j["radius"] = tidy(t.capsule_radius);
      j["length"] = tidy(t.capsule_length);
      break;
    case TargetKind::Mesh:
      j["shape"] = "mesh";
      j["mesh"] = meshPath(t, base_dir);
      break;
  }
  if (t.rotation_deg != Vec3::Zero()) j["rotation"] = vec(t.rotation_deg);
  if (t.control_count > 0) j["control_count"] = t.control_count;
  if (t.voxel_size > 0.0f) j["voxel_size"] = tidy(t.voxel_size);
  if (t.volume > 0.0f) j["volume"] = tidy(t.volume);
  return j;
}

json cameraJson(const CameraDesc& c) {
  json j = json::object();
  if (c.yaw_deg) j["yaw"] = tidy(*c.yaw_deg);
  if (c.pitch_deg) j["pitch"] = tidy(*c.pitch_deg);
  if (c.distance) j["distance"] = tidy(*c.distance);
  if (c.fov_deg) j["fov"] = tidy(*c.fov_deg);
  if (c.target) j["target"] = vec(*c.target);
  return j;
}

// Two-space indented JSON with each array of numbers on one line
// ("origin": [0.1, 0, 0.2]), keys in the order written.
void format(const json& j, int indent, std::string& out) {
  const std::string pad(size_t(indent) * 2, ' '), inner(size_t(indent + 1) * 2, ' ');
  if (j.is_object()) {
    if (j.empty()) {
      out += "{}";
      return;
    }
    out += "{\n";
    size_t i = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++i) {
      out += inner + json(it.key()).dump() + ": ";
      format(it.value(), indent + 1, out);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += pad + "}";
  } else if (j.is_array()) {
    bool flat = true;
    for (const json& e : j) flat = flat && e.is_primitive();
    out += "[";
    for (size_t i = 0; i < j.size(); ++i) {
      if (flat) {
        out += (i ? ", " : "") + j[i].dump();
      } else {
        out += (i ? ",\n" : "\n") + inner;
        format(j[i], indent + 1, out);
      }
    }
    if (!flat && !j.empty()) out += "\n" + pad;
    out += "]";
  } else {
    out += j.dump();
  }
}

[[noreturn]] void fail(const std::string& path, const std::string& what, int err) {
  throw Error(path + ": " + what + " (" + std::strerror(err) + ")");
}

}  // namespace

nlohmann::ordered_json sceneToJson(const SceneDesc& scene, const std::string& base_dir) {
  json j = json::object();
  j["name"] = scene.name;
  j["preset"] = scene.preset;
  json overlay = paramsOverlay(scene.params, presetParams(scene.preset));
  if (!overlay.empty()) j["params"] = overlay;
  j["duration"] = scene.duration;
  j["container"] = {{"min", vec(scene.container.min)}, {"max", vec(scene.container.max)}};
  j["fluid"] = json::array();
  for (const FluidBlockDesc& b : scene.fluid) j["fluid"].push_back(blockJson(b));
  j["region"] = regionJson(scene.region);
  if (scene.schedule.size() == 1 && scene.schedule[0].time == 0.0) {
    j["target"] = targetJson(scene.schedule[0].target, base_dir);
  } else if (!scene.schedule.empty()) {
    j["schedule"] = json::array();
    for (const ScheduleEntry& e : scene.schedule)
      j["schedule"].push_back({{"time", e.time}, {"target", targetJson(e.target, base_dir)}});
  }
  if (scene.camera) {
    json c = cameraJson(*scene.camera);
    if (!c.empty()) j["camera"] = c;
  }
  return j;
}

void writeSceneFile(const SceneDesc& scene, const std::string& path) {
  std::string dir = fs::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  std::string text;
  format(sceneToJson(scene, dir), 0, text);
  text += "\n";
  std::error_code ec;
  if (fs::exists(path, ec)) throw Error(path + ": a file of that name exists; not overwritten");
  // Written to a private temporary file, then linked into place: link() fails
  // when the name was taken meanwhile, so nothing is ever replaced.
  std::string tmp = path + ".XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) fail(path, "cannot create the scene file", errno);
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      fail(path, "cannot write the scene file", err);
    }
    done += size_t(n);
  }
  const mode_t mask = ::umask(0);  // mkstemp makes the file 0600; give it the usual 0666 & ~umask
  ::umask(mask);
  if (::fchmod(fd, 0666 & ~mask) != 0 || ::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail(path, "cannot write the scene file", err);
  }
  if (::link(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    if (err == EEXIST) throw Error(path + ": a file of that name exists; not overwritten");
    fail(path, "cannot create the scene file", err);
  }
  ::unlink(tmp.c_str());
}

std::string freeFileName(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return path;
  const fs::path p(path);
  const std::string stem = p.stem().string(), ext = p.extension().string();
  for (int i = 2; i < 100000; ++i) {
    const fs::path candidate = p.parent_path() / (stem + "_" + std::to_string(i) + ext);
    if (!fs::exists(candidate, ec)) return candidate.string();
  }
  throw Error(path + ": no free file name of the form " + stem + "_N" + ext);
}

}  // namespace ff
