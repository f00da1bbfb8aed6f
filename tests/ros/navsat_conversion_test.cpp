// sensor_msgs/NavSatFix -> core::GnssFix in the local ENU frame, on messages built by hand.
#include "rownav_ros/navsat_conversion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rb = rownav::ros_bridge;
using sensor_msgs::NavSatFix;
using sensor_msgs::NavSatStatus;

namespace {

constexpr double kLat = 51.597, kLon = -0.977;  // near the layout example of README.md
// WGS84 meridian / parallel arc of 1e-4 deg at kLat (M dphi, N cos(phi) dlambda).
constexpr double kNorthPer1e4Deg = 11.1260, kEastPer1e4Deg = 6.9293;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

NavSatFix fix(double lat, double lon, double alt = 80.0, double stamp = 12.5) {
  NavSatFix m;
  m.header.stamp.fromSec(stamp);
  m.header.frame_id = "gps";
  m.status.status = NavSatStatus::STATUS_FIX;
  m.latitude = lat, m.longitude = lon, m.altitude = alt;
  m.position_covariance_type = NavSatFix::COVARIANCE_TYPE_UNKNOWN;
  return m;
}

NavSatFix with_covariance(NavSatFix m, double east_var, double north_var) {
  m.position_covariance_type = NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
  m.position_covariance[0] = east_var;
  m.position_covariance[4] = north_var;
  m.position_covariance[8] = 4.0 * north_var;
  return m;
}

}  // namespace

TEST(NavSatConverter, TheFirstFixIsTheOriginAndLaterFixesAreMetresEastNorth) {
  rb::NavSatConverter c(rb::NavSatConfig{});
  EXPECT_FALSE(c.origin());
  const auto first = c.convert(fix(kLat, kLon));
  EXPECT_TRUE(first.rejected.empty()) << first.rejected;
  ASSERT_TRUE(first.fix.valid);
  EXPECT_DOUBLE_EQ(first.fix.stamp, 12.5);
  EXPECT_NEAR(first.fix.position_enu.norm(), 0.0, 1e-9);
  ASSERT_TRUE(c.origin());
  EXPECT_EQ(c.origin()->z(), 80.0);
  const auto moved = c.convert(fix(kLat + 1e-4, kLon + 1e-4, 81.0, 13.0));
  ASSERT_TRUE(moved.fix.valid);
  EXPECT_NEAR(moved.fix.position_enu.x(), kEastPer1e4Deg, 0.01);
  EXPECT_NEAR(moved.fix.position_enu.y(), kNorthPer1e4Deg, 0.01);
  EXPECT_NEAR(moved.fix.position_enu.z(), 1.0, 0.01);
  const auto west = c.convert(fix(kLat, kLon - 1e-4));
  EXPECT_NEAR(west.fix.position_enu.x(), -kEastPer1e4Deg, 0.01);
  EXPECT_NEAR(west.fix.position_enu.y(), 0.0, 0.01);
}

TEST(NavSatConverter, AConfiguredDatumIsTheOrigin) {
  rb::NavSatConfig config;
  config.origin_lat_deg = kLat - 1e-4;
  config.origin_lon_deg = kLon;
  config.origin_alt = 80.0;
  rb::NavSatConverter c(config);
  ASSERT_TRUE(c.origin());
  const auto f = c.convert(fix(kLat, kLon));
  ASSERT_TRUE(f.fix.valid);
  EXPECT_NEAR(f.fix.position_enu.x(), 0.0, 0.01);
  EXPECT_NEAR(f.fix.position_enu.y(), kNorthPer1e4Deg, 0.01);
  EXPECT_DOUBLE_EQ(c.origin()->x(), kLat - 1e-4);  // not moved by the first fix
}

TEST(NavSatConverter, TheHorizontalStdComesFromTheCovarianceWhenGiven) {
  rb::NavSatConfig config;
  rb::NavSatConverter c(config);
  EXPECT_DOUBLE_EQ(c.convert(fix(kLat, kLon)).fix.horizontal_std, config.default_std);
  // The larger of east / north: 3 m, whatever the vertical says.
  EXPECT_DOUBLE_EQ(c.convert(with_covariance(fix(kLat, kLon), 4.0, 9.0)).fix.horizontal_std, 3.0);
  EXPECT_DOUBLE_EQ(c.convert(with_covariance(fix(kLat, kLon), 0.25, 0.01)).fix.horizontal_std, 0.5);
  // An RTK receiver claiming zero: the floor.
  EXPECT_DOUBLE_EQ(c.convert(with_covariance(fix(kLat, kLon), 0.0, 0.0)).fix.horizontal_std,
                   config.min_std);
}

TEST(NavSatConverter, RejectsNoFixNonFiniteAndOutOfRangeFixes) {
  rb::NavSatConverter c(rb::NavSatConfig{});
  NavSatFix none = fix(kLat, kLon);
  none.status.status = NavSatStatus::STATUS_NO_FIX;
  const auto a = c.convert(none);
  EXPECT_FALSE(a.fix.valid);
  EXPECT_DOUBLE_EQ(a.fix.stamp, 12.5);  // stamped: the stack counts it as an outage
  EXPECT_NE(a.rejected.find("NO_FIX"), std::string::npos) << a.rejected;
  EXPECT_FALSE(c.origin());  // a rejected fix is no origin
  for (const auto& [lat, lon] :
       {std::pair{kNaN, kLon}, std::pair{kLat, kNaN}, std::pair{91.0, kLon},
        std::pair{kLat, -180.5}, std::pair{std::numeric_limits<double>::infinity(), kLon}}) {
    const auto r = c.convert(fix(lat, lon));
    EXPECT_FALSE(r.fix.valid) << lat << ", " << lon;
    EXPECT_FALSE(r.rejected.empty());
  }
  const auto bad_cov = c.convert(with_covariance(fix(kLat, kLon), -1.0, 1.0));
  EXPECT_FALSE(bad_cov.fix.valid);
  EXPECT_NE(bad_cov.rejected.find("covariance"), std::string::npos) << bad_cov.rejected;
  EXPECT_FALSE(c.convert(with_covariance(fix(kLat, kLon), 1.0, kNaN)).fix.valid);
  EXPECT_FALSE(c.origin());
  // An unknown altitude (NaN) is no reason to drop the horizontal position.
  const auto no_alt = c.convert(fix(kLat, kLon + 1e-4, kNaN));
  ASSERT_TRUE(no_alt.fix.valid) << no_alt.rejected;
  EXPECT_TRUE(no_alt.fix.position_enu.allFinite());
  EXPECT_EQ(c.origin()->z(), 0.0);
}

TEST(NavSatConfig, ValidatesTheDatumAndTheStds) {
  rb::NavSatConfig half;
  half.origin_lat_deg = kLat;  // without a longitude
  EXPECT_THROW(rb::NavSatConverter{half}, std::invalid_argument);
  rb::NavSatConfig far;
  far.origin_lat_deg = 95.0, far.origin_lon_deg = 0.0;
  EXPECT_THROW(rb::NavSatConverter{far}, std::invalid_argument);
  rb::NavSatConfig zero;
  zero.default_std = 0.0;
  EXPECT_THROW(rb::NavSatConverter{zero}, std::invalid_argument);
  rb::NavSatConfig floor;
  floor.min_std = -1.0;
  EXPECT_THROW(rb::NavSatConverter{floor}, std::invalid_argument);
}
