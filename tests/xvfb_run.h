// xvfb_run.h - runs a command line under xvfb-run for the viewer's tests and
// gives the command's own exit status.
//
// xvfb-run exits with the status of the program it ran, except when its own
// cleanup fails afterwards: "xvfb-run: error: problem while cleaning up
// temporary directory" turns the status into 5 (seen twice in CI, once on a
// viewer that had exited 1 as it should). So the shell that runs the command
// under xvfb-run writes the command's status to a file, and the tests assert on
// that; xvfb-run's own status only matters when no status was written.
#pragma once
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "temp_dir.h"

namespace fftest {

inline bool haveXvfb() {
  return runShell("command -v xvfb-run && command -v xauth").code == 0;
}

// Runs `cmd` (a shell command line) under `timeout 180 xvfb-run` with a screen
// of 1024x768x24. -a takes the first free display from `first_display` on;
// callers give each test (and process) its own start so that tests run in
// parallel do not race for the same display. The script and the status file
// go into `dir`. The result's code is the command's exit status (128 + N for a
// signal N), or -1 when the command never finished (xvfb-run failed to start
// or the time limit struck); its output is everything printed.
inline CliResult runUnderXvfb(const TempDir& dir, int first_display, const std::string& cmd) {
  static std::atomic<int> counter{0};
  const std::string stem = "xvfb_run_" + std::to_string(counter++);
  const std::filesystem::path script = dir / (stem + ".sh");
  const std::filesystem::path status = dir / (stem + ".status");
  std::ofstream(script) << cmd << " 2>&1\necho $? > '" << status.string() << "'\n";
  CliResult r = runShell("timeout 180 xvfb-run -a -n " + std::to_string(first_display) +
                         " -s '-screen 0 1024x768x24' sh '" + script.string() + "'");
  const int xvfb_code = r.code;
  std::ifstream in(status);
  int code = -1;
  if (in >> code) {
    r.code = code;
  } else {
    r.code = -1;
    r.out += "\n[test] the command under xvfb-run wrote no exit status; xvfb-run exited " +
             std::to_string(xvfb_code) + "\n";
  }
  return r;
}

}  // namespace fftest
