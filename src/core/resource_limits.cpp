// resource_limits.cpp - the memory limit and its checks.
#include "core/resource_limits.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace ff {

namespace {

ResourceLimits& current() {
  static ResourceLimits limits = machineMemoryLimit();
  return limits;
}

double rlimitBytes(int resource) {
  struct rlimit rl;
  if (getrlimit(resource, &rl) != 0 || rl.rlim_cur == RLIM_INFINITY) return INFINITY;
  return double(rl.rlim_cur);
}

double cgroupBytes() {
  std::ifstream in("/sys/fs/cgroup/memory.max");
  std::string text;
  if (!(in >> text) || text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return INFINITY;
  return std::strtod(text.c_str(), nullptr);
}

}  // namespace

ResourceLimits machineMemoryLimit() {
  const double pages = double(sysconf(_SC_PHYS_PAGES)), page = double(sysconf(_SC_PAGESIZE));
  ResourceLimits l;
  l.memory_bytes = pages > 0 && page > 0 ? 0.5 * pages * page : 4.0 * 1024 * 1024 * 1024;
  l.origin = "half of the machine's " + formatBytes(pages * page);
  // A process limit on the address space counts libraries, thread stacks and
  // the OpenCL runtime too: plan with half of it.
  const struct {
    double bytes;
    const char* name;
  } caps[] = {{rlimitBytes(RLIMIT_AS), "address-space limit (ulimit -v)"},
              {rlimitBytes(RLIMIT_DATA), "data limit (ulimit -d)"},
              {cgroupBytes(), "cgroup memory.max"}};
  for (const auto& c : caps) {
    if (std::isfinite(c.bytes) && 0.5 * c.bytes < l.memory_bytes) {
      l.memory_bytes = 0.5 * c.bytes;
      l.origin = std::string("half of the ") + c.name + " of " + formatBytes(c.bytes);
    }
  }
  return l;
}

const ResourceLimits& resourceLimits() {
  return current();
}

void setMemoryLimit(double bytes, const std::string& origin) {
  current() = ResourceLimits{bytes, origin};
}

std::string formatBytes(double bytes) {
  static const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
  char buf[64];
  if (!std::isfinite(bytes) || bytes >= 1024.0)
    std::snprintf(buf, sizeof buf, "%.3g %s", bytes, units[u]);
  else
    std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return buf;
}

double parseByteSize(const std::string& text, const std::string& what) {
  const char* s = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  std::string unit(end);
  unit.erase(std::remove(unit.begin(), unit.end(), ' '), unit.end());
  std::transform(unit.begin(), unit.end(), unit.begin(),
                 [](unsigned char c) { return char(std::toupper(c)); });
  if (unit.size() > 1 && unit.back() == 'B') unit.pop_back();
  if (unit.size() > 1 && unit.back() == 'I') unit.pop_back();
  double scale = 0.0;
  if (unit.empty() || unit == "B")
    scale = 1.0;
  else if (unit == "K")
    scale = 1024.0;
  else if (unit == "M")
    scale = 1024.0 * 1024.0;
  else if (unit == "G")
    scale = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "T")
    scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  if (end == s || scale == 0.0 || !std::isfinite(v) || !(v > 0.0) || !std::isfinite(v * scale))
    throw Error(what + ": must be a positive size like 4G, 512M or 2000000000 (got '" + text + "')");
  return v * scale;
}

void checkMemory(double bytes, const std::string& where, const std::string& key, const std::string& what) {
  const ResourceLimits& l = resourceLimits();
  if (bytes <= l.memory_bytes) return;
  std::string prefix = where.empty() ? std::string() : where + ": ";
  if (!key.empty()) prefix += key + ": ";
  const std::string origin =
      l.origin == "--max-memory" ? "set by --max-memory" : l.origin + "; --max-memory changes it";
  throw Error(prefix + what + " need about " + formatBytes(bytes) + " of memory, over the limit of " +
              formatBytes(l.memory_bytes) + " (" + origin + ")");
}

void checkFluidCount(double n, const std::string& where, const std::string& key) {
  std::string prefix = where.empty() ? std::string() : where + ": ";
  if (!key.empty()) prefix += key + ": ";
  char count[64];
  std::snprintf(count, sizeof count, "%.4g", n);
  if (!(n < 2147483647.0))
    throw Error(prefix + std::string(count) + " fluid particles are too many (at most 2147483646)");
  checkMemory(n * kBytesPerFluidParticle, where, key, std::string(count) + " fluid particles");
}

long runSteps(double seconds, double dt, const std::string& what) {
  char buf[160];
  if (!std::isfinite(seconds) || !(seconds > 0.0)) {
    std::snprintf(buf, sizeof buf, ": must be a finite number of seconds > 0 (got %g)", seconds);
    throw Error(what + buf);
  }
  // The fewest steps that reach `seconds`, where a count within 1e-6 of a
  // whole number (relative) is that number: the step is a float, and 4
  // steps of 0.005 s end at 0.0199999996 s, which has reached 0.02 s
  // (before, a fifth step ran).
  const double x = seconds / dt;
  const double steps = std::ceil(x - std::max(1e-9, 1e-6 * x));
  if (!(steps <= kMaxRunSteps)) {
    std::snprintf(buf, sizeof buf, ": %g s is %.3g steps of %g s, over the limit of %.3g steps", seconds,
                  steps, dt, kMaxRunSteps);
    throw Error(what + buf);
  }
  return std::max(1L, long(steps));
}

void checkThreadCount(long threads, const std::string& what) {
  if (threads >= 0 && threads <= kMaxThreads) return;
  throw Error(what + ": must be in [0, " + std::to_string(kMaxThreads) + "] (got " + std::to_string(threads) +
              "; 0: all cores)");
}

}  // namespace ff
