// temp_dir.h - a fresh folder in the system temp folder for one test, removed
// with everything in it when the TempDir goes out of scope.
#pragma once
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

namespace fftest {

class TempDir {
 public:
  // TMPDIR/flowform_test_NAME_PID_N, empty.
  explicit TempDir(const std::string& name) {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("flowform_test_" + name + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  operator const std::filesystem::path&() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // Writes `text` into NAME inside the folder; returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = path_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

 private:
  std::filesystem::path path_;
};

// A fresh folder TMPDIR/flowform_test_NAME_PID that lives until the test
// program exits (each ctest test is its own process), then is removed with
// everything in it. For helpers that hand out a plain path.
inline std::filesystem::path scratchDir(const std::string& name) {
  struct Registry {
    std::mutex mutex;
    std::vector<std::filesystem::path> paths;
    ~Registry() {
      std::error_code ec;
      for (const auto& p : paths) std::filesystem::remove_all(p, ec);
    }
  };
  static Registry registry;
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("flowform_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  std::lock_guard<std::mutex> lock(registry.mutex);
  registry.paths.push_back(d);
  return d;
}

}  // namespace fftest
