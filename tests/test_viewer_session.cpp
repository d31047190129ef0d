// The viewer's window-free parts: the target list (built-ins and the meshes of
// FLOWFORM_MESH_PATH), the typed-target field, and the session that owns the
// Simulation: picks stop the scene's schedule, rejected edits change nothing,
// and reset keeps what docs/VIEWER.md says it keeps.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "control/control_set.h"
#include "core/error.h"
#include "temp_dir.h"
#include "test_scenes.h"
#include "viewer/script.h"
#include "viewer/target_catalog.h"
#include "viewer/viewer_session.h"

namespace {

namespace fs = std::filesystem;
using ff::viewer::TargetChoice;
using ff::viewer::ViewerSession;

void touch(const fs::path& p) {
  std::ofstream(p) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
}

TEST(ViewerTargets, ListsBuiltinsThenTheMeshesOfEveryFolder) {
  const fftest::TempDir a("session_meshes_a"), b("session_meshes_b");
  touch(a / "zebra.obj");
  touch(a / "bunny.obj");
  touch(a / "Horse.PLY");
  touch(a / "notes.txt");
  fs::create_directories(a / "sub.obj");  // a folder, not a mesh
  touch(a / "sub.obj" / "hidden.stl");
  touch(b / "bunny.obj");
  touch(b / "cube.off");
  const std::string path = a.string() + ":" + (a / "missing").string() + "::" + b.string();
  const std::vector<TargetChoice> list = ff::viewer::targetChoices(path);
  std::vector<std::string> labels;
  for (const TargetChoice& c : list) labels.push_back(c.label);
  const std::vector<std::string> expected = {"No control",
                                             "sphere",
                                             "box",
                                             "torus",
                                             "capsule",
                                             "Horse.PLY",
                                             "bunny.obj (" + a.string() + ")",
                                             "zebra.obj",
                                             "bunny.obj (" + b.string() + ")",
                                             "cube.off"};
  EXPECT_EQ(labels, expected);
  EXPECT_TRUE(list[0].none);
  EXPECT_FALSE(list[1].none);
  EXPECT_EQ(list[3].spec.kind, ff::TargetKind::Torus);
  EXPECT_EQ(list[9].spec.kind, ff::TargetKind::Mesh);
  EXPECT_EQ(list[9].spec.resolved_path, (b / "cube.off").string());
  EXPECT_EQ(ff::viewer::targetChoices("").size(), 5u);
}

TEST(ViewerTargets, TypedTargetTakesNamesPathsAndSceneSyntax) {
  EXPECT_EQ(ff::viewer::parseTypedTarget("  torus ").kind, ff::TargetKind::Torus);
  const ff::TargetSpec box = ff::viewer::parseTypedTarget(R"({"shape": "box", "size": [2, 1, 1]})");
  EXPECT_EQ(box.kind, ff::TargetKind::Box);
  EXPECT_FLOAT_EQ(box.box_size.x(), 2.0f);
  const fftest::TempDir d("session_typed");
  touch(d / "tet.obj");
  const ff::TargetSpec mesh = ff::viewer::parseTypedTarget((d / "tet.obj").string());
  EXPECT_EQ(mesh.kind, ff::TargetKind::Mesh);
  EXPECT_EQ(mesh.resolved_path, (d / "tet.obj").string());

  auto message = [](const std::string& text) {
    try {
      ff::viewer::parseTypedTarget(text);
    } catch (const ff::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("cube").find("typed target: must be sphere, box"), std::string::npos) << message("cube");
  EXPECT_NE(message("").find("typed target: empty"), std::string::npos);
  EXPECT_NE(message("/no/such/dir/x.obj").find("typed target"), std::string::npos);
  EXPECT_NE(message(R"({"shape": "box", "size": [2, 1]})").find("size: must be an array of 3 numbers"),
            std::string::npos);
  EXPECT_NE(message("{\"shape\": ").find("invalid JSON"), std::string::npos);
}

// 216 particles in a small box; sphere at t = 0, box from t = 0.008 (step 2).
ff::SceneDesc tinyScene() {
  ff::SceneDesc s =
      fftest::blockScene(ff::Vec3(0.1f, 0.1f, 0.1f), ff::Vec3(0.03f, 0.0f, 0.03f), 6, 6, 6, "tiny.json");
  s.name = "tiny";
  s.schedule.push_back({0.0, fftest::target(ff::TargetKind::Sphere)});
  s.schedule.push_back({0.008, fftest::target(ff::TargetKind::Box)});
  return s;
}

ff::viewer::BackendChoice cpu() {
  return ff::viewer::BackendChoice{"cpu", -1, 2};
}

TEST(ViewerSession, PlaysTheScheduleUntilTheUserPicksATarget) {
  ViewerSession followed(tinyScene(), cpu());
  EXPECT_EQ(followed.targetLabel(), "sphere");
  for (int i = 0; i < 4; ++i) followed.step();
  EXPECT_EQ(followed.targetLabel(), "box");
  EXPECT_TRUE(followed.followsSchedule());

  ViewerSession picked(tinyScene(), cpu());
  picked.step();
  picked.chooseTarget(fftest::target(ff::TargetKind::Torus));
  EXPECT_FALSE(picked.followsSchedule());
  for (int i = 0; i < 4; ++i) picked.step();
  EXPECT_EQ(picked.targetLabel(), "torus");  // the scheduled box did not replace it
  picked.chooseNoTarget();
  picked.step();
  EXPECT_EQ(picked.targetLabel(), "none");
  EXPECT_EQ(picked.sim().target(), nullptr);
}

TEST(ViewerSession, RejectedEditsChangeNothing) {
  ViewerSession s(tinyScene(), cpu());
  s.step();
  ff::Params bad = s.params();
  bad.fluid.viscosity = -1.0f;
  EXPECT_THROW(s.setParams(bad), ff::Error);
  EXPECT_FLOAT_EQ(s.params().fluid.viscosity, tinyScene().params.fluid.viscosity);

  ff::RegionDesc empty;
  empty.kind = ff::RegionDesc::Kind::Box;
  empty.min = ff::Vec3(0.0f, 0.08f, 0.0f);  // above the fluid
  empty.max = ff::Vec3(0.01f, 0.09f, 0.01f);
  EXPECT_THROW(s.setRegion(empty), ff::Error);
  EXPECT_EQ(s.region().kind, ff::RegionDesc::Kind::All);

  const fftest::TempDir d("session_badmesh");
  std::ofstream(d / "broken.obj") << "this is not a mesh\n";
  ff::TargetSpec broken;
  broken.kind = ff::TargetKind::Mesh;
  broken.mesh = broken.resolved_path = (d / "broken.obj").string();
  EXPECT_THROW(s.chooseTarget(broken), ff::Error);
  EXPECT_EQ(s.targetLabel(), "sphere");
  EXPECT_TRUE(s.followsSchedule());
  EXPECT_NO_THROW(s.step());  // the simulation goes on
}

TEST(ViewerSession, ANewRegionRebuildsTheTargetFromAllTheFluidInIt) {
  // Two blocks of 64 particles, far apart; the sphere is made from the left one.
  ff::SceneDesc scene = tinyScene();
  scene.schedule.clear();
  scene.fluid[0].origin = ff::Vec3(0.005f, 0.0f, 0.04f);
  scene.fluid[0].dims[0] = scene.fluid[0].dims[1] = scene.fluid[0].dims[2] = 4;
  scene.fluid.push_back(scene.fluid[0]);
  scene.fluid[1].origin = ff::Vec3(0.07f, 0.0f, 0.04f);
  ViewerSession s(scene, cpu());
  ff::RegionDesc left;
  left.kind = ff::RegionDesc::Kind::Box;
  left.min = ff::Vec3(0.0f, 0.0f, 0.0f);
  left.max = ff::Vec3(0.05f, 0.1f, 0.1f);
  s.setRegion(left);
  s.chooseTarget(fftest::target(ff::TargetKind::Sphere));
  EXPECT_EQ(s.sim().controlledCount(), 64);
  s.step();
  // All: both blocks. (Simulation::setRegion alone would keep to the fluid
  // forming the current sphere, i.e. the left block.)
  s.setRegion(ff::RegionDesc());
  EXPECT_EQ(s.sim().controlledCount(), 128);
  EXPECT_EQ(s.targetLabel(), "sphere");
}

TEST(ViewerSession, ResetKeepsEditsOrRestoresTheScene) {
  ViewerSession s(tinyScene(), cpu());
  for (int i = 0; i < 3; ++i) s.step();
  ff::Params p = s.params();
  p.fluid.viscosity = 0.05f;
  s.setParams(p);
  ff::RegionDesc low;
  low.kind = ff::RegionDesc::Kind::Box;
  low.min = ff::Vec3(0.0f, 0.0f, 0.0f);
  low.max = ff::Vec3(0.1f, 0.02f, 0.1f);
  s.setRegion(low);
  s.chooseTarget(fftest::target(ff::TargetKind::Capsule));

  EXPECT_EQ(s.reset(true), "");
  EXPECT_DOUBLE_EQ(s.sim().time(), 0.0);
  EXPECT_FLOAT_EQ(s.params().fluid.viscosity, 0.05f);
  EXPECT_EQ(s.region().kind, ff::RegionDesc::Kind::Box);
  EXPECT_FLOAT_EQ(s.region().max.y(), 0.02f);
  EXPECT_EQ(s.targetLabel(), "capsule");
  for (int i = 0; i < 3; ++i) s.step();
  EXPECT_EQ(s.targetLabel(), "capsule");  // still no schedule

  s.chooseNoTarget();
  s.reset(true);
  EXPECT_EQ(s.targetLabel(), "none");

  s.reset(false);
  EXPECT_FLOAT_EQ(s.params().fluid.viscosity, tinyScene().params.fluid.viscosity);
  EXPECT_EQ(s.region().kind, ff::RegionDesc::Kind::All);
  EXPECT_EQ(s.targetLabel(), "sphere");
  EXPECT_TRUE(s.followsSchedule());
  for (int i = 0; i < 3; ++i) s.step();
  EXPECT_EQ(s.targetLabel(), "box");  // the schedule plays again
}

TEST(ViewerSession, ResetWarnsWhenTheKeptRegionHoldsNoFluidAtTimeZero) {
  ff::SceneDesc scene = tinyScene();
  scene.fluid[0].velocity = ff::Vec3(-1.0f, 0.0f, 0.0f);  // the block slides towards x = 0
  ViewerSession s(scene, cpu());
  for (int i = 0; i < 12; ++i) s.step();
  ff::RegionDesc left;  // beside the block's start, where the fluid is now
  left.kind = ff::RegionDesc::Kind::Box;
  left.min = ff::Vec3(0.0f, 0.0f, 0.0f);
  left.max = ff::Vec3(0.025f, 0.1f, 0.1f);
  s.setRegion(left);
  s.chooseTarget(fftest::target(ff::TargetKind::Torus));
  EXPECT_EQ(s.targetLabel(), "torus");
  const std::string warning = s.reset(true);
  EXPECT_NE(warning.find("the target was not applied"), std::string::npos) << warning;
  EXPECT_NE(warning.find("holds no fluid"), std::string::npos) << warning;
  EXPECT_EQ(s.targetLabel(), "none");
  EXPECT_EQ(s.region().kind, ff::RegionDesc::Kind::Box);  // kept, for the user to change
  EXPECT_NO_THROW(s.step());
}

// "A step given in seconds turns off its fall-time multiple", for the
// shape-matching step (ShapeMatchParams::setTimeStep): the panel's "sm time
// step s" slider and a script's params action giving
// shape_matching.time_step are honoured where the scene ran on
// shape_matching.time_step_fall > 0 (the water preset), which the session
// otherwise sets again at every target and edit; the same params giving
// time_step_fall too keep the fall-time step. The fall time sqrt(r / |g|) is
// computed here in double.
// Clusters are built when control particles are placed: a new coarse level
// (shape_matching.coarse_clusters) re-places them at once, as a new cluster
// size does. Its clusters are k times as wide, so the set gains clusters.
TEST(ViewerSession, CoarseClustersTakeEffectAtOnce) {
  ViewerSession s(tinyScene(), cpu());
  s.step();
  auto clusters = [&s] {
    ff::ControlSet set;
    ff::ControlFields fields;
    s.sim().backend().readControl(set, fields);
    return set.clusters.start.empty() ? size_t(0) : set.clusters.start.size() - 1;
  };
  const size_t one_level = clusters();
  ASSERT_GT(one_level, 0u);
  ff::Params p = s.params();
  p.shape.coarse_clusters = 2;
  s.setParams(p);
  EXPECT_GT(clusters(), one_level);
  p.shape.coarse_clusters = 0;
  s.setParams(p);
  EXPECT_EQ(clusters(), one_level);
}

TEST(ViewerSession, AShapeStepInSecondsTurnsTheFallTimeMultipleOff) {
  ff::SceneDesc scene = tinyScene();
  scene.params.shape.time_step_fall = 0.09f;
  ViewerSession s(scene, cpu());
  ASSERT_NE(s.sim().target(), nullptr);
  ff::Params p = s.params();
  const float* g = p.fluid.gravity;
  const double fall = std::sqrt(double(p.control.radius) /
                                std::sqrt(double(g[0]) * g[0] + double(g[1]) * g[1] + double(g[2]) * g[2]));
  EXPECT_NEAR(s.params().shape.time_step, 0.09 * fall, 1e-6 * fall);
  EXPECT_NEAR(p.shape.timeStepFor(p.control.radius, g), 0.09 * fall, 1e-6 * fall);  // what the slider shows

  p.shape.time_step = 0.004f;  // written directly, not through the setter: overridden
  s.setParams(p);
  EXPECT_NEAR(s.params().shape.time_step, 0.09 * fall, 1e-6 * fall);

  p = s.params();
  p.shape.setTimeStep(0.004f);  // as the slider does
  s.setParams(p);
  EXPECT_EQ(s.params().shape.time_step, 0.004f);
  EXPECT_EQ(s.params().shape.time_step_fall, 0.0f);
  s.step(), s.step(), s.step();  // past the schedule's box at 0.008 s: a new target
  EXPECT_EQ(s.targetLabel(), "box");
  EXPECT_EQ(s.params().shape.time_step, 0.004f);  // and stays

  // A script's params action, as the viewer applies it (applyParamsAction, then setParams).
  ViewerSession t(scene, cpu());
  const ff::viewer::Script script = ff::viewer::parseScript(
      R"({"actions": [{"at": 0, "params": {"shape_matching": {"time_step": 0.003}}},
                      {"at": 0, "params": {"shape_matching": {"time_step": 0.003, "time_step_fall": 0.05}}},
                      {"at": 0, "params": {"fluid": {"time_step": 0.002}}}]})",
      "demo.json", ".");
  ff::Params q = t.params();
  ff::viewer::applyParamsAction(script.actions[0], q);
  t.setParams(q);
  EXPECT_EQ(t.params().shape.time_step, 0.003f);
  EXPECT_EQ(t.params().shape.time_step_fall, 0.0f);
  t.step(), t.step(), t.step();
  EXPECT_EQ(t.targetLabel(), "box");
  EXPECT_EQ(t.params().shape.time_step, 0.003f);
  // Given with its time_step_fall, the fall time rules.
  q = t.params();
  ff::viewer::applyParamsAction(script.actions[1], q);
  t.setParams(q);
  EXPECT_NEAR(t.params().shape.time_step, 0.05 * fall, 1e-6 * fall);
  // The fluid's frame step likewise (the tiny scene is on the paper preset's
  // 4 ms; set its frame in fall times first).
  q = t.params();
  q.fluid.time_step_fall = 0.1f;
  t.setParams(q);
  ASSERT_NE(t.params().fluid.time_step, 0.002f);
  q = t.params();
  ff::viewer::applyParamsAction(script.actions[2], q);
  t.setParams(q);
  EXPECT_EQ(t.params().fluid.time_step, 0.002f);
  EXPECT_EQ(t.params().fluid.time_step_fall, 0.0f);
}

}  // namespace
