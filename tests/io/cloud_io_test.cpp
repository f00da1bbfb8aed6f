#include "rownav/io/cloud_io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "rownav/io/input_error.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

void expect_identical(const core::PointCloud& a, const core::PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(&a.stamp, &b.stamp, sizeof a.stamp), 0);
  EXPECT_EQ(a.frame_id, b.frame_id);
  EXPECT_EQ(a.has_intensity, b.has_intensity);
  EXPECT_EQ(a.has_ring, b.has_ring);
  EXPECT_EQ(a.has_time, b.has_time);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto &p = a.points[i], &q = b.points[i];
    ASSERT_TRUE(same_bits(p.x, q.x) && same_bits(p.y, q.y) && same_bits(p.z, q.z) &&
                same_bits(p.intensity, q.intensity) && same_bits(p.time, q.time) &&
                p.ring == q.ring && p.column == q.column)
        << "point " << i;
  }
}

core::PointCloud random_cloud(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  core::PointCloud c;
  c.stamp = 1700000000.123456789;
  c.frame_id = "os_sensor";
  c.has_intensity = true;
  c.has_ring = true;
  c.has_time = false;
  for (std::size_t i = 0; i < n; ++i) {
    core::PointXYZIRT p{u(rng),
                        u(rng),
                        u(rng) / 10.0f,
                        std::abs(u(rng)),
                        static_cast<std::uint16_t>(i % 128),
                        static_cast<std::uint16_t>(i % 2048),
                        static_cast<float>(i) * 1e-7f};
    c.points.push_back(p);
  }
  return c;
}

class CloudIoTest : public ::testing::Test {
 protected:
  fs::path dir_ = fs::temp_directory_path() / ("rownav_cloud_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  std::string error_of(const fs::path& f) {
    try {
      read_cloud(f);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      return e.what();
    }
    return "";
  }
};

TEST_F(CloudIoTest, PcdRoundTripBinaryAndAsciiIsBitIdentical) {
  const auto cloud = random_cloud(5000, 7);
  write_cloud_pcd(dir_ / "b.pcd", cloud, true);
  write_cloud_pcd(dir_ / "a.pcd", cloud, false);
  expect_identical(read_cloud(dir_ / "b.pcd"), cloud);
  expect_identical(read_cloud(dir_ / "a.pcd"), cloud);
  core::PointCloud empty;
  write_cloud_pcd(dir_ / "e.pcd", empty);
  expect_identical(read_cloud(dir_ / "e.pcd"), empty);
}

TEST_F(CloudIoTest, NanAndInfPointsAreDropped) {
  auto cloud = random_cloud(10, 1);
  cloud.points[3].x = std::numeric_limits<float>::quiet_NaN();
  cloud.points[7].z = std::numeric_limits<float>::infinity();
  write_cloud_pcd(dir_ / "n.pcd", cloud);
  const auto back = read_cloud(dir_ / "n.pcd");
  ASSERT_EQ(back.size(), 8u);
  EXPECT_EQ(back.points[3].ring, 4);
  EXPECT_EQ(back.points[6].ring, 8);
}

TEST_F(CloudIoTest, ForeignPcdWithOusterTimeAndDoubleXyz) {
  // Field order and types as a driver might write them: t = uint32 nanoseconds.
  const auto f = write("ouster.pcd",
                       "VERSION 0.7\nFIELDS t x y z reflectivity ring\nSIZE 4 8 8 8 2 1\n"
                       "TYPE U F F F U U\nCOUNT 1 1 1 1 1 1\nWIDTH 3\nHEIGHT 1\n"
                       "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n"
                       "0 1.5 2 3 10 0\n50000000 nan 1 1 5 1\n100000000 -1 -2 -3 7 63\n");
  const auto c = read_cloud(f);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_TRUE(c.has_time);
  EXPECT_TRUE(c.has_ring);
  EXPECT_FALSE(c.has_intensity);
  EXPECT_FLOAT_EQ(c.points[0].x, 1.5f);
  EXPECT_FLOAT_EQ(c.points[1].time, 0.1f);
  EXPECT_EQ(c.points[1].ring, 63);
  EXPECT_FLOAT_EQ(c.points[1].z, -3.0f);
}

TEST_F(CloudIoTest, BinaryCompressedPcd) {
  // binary_compressed stores the fields one after the other (x x y y z z), LZF-compressed.
  // An LZF stream of only literal runs is valid: control byte n-1, then n raw bytes.
  const float xyz[6] = {1.0f, 4.0f, 2.0f, 5.0f, 3.0f, 6.0f};  // x0 x1 y0 y1 z0 z1
  std::string data(1, static_cast<char>(sizeof xyz - 1));
  data.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(data.size()), sizeof xyz};
  const std::string head =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA binary_compressed\n";
  const auto c = read_cloud(write(
      "z.pcd", head + std::string(reinterpret_cast<const char*>(sizes), sizeof sizes) + data));
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c.points[0].x, 1.0f);
  EXPECT_EQ(c.points[1].y, 5.0f);
  EXPECT_EQ(c.points[1].z, 6.0f);
  EXPECT_FALSE(c.has_intensity || c.has_ring || c.has_time);
}

TEST_F(CloudIoTest, PlyAsciiWithIntensity) {
  const auto f = write("c.ply",
                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                       "property float y\nproperty float z\nproperty float intensity\n"
                       "end_header\n1 2 3 0.5\n4 5 6 1.5\n-1 -2 -3 9\n");
  const auto c = read_cloud(f);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_TRUE(c.has_intensity);
  EXPECT_FLOAT_EQ(c.points[1].y, 5.0f);
  EXPECT_FLOAT_EQ(c.points[2].intensity, 9.0f);
}

TEST_F(CloudIoTest, BadFilesGiveOneLineErrors) {
  EXPECT_NE(error_of(dir_ / "missing.pcd").find("missing.pcd: cannot open"), std::string::npos);
  EXPECT_NE(error_of(write("empty.pcd", "")).find("empty.pcd: empty file"), std::string::npos);
  EXPECT_NE(error_of(write("junk.pcd", "hello\nworld\n")).find("not a valid PCD"),
            std::string::npos);
  EXPECT_NE(error_of(write("c.xyz", "1 2 3\n")).find("unknown cloud format"), std::string::npos);
  EXPECT_NE(error_of(write("noz.pcd",
                           "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\n"
                           "HEIGHT 1\nPOINTS 1\nDATA ascii\n1 2\n"))
                .find("no x / y / z"),
            std::string::npos);
  const std::string head =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 1\n"
      "POINTS 4\nDATA ";
  EXPECT_NE(
      error_of(write("trunc.pcd", head + "binary\n" + std::string(20, 'a'))).find("truncated"),
      std::string::npos);
  EXPECT_NE(error_of(write("comp.pcd", head + "binary_compressed\n" + std::string(5, 'a')))
                .find("compressed"),
            std::string::npos);
  EXPECT_NE(error_of(write("pts.pcd",
                           "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4\nPOINTS 5\n"
                           "DATA ascii\n"))
                .find("POINTS"),
            std::string::npos);
  EXPECT_NE(error_of(write("ty.pcd",
                           "FIELDS x y z\nSIZE 4 4 3\nTYPE F F F\nWIDTH 0\nPOINTS 0\n"
                           "DATA ascii\n"))
                .find("field z"),
            std::string::npos);
  EXPECT_NE(error_of(write("junk.ply", "ply\nformat ascii 1.0\nelement vertex 9\nend_header\n1\n"))
                .find("junk.ply"),
            std::string::npos);
  EXPECT_NE(error_of(write("junk2.ply", "hello\n")).find("not a valid PLY"), std::string::npos);
  // Short ascii lines: PCL reports them; we must neither crash nor accept silently.
  const std::string ascii = error_of(write("short.pcd", head + "ascii\n1 2 3\n4 5\n"));
  EXPECT_FALSE(ascii.empty());
}

TEST_F(CloudIoTest, HeadersPclWouldCrashOnAreRefusedWithTheirLine) {
  const std::string body =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n";
  // PCL 1.13 crashes on an unknown first keyword (a corrupted "# .PCD" comment, "FERSION").
  for (const std::string first : {"FOO 1\n", "3 .PCD v0.7\n", "FERSION 0.7\n"}) {
    const std::string e = error_of(write("key.pcd", first + body));
    EXPECT_NE(e.find("key.pcd:line 1: not a valid PCD file (unknown header keyword"),
              std::string::npos)
        << e;
  }
  // A header line of control bytes (vertical tabs, pcd_fuzz): PCL 1.13 segfaults on it.
  const std::string vt = error_of(write("vt.pcd", "VERSION 0.7\n\x0b\n" + body));
  EXPECT_NE(vt.find("vt.pcd:line 2: not a valid PCD file (control character"), std::string::npos)
      << vt;
  // A header line of blanks only (a tab, spaces, a CRLF blank line; pcd_fuzz): PCL 1.13
  // segfaults when it precedes the header (fuzz/corpus/pcd/blank_header_line_crash.pcd).
  for (const std::string blank : {"\t\n", "   \n", "\r\n"}) {
    const std::string e = error_of(write("blank.pcd", blank + "VERSION 0.7\n" + body));
    EXPECT_NE(e.find("blank.pcd:line 1: not a valid PCD file (a header line of blanks only)"),
              std::string::npos)
        << e;
  }
  EXPECT_EQ(read_cloud(write("empty_line.pcd", "\nVERSION 0.7\n" + body)).size(), 1u);
  // More points than the data can hold: PCL would allocate them all.
  const std::string many =
      error_of(write("many.pcd",
                     "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2000000000\nHEIGHT 1\n"
                     "POINTS 2000000000\nDATA ascii\n1 2 3\n"));
  EXPECT_NE(many.find("do not fit"), std::string::npos) << many;
  const std::string wide =
      error_of(write("wide.pcd",
                     "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4294967296\nHEIGHT 1\n"
                     "POINTS 0\nDATA ascii\n"));
  EXPECT_NE(wide.find(":line 4: not a valid PCD file (WIDTH must be"), std::string::npos) << wide;
  // PLY counts of 2^32 / -2^63 trip a PCL assertion; counts beyond the data are refused too.
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex ";
  const std::string props = "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (const std::string n : {"4294967296", "-9223372036854775808", "1000"}) {
    const std::string e = error_of(write("n.ply", ply + n + props + "1 2 3\n"));
    EXPECT_NE(e.find("n.ply:line 3: not a valid PLY file (element 'vertex'"), std::string::npos)
        << e;
  }
  const std::string bin =
      error_of(write("b.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2" + props +
                                  std::string(12, '\0')));
  EXPECT_NE(bin.find("2 elements do not fit the 12 bytes"), std::string::npos) << bin;
  EXPECT_EQ(read_cloud(write("ok.ply", ply + "1" + props + "1 2 3\n")).size(), 1u);
}

// Found by pcd_fuzz (issue 13): PCL reads on past DATA while a line starts with a keyword
// ("COLUMNS" = FIELDS), a heap use-after-free on binary data that starts so.
TEST_F(CloudIoTest, DataThatPclWouldReadAsHeaderIsRefused) {
  const std::string head = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nPOINTS 2\nDATA binary\n";
  // "\v# c": a comment to PCL, which skips every isspace() byte before a line's first word.
  for (const std::string start :
       {"COLUMNS a b\n", "\n# c\nFIELDSx\n", "SIZE 8\n", "\v# c\nFIELDS x\n", "\f SIZE 4\n"}) {
    const std::string e = error_of(write("d.pcd", head + start + std::string(24, '\0')));
    EXPECT_NE(e.find("d.pcd:line "), std::string::npos) << e;
    EXPECT_NE(e.find(", which PCL would read as header)"), std::string::npos) << e;
  }
  EXPECT_EQ(read_cloud(write("d.pcd", head + std::string(24, '\0'))).size(), 2u);
}

// Found by the 600 s fuzz runs (issue 13, 2026-12-04).
TEST_F(CloudIoTest, FuzzFoundValuesAndListsGiveOneLineErrorsOrDroppedPoints) {
  // A ring far outside 0..65535 (UBSan: double -> uint16 cast) is refused with its point.
  const std::string head =
      "FIELDS x y z ring\nSIZE 4 4 4 4\nTYPE F F F F\nWIDTH 2\nPOINTS 2\n"
      "DATA ascii\n";
  const std::string ring = error_of(write("r.pcd", head + "1 2 3 4\n1 2 3 13893600\n"));
  EXPECT_NE(ring.find("r.pcd:point 1: ring 13893600"), std::string::npos) << ring;
  EXPECT_NE(ring.find("is not in 0..65535"), std::string::npos) << ring;
  EXPECT_NE(error_of(write("n.pcd", head + "1 2 3 -1\n1 2 3 4\n")).find("ring -1"),
            std::string::npos);
  // A double coordinate beyond float's range is no point (dropped, as NaN / Inf are).
  const auto big = read_cloud(write("big.pcd",
                                    "FIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nWIDTH 2\nPOINTS 2\n"
                                    "DATA ascii\n1e300 0 0\n1 2 3\n"));
  ASSERT_EQ(big.size(), 1u);
  EXPECT_FLOAT_EQ(big.points[0].x, 1.0f);
  // A list property in the vertex element trips a PCL assertion: refused from the header.
  const std::string list =
      error_of(write("l.ply",
                     "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\n"
                     "property double y\nproperty list uchar int vertex_indices\nend_header\n"
                     "1 2 3 7 1 0\n"));
  EXPECT_NE(list.find("l.ply:line 6: not a valid PLY file (list property 'vertex_indices' in "
                      "element 'vertex'"),
            std::string::npos)
      << list;
}

TEST(InputError, ControlCharactersFromAFileAreEscapedIntoOneLine) {
  const InputError e("a.mcap", "byte 75", "channel '\n:\x1b[31m' names unknown schema 3");
  EXPECT_STREQ(e.what(), "a.mcap:byte 75: channel '\\n:\\x1b[31m' names unknown schema 3");
}

TEST(PointsCsv, CornRowsDataset) {
  const auto clouds = read_points_csv(fs::path(ROWNAV_SHARED_DATA) / "corn_rows_2d/scans.csv");
  ASSERT_EQ(clouds.size(), 1630u);
  std::size_t points = 0;
  for (const auto& c : clouds) points += c.size();
  EXPECT_EQ(points, 660641u);
  EXPECT_EQ(clouds.front().stamp, 1.0);
  EXPECT_FLOAT_EQ(clouds.front().points[0].x, -0.0995f);
  EXPECT_FLOAT_EQ(clouds.front().points[0].y, -0.1f);
  EXPECT_EQ(clouds.front().points[0].z, 0.0f);
}

TEST_F(CloudIoTest, PointsCsvHeaderlessStampAndErrors) {
  const auto a = read_points_csv(write("a.csv", "1,2\n3,4\n"));
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].size(), 2u);
  const auto b =
      read_points_csv(write("b.csv", "x,stamp,y,frame\n1,10.5,2,a\n3,11,4,b\n5,12,6,a\n"));
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0].size(), 2u);
  EXPECT_EQ(b[0].stamp, 10.5);
  EXPECT_EQ(b[1].stamp, 11.0);
  EXPECT_FLOAT_EQ(b[0].points[1].x, 5.0f);
  const auto f = write("bad.csv", "frame,x,y\n1,0,0\n1,0,0\n1,0.5,zz\n");
  try {
    read_points_csv(f);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), f.string() + ":4: expected a number in column 'y', got 'zz'");
  }
  EXPECT_THROW(read_points_csv(write("cols.csv", "x,y\n1,2\n1,2,3\n")), InputError);
  EXPECT_THROW(read_points_csv(write("unk.csv", "x,y,w\n1,2,3\n")), InputError);
  EXPECT_THROW(read_points_csv(dir_ / "none.csv"), InputError);
  EXPECT_TRUE(read_points_csv(write("empty.csv", "")).empty());
}

// Found by points_csv_fuzz (issue 13): a '\r' in an unknown header cell broke the one line.
TEST_F(CloudIoTest, PointsCsvUnknownColumnIsEscaped) {
  try {
    read_points_csv(write("cr.csv", "x,y,a\rb\x01\n1,2,3\n"));
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cr.csv:1: unknown column 'a\\rb?'"), std::string::npos)
        << e.what();
  }
}

TEST_F(CloudIoTest, ScansCsvRoundTrip) {
  std::vector<core::Scan2D> scans(3);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    auto& s = scans[k];
    s.stamp = 0.1 * static_cast<double>(k) + 1e9;
    s.angle_min = -M_PI;
    s.angle_increment = 2 * M_PI / 7.0;
    s.range_min = 0.1;
    s.range_max = 30.0;
    s.ranges = {1.0f / 3.0f, std::numeric_limits<float>::infinity(), 2.5f, 1e-7f};
  }
  scans[1].ranges.push_back(std::numeric_limits<float>::quiet_NaN());
  scans[2].ranges.clear();
  write_scans_csv(dir_ / "s.csv", scans);
  const auto back = read_scans_csv(dir_ / "s.csv");
  ASSERT_EQ(back.size(), scans.size());
  for (std::size_t k = 0; k < scans.size(); ++k) {
    EXPECT_EQ(back[k].stamp, scans[k].stamp);
    EXPECT_EQ(back[k].angle_increment, scans[k].angle_increment);
    EXPECT_EQ(back[k].range_max, scans[k].range_max);
    ASSERT_EQ(back[k].ranges.size(), scans[k].ranges.size());
    for (std::size_t i = 0; i < scans[k].ranges.size(); ++i)
      EXPECT_TRUE(same_bits(back[k].ranges[i], scans[k].ranges[i]) ||
                  (std::isnan(back[k].ranges[i]) && std::isnan(scans[k].ranges[i])));
  }
  const auto bad = write("bad.csv", std::string(kScansCsvHeader) + "\n1,0,0.1,0,10,1,2\n2,0,0.1\n");
  try {
    read_scans_csv(bad);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), bad.string() + ":3: expected at least 5 columns, got 3");
  }
}

}  // namespace
}  // namespace rownav::io
