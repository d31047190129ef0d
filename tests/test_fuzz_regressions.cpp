// Every input the fuzzers found (tests/fuzz/regressions/) and every seed
// (tests/fuzz/corpus/) replayed through the normal build's readers, as the
// fuzz targets call them (tests/fuzz/*.cpp): each must end in a result or in
// an ff::Error that names the file, never a crash, a hang or another
// exception. The findings that needed a fix are also checked by name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "core/error.h"
#include "scene/scene.h"
#include "target/mesh_io.h"
#include "temp_dir.h"
#include "viewer/script.h"

namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(FF_SOURCE_DIR) / "tests" / "fuzz";

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Reads `file` with the reader of its folder ("scene", "script", "mesh_obj",
// ...). Returns the error message, or "" when it was accepted.
std::string replay(const std::string& kind, const fs::path& file, const fftest::TempDir& tmp) {
  const std::string text = readAll(file);
  try {
    if (kind == "scene") {
      ff::parseScene(text, file.string(), "");
    } else if (kind == "script") {
      ff::viewer::parseScript(text, file.string(), "");
    } else {
      // A copy named as the fuzz target names its input: the extension picks the format.
      const fs::path copy = tmp / ("input." + kind.substr(kind.find('_') + 1));
      fs::copy_file(file, copy, fs::copy_options::overwrite_existing);
      try {
        ff::loadMesh(copy.string());
      } catch (const ff::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(copy.string()), std::string::npos) << file << ": " << what;
        return what;
      }
    }
  } catch (const ff::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    return what;
  }
  return "";
}

TEST(FuzzRegressions, EveryFindingAndSeedEndsInAResultOrAnError) {
  fftest::TempDir tmp("fuzz_replay");
  int files = 0;
  for (const char* set : {"corpus", "regressions"}) {
    for (const auto& kind_dir : fs::directory_iterator(kFuzzDir / set)) {
      const std::string kind = kind_dir.path().filename().string();
      for (const auto& f : fs::directory_iterator(kind_dir.path())) {
        SCOPED_TRACE(f.path().string());
        try {
          replay(kind, f.path(), tmp);
        } catch (const std::exception& e) {
          ADD_FAILURE() << "not an ff::Error: " << e.what();
        }
        ++files;
      }
    }
  }
  EXPECT_GE(files, 25);
}

TEST(FuzzRegressions, TheSeedsAreValidInputs) {
  // The seeds are meant to be valid, so that the fuzzers start from inputs
  // that reach deep into the readers.
  fftest::TempDir tmp("fuzz_seeds");
  for (const auto& kind_dir : fs::directory_iterator(kFuzzDir / "corpus")) {
    const std::string kind = kind_dir.path().filename().string();
    if (kind == "scene") continue;  // the Table 1 scenes name meshes found only along FLOWFORM_MESH_PATH
    for (const auto& f : fs::directory_iterator(kind_dir.path()))
      EXPECT_EQ(replay(kind, f.path(), tmp), "") << f.path();
  }
}

TEST(FuzzRegressions, OffCountsPast64BitsAreRefused) {
  // "OFF\n82333333333333333373\n1`..." made assimp allocate 8.7 GB: the
  // vertex count overflowed the check's 64-bit integer, which then left the
  // file to assimp.
  fftest::TempDir tmp("fuzz_off");
  const std::string what =
      replay("mesh_off", kFuzzDir / "regressions" / "mesh_off" / "count_past_64_bits.off", tmp);
  EXPECT_NE(what.find("declares more than 2^64 vertices"), std::string::npos) << what;
  const fs::path big = tmp.write("big.off", "OFF\n99999999999 1 0\n0 0 0\n");
  try {
    ff::loadMesh(big.string());
    ADD_FAILURE() << "accepted";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find("declares 99999999999 vertices"), std::string::npos) << e.what();
  }
}

TEST(FuzzRegressions, OffCommentsBetweenTheCountsAreSkippedAsAssimpSkipsThem) {
  // "OFF\n#mo cment\n4 333333333333334 0": the check read the comment's words
  // as the counts; assimp skips comment lines and allocated 14.7 GB.
  fftest::TempDir tmp("fuzz_off_comment");
  const std::string what =
      replay("mesh_off", kFuzzDir / "regressions" / "mesh_off" / "face_count_after_comment.off", tmp);
  EXPECT_NE(what.find("declares 4 vertices and 333333333333334 faces"), std::string::npos) << what;
  // The same with the comment glued to the keyword, and between the counts.
  for (const char* text : {"OFF#x\n4 99999999999 0\n", "OFF\n4 # four\n99999999999 0\n"}) {
    const fs::path f = tmp.write("c.off", text);
    try {
      ff::loadMesh(f.string());
      ADD_FAILURE() << text << " accepted";
    } catch (const ff::Error& e) {
      EXPECT_NE(std::string(e.what()).find("declares 4 vertices and 99999999999 faces"), std::string::npos)
          << e.what();
    }
  }
}

TEST(FuzzRegressions, PlyMagicAfterABlankLineIsChecked) {
  // assimp skips a line end before "ply"; the checks looked for "ply" at the
  // first byte only, so this garbled header reached assimp, which looped.
  fftest::TempDir tmp("fuzz_ply_blank");
  const std::string what =
      replay("mesh_ply", kFuzzDir / "regressions" / "mesh_ply" / "blank_line_before_magic_hang.ply", tmp);
  EXPECT_NE(what.find("garbled PLY header (line 1)"), std::string::npos) << what;
}

TEST(FuzzRegressions, PlyMagicInAnyLetterCaseIsChecked) {
  // assimp reads "pLy" as PLY; the header checks only knew "ply" and "PLY",
  // so a garbled header behind "pLy" reached assimp, which looped forever.
  fftest::TempDir tmp("fuzz_ply");
  const std::string what =
      replay("mesh_ply", kFuzzDir / "regressions" / "mesh_ply" / "mixed_case_magic_hang.ply", tmp);
  EXPECT_NE(what.find("garbled PLY header"), std::string::npos) << what;
}

TEST(FuzzRegressions, PlyFileWithBytesBeforeTheMagicIsRefused) {
  // assimp reads every .ply file with its PLY reader and looks for the magic
  // past leading bytes; the checks looked only where the text starts, so
  // these reached assimp: one crashed it (a binary file behind 6 stray
  // bytes), the other (NUL bytes first) made it seek forever.
  fftest::TempDir tmp("fuzz_ply_prefix");
  for (const char* name : {"bytes_before_magic_crash.ply", "nul_bytes_before_magic_hang.ply"}) {
    SCOPED_TRACE(name);
    const std::string what = replay("mesh_ply", kFuzzDir / "regressions" / "mesh_ply" / name, tmp);
    EXPECT_NE(what.find("garbled PLY header (line 1): the first line must be 'ply'"), std::string::npos)
        << what;
  }
}

TEST(FuzzRegressions, PlyHeaderLineWithACarriageReturnInsideIsRefused) {
  // "\n\rend_header\n": the checks took "\rend_header" for end_header, and
  // assimp, which also ends a line at a lone CR, crashed reading the binary
  // data behind it (a fuzzed file). The same header with plain line ends is
  // read (below), so the CR is what is refused.
  fftest::TempDir tmp("fuzz_ply_cr");
  const std::filesystem::path crash =
      kFuzzDir / "regressions" / "mesh_ply" / "carriage_return_before_end_header_crash.ply";
  const std::string what = replay("mesh_ply", crash, tmp);
  EXPECT_NE(what.find("garbled PLY header (line 6): a control character inside a line"), std::string::npos)
      << what;
  std::ifstream in(crash, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t cr = bytes.find("\n\rend_header");
  ASSERT_NE(cr, std::string::npos);
  bytes.erase(cr + 1, 1);
  const std::filesystem::path plain = tmp / "plain.ply";
  std::ofstream(plain, std::ios::binary) << bytes;
  try {
    ff::loadMesh(plain.string());
  } catch (const ff::Error& e) {
    EXPECT_EQ(std::string(e.what()).find("garbled PLY header"), std::string::npos) << e.what();
  }
}

TEST(FuzzRegressions, PlyNamesAndAsciiLinesAreCheckedAsAssimpReadsThem) {
  // assimp read a count of 2^32 - 1 from an element name made of digits and
  // asked for 32 GB (both files); its ASCII reader reads one element per line.
  fftest::TempDir tmp("fuzz_ply_names");
  for (const char* name : {"element_name_of_digits_oom.ply", "empty_face_list_oom.ply"}) {
    SCOPED_TRACE(name);
    const std::string what = replay("mesh_ply", kFuzzDir / "regressions" / "mesh_ply" / name, tmp);
    EXPECT_NE(what.find("garbled PLY header (line 4): unexpected 'element 3333"), std::string::npos) << what;
  }
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string other_faces = "3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const struct {
    const char* first_face;
    const char* after;  // after the last face
    const char* expected;
  } kCases[] = {{"0\n", "", "line 5 after the header (face 1): bad list length 0"},
                {"3 0 1\n", "", "line 5 after the header (face 1): fewer values"},
                {"3 0 1 2 3\n", "", "line 5 after the header (face 1): more values"},
                {"3 0 1 0x2\n", "", "'0x2' is not a number of the declared type"},
                {"256 0 1 2\n", "", "bad list length (missing, or not a count of its type)"},
                {"3 0 2 1\n", "7\n", "data after the last element"}};
  for (const auto& c : kCases) {
    SCOPED_TRACE(c.first_face);
    const fs::path f = tmp.write("case.ply", head + c.first_face + other_faces + c.after);
    try {
      ff::loadMesh(f.string());
      ADD_FAILURE() << "accepted";
    } catch (const ff::Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(ff::loadMesh(tmp.write("tet.ply", head + "3 0 2 1\n" + other_faces).string()));
}

TEST(FuzzRegressions, AMeshWhoseNameGivesNoFormatIsRefused) {
  // Without a known extension assimp guesses the reader from the first
  // bytes; the file's checks are chosen by its name, so the name must say.
  fftest::TempDir tmp("fuzz_mesh_name");
  const std::string cube = readAll(kFuzzDir / "corpus" / "mesh_obj" / "cube_quads.obj");
  for (const char* name : {"cube", "cube.shape"}) {
    SCOPED_TRACE(name);
    const fs::path f = tmp.write(name, cube);
    try {
      ff::loadMesh(f.string());
      ADD_FAILURE() << name << " accepted";
    } catch (const ff::Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(f.string() + ": unknown mesh format"), std::string::npos) << what;
    }
  }
  EXPECT_NO_THROW(ff::loadMesh(tmp.write("cube.OBJ", cube).string()));
}

}  // namespace

namespace {

TEST(FuzzRegressions, OffWithoutTheKeywordHasItsCountsChecked) {
  // An .off file whose "OFF" sits only inside a comment: assimp reads the
  // counts from the first words all the same (the keyword is optional) and
  // asked for 62 GB; the check looked for the keyword and let it through.
  fftest::TempDir tmp("fuzz_off_nokeyword");
  const std::string what =
      replay("mesh_off", kFuzzDir / "regressions" / "mesh_off" / "counts_without_keyword.off", tmp);
  EXPECT_NE(what.find("garbled or truncated OFF file"), std::string::npos) << what;
  const fs::path f = tmp.write("nokey.off", "# a comment\n99999999999 1 0\n0 0 0\n");
  try {
    ff::loadMesh(f.string());
    ADD_FAILURE() << "accepted";
  } catch (const ff::Error& e) {
    EXPECT_NE(std::string(e.what()).find("declares 99999999999 vertices"), std::string::npos) << e.what();
  }
  // The same words in a file of another kind are not OFF counts.
  const fs::path obj = tmp.write("words.obj", "99999999999 1 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  try {
    ff::loadMesh(obj.string());
  } catch (const ff::Error& e) {
    EXPECT_EQ(std::string(e.what()).find("OFF"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

TEST(FuzzRegressions, OffFaceCountsInTheBodyAreBounded) {
  // "#OFF\n#mo cment\n4 3\n33333333333": assimp read the last word as a
  // count and asked for 52 GB; a number above the file's size and 2^24 is refused.
  fftest::TempDir tmp("fuzz_off_body");
  const std::string what =
      replay("mesh_off", kFuzzDir / "regressions" / "mesh_off" / "face_count_in_body.off", tmp);
  EXPECT_NE(what.find("garbled OFF file: the number at byte"), std::string::npos) << what;
  // A cube in millimetres, integer coordinates, stays a valid mesh.
  const fs::path cube =
      tmp.write("mm.off",
                "OFF\n8 12 0\n0 0 0\n1000 0 0\n1000 1000 0\n0 1000 0\n0 0 1000\n1000 0 1000\n"
                "1000 1000 1000\n0 1000 1000\n3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n"
                "3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n");
  EXPECT_NO_THROW(ff::loadMesh(cube.string()));
}

}  // namespace
