// progress.h - the progress of a long command: percent, simulated time,
// steps per second and an estimate of the time left.
//
// On a terminal it is one line that rewrites itself; otherwise (a log, a pipe)
// it prints plain lines. Either way it shows at most every `interval` wall
// seconds and at least once per wall second while steps keep coming.
#pragma once
#include <chrono>
#include <cstdio>
#include <string>

namespace ff::app {

class Progress {
 public:
  // `total` steps of `dt` simulated seconds, starting at `start_time`.
  // `tty`: rewrite one line ('\r'); default: whether `out` is a terminal.
  Progress(std::string label, long total, double dt, double start_time = 0.0, FILE* out = stdout);
  Progress(std::string label, long total, double dt, double start_time, FILE* out, bool tty);

  // Called after each step: `done` of the total steps, simulated time `time`.
  void update(long done, double time);
  // Before other output: clears the rewritten line on a terminal, so that the
  // next line starts in column 0; the progress line returns at the next update.
  void interrupt();
  // The last line (100% or wherever it stopped), ends the terminal line.
  void finish(long done, double time);

  // The text of one progress line (no line end), for the given wall seconds.
  std::string line(long done, double time, double wall_seconds) const;

 private:
  void show(long done, double time, bool final);

  std::string label_;
  long total_;
  double dt_, start_time_;
  FILE* out_;
  bool tty_;
  bool showing_ = false;  // a rewritten line is on the terminal now
  bool finished_ = false;
  std::chrono::steady_clock::time_point t0_, last_;
};

// "m:ss" or "h:mm:ss".
std::string clockText(double seconds);

}  // namespace ff::app
