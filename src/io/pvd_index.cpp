// pvd_index.cpp - the VTK Collection file.
#include "io/pvd_index.h"

#include <cstdio>

#include "io/atomic_file.h"

namespace ff {

void PvdIndex::add(double time, const std::string& file) {
  entries_.emplace_back(time, file);
  std::string xml =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  char t[64];
  for (const auto& [when, name] : entries_) {
    std::snprintf(t, sizeof t, "%.9g", when);
    xml += std::string("    <DataSet timestep=\"") + t + "\" group=\"\" part=\"0\" file=\"" + name + "\"/>\n";
  }
  xml += "  </Collection>\n</VTKFile>\n";
  writeFileAtomically(path_, "PVD index", {xml});
}

}  // namespace ff
