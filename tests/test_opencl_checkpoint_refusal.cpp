// The OpenCL backend cannot write checkpoints (only the OpenMP backend can):
// `flowform run --backend opencl` says so before it starts when asked for
// --checkpoint-every, and a SIGTERM stops the run cleanly with one line that
// says no checkpoint was written and why (not an error about checkpoints).
#include <gtest/gtest.h>

#include <string>

#include "cli_run.h"
#include "temp_dir.h"

namespace {

const char* kScene = R"({
  "container": {"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]},
  "fluid": [{"origin": [0.06, 0.0, 0.06], "dims": [8, 8, 8]}],
  "target": "sphere"
})";

TEST(OpenClCheckpoints, CheckpointEveryIsRefusedBeforeTheRun) {
  const fftest::TempDir d("ocl_ckpt_every");
  const std::string scene = d.write("s.json", kScene).string();
  const fftest::CliResult r = fftest::runFlowform(
      "run '" + scene + "' --backend opencl --steps 5 --checkpoint-every 0.01 --checkpoint '" +
      (d / "ck").string() + "'");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(
      r.out.find("flowform: error: --checkpoint-every: the opencl backend cannot write checkpoints; run "
                 "with --backend cpu"),
      std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("steps of"), std::string::npos) << "the run started: " << r.out;
}

TEST(OpenClCheckpoints, SigtermStopsWithAClearLine) {
  const fftest::TempDir d("ocl_ckpt_term");
  const std::string scene = d.write("s.json", kScene).string();
  const std::string csv = (d / "m.csv").string(), log = (d / "log").string();
  // A long run; once it has written a few metrics rows, SIGTERM.
  const std::string script = "'" + std::string(FF_FLOWFORM_EXE) + "' run '" + scene +
                             "' --backend opencl --seconds 1000 --metrics '" + csv + "' > '" + log +
                             "' 2>&1 & p=$!; i=0; "
                             "while [ \"$(wc -l < '" +
                             csv +
                             "' 2>/dev/null || echo 0)\" -lt 5 ] && [ $i -lt 1200 ]; "
                             "do sleep 0.05; i=$((i+1)); done; kill -TERM $p; wait $p; echo rc=$?; cat '" +
                             log + "'";
  const fftest::CliResult r = fftest::runShell(script);
  EXPECT_NE(r.out.find("rc=143"), std::string::npos) << r.out;  // 128 + SIGTERM
  EXPECT_NE(r.out.find("flowform: stopped by SIGTERM at step "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; no checkpoint: the opencl backend cannot write checkpoints (--backend cpu can)"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("flowform: error"), std::string::npos) << r.out;
}

}  // namespace
