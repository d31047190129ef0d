#include "app/run_checkpoints.h"

#include <csignal>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "sim/checkpoint.h"

namespace ff::app {

namespace {
volatile std::sig_atomic_t g_stop = 0;
extern "C" void onStopSignal(int sig) {
  g_stop = sig;
}
void (*g_old_int)(int) = SIG_DFL;
void (*g_old_term)(int) = SIG_DFL;
}  // namespace

StopSignals::StopSignals() {
  g_stop = 0;
  g_old_int = std::signal(SIGINT, onStopSignal);
  g_old_term = std::signal(SIGTERM, onStopSignal);
}

StopSignals::~StopSignals() {
  std::signal(SIGINT, g_old_int == SIG_ERR ? SIG_DFL : g_old_int);
  std::signal(SIGTERM, g_old_term == SIG_ERR ? SIG_DFL : g_old_term);
}

int StopSignals::caught() const {
  return int(g_stop);
}

Checkpoints::Checkpoints(std::string dir, double every, double now)
    : dir_(std::move(dir)), every_(every), next_(every > 0.0 ? now + every : 0.0) {}

std::string Checkpoints::due(const Simulation& sim) {
  if (every_ <= 0.0 || sim.time() < next_ - 1e-9) return "";
  while (next_ <= sim.time() + 1e-9) next_ += every_;
  return write(sim);
}

std::string Checkpoints::write(const Simulation& sim) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw Error(dir_ + ": cannot create the checkpoint folder: " + ec.message());
  char name[64];
  std::snprintf(name, sizeof(name), "checkpoint_%06ld.ffck", sim.stepCount());
  const std::string path = (std::filesystem::path(dir_) / name).string();
  writeCheckpoint(path, sim);
  return path;
}

}  // namespace ff::app
