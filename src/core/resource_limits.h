// resource_limits.h - how much memory a run may plan to use, and the
// estimates checked against it before anything large is allocated (fluid
// particles, control particles, voxel grids, cluster memberships).
//
// The default limit follows from the machine: half of the physical memory, or
// less where the process runs under a smaller limit (RLIMIT_AS, RLIMIT_DATA,
// the cgroup's memory.max). `--max-memory` overrides it.
#pragma once
#include <string>

namespace ff {

// Bytes one item of each kind costs, rounded up from the peak RSS of
// `flowform run --steps 2` (2026-11-29, 2-core Xeon): 10^6 fluid particles
// took 93 MB on the CPU backend and 360 MB on OpenCL (PoCL); 10^6 control
// particles in 27 clusters each over 1.25 10^5 fluid particles took 304 MB.
// Estimates multiply these by the counts.
constexpr double kBytesPerFluidParticle = 400.0;
constexpr double kBytesPerControlParticle = 150.0;
constexpr double kBytesPerVoxel = 8.0;              // the grid and three ray-parity passes
constexpr double kBytesPerClusterMembership = 8.0;  // member and reverse lists, while built
// The most clusters one control particle may belong to (work per
// shape-matching step grows with it).
constexpr double kMaxClustersPerParticle = 4096.0;
// The most steps one run may ask for (--seconds, --steps, "duration").
constexpr double kMaxRunSteps = 1e8;
// The most OpenMP threads a run may ask for (--threads, Python's threads=):
// 100000 crashed OpenMP's thread creation (a segfault, 2026-11-30).
constexpr int kMaxThreads = 1024;

struct ResourceLimits {
  double memory_bytes = 0.0;
  std::string origin;  // where the limit comes from, for messages
};

// The limit in force (computed from the machine on first use).
const ResourceLimits& resourceLimits();
// Overrides the limit (the --max-memory flag). `origin` names the flag.
void setMemoryLimit(double bytes, const std::string& origin);
// The default limit of this machine and process.
ResourceLimits machineMemoryLimit();

// "12.3 GiB", "512 MiB", "800 B".
std::string formatBytes(double bytes);
// Parses "4G", "512M", "1.5GiB", "2000000000" (bytes). Throws ff::Error naming `what`.
double parseByteSize(const std::string& text, const std::string& what);

// Throws ff::Error "WHERE: KEY: WHAT needs about X of memory, over the limit
// of Y (ORIGIN; --max-memory raises it)" when `bytes` is over the limit.
// `where` is the file (may be empty), `key` the setting responsible.
void checkMemory(double bytes, const std::string& where, const std::string& key, const std::string& what);

// Throws unless `n` fluid particles fit in memory (and in 32-bit indices).
void checkFluidCount(double n, const std::string& where, const std::string& key);

// The number of steps of `dt` that `seconds` make: the fewest that reach it,
// a count within 1e-6 (relative) of a whole number taken as that number (dt
// is a float: 0.005 is 0.004999999888). Throws ff::Error starting
// with `what` (e.g. "scene.json: duration", "--seconds") unless `seconds` is
// finite and > 0 and the run has at most kMaxRunSteps steps.
long runSteps(double seconds, double dt, const std::string& what);
// Throws ff::Error "WHAT: must be in [0, kMaxThreads] (got N)" for a thread
// count outside that range (0: OpenMP's default).
void checkThreadCount(long threads, const std::string& what);

// runSteps, for its checks only.
inline void checkRunLength(double seconds, double dt, const std::string& what) {
  (void)runSteps(seconds, dt, what);
}

}  // namespace ff
