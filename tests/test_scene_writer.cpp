// The scene writer (src/scene/scene_writer.cpp): a scene written and read back
// by the strict reader has the values the test put into it (compared field by
// field against the test's own values, not against another output of the
// writer), an existing file is never replaced, and the camera block is read
// and checked like the rest of a scene.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/param_table.h"
#include "scene/scene.h"
#include "scene/scene_json.h"
#include "scene/scene_writer.h"
#include "temp_dir.h"

namespace {

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A scene made in code, with every part away from its default: values such
// as 0.1f and 1.0f / 3.0f have no short decimal form in binary, so a writer
// that rounds them would be caught.
ff::SceneDesc handMadeScene() {
  ff::SceneDesc s;
  s.name = "hand_made";
  s.preset = "paper";
  s.params = ff::presetParams("paper");
  s.params.fluid.viscosity = 0.1f;
  s.params.fluid.gravity[0] = 1.0f / 3.0f;
  s.params.fluid.max_substeps = 7;
  s.params.control.attraction = 2.5e-5f;
  s.params.control.units = ff::ControlForceUnits::ForceDensity;
  s.params.shape.stiffness = 0.7f;
  s.params.shape.cluster_half_width = 3;
  s.duration = 1.25;
  s.container.min = ff::Vec3(-0.1f, 0.0f, 0.05f);
  s.container.max = ff::Vec3(0.3f, 0.25f, 0.35f);
  ff::FluidBlockDesc a;
  a.origin = ff::Vec3(0.0f, 0.0f, 0.1f);
  a.dims[0] = 4;
  a.dims[1] = 5;
  a.dims[2] = 6;
  ff::FluidBlockDesc b;
  b.origin = ff::Vec3(0.1f, 0.1f, 0.1f);
  b.dims[0] = b.dims[1] = b.dims[2] = 3;
  b.spacing = 0.011f;
  b.velocity = ff::Vec3(0.0f, -0.3f, 0.1f);
  s.fluid = {a, b};
  s.region.kind = ff::RegionDesc::Kind::Box;
  s.region.min = ff::Vec3(-0.05f, 0.0f, 0.07f);
  s.region.max = ff::Vec3(0.2f, 0.15f, 0.3f);
  ff::TargetSpec box;
  box.kind = ff::TargetKind::Box;
  box.box_size = ff::Vec3(2.0f, 1.0f, 0.5f);
  box.rotation_deg = ff::Vec3(0.0f, 45.0f, 10.0f);
  box.control_count = 900;
  ff::TargetSpec torus;
  torus.kind = ff::TargetKind::Torus;
  torus.torus_major = 1.5f;
  torus.torus_minor = 0.3f;
  torus.voxel_size = 0.007f;
  torus.volume = 2e-4f;
  ff::TargetSpec capsule;
  capsule.kind = ff::TargetKind::Capsule;
  capsule.capsule_radius = 0.4f;
  capsule.capsule_length = 0.0f;
  s.schedule = {{0.0, box}, {0.5, torus}, {0.875, capsule}};
  ff::CameraDesc cam;
  cam.yaw_deg = 33.3f;
  cam.pitch_deg = -12.5f;
  cam.distance = 0.55f;
  cam.fov_deg = 50.0f;
  cam.target = ff::Vec3(0.1f, 0.05f, 0.2f);
  s.camera = cam;
  return s;
}

void expectVec(const ff::Vec3& got, float x, float y, float z) {
  EXPECT_EQ(got.x(), x);
  EXPECT_EQ(got.y(), y);
  EXPECT_EQ(got.z(), z);
}

TEST(SceneWriter, WriteThenReadGivesTheSameScene) {
  fftest::TempDir dir("scene_writer");
  const std::string file = dir.file("saved.json");
  ff::writeSceneFile(handMadeScene(), file);
  const ff::SceneDesc r = ff::loadScene(file);

  EXPECT_EQ(r.name, "hand_made");
  EXPECT_EQ(r.preset, "paper");
  EXPECT_EQ(r.duration, 1.25);
  expectVec(r.container.min, -0.1f, 0.0f, 0.05f);
  expectVec(r.container.max, 0.3f, 0.25f, 0.35f);

  // The parameters set above, and every other one at the preset's value.
  EXPECT_EQ(r.params.fluid.viscosity, 0.1f);
  EXPECT_EQ(r.params.fluid.gravity[0], 1.0f / 3.0f);
  EXPECT_EQ(r.params.fluid.gravity[1], -9.81f);
  EXPECT_EQ(r.params.fluid.max_substeps, 7);
  EXPECT_EQ(r.params.control.attraction, 2.5e-5f);
  EXPECT_EQ(r.params.control.units, ff::ControlForceUnits::ForceDensity);
  EXPECT_EQ(r.params.shape.stiffness, 0.7f);
  EXPECT_EQ(r.params.shape.cluster_half_width, 3);
  const ff::Params paper = ff::presetParams("paper");
  EXPECT_EQ(r.params.fluid.rest_density, paper.fluid.rest_density);
  EXPECT_EQ(r.params.fluid.time_step, paper.fluid.time_step);
  EXPECT_EQ(r.params.control.velocity, paper.control.velocity);
  EXPECT_EQ(r.params.shape.cluster_stride, paper.shape.cluster_stride);

  ASSERT_EQ(r.fluid.size(), 2u);
  expectVec(r.fluid[0].origin, 0.0f, 0.0f, 0.1f);
  EXPECT_EQ(r.fluid[0].dims[0], 4);
  EXPECT_EQ(r.fluid[0].dims[1], 5);
  EXPECT_EQ(r.fluid[0].dims[2], 6);
  EXPECT_EQ(r.fluid[0].spacing, 0.0f);
  expectVec(r.fluid[0].velocity, 0.0f, 0.0f, 0.0f);
  EXPECT_EQ(r.fluid[1].spacing, 0.011f);
  expectVec(r.fluid[1].velocity, 0.0f, -0.3f, 0.1f);

  EXPECT_EQ(r.region.kind, ff::RegionDesc::Kind::Box);
  expectVec(r.region.min, -0.05f, 0.0f, 0.07f);
  expectVec(r.region.max, 0.2f, 0.15f, 0.3f);

  ASSERT_EQ(r.schedule.size(), 3u);
  EXPECT_EQ(r.schedule[1].time, 0.5);
  EXPECT_EQ(r.schedule[2].time, 0.875);
  const ff::TargetSpec& box = r.schedule[0].target;
  EXPECT_EQ(box.kind, ff::TargetKind::Box);
  expectVec(box.box_size, 2.0f, 1.0f, 0.5f);
  expectVec(box.rotation_deg, 0.0f, 45.0f, 10.0f);
  EXPECT_EQ(box.control_count, 900);
  EXPECT_EQ(box.voxel_size, 0.0f);
  const ff::TargetSpec& torus = r.schedule[1].target;
  EXPECT_EQ(torus.kind, ff::TargetKind::Torus);
  EXPECT_EQ(torus.torus_major, 1.5f);
  EXPECT_EQ(torus.torus_minor, 0.3f);
  EXPECT_EQ(torus.voxel_size, 0.007f);
  EXPECT_EQ(torus.volume, 2e-4f);
  EXPECT_EQ(torus.control_count, 0);
  const ff::TargetSpec& capsule = r.schedule[2].target;
  EXPECT_EQ(capsule.kind, ff::TargetKind::Capsule);
  EXPECT_EQ(capsule.capsule_radius, 0.4f);
  EXPECT_EQ(capsule.capsule_length, 0.0f);

  ASSERT_TRUE(r.camera.has_value());
  ASSERT_TRUE(r.camera->yaw_deg && r.camera->pitch_deg && r.camera->distance && r.camera->fov_deg &&
              r.camera->target);
  EXPECT_EQ(*r.camera->yaw_deg, 33.3f);
  EXPECT_EQ(*r.camera->pitch_deg, -12.5f);
  EXPECT_EQ(*r.camera->distance, 0.55f);
  EXPECT_EQ(*r.camera->fov_deg, 50.0f);
  expectVec(*r.camera->target, 0.1f, 0.05f, 0.2f);

  // Only the changed parameters are written, under the preset's name, and a
  // value such as 0.1f is written as 0.1, not 0.10000000149011612.
  const std::string text = readAll(file);
  EXPECT_NE(text.find("\"viscosity\": 0.1,"), std::string::npos) << text;
  EXPECT_EQ(text.find("rest_density"), std::string::npos) << text;
}

TEST(SceneWriter, EveryParameterOfTheTableRoundTrips) {
  // Each parameter in turn moved inside its range (towards its maximum), the
  // rest at the preset's values: written and read back, it has the new value.
  fftest::TempDir dir("scene_writer_params");
  int n = 0;
  for (const ff::ParamInfo& info : ff::paramTable()) {
    if (info.type != ff::ParamInfo::Type::Real && info.type != ff::ParamInfo::Type::Integer) continue;
    ff::SceneDesc s = handMadeScene();
    s.params = ff::presetParams("paper");
    void* field = info.field(s.params);
    double want = 0.0;
    if (info.type == ff::ParamInfo::Type::Real) {
      float& v = *static_cast<float*>(field);
      const double up = std::min(info.max, double(v) * 1.37 + 1e-3);
      v = float(up);
      if (!info.inRange(v)) v = float(info.max);
      want = v;
    } else {
      int& v = *static_cast<int*>(field);
      v = info.inRange(v + 1) ? v + 1 : v - 1;
      want = v;
    }
    try {
      ff::validateParams(s.params, "");
    } catch (const ff::Error&) {
      continue;  // a parameter bounded by another one (e.g. the shape-matching clock): skipped
    }
    const std::string file = dir.file("p" + std::to_string(n++) + ".json");
    ff::writeSceneFile(s, file);
    ff::SceneDesc r = ff::loadScene(file);
    const void* got = info.field(r.params);
    if (info.type == ff::ParamInfo::Type::Real)
      EXPECT_EQ(*static_cast<const float*>(got), float(want)) << info.name();
    else
      EXPECT_EQ(*static_cast<const int*>(got), int(want)) << info.name();
  }
  EXPECT_GT(n, 10);
}

// A step that its *_fall sets (the water preset's fluid and shape-matching
// steps, derived at the run's start and at every target) is not written, so
// that read back it still follows the scene: written in seconds it would turn
// the *_fall off. A step given in seconds (the *_fall off) is written and read
// back as it was.
TEST(SceneWriter, AStepThatItsFallTimeSetsIsNotWrittenInSeconds) {
  fftest::TempDir dir("scene_writer_steps");
  const ff::Params water = ff::presetParams("water");
  ASSERT_GT(water.fluid.time_step_fall, 0.0f);
  ASSERT_GT(water.shape.time_step_fall, 0.0f);
  ff::SceneDesc s = handMadeScene();
  s.preset = "water";
  s.params = water;
  s.params.fluid.time_step = 0.0047f;  // as a derived step of another scale would be
  s.params.shape.time_step = 0.0063f;
  ff::writeSceneFile(s, dir.file("fall.json"));
  const ff::SceneDesc r = ff::loadScene(dir.file("fall.json"));
  EXPECT_EQ(r.params.fluid.time_step_fall, water.fluid.time_step_fall);
  EXPECT_EQ(r.params.shape.time_step_fall, water.shape.time_step_fall);

  s.params.fluid.setTimeStep(0.0047f);
  s.params.shape.setTimeStep(0.0063f);
  ff::writeSceneFile(s, dir.file("seconds.json"));
  const ff::SceneDesc q = ff::loadScene(dir.file("seconds.json"));
  EXPECT_EQ(q.params.fluid.time_step, 0.0047f);
  EXPECT_EQ(q.params.fluid.time_step_fall, 0.0f);
  EXPECT_EQ(q.params.shape.time_step, 0.0063f);
  EXPECT_EQ(q.params.shape.time_step_fall, 0.0f);
}

TEST(SceneWriter, ASingleTargetAllFluidAndNoControlAreWrittenAsSuch) {
  fftest::TempDir dir("scene_writer_forms");
  ff::SceneDesc s = handMadeScene();
  s.region = ff::RegionDesc();
  s.region.kind = ff::RegionDesc::Kind::Sphere;
  s.region.center = ff::Vec3(0.1f, 0.1f, 0.2f);
  s.region.radius = 0.07f;
  s.schedule.resize(1);
  s.camera.reset();
  ff::writeSceneFile(s, dir.file("one.json"));
  ff::SceneDesc r = ff::loadScene(dir.file("one.json"));
  ASSERT_EQ(r.schedule.size(), 1u);
  EXPECT_EQ(r.schedule[0].target.kind, ff::TargetKind::Box);
  EXPECT_EQ(r.region.kind, ff::RegionDesc::Kind::Sphere);
  expectVec(r.region.center, 0.1f, 0.1f, 0.2f);
  EXPECT_EQ(r.region.radius, 0.07f);
  EXPECT_FALSE(r.camera.has_value());
  EXPECT_NE(readAll(dir.file("one.json")).find("\"target\""), std::string::npos);

  s.schedule.clear();
  s.region = ff::RegionDesc();
  ff::writeSceneFile(s, dir.file("none.json"));
  r = ff::loadScene(dir.file("none.json"));
  EXPECT_TRUE(r.schedule.empty());
  EXPECT_EQ(r.region.kind, ff::RegionDesc::Kind::All);
}

TEST(SceneWriter, AMeshTargetStillFindsItsFileFromTheNewFolder) {
  fftest::TempDir dir("scene_writer_mesh");
  // A tetrahedron written by the test, read from a scene in one folder and
  // saved into another: the saved path must lead to the same file.
  std::filesystem::create_directories(dir / "a");
  std::filesystem::create_directories(dir / "b");
  dir.write("a/tet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  dir.write("a/scene.json", R"({"fluid": [{"origin": [0, 0, 0], "dims": [4, 4, 4]}],
    "target": {"shape": "mesh", "mesh": "tet.obj", "control_count": 100}})");
  const ff::SceneDesc s = ff::loadScene(dir.file("a/scene.json"));
  ff::writeSceneFile(s, dir.file("a/same_folder.json"));
  ff::writeSceneFile(s, dir.file("b/other_folder.json"));
  const ff::SceneDesc same = ff::loadScene(dir.file("a/same_folder.json"));
  const ff::SceneDesc other = ff::loadScene(dir.file("b/other_folder.json"));
  EXPECT_EQ(same.schedule.at(0).target.mesh, "tet.obj");  // kept as written
  EXPECT_TRUE(std::filesystem::equivalent(other.schedule.at(0).target.resolved_path, dir / "a" / "tet.obj"));
  EXPECT_EQ(other.schedule.at(0).target.control_count, 100);
}

TEST(SceneWriter, AnExistingFileIsNeverReplaced) {
  fftest::TempDir dir("scene_writer_exists");
  const std::string file = dir.write("mine.json", "my own notes").string();
  try {
    ff::writeSceneFile(handMadeScene(), file);
    FAIL() << "an existing file was replaced";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find("mine.json: a file of that name exists; not overwritten"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(readAll(file), "my own notes");
  EXPECT_EQ(ff::freeFileName(file), dir.file("mine_2.json"));
  dir.write("mine_2.json", "");
  EXPECT_EQ(ff::freeFileName(file), dir.file("mine_3.json"));
  EXPECT_EQ(ff::freeFileName(dir.file("new.json")), dir.file("new.json"));
  // Nothing else was left in the folder (no temporary file).
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 2);
}

TEST(SceneWriter, TheCameraBlockIsCheckedLikeTheRestOfTheScene) {
  const std::string fluid = R"("fluid": [{"origin": [0, 0, 0], "dims": [2, 2, 2]}])";
  const std::pair<std::string, std::string> bad[] = {
      {R"("camera": {"pitch": 90})", "s.json: camera.pitch: must be in [-89, 89]"},
      {R"("camera": {"fov": 2})", "s.json: camera.fov: must be in [5, 150]"},
      {R"("camera": {"distance": -1})", "s.json: camera.distance: must be > 0"},
      {R"("camera": {"roll": 1})", "s.json: camera.roll: unknown key"},
      {R"("camera": {})", "s.json: camera: must not be empty"},
      {R"("camera": [1, 2])", "s.json: camera: must be an object"},
      {R"("camera": {"target": [0, "x", 0]})", "s.json: camera.target: must be an array of 3 numbers"},
  };
  for (const auto& [block, message] : bad) {
    try {
      ff::parseScene("{" + fluid + ", " + block + "}", "s.json", "");
      ADD_FAILURE() << block << " was accepted";
    } catch (const ff::Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  const ff::SceneDesc s = ff::parseScene("{" + fluid + R"(, "camera": {"yaw": 10}})", "s.json", "");
  ASSERT_TRUE(s.camera && s.camera->yaw_deg);
  EXPECT_EQ(*s.camera->yaw_deg, 10.0f);
  EXPECT_FALSE(s.camera->pitch_deg || s.camera->distance || s.camera->fov_deg || s.camera->target);
}

}  // namespace
