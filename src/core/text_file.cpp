#include "core/text_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace ff {

std::string readTextFile(const std::string& path, const std::string& what) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error(path + ": cannot open " + what + " file (" + std::strerror(errno) + ")");
  std::string text;
  char buf[65536];
  size_t got;
  while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) {
    text.append(buf, got);
    if (text.size() > kMaxTextFileBytes) {
      std::fclose(f);
      throw Error(path + ": the " + what + " file is larger than " + std::to_string(kMaxTextFileBytes >> 20) +
                  " MiB; a " + what + " is a small JSON text file");
    }
  }
  const int err = std::ferror(f) ? errno : 0;
  std::fclose(f);
  if (err != 0 || (text.empty() && std::filesystem::is_directory(path)))
    throw Error(path + ": cannot open " + what + " file (" + std::strerror(err != 0 ? err : EISDIR) + ")");
  return text;
}

}  // namespace ff
