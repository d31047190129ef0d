// png_writer.cpp - RGBA8 frames to PNG files (stb_image_write, from libstb).
#include <stb_image_write.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "render/offscreen_context.h"

namespace ff::render {

void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba) {
  if (width < 1 || height < 1 || rgba.size() != size_t(width) * size_t(height) * 4)
    throw Error(path + ": cannot write PNG: " + std::to_string(rgba.size()) + " bytes do not make a " +
                std::to_string(width) + " x " + std::to_string(height) + " RGBA image");
  errno = 0;
  if (!stbi_write_png(path.c_str(), width, height, 4, rgba.data(), width * 4)) {
    const int e = errno;
    throw Error(path + ": cannot write PNG" + (e ? std::string(": ") + std::strerror(e) : std::string()));
  }
}

}  // namespace ff::render
