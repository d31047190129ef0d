// fluid_mode.h - how the fluid is drawn, and its names: one list for
// `flowform render --mode` and a viewer script's `render` action.
#pragma once
#include <optional>
#include <string>

namespace ff::render {

enum class FluidMode { ScreenSpace, Particles };

// The names a user gives, for messages.
inline constexpr const char* kFluidModeNames = "\"fluid\" (or \"screen_space\") or \"particles\"";

// "fluid", or its old script name "screen_space": the screen-space liquid
// surface; "particles": one lit sphere per particle; nullopt otherwise.
inline std::optional<FluidMode> fluidModeByName(const std::string& name) {
  if (name == "fluid" || name == "screen_space") return FluidMode::ScreenSpace;
  if (name == "particles") return FluidMode::Particles;
  return std::nullopt;
}

}  // namespace ff::render
