// The offscreen renderer: liquid pixels cover exactly where the particles
// project, a target change shows up where the liquid moved, and
// `flowform render` writes PNG frames or refuses bad input with a reason.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "cli_run.h"
#include "cpu/backend_cpu.h"
#include "render/camera.h"
#include "render/frame_data.h"
#include "render/offscreen_context.h"
#include "render/scene_renderer.h"
#include "sim/simulation.h"
#include "test_scenes.h"

namespace {

namespace fs = std::filesystem;
using ff::Vec3;
using ff::render::FrameData;
using ff::render::OrbitCamera;

constexpr int kW = 256, kH = 256;

// One pixel per entry, row-major, top row first.
using Mask = std::vector<uint8_t>;

// Independent of the renderer: each particle's sphere seen as a disc around
// its projected centre with radius r * P11 * (h / 2) / depth, from the
// camera's view and projection matrices (checked in test_camera.cpp).
Mask projectedDiscs(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z,
                    float radius, const OrbitCamera& cam, int w, int h) {
  const ff::render::Mat4 proj = cam.projection(float(w) / float(h));
  const ff::render::Mat4 vp = proj * cam.view();
  Mask m(size_t(w) * size_t(h), 0);
  for (size_t i = 0; i < x.size(); ++i) {
    const Eigen::Vector4f c = vp * Eigen::Vector4f(x[i], y[i], z[i], 1.0f);
    const float px = (0.5f * c.x() / c.w() + 0.5f) * float(w);  // pixel units, left edge = 0
    const float py = (0.5f - 0.5f * c.y() / c.w()) * float(h);  // top edge = 0
    const float pr = radius * proj(1, 1) * 0.5f * float(h) / c.w();
    for (int j = std::max(0, int(py - pr) - 1); j <= std::min(h - 1, int(py + pr) + 1); ++j)
      for (int i2 = std::max(0, int(px - pr) - 1); i2 <= std::min(w - 1, int(px + pr) + 1); ++i2) {
        const float dx = float(i2) + 0.5f - px, dy = float(j) + 0.5f - py;
        if (dx * dx + dy * dy <= pr * pr) m[size_t(j) * size_t(w) + size_t(i2)] = 1;
      }
  }
  return m;
}

// Pixels whose colour differs by more than `threshold` in some channel.
Mask differing(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int threshold) {
  Mask m(a.size() / 4, 0);
  for (size_t p = 0; p < m.size(); ++p)
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(a[4 * p + size_t(c)]) - int(b[4 * p + size_t(c)])) > threshold) m[p] = 1;
  return m;
}

size_t count(const Mask& m) {
  size_t n = 0;
  for (uint8_t v : m) n += v;
  return n;
}

double iou(const Mask& a, const Mask& b) {
  size_t inter = 0, uni = 0;
  for (size_t p = 0; p < a.size(); ++p) inter += a[p] & b[p], uni += a[p] | b[p];
  return uni ? double(inter) / double(uni) : 0.0;
}

// A block of particles resting on the floor and a ball above it.
FrameData handMadeFrame() {
  FrameData f;
  f.container.min = Vec3(0.0f, 0.0f, 0.0f);
  f.container.max = Vec3(0.3f, 0.3f, 0.3f);
  f.particle_radius = 0.0059f;
  f.particle_volume = 2.5e-7f;
  const float s = 0.0063f;
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 14; ++i) {
        f.x.push_back(0.06f + float(i) * s), f.y.push_back(0.0035f + float(j) * s);
        f.z.push_back(0.08f + float(k) * s);
      }
  for (int k = -6; k <= 6; ++k)
    for (int j = -6; j <= 6; ++j)
      for (int i = -6; i <= 6; ++i)
        if (i * i + j * j + k * k <= 36) {
          f.x.push_back(0.2f + float(i) * s), f.y.push_back(0.16f + float(j) * s);
          f.z.push_back(0.17f + float(k) * s);
        }
  return f;
}

struct Renders {
  std::unique_ptr<ff::render::OffscreenContext> ctx;
  std::unique_ptr<ff::render::SceneRenderer> renderer;
  Renders(int w, int h)
      : ctx(std::make_unique<ff::render::OffscreenContext>(w, h)),
        renderer(std::make_unique<ff::render::SceneRenderer>()) {}
  ~Renders() { renderer.reset(); }  // GL objects go while the context lives
  std::vector<uint8_t> draw(const FrameData& f, const OrbitCamera& cam, const ff::render::RenderOptions& o) {
    renderer->draw(f, cam, o, ctx->width(), ctx->height(), ctx->framebuffer());
    return ctx->readPixels();
  }
};

// The liquid's own pixels only: no shadow on the floor (which would darken
// pixels next to the liquid) and no region outline.
ff::render::RenderOptions liquidOnly(ff::render::FluidMode mode) {
  ff::render::RenderOptions o;
  o.mode = mode;
  o.show_shadow = false;
  o.show_region = false;
  return o;
}

// A pixel counts as changed when a channel moves by more than this (of 255):
// above the 8-bit rounding noise, well below what a liquid layer does to the
// background (the thinnest rim still reflects sky and tints blue by more).
constexpr int kDiffThreshold = 6;

TEST(RenderOffscreen, LiquidCoversTheProjectedParticleDiscsAndIsBlue) {
  Renders r(kW, kH);
  const FrameData with = handMadeFrame();
  FrameData without = with;
  without.x.clear(), without.y.clear(), without.z.clear();
  const OrbitCamera cam = OrbitCamera::framing(with.container.min, with.container.max);
  const auto o = liquidOnly(ff::render::FluidMode::ScreenSpace);
  const std::vector<uint8_t> a = r.draw(with, cam, o), b = r.draw(without, cam, o);
  ASSERT_EQ(a.size(), size_t(kW) * kH * 4);

  const Mask rendered = differing(a, b, kDiffThreshold);
  const Mask expected = projectedDiscs(with.x, with.y, with.z, with.particle_radius, cam, kW, kH);
  ASSERT_GT(count(expected), 1500u) << "the test scene should fill a good part of the image";
  // The smoothing filter moves depth only between pixels that hold liquid,
  // and into gaps narrower than a particle's diameter with liquid on both
  // sides (holes in a sheet), so it neither grows nor shrinks the outline
  // beyond closing such notches. What remains is the disc approximation of
  // each sphere's perspective outline (an ellipse up to 1/cos(off-axis
  // angle), under 3 % larger here), the one-pixel rasterisation rim of a
  // union of discs about 5 px in radius and the few closed notches: a few
  // percent of the area (0.97 is typical). 0.85 leaves room for that and
  // fails as soon as the liquid lands a few pixels off (a shift of two
  // particle diameters, 5 px, gives 0.70).
  const double overlap = iou(rendered, expected);
  EXPECT_GE(overlap, 0.85) << "rendered " << count(rendered) << " px, expected " << count(expected) << " px";

  // Blue: over the liquid pixels, blue exceeds red clearly, and far more than
  // in the background at the same pixels.
  double blue_minus_red = 0.0, background_blue_minus_red = 0.0;
  size_t n = 0;
  for (size_t p = 0; p < rendered.size(); ++p)
    if (rendered[p]) {
      blue_minus_red += double(a[4 * p + 2]) - double(a[4 * p]);
      background_blue_minus_red += double(b[4 * p + 2]) - double(b[4 * p]);
      ++n;
    }
  ASSERT_GT(n, 0u);
  EXPECT_GT(blue_minus_red / double(n), 40.0);
  EXPECT_GT((blue_minus_red - background_blue_minus_red) / double(n), 30.0);
}

TEST(RenderOffscreen, ParticleModeDrawsTheSameDiscs) {
  Renders r(kW, kH);
  const FrameData with = handMadeFrame();
  FrameData without = with;
  without.x.clear(), without.y.clear(), without.z.clear();
  const OrbitCamera cam = OrbitCamera::framing(with.container.min, with.container.max);
  const auto o = liquidOnly(ff::render::FluidMode::Particles);
  const Mask rendered = differing(r.draw(with, cam, o), r.draw(without, cam, o), kDiffThreshold);
  const Mask expected = projectedDiscs(with.x, with.y, with.z, with.particle_radius, cam, kW, kH);
  // Opaque spheres: only the discs' rasterisation rims differ.
  EXPECT_GE(iou(rendered, expected), 0.9);
}

TEST(RenderOffscreen, NothingButBackgroundWithoutLiquid) {
  // The difference test above relies on an empty frame being stable: two
  // draws of the same frame give the same pixels, and the container shows.
  Renders r(kW, kH);
  FrameData empty = handMadeFrame();
  empty.x.clear(), empty.y.clear(), empty.z.clear();
  const OrbitCamera cam = OrbitCamera::framing(empty.container.min, empty.container.max);
  auto o = liquidOnly(ff::render::FluidMode::ScreenSpace);
  const std::vector<uint8_t> a = r.draw(empty, cam, o), b = r.draw(empty, cam, o);
  EXPECT_EQ(count(differing(a, b, 0)), 0u);
  o.show_container = false;
  const std::vector<uint8_t> bare = r.draw(empty, cam, o);
  EXPECT_GT(count(differing(a, bare, kDiffThreshold)), size_t(kW) * kH / 4) << "floor and edges missing";
}

ff::SceneDesc smallScene() {
  return fftest::blockScene(Vec3(0.2f, 0.2f, 0.2f), Vec3(0.055f, 0.0f, 0.055f), 14, 12, 14, "render test");
}

TEST(RenderOffscreen, TargetChangeShowsWhereTheLiquidMoved) {
  ff::Simulation sim(smallScene(), std::make_unique<ff::CpuBackend>());
  sim.setTarget(fftest::target(ff::TargetKind::Sphere, 400));
  for (int i = 0; i < 60; ++i) sim.step();
  const FrameData a = ff::render::captureFrame(sim);
  ASSERT_FALSE(a.ghost.empty());
  // A flat box, wider than the ball: the liquid spreads sideways.
  ff::TargetSpec box = fftest::target(ff::TargetKind::Box, 400);
  box.box_size = Vec3(3.0f, 0.6f, 3.0f);
  sim.setTarget(box);
  for (int i = 0; i < 60; ++i) sim.step();
  const FrameData b = ff::render::captureFrame(sim);

  Renders r(kW, kH);
  const OrbitCamera cam = OrbitCamera::framing(a.container.min, a.container.max);
  const auto o = liquidOnly(ff::render::FluidMode::ScreenSpace);
  const std::vector<uint8_t> ia = r.draw(a, cam, o), ib = r.draw(b, cam, o);
  const Mask changed = differing(ia, ib, kDiffThreshold);
  const Mask ma = projectedDiscs(a.x, a.y, a.z, a.particle_radius, cam, kW, kH);
  const Mask mb = projectedDiscs(b.x, b.y, b.z, b.particle_radius, cam, kW, kH);
  // Where the renderer may draw liquid: the depth smoothing closes gaps up to
  // a particle diameter between liquid on both sides, and every pixel of such
  // a gap lies within two radii of a particle centre.
  const Mask reach_a = projectedDiscs(a.x, a.y, a.z, 2.0f * a.particle_radius, cam, kW, kH);
  const Mask reach_b = projectedDiscs(b.x, b.y, b.z, 2.0f * b.particle_radius, cam, kW, kH);
  size_t in_reach = 0, moved_area = 0;
  for (size_t p = 0; p < changed.size(); ++p) {
    in_reach += changed[p] & (reach_a[p] | reach_b[p]);
    moved_area += ma[p] ^ mb[p];
  }
  ASSERT_GT(moved_area, size_t(kW) * kH / 100) << "the target change did not move the liquid";
  // Substantially different: at least the area the liquid's outline moved
  // over (pixels covered in one state only must change), at least 2 % of the image.
  EXPECT_GE(count(changed), size_t(0.8 * double(moved_area)));
  EXPECT_GE(count(changed), size_t(kW) * kH / 50);
  // And only there: the changed pixels lie where liquid is in either state.
  EXPECT_GE(double(in_reach) / double(count(changed)), 0.97)
      << count(changed) << " changed pixels, " << in_reach << " of them where liquid can be";
}

// ---- the `flowform render` command ---------------------------------------------

using fftest::CliResult;
using fftest::runFlowform;

// A scene that simulates in moments: 512 particles, a sphere target.
fs::path tinyScene(const fs::path& dir) {
  const fs::path p = dir / "tiny.json";
  std::ofstream(p) << fftest::blockSceneJson("tiny", 0.12, 0.035, 0.035, 8,
                                             R"("target": {"shape": "sphere", "control_count": 100})");
  return p;
}

// Width and height from a PNG's IHDR chunk (big-endian, bytes 16..23).
bool pngSize(const fs::path& p, int& w, int& h) {
  std::ifstream in(p, std::ios::binary);
  unsigned char head[24] = {};
  if (!in.read(reinterpret_cast<char*>(head), sizeof(head))) return false;
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!std::equal(sig, sig + 8, head) || std::string(reinterpret_cast<char*>(head + 12), 4) != "IHDR")
    return false;
  w = int(head[16]) << 24 | int(head[17]) << 16 | int(head[18]) << 8 | int(head[19]);
  h = int(head[20]) << 24 | int(head[21]) << 16 | int(head[22]) << 8 | int(head[23]);
  return true;
}

const char* kCliEnv = "OMP_NUM_THREADS=2";

TEST(RenderCli, WritesTheFramesAsPngsOfTheAskedSize) {
  const fftest::TempDir d("render_frames");
  const fs::path out = d / "out";
  const CliResult r = runFlowform("render '" + tinyScene(d).string() + "' --frames 2 --every 2 --width 160 " +
                                      "--height 120 --backend cpu --out '" + out.string() + "'",
                                  kCliEnv);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("frame 2/2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("GL renderer"), std::string::npos) << r.out;
  for (const char* name : {"frame_00000.png", "frame_00001.png"}) {
    int w = 0, h = 0;
    ASSERT_TRUE(pngSize(out / name, w, h)) << name;
    EXPECT_EQ(w, 160);
    EXPECT_EQ(h, 120);
    // The image decodes and shows something (not one flat colour).
    int iw = 0, ih = 0, ch = 0;
    unsigned char* px = stbi_load((out / name).c_str(), &iw, &ih, &ch, 4);
    ASSERT_NE(px, nullptr) << name;
    int lo = 255, hi = 0;
    for (int i = 0; i < iw * ih * 4; i += 4)
      lo = std::min(lo, int(px[i + 2])), hi = std::max(hi, int(px[i + 2]));
    stbi_image_free(px);
    EXPECT_GT(hi - lo, 50) << name;
  }
  EXPECT_FALSE(fs::exists(out / "frame_00002.png"));
}

TEST(RenderCli, BadInputIsRefusedWithTheReason) {
  const fftest::TempDir d("render_bad");
  const std::string scene = "'" + tinyScene(d).string() + "' ";
  const std::string out = " --out '" + (d / "o").string() + "'";
  struct Case {
    std::string args, says;
  };
  for (const Case& c :
       {Case{"--frames 0" + out, "--frames"}, Case{"--frames -3" + out, "--frames"},
        Case{"--frames 1 --width 4" + out, "--width"}, Case{"--frames 1 --height 100000" + out, "--height"},
        Case{"--frames 1 --camera 10,20" + out, "--camera"},
        Case{"--frames 1 --camera a,b,c" + out, "--camera"},
        Case{"--frames 1 --camera 0,95,1" + out, "pitch"}, Case{"--frames 1 --mode voxels" + out, "--mode"},
        // screen_space (a script's name for fluid) passes --mode: the camera is refused.
        Case{"--frames 1 --mode screen_space --camera 10,20" + out, "--camera"},
        Case{"--frames 1 --out /proc/flowform_no/x", "/proc/flowform_no/x"},
        Case{"--frames 1 --width 161 --video v.mp4" + out, "even width"},
        Case{"--frames 2 --every 0" + out, "--every"}, Case{"--frames 1 --start -1" + out, "--start"},
        Case{"--frames 1 --video /nonexistent_ff/v.mp4" + out, "/nonexistent_ff"}}) {
    const CliResult r = runFlowform("render " + scene + c.args, kCliEnv);
    EXPECT_TRUE(fftest::isRefusal(r.code)) << c.args << ": exit code " << r.code << "\n" << r.out;
    EXPECT_NE(r.out.find(c.says), std::string::npos) << c.args << "\n" << r.out;
    EXPECT_EQ(r.out.find("internal error"), std::string::npos) << c.args << "\n" << r.out;
  }
  EXPECT_FALSE(fs::exists(d / "o" / "frame_00000.png"));
}

TEST(RenderCli, VideoWithoutFfmpegStopsBeforeAnyWork) {
  const fftest::TempDir d("render_video");
  const fs::path empty_bin = d / "bin";  // a PATH with no ffmpeg on it
  fs::create_directories(empty_bin);
  const fs::path out = d / "frames";
  const CliResult r =
      runFlowform("render '" + tinyScene(d).string() + "' --frames 1 --width 64 --height 64 --out '" +
                      out.string() + "' --video '" + (d / "v.mp4").string() + "'",
                  std::string(kCliEnv) + " PATH='" + empty_bin.string() + "'");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("--video needs ffmpeg"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("apt-get install ffmpeg"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out)) << "the check comes before any work, so not even the folder is made";
  EXPECT_FALSE(fs::exists(d / "v.mp4"));
}

}  // namespace
