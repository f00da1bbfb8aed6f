// End-to-end tests of `rownav track`: a short simulated vineyard recording, detector + tracker.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/cli_runner.hpp"

namespace rownav {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::Result;
using test::rownav;
using test::TempDir;

TEST(TrackCli, TracksARecordingAndScoresItAgainstTheTruth) {
  TempDir dir;
  std::ofstream(dir / "field.yaml")
      << "kind: vineyard\nname: tiny\nseed: 3\nvineyard:\n  rows: 3\n  row_length: 6.0\n";
  const Result sim = rownav(dir.path(), "sim --field field.yaml --out rec --quiet");
  ASSERT_EQ(sim.code, 0) << sim.err;
  const std::string detect = std::string(ROWNAV_SOURCE_DIR) + "/config/detect/vineyard.yaml";
  const std::string track = std::string(ROWNAV_SOURCE_DIR) + "/config/track/default.yaml";
  const Result r = rownav(dir.path(),
                          "track --in rec --detector hough_skew --tracker line_ekf "
                          "--out t.csv --svg t.svg --detect-config " +
                              detect + " --track-config " + track);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("line_ekf on hough_skew"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lateral RMSE"), std::string::npos) << r.out;
  // The Localizer on the recorded encoders + IMU, configured from the manifest's robot.
  EXPECT_EQ(r.out.rfind("odometry: Localizer, nominal kinematics of the manifest's robot\n", 0),
            0u)
      << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2) << r.out;
  const Result t = rownav(dir.path(),
                          "track --in rec --detector hough_skew --tracker line_ekf --out u.csv "
                          "--odometry truth");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(t.out.rfind("odometry: recorded ground truth\n", 0), 0u) << t.out;
  const std::string csv = read_file(dir / "t.csv");
  EXPECT_EQ(csv.rfind("stamp,status,confidence,lateral,heading_deg,spacing,true_lateral", 0), 0u);
  EXPECT_NE(csv.find(",tracking,"), std::string::npos);
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 20);
  EXPECT_TRUE(fs::exists(dir / "t.svg"));
  EXPECT_FALSE(fs::exists(dir / "t.csv.partial"));
}

TEST(TrackCli, BadInputIsOneLineAndExitCode2) {
  TempDir dir;
  fs::create_directories(dir / "empty");
  std::ofstream(dir / "bad.yaml") << "line_ekf:\n  gatee: 1\n";
  for (const std::string args :
       {"track --in empty --detector hough_skew --tracker line_ekf --out t.csv",
        "track --in . --detector hough_skew --tracker kalman --out t.csv"}) {
    const Result r = rownav(dir.path(), args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "t.csv"));
  }
}

}  // namespace
}  // namespace rownav
