// Inputs that pass the JSON syntax but ask for unbounded memory or work, or
// that overflow: each must give exit code 1 and a one-line error naming the
// file and the key, quickly and under a memory cap (issue 14's list, and
// neighbours of each entry). A crash, a hang or std::bad_alloc fails them:
// the program runs under `timeout` and `ulimit -v`, and the exit code must be
// exactly 1 with the message.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli_run.h"
#include "core/error.h"
#include "core/param_table.h"
#include "core/params.h"
#include "core/resource_limits.h"
#include "host/cl_program.h"
#include "temp_dir.h"

namespace {

using fftest::CliResult;
using fftest::TempDir;

// `flowform ARGS` with at most 20 s and 2 GB of address space. Under
// AddressSanitizer (the sanitizer build, .ci/sanitizers) the address space
// cannot be capped, as ASan reserves terabytes of shadow memory at start:
// there only the time is, and the program plans with its default limit.
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kAddressSpaceCap = "";
#else
constexpr const char* kAddressSpaceCap = "ulimit -v 2000000; ";
#endif
CliResult runLimited(const std::string& args) {
  return fftest::runShell("(" + std::string(kAddressSpaceCap) + "FLOWFORM_MESH_PATH='" +
                          fftest::meshSearchPath() + "' timeout 20 '" + std::string(FF_FLOWFORM_EXE) + "' " +
                          args + ")");
}

const char* kBase =
    R"("container": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
       "fluid": [{"origin": [0.1, 0, 0.1], "dims": [10, 10, 10]}])";

std::string scene(const std::string& extra) {
  return std::string("{") + kBase + (extra.empty() ? "" : ", " + extra) + "}";
}

struct BadScene {
  const char* name;
  std::string json;
  std::vector<std::string> expected;  // substrings of the one-line error, after "FILE: "
};

void expectRefused(const TempDir& dir, const BadScene& c, const std::string& extra_args = "") {
  const std::string file = (dir / (std::string(c.name) + ".json")).string();
  dir.write(std::string(c.name) + ".json", c.json);
  const CliResult r = runLimited("run '" + file + "' --backend cpu --threads 1 --steps 2 " + extra_args);
  EXPECT_EQ(r.code, 1) << c.name << ": " << r.out;
  const std::string line = "flowform: error: " + file + ": ";
  EXPECT_NE(r.out.find(line), std::string::npos) << c.name << ": " << r.out;
  for (const std::string& e : c.expected)
    EXPECT_NE(r.out.find(e), std::string::npos) << c.name << ": " << r.out;
  EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
  // One line: the error is the last line and the only one after the header.
  const size_t at = r.out.find("flowform: error:");
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(r.out.find('\n', at), r.out.size() - 1) << c.name << ": " << r.out;
}

TEST(InputLimits, HugeFluidBlocksAreRefusedBeforeAllocating) {
  TempDir dir("limits_fluid");
  const std::string big = R"("container": {"min": [0, 0, 0], "max": [1000, 1000, 1000]}, )";
  for (const BadScene& c : std::vector<BadScene>{
           {"dims2000",
            "{" + big + R"("fluid": [{"origin": [0, 0, 0], "dims": [2000, 2000, 2000]}]})",
            {"fluid[0].dims", "8e+09 fluid particles"}},
           {"dimsmax",
            "{" + big +
                R"("fluid": [{"origin": [0, 0, 0], "dims": [2147483647, 2147483647, 1], "spacing": 1e-7}]})",
            {"fluid[0].dims", "fluid particles"}},
           // Under the 32-bit index limit, but over the memory limit (set to 4 GiB).
           {"dims300",
            "{" + big + R"("fluid": [{"origin": [0, 0, 0], "dims": [300, 300, 300]}]})",
            {"fluid[0].dims", "2.7e+07 fluid particles need about",
             "over the limit of 4 GiB (set by --max-memory)"}},
           // Overlapping particles: many times the rest density, junk after one step.
           {"spacing",
            "{" + big + R"("fluid": [{"origin": [0, 0, 0], "dims": [10, 10, 10], "spacing": 1e-9}]})",
            {"fluid[0].spacing", "must be in [0.5, 10] times the rest spacing"}},
           // A container whose squared lengths overflow a float.
           {"container1e30",
            R"({"container": {"min": [0, 0, 0], "max": [1e30, 1, 1]},
                "fluid": [{"origin": [0, 0, 0], "dims": [10, 10, 10]}]})",
            {"container.max[0]", "must lie within -1e6 .. 1e6 m (got 1e+30)"}},
           // Many small blocks add up: the block that crosses the limit is named.
           {"manyblocks",
            "{" + big + R"("fluid": [{"origin": [0, 0, 0], "dims": [200, 200, 200]},
                                                  {"origin": [0, 0, 0], "dims": [200, 200, 200]}]})",
            {"fluid[1].dims", "1.6e+07 fluid particles"}},
       })
    expectRefused(dir, c, "--max-memory 4G");
}

TEST(InputLimits, ControlParticleCountsAreBoundedByTheFluid) {
  TempDir dir("limits_control");
  for (const BadScene& c : std::vector<BadScene>{
           {"count1e8",
            scene(R"("target": {"shape": "sphere", "control_count": 100000000})"),
            {"target.control_count", "1e+08 control particles for 1000 controlled fluid particles"}},
           {"countmax",
            scene(R"("target": {"shape": "torus", "control_count": 2147483647})"),
            {"target.control_count", "control particles"}},
           {"voxel1e-4",
            scene(R"("target": {"shape": "sphere", "voxel_size": 1e-4})"),
            {"target.voxel_size", "control particles for 1000 controlled fluid particles"}},
           {"volume",
            scene(R"("target": {"shape": "sphere", "volume": 1000})"),
            {"target.volume", "control particles"}},
           // Too small for the fluid's voxel: the volume is the key to change.
           {"tinyvolume",
            scene(R"("target": {"shape": "sphere", "volume": 1e-12})"),
            {"target.volume: only ", "voxel(s) inside"}},
           {"schedule",
            scene(R"("schedule": [{"time": 0, "target": "sphere"},
                                             {"time": 0.001, "target": {"shape": "box", "control_count": 5}}])"),
            {"schedule[1].target.control_count", "must be at least 8 (got 5)"}},
           {"torus3",
            scene(R"("target": {"shape": "torus", "control_count": 3})"),
            {"target.control_count", "must be at least 8 (got 3)"}},
       })
    expectRefused(dir, c);
}

TEST(InputLimits, DegenerateTargetsAreRefusedBeforeVoxelising) {
  TempDir dir("limits_degenerate");
  for (const BadScene& c : std::vector<BadScene>{
           {"flatbox",
            scene(R"("target": {"shape": "box", "size": [2, 1, 1e-7]})"),
            {"target.size", "is 2e+07 times longer than thick; at most 4096"}},
           {"flatbox_count",
            scene(R"("target": {"shape": "box", "size": [1, 1e-5, 1], "control_count": 500})"),
            {"target.size", "times longer than thick"}},
           {"needle",
            scene(R"("target": {"shape": "capsule", "radius": 1e-6, "length": 10})"),
            {"target.radius", "times longer than thick"}},
           {"thinring",
            scene(R"("target": {"shape": "torus", "major": 1, "minor": 1e-6})"),
            {"target.minor", "times longer than thick"}},
       })
    expectRefused(dir, c);
}

TEST(InputLimits, ShapeMatchingSettingsAreBounded) {
  TempDir dir("limits_shape");
  auto sm = [](const std::string& key, const std::string& v) {
    return scene(R"("params": {"shape_matching": {")" + key + R"(": )" + v + R"(}}, "target": "sphere")");
  };
  for (const BadScene& c : std::vector<BadScene>{
           {"hw2e6",
            sm("cluster_half_width", "2000000"),
            {"params.shape_matching.cluster_half_width", "must be in [1, 64] (got 2000000)"}},
           {"hwmax",
            sm("cluster_half_width", "2147483647"),
            {"params.shape_matching.cluster_half_width", "(got 2147483647)"}},
           {"hw1000", sm("cluster_half_width", "1000"), {"params.shape_matching.cluster_half_width"}},
           {"hw64",
            sm("cluster_half_width", "64"),
            {"params.shape_matching.cluster_half_width", "clusters; at most 4096"}},
           {"stridemax", sm("cluster_stride", "2147483647"), {"params.shape_matching.cluster_stride"}},
           {"rotmax",
            sm("rotation_iterations", "2147483647"),
            {"params.shape_matching.rotation_iterations", "must be in [1, 100]"}},
           {"smdt", sm("time_step", "5e-9"), {"params.shape_matching.time_step", "must be in [1e-06, 1]"}},
           {"smdt_ratio",
            sm("time_step", "2e-6"),
            {"params.shape_matching.time_step", "2000 shape-matching steps per fluid step"}},
           {"substeps",
            scene(R"("params": {"fluid": {"max_substeps": 100000}})"),
            {"params.fluid.max_substeps", "must be in [1, 1000]"}},
           {"fluiddt", scene(R"("params": {"fluid": {"time_step": 1e-9}})"), {"params.fluid.time_step"}},
       })
    expectRefused(dir, c);
}

TEST(InputLimits, RunLengthsAreFiniteAndBounded) {
  TempDir dir("limits_duration");
  expectRefused(dir, {"duration", scene(R"("duration": 1e30)"), {"duration: 1e+30 s is 2.5e+32 steps"}}, "");
  const std::string file = dir.write("ok.json", scene("")).string();
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"--seconds 1e17", "--seconds: 1e+17 s is 2.5e+19 steps of 0.004 s, over the limit"},
           {"--seconds nan", "--seconds: must be a finite number of seconds > 0 (got nan)"},
           {"--seconds inf", "--seconds: must be a finite number of seconds > 0 (got inf)"},
           {"--seconds -1", "--seconds: must be a finite number of seconds > 0 (got -1)"},
           {"--steps 0", "--steps: must be in [1, 100000000] (got 0)"},
           {"--steps 1000000000", "--steps: must be in [1, 100000000]"},
       }) {
    const CliResult r = runLimited("run '" + file + "' --backend cpu " + args);
    EXPECT_EQ(r.code, 1) << args << ": " << r.out;
    EXPECT_NE(r.out.find("flowform: error: " + message), std::string::npos) << args << ": " << r.out;
  }
}

TEST(InputLimits, FilesThatAreNotScenesOrMeshes) {
  TempDir dir("limits_files");
  CliResult r = runLimited("run /dev/zero");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("flowform: error: /dev/zero: the scene file is larger than 16 MiB"), std::string::npos)
      << r.out;
  // A folder named like a mesh.
  std::filesystem::create_directories(dir / "folder.obj");
  expectRefused(
      dir, {"foldermesh", scene(R"("target": "folder.obj")"), {"folder.obj: is a folder, not a mesh file"}});
  // --max-memory must be a size.
  r = runLimited("--max-memory lots run");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("flowform: error: --max-memory: must be a positive size like 4G"), std::string::npos)
      << r.out;
}

// An open box (its top missing) is used, with a warning naming the file.
TEST(InputLimits, OpenMeshIsAcceptedWithAWarning) {
  TempDir dir("limits_open");
  dir.write("open.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
            "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 4 1 5\nf 4 5 8\n");
  const std::string file = dir.write("s.json", scene(R"("target": "open.obj")")).string();
  const CliResult r = runLimited("run '" + file + "' --backend cpu --threads 1 --steps 1");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("flowform: warning: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("open.obj: the mesh is not watertight (4 edges"), std::string::npos) << r.out;
}

// Every parameter of the table has a finite range that its default lies in,
// and validateParams refuses a value just outside it, naming the key.
TEST(ParamTable, EveryRangeHoldsItsDefaultAndIsEnforced) {
  for (const ff::ParamInfo& info : ff::paramTable()) {
    SCOPED_TRACE(info.name());
    if (info.type == ff::ParamInfo::Type::Units || info.type == ff::ParamInfo::Type::Solver) continue;
    EXPECT_TRUE(std::isfinite(info.min) && std::isfinite(info.max) && info.min < info.max);
    EXPECT_NE(std::string(info.doc), "");
    ff::Params p;
    void* f = info.field(p);
    const double def =
        info.type == ff::ParamInfo::Type::Integer ? *static_cast<int*>(f) : *static_cast<float*>(f);
    EXPECT_TRUE(info.inRange(def)) << def;
    EXPECT_NO_THROW(ff::validateParams(p, "F"));
    const double above = info.max * 2 + 1;
    if (info.type == ff::ParamInfo::Type::Integer)
      *static_cast<int*>(f) = int(above);
    else
      static_cast<float*>(f)[0] = float(above);
    try {
      ff::validateParams(p, "F");
      ADD_FAILURE() << "accepted " << above;
    } catch (const ff::Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("F: " + info.name(), 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(info.rangeText()), std::string::npos) << e.what();
    }
  }
}

// A run of T seconds takes the fewest steps that reach T (flowform run
// --seconds, a scene's duration, Python's run(seconds=)). The step is a
// float: 0.005f is 0.004999999888, so 4 steps end at 0.0199999996 s, which
// has reached 0.02 s (before, 5 steps ran, and 601 for 3 s).
TEST(ResourceLimits, RunStepsAreTheFewestThatReachTheTime) {
  EXPECT_EQ(ff::runSteps(0.02, double(0.005f), "t"), 4);
  EXPECT_EQ(ff::runSteps(3.0, double(0.005f), "t"), 600);
  EXPECT_EQ(ff::runSteps(0.04, double(0.004f), "t"), 10);  // 0.004f is above 0.004
  EXPECT_EQ(ff::runSteps(0.021, double(0.005f), "t"), 5);  // between two steps: the one after
  EXPECT_EQ(ff::runSteps(0.001, double(0.004f), "t"), 1);
  EXPECT_EQ(ff::runSteps(4.0, 0.004, "t"), 1000);
}

TEST(ResourceLimits, ByteSizesParseAndTheLimitNamesItsOrigin) {
  EXPECT_DOUBLE_EQ(ff::parseByteSize("4G", "x"), 4.0 * 1024 * 1024 * 1024);
  EXPECT_DOUBLE_EQ(ff::parseByteSize("512MiB", "x"), 512.0 * 1024 * 1024);
  EXPECT_DOUBLE_EQ(ff::parseByteSize("1000", "x"), 1000.0);
  EXPECT_THROW(ff::parseByteSize("-1G", "x"), ff::Error);
  EXPECT_THROW(ff::parseByteSize("4Q", "x"), ff::Error);
  const ff::ResourceLimits machine = ff::machineMemoryLimit();
  EXPECT_GT(machine.memory_bytes, 0.0);
  try {
    ff::checkMemory(1e30, "F", "K", "everything");
    ADD_FAILURE();
  } catch (const ff::Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("F: K: everything need about ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("--max-memory"), std::string::npos) << e.what();
  }
}

// A long kernel build log is cut to its first errors; the whole log is in the
// file the message names.
TEST(KernelBuildLog, LongLogsAreCutAndKeptInAFile) {
  std::string log;
  for (int i = 0; i < 5000; ++i)
    log += "<source>:" + std::to_string(i) + ":1: " + (i % 2 ? "warning: unused" : "error: bad thing") +
           " number " + std::to_string(i) + "\n  some code\n";
  const std::string text = ff::shortBuildLog(log);
  EXPECT_LT(text.size(), 2600u);
  EXPECT_NE(text.find("error: bad thing number 0"), std::string::npos) << text;
  const size_t at = text.find("is in ");
  ASSERT_NE(at, std::string::npos) << text;
  const std::string path = text.substr(at + 6, text.find(')', at) - at - 6);
  std::ifstream in(path, std::ios::binary);
  const std::string saved((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(saved, log);
  std::filesystem::remove(path);
  // A short log is given whole.
  EXPECT_EQ(ff::shortBuildLog("a: error: x"), "build log:\na: error: x");
}

}  // namespace
