// test_io_writers.cpp - PLY snapshots and the metrics CSV, read back
// independently of the writers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/metrics_csv.h"
#include "io/ply_writer.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Ply {
  std::vector<std::string> header;  // lines up to and including end_header
  std::string body;
};

Ply readPly(const std::string& path) {
  std::string all = readAll(path);
  Ply ply;
  size_t end = all.find("end_header\n");
  if (end == std::string::npos) return ply;
  std::istringstream head(all.substr(0, end + 11));
  for (std::string line; std::getline(head, line);) ply.header.push_back(line);
  ply.body = all.substr(end + 11);
  return ply;
}

uint32_t le32(const std::string& body, size_t offset) {
  uint32_t v = 0;
  for (int b = 0; b < 4; ++b) v |= uint32_t(uint8_t(body[offset + b])) << (8 * b);
  return v;
}

float leFloat(const std::string& body, size_t offset) {
  uint32_t bits = le32(body, offset);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

static ff::PointCloud plyCloud(size_t n, const float* const* a, const uint32_t* id, double time) {
  ff::PointCloud c{n, a[0], a[1], a[2], {}, time, "test particles"};
  c.attributes = {ff::PointAttribute::scalar("vx", a[3]), ff::PointAttribute::scalar("vy", a[4]),
                  ff::PointAttribute::scalar("vz", a[5]),
                  ff::PointAttribute::integer("id", reinterpret_cast<const int32_t*>(id))};
  return c;
}

TEST(PlyWriter, RoundTripWithIntIdsAndTime) {
  const fftest::TempDir dir("io");
  const size_t n = 5;
  std::vector<float> a[6];
  std::vector<uint32_t> id(n);
  for (int c = 0; c < 6; ++c)
    for (size_t i = 0; i < n; ++i)
      a[c].push_back(float(c) * 1.5f - float(i) * 0.123f + (c == 4 ? 1e-7f : 0.0f));
  for (size_t i = 0; i < n; ++i) id[i] = uint32_t(1000 + 7 * i);
  const std::string path = dir.file("fluid.ply");
  const float* cols[6] = {a[0].data(), a[1].data(), a[2].data(), a[3].data(), a[4].data(), a[5].data()};
  ff::writePly(path, plyCloud(n, cols, id.data(), 0.25));

  Ply ply = readPly(path);
  const std::vector<std::string> expected_props = {
      "property float x",  "property float y",  "property float z", "property float vx",
      "property float vy", "property float vz", "property int id"};
  ASSERT_GE(ply.header.size(), 3u);
  EXPECT_EQ(ply.header.front(), "ply");
  EXPECT_EQ(ply.header[1], "format binary_little_endian 1.0");
  EXPECT_EQ(ply.header.back(), "end_header");
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "comment time 0.25"), ply.header.end());
  std::vector<std::string> props;
  bool saw_count = false;
  for (const std::string& l : ply.header) {
    if (l.rfind("property ", 0) == 0) props.push_back(l);
    if (l == "element vertex 5") saw_count = true;
  }
  EXPECT_TRUE(saw_count);
  EXPECT_EQ(props, expected_props);
  ASSERT_EQ(ply.body.size(), n * 28);
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 6; ++c)
      EXPECT_EQ(leFloat(ply.body, i * 28 + 4 * c), a[c][i]) << "vertex " << i << " prop " << c;
    EXPECT_EQ(le32(ply.body, i * 28 + 24), id[i]);
  }
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(PlyWriter, VectorAttributeIsThreeProperties) {
  const fftest::TempDir dir("io");
  float v[2] = {1.0f, 2.0f};
  ff::PointCloud c{2, v, v, v, {ff::PointAttribute::vector("rest", v, v, v)}, 0.0, "test"};
  const std::string path = dir.file("vec.ply");
  ff::writePly(path, c);
  Ply ply = readPly(path);
  std::vector<std::string> props;
  for (const std::string& l : ply.header)
    if (l.rfind("property ", 0) == 0) props.push_back(l);
  const std::vector<std::string> expected = {"property float x",      "property float y",
                                             "property float z",      "property float rest_x",
                                             "property float rest_y", "property float rest_z"};
  EXPECT_EQ(props, expected);
  EXPECT_EQ(ply.body.size(), 2u * 24);
}

TEST(PlyWriter, EmptyCloud) {
  const fftest::TempDir dir("io");
  const std::string path = dir.file("empty.ply");
  ff::writePly(path, ff::PointCloud{});
  Ply ply = readPly(path);
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "element vertex 0"), ply.header.end());
  EXPECT_TRUE(ply.body.empty());
}

TEST(PlyWriter, ErrorNamesPathAndLeavesNoFile) {
  const fftest::TempDir dir("io");
  const std::string path = dir.file("no_such_folder/out.ply");
  float v[1] = {0.0f};
  try {
    ff::writePly(path, ff::PointCloud{1, v, v, v, {}, 0.0, "test"});
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(PlyWriter, OverwritesExistingFile) {
  const fftest::TempDir dir("io");
  const std::string path = dir.file("again.ply");
  float v[2] = {1.0f, 2.0f};
  ff::writePly(path, ff::PointCloud{2, v, v, v, {}, 0.0, "test"});
  ff::writePly(path, ff::PointCloud{1, v, v, v, {}, 0.0, "test"});
  Ply ply = readPly(path);
  EXPECT_EQ(ply.body.size(), 12u);
}

TEST(MetricsCsv, HeaderAndRowsReadBack) {
  const fftest::TempDir dir("io");
  const std::string path = dir.file("metrics.csv");
  ff::MetricsCsv csv;
  csv.open(path, {"step", "time", "error", "note,with comma"});
  EXPECT_TRUE(csv.isOpen());
  csv.row(0, 0.0, 0.5, -1);
  // Flushed at once: readable before close.
  std::vector<std::string> got = lines(readAll(path));
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], "step,time,error,\"note,with comma\"");
  EXPECT_EQ(got[1], "0,0,0.5,-1");

  const double third = 1.0 / 3.0;
  csv.row(std::vector<double>{1, 0.004, third, 1e-12});
  csv.close();
  got = lines(readAll(path));
  ASSERT_EQ(got.size(), 3u);
  std::vector<double> values;
  std::istringstream row(got[2]);
  for (std::string cell; std::getline(row, cell, ',');) values.push_back(std::strtod(cell.c_str(), nullptr));
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[0], 1.0);
  EXPECT_DOUBLE_EQ(values[1], 0.004);
  EXPECT_NEAR(values[2], third, 1e-9);
  EXPECT_NEAR(values[3], 1e-12, 1e-20);
}

TEST(MetricsCsv, WrongValueCountThrows) {
  const fftest::TempDir dir("io");
  ff::MetricsCsv csv;
  csv.open(dir.file("m.csv"), {"a", "b"});
  EXPECT_THROW(csv.row(1.0), ff::Error);
  EXPECT_THROW(csv.row(1.0, 2.0, 3.0), ff::Error);
  EXPECT_NO_THROW(csv.row(1.0, 2.0));
}

TEST(MetricsCsv, OpenErrorNamesPath) {
  const fftest::TempDir dir("io");
  const std::string path = dir.file("missing_folder/m.csv");
  ff::MetricsCsv csv;
  try {
    csv.open(path, {"a"});
    ADD_FAILURE() << "no error";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_FALSE(csv.isOpen());
}
