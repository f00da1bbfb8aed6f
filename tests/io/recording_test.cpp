#include "rownav/io/recording.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <random>

#include "rownav/io/cloud_io.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

struct RunData {
  std::vector<core::PointCloud> clouds;
  std::vector<core::Scan2D> scans;
  std::vector<core::WheelEncoderSample> enc;
  std::vector<core::ImuSample> imu;
  std::vector<core::GnssFix> gnss;
  std::vector<sim::GroundTruth> gt;
  sim::Field field;
};

RunData make_run() {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  RunData r;
  for (int k = 0; k < 3; ++k) {
    core::PointCloud c;
    c.stamp = 100.0 + 0.1 * k;
    c.has_intensity = true;
    for (int i = 0; i < 50; ++i)
      c.points.push_back({static_cast<float>(u(rng)), static_cast<float>(u(rng)), 0.3f,
                          static_cast<float>(i), 0, 0, 0.0f});
    r.clouds.push_back(c);
    core::Scan2D s;
    s.stamp = c.stamp;
    s.angle_min = -M_PI / 3;
    s.angle_increment = 0.01;
    s.range_max = 20.0;
    s.ranges = {1.1f, 2.2f, std::numeric_limits<float>::infinity()};
    r.scans.push_back(s);
    r.enc.push_back({c.stamp, 1000 * k - 7, -123456789012LL, u(rng)});
    r.imu.push_back({c.stamp, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), 9.81}});
    r.gnss.push_back({c.stamp, k != 1, {u(rng), u(rng), u(rng)}, 0.02});
    sim::GroundTruth g;
    g.stamp = c.stamp;
    g.T_world_base = core::Pose2(u(rng), u(rng), u(rng) / 2.0);
    g.z = u(rng);
    g.twist = {1.0 / 3.0, 0.0, 0.1};
    g.place = k == 2 ? sim::Place::headland : sim::Place::lane;
    g.corridor = k == 2 ? -1 : 4;
    g.left_row = 5;
    g.right_row = k == 2 ? -1 : 4;
    g.lateral_error = u(rng);
    g.plants_crushed = k;
    sim::RowTruth left;
    left.row = 5;
    left.line_base = core::Line2({0.2, 1.0}, {1.0, 0.05});
    g.rows.push_back(left);
    if (k != 2) {
      sim::RowTruth right;
      right.row = 4;
      right.line_base = core::Line2({0.0, -1.1}, {1.0, -0.02});
      g.rows.push_back(right);
    }
    r.gt.push_back(g);
  }
  for (int i = 0; i < 2; ++i) {
    sim::Row row;
    row.id = i;
    row.block = 1;
    row.polyline = {{0.0, 2.0 * i}, {u(rng), 2.0 * i + 0.1}, {50.0, 2.0 * i}};
    r.field.rows.push_back(row);
    r.field.plants.push_back({{u(rng), u(rng)}, 0.04, 1.7, i, sim::PlantKind::post});
  }
  r.field.plants.push_back({{1.5, 0.5}, 0.02, 0.2, -1, sim::PlantKind::weed});
  return r;
}

void write_run(RecordingWriter& w, const RunData& r) {
  w.write_field(r.field);
  for (std::size_t k = 0; k < r.clouds.size(); ++k) {
    w.write_cloud(r.clouds[k]);
    w.write_scan(r.scans[k]);
    w.write_encoders(r.enc[k]);
    w.write_imu(r.imu[k]);
    w.write_gnss(r.gnss[k]);
    w.write_ground_truth(r.gt[k]);
  }
}

class RecordingTest : public ::testing::Test {
 protected:
  fs::path root_ = fs::temp_directory_path() / ("rownav_rec_" + std::to_string(::getpid()));
  fs::path dir_ = root_ / "run";
  void SetUp() override { fs::create_directories(root_); }
  void TearDown() override { fs::remove_all(root_); }
};

TEST_F(RecordingTest, WriteThenReadIsBitIdentical) {
  const RunData r = make_run();
  YAML::Node m;
  m["scenario"] = "vineyard_straight";
  m["seed"] = 42;
  {
    RecordingWriter w(dir_, m);
    write_run(w, r);
    w.commit();
  }
  ASSERT_FALSE(fs::exists(root_ / "run.partial"));
  const Recording rec = read_recording(dir_);
  EXPECT_EQ(rec.manifest["format"].as<std::string>(), "rownav-recording");
  EXPECT_EQ(rec.manifest["version"].as<int>(), 1);
  EXPECT_EQ(rec.manifest["scenario"].as<std::string>(), "vineyard_straight");
  ASSERT_EQ(rec.cloud_count(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const auto c = rec.cloud(k);
    EXPECT_TRUE(same_bits(c.stamp, r.clouds[k].stamp));
    ASSERT_EQ(c.size(), r.clouds[k].size());
    for (std::size_t i = 0; i < c.size(); ++i)
      EXPECT_TRUE(same_bits(c.points[i].x, r.clouds[k].points[i].x) &&
                  same_bits(c.points[i].intensity, r.clouds[k].points[i].intensity));
    EXPECT_TRUE(same_bits(rec.scans[k].angle_min, r.scans[k].angle_min));
    EXPECT_EQ(rec.scans[k].ranges, r.scans[k].ranges);
    EXPECT_TRUE(same_bits(rec.encoders[k].steering_angle, r.enc[k].steering_angle));
    EXPECT_EQ(rec.encoders[k].right_ticks, r.enc[k].right_ticks);
    EXPECT_EQ(rec.imu[k].angular_velocity, r.imu[k].angular_velocity);
    EXPECT_EQ(rec.imu[k].linear_acceleration, r.imu[k].linear_acceleration);
    EXPECT_EQ(rec.gnss[k].valid, r.gnss[k].valid);
    EXPECT_EQ(rec.gnss[k].position_enu, r.gnss[k].position_enu);
    const auto &a = rec.ground_truth[k], &b = r.gt[k];
    EXPECT_TRUE(same_bits(a.T_world_base.x, b.T_world_base.x) &&
                same_bits(a.T_world_base.theta, b.T_world_base.theta) && same_bits(a.z, b.z) &&
                same_bits(a.twist.v, b.twist.v) && same_bits(a.lateral_error, b.lateral_error));
    EXPECT_EQ(a.place, b.place);
    EXPECT_EQ(a.corridor, b.corridor);
    EXPECT_EQ(a.right_row, b.right_row);
    EXPECT_EQ(a.plants_crushed, b.plants_crushed);
    ASSERT_EQ(a.rows.size(), b.rows.size());
    for (std::size_t j = 0; j < a.rows.size(); ++j) {
      EXPECT_EQ(a.rows[j].row, b.rows[j].row);
      EXPECT_NEAR(a.rows[j].line_base.y_at(3.0), b.rows[j].line_base.y_at(3.0), 1e-12);
      EXPECT_NEAR(a.rows[j].line_base.heading(), b.rows[j].line_base.heading(), 1e-15);
    }
  }
  ASSERT_EQ(rec.rows.size(), 2u);
  EXPECT_EQ(rec.rows[1].polyline, r.field.rows[1].polyline);
  EXPECT_EQ(rec.rows[1].block, 1);
  ASSERT_EQ(rec.plants.size(), 3u);
  EXPECT_EQ(rec.plants[2].kind, sim::PlantKind::weed);
  EXPECT_EQ(rec.plants[0].position, r.field.plants[0].position);
  EXPECT_EQ(rec.plants[1].row, 1);
}

TEST_F(RecordingTest, UncommittedRunLeavesNothing) {
  try {
    RecordingWriter w(dir_, {});
    w.write_cloud(make_run().clouds[0]);
    EXPECT_TRUE(fs::exists(w.partial_dir() / "lidar/000000.pcd"));
    EXPECT_FALSE(fs::exists(dir_));
    throw std::runtime_error("simulated failure mid-run");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(dir_));
  for (const auto& e : fs::directory_iterator(root_))  // no staging folder left either
    EXPECT_EQ(e.path().filename().string().find(".rownav-partial"), std::string::npos) << e.path();
}

TEST_F(RecordingTest, ReplacesOnlyAnEarlierRecordingAndOnlyWithOverwrite) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "keep.txt") << "x";
  EXPECT_THROW(RecordingWriter(dir_, {}), std::runtime_error);
  EXPECT_THROW(RecordingWriter(dir_, {}, true), std::runtime_error);  // not rownav's folder
  EXPECT_TRUE(fs::exists(dir_ / "keep.txt"));
  fs::remove_all(dir_);
  for (int imu : {2, 1}) {
    RecordingWriter w(dir_, {}, true);
    for (int i = 0; i < imu; ++i) w.write_imu({});
    w.commit();
  }
  EXPECT_EQ(read_recording(dir_).imu.size(), 1u);
  EXPECT_THROW(RecordingWriter(dir_, {}), std::runtime_error);  // without --overwrite
}

TEST_F(RecordingTest, MalformedCsvNamesFileAndLine) {
  {
    RecordingWriter w(dir_, {});
    write_run(w, make_run());
    w.commit();
  }
  std::ofstream(dir_ / "imu.csv", std::ios::app) << "1.0,2,3,4,5,6,oops\n";
  try {
    read_recording(dir_);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir_ / "imu.csv").string() + ":5: expected a number in column 'az', got 'oops'");
  }
  std::ofstream(dir_ / "imu.csv") << "stamp,gx\n";
  EXPECT_THROW(read_recording(dir_), InputError);
  fs::remove(dir_ / "imu.csv");
  std::ofstream(dir_ / "ground_truth.csv", std::ios::app) << "1,2\n";
  try {
    read_recording(dir_);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir_ / "ground_truth.csv").string() + ":5: expected 22 columns, got 2");
  }
  std::ofstream(dir_ / "manifest.yaml") << "format: something\n";
  EXPECT_THROW(read_recording(dir_), InputError);
  EXPECT_THROW(read_recording(root_ / "nope"), InputError);
}

}  // namespace
}  // namespace rownav::io
