#pragma once
/// @file navsat_conversion.hpp sensor_msgs/NavSatFix -> core::GnssFix: WGS84 latitude /
/// longitude / altitude to the local east-north-up frame the Localizer fuses GNSS in, with
/// GeographicLib::LocalCartesian as the GeoJSON layouts are (io/layout_reader.hpp). The origin
/// is a configured datum or, when none is set, the first accepted fix. The fix is taken as the
/// position of the base frame's origin (no antenna lever arm), as the simulator produces it.
#include <sensor_msgs/NavSatFix.h>

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/sensor_samples.hpp"

namespace rownav::ros_bridge {

/// How NavSatFix messages become GNSS samples (rownav_node's ~gnss/... parameters).
struct NavSatConfig {
  /// [deg] WGS84 latitude of the local ENU origin; NaN (with origin_lon_deg): the first fix
  double origin_lat_deg = std::numeric_limits<double>::quiet_NaN();
  /// [deg] WGS84 longitude of the local ENU origin; NaN (with origin_lat_deg): the first fix
  double origin_lon_deg = std::numeric_limits<double>::quiet_NaN();
  /// [m] ellipsoidal height of a configured origin (a first-fix origin takes the fix's own, 0
  /// when it has none)
  double origin_alt = 0.0;
  /// [m] horizontal 1-sigma when the message gives no covariance (COVARIANCE_TYPE_UNKNOWN):
  /// an unaugmented single-frequency receiver's few metres
  double default_std = 2.5;
  /// [m] smallest horizontal 1-sigma used: a receiver's claimed covariance below an RTK fix's
  /// centimetre (or zero) would make the filter trust it without bound
  double min_std = 0.01;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("origin_lat_deg", s.origin_lat_deg);
    v("origin_lon_deg", s.origin_lon_deg);
    v("origin_alt", s.origin_alt);
    v("default_std", s.default_std);
    v("min_std", s.min_std);
  }
  void validate() const;
};

/// One converted message.
struct NavSatConversion {
  /// stamped; valid = false when rejected (handed on as an outage, as the simulator's are)
  core::GnssFix fix;
  std::string rejected;  ///< empty, or why the fix was rejected (one line)
};

/// Converts NavSatFix messages in one local ENU frame. Never throws after construction.
class NavSatConverter {
 public:
  /// Validates `config` (std::invalid_argument naming the field).
  explicit NavSatConverter(const NavSatConfig& config);

  /// Rejects (valid = false) a fix with status NO_FIX, a latitude / longitude that is not
  /// finite or out of range, or a horizontal covariance that is not finite or negative. The
  /// first accepted fix sets the origin unless one is configured; a non-finite altitude is
  /// taken as the origin's (east / north are what the Localizer fuses). horizontal_std is
  /// sqrt(max(east, north variance)) when the covariance is given, else default_std; at least
  /// min_std.
  NavSatConversion convert(const sensor_msgs::NavSatFix& msg);

  /// (latitude [deg], longitude [deg], altitude [m]) of the origin; nullopt before the first
  /// accepted fix (no datum configured).
  const std::optional<Eigen::Vector3d>& origin() const { return origin_; }

 private:
  std::optional<std::string> check(const sensor_msgs::NavSatFix& msg) const;
  double horizontal_std(const sensor_msgs::NavSatFix& msg) const;

  NavSatConfig config_;
  std::optional<Eigen::Vector3d> origin_;
};

}  // namespace rownav::ros_bridge
