// bench_report.h - what `flowform bench` prints and writes: a markdown table,
// the CSV (scene,backend,device,fluid,control,phase,ms_median,ms_min,ms_max;
// one row per phase, a `total` row, then one row per named stage inside a
// phase, "PHASE/STAGE", with its mean ms per step as ms_median and ms_min,
// ms_max empty) and PNG plots.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench_runner.h"

namespace ff::app {

// One markdown table: a row per result, a column per phase (medians), the
// total with its min-max, the substeps and the backend's bytes per fluid particle.
void printMarkdown(std::FILE* out, const std::string& title, const std::vector<BenchResult>& results);

// Writes the CSV. Throws ff::Error naming the file when it cannot be written.
void writeBenchCsv(const std::string& path, const std::vector<BenchResult>& results);

// Plots the CSV with python3 + matplotlib (Debian's python3-matplotlib) into
// PNG files next to it (<stem>_table1.png, <stem>_fluid.png, <stem>_control.png,
// each only when the CSV has such rows). Returns the files written. Throws
// ff::Error saying what to install when python3 or matplotlib is missing.
std::vector<std::string> plotBenchCsv(const std::string& csv_path);

}  // namespace ff::app
