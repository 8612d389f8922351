// Reading points and writing lists: round trips, every text flavour, and every malformed file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/io.hpp"
#include "horizon/search.hpp"

namespace horizon {
namespace {

namespace fs = std::filesystem;

class IoTest : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("horizon_io_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  // The message of the horizon::Error that reading `file` throws.
  static std::string read_error(const std::string& file) {
    try {
      read_points(file);
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  }
  fs::path dir_;
};

TEST_F(IoTest, NpyRoundTrip) {
  const PointSet points = random_cloud(100, 3, 1);
  write_points(path("p.npy"), points);
  const PointSet back = read_points(path("p.npy"));
  EXPECT_EQ(back.dims, 3);
  EXPECT_EQ(back.xyz, points.xyz);
}

TEST_F(IoTest, TextRoundTripIsExact) {
  const PointSet points = random_cloud(100, 2, 1);
  write_points(path("p.csv"), points);
  EXPECT_EQ(read_points(path("p.csv")).xyz, points.xyz);
}

TEST_F(IoTest, TextFlavours) {
  const auto csv = read_points(write("a.csv", "x,y,z\n# comment\n1,2,3\n\n4, 5, 6 # trailing\n"));
  EXPECT_EQ(csv.dims, 3);
  EXPECT_EQ(csv.xyz, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  const auto xyz = read_points(write("b.xyz", "1 2\n3\t4\n"));
  EXPECT_EQ(xyz.dims, 2);
  // Peridigm's text discretization: x y z block_id volume.
  const auto peridigm = read_points(write("c.txt", "# x y z block_id volume\n0 0 0 1 0.001\n1e-1 2 3 2 0.001\n"));
  EXPECT_EQ(peridigm.dims, 3);
  EXPECT_EQ(peridigm.xyz, (std::vector<double>{0, 0, 0, 0.1, 2, 3}));
}

TEST_F(IoTest, MalformedTextNamesFileAndLine) {
  const auto ragged = write("r.csv", "1 2 3\n4 5\n");
  EXPECT_NE(read_error(ragged).find("r.csv:2: expected 3 columns, found 2"), std::string::npos) << read_error(ragged);
  const auto word = write("w.csv", "1 2 3\n4 five 6\n");
  EXPECT_NE(read_error(word).find("w.csv:2: 'five' is not a number"), std::string::npos) << read_error(word);
  const auto nan = write("n.csv", "1 2 3\n4 nan 6\n");
  EXPECT_NE(read_error(nan).find("n.csv:2: non-finite coordinate"), std::string::npos) << read_error(nan);
  const auto four = write("f.csv", "1 2 3 4\n");
  EXPECT_NE(read_error(four).find("f.csv:1: expected 2 or 3 columns"), std::string::npos) << read_error(four);
  EXPECT_NE(read_error(path("missing.csv")).find("missing.csv: cannot open"), std::string::npos);
}

TEST_F(IoTest, MalformedNpy) {
  const std::string magic("\x93NUMPY\x01\x00", 8);
  auto npy = [&](const std::string& name, const std::string& header, std::size_t data_bytes) {
    std::string h = header;
    while ((10 + h.size() + 1) % 64) h += ' ';
    h += '\n';
    std::string text = magic + std::string(1, static_cast<char>(h.size() & 0xff)) +
                       std::string(1, static_cast<char>(h.size() >> 8)) + h + std::string(data_bytes, '\0');
    return write(name, text);
  };
  EXPECT_NE(read_error(npy("be.npy", "{'descr': '>f8', 'fortran_order': False, 'shape': (2, 3), }", 48))
                .find("big-endian"), std::string::npos);
  EXPECT_NE(read_error(npy("i.npy", "{'descr': '<i4', 'fortran_order': False, 'shape': (2, 3), }", 24))
                .find("expected float64 or float32"), std::string::npos);
  EXPECT_NE(read_error(npy("s.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 4), }", 64))
                .find("N x 2 or N x 3"), std::string::npos);
  EXPECT_NE(read_error(npy("t.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", 40))
                .find("truncated"), std::string::npos);
  // A header promising 2.4 TB in a small file: the header and the file size disagree (not "out
  // of memory"), and nothing that large is allocated.
  const std::string huge = read_error(npy("h.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (100000000000, 3), }", 4800));
  EXPECT_NE(huge.find("needs 2400000000000 bytes of data, the file holds 4800"), std::string::npos) << huge;
  EXPECT_NE(read_error(npy("o.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (4000000000000000000, 3), }", 8))
                .find("too large"), std::string::npos);
  EXPECT_NE(read_error(write("m.npy", "not numpy")).find("bad magic"), std::string::npos);
  // Found by the fuzzer: a version 2 header length of 4 GB was allocated before it was read.
  const std::string v2_huge_header = read_error(write("v2.npy", std::string("\x93NUMPY\x02\x00\x00\x00\x00\xff{'descr'", 18)));
  EXPECT_NE(v2_huge_header.find("truncated .npy header (4278190080 bytes announced, 6 in the file)"), std::string::npos)
      << v2_huge_header;
  // float32 and Fortran order are read correctly.
  const std::string values("\x00\x00\x80\x3f\x00\x00\x00\x40\x00\x00\x40\x40\x00\x00\x80\x40", 16);
  std::string h = "{'descr': '<f4', 'fortran_order': True, 'shape': (2, 2), }";
  while ((10 + h.size() + 1) % 64) h += ' ';
  h += '\n';
  const auto f32 = read_points(write("f32.npy", magic + std::string(1, static_cast<char>(h.size())) + std::string(1, '\0') + h + values));
  EXPECT_EQ(f32.xyz, (std::vector<double>{1, 3, 2, 4}));
  // A non-finite coordinate is named by its point, float64 (read straight into the points) and
  // float32 alike.
  for (const bool single : {false, true}) {
    std::string data;
    for (int e = 0; e < 9; ++e) {
      const double x = e == 5 ? HUGE_VAL : e;
      const float f = static_cast<float>(x);
      data += single ? std::string(reinterpret_cast<const char*>(&f), 4) : std::string(reinterpret_cast<const char*>(&x), 8);
    }
    const std::string file = npy(single ? "inf4.npy" : "inf8.npy",
                                 single ? "{'descr': '<f4', 'fortran_order': False, 'shape': (3, 3), }"
                                        : "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 3), }", 0);
    std::ofstream(file, std::ios::app | std::ios::binary) << data;
    EXPECT_NE(read_error(file).find("point 1 has a non-finite coordinate"), std::string::npos) << read_error(file);
  }
}

TEST_F(IoTest, ListRoundTripsInBothFormats) {
  const PointSet points = random_cloud(500, 3, 3);
  SearchOptions options;
  options.horizon = 1.5;
  const NeighborList list = search(points.view(), options);
  write_neighbor_list(path("l"), list, ListFormat::npy);
  EXPECT_EQ(read_neighbor_list(path("l"), 500, false), list);
  write_neighbor_list(path("c"), list, ListFormat::csv);
  EXPECT_EQ(read_neighbor_list(path("c"), 500, false), list);
}

TEST_F(IoTest, WritesAreAtomicAndNameTheDirectory) {
  try {
    write_points(path("nowhere/p.npy"), random_cloud(3));
    FAIL() << "wrote into a missing directory";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  write_points(path("p.npy"), random_cloud(10));
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace horizon
