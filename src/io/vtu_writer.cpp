// vtu_writer.cpp - VTK XML UnstructuredGrid with appended raw data.
#include "io/vtu_writer.h"

#include <cstdint>
#include <cstdio>

#include "io/atomic_file.h"
#include "io/byte_order.h"

namespace ff {
namespace {

// One appended block: its byte count (UInt64), then the bytes. Returns the
// block's offset, as the DataArray's `offset` attribute gives it.
class Appended {
 public:
  size_t begin(uint64_t bytes) {
    const size_t at = data_.size();
    data_.reserve(data_.size() + 8 + bytes);
    putLE64(data_, bytes);
    return at;
  }
  std::string& data() { return data_; }

 private:
  std::string data_;
};

std::string arrayTag(const char* type, const std::string& name, int components, size_t offset) {
  std::string t = std::string("        <DataArray type=\"") + type + "\"";
  if (!name.empty()) t += " Name=\"" + name + "\"";
  t += " NumberOfComponents=\"" + std::to_string(components) + "\" format=\"appended\" offset=\"" +
       std::to_string(offset) + "\"/>\n";
  return t;
}

}  // namespace

void writeVtu(const std::string& path, const PointCloud& c) {
  const size_t n = c.n;
  Appended app;
  std::string& d = app.data();
  std::string point_data;
  for (const PointAttribute& a : c.attributes) {
    const bool is_int = a.type == PointAttribute::Type::Int32;
    point_data += arrayTag(is_int ? "Int32" : "Float32", a.name, a.components,
                           app.begin(uint64_t(n) * 4 * uint64_t(a.components)));
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < a.components; ++k) putLE32(d, a.bits(k, i));
  }
  const std::string points = arrayTag("Float32", "", 3, app.begin(uint64_t(n) * 12));
  for (size_t i = 0; i < n; ++i)
    for (const float* p : {c.x, c.y, c.z}) putLE32(d, bitsOf(p[i]));
  // One VTK_VERTEX (type 1) cell per point: connectivity i, offsets i + 1.
  std::string cells = arrayTag("Int64", "connectivity", 1, app.begin(uint64_t(n) * 8));
  for (size_t i = 0; i < n; ++i) putLE64(d, uint64_t(i));
  cells += arrayTag("Int64", "offsets", 1, app.begin(uint64_t(n) * 8));
  for (size_t i = 0; i < n; ++i) putLE64(d, uint64_t(i + 1));
  cells += arrayTag("UInt8", "types", 1, app.begin(uint64_t(n)));
  d.append(n, char(1));

  char time[64];
  std::snprintf(time, sizeof time, "%.9g", c.time);
  const std::string count = std::to_string(n);
  const std::string head =
      std::string(
          "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
          "byte_order=\"LittleEndian\" "
          "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <FieldData>\n"
          "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">") +
      time + "</DataArray>\n    </FieldData>\n    <Piece NumberOfPoints=\"" + count + "\" NumberOfCells=\"" +
      count + "\">\n      <PointData>\n" + point_data + "      </PointData>\n      <Points>\n" + points +
      "      </Points>\n      <Cells>\n" + cells +
      "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  static const char tail[] = "\n  </AppendedData>\n</VTKFile>\n";
  writeFileAtomically(path, "VTU file", {head, d, tail});
}

}  // namespace ff
