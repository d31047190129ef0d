// test_target_mesh_io.cpp - loadMesh (OBJ, PLY, STL, OFF), meshVolume, bad
// files, and resolveMeshPath.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "core/error.h"
#include "target/mesh_io.h"
#include "target/target_shape.h"
#include "temp_dir.h"
#include "test_meshes.h"

namespace fs = std::filesystem;

namespace {

// A fresh temporary folder per test, removed afterwards.
class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    temp_ = std::make_unique<fftest::TempDir>(std::string("mesh_io_") + info->name());
    dir_ = temp_->path();
  }
  void TearDown() override { temp_.reset(); }
  std::unique_ptr<fftest::TempDir> temp_;
  std::string write(const std::string& name, const std::string& content) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }
  // Expects loadMesh(path) to throw ff::Error whose message contains the path
  // and `detail`.
  void expectLoadError(const std::string& path, const std::string& detail) const {
    try {
      loadMeshResult_ = ff::loadMesh(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const ff::Error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(path), std::string::npos) << msg;
      EXPECT_NE(msg.find(detail), std::string::npos) << "expected '" << detail << "' in: " << msg;
    }
  }
  fs::path dir_;
  mutable ff::TriangleMesh loadMeshResult_;
};

// Cube [x0, x0 + 2]^3 (volume 8) as 8 vertices and 6 outward quads.
const double kCubeCorner[3] = {1.0, -2.0, 0.5};
std::vector<std::array<double, 3>> cubeVertices() {
  std::vector<std::array<double, 3>> v;
  for (int k = 0; k < 8; ++k) {
    v.push_back({kCubeCorner[0] + 2.0 * (k & 1), kCubeCorner[1] + 2.0 * ((k >> 1) & 1),
                 kCubeCorner[2] + 2.0 * ((k >> 2) & 1)});
  }
  return v;
}
// 0-based corner indices, counter-clockwise seen from outside.
const int kCubeQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                              {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

std::string cubeObj() {
  std::ostringstream s;
  s << "# cube\n";
  for (const auto& p : cubeVertices()) s << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& q : kCubeQuads)
    s << "f " << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1 << "\n";
  return s.str();
}

std::string cubePly() {
  std::ostringstream s;
  s << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : cubeVertices()) s << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& q : kCubeQuads) s << "4 " << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << "\n";
  return s.str();
}

std::string cubeOff() {
  std::ostringstream s;
  s << "OFF\n# a cube\n8 6 0\n";
  for (const auto& p : cubeVertices()) s << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& q : kCubeQuads) s << "4 " << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << "\n";
  return s.str();
}

// Tetrahedron (0,0,0), (a,0,0), (0,b,0), (0,0,c): volume abc/6.
std::string tetraStl(double a, double b, double c) {
  const double p[4][3] = {{0, 0, 0}, {a, 0, 0}, {0, b, 0}, {0, 0, c}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::ostringstream s;
  s << "solid tetra\n";
  for (const auto& f : faces) {
    s << "facet normal 0 0 0\nouter loop\n";
    for (int k : f) s << "vertex " << p[k][0] << " " << p[k][1] << " " << p[k][2] << "\n";
    s << "endloop\nendfacet\n";
  }
  s << "endsolid tetra\n";
  return s.str();
}

// Independent reader for the shared meshes' plain "v x y z" / "f a b c" OBJ.
double objVolumeByHand(const std::string& path, size_t* vertex_count, size_t* face_count) {
  std::ifstream in(path);
  std::vector<std::array<double, 3>> v;
  std::string line;
  double six_volume = 0.0;
  *face_count = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      std::array<double, 3> p{};
      words >> p[0] >> p[1] >> p[2];
      v.push_back(p);
    } else if (tag == "f") {
      int a, b, c;
      words >> a >> b >> c;
      const auto &p = v[size_t(a - 1)], &q = v[size_t(b - 1)], &r = v[size_t(c - 1)];
      six_volume += p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
                    p[2] * (q[0] * r[1] - q[1] * r[0]);
      ++*face_count;
    }
  }
  *vertex_count = v.size();
  return six_volume / 6.0;
}

void expectCube(const ff::TriangleMesh& mesh) {
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_NEAR(ff::meshVolume(mesh), 8.0, 1e-9);
  ff::Vec3 lo, hi;
  ff::meshBounds(mesh, lo, hi);
  for (int a = 0; a < 3; ++a) {
    EXPECT_FLOAT_EQ(lo[a], float(kCubeCorner[a]));
    EXPECT_FLOAT_EQ(hi[a], float(kCubeCorner[a] + 2.0));
  }
}

}  // namespace

TEST_F(MeshIoTest, ObjCubeOfQuadsIsTriangulatedAndHasItsVolume) {
  expectCube(ff::loadMesh(write("cube.obj", cubeObj())));
}

TEST_F(MeshIoTest, PlyAsciiCubeHasItsVolume) {
  expectCube(ff::loadMesh(write("cube.ply", cubePly())));
}

TEST_F(MeshIoTest, OffCubeHasItsVolume) {
  expectCube(ff::loadMesh(write("cube.off", cubeOff())));
}

TEST_F(MeshIoTest, StlAsciiTetrahedronIsWeldedAndHasItsVolume) {
  const ff::TriangleMesh mesh = ff::loadMesh(write("tetra.stl", tetraStl(1.0, 2.0, 3.0)));
  EXPECT_EQ(mesh.vertices.size(), 4u);  // 12 STL corners joined into 4 vertices
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_NEAR(ff::meshVolume(mesh), 1.0 * 2.0 * 3.0 / 6.0, 1e-7);
}

TEST_F(MeshIoTest, SeveralObjectsAreMergedIntoOneMesh) {
  // Two disjoint cubes in two OBJ objects: volume 16.
  std::string text = "o first\n" + cubeObj() + "o second\n";
  for (const auto& p : cubeVertices())
    text +=
        "v " + std::to_string(p[0] + 10.0) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
  for (const auto& q : kCubeQuads) {
    text += "f " + std::to_string(q[0] + 9) + " " + std::to_string(q[1] + 9) + " " +
            std::to_string(q[2] + 9) + " " + std::to_string(q[3] + 9) + "\n";
  }
  const ff::TriangleMesh mesh = ff::loadMesh(write("two.obj", text));
  EXPECT_EQ(mesh.triangles.size(), 24u);
  EXPECT_NEAR(ff::meshVolume(mesh), 16.0, 1e-6);
}

TEST_F(MeshIoTest, InsideOutMeshHasNegativeSignedVolume) {
  std::string text;
  for (const auto& p : cubeVertices())
    text += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
  for (const auto& q : kCubeQuads) {  // reversed winding
    text += "f " + std::to_string(q[3] + 1) + " " + std::to_string(q[2] + 1) + " " +
            std::to_string(q[1] + 1) + " " + std::to_string(q[0] + 1) + "\n";
  }
  EXPECT_NEAR(ff::meshVolume(ff::loadMesh(write("inverted.obj", text))), -8.0, 1e-9);
}

TEST(MeshIoShared, BunnyMatchesAnIndependentReading) {
  FF_MESH_OR_SKIP(path, "bunny.obj");
  size_t vertices = 0, faces = 0;
  const double volume = objVolumeByHand(path, &vertices, &faces);
  const ff::TriangleMesh mesh = ff::loadMesh(path);
  EXPECT_EQ(mesh.vertices.size(), vertices);
  EXPECT_EQ(mesh.triangles.size(), faces);
  EXPECT_GT(volume, 0.0);
  EXPECT_NEAR(ff::meshVolume(mesh), volume, 1e-6 * volume);
}

TEST_F(MeshIoTest, MissingFileNamesThePath) {
  expectLoadError((dir_ / "nope.obj").string(), "not found");
}

TEST_F(MeshIoTest, EmptyFileNamesThePath) {
  expectLoadError(write("empty.obj", ""), "empty");
}

TEST_F(MeshIoTest, FolderIsNotAMesh) {
  expectLoadError(dir_.string(), "folder");
}

TEST_F(MeshIoTest, GarbageBytesGiveAnErrorForEveryFormat) {
  std::mt19937 random(12345);
  for (const char* ext : {"obj", "ply", "stl", "off", "xyz"}) {
    std::string bytes(4096, '\0');
    for (char& c : bytes) c = char(random() & 0xff);
    expectLoadError(write(std::string("garbage.") + ext, bytes), "");
  }
}

TEST_F(MeshIoTest, ObjFaceIndexOutOfRange) {
  expectLoadError(
      write("oor.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 9\n"),
      "out of range");
}

TEST_F(MeshIoTest, ObjNanCoordinate) {
  expectLoadError(
      write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"), "NaN");
}

TEST_F(MeshIoTest, ObjInfiniteCoordinate) {
  expectLoadError(
      write("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"),
      "infinite");
}

TEST_F(MeshIoTest, FileWithoutTriangles) {
  expectLoadError(write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n"), "no triangles");
}

TEST_F(MeshIoTest, FlatMeshIsDegenerate) {
  expectLoadError(write("flat.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"),
                  "flat along z");
}

TEST_F(MeshIoTest, ZeroVolumeMeshIsDegenerate) {
  // A triangle and its reverse: a closed surface with extent in x, y and z but no volume.
  expectLoadError(write("sheet.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 2\n"), "no volume");
}

TEST_F(MeshIoTest, HeaderDeclaringHugeCountsIsRejectedQuickly) {
  // assimp would loop over a billion faces, or try to allocate 48 GB.
  expectLoadError(write("huge.off", "OFF\n4 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n"),
                  "declares");
  expectLoadError(write("huge.ply",
                        "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                        "property float y\nproperty float z\nend_header\n"),
                  "declares");
}

TEST_F(MeshIoTest, GarbledPlyFilesAreRejected) {
  // Each of these made assimp 5.2 hang or crash (found by fuzzing).
  const std::string ply = cubePly();
  const std::string cut = ply.substr(0, ply.find("end_header") + 4);  // header cut short
  std::string glued = ply;                                            // data glued to end_header
  glued.erase(glued.find("end_header") + 10, 1);
  std::string typo = ply;
  typo.replace(typo.find("property float z"), 16, "property-float z");
  std::string long_list = ply;  // a face claiming a billion corners
  long_list.replace(long_list.rfind("\n4 ") + 1, 1, "999999994");
  const std::string short_data = ply.substr(0, ply.rfind("\n4 ") + 1);  // the last face missing
  expectLoadError(write("cut.ply", cut), "end_header");
  expectLoadError(write("glued.ply", glued), "garbled PLY header");
  expectLoadError(write("typo.ply", typo), "garbled PLY header");
  expectLoadError(write("long_list.ply", long_list), "bad list length");
  expectLoadError(write("short_data.ply", short_data), "ends early");
}

TEST_F(MeshIoTest, BinaryPlyCubeLoadsAndABadListLengthIsRejected) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
      "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : cubeVertices()) {
    for (double c : p) {
      const float f = float(c);
      ply.append(reinterpret_cast<const char*>(&f), 4);  // the test machines are little-endian (x86-64)
    }
  }
  for (const auto& q : kCubeQuads) {
    ply.push_back(char(4));
    for (int i : q) ply.append(reinterpret_cast<const char*>(&i), 4);
  }
  expectCube(ff::loadMesh(write("cube_binary.ply", ply)));
  ply[ply.size() - 17] = char(200);  // the last face's corner count
  expectLoadError(write("bad_binary.ply", ply), "bad list length");
}

TEST_F(MeshIoTest, TruncatedAndMutatedMeshesNeverCrash) {
  // Truncations, byte flips and inserted digits or separators in valid
  // files: either a mesh or an ff::Error naming the file, never a crash, a
  // hang or another exception. (Before the header checks, such mutants made
  // assimp hang, abort or crash.)
  std::mt19937 random(777);
  const std::string sources[] = {cubeObj(), cubePly(), cubeOff(), tetraStl(1, 1, 1)};
  const char* exts[] = {"obj", "ply", "off", "stl"};
  const std::string inserts = "0123456789-. \n";
  for (int s = 0; s < 4; ++s) {
    for (int trial = 0; trial < 150; ++trial) {
      std::string bytes = sources[s];
      if (trial % 3 == 0) {
        bytes.resize(random() % bytes.size());
      } else if (trial % 3 == 1) {
        for (int f = 0; f < 3; ++f) bytes[random() % bytes.size()] = char(random() & 0xff);
      } else {
        for (int f = 0; f < 2; ++f) bytes[random() % bytes.size()] = inserts[random() % inserts.size()];
      }
      const std::string path = write(std::string("mutant.") + exts[s], bytes);
      try {
        ff::loadMesh(path);
      } catch (const ff::Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      }
    }
  }
}

// ---- resolveMeshPath ---------------------------------------------------------

namespace {
// Sets FLOWFORM_MESH_PATH for one test, restoring the old value afterwards.
struct MeshPathEnv : fftest::ScopedEnv {
  explicit MeshPathEnv(const std::string& value) : fftest::ScopedEnv("FLOWFORM_MESH_PATH", value.c_str()) {}
};
}  // namespace

TEST(MeshPath, AbsolutePathIsTakenAsIs) {
  FF_MESH_OR_SKIP(path, "teapot.obj");
  EXPECT_TRUE(
      fs::equivalent(ff::resolveMeshPath(fs::absolute(path).string(), "/nonexistent_ff_scene"), path));
}

TEST(MeshPath, MissingAbsolutePathIsAnError) {
  MeshPathEnv env(fftest::meshSearchPath());
  const std::string missing = "/nonexistent_ff_dir/no_such_mesh.obj";
  try {
    ff::resolveMeshPath(missing, "");
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}

TEST_F(MeshIoTest, RelativePathIsFoundInTheSceneFolderFirst) {
  const std::string local = write("bunny.obj", cubeObj());
  MeshPathEnv env(fftest::meshSearchPath());
  EXPECT_TRUE(fs::equivalent(ff::resolveMeshPath("bunny.obj", dir_.string()), local));
}

TEST(MeshPath, RelativePathIsFoundAlongFlowformMeshPath) {
  FF_MESH_OR_SKIP(dragon, "dragon.obj");
  const std::string folder = fs::path(dragon).parent_path().string();
  MeshPathEnv env("/nonexistent_ff_a::/nonexistent_ff_b:" + folder);
  const std::string found = ff::resolveMeshPath("dragon.obj", "/nonexistent_ff_scene");
  EXPECT_TRUE(fs::equivalent(found, dragon)) << found;
}

TEST(MeshPath, ErrorListsEveryFolderTried) {
  MeshPathEnv env("/nonexistent_ff_a:/nonexistent_ff_b");
  try {
    ff::resolveMeshPath("missing_shape.obj", "/nonexistent_ff_scene");
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    const std::string msg = e.what();
    for (const char* part : {"missing_shape.obj", "/nonexistent_ff_scene", "/nonexistent_ff_a",
                             "/nonexistent_ff_b", "FLOWFORM_MESH_PATH"}) {
      EXPECT_NE(msg.find(part), std::string::npos) << part << " missing in: " << msg;
    }
  }
}
