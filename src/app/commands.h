// commands.h - the subcommands of the flowform program.
#pragma once
#include <CLI/CLI.hpp>

namespace ff::app {

// Each adds its subcommand to `app`; the returned function runs it and gives
// the process exit code.
std::function<int()> addRunCommand(CLI::App& app);
std::function<int()> addDevicesCommand(CLI::App& app);
std::function<int()> addViewCommand(CLI::App& app);    // cmd_view.cpp
std::function<int()> addRenderCommand(CLI::App& app);  // cmd_render.cpp
std::function<int()> addBenchCommand(CLI::App& app);   // cmd_bench.cpp

}  // namespace ff::app
