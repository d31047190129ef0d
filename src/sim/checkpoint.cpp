#include "sim/checkpoint.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.h"
#include "scene/scene_state.h"

namespace ff {

namespace {

constexpr char kMagic[8] = {'F', 'F', 'C', 'K', 'P', 'T', '\r', '\n'};
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;
// Checkpoints above this are refused before reading (a corrupted size field
// must not allocate without bound).
constexpr uint64_t kMaxPayload = uint64_t(16) << 30;

uint32_t layout() {
  return uint32_t(sizeof(Params) * 1009u + sizeof(StepMetrics));
}

uint64_t fnv1a(const char* p, size_t n) {
  uint64_t h = 14695981039346656037ull;  // FNV-1a 64's offset basis (0xcbf29ce484222325)
  for (size_t i = 0; i < n; ++i) {
    h ^= uint8_t(p[i]);
    h *= 1099511628211ull;
  }
  return h;
}

// Whether `path` is an existing folder or ends in a separator (".", "out/"):
// given as a checkpoint file, the folder is named as such (renaming onto "."
// said "Device or resource busy").
bool namesAFolder(const std::string& path) {
  std::error_code ec;
  return (!path.empty() && path.back() == '/') || std::filesystem::is_directory(path, ec);
}

}  // namespace

void writeCheckpoint(const std::string& path, const Simulation& sim) {
  StateWriter w;
  writeSceneState(w, sim.scene());
  sim.saveState(w);
  const std::vector<char>& payload = w.data();
  StateWriter head;
  head.bytes(kMagic, sizeof(kMagic));
  head.pod(uint32_t(kCheckpointVersion));
  head.pod(layout());
  head.pod(uint64_t(payload.size()));
  head.pod(fnv1a(payload.data(), payload.size()));

  if (namesAFolder(path))
    throw Error(path + ": cannot write the checkpoint: this is a folder; give a file name (e.g. run.ffck)");
  const std::string tmp = path + ".part";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw Error(path + ": cannot write the checkpoint: " + std::strerror(errno));
  bool ok = std::fwrite(head.data().data(), 1, head.data().size(), f) == head.data().size() &&
            std::fwrite(payload.data(), 1, payload.size(), f) == payload.size();
  const int err = errno;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) {
    std::remove(tmp.c_str());
    throw Error(path + ": cannot write the checkpoint: " + std::strerror(err));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw Error(path + ": cannot write the checkpoint: " + ec.message());
  }
}

std::unique_ptr<Simulation> loadCheckpoint(const std::string& path, std::unique_ptr<Backend> backend) {
  if (namesAFolder(path))
    throw Error(path + ": cannot open the checkpoint: this is a folder; give a checkpoint file (.ffck)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the checkpoint: " + std::strerror(errno));
  char head[kHeaderBytes];
  if (!in.read(head, sizeof(head)) || std::memcmp(head, kMagic, sizeof(kMagic)) != 0)
    throw Error(path + ": not a flowform checkpoint (no FFCKPT header)");
  StateReader h(head + sizeof(kMagic), sizeof(head) - sizeof(kMagic), path);
  const uint32_t version = h.pod<uint32_t>(), lay = h.pod<uint32_t>();
  const uint64_t size = h.pod<uint64_t>(), sum = h.pod<uint64_t>();
  if (version != kCheckpointVersion || lay != layout())
    throw Error(path + ": the checkpoint was written by another version of flowform (format " +
                std::to_string(version) + ", layout " + std::to_string(lay) + "; this program reads format " +
                std::to_string(kCheckpointVersion) + ", layout " + std::to_string(layout()) + ")");
  std::error_code ec;
  const uintmax_t file_size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxPayload || file_size != kHeaderBytes + size)
    throw Error(path + ": the checkpoint is truncated or corrupted (the file has " +
                (ec ? std::string("an unknown size") : std::to_string(file_size) + " bytes") +
                ", its header says " + std::to_string(kHeaderBytes + size) + ")");
  std::vector<char> payload(static_cast<size_t>(size));
  if (!in.read(payload.data(), std::streamsize(size)))
    throw Error(path + ": the checkpoint is truncated (cannot read " + std::to_string(size) + " bytes)");
  if (fnv1a(payload.data(), payload.size()) != sum)
    throw Error(path + ": the checkpoint is corrupted (its checksum does not match)");
  StateReader r(payload.data(), payload.size(), path);
  SceneDesc scene = readSceneState(r);
  return std::make_unique<Simulation>(std::move(scene), std::move(backend), r);
}

}  // namespace ff
