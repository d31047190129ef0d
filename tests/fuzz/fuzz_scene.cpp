// fuzz_scene.cpp - libFuzzer target: the strict scene reader (parseScene).
// Any input must give a SceneDesc or an ff::Error; anything else (a crash,
// another exception, a sanitizer report, a hang) is a finding. A scene that
// is accepted is also written back (scene_writer) and read again: the writer
// must produce what the reader accepts, with the same fluid, region and
// targets. Built with -DFLOWFORM_FUZZ=ON (tests/fuzz/README.md).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "scene/scene.h"
#include "scene/scene_writer.h"

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ff::SceneDesc scene;
  try {
    scene = ff::parseScene(text, "fuzz.json", "");
  } catch (const ff::Error&) {
    return 0;
  }
  const std::string again = ff::sceneToJson(scene, ".").dump();
  ff::SceneDesc r;
  try {
    r = ff::parseScene(again, "rewritten.json", "");
  } catch (const ff::Error& e) {
    check(false);  // the writer wrote a scene its reader refuses
  }
  check(r.fluidCount() == scene.fluidCount());
  check(r.schedule.size() == scene.schedule.size());
  check(r.region.kind == scene.region.kind);
  check(r.params.fluid.time_step == scene.params.fluid.time_step);
  check(r.duration == scene.duration);
  check(r.camera.has_value() == scene.camera.has_value());
  return 0;
}
