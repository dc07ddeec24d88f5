// The PLY check that runs before assimp reads a cloud: a file written by
// write_ply passes with its counts; a cut, short or malformed one is one
// error naming the file, where assimp would pad it and go on.
#include "slam/io/ply_file.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "common/testing/scratch_folder.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace depot::slam {
namespace {

class PlyCheckTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return scratch_.file(name); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
    return path(name);
  }
  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
  }
  std::string written_cloud(size_t n) const {
    std::vector<PlyPoint> points(n);
    for (size_t i = 0; i < n; ++i) points[i].position = Eigen::Vector3f(float(i), 1.f, 2.f);
    write_ply(path("cloud.ply"), points, "observations");
    return path("cloud.ply");
  }
  testkit::ScratchFolder scratch_{"ply_test"};
};

TEST_F(PlyCheckTest, AWrittenCloudPassesWithItsCounts) {
  const std::string p = written_cloud(100);
  const PlyCheck c = check_ply_file(p);
  EXPECT_EQ(c.format, "binary_little_endian");
  EXPECT_EQ(c.vertices, 100u);
  EXPECT_TRUE(c.only_vertices);
  EXPECT_EQ(c.header_bytes + c.data_bytes, fs::file_size(p));
  EXPECT_EQ(c.data_bytes, 100u * (3 * 4 + 3 + 4));
}

TEST_F(PlyCheckTest, ACutBinaryCloudIsRefused) {
  const std::string whole = read(written_cloud(1000));
  const std::string cut = write("cut.ply", whole.substr(0, 3000));
  EXPECT_THAT(error_of([&] { check_ply_file(cut); }),
              HasSubstr("cut.ply: is shorter than its header declares: element 'vertex' ends at "
                        "row "));
  // One byte short is short too.
  const std::string one = write("one.ply", whole.substr(0, whole.size() - 1));
  EXPECT_THAT(error_of([&] { check_ply_file(one); }), HasSubstr("row 999 of 1000"));
}

TEST_F(PlyCheckTest, AnAsciiCloudWithFewerRowsThanDeclaredIsRefused) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 100\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  const std::string p = write("rows.ply", header + "0 0 0\n1 1 1\n");
  EXPECT_THAT(error_of([&] { check_ply_file(p); }),
              HasSubstr("rows.ply: is shorter than its header declares: element 'vertex' ends at "
                        "row 2 of 100"));
  const std::string good =
      write("good.ply", header.substr(0, header.find("100")) + "2" +
                            header.substr(header.find("100") + 3) + "0 0 0\n1 1 1\n");
  EXPECT_EQ(check_ply_file(good).vertices, 2u);
  const std::string word = write("word.ply", header + "0 0 zero\n");
  EXPECT_THAT(error_of([&] { check_ply_file(word); }),
              HasSubstr("word.ply:8: 'zero' is not a number"));
  const std::string few = write("few.ply", header + "0 0\n");
  EXPECT_THAT(error_of([&] { check_ply_file(few); }),
              HasSubstr("few.ply:8: has 2 values where element 'vertex' has 3 properties"));
}

TEST_F(PlyCheckTest, ListElementsAreWalkedRowByRow) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  bytes += std::string(4, '\0');                          // the vertex
  bytes += std::string(1, '\3') + std::string(12, '\0');  // a triangle
  const std::string whole =
      write("faces.ply", bytes + std::string(1, '\3') + std::string(12, '\0'));
  EXPECT_FALSE(check_ply_file(whole).only_vertices);
  const std::string cut =
      write("faces-cut.ply", bytes + std::string(1, '\3') + std::string(8, '\0'));
  EXPECT_THAT(error_of([&] { check_ply_file(cut); }),
              HasSubstr("element 'face' ends at row 1 of 2"));
}

TEST_F(PlyCheckTest, BadHeadersAreOneErrorEach) {
  const struct {
    const char* bytes;
    const char* problem;
  } cases[] = {
      {"", "is empty"},
      {"PLY\n", "not a PLY file"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "has no end_header line"},
      {"ply\nelement vertex 0\nend_header\n", "has no format line"},
      {"ply\nformat text 1.0\nend_header\n", ":2: unknown format 'text'"},
      {"ply\nformat ascii 1.0\nelement vertex -3\nend_header\n",
       ":3: element 'vertex' has no valid count"},
      {"ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nend_header\n",
       ":3: element 'vertex' has no valid count"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n",
       ":3: a property before any element"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
       ":4: unknown property type 'float128'"},
      {"ply\nformat ascii 1.0\nvertex 1\nend_header\n", ":3: unknown header line 'vertex'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x y\nend_header\n",
       ":4: unexpected 'y' after property 'x'"},
  };
  int i = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.bytes);
    const std::string p = write("bad" + std::to_string(i++) + ".ply", c.bytes);
    EXPECT_THAT(error_of([&] { check_ply_file(p); }, "(no error)"), HasSubstr(c.problem));
  }
  // fuzz_ply_file's find: NUL bytes inside a property line passed this check
  // and kept assimp reading for ever.
  const std::string nul_header(
      "ply\nformat ascii 2.0\nelement vertex 3\nproperty float x\0\0\0"
      "roperty f verxte_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
      111);
  EXPECT_THAT(error_of([&] { check_ply_file(write("nul.ply", nul_header)); }, "(no error)"),
              HasSubstr(":4: holds a control byte (0x00); a PLY header is text"));
  EXPECT_THAT(error_of([&] { check_ply_file(path("absent.ply")); }),
              HasSubstr("absent.ply: no such file"));
}

TEST_F(PlyCheckTest, AHugeDeclaredCountDoesNotOverflow) {
  const std::string p = write(
      "huge.ply",
      "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\nproperty double "
      "x\nproperty double y\nend_header\n" +
          std::string(32, '\0'));
  EXPECT_THAT(error_of([&] { check_ply_file(p); }),
              HasSubstr("is shorter than its header declares"));
}

}  // namespace
}  // namespace depot::slam
