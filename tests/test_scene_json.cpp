// test_scene_json.cpp - scene files, parameter presets and their validation.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/param_table.h"
#include "core/params.h"
#include "core/warning.h"
#include "scene/scene.h"
#include "temp_dir.h"
#include "test_meshes.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char* kSource = "scenes/x.json";

// A small valid scene; tests change one thing in it.
json baseScene() {
  return json::parse(R"({
    "name": "t", "preset": "paper", "duration": 1.0,
    "container": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
    "fluid": [{"origin": [0.1, 0.0, 0.1], "dims": [4, 5, 6]}],
    "region": "all",
    "schedule": [{"time": 0, "target": "sphere"}, {"time": 1.5, "target": "torus"}]
  })");
}

// The ff::Error message that parsing `text` gives, or "" when it parses.
std::string errorOf(const std::string& text) {
  try {
    ff::parseScene(text, kSource, "");
  } catch (const ff::Error& e) {
    return e.what();
  }
  return "";
}

// Expects parsing to fail with a message holding the file name and every one
// of `parts` (the key path, the problem).
void expectError(const std::string& text, std::initializer_list<const char*> parts) {
  std::string msg = errorOf(text);
  ASSERT_FALSE(msg.empty()) << "parsed without error: " << text;
  EXPECT_NE(msg.find(kSource), std::string::npos) << msg;
  for (const char* p : parts)
    EXPECT_NE(msg.find(p), std::string::npos) << "missing '" << p << "' in: " << msg;
}

std::string sceneFile(const std::string& name) {
  return std::string(FF_SOURCE_DIR) + "/scenes/" + name;
}

// Each test sees FLOWFORM_MESH_PATH = the folders the tests search for meshes
// (test_meshes.h), restored afterwards; those that need a mesh skip without it.
class SceneJson : public ::testing::Test {
 protected:
  fftest::ScopedEnv mesh_path_{"FLOWFORM_MESH_PATH", fftest::meshSearchPath().c_str()};
};

}  // namespace

using ff::parseScene;

TEST_F(SceneJson, BaseSceneParses) {
  ff::SceneDesc s = parseScene(baseScene().dump(), kSource, "");
  EXPECT_EQ(s.name, "t");
  EXPECT_EQ(s.source, kSource);
  ASSERT_EQ(s.fluid.size(), 1u);
  EXPECT_EQ(s.fluidCount(), 4 * 5 * 6);
  EXPECT_FLOAT_EQ(s.fluid[0].spacing, 0.0f);
  EXPECT_EQ(s.region.kind, ff::RegionDesc::Kind::All);
  ASSERT_EQ(s.schedule.size(), 2u);
  EXPECT_EQ(s.schedule[0].target.kind, ff::TargetKind::Sphere);
  EXPECT_EQ(s.schedule[1].target.kind, ff::TargetKind::Torus);
  EXPECT_DOUBLE_EQ(s.schedule[1].time, 1.5);
  EXPECT_DOUBLE_EQ(s.duration, 1.0);
}

TEST_F(SceneJson, EverySceneFileParses) {
  FF_SCENE_MESHES_OR_SKIP();
  int n = 0;
  const fs::path scenes = std::string(FF_SOURCE_DIR) + "/scenes";
  for (const auto& entry : fs::recursive_directory_iterator(scenes)) {
    // scenes/scripts holds viewer scripts, not scenes.
    if (entry.path().extension() != ".json" || entry.path().parent_path() == scenes / "scripts") continue;
    SCOPED_TRACE(entry.path().string());
    // Each scene names its preset (issue 9): the default may change.
    std::ifstream in(entry.path());
    const json text = json::parse(in);
    ASSERT_TRUE(text.contains("preset"));
    ff::SceneDesc s;
    ASSERT_NO_THROW(s = ff::loadScene(entry.path().string()));
    EXPECT_EQ(s.preset, text["preset"].get<std::string>());
    EXPECT_GT(s.fluidCount(), 0);
    EXPECT_FALSE(s.schedule.empty());
    for (const ff::ScheduleEntry& e : s.schedule)
      if (e.target.kind == ff::TargetKind::Mesh) {
        EXPECT_TRUE(fs::exists(e.target.resolved_path)) << e.target.resolved_path;
      }
    ++n;
  }
  EXPECT_GE(n, 11);  // scenes/*.json and the water variants of Table 1 and Fig. 12
}

TEST_F(SceneJson, DefaultSceneIsBuiltInShapesOnly) {
  ff::SceneDesc s = ff::defaultScene();
  EXPECT_EQ(s.source, "<built-in default scene>");
  EXPECT_EQ(s.fluidCount(), 8000);
  ASSERT_EQ(s.schedule.size(), 3u);
  EXPECT_EQ(s.schedule[0].target.kind, ff::TargetKind::Sphere);
  EXPECT_EQ(s.schedule[1].target.kind, ff::TargetKind::Torus);
  EXPECT_EQ(s.schedule[2].target.kind, ff::TargetKind::Capsule);
  EXPECT_DOUBLE_EQ(s.schedule[0].time, 0.0);
  EXPECT_DOUBLE_EQ(s.schedule[1].time, 2.0);
  EXPECT_DOUBLE_EQ(s.schedule[2].time, 4.0);
  EXPECT_DOUBLE_EQ(s.duration, 6.0);
  for (const ff::ScheduleEntry& e : s.schedule) EXPECT_NE(e.target.kind, ff::TargetKind::Mesh);
}

TEST_F(SceneJson, DefaultSceneWorksWithoutMeshPath) {
  unsetenv("FLOWFORM_MESH_PATH");
  EXPECT_NO_THROW(ff::defaultScene());
}

TEST_F(SceneJson, TableOneScenes) {
  FF_SCENE_MESHES_OR_SKIP();
  const struct {
    const char* file;
    const char* mesh;
    int control_count;
  } kScenes[] = {{"bunny.json", "bunny.obj", 3197},
                 {"teapot.json", "teapot.obj", 2154},
                 {"runner.json", "runner.obj", 549},
                 {"dragon.json", "dragon.obj", 2714}};
  // The paper's appendix in scenes/, the same scenes on the water preset in
  // scenes/water/.
  for (const auto& k : kScenes)
    for (const std::string preset : {"paper", "water"}) {
      const std::string file = (preset == "paper" ? "" : preset + "/") + k.file;
      SCOPED_TRACE(file);
      ff::SceneDesc s = ff::loadScene(sceneFile(file));
      EXPECT_EQ(s.fluidCount(), 12000);
      EXPECT_EQ(s.preset, preset);
      EXPECT_DOUBLE_EQ(s.duration, 4.0);
      ASSERT_EQ(s.schedule.size(), 1u);
      const ff::TargetSpec& t = s.schedule[0].target;
      EXPECT_EQ(t.kind, ff::TargetKind::Mesh);
      EXPECT_EQ(t.mesh, k.mesh);
      // Water derives the count from the target and the fluid (control_count
      // is an optional override, docs/CONTROL_UNITS.md "How many control
      // particles"); the paper's scenes give Table 1's.
      EXPECT_EQ(t.control_count, preset == "paper" ? k.control_count : 0);
      EXPECT_EQ(fs::path(t.resolved_path).filename().string(), k.mesh);
      EXPECT_TRUE(fs::exists(t.resolved_path)) << t.resolved_path;
    }
}

TEST_F(SceneJson, BunnyBoxTeapotSchedule) {
  FF_SCENE_MESHES_OR_SKIP();
  ff::SceneDesc s = ff::loadScene(sceneFile("bunny_box_teapot.json"));
  EXPECT_EQ(s.fluidCount(), 12000);
  EXPECT_DOUBLE_EQ(s.duration, 9.0);
  ASSERT_EQ(s.schedule.size(), 3u);
  EXPECT_EQ(s.schedule[0].target.mesh, "bunny.obj");
  EXPECT_EQ(s.schedule[1].target.kind, ff::TargetKind::Box);
  EXPECT_EQ(s.schedule[2].target.mesh, "teapot.obj");
  EXPECT_DOUBLE_EQ(s.schedule[1].time, 3.0);
  EXPECT_DOUBLE_EQ(s.schedule[2].time, 6.0);
}

TEST_F(SceneJson, OverridesApplyOnTopOfPreset) {
  json j = baseScene();
  j["params"]["fluid"]["gas_constant"] = 0.7;
  j["params"]["fluid"]["gravity"] = {0.0, -1.0, 0.0};
  j["params"]["control"]["units"] = "force_density";
  j["params"]["shape_matching"]["cluster_stride"] = 3;
  ff::SceneDesc s = parseScene(j.dump(), kSource, "");
  ff::Params paper = ff::presetParams("paper");
  EXPECT_FLOAT_EQ(s.params.fluid.gas_constant, 0.7f);
  EXPECT_FLOAT_EQ(s.params.fluid.gravity[1], -1.0f);
  EXPECT_EQ(s.params.control.units, ff::ControlForceUnits::ForceDensity);
  EXPECT_EQ(s.params.shape.cluster_stride, 3);
  // Everything not overridden keeps the preset's value.
  EXPECT_FLOAT_EQ(s.params.fluid.viscosity, paper.fluid.viscosity);
  EXPECT_FLOAT_EQ(s.params.fluid.particle_mass, paper.fluid.particle_mass);
  EXPECT_FLOAT_EQ(s.params.control.attraction, paper.control.attraction);
  EXPECT_FLOAT_EQ(s.params.shape.stiffness, paper.shape.stiffness);
  EXPECT_EQ(s.params.shape.cluster_half_width, paper.shape.cluster_half_width);
}

TEST_F(SceneJson, TargetForms) {
  json j = baseScene();
  j.erase("schedule");
  j["target"] = {
      {"shape", "torus"}, {"major", 2.0}, {"minor", 0.5}, {"rotation", {90, 0, 0}}, {"voxel_size", 0.01}};
  ff::SceneDesc s = parseScene(j.dump(), kSource, "");
  ASSERT_EQ(s.schedule.size(), 1u);
  EXPECT_DOUBLE_EQ(s.schedule[0].time, 0.0);
  const ff::TargetSpec& t = s.schedule[0].target;
  EXPECT_EQ(t.kind, ff::TargetKind::Torus);
  EXPECT_FLOAT_EQ(t.torus_major, 2.0f);
  EXPECT_FLOAT_EQ(t.torus_minor, 0.5f);
  EXPECT_FLOAT_EQ(t.rotation_deg.x(), 90.0f);
  EXPECT_FLOAT_EQ(t.voxel_size, 0.01f);

  FF_MESH_OR_SKIP(bunny, "bunny.obj");
  j["target"] = "bunny.obj";
  s = parseScene(j.dump(), kSource, "");
  EXPECT_EQ(s.schedule[0].target.kind, ff::TargetKind::Mesh);
  EXPECT_EQ(s.schedule[0].target.mesh, "bunny.obj");
  EXPECT_TRUE(fs::exists(s.schedule[0].target.resolved_path));

  j.erase("target");
  s = parseScene(j.dump(), kSource, "");
  EXPECT_TRUE(s.schedule.empty());
}

TEST_F(SceneJson, RegionForms) {
  json j = baseScene();
  j["region"] = {{"box", {{"min", {0, 0, 0}}, {"max", {0.1, 0.2, 0.3}}}}};
  ff::SceneDesc s = parseScene(j.dump(), kSource, "");
  EXPECT_EQ(s.region.kind, ff::RegionDesc::Kind::Box);
  EXPECT_FLOAT_EQ(s.region.max.z(), 0.3f);
  j["region"] = {{"sphere", {{"center", {0.1, 0.1, 0.1}}, {"radius", 0.05}}}};
  s = parseScene(j.dump(), kSource, "");
  EXPECT_EQ(s.region.kind, ff::RegionDesc::Kind::Sphere);
  EXPECT_FLOAT_EQ(s.region.radius, 0.05f);
}

TEST_F(SceneJson, UnknownTopLevelKey) {
  json j = baseScene();
  j["_comment"] = "comments are not allowed";
  expectError(j.dump(), {"_comment", "unknown key", "expected one of"});
}

TEST_F(SceneJson, UnknownNestedKeys) {
  json j = baseScene();
  j["fluid"][0]["dimz"] = {1, 2, 3};
  expectError(j.dump(), {"fluid[0].dimz", "unknown key", "origin, dims, spacing, velocity"});
  j = baseScene();
  j["params"]["fluid"]["gas_constnt"] = 0.5;
  expectError(j.dump(), {"params.fluid.gas_constnt", "unknown key"});
  j = baseScene();
  j["schedule"][1]["target"] = {{"shape", "sphere"}, {"major", 1.0}};
  expectError(j.dump(), {"schedule[1].target.major", "unknown key"});
}

TEST_F(SceneJson, WrongType) {
  json j = baseScene();
  j["container"]["max"] = "big";
  expectError(j.dump(), {"container.max", "must be an array of 3 numbers"});
  j = baseScene();
  j["fluid"][0]["dims"] = {4, 5.5, 6};
  expectError(j.dump(), {"fluid[0].dims[1]", "integer"});
  j = baseScene();
  j["duration"] = true;
  expectError(j.dump(), {"duration", "must be a number"});
  j = baseScene();
  j["fluid"] = {{"origin", {0, 0, 0}}};
  expectError(j.dump(), {"fluid", "must be an array"});
}

TEST_F(SceneJson, NanAndInfinityRejected) {
  json j = baseScene();
  j["params"]["fluid"]["gas_constant"] = "nan";
  expectError(j.dump(), {"params.fluid.gas_constant", "must be a number"});

  // nlohmann refuses 1e999 (number overflow); the message still names the key.
  std::string text = baseScene().dump();
  text.insert(1, "\"params\": {\"fluid\": {\"viscosity\": 0.01,\n \"gas_constant\": 1e999}}, ");
  expectError(text, {"scenes/x.json:2:", "params.fluid.gas_constant", "out of range", "1e999"});

  j = baseScene();
  j.erase("duration");
  text = j.dump();
  text.insert(1, R"("duration": -1e999, )");
  expectError(text, {"duration", "out of range"});

  // A finite double that overflows a float.
  j = baseScene();
  j["fluid"][0]["velocity"] = {0.0, 1e300, 0.0};
  expectError(j.dump(), {"fluid[0].velocity[1]", "1e+300"});
}

TEST_F(SceneJson, DuplicateKey) {
  std::string text = baseScene().dump();
  text.insert(1, R"("duration": 2.0, )");
  expectError(text, {"duration", "duplicate key"});
}

TEST_F(SceneJson, NegativeGasConstant) {
  json j = baseScene();
  j["params"]["fluid"]["gas_constant"] = -0.5;
  expectError(j.dump(), {"params.fluid.gas_constant", "must be in [0, 1e+06]", "(got -0.5)"});
}

TEST_F(SceneJson, BadParamRanges) {
  json j = baseScene();
  j["params"]["fluid"]["time_step"] = 0.5;
  expectError(j.dump(), {"params.fluid.time_step"});
  j = baseScene();
  j["params"]["control"]["feedback"] = 1.5;
  expectError(j.dump(), {"params.control.feedback"});
  j = baseScene();
  j["params"]["shape_matching"]["rotation_iterations"] = 0;
  expectError(j.dump(), {"params.shape_matching.rotation_iterations", "must be in [1, 100] (got 0)"});
  j = baseScene();
  j["params"]["control"]["units"] = "newtons";
  expectError(j.dump(), {"params.control.units", "force_density"});
  j = baseScene();
  j["preset"] = "fast";
  expectError(j.dump(), {"preset", "fast", "paper"});
}

TEST_F(SceneJson, FluidBlockOutsideContainer) {
  json j = baseScene();
  j["fluid"][0]["origin"] = {0.28, 0.0, 0.1};  // 4 particles at ~0.0063 reach x = 0.305
  expectError(j.dump(), {"fluid[0]", "not inside the container"});
  j = baseScene();
  j["fluid"][0]["origin"] = {0.1, -0.01, 0.1};
  expectError(j.dump(), {"fluid[0]", "not inside the container"});
  j = baseScene();
  j["fluid"][0]["dims"] = {4, 0, 6};
  expectError(j.dump(), {"fluid[0].dims[1]", ">= 1"});
  j = baseScene();
  j["fluid"] = json::array();
  expectError(j.dump(), {"fluid", "at least one"});
}

TEST_F(SceneJson, ContainerMinBelowMax) {
  json j = baseScene();
  j["container"]["min"] = {0, 0.3, 0};
  expectError(j.dump(), {"container", "min must be < max"});
}

TEST_F(SceneJson, ScheduleMustIncrease) {
  json j = baseScene();
  j["schedule"][1]["time"] = 0.0;
  expectError(j.dump(), {"schedule[1].time", "strictly increasing"});
  j = baseScene();
  j["schedule"][0]["time"] = 0.5;
  expectError(j.dump(), {"schedule[0].time", "time 0"});
  j = baseScene();
  j["target"] = "box";
  expectError(j.dump(), {"target", "not both"});
}

TEST_F(SceneJson, TargetValueErrors) {
  json j = baseScene();
  j["schedule"][1]["target"] = "cube";
  expectError(j.dump(), {"schedule[1].target", "cube"});
  j["schedule"][1]["target"] = {{"shape", "box"}, {"control_count", 100}, {"voxel_size", 0.01}};
  expectError(j.dump(), {"schedule[1].target", "not both"});
  j["schedule"][1]["target"] = {{"shape", "box"}, {"control_count", 0}};
  expectError(j.dump(), {"schedule[1].target.control_count", "> 0"});
  j["schedule"][1]["target"] = {{"shape", "box"}, {"size", {1, -1, 1}}};
  expectError(j.dump(), {"schedule[1].target.size[1]", "> 0"});
  j["region"] = {{"sphere", {{"center", {0, 0, 0}}, {"radius", 0}}}};
  j["schedule"][1]["target"] = "box";
  expectError(j.dump(), {"region.sphere.radius", "> 0"});
}

TEST_F(SceneJson, MissingMesh) {
  json j = baseScene();
  j["schedule"][1]["target"] = "no_such_mesh_7f3a.obj";
  expectError(j.dump(), {"schedule[1].target", "no_such_mesh_7f3a.obj"});
}

TEST_F(SceneJson, MalformedJsonNamesLine) {
  std::string text = "{\n  \"name\": \"t\",\n  \"duration\": 4.0,,\n}\n";
  std::string msg = errorOf(text);
  EXPECT_NE(msg.find("scenes/x.json:3:"), std::string::npos) << msg;
}

TEST_F(SceneJson, LoadSceneNamesTheFile) {
  const fftest::TempDir dir("scene_json");
  std::string path = (dir / "broken.json").string();
  json j = baseScene();
  j["fluid"][0]["dimz"] = 3;
  std::ofstream(path) << j.dump(2);
  try {
    ff::loadScene(path);
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(path + ": fluid[0].dimz: unknown key"), std::string::npos) << msg;
  }

  // Mesh paths resolve relative to the scene file's folder first.
  unsetenv("FLOWFORM_MESH_PATH");
  std::ofstream(dir / "tiny.obj")
      << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  j = baseScene();
  j.erase("name");
  j["schedule"][1]["target"] = "tiny.obj";
  std::string good = (dir / "tiny_scene.json").string();
  std::ofstream(good) << j.dump(2);
  ff::SceneDesc s = ff::loadScene(good);
  EXPECT_EQ(s.schedule[1].target.mesh, "tiny.obj");
  EXPECT_TRUE(fs::equivalent(s.schedule[1].target.resolved_path, dir / "tiny.obj"));
  EXPECT_EQ(s.name, "tiny_scene");  // the file's stem when the scene has no name
}

TEST_F(SceneJson, LoadSceneMissingFile) {
  try {
    ff::loadScene("/nonexistent/flowform/none.json");
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("/nonexistent/flowform/none.json: cannot open scene file"), std::string::npos) << msg;
  }
}

TEST(Params, PresetsAndRestSpacing) {
  ff::Params paper = ff::presetParams("paper");
  EXPECT_FLOAT_EQ(paper.fluid.particle_mass, 0.0002f);
  EXPECT_FLOAT_EQ(paper.fluid.smoothing_radius, 0.012f);
  EXPECT_FLOAT_EQ(paper.fluid.rest_density, 800.0f);
  EXPECT_FLOAT_EQ(paper.fluid.gas_constant, 0.5f);
  EXPECT_FLOAT_EQ(paper.fluid.time_step, 0.004f);
  EXPECT_FLOAT_EQ(paper.control.radius, 0.03f);
  EXPECT_FLOAT_EQ(paper.shape.stiffness, 0.3f);
  EXPECT_NEAR(paper.fluid.restSpacing(), 0.0062996f, 1e-6f);
  // The default is the incompressible water (issue 9), the paper's spacing.
  const ff::Params def = ff::presetParams("default"), water = ff::presetParams("water");
  EXPECT_EQ(def.fluid.solver, ff::PressureSolverKind::Dfsph);
  EXPECT_FLOAT_EQ(def.fluid.rest_density, 1000.0f);
  EXPECT_FLOAT_EQ(def.fluid.particle_mass, water.fluid.particle_mass);
  EXPECT_FLOAT_EQ(def.fluid.viscosity, water.fluid.viscosity);
  EXPECT_NEAR(def.fluid.restSpacing(), paper.fluid.restSpacing(), 1e-7f);
  EXPECT_NO_THROW(ff::validateParams(paper, "paper"));
  EXPECT_NO_THROW(ff::validateParams(def, "default"));
}

TEST(Params, UnknownPresetListsKnownOnes) {
  try {
    ff::presetParams("turbo");
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("turbo"), std::string::npos) << msg;
    EXPECT_NE(msg.find("paper"), std::string::npos) << msg;
    EXPECT_NE(msg.find("default"), std::string::npos) << msg;
  }
}

TEST(Params, ValidateRejectsNanAndRanges) {
  auto message = [](const ff::Params& p) {
    try {
      ff::validateParams(p, "WHERE");
    } catch (const ff::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  ff::Params p;
  p.fluid.gas_constant = std::nanf("");
  EXPECT_EQ(message(p), "WHERE: params.fluid.gas_constant: must be in [0, 1e+06] (got nan)");
  p = ff::Params{};
  p.fluid.viscosity = INFINITY;
  EXPECT_NE(message(p).find("params.fluid.viscosity: must be in [0, 10000] (got inf)"), std::string::npos)
      << message(p);
  p = ff::Params{};
  p.fluid.gravity[2] = -INFINITY;
  EXPECT_NE(message(p).find("params.fluid.gravity[2]"), std::string::npos) << message(p);
  p = ff::Params{};
  p.fluid.particle_mass = 0.0f;
  EXPECT_NE(message(p).find("params.fluid.particle_mass: must be in (0, 1000] (got 0)"), std::string::npos)
      << message(p);
  p = ff::Params{};
  p.fluid.max_step_fraction = 1.5f;
  EXPECT_NE(message(p).find("params.fluid.max_step_fraction"), std::string::npos) << message(p);
  p = ff::Params{};
  p.shape.stiffness = -0.1f;
  EXPECT_NE(message(p).find("params.shape_matching.stiffness"), std::string::npos) << message(p);
  p = ff::Params{};
  p.shape.cluster_half_width = 0;
  EXPECT_NE(message(p).find("params.shape_matching.cluster_half_width: must be in [1, 64] (got 0)"),
            std::string::npos)
      << message(p);
  p = ff::Params{};
  p.control.radius = -1.0f;
  EXPECT_NE(message(p).find("params.control.radius"), std::string::npos) << message(p);
}

// scenes/README.md documents every key of the parameter table: each key a
// scene's "params" accepts is named there as `KEY` or `GROUP.KEY`, or in its
// example scene as "KEY".
TEST(Params, EveryTableKeyIsDocumentedInTheSceneFormat) {
  std::ifstream in(std::string(FF_SOURCE_DIR) + "/scenes/README.md");
  ASSERT_TRUE(in) << "scenes/README.md";
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const ff::ParamInfo& info : ff::paramTable()) {
    const std::string key = std::string("`") + info.key + "`";
    const std::string full = std::string("`") + info.group + "." + info.key + "`";
    const std::string quoted = std::string("\"") + info.key + "\":";
    EXPECT_TRUE(doc.find(key) != std::string::npos || doc.find(full) != std::string::npos ||
                doc.find(quoted) != std::string::npos)
        << info.name();
  }
}

// The table of scene files in scenes/README.md against the files: each
// row's preset, fluid particle count and duration are the file's, and every
// scene file has a row (water/*.json: the row of the same name in this
// folder, on the water preset). Before, it said every scene in the folder
// used `paper`; default.json uses `default`.
TEST(Params, TheSceneFolderTableSaysWhatTheFilesHold) {
  const std::string dir = std::string(FF_SOURCE_DIR) + "/scenes/";
  std::ifstream in(dir + "README.md");
  ASSERT_TRUE(in);
  struct Row {
    std::string preset, particles, duration;
  };
  std::map<std::string, Row> rows;  // file name -> its row
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| `", 0) != 0) continue;
    std::vector<std::string> cells;
    std::istringstream ls(line.substr(1));
    for (std::string c; std::getline(ls, c, '|');) cells.push_back(c.substr(1, c.size() - 2));
    if (cells.size() < 5) continue;
    auto unquote = [](const std::string& t) { return t.size() > 2 ? t.substr(1, t.size() - 2) : t; };
    rows[unquote(cells[0])] = {unquote(cells[1]), cells[2].substr(0, cells[2].find(' ')), cells[4]};
  }
  ASSERT_TRUE(rows.count("water/*.json"));
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.path().extension() != ".json" || e.path().parent_path().filename() == "scripts") continue;
    const std::string rel = std::filesystem::relative(e.path(), dir).string();
    const bool water = rel.rfind("water/", 0) == 0;
    const std::string name = water ? rel.substr(6) : rel;
    ASSERT_TRUE(rows.count(name)) << rel << " has no row";
    std::ifstream f(e.path());
    const json j = json::parse(f);
    long particles = 0;
    for (const json& b : j["fluid"])
      particles += b["dims"][0].get<long>() * b["dims"][1].get<long>() * b["dims"][2].get<long>();
    const Row& r = rows[name];
    EXPECT_EQ(j["preset"].get<std::string>(), water ? rows["water/*.json"].preset : r.preset) << rel;
    EXPECT_EQ(std::to_string(particles), r.particles) << rel;
    char duration[32];
    std::snprintf(duration, sizeof duration, "%g s", j["duration"].get<double>());
    EXPECT_EQ(duration, r.duration) << rel;
    ++files;
  }
  EXPECT_GE(files, 11);
}

// A key a scene's params give that another parameter's mode overrides does
// nothing (SimulationApi.AParameterActsWhereParamActsSaysSo runs it): it is
// warned, naming the file, the key and the mode; a key that acts is not.
// The warnings that reading a scene "w.json" on `preset` with `params` (JSON) gives.
static std::vector<std::string> paramWarnings(const std::string& preset, const std::string& params) {
  std::vector<std::string> warnings;
  const ff::WarningSink old = ff::setWarningSink([&](const std::string& m) { warnings.push_back(m); });
  ff::parseScene(R"({"preset": ")" + preset + R"(", "params": )" + params +
                     R"(, "fluid": [{"origin": [0, 0, 0], "dims": [2, 2, 2]}]})",
                 "w.json", ".");
  ff::setWarningSink(old);
  return warnings;
}

TEST(Params, AKeyThatHasNoEffectIsWarned) {
  auto parse = [&](const std::string& preset, const std::string& control) {
    return paramWarnings(preset, R"({"control": )" + control + "}");
  };
  const std::vector<std::string> normalised = parse("water", R"({"attraction": 0.0001, "attraction_g": 9})");
  ASSERT_EQ(normalised.size(), 1u);
  EXPECT_EQ(normalised[0].rfind("w.json: params.control.attraction: has no effect while "
                                "params.control.normalise is 1",
                                0),
            0u)
      << normalised[0];
  const std::vector<std::string> radius = parse("water", R"({"radius": 0.04})");
  ASSERT_EQ(radius.size(), 1u);
  EXPECT_NE(radius[0].find("params.control.radius: has no effect while params.control.radius_spacings > 0"),
            std::string::npos)
      << radius[0];
  EXPECT_TRUE(parse("water", R"({"radius": 0.04, "radius_spacings": 0})").empty());
  EXPECT_TRUE(parse("paper", R"({"attraction": 0.0001, "radius": 0.04})").empty());
  ASSERT_EQ(parse("paper", R"({"velocity_rate": 2})").size(), 1u);
}

// A step in seconds given with its *_fall > 0 in the same params: the fall
// time sets the step (the table lists *_fall later), so the seconds do
// nothing and are warned, as the other keys that another overrides (one
// table, overrideRules). Given alone, a step in seconds turns its *_fall
// off and acts: no warning.
TEST(Params, AStepInSecondsThatItsFallTimeOverridesIsWarned) {
  auto parse = [](const std::string& params) { return paramWarnings("water", params); };
  const std::vector<std::string> sm =
      parse(R"({"shape_matching": {"time_step": 0.003, "time_step_fall": 0.05}})");
  ASSERT_EQ(sm.size(), 1u);
  EXPECT_NE(sm[0].find("w.json: params.shape_matching.time_step: has no effect while "
                       "params.shape_matching.time_step_fall > 0"),
            std::string::npos)
      << sm[0];
  const std::vector<std::string> fluid = parse(R"({"fluid": {"time_step": 0.003, "time_step_fall": 0.1}})");
  ASSERT_EQ(fluid.size(), 1u);
  EXPECT_NE(fluid[0].find("params.fluid.time_step: has no effect while params.fluid.time_step_fall > 0"),
            std::string::npos)
      << fluid[0];
  EXPECT_TRUE(parse(R"({"fluid": {"time_step": 0.003}, "shape_matching": {"time_step": 0.003}})").empty());
}

// Each override rule names keys of the parameter table, of the same group.
TEST(Params, EveryOverrideRuleNamesParametersOfTheTable) {
  auto find = [](const char* group, const char* key) {
    for (const ff::ParamInfo& i : ff::paramTable())
      if (std::string(i.group) == group && std::string(i.key) == key) return true;
    return false;
  };
  ASSERT_FALSE(ff::overrideRules().empty());
  for (const ff::OverrideRule& r : ff::overrideRules()) {
    EXPECT_TRUE(find(r.group, r.key)) << r.group << "." << r.key;
    EXPECT_TRUE(find(r.group, r.by)) << r.group << "." << r.by;
  }
}

// Each rule holds where its condition in words (the scene reader's warning)
// says: BY at 0 and at 1 (each BY is a mode 0 or 1, or a number off at 0).
TEST(Params, EveryOverrideRuleHoldsWhereItsWordsSay) {
  for (const ff::OverrideRule& r : ff::overrideRules()) {
    const ff::ParamInfo* by = nullptr;
    for (const ff::ParamInfo& i : ff::paramTable())
      if (std::string(i.group) == r.group && std::string(i.key) == r.by) by = &i;
    ASSERT_NE(by, nullptr) << r.by;
    ff::Params p;
    auto holdsAt = [&](int v) {
      void* f = by->field(p);
      if (by->type == ff::ParamInfo::Type::Integer)
        *static_cast<int*>(f) = v;
      else
        *static_cast<float*>(f) = float(v);
      return r.holds(p);
    };
    const std::string words = r.condition();
    EXPECT_EQ(holdsAt(0), words == "is 0") << r.key << " " << words;
    EXPECT_EQ(holdsAt(1), words == "> 0" || words == "is 1") << r.key << " " << words;
  }
}
