// `flowform bench`: the CSV it writes (columns, one row per phase and a total
// consistent with the phases, the stage rows inside the phases), the Table 1
// control counts, the plots and the messages for bad input. No timing is
// asserted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <vector>

#include "app/bench_runner.h"
#include "app/bench_stability.h"
#include "cli_run.h"
#include "core/param_table.h"
#include "core/params.h"
#include "cpu/backend_cpu.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

namespace fs = std::filesystem;
using fftest::runFlowform;

struct Row {
  std::string scene, backend, device, phase;
  long fluid = 0, control = 0;
  double med = 0, min = 0, max = 0;
};

// Splits one CSV line, honouring quoted fields.
std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        f.back() += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        f.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      f.emplace_back();
    } else {
      f.back() += c;
    }
  }
  return f;
}

std::vector<Row> readCsv(const fs::path& p, std::string* header) {
  std::ifstream in(p);
  std::getline(in, *header);
  std::vector<Row> rows;
  for (std::string line; std::getline(in, line);) {
    auto f = splitCsv(line);
    EXPECT_EQ(f.size(), 9u) << line;
    if (f.size() != 9) continue;
    // A stage row leaves min and max empty.
    const auto num = [](const std::string& v) { return v.empty() ? std::nan("") : std::stod(v); };
    rows.push_back(
        {f[0], f[1], f[2], f[5], std::stol(f[3]), std::stol(f[4]), num(f[6]), num(f[7]), num(f[8])});
  }
  return rows;
}

const std::vector<std::string> kPhases = {"grid",          "density",        "forces",
                                          "control_scale", "control_forces", "pressure",
                                          "integrate",     "shape_matching", "metrics"};

TEST(BenchStats, MedianMinMaxMatchASortedCopy) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  for (size_t n : {1u, 2u, 5u, 200u, 201u}) {
    std::vector<double> v(n);
    for (double& x : v) x = u(rng);
    std::vector<double> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    ff::app::PhaseStats s = ff::app::summarise(v);
    EXPECT_DOUBLE_EQ(s.median, median) << n;
    EXPECT_DOUBLE_EQ(s.min, sorted.front()) << n;
    EXPECT_DOUBLE_EQ(s.max, sorted.back()) << n;
  }
}

// A small control sweep on every backend: per backend and case, one row per
// phase plus a total whose per-step sums bound it by the phases' extremes.
TEST(BenchCli, ControlSweepCsvHasEveryPhaseAndAConsistentTotal) {
  const fftest::TempDir d("bench_sweep");
  const fs::path csv = d / "b.csv";
  auto r = runFlowform(
      "bench --control-sweep --max-control 1000 --sweep-steps 4 --sweep-warmup 1 --threads 2 "
      "--csv '" +
      csv.string() + "' --plot");
  ASSERT_EQ(r.code, 0) << r.out;
  std::string header;
  const auto rows = readCsv(csv, &header);
  EXPECT_EQ(header, "scene,backend,device,fluid,control,phase,ms_median,ms_min,ms_max");
  std::map<std::string, std::vector<Row>> runs, stages;  // backend+device+control -> phase, stage rows
  for (const Row& row : rows) {
    const std::string key = row.backend + "|" + row.device + "|" + std::to_string(row.control);
    (row.phase.find('/') == std::string::npos ? runs : stages)[key].push_back(row);
  }
  // cpu at two control counts (500, 1000), and the same for each OpenCL device.
  ASSERT_GE(runs.size(), 2u);
  bool has_cpu = false;
  for (const auto& [key, rs] : runs) {
    has_cpu |= rs.front().backend == "cpu";
    ASSERT_EQ(rs.size(), kPhases.size() + 1) << key;
    double sum_min = 0, sum_max = 0;
    for (size_t i = 0; i < kPhases.size(); ++i) {
      EXPECT_EQ(rs[i].phase, kPhases[i]) << key;
      EXPECT_LE(rs[i].min, rs[i].med) << key << " " << rs[i].phase;
      EXPECT_LE(rs[i].med, rs[i].max) << key << " " << rs[i].phase;
      EXPECT_GE(rs[i].min, 0.0);
      sum_min += rs[i].min;
      sum_max += rs[i].max;
    }
    const Row& total = rs.back();
    EXPECT_EQ(total.phase, "total");
    EXPECT_GT(total.min, 0.0) << key;
    // Each step's total is the sum of its phases, so it lies between the sums
    // of the phases' minima and maxima (printed with 6 significant digits).
    EXPECT_GE(total.min, sum_min * (1 - 1e-5)) << key;
    EXPECT_LE(total.max, sum_max * (1 + 1e-5)) << key;
    EXPECT_EQ(total.scene, "control-sweep");
    EXPECT_NEAR(double(total.fluid), 12000.0, 200.0);
    // The placed control count is within the voxel search's 3% of the asked one.
    EXPECT_TRUE(std::abs(total.control - 500) <= 15 || std::abs(total.control - 1000) <= 30) << total.control;
    // The stage rows ("PHASE/STAGE", the mean per step, no min or max): each
    // lies inside a phase, so the stages of a phase add up to at most its
    // largest step. The OpenMP backend times each force plug-in.
    std::map<std::string, double> stage_sum;
    bool viscosity = false;
    for (const Row& st : stages[key]) {
      const std::string phase = st.phase.substr(0, st.phase.find('/'));
      EXPECT_NE(std::find(kPhases.begin(), kPhases.end(), phase), kPhases.end()) << st.phase;
      EXPECT_GE(st.med, 0.0) << st.phase;
      EXPECT_TRUE(std::isnan(st.min) && std::isnan(st.max)) << st.phase;
      stage_sum[phase] += st.med;
      viscosity |= st.phase == "forces/viscosity";
    }
    for (size_t i = 0; i < kPhases.size(); ++i) {
      if (stage_sum.count(kPhases[i])) {
        EXPECT_LE(stage_sum[kPhases[i]], rs[i].max * (1 + 1e-5)) << key << " " << kPhases[i];
      }
    }
    if (rs.front().backend == "cpu") {
      EXPECT_TRUE(viscosity) << key;
    }
  }
  EXPECT_TRUE(has_cpu);
  // The markdown table on stdout names every phase.
  for (const std::string& p : kPhases) EXPECT_NE(r.out.find("| " + p + " |"), std::string::npos) << p;
  // Its stage table names each non-pressure force plug-in under its phase, on
  // every backend (bench profiles, so OpenCL times them too).
  for (const auto& [key, rs] : runs)
    for (const char* stage :
         {"forces | gravity", "forces | viscosity", "control_scale | control", "control_forces | control"})
      EXPECT_NE(r.out.find("| control-sweep | " + rs.front().backend + " | " +
                           std::to_string(rs.front().fluid) + " | " + stage + " |"),
                std::string::npos)
          << key << ": " << stage << "\n"
          << r.out;
  // --plot: the control sweep's plot, a PNG.
  std::ifstream png(d / "b_control.png", std::ios::binary);
  ASSERT_TRUE(png.good()) << r.out;
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

// Table 1: the four meshes at the paper's control-particle counts.
TEST(BenchCli, Table1RunsTheFourScenesAtThePapersControlCounts) {
  FF_SCENE_MESHES_OR_SKIP();
  const fftest::TempDir d("bench_table1");
  const fs::path csv = d / "t.csv";
  auto r = runFlowform("bench --table1 --backend cpu --steps 1 --warmup 0 --threads 2 --csv '" +
                       csv.string() + "'");
  ASSERT_EQ(r.code, 0) << r.out;
  std::string header;
  const std::map<std::string, long> paper = {
      {"bunny", 3197}, {"teapot", 2154}, {"runner", 549}, {"dragon", 2714}};
  std::map<std::string, long> seen;
  for (const Row& row : readCsv(csv, &header)) {
    if (row.phase != "total") continue;
    EXPECT_EQ(row.fluid, 12000) << row.scene;
    EXPECT_EQ(row.backend, "cpu");
    seen[row.scene] = row.control;
  }
  ASSERT_EQ(seen.size(), 4u) << r.out;
  for (const auto& [scene, count] : paper)
    EXPECT_NEAR(double(seen[scene]), double(count), 0.03 * double(count)) << scene;
}

// --stability: the unscaled run and one per parameter and factor, each
// parameter scaled from the preset's value (the paper's w_a = 0.00008,
// alpha = 0.3) and kept in its range (alpha x4 = 1.2 is clipped to 1); an
// on/off parameter (adaptive, 0 in the paper preset) runs once, switched on;
// a mode parameter (anchor, 0 in the paper preset, of 0, 1, 2) once in each
// other mode.
TEST(BenchCli, StabilitySweepScalesEachParameterInTurn) {
  const fftest::TempDir d("bench_stability");
  const fs::path scene = d / "s.json";
  std::ofstream(scene) << fftest::blockSceneJson("tiny", 0.2, 0.07, 0.07, 8,
                                                 "\"preset\": \"paper\", \"target\": \"sphere\"");
  auto r = runFlowform("bench --stability --backend cpu --threads 2 --stability-scene '" + scene.string() +
                       "' --stability-seconds 0.02 --stability-factors 0.5,4 "
                       "--stability-params control.attraction,shape_matching.stiffness,control.adaptive,"
                       "shape_matching.anchor");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("| shape_matching.anchor | switched | 1 | stable |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| shape_matching.anchor | switched | 2 | stable |"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("| shape_matching.anchor | switched | 0 |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| control.adaptive | switched | 1 | stable |"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("| control.adaptive | 0.5 |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| (none) | 1 | - | stable |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| control.attraction | 0.5 | 4e-05 | stable |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| control.attraction | 4 | 0.00032 | stable |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| shape_matching.stiffness | 0.5 | 0.15 | stable |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| shape_matching.stiffness | 4 | 1 (range limit) | stable |"), std::string::npos)
      << r.out;
  // Not a number parameter: refused, naming the option.
  auto bad = runFlowform("bench --stability --backend cpu --stability-scene '" + scene.string() +
                         "' --stability-params control.units");
  EXPECT_EQ(bad.code, 1) << bad.out;
  EXPECT_NE(bad.out.find("--stability-params: 'control.units'"), std::string::npos) << bad.out;
}

// On the water preset the shape-matching step is set at every target by its
// fall time, time_step_fall sqrt(r / |g|) (r the control radius; here
// time_step_fall 0.2), and the preset's time_step (0.005 s) is not the step
// taken. Named in the sweep,
// shape_matching.time_step is scaled from the step the run took, computed
// here; before, the sweep scaled 0.005 s. control.radius, which
// radius_spacings sets whatever it is given, is said to have no effect and
// is not run.
TEST(BenchCli, AStepThatItsFallTimeSetsIsSweptFromTheStepTaken) {
  const fftest::TempDir d("bench_stability_water");
  const fs::path scene = d / "s.json";
  std::ofstream(scene) << fftest::blockSceneJson(
      "tiny", 0.2, 0.07, 0.07, 8,
      "\"preset\": \"water\", \"target\": \"sphere\", "
      "\"params\": {\"shape_matching\": {\"time_step_fall\": 0.2}}");
  const ff::Simulation sim(ff::loadScene(scene.string()), std::make_unique<ff::CpuBackend>(1));
  const ff::Params& p = sim.scene().params;
  ASSERT_GT(p.shape.time_step_fall, 0.0f);
  const double g = std::sqrt(double(p.fluid.gravity[0]) * p.fluid.gravity[0] +
                             double(p.fluid.gravity[1]) * p.fluid.gravity[1] +
                             double(p.fluid.gravity[2]) * p.fluid.gravity[2]);
  const double step = double(p.shape.time_step_fall) * std::sqrt(double(p.control.radius) / g);
  ASSERT_GT(std::fabs(step - 0.005), 1e-3);  // the test tells the two apart
  auto r = runFlowform("bench --stability --backend cpu --threads 2 --stability-scene '" + scene.string() +
                       "' --stability-seconds 0.008 --stability-factors 0.5 "
                       "--stability-params shape_matching.time_step,control.radius");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string row = "| shape_matching.time_step | 0.5 | ";
  const size_t at = r.out.find(row);
  ASSERT_NE(at, std::string::npos) << r.out;
  const double swept = std::stod(r.out.substr(at + row.size()));
  EXPECT_NEAR(swept, 0.5 * step, 1e-5 * step) << r.out;
  const size_t radius = r.out.find("| control.radius | 0.5 | ");
  ASSERT_NE(radius, std::string::npos) << r.out;
  const std::string radius_row = r.out.substr(radius, r.out.find('\n', radius) - radius);
  EXPECT_NE(radius_row.find("| no effect while params.control.radius_spacings > 0"), std::string::npos)
      << radius_row;
  // Not run: no figures, rather than zeros that read as measured.
  EXPECT_NE(radius_row.find(") | - | - | - | - | - | - |"), std::string::npos) << radius_row;
}

// The modes of the param table (ParamInfo::mode) are the parameters the
// stability sweep switches instead of scaling. The test's own reading of
// each integer parameter's doc (scenes/README.md): five pick a mode, the
// rest count something (iterations, substeps, control particles, voxels),
// and every integer of the table is one or the other (coarse_clusters counts
// how many times wider the coarse clusters are). The default sweep on
// both presets switches exactly the flagged set of the control and
// shape-matching groups, each through all its other values; a count, named
// explicitly, is scaled by the factors.
TEST(BenchStability, ModesAreTheTablesFlaggedParametersAndNoCountIsSwitched) {
  // The default sweep switches the modes of the control and shape-matching
  // groups; fluid.substep_carry only where it is named.
  const std::set<std::string> swept_modes = {"control.normalise", "control.adaptive", "shape_matching.anchor",
                                             "shape_matching.coarse_bars"};
  std::set<std::string> modes = swept_modes;
  modes.insert("fluid.substep_carry");
  const std::set<std::string> counts = {"fluid.max_iterations",
                                        "fluid.divergence_min_iterations",
                                        "fluid.max_substeps",
                                        "control.auto_count",
                                        "shape_matching.cluster_stride",
                                        "shape_matching.cluster_half_width",
                                        "shape_matching.rotation_iterations",
                                        "shape_matching.coarse_clusters"};
  std::set<std::string> flagged;
  for (const ff::ParamInfo& p : ff::paramTable()) {
    const std::string name = std::string(p.group) + "." + p.key;
    if (p.mode) flagged.insert(name);
    if (p.type == ff::ParamInfo::Type::Integer)
      EXPECT_TRUE(modes.count(name) + counts.count(name) == 1) << name << ": a mode or a count?";
    else
      EXPECT_FALSE(p.mode) << name << ": only an integer picks a mode";
  }
  EXPECT_EQ(flagged, modes);
  ff::app::StabilityOptions o;
  o.factors = {0.5, 4.0};
  for (const char* preset : {"paper", "water"}) {
    SCOPED_TRACE(preset);
    const ff::Params params = ff::presetParams(preset);
    std::set<std::string> switched;
    for (const ff::app::StabilityPlan& q : ff::app::stabilityPlan(params, o)) {
      const std::string name = std::string(q.param->group) + "." + q.param->key;
      if (!q.mode) {
        EXPECT_EQ(q.factors, o.factors) << name;
        continue;
      }
      switched.insert(name);
      EXPECT_EQ(q.factors.size(), size_t(q.param->max - q.param->min)) << name << ": every other mode";
    }
    EXPECT_EQ(switched, swept_modes);
    ff::app::StabilityOptions named = o;
    named.params.assign(counts.begin(), counts.end());
    for (const ff::app::StabilityPlan& q : ff::app::stabilityPlan(params, named)) {
      EXPECT_FALSE(q.mode) << q.param->key;
      EXPECT_EQ(q.factors, o.factors) << q.param->key;
    }
  }
}

// The rows of a `bench --dambreak` table by solver, each as its cells.
std::map<std::string, std::vector<std::string>> dambreakRows(const std::string& out) {
  std::map<std::string, std::vector<std::string>> rows;  // solver -> cells
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| wcsph |", 0) != 0 && line.rfind("| dfsph |", 0) != 0) continue;
    std::vector<std::string> cells;
    std::istringstream ls(line.substr(1));
    for (std::string c; std::getline(ls, c, '|');) {
      const size_t b = c.find_first_not_of(" *"), e = c.find_last_not_of(" *");
      cells.push_back(b == std::string::npos ? "" : c.substr(b, e - b + 1));
    }
    rows[cells[0]] = cells;
  }
  return rows;
}

// --dambreak --quick: a row per solver the backend runs (wcsph everywhere),
// each with a finite positive wall time per simulated second, substeps within
// the CFL range, iterations only for dfsph, a small density error and no
// particle outside the container; a solver a backend cannot run is named.
TEST(BenchCli, DambreakQuickReportsEverySolverWithSaneValues) {
  auto r = runFlowform("bench --dambreak --quick --geometry paper --seconds 0.02 --threads 2 --backend cpu");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto rows = dambreakRows(r.out);
  // dfsph: a row, or (a build without it) a line saying why not.
  ASSERT_EQ(rows.count("wcsph"), 1u) << r.out;
  EXPECT_TRUE(rows.count("dfsph") == 1 || r.out.find("not run: dfsph on cpu") != std::string::npos) << r.out;
  for (const auto& [solver, c] : rows) {
    ASSERT_EQ(c.size(), 18u) << solver;
    EXPECT_EQ(c[1], solver == "dfsph" ? "water" : "paper");
    EXPECT_EQ(c[2], "paper");
    // The paper's rest volume: 0.2 g / 800 kg/m^3 = 2.5e-7 m^3.
    EXPECT_NEAR(std::stod(c[3]), std::cbrt(2.5e-7), 1e-5) << solver;
    EXPECT_EQ(c[4], "cpu");
    EXPECT_EQ(std::stol(c[6]), 10L * 20 * 8);
    // 0.02 s of timed frame steps of 4 ms: 5 steps (after an untimed one).
    EXPECT_NEAR(std::stod(c[7]), 0.02, 1e-6) << solver;
    EXPECT_EQ(std::stoi(c[8]), 5) << solver;
    const double wall = std::stod(c[9]), ms = std::stod(c[10]);
    EXPECT_GT(wall, 0.0) << solver;
    // wall s per sim s = ms per step / the 4 ms frame step (printed rounded).
    EXPECT_NEAR(wall, ms / 4.0, 1e-3 + 1e-2 * wall) << solver;
    const double substeps = std::stod(c[11]);
    EXPECT_GE(substeps, 1.0) << solver;
    EXPECT_LE(substeps, 16.0) << solver;
    const double iterations = std::stod(c[12]);
    if (solver == "wcsph")
      EXPECT_EQ(iterations, 0.0);
    else  // at least 1 divergence and 2 density iterations per substep
      EXPECT_GE(iterations, 3.0 * substeps) << solver;
    const double mean_err = std::stod(c[13]), compression = std::stod(c[14]), max_err = std::stod(c[15]);
    EXPECT_GE(mean_err, 0.0) << solver;
    EXPECT_LT(mean_err, 0.5) << solver;  // the first 20 ms of a block at rest density
    // The mean compression counts only particles above rho0: at most the
    // mean absolute error and at most the largest compression.
    EXPECT_GE(compression, 0.0) << solver;
    EXPECT_LE(compression, mean_err + 1e-6) << solver;
    EXPECT_LE(compression, max_err + 1e-6) << solver;
    EXPECT_LT(max_err, 1.0) << solver;
    EXPECT_EQ(std::stol(c[17]), 0L) << solver;  // no particle outside the container
  }
  // The per-phase table of the same runs.
  EXPECT_NE(r.out.find("### Dam break phases"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| dambreak-wcsph | cpu |"), std::string::npos) << r.out;
}

// --geometry peer (the default): SPlisHSPlasH's DamBreakModel, an n^3 block
// of spacing 1 / (n + 1) m (quick: 11^3, 1/12 m), on the water preset.
TEST(BenchCli, DambreakPeerGeometryUsesThePeersParticleSize) {
  auto r = runFlowform("bench --dambreak --quick --solver dfsph --seconds 0.029 --threads 2 --backend cpu");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto rows = dambreakRows(r.out);
  if (rows.count("dfsph") == 0) GTEST_SKIP() << "this build has no dfsph: " << r.out;
  const std::vector<std::string>& c = rows.at("dfsph");
  ASSERT_EQ(c.size(), 18u);
  EXPECT_EQ(c[1], "water");
  EXPECT_EQ(c[2], "peer");
  EXPECT_NEAR(std::stod(c[3]), 1.0 / 12.0, 1e-5);
  EXPECT_EQ(std::stol(c[6]), 11L * 11 * 11);
  // The water preset's frame step is time_step_fall sqrt(H / g) at the
  // support H = 2 spacings = 1/6 m: 14.5 ms, so 0.029 s is 2 frame steps.
  const double frame =
      double(ff::presetParams("water").fluid.time_step_fall) * std::sqrt((2.0 / 12.0) / 9.81);
  EXPECT_EQ(std::stol(c[8]), std::lround(0.029 / frame));
  EXPECT_EQ(std::stol(c[8]), 2L);
  // A block on the rest lattice that has just started to fall: the solver
  // holds its compression within its tolerance (0.05 %; the free surface's
  // missing neighbours count in the mean density error, not here).
  EXPECT_LT(std::stod(c[14]), 0.001);
  EXPECT_EQ(std::stol(c[17]), 0L);
  // The solver's stages are named and timed (positive ms per step).
  for (const char* stage : {"| density | dfsph factor + neighbour cache | ",
                            "| pressure | divergence solve | ", "| pressure | density solve | "}) {
    const std::string row = std::string("| dambreak-dfsph | cpu | 1331 ") + stage;
    const size_t at = r.out.find(row);
    ASSERT_NE(at, std::string::npos) << stage << "\n" << r.out;
    EXPECT_GT(std::stod(r.out.substr(at + row.size())), 0.0) << stage;
  }
}

TEST(BenchCli, BadInputIsRefusedWithTheOptionNamed) {
  const fftest::TempDir d("bench_bad");
  struct Case {
    std::string args, env, says;
  };
  const std::vector<Case> cases = {
      {"bench --backend gpu", "", "--backend"},
      {"bench --steps 0", "", "--steps"},
      {"bench --plot", "", "--plot"},
      {"bench --budget nan", "", "--budget"},
      {"bench --dambreak --seconds 0", "", "--seconds"},
      {"bench --dambreak --solver pcisph", "", "--solver"},
      {"bench --dambreak --geometry tiny", "", "--geometry"},
      // No upper bound before: each ran for days (the soak at 2e9 changes, 1e9 timed steps).
      {"bench --soak --soak-changes 2000000000", "", "--soak-changes: must be at most 100000"},
      {"bench --table1 --steps 1000000000", "", "--steps: must be at most 100000"},
      {"bench --stability --stability-seconds 1e9", "", "--stability-seconds: must be at most 600"},
      {"bench --table1 --preset honey", "", "--preset: unknown parameter preset 'honey'"},
      // Timed every device (-2), or the CPU with the device ignored, before.
      {"bench --table1 --steps 1 --warmup 0 --device -2", "", "--device: must be >= 0 (got -2)"},
      {"bench --table1 --steps 1 --warmup 0 --backend cpu --device 0", "",
       "--device: only applies to the OpenCL backend"},
      {"bench --table1 --backend cpu --csv '" + (d / "no" / "such" / "dir.csv").string() + "'", "",
       "dir.csv"},
  };
  for (const Case& c : cases) {
    auto r = runFlowform(c.args, c.env);
    EXPECT_EQ(r.code, 1) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.says), std::string::npos) << c.args << "\n" << r.out;
  }
  // No meshes: the message names the mesh and the search path.
  auto r = runFlowform("bench --table1 --backend cpu --steps 1", "FLOWFORM_MESH_PATH=/nonexistent ");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("target.mesh: mesh 'bunny.obj' not found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FLOWFORM_MESH_PATH"), std::string::npos) << r.out;
}

}  // namespace
