// vtu_writer.h - particle snapshots as VTK XML unstructured grids (.vtu):
// one vertex cell per particle, every attribute as point data, the
// simulated time as the field-data array TimeValue (which ParaView reads as
// the dataset's time). Raw little-endian appended data with UInt64 block
// headers, uncompressed. Written atomically; errors throw ff::Error naming
// the path.
#pragma once
#include <string>

#include "io/point_cloud.h"

namespace ff {

void writeVtu(const std::string& path, const PointCloud& cloud);

}  // namespace ff
