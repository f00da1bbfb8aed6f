// Every YAML file shipped under config/ loads through the strict loader the commands use, so a
// renamed or removed config field cannot leave a stale example behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "rownav/io/field_builder.hpp"
#include "rownav/io/sim_setup.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/navigate/nav_stack_config.hpp"
#include "rownav/sim/field_config.hpp"
#include "rownav/sim/robot.hpp"
#include "rownav/sim/scripted_path.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> yaml_files(const char* folder) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(fs::path(ROWNAV_SOURCE_DIR) / "config" / folder))
    if (e.path().extension() == ".yaml") out.push_back(e.path());
  return out;
}

TEST(ConfigFiles, RobotsLoadStrictly) {
  const auto files = yaml_files("robots");
  ASSERT_GE(files.size(), 4u);
  for (const auto& f : files) EXPECT_NO_THROW(load_config<sim::RobotConfig>(f)) << f;
}

TEST(ConfigFiles, NavigateLoadStrictlyAndVineyardIsTheDefaults) {
  const auto files = yaml_files("navigate");
  ASSERT_EQ(files.size(), 4u);  // vineyard, orchard, row_crop, market_garden
  for (const auto& f : files) EXPECT_NO_THROW(load_config<navigate::NavStackConfig>(f)) << f;
  const fs::path dir = fs::path(ROWNAV_SOURCE_DIR) / "config/navigate";
  // The demo runs on vineyard.yaml: it must be exactly the built-in defaults.
  YAML::Emitter vineyard, defaults;
  vineyard << encode_config(load_config<navigate::NavStackConfig>(dir / "vineyard.yaml"));
  defaults << encode_config(navigate::NavStackConfig{});
  EXPECT_EQ(std::string(vineyard.c_str()), std::string(defaults.c_str()));
  // The crops differ where their canopy does (001 eq. 24's band suits vines only).
  const auto orchard = load_config<navigate::NavStackConfig>(dir / "orchard.yaml");
  const auto maize = load_config<navigate::NavStackConfig>(dir / "row_crop.yaml");
  EXPECT_GT(orchard.end_of_row.band_z_min, navigate::EndOfRowConfig{}.band_z_min);
  EXPECT_LT(maize.end_of_row.band_z_min, navigate::EndOfRowConfig{}.band_z_min);
  // The weeding robot's low 2D scanner drives over what it sees between the rows (issue 11).
  const auto garden = load_config<navigate::NavStackConfig>(dir / "market_garden.yaml");
  EXPECT_FALSE(garden.stack.planar_obstacles);
  EXPECT_TRUE(maize.stack.planar_obstacles);
}

TEST(ConfigFiles, PathsLoadStrictly) {
  const auto files = yaml_files("paths");
  ASSERT_GE(files.size(), 1u);
  for (const auto& f : files) EXPECT_NO_THROW(load_config<sim::PathConfig>(f)) << f;
}

TEST(ConfigFiles, SensorsLoadStrictlyWithPresets) {
  const auto files = yaml_files("sensors");
  ASSERT_GE(files.size(), 5u);
  for (const auto& f : files) {
    sim::SimConfig c;
    ASSERT_NO_THROW(c = load_sim_config(f)) << f;
    EXPECT_GT(c.lidar.columns, 0) << f;
  }
  const sim::SimConfig planar =
      load_sim_config(fs::path(ROWNAV_SOURCE_DIR) / "config/sensors/lms_1081.yaml");
  EXPECT_EQ(planar.lidar.kind, sim::LidarKind::planar);
  EXPECT_EQ(planar.lidar.columns, 1081);
  EXPECT_DOUBLE_EQ(planar.lidar.mount_xyz.z(), 0.40);  // the file overrides the preset's mount
}

TEST(ConfigFiles, FieldsLoadAndBuild) {
  const auto files = yaml_files("fields");
  ASSERT_GE(files.size(), 5u);
  for (const auto& f : files) {
    sim::FieldConfig c;
    ASSERT_NO_THROW(c = load_config<sim::FieldConfig>(f)) << f;
    const sim::Field field = build_field(c, f.parent_path());
    EXPECT_GE(field.rows.size(), 2u) << f;
    EXPECT_GT(field.mesh.triangle_count(), 1000u) << f;
  }
}

TEST(ConfigFiles, PresetOverrideErrorsNameTheFileAndKey) {
  const fs::path dir = fs::temp_directory_path() / "rownav_config_files_test";
  fs::create_directories(dir);
  const fs::path f = dir / "bad_sensors.yaml";
  {
    std::ofstream o(f);
    o << "lidar:\n  preset: os1_16\n  range_noise_std: abc\n";
  }
  try {
    load_sim_config(f);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad_sensors.yaml:3:"), std::string::npos) << what;
    EXPECT_NE(what.find("range_noise_std"), std::string::npos) << what;
  }
  {
    std::ofstream o(f);
    o << "lidar:\n  preset: os9\n";
  }
  EXPECT_THROW(load_sim_config(f), InputError);
  fs::remove_all(dir);
}

TEST(ConfigFiles, AFarOffLidarMountIsRefusedAtItsKey) {
  // Rays cast from a mount at ~1e19 m made Embree abort (issue 13); the limit is a field.
  const fs::path dir = fs::temp_directory_path() / "rownav_config_mount_test";
  fs::create_directories(dir);
  const fs::path f = dir / "mount.yaml";
  std::ofstream(f) << "lidar:\n  preset: os1_16\n  mount_xyz: [1e19, 0.0, 0.75]\n";
  try {
    load_sim_config(f);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.position(), "3:3") << e.what();
    EXPECT_NE(std::string(e.what()).find("lidar.mount_xyz: every component must be within "
                                         "+-max_mount_offset = 100 m"),
              std::string::npos)
        << e.what();
  }
  std::ofstream(f) << "lidar:\n  mount_xyz: [150, 0, 1]\n  max_mount_offset: 200\n";
  EXPECT_DOUBLE_EQ(load_sim_config(f).lidar.mount_xyz.x(), 150.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rownav::io
