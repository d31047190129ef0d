// Viewer scripts (`flowform view --script`): a valid file becomes the expected
// actions; every kind of bad input is an ff::Error naming the file and field.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "core/error.h"
#include "temp_dir.h"
#include "viewer/script.h"

namespace {

namespace fs = std::filesystem;
using ff::viewer::Script;
using ff::viewer::ScriptAction;
using Kind = ff::viewer::ScriptAction::Kind;

// The message of the ff::Error that parsing `text` as "demo.json" throws ("" if none).
std::string errorOf(const std::string& text) {
  try {
    ff::viewer::parseScript(text, "demo.json", "");
  } catch (const ff::Error& e) {
    return e.what();
  }
  return "";
}

// A script's render mode takes the names of `flowform render --mode`:
// "fluid" (the screen-space surface) and "particles", and the scripts' old
// name "screen_space" for "fluid" (before, a script refused "fluid" and the
// CLI refused "screen_space"; RenderCli.BadInputIsRefusedWithTheReason
// checks the CLI).
TEST(ViewerScript, RenderModeTakesTheNamesOfTheRenderCommand) {
  for (const auto& [name, particles] :
       {std::pair<const char*, bool>{"fluid", false}, {"screen_space", false}, {"particles", true}}) {
    const Script s = ff::viewer::parseScript(
        std::string(R"({"actions": [{"at": 0, "render": {"mode": ")") + name + R"("}}]})", "demo.json", ".");
    ASSERT_EQ(s.actions.size(), 1u);
    ASSERT_TRUE(s.actions[0].render.particles.has_value()) << name;
    EXPECT_EQ(*s.actions[0].render.particles, particles) << name;
  }
}

TEST(ViewerScript, ValidFileGivesTheActionsInOrder) {
  const fftest::TempDir dir("script_valid");
  std::ofstream(dir / "tet.obj")
      << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::ofstream(dir / "demo.json") << R"({"actions": [
    {"at": 0, "camera": {"yaw": 30, "pitch": 20, "distance": 0.5, "fov": 45, "target": [0.1, 0.05, 0.2]}},
    {"at": 0.5, "target": {"shape": "box", "size": [2, 1, 1]}},
    {"at": 0.5, "region": {"box": {"min": [0, 0, 0], "max": [0.1, 0.2, 0.3]}}},
    {"at": 0.75, "region": {"sphere": {"center": [0.1, 0.1, 0.1], "radius": 0.05}}},
    {"at": 1.0, "params": {"fluid": {"viscosity": 0.05}, "control": {"units": "force_density"},
                           "shape_matching": {"cluster_stride": 3}}},
    {"at": 1.0, "render": {"mode": "particles", "control": true, "ghost": false}},
    {"at": 1.0, "panel": false},
    {"at": 1.2, "target": "tet.obj"},
    {"at": 1.2, "target": "none"},
    {"at": 1.25, "pause": true},
    {"at": 1.25, "play": true},
    {"at": 1.5, "screenshot": "shots/out.png"},
    {"at": 1.5, "quit": true}
  ]})";
  const Script s = ff::viewer::loadScript((dir / "demo.json").string());
  ASSERT_EQ(s.actions.size(), 13u);
  const Kind kinds[] = {Kind::Camera, Kind::Target,     Kind::Region, Kind::Region,   Kind::Params,
                        Kind::Render, Kind::Panel,      Kind::Target, Kind::NoTarget, Kind::Pause,
                        Kind::Play,   Kind::Screenshot, Kind::Quit};
  const double times[] = {0, 0.5, 0.5, 0.75, 1.0, 1.0, 1.0, 1.2, 1.2, 1.25, 1.25, 1.5, 1.5};
  for (size_t i = 0; i < 13; ++i) {
    EXPECT_EQ(s.actions[i].kind, kinds[i]) << i;
    EXPECT_DOUBLE_EQ(s.actions[i].at, times[i]) << i;
    EXPECT_NE(s.actions[i].where.find("actions[" + std::to_string(i) + "]"), std::string::npos);
  }
  const ff::viewer::CameraAction& cam = s.actions[0].camera;
  ASSERT_TRUE(cam.yaw_deg && cam.pitch_deg && cam.distance && cam.fov_deg && cam.target);
  EXPECT_FLOAT_EQ(*cam.yaw_deg, 30.0f);
  EXPECT_FLOAT_EQ(*cam.pitch_deg, 20.0f);
  EXPECT_FLOAT_EQ(*cam.distance, 0.5f);
  EXPECT_FLOAT_EQ(*cam.fov_deg, 45.0f);
  EXPECT_FLOAT_EQ(cam.target->z(), 0.2f);

  EXPECT_EQ(s.actions[1].target.kind, ff::TargetKind::Box);
  EXPECT_FLOAT_EQ(s.actions[1].target.box_size.x(), 2.0f);

  EXPECT_EQ(s.actions[2].region.kind, ff::RegionDesc::Kind::Box);
  EXPECT_FLOAT_EQ(s.actions[2].region.max.y(), 0.2f);
  EXPECT_EQ(s.actions[3].region.kind, ff::RegionDesc::Kind::Sphere);
  EXPECT_FLOAT_EQ(s.actions[3].region.radius, 0.05f);

  // A params action changes the keys it names and nothing else.
  ff::Params p;
  p.fluid.gas_constant = 3.0f;
  ff::viewer::applyParamsAction(s.actions[4], p);
  EXPECT_FLOAT_EQ(p.fluid.viscosity, 0.05f);
  EXPECT_EQ(p.control.units, ff::ControlForceUnits::ForceDensity);
  EXPECT_EQ(p.shape.cluster_stride, 3);
  EXPECT_FLOAT_EQ(p.fluid.gas_constant, 3.0f);
  EXPECT_FLOAT_EQ(p.control.attraction, ff::Params().control.attraction);

  const ff::viewer::RenderAction& r = s.actions[5].render;
  ASSERT_TRUE(r.particles && r.control && r.ghost);
  EXPECT_TRUE(*r.particles);
  EXPECT_TRUE(*r.control);
  EXPECT_FALSE(*r.ghost);
  EXPECT_FALSE(r.region.has_value());
  EXPECT_FALSE(s.actions[6].panel);

  // Mesh names resolve relative to the script's folder.
  EXPECT_EQ(s.actions[7].target.kind, ff::TargetKind::Mesh);
  EXPECT_EQ(fs::weakly_canonical(s.actions[7].target.resolved_path), fs::weakly_canonical(dir / "tet.obj"));
  EXPECT_EQ(s.actions[11].screenshot, "shots/out.png");
}

TEST(ViewerScript, CursorRunsActionsWhenTheSimulatedTimeReachesThem) {
  ff::viewer::ScriptCursor c(ff::viewer::parseScript(
      R"({"actions": [{"at": 0, "pause": true}, {"at": 0.012, "play": true}, {"at": 0.012, "quit": true}]})",
      "demo.json", ""));
  ASSERT_TRUE(c.due(0.0));
  EXPECT_EQ(c.take().kind, Kind::Pause);
  EXPECT_FALSE(c.due(0.008));
  EXPECT_TRUE(c.due(0.004 * 3));  // 0.012 in float steps: within the 1e-9 s tolerance
  EXPECT_EQ(c.take().kind, Kind::Play);
  EXPECT_TRUE(c.due(0.012));
  EXPECT_EQ(c.take().kind, Kind::Quit);
  EXPECT_TRUE(c.done());
  EXPECT_FALSE(c.due(100.0));
}

TEST(ViewerScript, EmptyActionListIsValid) {
  EXPECT_TRUE(ff::viewer::parseScript(R"({"actions": []})", "demo.json", "").actions.empty());
}

struct BadCase {
  const char* text;
  const char* message;  // the error must contain this
};

TEST(ViewerScript, EveryBadInputNamesTheFileAndTheField) {
  const BadCase cases[] = {
      {R"({"actions": [{"at": 0, "quit": true}, {"at": 1, "pause": true},
                       {"at": 2, "target": {"shape": "cube"}}]})",
       "demo.json: actions[2].target.shape: must be one of: sphere, box, torus, capsule, mesh (got 'cube')"},
      {R"({"actions": [{"at": 0, "target": "cube"}]})", "demo.json: actions[0].target: must be sphere, box"},
      {R"({"actions": [{"at": 0, "target": "missing_mesh_xyz.obj"}]})", "demo.json: actions[0].target: "},
      {R"({"actions": [{"at": 0, "colour": "red"}]})", "demo.json: actions[0].colour: unknown key"},
      {R"({"actions": [], "speed": 2})", "demo.json: speed: unknown key"},
      {R"({"steps": []})", "demo.json: steps: unknown key"},
      {R"({})", "demo.json: actions: required key is missing"},
      {R"({"actions": {"at": 0}})", "demo.json: actions: must be an array"},
      {R"([1, 2])", "demo.json: a script must be a JSON object"},
      {R"({"actions": [3]})", "demo.json: actions[0]: must be an object"},
      {R"({"actions": [{"quit": true}]})", "demo.json: actions[0].at: required key is missing"},
      {R"({"actions": [{"at": 1}]})", "demo.json: actions[0]: has no action"},
      {R"({"actions": [{"at": 1, "pause": true, "quit": true}]})",
       "demo.json: actions[0]: holds two actions"},
      {R"({"actions": [{"at": "soon", "quit": true}]})", "demo.json: actions[0].at: must be a number"},
      {R"({"actions": [{"at": -0.5, "quit": true}]})", "demo.json: actions[0].at: must be >= 0"},
      {R"({"actions": [{"at": 1, "pause": true}, {"at": 0.5, "quit": true}]})",
       "demo.json: actions[1].at: times must not decrease (got 0.5 after 1)"},
      {R"({"actions": [{"at": 0, "camera": {"yaw": "left"}}]})",
       "demo.json: actions[0].camera.yaw: must be a number"},
      {R"({"actions": [{"at": 0, "camera": {"pitch": 95}}]})",
       "demo.json: actions[0].camera.pitch: must be in [-89, 89]"},
      {R"({"actions": [{"at": 0, "camera": {"distance": 0}}]})",
       "demo.json: actions[0].camera.distance: must be > 0"},
      {R"({"actions": [{"at": 0, "camera": {"roll": 3}}]})",
       "demo.json: actions[0].camera.roll: unknown key"},
      {R"({"actions": [{"at": 0, "camera": {}}]})", "demo.json: actions[0].camera: must not be empty"},
      {R"({"actions": [{"at": 0, "camera": {"target": [1, 2]}}]})",
       "demo.json: actions[0].camera.target: must be an array of 3 numbers"},
      {R"({"actions": [{"at": 0, "region": {"box": {"min": [0, 0, 0], "max": [0.1, 0, 0.1]}}}]})",
       "demo.json: actions[0].region.box: min must be < max"},
      {R"({"actions": [{"at": 0, "region": {"sphere": {"center": [0, 0, 0]}}}]})",
       "demo.json: actions[0].region.sphere.radius: required key is missing"},
      {R"({"actions": [{"at": 0, "region": "some"}]})", "demo.json: actions[0].region: must be \"all\""},
      {R"({"actions": [{"at": 0, "params": {"fluid": {"viscosity": -1}}}]})",
       "demo.json: actions[0].params.fluid.viscosity: must be in [0, 10000] (got -1)"},
      {R"({"actions": [{"at": 0, "params": {"fluid": {"viscosity": "thick"}}}]})",
       "demo.json: actions[0].params.fluid.viscosity: must be a number"},
      {R"({"actions": [{"at": 0, "params": {"shape_matching": {"cluster_stride": 1.5}}}]})",
       "demo.json: actions[0].params.shape_matching.cluster_stride: must be an integer"},
      {R"({"actions": [{"at": 0, "params": {"solver": {}}}]})",
       "demo.json: actions[0].params.solver: unknown key"},
      {R"({"actions": [{"at": 0, "render": {"mode": "wireframe"}}]})",
       "demo.json: actions[0].render.mode: must be \"fluid\" (or \"screen_space\") or \"particles\""},
      {R"({"actions": [{"at": 0, "render": {"ghost": 1}}]})",
       "demo.json: actions[0].render.ghost: must be true or false"},
      {R"({"actions": [{"at": 0, "panel": "off"}]})", "demo.json: actions[0].panel: must be true or false"},
      {R"({"actions": [{"at": 0, "screenshot": "out.jpg"}]})",
       "demo.json: actions[0].screenshot: must be a .png"},
      {R"({"actions": [{"at": 0, "screenshot": 7}]})", "demo.json: actions[0].screenshot: must be a string"},
      {R"({"actions": [{"at": 0, "quit": false}]})", "demo.json: actions[0].quit: must be true"},
      {R"({"actions": [{"at": 0, "pause": 1}]})", "demo.json: actions[0].pause: must be true"},
      {R"({"actions": [{"at": 0, "quit": true, "at": 1}]})", "demo.json: actions[0].at: duplicate key"},
      {R"({"actions": [{"at": 1e999, "quit": true}]})", "actions[0].at: number out of range"},
      {"{\"actions\": [\n{\"at\": 0 \"quit\": true}]}", "demo.json:2:"},
  };
  for (const BadCase& c : cases) {
    const std::string msg = errorOf(c.text);
    EXPECT_NE(msg.find(c.message), std::string::npos) << "input: " << c.text << "\nmessage: " << msg;
    EXPECT_EQ(msg.rfind("demo.json", 0), 0u) << msg;
  }
}

TEST(ViewerScript, TheDemoScriptParses) {
  const Script s = ff::viewer::loadScript(std::string(FF_SOURCE_DIR) + "/scenes/scripts/demo_view.json");
  ASSERT_GE(s.actions.size(), 5u);
  int targets = 0, screenshots = 0;
  for (const ScriptAction& a : s.actions) {
    targets += a.kind == Kind::Target;
    screenshots += a.kind == Kind::Screenshot;
  }
  EXPECT_GE(targets, 3);
  EXPECT_EQ(screenshots, 1);
}

TEST(ViewerScript, MissingFileIsAnErrorNamingIt) {
  const fftest::TempDir dir("script_missing");
  const fs::path missing = dir / "nope.json";
  try {
    ff::viewer::loadScript(missing.string());
    FAIL() << "no error for a missing script";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string() + ": cannot open script file"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(ff::viewer::loadScript(missing.parent_path().string()), ff::Error);  // a folder
}

}  // namespace
