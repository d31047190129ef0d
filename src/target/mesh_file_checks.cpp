// mesh_file_checks.cpp - PLY structure (header grammar, data layout) and OFF
// declared counts.
#include "target/mesh_file_checks.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "core/error.h"

namespace ff {
namespace {

constexpr size_t kHeadBytes = 65536;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

std::string readBytes(const std::string& path, size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(max_bytes, '\0');
  in.read(&bytes[0], std::streamsize(max_bytes));
  bytes.resize(size_t(in.gcount()));
  return bytes;
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// Whether the file name ends in "." + ext (lower case), in any letter case.
bool hasExtension(const std::string& path, const std::string& ext) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.size() - dot != ext.size() + 1) return false;
  std::string own = path.substr(dot + 1);
  for (char& c : own) c = char(std::tolower((unsigned char)c));
  return own == ext;
}

bool isCount(const std::string& s) {
  return !s.empty() && s.size() <= 18 && s.find_first_not_of("0123456789") == std::string::npos;
}

// ---- PLY ------------------------------------------------------------------------

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

struct PlyType {
  int size = 0;  // 0: not a PLY type
  bool integer = false, is_signed = false;
};

PlyType plyType(const std::string& t) {
  struct Named {
    const char* name;
    PlyType type;
  };
  static const Named kTypes[] = {
      {"char", {1, true, true}},    {"uchar", {1, true, false}},   {"int8", {1, true, true}},
      {"uint8", {1, true, false}},  {"short", {2, true, true}},    {"ushort", {2, true, false}},
      {"int16", {2, true, true}},   {"uint16", {2, true, false}},  {"int", {4, true, true}},
      {"uint", {4, true, false}},   {"int32", {4, true, true}},    {"uint32", {4, true, false}},
      {"float", {4, false, true}},  {"float32", {4, false, true}}, {"double", {8, false, true}},
      {"float64", {8, false, true}}};
  for (const Named& n : kTypes) {
    if (t == n.name) return n.type;
  }
  return {};
}

struct PlyProperty {
  bool list = false;
  PlyType count_type, value_type;
};

struct PlyElement {
  std::string name;
  uintmax_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;
};

// assimp takes "ply" in any letter case ("pLy") as a PLY file's first bytes.
bool isPlyMagic(const std::string& s) {
  return s.size() >= 3 && std::tolower((unsigned char)s[0]) == 'p' &&
         std::tolower((unsigned char)s[1]) == 'l' && std::tolower((unsigned char)s[2]) == 'y';
}

// An element or property name: a letter or '_' first, then letters, digits,
// '_', '-' or '.' (assimp read a count of 2^32 - 1 from an element name
// that began with digits and asked for 32 GB).
bool isPlyName(const std::string& s) {
  if (s.empty() || !(std::isalpha((unsigned char)s[0]) || s[0] == '_')) return false;
  for (char c : s) {
    if (!(std::isalnum((unsigned char)c) || c == '_' || c == '-' || c == '.')) return false;
  }
  return true;
}

// Strict PLY header grammar.
PlyHeader parsePlyHeader(const std::string& path, const std::string& head) {
  auto garbled = [&path](size_t line_no, const std::string& why) {
    fail(path, "garbled PLY header (line " + std::to_string(line_no) + "): " + why);
  };
  PlyHeader header;
  size_t pos = 0;
  for (size_t line_no = 1;; ++line_no) {
    const size_t eol = head.find('\n', pos);
    if (eol == std::string::npos)
      fail(path, "garbled or truncated PLY file: no end_header line in its first 64 KiB");
    std::string line = head.substr(pos, eol - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = eol + 1;
    // Only a CR before the LF ends a line here; assimp also takes a CR
    // elsewhere as a line end, so it read "\rend_header" otherwise and
    // crashed on what followed (a fuzzed binary file). No other control
    // character than a tab belongs in a header line either (line 1 must be
    // "ply" alone, which its own check says).
    for (const char c : line)
      if (line_no > 1 && (unsigned char)c < 0x20 && c != '\t')
        garbled(line_no, "a control character inside a line");
    const std::vector<std::string> w = words(line);
    if (line_no == 1) {
      if (w.size() != 1 || !isPlyMagic(w[0])) garbled(line_no, "the first line must be 'ply'");
    } else if (line_no == 2) {
      if (w.size() != 3 || w[0] != "format") garbled(line_no, "expected 'format TYPE VERSION'");
      if (w[1] == "ascii") {
        header.format = PlyFormat::Ascii;
      } else if (w[1] == "binary_little_endian") {
        header.format = PlyFormat::BinaryLittle;
      } else if (w[1] == "binary_big_endian") {
        header.format = PlyFormat::BinaryBig;
      } else {
        garbled(line_no, "unknown format '" + w[1] + "'");
      }
    } else if (w.empty()) {
      garbled(line_no, "empty line");
    } else if (w[0] == "comment" || w[0] == "obj_info") {
      continue;
    } else if (w[0] == "end_header" && w.size() == 1) {
      header.data_offset = pos;
      return header;
    } else if (w[0] == "element" && w.size() == 3 && isPlyName(w[1]) && isCount(w[2])) {
      header.elements.push_back({w[1], std::stoull(w[2]), {}});
    } else if (w[0] == "property" && !header.elements.empty() && w.size() == 3 && plyType(w[1]).size > 0 &&
               isPlyName(w[2])) {
      header.elements.back().properties.push_back({false, {}, plyType(w[1])});
    } else if (w[0] == "property" && !header.elements.empty() && w.size() == 5 && w[1] == "list" &&
               plyType(w[2]).integer && plyType(w[3]).size > 0 && isPlyName(w[4])) {
      header.elements.back().properties.push_back({true, plyType(w[2]), plyType(w[3])});
    } else {
      garbled(line_no, "unexpected '" + line.substr(0, 60) + "'");
    }
  }
}

// Every value takes at least one byte (ASCII) or its size (binary; the count
// of a list), so the declared elements must fit into the file.
void checkPlySize(const std::string& path, const PlyHeader& header, uintmax_t file_size) {
  uintmax_t needed = std::min(uintmax_t(header.data_offset), file_size);
  for (const PlyElement& e : header.elements) {
    uintmax_t bytes = 0;
    for (const PlyProperty& p : e.properties) {
      bytes +=
          header.format == PlyFormat::Ascii ? 1 : uintmax_t(p.list ? p.count_type.size : p.value_type.size);
    }
    if (bytes == 0) continue;
    if (e.count > (file_size - needed) / bytes) {
      fail(path, "garbled or truncated PLY file: its header declares " + std::to_string(e.count) + " " +
                     e.name + " elements, more than the file can hold");
    }
    needed += e.count * bytes;
  }
}

// Whether `token` is a decimal number of the property's type: an integer in
// the type's range, or a decimal floating-point number (no hex, inf or nan,
// which assimp's number reader does not know).
bool isPlyNumber(const std::string& token, const PlyType& type) {
  size_t k = token.empty() || (token[0] != '-' && token[0] != '+') ? 0 : 1;
  const bool negative = k == 1 && token[0] == '-';
  const size_t digits_start = k;
  while (k < token.size() && std::isdigit((unsigned char)token[k])) ++k;
  if (type.integer) {
    if (k != token.size() || k == digits_start || k - digits_start > 10) return false;
    const long long value = std::stoll(token.substr(digits_start)) * (negative ? -1 : 1);
    const int bits = 8 * type.size;
    const long long lo = type.is_signed ? -(1LL << (bits - 1)) : 0;
    const long long hi = type.is_signed ? (1LL << (bits - 1)) - 1 : (1LL << bits) - 1;
    return value >= lo && value <= hi;
  }
  size_t mantissa = k - digits_start;
  if (k < token.size() && token[k] == '.') {
    const size_t frac = ++k;
    while (k < token.size() && std::isdigit((unsigned char)token[k])) ++k;
    mantissa += k - frac;
  }
  if (mantissa == 0) return false;
  if (k < token.size() && (token[k] == 'e' || token[k] == 'E')) {
    ++k;
    if (k < token.size() && (token[k] == '-' || token[k] == '+')) ++k;
    const size_t exponent = k;
    while (k < token.size() && std::isdigit((unsigned char)token[k])) ++k;
    if (k == exponent) return false;
  }
  return k == token.size();
}

// Walks the ASCII data as assimp reads it, one element per line: every line
// holds exactly the values its element declares, each a number of its type;
// every list has at least one value; nothing but white space follows the last
// element. (assimp read past the end, looped for minutes or asked for 32 GB
// on files that broke one of these.)
void checkPlyAsciiData(const std::string& path, const PlyHeader& header, const std::string& data) {
  size_t pos = header.data_offset;
  size_t line_no = 0;
  for (const PlyElement& e : header.elements) {
    for (uintmax_t n = 0; n < e.count; ++n) {
      const std::string where = " (" + e.name + " " + std::to_string(n + 1) + ")";
      if (pos >= data.size()) fail(path, "truncated PLY file: the " + e.name + " data ends early");
      size_t eol = data.find('\n', pos);
      if (eol == std::string::npos) eol = data.size();
      const std::vector<std::string> w = words(data.substr(pos, eol - pos));
      pos = eol + 1;
      ++line_no;
      const std::string line =
          "garbled PLY data, line " + std::to_string(line_no) + " after the header" + where;
      size_t next = 0;
      for (const PlyProperty& p : e.properties) {
        uintmax_t values = 1;
        if (p.list) {
          if (next >= w.size() || !isPlyNumber(w[next], p.count_type) || w[next][0] == '-')
            fail(path, line + ": bad list length (missing, or not a count of its type)");
          values = std::stoull(w[next++]);
          if (values == 0) fail(path, line + ": bad list length 0 (a list of no values)");
        }
        if (values > w.size() - next) fail(path, line + ": fewer values than the header declares");
        for (uintmax_t v = 0; v < values; ++v, ++next) {
          if (!isPlyNumber(w[next], p.value_type))
            fail(path, line + ": '" + w[next].substr(0, 20) + "' is not a number of the declared type");
        }
      }
      if (next != w.size()) fail(path, line + ": more values than the header declares");
    }
  }
  if (pos < data.size() && data.find_first_not_of(" \t\r\n", pos) != std::string::npos)
    fail(path, "garbled PLY file: data after the last element the header declares");
}

uintmax_t readCount(const unsigned char* p, const PlyType& type, bool big_endian, bool& negative) {
  uintmax_t value = 0;
  for (int i = 0; i < type.size; ++i)
    value |= uintmax_t(p[big_endian ? i : type.size - 1 - i]) << (8 * (type.size - 1 - i));
  negative = type.is_signed && (value >> (8 * type.size - 1)) != 0;
  return value;
}

// Walks the binary data: every list has at least one value and fits into the file.
void checkPlyBinaryData(const std::string& path, const PlyHeader& header, const std::string& data) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  const uintmax_t size = data.size();
  uintmax_t pos = header.data_offset;
  const bool big = header.format == PlyFormat::BinaryBig;
  for (const PlyElement& e : header.elements) {
    for (uintmax_t n = 0; n < e.count; ++n) {
      for (const PlyProperty& p : e.properties) {
        if (!p.list) {
          pos += uintmax_t(p.value_type.size);
        } else {
          if (pos + uintmax_t(p.count_type.size) > size) {
            fail(path, "truncated PLY file: the " + e.name + " data ends early");
          }
          bool negative = false;
          const uintmax_t count = readCount(bytes + pos, p.count_type, big, negative);
          pos += uintmax_t(p.count_type.size);
          if (negative || count == 0 || count > (size - pos) / uintmax_t(p.value_type.size)) {
            fail(path,
                 "garbled or truncated PLY data: bad list length in " + e.name + " " + std::to_string(n + 1));
          }
          pos += count * uintmax_t(p.value_type.size);
        }
        if (pos > size) fail(path, "truncated PLY file: the " + e.name + " data ends early");
      }
    }
  }
}

void checkPly(const std::string& path, const std::string& head, uintmax_t file_size) {
  const PlyHeader header = parsePlyHeader(path, head);
  checkPlySize(path, header, file_size);
  const std::string data = readBytes(path, size_t(file_size));
  if (header.format == PlyFormat::Ascii) {
    checkPlyAsciiData(path, header, data);
  } else {
    checkPlyBinaryData(path, header, data);
  }
}

// ---- OFF -------------------------------------------------------------------------

// The words of an OFF header as assimp's NextToken walks them: separated by
// white space, and a word that starts with '#' skips the rest of its line
// (a comment, anywhere between two values). Returns [start, end) positions.
std::vector<std::pair<size_t, size_t>> offWords(const std::string& text, size_t max_words) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t i = 0;
  const size_t n = text.size();
  while (out.size() < max_words) {
    while (i < n && std::isspace((unsigned char)text[i])) ++i;
    if (i >= n) break;
    if (text[i] == '#') {
      while (i < n && text[i] != '\n') ++i;
      continue;
    }
    const size_t start = i;
    while (i < n && !std::isspace((unsigned char)text[i])) ++i;
    out.push_back({start, i});
  }
  return out;
}

void checkOff(const std::string& path, const std::string& head, uintmax_t file_size) {
  const auto first = offWords(head, 1);
  if (first.empty()) return;
  const std::string token = head.substr(first[0].first, first[0].second - first[0].first);
  const size_t keyword = token.find("OFF");
  // The keyword is optional in an .off file (assimp then reads the counts
  // from its first words); any other file without it is not OFF.
  if (keyword == std::string::npos && !hasExtension(path, "off")) return;
  // The counts follow the keyword, even glued to it ("OFF8 6 0"); after
  // "nOFF" comes the dimension first.
  const std::string rest =
      head.substr(keyword == std::string::npos ? first[0].first : first[0].first + keyword + 3);
  const size_t skip = keyword != std::string::npos && token == "nOFF" ? 1 : 0;
  const auto next = offWords(rest, skip + 2);
  if (next.size() < skip + 2) return;  // not a layout this check knows: leave it to assimp
  std::string words[2];
  for (int i = 0; i < 2; ++i)
    words[i] = rest.substr(next[skip + size_t(i)].first,
                           next[skip + size_t(i)].second - next[skip + size_t(i)].first);
  // The counts as assimp reads them: the leading digits of each word (it
  // reads "1`*" as 1). A count too large for 64 bits is too large for the file.
  uintmax_t count[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    if (words[i][0] == '-') fail(path, "garbled OFF header: negative vertex or face count");
    const size_t sign = words[i][0] == '+' ? 1 : 0;
    for (size_t k = sign; k < words[i].size() && std::isdigit((unsigned char)words[i][k]); ++k) {
      const uintmax_t digit = uintmax_t(words[i][k] - '0');
      count[i] = count[i] > (UINTMAX_MAX - digit) / 10 ? UINTMAX_MAX : count[i] * 10 + digit;
    }
  }
  // Every vertex and face takes at least one byte.
  if (count[0] > file_size || count[1] > file_size || count[0] + count[1] > file_size) {
    auto shown = [](uintmax_t n) {
      return n == UINTMAX_MAX ? std::string("more than 2^64") : std::to_string(n);
    };
    fail(path, "garbled or truncated OFF file: its header declares " + shown(count[0]) + " vertices and " +
                   shown(count[1]) + " faces but the file holds only " + std::to_string(file_size) +
                   " bytes");
  }
  // assimp reads a face's vertex count (and, in some layouts, the counts
  // themselves) from words further on, as the leading digits of a word, and
  // allocates for it (a fuzzed file asked for 52 GB). A number above both the
  // file's size and 2^24 can only be garbage there; 2^24 keeps integer
  // coordinates (a cube in millimetres) well clear of the check.
  if (file_size > (uintmax_t(256) << 20)) return;
  const uintmax_t limit = std::max(file_size, uintmax_t(1) << 24);
  const std::string all = readBytes(path, size_t(file_size));
  for (const auto& w : offWords(all, SIZE_MAX)) {
    size_t k = w.first + (all[w.first] == '+' ? 1 : 0);
    uintmax_t v = 0;
    for (; k < w.second && std::isdigit((unsigned char)all[k]) && v <= limit; ++k)
      v = v * 10 + uintmax_t(all[k] - '0');
    if (v > limit)
      fail(path, "garbled OFF file: the number at byte " + std::to_string(w.first) + " is larger than " +
                     std::to_string(limit) + ", the most a count in this file can be");
  }
}

}  // namespace

void checkMeshFileStructure(const std::string& path, uintmax_t file_size) {
  const std::string head = readBytes(path, kHeadBytes);
  // assimp picks its PLY reader for every .ply file, whatever its first
  // bytes, and then searches them for the magic (it skips line ends and NUL
  // bytes; a fuzzed file with bytes before "ply" crashed it, another made it
  // seek forever). A .ply file must therefore be a PLY file from its first
  // byte on. assimp also skips line ends before the magic of a file of
  // another name; the PLY checks then refuse them.
  const size_t text = std::min(head.find_first_not_of(" \t\r\n"), head.size());
  if (hasExtension(path, "ply") || isPlyMagic(head.substr(text, 3))) {
    checkPly(path, head, file_size);
  } else {
    checkOff(path, head, file_size);
  }
}

}  // namespace ff
