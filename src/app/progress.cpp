#include "app/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace ff::app {

namespace {
// Shown at most this often (seconds); at least once per wall second.
constexpr double kTtyInterval = 0.25;
constexpr double kLineInterval = 0.9;
}  // namespace

std::string clockText(double seconds) {
  const long s = long(std::lround(std::max(seconds, 0.0)));
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof(buf), "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof(buf), "%ld:%02ld", s / 60, s % 60);
  return buf;
}

Progress::Progress(std::string label, long total, double dt, double start_time, FILE* out)
    : Progress(std::move(label), total, dt, start_time, out, ::isatty(::fileno(out)) == 1) {}

Progress::Progress(std::string label, long total, double dt, double start_time, FILE* out, bool tty)
    : label_(std::move(label)),
      total_(std::max(total, 0L)),
      dt_(dt),
      start_time_(start_time),
      out_(out),
      tty_(tty),
      t0_(std::chrono::steady_clock::now()),
      last_(t0_) {}

std::string Progress::line(long done, double time, double wall) const {
  const double pct = total_ > 0 ? 100.0 * double(done) / double(total_) : 100.0;
  const double end_time = start_time_ + double(total_) * dt_;
  const double rate = wall > 0.0 ? double(done) / wall : 0.0;
  char buf[256];
  if (done >= total_)
    std::snprintf(buf, sizeof(buf), "%s %5.1f%%  t=%.3f/%.3f s  %.1f steps/s  done in %s", label_.c_str(),
                  pct, time, end_time, rate, clockText(wall).c_str());
  else if (rate > 0.0)
    std::snprintf(buf, sizeof(buf), "%s %5.1f%%  t=%.3f/%.3f s  %.1f steps/s  ETA %s", label_.c_str(), pct,
                  time, end_time, rate, clockText(double(total_ - done) / rate).c_str());
  else
    std::snprintf(buf, sizeof(buf), "%s %5.1f%%  t=%.3f/%.3f s  - steps/s  ETA -", label_.c_str(), pct, time,
                  end_time);
  return buf;
}

void Progress::show(long done, double time, bool final) {
  const auto now = std::chrono::steady_clock::now();
  const std::string text = line(done, time, std::chrono::duration<double>(now - t0_).count());
  if (tty_) {
    // \r back to column 0, the text, then clear whatever a longer line left.
    std::fprintf(out_, "\r%s\033[K%s", text.c_str(), final ? "\n" : "");
    showing_ = !final;
  } else {
    std::fprintf(out_, "%s\n", text.c_str());
  }
  std::fflush(out_);
  last_ = now;
}

void Progress::update(long done, double time) {
  if (finished_) return;
  const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count();
  if (since >= (tty_ ? kTtyInterval : kLineInterval)) show(done, time, false);
}

void Progress::interrupt() {
  if (tty_ && showing_) {
    std::fprintf(out_, "\r\033[K");
    std::fflush(out_);
    showing_ = false;
    last_ = std::chrono::steady_clock::time_point();  // redraw at the next update
  }
}

void Progress::finish(long done, double time) {
  if (finished_) return;
  show(done, time, true);
  finished_ = true;
}

}  // namespace ff::app
