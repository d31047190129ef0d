// The viewer's "Save scene..." end to end, under xvfb-run: a script changes
// the target, the region, a parameter and the camera and saves the scene;
// `flowform run` on the saved file starts from that target and region (its
// control particle count at the first step equals that of a scene the test
// writes by hand with the same target and region, and differs from the
// original scene's), and `flowform view` reads it back into the same state
// (a second save from it gives the same scene). An existing file is never
// replaced.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "scene/scene.h"
#include "xvfb_run.h"

namespace {

namespace fs = std::filesystem;

const std::string kExe = std::string("'") + FF_FLOWFORM_EXE + "'";

// As in test_viewer_xvfb.cpp: a display number of its own for each test.
int firstDisplay(int test) {
  return 1800 + int(::getpid() % 400) * 4 + test;
}

// 1000 particles resting on the floor of a 0.2 m box, a sphere target from the start.
const char* kSmallScene = R"({"name": "small", "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
    "fluid": [{"origin": [0.068, 0.0, 0.068], "dims": [10, 10, 10]}], "target": "sphere"})";

// The lower part of the block (it reaches y = 0.063 at rest).
const char* kRegion = R"({"box": {"min": [0.05, 0.0, 0.05], "max": [0.15, 0.03, 0.15]}})";
const char* kTarget = R"({"shape": "box", "size": [2, 1, 1], "control_count": 400})";

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The control_count column of the first data row of a metrics CSV.
long firstControlCount(const fs::path& csv) {
  std::ifstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  auto cells = [](const std::string& line) {
    std::vector<std::string> out;
    std::stringstream s(line);
    std::string c;
    while (std::getline(s, c, ',')) out.push_back(c);
    return out;
  };
  const auto names = cells(header), values = cells(row);
  for (size_t i = 0; i < names.size() && i < values.size(); ++i)
    if (names[i] == "control_count") return std::stol(values[i]);
  return -1;
}

long controlCountOfRun(const fs::path& scene, const fs::path& csv) {
  const fftest::CliResult r =
      fftest::runShell(kExe + " run '" + scene.string() +
                       "' --backend cpu --threads 2 --steps 2 --metrics '" + csv.string() + "'");
  EXPECT_EQ(r.code, 0) << r.out;
  return firstControlCount(csv);
}

TEST(ViewerSave, AScriptedSaveIsWhatRunAndViewStartFrom) {
  if (!fftest::haveXvfb())
    FAIL() << "this test runs `flowform view` under xvfb-run: install xvfb and xauth "
              "(Debian/Ubuntu: apt-get install xvfb xauth)";
  const fftest::TempDir dir("view_save");
  std::ofstream(dir / "small.json") << kSmallScene;
  const fs::path saved = dir / "out" / "saved.json";  // the folder exists: made below
  fs::create_directories(saved.parent_path());
  std::ofstream(dir / "script.json") << R"({"actions": [
    {"at": 0.02, "target": )" << kTarget
                                     << R"(},
    {"at": 0.03, "region": )" << kRegion
                                     << R"(},
    {"at": 0.03, "params": {"fluid": {"viscosity": 0.05}}},
    {"at": 0.03, "camera": {"yaw": 30, "pitch": 20, "distance": 0.45, "fov": 50, "target": [0.1, 0.05, 0.1]}},
    {"at": 0.04, "save": ")" << saved.string()
                                     << R"("},
    {"at": 0.04, "quit": true}
  ]})";
  fftest::CliResult r = fftest::runUnderXvfb(
      dir, firstDisplay(1),
      kExe + " view '" + (dir / "small.json").string() + "' --backend cpu --threads 2 --script '" +
          (dir / "script.json").string() + "' --width 400 --height 300");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("scene saved to " + saved.string()), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(saved)) << r.out;

  // The saved file, read by the strict reader: the script's target, region,
  // parameter and camera; the container and fluid of the original scene.
  const ff::SceneDesc s = ff::loadScene(saved.string());
  ASSERT_EQ(s.schedule.size(), 1u);
  EXPECT_EQ(s.schedule[0].target.kind, ff::TargetKind::Box);
  EXPECT_EQ(s.schedule[0].target.box_size, ff::Vec3(2.0f, 1.0f, 1.0f));
  EXPECT_EQ(s.schedule[0].target.control_count, 400);
  EXPECT_EQ(s.region.kind, ff::RegionDesc::Kind::Box);
  EXPECT_EQ(s.region.min, ff::Vec3(0.05f, 0.0f, 0.05f));
  EXPECT_EQ(s.region.max, ff::Vec3(0.15f, 0.03f, 0.15f));
  EXPECT_EQ(s.params.fluid.viscosity, 0.05f);
  EXPECT_EQ(s.container.max, ff::Vec3(0.2f, 0.2f, 0.2f));
  ASSERT_EQ(s.fluid.size(), 1u);
  EXPECT_EQ(s.fluid[0].dims[1], 10);
  ASSERT_TRUE(s.camera && s.camera->yaw_deg && s.camera->pitch_deg && s.camera->distance &&
              s.camera->fov_deg && s.camera->target);
  EXPECT_NEAR(*s.camera->yaw_deg, 30.0f, 1e-4);  // degrees -> radians -> degrees
  EXPECT_NEAR(*s.camera->pitch_deg, 20.0f, 1e-4);
  EXPECT_EQ(*s.camera->distance, 0.45f);
  EXPECT_EQ(*s.camera->fov_deg, 50.0f);
  EXPECT_EQ(*s.camera->target, ff::Vec3(0.1f, 0.05f, 0.1f));

  // `flowform run` on it starts from that target and region: as many control
  // particles at the first step as a scene written here by hand with them.
  std::ofstream(dir / "by_hand.json") << R"({"container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
    "fluid": [{"origin": [0.068, 0.0, 0.068], "dims": [10, 10, 10]}], "params": {"fluid": {"viscosity": 0.05}},
    "region": )" << kRegion << R"(, "target": )"
                                      << kTarget << "}";
  const long from_saved = controlCountOfRun(saved, dir / "saved.csv");
  const long by_hand = controlCountOfRun(dir / "by_hand.json", dir / "by_hand.csv");
  const long original = controlCountOfRun(dir / "small.json", dir / "small.csv");
  EXPECT_GT(from_saved, 0);
  EXPECT_EQ(from_saved, by_hand);
  EXPECT_NE(from_saved, original);  // all the fluid into a sphere: another count

  // `flowform view` reads it back into the same state: saved again at once,
  // the scene is the same (and the existing file was not replaced).
  const fs::path again = dir / "out" / "again.json";
  std::ofstream(dir / "resave.json") << R"({"actions": [{"at": 0, "save": ")" << again.string()
                                     << R"("}, {"at": 0, "quit": true}]})";
  const std::string before = readAll(saved);
  r = fftest::runUnderXvfb(dir, firstDisplay(3),
                           kExe + " view '" + saved.string() + "' --backend cpu --threads 2 --script '" +
                               (dir / "resave.json").string() + "' --width 400 --height 300");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(readAll(saved), before);
  const ff::SceneDesc t = ff::loadScene(again.string());
  ASSERT_EQ(t.schedule.size(), 1u);
  EXPECT_EQ(t.schedule[0].target.box_size, s.schedule[0].target.box_size);
  EXPECT_EQ(t.schedule[0].target.control_count, 400);
  EXPECT_EQ(t.region.min, s.region.min);
  EXPECT_EQ(t.region.max, s.region.max);
  EXPECT_EQ(t.params.fluid.viscosity, 0.05f);
  ASSERT_TRUE(t.camera && t.camera->yaw_deg && t.camera->distance && t.camera->target);
  EXPECT_NEAR(*t.camera->yaw_deg, *s.camera->yaw_deg, 1e-4);
  EXPECT_NEAR(*t.camera->pitch_deg, *s.camera->pitch_deg, 1e-4);
  EXPECT_EQ(*t.camera->distance, *s.camera->distance);
  EXPECT_EQ(*t.camera->target, *s.camera->target);

  // A script that saves over an existing file is stopped with a message naming
  // the action and the file; the file keeps what it held.
  std::ofstream(dir / "over.json") << R"({"actions": [{"at": 0, "save": ")" << saved.string()
                                   << R"("}, {"at": 0, "quit": true}]})";
  r = fftest::runUnderXvfb(dir, firstDisplay(3),
                           kExe + " view '" + (dir / "small.json").string() +
                               "' --backend cpu --threads 2 --script '" + (dir / "over.json").string() +
                               "' --width 400 --height 300");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("over.json: actions[0] (save): " + saved.string() +
                       ": a file of that name exists; not overwritten"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(readAll(saved), before);
}

}  // namespace
