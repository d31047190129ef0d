// The program's usage, exit codes for usage errors, and the progress line.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "app/progress.h"
#include "cli_run.h"

namespace {

int countLines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(CliUsage, BareProgramPrintsUsageAndExitsZero) {
  fftest::CliResult r = fftest::runFlowform("");
  EXPECT_EQ(r.code, 0) << r.out;
  // Named as the README writes it (it read "Usage: [OPTIONS]": no program name).
  EXPECT_NE(r.out.find("Usage: flowform [OPTIONS] [SUBCOMMAND]"), std::string::npos) << r.out;
  for (const char* cmd : {"run", "devices", "view", "render", "bench"})
    EXPECT_NE(r.out.find(cmd), std::string::npos) << cmd << "\n" << r.out;
  // It did not start a run.
  EXPECT_EQ(r.out.find("fluid particles"), std::string::npos) << r.out;
}

TEST(CliUsage, UnknownCommandIsOneLineAndExitCode2) {
  fftest::CliResult r = fftest::runFlowform("rn scenes/default.json");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(countLines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("unknown command 'rn'"), std::string::npos) << r.out;
}

TEST(CliUsage, BadOptionIsAUsageErrorWithExitCode2) {
  fftest::CliResult r = fftest::runFlowform("run --steps 1 --no-such-option");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--no-such-option"), std::string::npos) << r.out;
}

TEST(CliUsage, HelpExitsZero) {
  fftest::CliResult r = fftest::runFlowform("run --help");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("Usage: flowform run [OPTIONS] [scene]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--seconds"), std::string::npos) << r.out;
}

TEST(CliUsage, RunWithoutSceneRunsTheDefaultSceneWithProgress) {
  // The README's first command, `flowform run`, shortened to 3 steps.
  fftest::CliResult r = fftest::runFlowform("run --backend cpu --steps 3");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("scene 'default'"), std::string::npos) << r.out;
  // Not a terminal: plain lines, the last at 100% (3 steps of 0.004 s).
  EXPECT_NE(r.out.find("100.0%  t=0.012/0.012 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("steps/s  done in"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\r'), std::string::npos) << r.out;
}

TEST(Progress, LineShowsPercentTimeRateAndEta) {
  ff::app::Progress p("  run", 100, 0.004, 1.0, stdout, false);
  // 50 of 100 steps in 2 s: 25 steps/s, 50 left -> 2 s.
  EXPECT_EQ(p.line(50, 1.2, 2.0), "  run  50.0%  t=1.200/1.400 s  25.0 steps/s  ETA 0:02");
  // 30 of 100 steps in 100 s: 70 left at 0.3 steps/s -> 233.3 s = 3:53.
  EXPECT_EQ(p.line(30, 1.12, 100.0), "  run  30.0%  t=1.120/1.400 s  0.3 steps/s  ETA 3:53");
  EXPECT_EQ(p.line(100, 1.4, 3700.0), "  run 100.0%  t=1.400/1.400 s  0.0 steps/s  done in 1:01:40");
}

TEST(Progress, TerminalLineRewritesItself) {
  FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ff::app::Progress p("  run", 4, 0.5, 0.0, f, true);
    p.finish(4, 2.0);
  }
  std::rewind(f);
  std::string text;
  char buf[256];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) text.append(buf, n);
  std::fclose(f);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.front(), '\r');                              // back to column 0
  EXPECT_NE(text.find("\033[K"), std::string::npos) << text;  // clears the rest of the old line
  EXPECT_EQ(text.back(), '\n');                               // the final line ends
  EXPECT_NE(text.find("100.0%  t=2.000/2.000 s"), std::string::npos) << text;
}

}  // namespace
