// fuzz_script.cpp - libFuzzer target: the viewer script reader (parseScript).
// Any input must give a Script or an ff::Error.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "viewer/script.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const ff::viewer::Script s = ff::viewer::parseScript(text, "fuzz.json", "");
    ff::Params p;
    for (const ff::viewer::ScriptAction& a : s.actions) ff::viewer::applyParamsAction(a, p);
  } catch (const ff::Error&) {
  }
  return 0;
}
