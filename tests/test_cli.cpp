// The flowform program as a user runs it: exit codes, one-line reasons for
// bad input, the metrics CSV, the PLY export and the phase timings.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;

using Result = fftest::CliResult;

Result run(const std::string& args) {
  return fftest::runFlowform(args);
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

TEST(Cli, DefaultSceneRunsAndReportsPhaseTimes) {
  const fftest::TempDir d("cli_default");
  Result r = run("run --backend cpu --steps 3 --metrics '" + (d / "m.csv").string() + "' --export '" +
                 d.string() + "' --export-every 3 --format ply");
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* phase : {"grid", "density", "forces", "control_scale", "control_forces", "pressure",
                            "integrate", "shape_matching", "metrics", "total"})
    EXPECT_NE(r.out.find(phase), std::string::npos) << phase << "\n" << r.out;
  std::ifstream csv(d / "m.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("step,time,iou,coverage,max_speed,density_error", 0), 0u) << header;
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 3);
  EXPECT_TRUE(fs::exists(d / "fluid_00000.ply"));
  EXPECT_TRUE(fs::exists(d / "fluid_00001.ply"));
  EXPECT_TRUE(fs::exists(d / "control_00001.ply"));
}

TEST(Cli, MissingSceneFileIsAOneLineError) {
  Result r = run("run /nonexistent/scene.json --steps 1");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("flowform: error: /nonexistent/scene.json: cannot open scene file"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
}

TEST(Cli, BadSceneFieldNamesFileAndKey) {
  const fftest::TempDir d("cli_badscene");
  write(d / "bad.json",
        R"({"fluid": [{"origin": [0,0,0], "dims": [4,4,4]}], "params": {"fluid": {"viscosity": -1}}})");
  Result r = run("run '" + (d / "bad.json").string() + "' --steps 1");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("bad.json"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("params.fluid.viscosity"), std::string::npos) << r.out;
}

TEST(Cli, BrokenMeshNamesTheMeshFile) {
  const fftest::TempDir d("cli_badmesh");
  write(d / "broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
  write(d / "s.json", R"({"fluid": [{"origin": [0.1,0,0.1], "dims": [6,6,6]}], "target": "broken.obj"})");
  Result r = run("run '" + (d / "s.json").string() + "' --steps 1");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("broken.obj"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
}

TEST(Cli, UnwritableExportFolderIsAnError) {
  Result r = run("run --backend cpu --steps 1 --export /proc/flowform_cannot_write_here");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("/proc/flowform_cannot_write_here: cannot create export folder"), std::string::npos)
      << r.out;
}

TEST(Cli, BadOptionIsRejected) {
  Result r = run("run --steps -5 --seconds 2");
  EXPECT_EQ(r.code, 2) << r.out;  // a usage error
  EXPECT_NE(r.out.find("--steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Run with --help for more information."), std::string::npos) << r.out;
}

// A thread count OpenMP cannot create (100000 crashed its thread creation
// with a segfault) is refused before anything runs, by every command that
// takes --threads; a negative print interval is a usage error.
TEST(Cli, ThreadCountsAreBounded) {
  for (const char* cmd : {"run --backend cpu --steps 1", "render --frames 1 --out /proc/ff_no_frames",
                          "bench --table1 --backend cpu", "view"}) {
    Result r = run(std::string(cmd) + " --threads 100000");
    EXPECT_EQ(r.code, 1) << cmd << "\n" << r.out;
    EXPECT_NE(r.out.find("--threads: must be in [0, 1024] (got 100000"), std::string::npos) << cmd << "\n"
                                                                                            << r.out;
  }
  Result r = run("run --backend cpu --steps 1 --print-every -3");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--print-every"), std::string::npos) << r.out;
}

// FLOWFORM_CL_POISON=yes was read as off without a word; a value other
// than 1 or 0 is refused, naming the variable.
TEST(Cli, AnUnknownPoisonSettingIsRefused) {
  const fftest::CliResult r = fftest::runFlowform("run --backend opencl --steps 1", "FLOWFORM_CL_POISON=yes");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("FLOWFORM_CL_POISON: must be 1 (on) or 0 (off), got 'yes'"), std::string::npos)
      << r.out;
}

}  // namespace
