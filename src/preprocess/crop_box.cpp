#include "rownav/preprocess/crop_box.hpp"

namespace rownav::preprocess {

void CropBoxConfig::validate() const {
  core::check(x_min < x_max, "x_max", "must be > x_min");
  core::check(y_min < y_max, "y_max", "must be > y_min");
  core::check(z_min < z_max, "z_max", "must be > z_min");
  core::check_non_negative(range_min, "range_min");
  core::check(range_min < range_max, "range_max", "must be > range_min");
  core::check(sensor_xy.allFinite(), "sensor_xy", "must be finite");
}

CropBox::CropBox(const CropBoxConfig& config)
    : config_(config),
      x_min_(static_cast<float>(config.x_min)),
      x_max_(static_cast<float>(config.x_max)),
      y_min_(static_cast<float>(config.y_min)),
      y_max_(static_cast<float>(config.y_max)),
      z_min_(static_cast<float>(config.z_min)),
      z_max_(static_cast<float>(config.z_max)),
      sx_(static_cast<float>(config.sensor_xy.x())),
      sy_(static_cast<float>(config.sensor_xy.y())),
      r2_min_(static_cast<float>(config.range_min * config.range_min)),
      r2_max_(static_cast<float>(config.range_max * config.range_max)) {
  config_.validate();
}

}  // namespace rownav::preprocess
