// test_frame_export.cpp - the export folder policy, the format list and the
// frame cadence of io/frame_exporter. (The files themselves are read back by
// meshio and a BGEO parser in tests/python/test_export_readers.py.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "core/error.h"
#include "io/export_folder.h"
#include "io/export_options.h"

namespace fs = std::filesystem;

namespace {

TEST(ExportFolder, FrameNamingIsNarrow) {
  for (const char* yes : {"fluid_00000.vtu", "control_12.bgeo", "surface_00003.obj", "surface_1.vdb",
                          "fluid.pvd", "control.pvd", "fluid_00001.ply.tmp", "fluid_00000.pcache"})
    EXPECT_TRUE(ff::isFrameFileName(yes)) << yes;
  for (const char* no : {"notes.txt", "fluid_notes.vtu", "fluid_00000.vtu.bak", "my_fluid_00000.vtu",
                         "fluid_.vtu", "fluid_00000.png", "Fluid_00000.vtu", "scene.json", "fluid.pvd.old"})
    EXPECT_FALSE(ff::isFrameFileName(no)) << no;
}

TEST(ExportFolder, RefusesAnotherRunsFramesAndCleansOnlyThemWithOverwrite) {
  const fftest::TempDir d("export_folder");
  for (const char* name : {"fluid_00000.vtu", "fluid.pvd", "notes.txt", "fluid_notes.vtu"})
    std::ofstream(d / name) << "x";
  fs::create_directories(d / "fluid_00001.vtu");  // a folder of that name is the user's, kept
  try {
    ff::prepareExportFolder(d.string(), false);
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(d.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("--overwrite"), std::string::npos) << msg;
  }
  EXPECT_TRUE(fs::exists(d / "fluid_00000.vtu"));
  ff::prepareExportFolder(d.string(), true);
  EXPECT_FALSE(fs::exists(d / "fluid_00000.vtu"));
  EXPECT_FALSE(fs::exists(d / "fluid.pvd"));
  EXPECT_TRUE(fs::exists(d / "notes.txt"));
  EXPECT_TRUE(fs::exists(d / "fluid_notes.vtu"));
  EXPECT_TRUE(fs::is_directory(d / "fluid_00001.vtu"));
  ff::prepareExportFolder(d.string(), false);  // nothing of ours left: accepted
}

TEST(ExportFolder, ANonFolderIsAnError) {
  const fftest::TempDir d("export_file");
  std::ofstream(d / "file") << "x";
  EXPECT_THROW(ff::prepareExportFolder((d / "file").string(), false), ff::Error);
}

TEST(ExportOptions, FormatList) {
  using F = ff::ExportFormat;
  EXPECT_EQ(ff::parseExportFormats("vtk", "--format"), std::vector<F>{F::Vtk});
  EXPECT_EQ(ff::parseExportFormats("ply,bgeo,vtk", "--format"), (std::vector<F>{F::Ply, F::Bgeo, F::Vtk}));
  for (const char* bad : {"", "vtk,", "vtk,vtk", "VTK", "obj", "vtk bgeo"}) {
    try {
      ff::parseExportFormats(bad, "--format");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const ff::Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--format: ", 0), 0u) << e.what();
    }
  }
}

TEST(ExportOptions, FpsRange) {
  ff::ExportOptions o;
  o.dir = "x";
  EXPECT_NO_THROW(ff::validateExportOptions(o, "export"));
  for (double fps : {0.0, -1.0, 1e9, std::nan("")}) {
    o.fps = fps;
    EXPECT_THROW(ff::validateExportOptions(o, "export"), ff::Error) << fps;
  }
}

}  // namespace

namespace {

TEST(ExportOptions, SurfaceRanges) {
  ff::ExportOptions o;
  o.dir = "x";
  o.surface.enabled = true;
  EXPECT_NO_THROW(ff::validateExportOptions(o, "export"));
  auto expectError = [&](const char* field) {
    try {
      ff::validateExportOptions(o, "export");
      ADD_FAILURE() << "accepted bad " << field;
    } catch (const ff::Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
    o.surface = ff::SurfaceOptions();
    o.surface.enabled = true;
  };
  o.surface.radius = 0.5f;  // leaves gaps in the rest lattice
  expectError("radius");
  o.surface.radius = std::nanf("");
  expectError("radius");
  o.surface.voxel = 0.0f;
  expectError("voxel");
  o.surface.smoothing = -1;
  expectError("smoothing");
  o.surface.radius = 0.8f;
  o.surface.voxel = 0.6f;  // under 1.5 voxels per radius
  expectError("radius");
}

}  // namespace
