#include "rownav/io/controller_registry.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "rownav/control/fir_pid.hpp"
#include "rownav/control/lookahead_pid.hpp"
#include "rownav/control/pure_pursuit.hpp"
#include "rownav/control/stanley.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"

#include "common/registry_test_util.hpp"

namespace rownav::io {
namespace {

namespace fs = std::filesystem;

const fs::path kDefault = fs::path(ROWNAV_SOURCE_DIR) / "config" / "control" / "default.yaml";

fs::path write_temp(const std::string& name, const std::string& text) {
  return test::write_temp_yaml("ctrl_registry", name, text);
}

std::string error_of(const std::function<void()>& f) { return test::input_error_of(f); }

TEST(ControllerRegistry, EveryControllerFromDefaultsAndFromTheFile) {
  const auto names = controller_names();
  ASSERT_EQ(names.size(), 4u);
  for (const auto& n : names) {
    EXPECT_EQ(make_controller(n, {})->name(), n);
    EXPECT_EQ(make_controller(n, kDefault)->name(), n);
  }
}

// default.yaml restates the defaults for reading; it must not drift from the headers.
template <class Config>
void expect_section_is_default(const char* key) {
  const YAML::Node from_file = load_yaml_file(kDefault)[key];
  EXPECT_EQ(YAML::Dump(encode_config(load_config<Config>(kDefault, key))),
            YAML::Dump(encode_config(Config{})))
      << key;
  EXPECT_TRUE(from_file.IsMap()) << key;
}

TEST(ControllerRegistry, DefaultFileMatchesTheHeaderDefaults) {
  expect_section_is_default<control::StanleyConfig>("stanley");
  expect_section_is_default<control::LookaheadPidConfig>("lookahead_pid");
  expect_section_is_default<control::FirPidConfig>("fir_pid");
  expect_section_is_default<control::PurePursuitConfig>("pure_pursuit");
}

TEST(ControllerRegistry, UnknownNameListsTheKnownOnes) {
  const std::string e = error_of([] { make_controller("mpc", {}); });
  EXPECT_NE(e.find("unknown controller 'mpc'"), std::string::npos) << e;
  EXPECT_NE(e.find("stanley"), std::string::npos) << e;
}

TEST(ControllerRegistry, StrictKeysWithPositionsInEverySection) {
  const auto f1 = write_temp("bad_section", "stanley:\n  k: 2\nmpc: {}\n");
  EXPECT_NE(error_of([&] { make_controller("stanley", f1); }).find(":3:1:"), std::string::npos)
      << error_of([&] { make_controller("stanley", f1); });
  // A typo in another controller's section is reported too.
  const auto f2 = write_temp("bad_key", "fir_pid:\n  pid:\n    kpp: 1\n");
  const std::string e2 = error_of([&] { make_controller("stanley", f2); });
  EXPECT_NE(e2.find(":3:5:"), std::string::npos) << e2;
  EXPECT_NE(e2.find("kpp"), std::string::npos) << e2;
  const auto f3 = write_temp("bad_value", "lookahead_pid:\n  lookahead: -1\n");
  const std::string e3 = error_of([&] { make_controller("lookahead_pid", f3); });
  EXPECT_NE(e3.find("lookahead"), std::string::npos) << e3;
  EXPECT_NE(e3.find("must be > 0"), std::string::npos) << e3;
}

TEST(ControllerRegistry, SectionValuesReachTheController) {
  const auto f = write_temp("values", "stanley:\n  k: 3.5\n");
  const auto c = make_controller("stanley", f);
  const auto* s = dynamic_cast<const control::StanleyController*>(c.get());
  ASSERT_NE(s, nullptr);
  EXPECT_DOUBLE_EQ(s->config().k, 3.5);
}

}  // namespace
}  // namespace rownav::io
