// atomic_file.cpp - write to PATH.tmp, rename into place.
#include "io/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace ff {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int err) {
  throw Error(path + ": " + what + " (" + std::strerror(err) + ")");
}

}  // namespace

void writeFileAtomically(const std::string& path, const char* kind,
                         std::initializer_list<std::string_view> parts) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) fail(path, std::string("cannot create ") + kind, errno);
  bool ok = true;
  for (std::string_view p : parts) ok = ok && std::fwrite(p.data(), 1, p.size(), f) == p.size();
  int err = ok ? 0 : errno;
  if (std::fclose(f) != 0 && ok) {
    ok = false;
    err = errno;
  }
  if (!ok) {
    std::remove(tmp.c_str());
    fail(path, std::string("cannot write ") + kind, err);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    err = errno;
    std::remove(tmp.c_str());
    fail(path, std::string("cannot rename the ") + kind + " into place", err);
  }
}

}  // namespace ff
