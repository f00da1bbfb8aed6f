// sensor_msgs/NavSatFix -> core::GnssFix in a local ENU frame.
#include "rownav_ros/navsat_conversion.hpp"

#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>

namespace rownav::ros_bridge {

namespace {

constexpr double kMaxLatitudeDeg = 90.0;    // WGS84 latitude range
constexpr double kMaxLongitudeDeg = 180.0;  // WGS84 longitude range

using sensor_msgs::NavSatFix;
using sensor_msgs::NavSatStatus;

}  // namespace

void NavSatConfig::validate() const {
  core::check(std::isnan(origin_lat_deg) == std::isnan(origin_lon_deg), "origin_lat_deg",
              "origin_lat_deg and origin_lon_deg are set together (or both left NaN)");
  if (!std::isnan(origin_lat_deg)) {
    core::check_range(origin_lat_deg, -kMaxLatitudeDeg, kMaxLatitudeDeg, "origin_lat_deg");
    core::check_range(origin_lon_deg, -kMaxLongitudeDeg, kMaxLongitudeDeg, "origin_lon_deg");
  }
  core::check(std::isfinite(origin_alt), "origin_alt", "must be finite");
  core::check_positive(default_std, "default_std");
  core::check_positive(min_std, "min_std");
  core::check(std::isfinite(default_std), "default_std", "must be finite");
}

NavSatConverter::NavSatConverter(const NavSatConfig& config) : config_(config) {
  config_.validate();
  if (!std::isnan(config_.origin_lat_deg))
    origin_ = Eigen::Vector3d(config_.origin_lat_deg, config_.origin_lon_deg, config_.origin_alt);
}

std::optional<std::string> NavSatConverter::check(const NavSatFix& msg) const {
  if (msg.status.status < NavSatStatus::STATUS_FIX) return "status NO_FIX";
  if (!std::isfinite(msg.latitude) || !std::isfinite(msg.longitude))
    return "latitude / longitude not finite";
  if (std::abs(msg.latitude) > kMaxLatitudeDeg || std::abs(msg.longitude) > kMaxLongitudeDeg)
    return "latitude / longitude out of range (" + std::to_string(msg.latitude) + ", " +
           std::to_string(msg.longitude) + ")";
  if (msg.position_covariance_type != NavSatFix::COVARIANCE_TYPE_UNKNOWN) {
    const double e = msg.position_covariance[0], n = msg.position_covariance[4];
    if (!std::isfinite(e) || !std::isfinite(n) || e < 0.0 || n < 0.0)
      return "horizontal covariance not finite or negative";
  }
  return std::nullopt;
}

double NavSatConverter::horizontal_std(const NavSatFix& msg) const {
  if (msg.position_covariance_type == NavSatFix::COVARIANCE_TYPE_UNKNOWN)
    return std::max(config_.default_std, config_.min_std);
  // An isotropic 1-sigma for the filter: the larger of the east / north variances (ENU order).
  const double var = std::max(msg.position_covariance[0], msg.position_covariance[4]);
  return std::max(std::sqrt(var), config_.min_std);
}

NavSatConversion NavSatConverter::convert(const NavSatFix& msg) {
  NavSatConversion r;
  r.fix.stamp = msg.header.stamp.toSec();
  if (const auto why = check(msg)) {
    r.rejected = *why;
    return r;
  }
  const bool has_alt = std::isfinite(msg.altitude);
  if (!origin_)
    origin_ = Eigen::Vector3d(msg.latitude, msg.longitude, has_alt ? msg.altitude : 0.0);
  const GeographicLib::LocalCartesian enu((*origin_)(0), (*origin_)(1), (*origin_)(2));
  double x = 0.0, y = 0.0, z = 0.0;
  enu.Forward(msg.latitude, msg.longitude, has_alt ? msg.altitude : (*origin_)(2), x, y, z);
  r.fix.valid = true;
  r.fix.position_enu = Eigen::Vector3d(x, y, z);
  r.fix.horizontal_std = horizontal_std(msg);
  return r;
}

}  // namespace rownav::ros_bridge
