#pragma once
/// @file detector_registry.hpp Row detectors by name, and detection pipelines built from a
/// detection config file.
///
/// A detection config file (config/detect/<crop>.yaml) is a map with an optional `preprocess:`
/// section (preprocess::PreprocessConfig) and one optional section per detector, named as the
/// detector (its Config). Keys are strict (io::decode_config); an absent section keeps the
/// defaults. Every section is checked (the other detectors' too), every section name must be a
/// known detector.
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rownav/detect/pipeline.hpp"
#include "rownav/detect/row_detector.hpp"

namespace rownav::io {

/// Names of the registered detectors, in registration order.
std::vector<std::string> detector_names();

/// Builds detector `name` from its config section (null node: defaults) of `file`. InputError
/// "--detector: unknown detector 'x' (known: a, b)" for an unknown name, or at the offending key.
std::unique_ptr<detect::RowDetector> make_detector(const std::string& name,
                                                   const YAML::Node& section,
                                                   const std::string& file);

/// The detector a detection config file names as its crop's default (top-level key
/// `detector:`), else hough_skew (the empty path too). InputError on a bad file or an unknown name.
std::string default_detector(const std::filesystem::path& config);

/// The `preprocess:` and `row_profile:` sections of a detection config file (a row_profile
/// inside `preprocess:`, where it was before, is still read). InputError on a bad file or key.
detect::PipelineConfig load_pipeline_config(const std::filesystem::path& config);

/// Builds the pipeline of detector `name` from a detection config file (empty path: every
/// default). InputError on an unknown name, a bad file or a bad key.
detect::DetectionPipeline make_pipeline(
    const std::string& name, const std::filesystem::path& config,
    const Eigen::Isometry3d& T_base_lidar = Eigen::Isometry3d::Identity());

}  // namespace rownav::io
