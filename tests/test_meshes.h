// test_meshes.h - where the tests find the shared meshes (bunny, dragon, ...):
// the folders of FLOWFORM_MESH_PATH first, then ../shared/meshes beside the
// source tree. A test that needs one and finds none skips with a message
// (FF_MESH_OR_SKIP); ctest counts it as skipped, not passed.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

namespace fftest {

// The path of mesh file `name`, or "" when no folder has it.
inline std::string findMesh(const std::string& name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (const char* env = std::getenv("FLOWFORM_MESH_PATH")) {
    std::stringstream folders(env);
    std::string folder;
    while (std::getline(folders, folder, ':'))
      if (!folder.empty() && fs::is_regular_file(fs::path(folder) / name, ec))
        return (fs::path(folder) / name).string();
  }
  const fs::path shared = fs::path(FF_SHARED_MESHES) / name;
  return fs::is_regular_file(shared, ec) ? shared.string() : std::string();
}

}  // namespace fftest

// Declares `const std::string var` = the path of mesh `name`, or skips the test.
#define FF_MESH_OR_SKIP(var, name)                                                                   \
  const std::string var = fftest::findMesh(name);                                                    \
  if (var.empty())                                                                                   \
  GTEST_SKIP() << "mesh " << (name) << " not found: set FLOWFORM_MESH_PATH to a folder holding it, " \
               << "or put the meshes in ../shared/meshes beside the source tree"
