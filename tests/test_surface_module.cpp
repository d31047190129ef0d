// The surface module (src/surface/surface_module.h): OpenVDB is loaded the
// first time a surface is made, not when the program starts, and the surface
// it makes through the module is the liquid's. Each test runs in a process of
// its own (gtest_discover_tests), so the first reading of the process's maps
// is before any surface.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "surface/particle_surface.h"

namespace {

bool openVdbMapped() {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find("libopenvdb") != std::string::npos) return true;
  return false;
}

TEST(SurfaceModule, OpenVdbLoadsOnlyWhenASurfaceIsMade) {
  EXPECT_FALSE(openVdbMapped()) << "OpenVDB was loaded before any surface";
  // A resting block of 8 x 8 x 8 particles on a lattice of spacing s.
  const int m = 8;
  const float s = 0.01f;
  std::vector<float> x, y, z;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        x.push_back(s * float(i)), y.push_back(s * float(j)), z.push_back(s * float(k));
  const ff::SurfaceMesh mesh =
      ff::particleSurface(x.size(), x.data(), y.data(), z.data(), s, ff::SurfaceOptions());
  EXPECT_TRUE(openVdbMapped());
  // The block's volume: its faces half a spacing beyond the outer centres
  // (particle_surface.h), a cube of side m s, less what the smoothing
  // rounds off its edges and corners.
  const double cube = double(m * s) * double(m * s) * double(m * s);
  ASSERT_GT(mesh.triangles.size(), 0u);
  EXPECT_NEAR(mesh.volume(), cube, 0.1 * cube);
  // The module is loaded once: a second surface of no particles is empty.
  EXPECT_TRUE(ff::particleSurface(0, nullptr, nullptr, nullptr, s, ff::SurfaceOptions()).triangles.empty());
}

TEST(SurfaceModule, ItsErrorsReachTheCallerAsErrors) {
  const float p[1] = {0.0f};
  // An unwritable level-set path: the module's message, naming the file.
  try {
    ff::particleSurface(1, p, p, p, 0.01f, ff::SurfaceOptions(), "/nonexistent-folder/surface.vdb");
    ADD_FAILURE() << "wrote into a folder that does not exist";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/surface.vdb"), std::string::npos) << e.what();
  }
}

}  // namespace
