// `flowform view` end to end: under xvfb-run a script changes the target,
// hides the panel, saves a screenshot and quits with status 0; without a
// display, and with a bad script, the viewer exits 1 with a clear message.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "cli_run.h"
#include "test_scenes.h"
#include "xvfb_run.h"

namespace {

namespace fs = std::filesystem;

using Result = fftest::CliResult;

Result shell(const std::string& cmd) {
  return fftest::runShell(cmd);
}

// 1000 particles in a 0.2 m box, a sphere target from the start.
void writeSmallScene(const fs::path& file) {
  std::ofstream(file) << fftest::blockSceneJson("small", 0.2, 0.068, 0.068, 10, R"("target": "sphere")");
}

const std::string kExe = std::string("'") + FF_FLOWFORM_EXE + "'";

// The first display number xvfb-run tries for a test: starting each test (and
// process) elsewhere keeps tests run in parallel from racing for the same one.
int firstDisplay(int test) {
  return 200 + int(::getpid() % 400) * 4 + test;
}

TEST(ViewerXvfb, ScriptChangesTheTargetSavesAScreenshotAndQuits) {
  if (!fftest::haveXvfb())
    FAIL() << "this test runs `flowform view` under xvfb-run: install xvfb and xauth "
              "(Debian/Ubuntu: apt-get install xvfb xauth)";
  const fftest::TempDir dir("view_xvfb");
  writeSmallScene(dir / "small.json");
  const fs::path shot = dir / "shots" / "view.png";  // the folder does not exist yet
  std::ofstream(dir / "script.json") << R"({"actions": [
    {"at": 0, "camera": {"yaw": 30, "pitch": 30, "distance": 0.45, "target": [0.1, 0.05, 0.1]}},
    {"at": 0.04, "target": {"shape": "box", "size": [2, 1, 1]}},
    {"at": 0.1, "panel": false},
    {"at": 0.1, "screenshot": ")" + shot.string() +
                                            R"("},
    {"at": 0.1, "quit": true}
  ]})";
  const Result r = fftest::runUnderXvfb(dir, firstDisplay(0),
                                        kExe + " view '" + (dir / "small.json").string() +
                                            "' --backend cpu --threads 2 --script '" +
                                            (dir / "script.json").string() + "' --width 640 --height 480");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("script t=0.040 s: target"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("script t=0.100 s: quit"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(shot)) << r.out;

  int w = 0, h = 0, channels = 0;
  unsigned char* px = stbi_load(shot.string().c_str(), &w, &h, &channels, 3);
  ASSERT_NE(px, nullptr) << stbi_failure_reason();
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  std::set<unsigned> colours;
  long fluid = 0;
  for (long i = 0; i < long(w) * h; ++i) {
    const int r8 = px[3 * i], g8 = px[3 * i + 1], b8 = px[3 * i + 2];
    colours.insert(unsigned(r8) << 16 | unsigned(g8) << 8 | unsigned(b8));
    // The liquid is tinted blue (0.10, 0.45, 0.85); floor, walls and sky are
    // grey or pale blue, and the panel is hidden.
    if (b8 > r8 + 80 && b8 > g8 + 30) ++fluid;
  }
  stbi_image_free(px);
  EXPECT_GT(colours.size(), 50u) << "the screenshot is (nearly) uniform";
  EXPECT_GT(fluid, 500) << "no fluid-coloured pixels in the screenshot";
  EXPECT_LT(fluid, long(w) * h / 2) << "blue everywhere: not a picture of the scene";
}

TEST(ViewerXvfb, AScriptActionThatFailsWhileRunningEndsTheViewerWithStatus1) {
  if (!fftest::haveXvfb())
    FAIL() << "this test runs `flowform view` under xvfb-run: install xvfb and xauth "
              "(Debian/Ubuntu: apt-get install xvfb xauth)";
  const fftest::TempDir dir("view_xvfb_fail");
  writeSmallScene(dir / "small.json");
  // The region is valid syntax but holds no fluid (above the resting block).
  std::ofstream(dir / "late.json") << R"({"actions": [
    {"at": 0.008, "region": {"box": {"min": [0.0, 0.15, 0.0], "max": [0.05, 0.2, 0.05]}}},
    {"at": 0.02, "quit": true}
  ]})";
  const Result r = fftest::runUnderXvfb(dir, firstDisplay(2),
                                        kExe + " view '" + (dir / "small.json").string() +
                                            "' --backend cpu --threads 2 --script '" +
                                            (dir / "late.json").string() + "' --width 400 --height 300");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("late.json: actions[0] (region): "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("holds no fluid"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("script t=0.020 s: quit"), std::string::npos) << r.out;
}

TEST(ViewerCli, WithoutADisplayTheViewerSaysSoAndExits1) {
  const fftest::TempDir dir("view_nodisplay");
  writeSmallScene(dir / "small.json");
  const Result r = shell("env -u DISPLAY -u WAYLAND_DISPLAY " + kExe + " view '" +
                         (dir / "small.json").string() + "' --backend cpu --threads 2");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("flowform view needs a display (X11)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("flowform render"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("xvfb-run"), std::string::npos) << r.out;
}

TEST(ViewerCli, ABadScriptIsRejectedBeforeAnyWindowOpens) {
  const fftest::TempDir dir("view_badscript");
  writeSmallScene(dir / "small.json");
  std::ofstream(dir / "demo.json") << R"({"actions": [{"at": 0.5, "target": {"shape": "cube"}}]})";
  // No display either: the script is read first, so its error is the one reported.
  Result r = shell("cd '" + dir.string() + "' && env -u DISPLAY " + kExe +
                   " view small.json --backend cpu --script demo.json");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("demo.json: actions[0].target.shape: must be one of"), std::string::npos) << r.out;

  r = shell("cd '" + dir.string() + "' && env -u DISPLAY " + kExe + " view small.json --script missing.json");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("missing.json: cannot open script file"), std::string::npos) << r.out;

  r = shell(kExe + " view '" + (dir / "small.json").string() + "' --width 10");
  EXPECT_EQ(r.code, 2) << r.out;  // a usage error
  EXPECT_NE(r.out.find("--width"), std::string::npos) << r.out;
}

}  // namespace
