#include "rownav/io/detector_registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "rownav/io/input_error.hpp"

#include "common/registry_test_util.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

fs::path write_temp(const std::string& name, const std::string& text) {
  return test::write_temp_yaml("registry", name, text);
}

std::string error_of(const std::function<void()>& f) { return test::input_error_of(f); }

TEST(DetectorRegistry, KnowsTheBaseline) {
  const auto names = detector_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "baseline"), names.end());
  EXPECT_EQ(make_detector("baseline", YAML::Node(), "")->name(), "baseline");
}

TEST(DetectorRegistry, UnknownNameListsTheKnownOnes) {
  const std::string e = error_of([] { make_detector("hough", YAML::Node(), "x.yaml"); });
  EXPECT_NE(e.find("unknown detector 'hough'"), std::string::npos) << e;
  EXPECT_NE(e.find("baseline"), std::string::npos) << e;
  EXPECT_FALSE(error_of([] { make_pipeline("hough", {}); }).empty());
}

TEST(DetectorRegistry, EveryCropConfigLoadsWithEveryDetector) {
  for (const char* crop : {"vineyard", "orchard", "row_crop", "market_garden"})
    for (const auto& name : detector_names()) {
      const fs::path file =
          fs::path(ROWNAV_SOURCE_DIR) / "config" / "detect" / (std::string(crop) + ".yaml");
      EXPECT_NO_THROW(make_pipeline(name, file)) << crop << " " << name;
    }
}

TEST(DetectorRegistry, StrictKeysWithPositions) {
  const auto f1 = write_temp("bad_section", "preprocess:\n  x_min: 0\nhough: {}\n");
  EXPECT_NE(error_of([&] { make_pipeline("baseline", f1); }).find(":3:1:"), std::string::npos)
      << error_of([&] { make_pipeline("baseline", f1); });
  const auto f2 = write_temp("bad_key", "baseline:\n  y_maxx: 1\n");
  EXPECT_NE(error_of([&] {
              make_pipeline("baseline", f2);
            }).find(":2:3: unknown key 'y_maxx' in 'baseline'"),
            std::string::npos);
  const auto f3 = write_temp("bad_value", "baseline:\n  y_max: 0\n");
  const std::string e3 = error_of([&] { make_pipeline("baseline", f3); });
  EXPECT_NE(e3.find(":2:3: baseline.y_max: must be > 0"), std::string::npos) << e3;
  const auto f4 = write_temp("bad_pre", "preprocess:\n  voxel:\n    voxel_size: -1\n");
  EXPECT_NE(error_of([&] { make_pipeline("baseline", f4); }).find("preprocess.voxel.voxel_size"),
            std::string::npos);
  const auto f5 = write_temp("custom", "baseline:\n  y_max: 0.5\n");
  EXPECT_NO_THROW(make_pipeline("baseline", f5));
  for (const auto& f : {f1, f2, f3, f4, f5}) fs::remove(f);
}

TEST(DetectorRegistry, TheRowProfileIsItsOwnSectionAndStillReadInsidePreprocess) {
  const auto top = write_temp("profile_top", "row_profile:\n  min_points: 21\n");
  EXPECT_EQ(load_pipeline_config(top).row_profile.min_points, 21);
  // Where it was before it left the preprocessing (it runs after the detector).
  const auto old = write_temp("profile_old", "preprocess:\n  row_profile:\n    min_points: 22\n");
  EXPECT_EQ(load_pipeline_config(old).row_profile.min_points, 22);
  EXPECT_NO_THROW(make_pipeline("baseline", old));
  const auto both = write_temp("profile_both", "preprocess:\n  row_profile:\n    min_points: 22\n"
                                               "row_profile:\n  min_points: 21\n");
  const std::string e = error_of([&] { make_pipeline("baseline", both); });
  EXPECT_NE(e.find(":3:5: preprocess.row_profile: given twice"), std::string::npos) << e;
  const auto bad = write_temp("profile_bad", "row_profile:\n  min_points: -1\n");
  EXPECT_NE(error_of([&] { make_pipeline("baseline", bad); }).find("row_profile.min_points"),
            std::string::npos);
  for (const auto& f : {top, old, both, bad}) fs::remove(f);
}

}  // namespace
}  // namespace rownav::io
