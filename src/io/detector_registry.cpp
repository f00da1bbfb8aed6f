#include "rownav/io/detector_registry.hpp"

#include <array>
#include <functional>
#include <string_view>

#include "rownav/detect/baseline.hpp"
#include "rownav/detect/cluster_rows.hpp"
#include "rownav/detect/cone_rect.hpp"
#include "rownav/detect/hough_skew.hpp"
#include "rownav/detect/parallel_lines.hpp"
#include "rownav/detect/pearl.hpp"
#include "rownav/detect/ransac_lines.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"

namespace rownav::io {

namespace {

// Strict decoding of one section `path` of a file, validation errors placed at the key.
template <class T>
void decode_section(const YAML::Node& node, T& out, const std::string& file,
                    const std::string& path) {
  detail::decode_fields(node, out, file, path, {});
  try {
    out.validate();
  } catch (const std::invalid_argument& e) {
    detail::yaml_fail_validation(file, node, path, e.what());
  }
}

// (section, file, section name) -> detector.
using Creator = std::function<std::unique_ptr<detect::RowDetector>(
    const YAML::Node&, const std::string&, const std::string&)>;

// A creator for a detector class D whose constructor takes D::Config (or the given Config).
template <class D, class Config = typename D::Config>
Creator creator() {
  return [](const YAML::Node& section, const std::string& file, const std::string& path) {
    Config c;
    decode_section(section, c, file, path);
    return std::unique_ptr<detect::RowDetector>(std::make_unique<D>(c));
  };
}

// PEARL, OPAL and RUBY share PearlConfig; the section name picks the variant (Malavazi 2018).
Creator pearl_creator(detect::PearlVariant variant) {
  return [variant](const YAML::Node& section, const std::string& file, const std::string& path) {
    detect::PearlConfig c;
    c.variant = variant;
    decode_section(section, c, file, path);
    if (c.variant != variant)
      detail::yaml_fail_validation(file, section, path,
                                   "variant: must be '" + std::string(core::enum_name(variant)) +
                                       "' in section '" + path + "' (the section picks it)");
    return std::unique_ptr<detect::RowDetector>(std::make_unique<detect::PearlDetector>(c));
  };
}

struct Entry {
  std::string_view name;
  Creator make;
};

// Registered detectors: adding one is one line here (and its section in config/detect/*.yaml).
const std::vector<Entry>& registry() {
  static const std::vector<Entry> entries = {
      {"baseline", creator<detect::BaselineDetector>()},
      {"hough_skew", creator<detect::HoughSkewDetector, detect::HoughSkewConfig>()},
      {"parallel_lines", creator<detect::ParallelLinesDetector, detect::ParallelLinesConfig>()},
      {"cluster_rows", creator<detect::ClusterRowsDetector, detect::ClusterRowsConfig>()},
      {"cone_rect", creator<detect::ConeRectDetector, detect::ConeRectConfig>()},
      {"ransac_lines", creator<detect::RansacLinesDetector, detect::RansacLinesConfig>()},
      {"pearl", pearl_creator(detect::PearlVariant::pearl)},
      {"opal", pearl_creator(detect::PearlVariant::opal)},
      {"ruby", pearl_creator(detect::PearlVariant::ruby)},
  };
  return entries;
}

std::string known_names() {
  std::string out;
  for (const auto& n : detector_names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<std::string> detector_names() {
  std::vector<std::string> out;
  for (const auto& e : registry()) out.emplace_back(e.name);
  return out;
}

std::unique_ptr<detect::RowDetector> make_detector(const std::string& name,
                                                   const YAML::Node& section,
                                                   const std::string& file) {
  for (const auto& e : registry())
    if (e.name == name) return e.make(section, file, name);
  (void)file;  // the name is at fault, not the file
  throw InputError("--detector", "",
                   "unknown detector '" + name + "' (known: " + known_names() + ")");
}

detect::DetectionPipeline make_pipeline(const std::string& name,
                                        const std::filesystem::path& config,
                                        const Eigen::Isometry3d& T_base_lidar) {
  preprocess::PreprocessConfig pre;
  if (config.empty()) return {pre, make_detector(name, YAML::Node(), ""), T_base_lidar};
  const std::string file = config.string();
  const YAML::Node root = load_yaml_file(config);
  if (root && !root.IsNull() && !root.IsMap())
    detail::yaml_fail(file, root, "", "expected a map, got " + detail::yaml_describe(root));
  std::vector<std::string> keys = detector_names();
  keys.emplace_back("preprocess");
  if (root && root.IsMap()) detail::yaml_check_keys(file, root, "", keys, {});
  const auto section = [&](const std::string& key) {
    return root && root.IsMap() ? root[key] : YAML::Node();
  };
  decode_section(section("preprocess"), pre, file, "preprocess");
  auto detector = make_detector(name, section(name), file);
  // The other sections are checked too: a typo there is reported even when unused.
  for (const auto& e : registry())
    if (e.name != name && section(std::string(e.name)))
      e.make(section(std::string(e.name)), file, std::string(e.name));
  return {pre, std::move(detector), T_base_lidar};
}

}  // namespace rownav::io
