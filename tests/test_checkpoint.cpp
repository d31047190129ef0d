// Checkpoints: a resumed run is bit-identical to one never interrupted (CPU
// backend); SIGINT leaves a loadable checkpoint and complete output files; a
// corrupted checkpoint or one of another version is a clear error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "core/error.h"
#include "core/fluid_state.h"
#include "cpu/backend_cpu.h"
#include "metrics/fluid_shares.h"
#include "scene/scene.h"
#include "sim/checkpoint.h"

namespace {

namespace fs = std::filesystem;

// 1000 particles, a sphere, then a box at 1.5 s: a resume at 1 s has to carry
// the schedule position and the current target over.
const char* kScene = R"({
  "name": "ckpt",
  "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
  "fluid": [{"origin": [0.06, 0.0, 0.06], "dims": [10, 10, 10]}],
  "schedule": [{"time": 0.0, "target": "sphere"}, {"time": 1.5, "target": "box"}]
})";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(Checkpoint, ResumeGivesByteIdenticalExports) {
  const fftest::TempDir d("ckpt_resume");
  spit(d / "s.json", kScene);
  const std::string scene = "'" + (d / "s.json").string() + "' --backend cpu";
  // 1 s with a checkpoint at its end.
  fftest::CliResult a = fftest::runFlowform(
      "run " + scene + " --seconds 1 --checkpoint-every 1 --checkpoint '" + (d / "ck").string() + "'");
  ASSERT_EQ(a.code, 0) << a.out;
  const fs::path ck = d / "ck" / "checkpoint_000250.ffck";
  ASSERT_TRUE(fs::exists(ck)) << a.out;
  // Straight to 2 s, and the checkpoint resumed to 2 s.
  fftest::CliResult b = fftest::runFlowform("run " + scene + " --seconds 2 --format ply --export '" +
                                            (d / "straight").string() + "' --export-every 250 --metrics '" +
                                            (d / "straight.csv").string() + "'");
  ASSERT_EQ(b.code, 0) << b.out;
  fftest::CliResult c = fftest::runFlowform(
      "run --backend cpu --resume '" + ck.string() + "' --seconds 2 --format ply --export '" +
      (d / "resumed").string() + "' --export-every 250 --metrics '" + (d / "resumed.csv").string() + "'");
  ASSERT_EQ(c.code, 0) << c.out;
  EXPECT_NE(c.out.find("resuming"), std::string::npos) << c.out;
  // Step 500 (t = 2 s) is the straight run's frame 2 (frames at steps 0, 250,
  // 500) and the resumed run's frame 1 (its export starts at step 250). The box
  // target took over at 1.5 s.
  for (const char* f : {"fluid", "control"}) {
    const std::string s = slurp(d / "straight" / (std::string(f) + "_00002.ply"));
    const std::string r = slurp(d / "resumed" / (std::string(f) + "_00001.ply"));
    ASSERT_GT(s.size(), 1000u) << f;
    EXPECT_TRUE(s == r) << f << " differs after resuming";
  }
  // The resumed run's first frame is the checkpoint's state: the straight run's frame 1.
  EXPECT_TRUE(slurp(d / "straight" / "fluid_00001.ply") == slurp(d / "resumed" / "fluid_00000.ply"));
  // The resumed metrics are the straight run's rows 251..500, bit for bit.
  const auto s = lines(slurp(d / "straight.csv")), r = lines(slurp(d / "resumed.csv"));
  ASSERT_EQ(s.size(), 501u);
  ASSERT_EQ(r.size(), 251u);
  EXPECT_EQ(s[0], r[0]);
  for (size_t i = 1; i < r.size(); ++i) ASSERT_EQ(s[250 + i], r[i]) << "row " << i;
}

TEST(Checkpoint, SigintLeavesALoadableCheckpointAndCompleteFiles) {
  const fftest::TempDir d("ckpt_sigint");
  spit(d / "s.json", kScene);
  const std::string csv = (d / "m.csv").string();
  // Start a long run, wait until it has written a few metrics rows, interrupt it.
  const std::string script = "'" + std::string(FF_FLOWFORM_EXE) + "' run '" + (d / "s.json").string() +
                             "' --backend cpu --seconds 1000 --metrics '" + csv + "' --checkpoint '" +
                             (d / "ck").string() + "' > '" + (d / "log").string() +
                             "' 2>&1 & p=$!; i=0; "
                             "while [ \"$(wc -l < '" +
                             csv +
                             "' 2>/dev/null || echo 0)\" -lt 20 ] && [ $i -lt 1200 ]; "
                             "do sleep 0.05; i=$((i+1)); done; kill -INT $p; wait $p; echo rc=$?";
  fftest::CliResult r = fftest::runShell(script);
  const std::string log = slurp(d / "log");
  EXPECT_NE(r.out.find("rc=130"), std::string::npos) << r.out << log;  // 128 + SIGINT
  EXPECT_NE(log.find("stopped by SIGINT"), std::string::npos) << log;
  // It names the checkpoint, and the named file resumes.
  const size_t at = log.find("checkpoint " + (d / "ck").string() + "/checkpoint_");
  ASSERT_NE(at, std::string::npos) << log;
  const std::string path = log.substr(at + 11, log.find('\n', at) - at - 11);
  ASSERT_TRUE(fs::exists(path)) << path;
  EXPECT_FALSE(fs::exists(path + ".part"));
  // Every metrics row is complete: as many values as the header and a line end.
  const std::string text = slurp(csv);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const auto rows = lines(text);
  ASSERT_GE(rows.size(), 20u);
  const auto commas = std::count(rows.front().begin(), rows.front().end(), ',');
  EXPECT_GE(commas, 9) << rows.front();  // at least the columns of docs/METRICS.md's first ten
  for (const std::string& row : rows) EXPECT_EQ(std::count(row.begin(), row.end(), ','), commas) << row;
  // The checkpoint is at the last row's step.
  const long step = std::stol(rows.back().substr(0, rows.back().find(',')));
  EXPECT_NE(
      path.find("checkpoint_" + std::string(6 - std::to_string(step).size(), '0') + std::to_string(step)),
      std::string::npos)
      << path << " vs " << rows.back();
  fftest::CliResult resumed =
      fftest::runFlowform("run --backend cpu --resume '" + path + "' --steps " + std::to_string(step + 2));
  EXPECT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_NE(resumed.out.find("2 steps"), std::string::npos) << resumed.out;
}

class CheckpointFile : public ::testing::Test {
 protected:
  void SetUp() override {
    Simulation sim(ff::parseScene(kScene, "ckpt.json", ""), std::make_unique<ff::CpuBackend>(2));
    for (int i = 0; i < 3; ++i) sim.step();
    good = (dir / "good.ffck").string();
    ff::writeCheckpoint(good, sim);
    bytes = slurp(good);
  }
  using Simulation = ff::Simulation;
  // The message of loading `text` as a checkpoint file ("" if it loads).
  std::string loadError(const std::string& text) {
    const std::string p = (dir / "bad.ffck").string();
    spit(p, text);
    try {
      ff::loadCheckpoint(p, std::make_unique<ff::CpuBackend>(2));
    } catch (const ff::Error& e) {
      return e.what();
    }
    return "";
  }
  const fftest::TempDir dir{"ckpt_file"};
  std::string good, bytes;
};

TEST_F(CheckpointFile, RoundTripRestoresStepTimeAndParticles) {
  auto sim = ff::loadCheckpoint(good, std::make_unique<ff::CpuBackend>(2));
  EXPECT_EQ(sim->stepCount(), 3);
  EXPECT_DOUBLE_EQ(sim->time(), 3.0 * double(0.004f));
  ff::FluidState f;
  sim->backend().readFluid(f);
  EXPECT_EQ(f.size(), 1000u);
  ASSERT_NE(sim->target(), nullptr);
  EXPECT_EQ(sim->target()->label, "sphere");
  EXPECT_EQ(sim->scene().name, "ckpt");
}

TEST_F(CheckpointFile, CorruptedByteIsAChecksumError) {
  std::string b = bytes;
  b[b.size() / 2] ^= 0x10;
  const std::string e = loadError(b);
  EXPECT_NE(e.find("bad.ffck"), std::string::npos) << e;
  EXPECT_NE(e.find("checksum does not match"), std::string::npos) << e;
}

TEST_F(CheckpointFile, AnotherVersionIsNamed) {
  std::string b = bytes;
  const uint32_t v = ff::kCheckpointVersion + 1;
  std::memcpy(&b[8], &v, 4);  // the version follows the 8-byte magic
  const std::string e = loadError(b);
  EXPECT_NE(e.find("another version of flowform"), std::string::npos) << e;
  EXPECT_NE(e.find("format " + std::to_string(v)), std::string::npos) << e;
}

// The FNV-1a 64 checksum of the checkpoint's payload (checkpoint.h), from
// FNV's published offset basis and prime, written out here: a test that
// edits the payload seals it again.
uint64_t fnv1a64(const std::string& b, size_t from) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = from; i < b.size(); ++i) h = (h ^ uint8_t(b[i])) * 0x100000001b3ull;
  return h;
}

// A lead of the substeps that is not a finite time >= 0, in a file whose
// checksum matches (edited on purpose), is named, not resumed from.
TEST_F(CheckpointFile, ABadLeadOfTheSubstepsIsNamed) {
  constexpr size_t kHeader = 32;  // magic 8, version 4, layout 4, size 8, checksum 8
  const size_t simu = bytes.find("SIMU", kHeader);
  ASSERT_NE(simu, std::string::npos);
  const size_t at = simu + 4 + sizeof(long) + sizeof(double);  // after the tag, step_ and time_
  ASSERT_LE(at + sizeof(double), bytes.size());
  double lead = 0.0;
  std::memcpy(&lead, &bytes[at], sizeof lead);
  EXPECT_EQ(lead, 0.0) << "the sphere scene's first steps take whole substeps";
  for (const double bad : {-1e-3, std::nan("")}) {
    std::string b = bytes;
    std::memcpy(&b[at], &bad, sizeof bad);
    const uint64_t sum = fnv1a64(b, kHeader);
    std::memcpy(&b[24], &sum, sizeof sum);
    const std::string e = loadError(b);
    EXPECT_NE(e.find("bad.ffck"), std::string::npos) << e;
    EXPECT_NE(e.find("its substeps' lead is not a finite time >= 0"), std::string::npos) << e;
  }
}

TEST_F(CheckpointFile, TruncatedAndForeignFilesAreRefused) {
  std::string e = loadError(bytes.substr(0, bytes.size() - 100));
  EXPECT_NE(e.find("truncated or corrupted"), std::string::npos) << e;
  e = loadError("{\"name\": \"a scene, not a checkpoint\"}");
  EXPECT_NE(e.find("not a flowform checkpoint"), std::string::npos) << e;
  e = loadError("");
  EXPECT_NE(e.find("not a flowform checkpoint"), std::string::npos) << e;
}

// A folder given as the checkpoint's file name (".", a folder, "out/") is
// named as such, for writing and for loading, and nothing is left behind
// (before, "." said "Device or resource busy" and left "..part" in the
// working folder; a folder said "Is a directory" or "not a flowform checkpoint").
TEST_F(CheckpointFile, AFolderGivenAsTheFileIsNamed) {
  Simulation sim(ff::parseScene(kScene, "ckpt.json", ""), std::make_unique<ff::CpuBackend>(2));
  const std::string folder = dir.path().string();
  for (const std::string& path : {std::string("."), folder, folder + "/", folder + "/new/"}) {
    try {
      ff::writeCheckpoint(path, sim);
      ADD_FAILURE() << path << ": written";
    } catch (const ff::Error& e) {
      EXPECT_EQ(std::string(e.what()), path +
                                           ": cannot write the checkpoint: this is a folder; give a file "
                                           "name (e.g. run.ffck)");
    }
  }
  EXPECT_FALSE(std::filesystem::exists("..part"));
  EXPECT_FALSE(std::filesystem::exists(folder + ".part"));
  try {
    ff::loadCheckpoint(folder, std::make_unique<ff::CpuBackend>(2));
    ADD_FAILURE() << "loaded";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find(folder + ": cannot open the checkpoint: this is a folder"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(CheckpointFile, CliNamesTheBadCheckpoint) {
  std::string b = bytes;
  b[b.size() - 1] ^= 0x01;
  spit(dir / "bad.ffck", b);
  fftest::CliResult r =
      fftest::runFlowform("run --backend cpu --resume '" + (dir / "bad.ffck").string() + "'");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("bad.ffck: the checkpoint is corrupted"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
}

// A small water dam break (DFSPH), its checkpoint written after `k` frame
// steps and resumed to `steps`: how many particles differ (position or
// velocity, bit for bit, by identity) from the run that went on, and
// whether the fluid's clocks agree at the end.
struct WaterResume {
  size_t differ = 0;
  bool same_clock = false;
};
constexpr char kWaterScene[] = R"({
    "name": "ckpt-water", "preset": "water",
    "container": {"min": [0, 0, 0], "max": [0.25, 0.15, 0.06]},
    "fluid": [{"origin": [0, 0, 0], "dims": [10, 16, 8]}]
  })";
std::unique_ptr<ff::Simulation> freshWater() {
  return std::make_unique<ff::Simulation>(ff::parseScene(kWaterScene, "ckpt-water.json", ""),
                                          std::make_unique<ff::CpuBackend>(2));
}
WaterResume resumeWater(ff::Simulation& straight, int k, int steps) {
  auto first = freshWater();
  for (int i = 0; i < k; ++i) first->step();
  const fftest::TempDir d("ckpt_water");
  const std::string path = (d / "water.ffck").string();
  ff::writeCheckpoint(path, *first);
  auto resumed = ff::loadCheckpoint(path, std::make_unique<ff::CpuBackend>(2));
  for (int i = k; i < steps; ++i) resumed->step();
  EXPECT_EQ(resumed->stepCount(), straight.stepCount());
  ff::FluidState a, b;
  straight.backend().readFluid(a);
  resumed->backend().readFluid(b);
  EXPECT_EQ(a.size(), b.size());
  EXPECT_GT(a.size(), 0u);
  WaterResume r;
  r.same_clock = resumed->time() == straight.time();
  if (a.size() != b.size()) return r;
  std::vector<size_t> at(a.size());
  for (size_t i = 0; i < b.size(); ++i) at[b.id[i]] = i;
  for (size_t i = 0; i < a.size(); ++i) {
    const size_t j = at[a.id[i]];
    const float va[6] = {a.x[i], a.y[i], a.z[i], a.vx[i], a.vy[i], a.vz[i]};
    const float vb[6] = {b.x[j], b.y[j], b.z[j], b.vx[j], b.vy[j], b.vz[j]};
    r.differ += std::memcmp(va, vb, sizeof va) != 0;
  }
  return r;
}

// Resumed at the step where its substep count changes: the solver's warm
// start scales k by the change of the substep, so a checkpoint that forgot
// the last substep would resume with another start.
TEST(Checkpoint, WaterResumeIsBitIdenticalWhereTheSubstepChanges) {
  constexpr int kSteps = 60;
  auto straight = freshWater();
  std::vector<int> substeps;
  for (int i = 0; i < kSteps; ++i) {
    straight->step();
    substeps.push_back(straight->metrics().substeps);
  }
  int k = 1;
  while (k < kSteps - 5 && substeps[size_t(k)] == substeps[size_t(k) - 1]) ++k;
  ASSERT_LT(k, kSteps - 5) << "the substep count never changed; the test needs a step where it does";
  // Stop after step k - 1 (k steps), so the resumed run's first step has a new substep.
  const WaterResume r = resumeWater(*straight, k, kSteps);
  EXPECT_EQ(r.differ, 0u) << "resumed before step " << k << " (" << substeps[size_t(k) - 1] << " -> "
                          << substeps[size_t(k)] << " substeps)";
  EXPECT_TRUE(r.same_clock);
}

// Resumed where the fluid's clock runs ahead of the frame steps (its
// substeps carry over the frame, fluid.substep_carry): a checkpoint that
// forgot the lead would plan the next frame step's substeps from the frame
// and resume on another clock.
TEST(Checkpoint, WaterResumeKeepsTheLeadOfCarriedSubsteps) {
  constexpr int kSteps = 60;
  auto straight = freshWater();
  const double frame = double(straight->scene().params.fluid.time_step);
  int k = 0;
  for (int i = 0; i < kSteps; ++i) {
    straight->step();
    const double lead = straight->time() - double(straight->stepCount()) * frame;
    if (k == 0 && i < kSteps - 5 && lead > 0.1 * frame) k = i + 1;
  }
  ASSERT_GT(k, 0) << "the fluid's clock never led the frames by a tenth of a frame step";
  const WaterResume r = resumeWater(*straight, k, kSteps);
  EXPECT_EQ(r.differ, 0u) << "resumed after step " << k;
  EXPECT_TRUE(r.same_clock);
}

// The control radius edited while a target is active (as the viewer, a
// script or Python does) takes its thin voxels along (metric filled_thin):
// a run resumed from a checkpoint written after the edit reads the same
// filled_thin, bit for bit, as the run that went on (before, the running
// backend kept the thin voxels of the radius the target was set with, and
// only a resume found them at the new one).
TEST(Checkpoint, ARadiusEditKeepsFilledThinTheSameOnResume) {
  auto straight = std::make_unique<ff::Simulation>(ff::parseScene(kScene, "ckpt.json", ""),
                                                   std::make_unique<ff::CpuBackend>(2));
  for (int i = 0; i < 3; ++i) straight->step();
  ASSERT_NE(straight->target(), nullptr);
  const float before = straight->scene().params.control.radius;
  ff::Params p = straight->scene().params;
  ASSERT_GT(p.control.radius_spacings, 1.5f);
  p.control.radius_spacings = 1.5f;
  straight->setParams(p);
  const float after = straight->scene().params.control.radius;
  // The edit changes the thin voxels, so the test can tell the two apart.
  ASSERT_NE(ff::metricsThinVoxels(*straight->target(), before).count,
            ff::metricsThinVoxels(*straight->target(), after).count);
  straight->step();
  const fftest::TempDir d("ckpt_radius");
  const std::string path = (d / "radius.ffck").string();
  ff::writeCheckpoint(path, *straight);
  auto resumed = ff::loadCheckpoint(path, std::make_unique<ff::CpuBackend>(2));
  for (int i = 0; i < 3; ++i) {
    straight->step(), resumed->step();
    EXPECT_EQ(straight->metrics().filled_thin, resumed->metrics().filled_thin) << "step " << i;
    EXPECT_EQ(straight->metrics().iou, resumed->metrics().iou) << "step " << i;
  }
}

}  // namespace
