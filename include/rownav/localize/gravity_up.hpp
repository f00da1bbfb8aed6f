#pragma once
/// @file gravity_up.hpp The base frame's "up" (gravity) direction from the accelerometer, to
/// level LiDAR sweeps (detect::DetectionPipeline::process(cloud, up_base)).
///
/// A robot on uneven ground rolls and pitches with the terrain; the planar Localizer ignores
/// that, but a LiDAR 0.6 m above the ground then sees a vertical row shifted sideways by
/// h sin(roll) (measured on the simulated vineyards: 3 deg mean roll along a corridor, a 2.5 cm
/// bias of the detected corridor centre). At row-following speeds the specific force is nearly
/// gravity alone: f = a_body + g up (Lan 2021 sec. 2.1 likewise uses the IMU for the attitude);
/// the averaged f, minus the centripetal term v omega, points up.
#include <Eigen/Core>
#include <optional>
#include <span>

#include "rownav/core/sensor_samples.hpp"

namespace rownav::localize {

/// Unit "up" in the base frame from the IMU samples with stamps in [t0, t1] (e.g. one sweep):
/// the mean specific force minus the centripetal acceleration forward_speed * mean yaw rate
/// (along base y), normalised. nullopt when there is no such sample, a sample is not finite or
/// the mean's norm is not within 20 % of standard gravity (the robot is accelerating hard or the
/// IMU is faulty: better not level than level wrongly). Samples must be sorted by stamp.
std::optional<Eigen::Vector3d> gravity_up(std::span<const core::ImuSample> imu, double t0,
                                          double t1, double forward_speed = 0.0);

}  // namespace rownav::localize
