// mesh_file_checks.cpp - PLY header grammar and OFF/PLY declared counts.
#include "target/mesh_file_checks.h"

#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace ff {
namespace {

constexpr size_t kHeadBytes = 65536;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

std::string readHead(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kHeadBytes, '\0');
  in.read(&head[0], std::streamsize(kHeadBytes));
  head.resize(size_t(in.gcount()));
  return head;
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

bool isCount(const std::string& s) {
  return !s.empty() && s.size() <= 18 && s.find_first_not_of("0123456789") == std::string::npos;
}

// Size in bytes of a PLY scalar type, 0 if it is not one.
uintmax_t plyTypeSize(const std::string& t) {
  static const std::pair<const char*, int> kTypes[] = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& type : kTypes) {
    if (t == type.first) return uintmax_t(type.second);
  }
  return 0;
}

// Strict PLY header grammar; the data must hold at least one byte per ASCII
// value, or the fixed part of every binary element.
void checkPly(const std::string& path, const std::string& head, uintmax_t file_size) {
  auto garbled = [&path](size_t line_no, const std::string& why) {
    fail(path, "garbled PLY header (line " + std::to_string(line_no) + "): " + why);
  };
  size_t pos = 0, line_no = 0;
  bool binary = false, ended = false;
  uintmax_t minimum = 0, count = 0, element_bytes = 0;
  bool in_element = false;
  auto closeElement = [&]() {
    if (in_element) minimum += count * element_bytes;
    if (minimum > file_size)
      fail(path, "garbled or truncated PLY file: its header declares more data than the file holds");
  };
  while (!ended) {
    const size_t eol = head.find('\n', pos);
    if (eol == std::string::npos)
      fail(path, "garbled or truncated PLY file: no end_header line in its first 64 KiB");
    std::string line = head.substr(pos, eol - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = eol + 1;
    ++line_no;
    const std::vector<std::string> w = words(line);
    if (line_no == 1) {
      if (w.size() != 1 || (w[0] != "ply" && w[0] != "PLY")) garbled(line_no, "the first line must be 'ply'");
      continue;
    }
    if (line_no == 2) {
      if (w.size() != 3 || w[0] != "format" ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian")) {
        garbled(line_no, "expected 'format ascii|binary_little_endian|binary_big_endian VERSION'");
      }
      binary = w[1] != "ascii";
      continue;
    }
    if (w.empty()) garbled(line_no, "empty line");
    if (w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header" && w.size() == 1) {
      ended = true;
    } else if (w[0] == "element" && w.size() == 3 && isCount(w[2])) {
      closeElement();
      in_element = true;
      count = std::stoull(w[2]);
      element_bytes = 0;
    } else if (w[0] == "property" && in_element && w.size() == 3 && plyTypeSize(w[1]) > 0) {
      element_bytes += binary ? plyTypeSize(w[1]) : 1;
    } else if (w[0] == "property" && in_element && w.size() == 5 && w[1] == "list" && plyTypeSize(w[2]) > 0 &&
               plyTypeSize(w[3]) > 0) {
      element_bytes += binary ? plyTypeSize(w[2]) : 1;
    } else {
      garbled(line_no, "unexpected '" + line.substr(0, 60) + "'");
    }
  }
  minimum += pos;  // the header itself
  closeElement();
}

void checkOff(const std::string& path, const std::string& head, uintmax_t file_size) {
  std::istringstream in(head);
  std::string token, rest;
  while (in >> token && token[0] == '#') std::getline(in, rest);  // comments
  const size_t keyword = token.find("OFF");
  if (keyword == std::string::npos) return;
  // assimp also reads counts glued to the keyword ("OFF8 6 0").
  std::string glued = token.substr(keyword + 3);
  if (token == "nOFF") {  // then the dimension
    in >> token;
    glued.clear();
  }
  std::getline(in, rest, '\0');
  in.clear();
  in.str(glued + " " + rest);
  long long nv = 0, nf = 0;
  if (!(in >> nv >> nf)) return;  // not a layout this check knows: leave it to assimp
  if (nv < 0 || nf < 0) fail(path, "garbled OFF header: negative vertex or face count");
  // Every vertex and face takes at least one byte.
  if (uintmax_t(nv) > file_size || uintmax_t(nf) > file_size || uintmax_t(nv) + uintmax_t(nf) > file_size) {
    fail(path, "garbled or truncated OFF file: its header declares " + std::to_string(nv) + " vertices and " +
                   std::to_string(nf) + " faces but the file holds only " + std::to_string(file_size) +
                   " bytes");
  }
}

}  // namespace

void checkMeshFileHeader(const std::string& path, uintmax_t file_size) {
  const std::string head = readHead(path);
  if (head.compare(0, 3, "ply") == 0 || head.compare(0, 3, "PLY") == 0) {
    checkPly(path, head, file_size);
  } else {
    checkOff(path, head, file_size);
  }
}

}  // namespace ff
