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
#include "rownav/detect/trunk_lines.hpp"
#include "rownav/io/section_registry.hpp"

namespace rownav::io {

namespace {

using Registry = SectionRegistry<detect::RowDetector>;
using Creator = Registry::Creator;

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

// Registered detectors: adding one is one line here (and its section in config/detect/*.yaml).
const Registry& registry() {
  static const Registry r(
      "--detector", "detector",
      {
          {"baseline", Registry::creator<detect::BaselineDetector>()},
          {"hough_skew", Registry::creator<detect::HoughSkewDetector, detect::HoughSkewConfig>()},
          {"parallel_lines",
           Registry::creator<detect::ParallelLinesDetector, detect::ParallelLinesConfig>()},
          {"cluster_rows",
           Registry::creator<detect::ClusterRowsDetector, detect::ClusterRowsConfig>()},
          {"cone_rect", Registry::creator<detect::ConeRectDetector, detect::ConeRectConfig>()},
          {"ransac_lines",
           Registry::creator<detect::RansacLinesDetector, detect::RansacLinesConfig>()},
          {"trunk_lines",
           Registry::creator<detect::TrunkLinesDetector, detect::TrunkLinesConfig>()},
          {"pearl", pearl_creator(detect::PearlVariant::pearl)},
          {"opal", pearl_creator(detect::PearlVariant::opal)},
          {"ruby", pearl_creator(detect::PearlVariant::ruby)},
      });
  return r;
}

}  // namespace

std::vector<std::string> detector_names() { return registry().names(); }

std::unique_ptr<detect::RowDetector> make_detector(const std::string& name,
                                                   const YAML::Node& section,
                                                   const std::string& file) {
  return registry().find(name).make(section, file, name);
}

std::string default_detector(const std::filesystem::path& config) {
  const std::string fallback = "hough_skew";
  if (config.empty()) return fallback;
  const YAML::Node root = load_yaml_file(config);
  if (!root || !root.IsMap() || !root["detector"]) return fallback;
  const YAML::Node key = root["detector"];
  if (!key.IsScalar())
    detail::yaml_fail_validation(config.string(), key, "detector", "must be a detector name");
  const std::string name = key.as<std::string>();
  registry().find(name);  // unknown name: the registry's one-line error
  return name;
}

namespace {

void decode_pipeline_sections(const YAML::Node& root, detect::PipelineConfig& pipe,
                              const std::string& file) {
  YAML::Node pre = root["preprocess"];
  // Before rownav 0.x the row profile was a key of `preprocess:` (it runs after the detector):
  // still read there, but not in both places.
  if (pre && pre.IsMap() && pre["row_profile"]) {
    if (root["row_profile"]) {
      const YAML::Mark m = pre["row_profile"].Mark();
      throw InputError(file, std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1),
                       "preprocess.row_profile: given twice: keep the top-level row_profile");
    }
    decode_section(pre["row_profile"], pipe.row_profile, file, "preprocess.row_profile");
    pre = YAML::Clone(pre);
    pre.remove("row_profile");
  }
  decode_section(pre, pipe.preprocess, file, "preprocess");
  decode_section(root["row_profile"], pipe.row_profile, file, "row_profile");
}

}  // namespace

detect::PipelineConfig load_pipeline_config(const std::filesystem::path& config) {
  detect::PipelineConfig pipe;
  const YAML::Node root = load_yaml_file(config);
  if (root && root.IsMap()) decode_pipeline_sections(root, pipe, config.string());
  return pipe;
}

detect::DetectionPipeline make_pipeline(const std::string& name,
                                        const std::filesystem::path& config,
                                        const Eigen::Isometry3d& T_base_lidar) {
  detect::PipelineConfig pipe;
  if (config.empty()) return {pipe, registry().make(name, config), T_base_lidar};
  const std::string file = config.string();
  const YAML::Node root = load_yaml_file(config);
  auto detector = registry().make(name, root, file, {"preprocess", "row_profile", "detector"});
  if (root && root.IsMap()) decode_pipeline_sections(root, pipe, file);
  return {pipe, std::move(detector), T_base_lidar};
}

}  // namespace rownav::io
