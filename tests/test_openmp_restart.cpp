// The restart of `run` and `bench` with libgomp's wait policy set
// (src/app/main.cpp): the policy reaches the OpenMP runtime, and a binding
// the user chose keeps every CPU it had (libgomp's OMP_DISPLAY_ENV shows what
// each start of the program read).
#include <gtest/gtest.h>
#include <sched.h>

#include <string>
#include <vector>

#include "cli_run.h"

namespace {

// The values of `name` in each OMP_DISPLAY_ENV block of `out`, in order.
std::vector<std::string> displayed(const std::string& out, const std::string& name) {
  std::vector<std::string> v;
  const std::string key = "  " + name + " = '";
  for (size_t at = out.find(key); at != std::string::npos; at = out.find(key, at + 1)) {
    const size_t b = at + key.size(), e = out.find('\'', b);
    if (e == std::string::npos) break;
    v.push_back(out.substr(b, e - b));
  }
  return v;
}

// The places of an OMP_PLACES value such as "{0},{1}" or "{0:2}".
int placeCount(const std::string& places) {
  int n = 0;
  for (char c : places) n += c == '{' ? 1 : 0;
  return n;
}

TEST(OpenMpRestart, RunAndBenchTakeThePassivePolicy) {
  for (const char* cmd : {"bench --help", "run --help"}) {
    const fftest::CliResult r = fftest::runFlowform(cmd, "OMP_DISPLAY_ENV=true");
    EXPECT_EQ(r.code, 0) << cmd << "\n" << r.out;
    const std::vector<std::string> policy = displayed(r.out, "OMP_WAIT_POLICY");
    ASSERT_FALSE(policy.empty()) << cmd << "\n" << r.out;
    EXPECT_EQ(policy.back(), "PASSIVE") << cmd << "\n" << r.out;
  }
}

// With OMP_PROC_BIND and OMP_PLACES set, the restart ran on the one CPU that
// libgomp had bound the first start to: OMP_PLACES read '{0}' after the
// restart where the first start read '{0},{1}'.
TEST(OpenMpRestart, ABindingKeepsEveryCpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  ASSERT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
  if (CPU_COUNT(&set) < 2) GTEST_SKIP() << "one CPU: a binding cannot narrow it";
  for (const char* env : {"OMP_PROC_BIND=true OMP_PLACES=cores", "OMP_PROC_BIND=close OMP_PLACES=threads"}) {
    const fftest::CliResult r =
        fftest::runFlowform("bench --help", std::string("OMP_DISPLAY_ENV=true ") + env);
    EXPECT_EQ(r.code, 0) << env << "\n" << r.out;
    const std::vector<std::string> places = displayed(r.out, "OMP_PLACES");
    ASSERT_FALSE(places.empty()) << env << "\n" << r.out;
    for (const std::string& p : places) EXPECT_EQ(placeCount(p), CPU_COUNT(&set)) << env << ": " << p;
  }
}

}  // namespace
