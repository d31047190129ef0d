// kernels_option.h - the `--kernels auto|scalar|lanes` option of run, bench,
// view and render (setKernelChoice in host/backend_factory.h).
#pragma once
#include <CLI/CLI.hpp>

namespace ff::app {

void addKernelsOption(CLI::App* cmd);

}  // namespace ff::app
