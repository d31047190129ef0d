// test_meshes.h - where the tests find the shared meshes (bunny, dragon, ...):
// the folders of FLOWFORM_MESH_PATH first, then ../shared/meshes beside the
// source tree. Setting FLOWFORM_TEST_NO_SHARED_MESHES=1 leaves the latter out,
// to run the suite as on a machine without the meshes. A test that needs one
// and finds none skips with a message (FF_MESH_OR_SKIP); ctest counts it as
// skipped, not passed, and prints the count.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fftest {

// The folders searched, in order.
inline std::vector<std::string> meshFolders() {
  std::vector<std::string> out;
  if (const char* env = std::getenv("FLOWFORM_MESH_PATH")) {
    std::stringstream folders(env);
    std::string folder;
    while (std::getline(folders, folder, ':'))
      if (!folder.empty()) out.push_back(folder);
  }
  const char* no_shared = std::getenv("FLOWFORM_TEST_NO_SHARED_MESHES");
  if (!no_shared || std::string(no_shared).empty() || std::string(no_shared) == "0")
    out.push_back(FF_SHARED_MESHES);
  return out;
}

// The same folders as one FLOWFORM_MESH_PATH value, for the program under test.
inline std::string meshSearchPath() {
  std::string path;
  for (const std::string& f : meshFolders()) path += (path.empty() ? "" : ":") + f;
  return path;
}

// The path of mesh file `name`, or "" when no folder has it.
inline std::string findMesh(const std::string& name) {
  std::error_code ec;
  for (const std::string& folder : meshFolders()) {
    const std::filesystem::path p = std::filesystem::path(folder) / name;
    if (std::filesystem::is_regular_file(p, ec)) return p.string();
  }
  return std::string();
}

// The first mesh named by scenes/*.json that no folder has, or "".
inline std::string missingSceneMesh() {
  for (const char* name : {"bunny.obj", "teapot.obj", "runner.obj", "dragon.obj"})
    if (findMesh(name).empty()) return name;
  return std::string();
}

// Sets (or, with nullptr, removes) an environment variable until it goes out
// of scope, then restores the old value.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) had_ = true, old_ = old;
    if (value)
      setenv(name, value, 1);
    else
      unsetenv(name);
  }
  ~ScopedEnv() {
    if (had_)
      setenv(name_.c_str(), old_.c_str(), 1);
    else
      unsetenv(name_.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_, old_;
  bool had_ = false;
};

}  // namespace fftest

// Declares `const std::string var` = the path of mesh `name`, or skips the test.
#define FF_MESH_OR_SKIP(var, name)                                                                   \
  const std::string var = fftest::findMesh(name);                                                    \
  if (var.empty())                                                                                   \
  GTEST_SKIP() << "mesh " << (name) << " not found: set FLOWFORM_MESH_PATH to a folder holding it, " \
               << "or put the meshes in ../shared/meshes beside the source tree"

// Skips the test unless every mesh that the repository's scenes name is
// found; then points FLOWFORM_MESH_PATH at the folders searched until the end
// of the test (declares `mesh_env`).
#define FF_SCENE_MESHES_OR_SKIP()                                                                      \
  if (const std::string ff_missing = fftest::missingSceneMesh(); !ff_missing.empty())                  \
    GTEST_SKIP() << "mesh " << ff_missing << " not found: set FLOWFORM_MESH_PATH to a folder holding " \
                 << "it, or put the meshes in ../shared/meshes beside the source tree";                \
  const fftest::ScopedEnv mesh_env("FLOWFORM_MESH_PATH", fftest::meshSearchPath().c_str())
