// cli_run.h - runs the built flowform program as a user would, for the tests
// of its commands: exit code and everything it printed.
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "temp_dir.h"
#include "test_meshes.h"

namespace fftest {

struct CliResult {
  int code = -1;
  std::string out;  // stdout and stderr together
};

// Runs a shell command line; stdout and stderr together.
inline CliResult runShell(const std::string& cmd) {
  CliResult r;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), p)) > 0) r.out.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Exit codes of a refusal: 1 for an error the program reports, 2 for a usage
// error (a bad option). A crash is neither: runShell gives -1 for a signal.
inline bool isRefusal(int code) {
  return code == 1 || code == 2;
}

// Runs `flowform ARGS` with FLOWFORM_MESH_PATH at the folders the tests search
// for meshes (test_meshes.h); `env` holds further assignments for its
// environment (e.g. "PATH=/nonexistent "), which may override FLOWFORM_MESH_PATH.
inline CliResult runFlowform(const std::string& args, const std::string& env = "") {
  return runShell("FLOWFORM_MESH_PATH='" + meshSearchPath() + "' " + env + " '" +
                  std::string(FF_FLOWFORM_EXE) + "' " + args);
}

}  // namespace fftest
