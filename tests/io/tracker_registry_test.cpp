#include "rownav/io/tracker_registry.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/track/line_ekf.hpp"
#include "rownav/track/model_filter.hpp"
#include "rownav/track/model_matching.hpp"

#include "common/registry_test_util.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

const fs::path kDefault = fs::path(ROWNAV_SOURCE_DIR) / "config" / "track" / "default.yaml";

fs::path write_temp(const std::string& name, const std::string& text) {
  return test::write_temp_yaml("track_registry", name, text);
}

std::string error_of(const std::function<void()>& f) { return test::input_error_of(f); }

TEST(TrackerRegistry, BuildsEveryTrackerFromDefaultsAndTheDefaultFile) {
  ASSERT_EQ(tracker_names().size(), 4u);  // model_matching, line_ekf, model_filter, none
  for (const auto& name : tracker_names()) {
    EXPECT_EQ(make_tracker(name, {})->name(), name);
    EXPECT_EQ(make_tracker(name, kDefault)->name(), name);
  }
}

// config/track/default.yaml restates every default: it must match the structs exactly.
template <class C>
void expect_file_matches_defaults(const std::string& section) {
  const YAML::Node root = load_yaml_file(kDefault);
  C from_file;
  detail::decode_fields(root[section], from_file, kDefault.string(), section, {});
  EXPECT_EQ(YAML::Dump(detail::encode_fields(from_file)), YAML::Dump(detail::encode_fields(C{})))
      << section;
}

TEST(TrackerRegistry, DefaultFileHoldsTheDefaults) {
  expect_file_matches_defaults<track::ModelMatchingConfig>("model_matching");
  expect_file_matches_defaults<track::LineEkfConfig>("line_ekf");
  expect_file_matches_defaults<track::ModelFilterConfig>("model_filter");
}

TEST(TrackerRegistry, OneLineErrors) {
  std::string e = error_of([] { make_tracker("kalman", {}); });
  EXPECT_NE(e.find("unknown tracker 'kalman'"), std::string::npos) << e;
  EXPECT_NE(e.find("line_ekf"), std::string::npos) << e;
  const fs::path typo = write_temp("typo", "line_ekf:\n  gate: 3\nmodel_filter:\n  boxx: 1\n");
  e = error_of([&] { make_tracker("line_ekf", typo); });  // unused section checked too
  EXPECT_NE(e.find(":4:"), std::string::npos) << e;
  EXPECT_NE(e.find("boxx"), std::string::npos) << e;
  const fs::path bad = write_temp("bad", "model_matching:\n  alpha: -1\n");
  e = error_of([&] { make_tracker("model_matching", bad); });
  EXPECT_NE(e.find("model_matching.alpha"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  const fs::path unknown = write_temp("unknown", "pf:\n  x: 1\n");
  EXPECT_NE(error_of([&] { make_tracker("line_ekf", unknown); }).find("pf"), std::string::npos);
}

}  // namespace
}  // namespace rownav::io
