// test_recording.cpp - recording frames from the viewer (viewer/recording.h,
// no window needed) and from `flowform render --export`: the same exporter,
// the frames at the asked rate, every take in a folder of its own.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "core/error.h"
#include "host/backend_factory.h"
#include "sim/simulation.h"
#include "test_scenes.h"
#include "viewer/recording.h"

namespace fs = std::filesystem;

namespace {

// The timestep values of a .pvd collection, read with a regex (not the writer).
std::vector<double> pvdTimes(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::vector<double> out;
  const std::regex ds("<DataSet timestep=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), ds); it != std::sregex_iterator(); ++it)
    out.push_back(std::stod((*it)[1].str()));
  return out;
}

ff::SceneDesc smallScene() {
  ff::SceneDesc s =
      fftest::blockScene(ff::Vec3(0.1f, 0.1f, 0.1f), ff::Vec3(0.03f, 0.0f, 0.03f), 5, 5, 5, "small.json");
  s.name = "small";
  return s;
}

TEST(ViewerRecording, TakesInFoldersOfTheirOwnAtTheFrameRate) {
  const fftest::TempDir d("recording");
  fs::create_directories(d / "take_003");  // the user's folder of that name: skipped, kept
  std::ofstream(d / "take_003" / "mine.txt") << "x";
  ff::Simulation sim(smallScene(), ff::makeBackend("cpu", -1, 2, nullptr));
  ff::viewer::Recording rec;
  ff::ExportOptions o;
  o.dir = d.string();
  o.fps = 50.0;  // a frame every 20 ms: every 5 steps of 4 ms
  o.formats = {ff::ExportFormat::Vtk, ff::ExportFormat::Ply};
  rec.configure(o);
  EXPECT_FALSE(rec.active());
  EXPECT_EQ(rec.stop(), "");
  std::vector<std::string> takes;
  for (int take = 0; take < 3; ++take) {
    takes.push_back(rec.start(sim));
    EXPECT_TRUE(rec.active());
    EXPECT_EQ(rec.frames(), 1);  // the state when recording starts
    for (int s = 0; s < 10; ++s) {
      sim.step();
      rec.afterStep(sim);
    }
    EXPECT_EQ(rec.frames(), 3);
    EXPECT_NE(rec.stop().find("3 frames"), std::string::npos);
    EXPECT_FALSE(rec.active());
  }
  EXPECT_EQ(takes, (std::vector<std::string>{(d / "take_001").string(), (d / "take_002").string(),
                                             (d / "take_004").string()}));
  EXPECT_TRUE(fs::exists(d / "take_003" / "mine.txt"));
  // The second take starts where the first stopped: 10 steps of 4 ms later.
  const std::vector<double> t = pvdTimes(d / "take_002" / "fluid.pvd");
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t[0], 0.040, 1e-6);
  EXPECT_NEAR(t[1], 0.060, 1e-6);
  EXPECT_NEAR(t[2], 0.080, 1e-6);
  EXPECT_TRUE(fs::exists(d / "take_002" / "fluid_00002.ply"));
  EXPECT_FALSE(fs::exists(d / "take_002" / "fluid_00003.ply"));
}

TEST(ViewerRecording, AnUnwritableFolderIsReportedAndNothingRecords) {
  ff::Simulation sim(smallScene(), ff::makeBackend("cpu", -1, 2, nullptr));
  ff::viewer::Recording rec;
  ff::ExportOptions o;
  o.dir = "/proc/flowform_cannot_record_here";
  rec.configure(o);
  try {
    rec.start(sim);
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find(o.dir), std::string::npos) << e.what();
  }
  EXPECT_FALSE(rec.active());
}

TEST(RenderCli, ExportsEveryRenderedFrame) {
  const fftest::TempDir d("render_export");
  std::ofstream(d / "s.json") << R"({"name": "tiny", "container": {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]},
    "fluid": [{"origin": [0.03, 0.0, 0.03], "dims": [6, 6, 6]}]})";
  const fftest::CliResult r = fftest::runFlowform(
      "render '" + (d / "s.json").string() +
          "' --frames 3 --every 2 --width 64 --height 64 --backend cpu --out '" + (d / "png").string() +
          "' --export '" + (d / "exp").string() + "' --format vtk,bgeo",
      "OMP_NUM_THREADS=2");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("exported 3 frames"), std::string::npos) << r.out;
  const std::vector<double> t = pvdTimes(d / "exp" / "fluid.pvd");
  ASSERT_EQ(t.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(t[size_t(k)], 0.008 * k, 1e-6);
  EXPECT_TRUE(fs::exists(d / "exp" / "fluid_00002.bgeo"));
  EXPECT_TRUE(fs::exists(d / "png" / "frame_00002.png"));
}

}  // namespace
