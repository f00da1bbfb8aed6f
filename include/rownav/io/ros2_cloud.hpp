#pragma once
/// @file ros2_cloud.hpp sensor_msgs/msg/PointCloud2 in CDR <-> core::PointCloud.
///
/// Decoding takes any point_step, field offsets and numeric field types (INT8 .. FLOAT64, either
/// byte order), organised (height > 1: column = the column index) or not. Fields: x, y, z
/// (required); intensity; ring; column (rownav's writer); the per-point time as the first of `t` (Ouster: [ns] from the
/// header stamp), `time` (Velodyne: [s] from the header stamp) or `timestamp` (Hesai: absolute
/// [s]). Points with a non-finite x, y or z are dropped.
#include <cstdint>
#include <span>
#include <vector>

#include "rownav/core/point_cloud.hpp"

namespace rownav::io {

/// How encode_point_cloud2 writes the per-point time.
enum class CloudTimeField : std::uint8_t {
  ouster_t,       ///< `t` UINT32 [ns] from the stamp (rounded)
  velodyne_time,  ///< `time` FLOAT32 [s] from the stamp (exact)
  timestamp,      ///< `timestamp` FLOAT64 absolute [s]
};

/// Throws CdrError on a malformed message (fields outside the point, data shorter than
/// height x row_step, no x / y / z).
core::PointCloud decode_point_cloud2(std::span<const std::uint8_t> msg);

/// x, y, z, intensity FLOAT32, ring and column UINT16 and the time field, the last three only
/// when the cloud's has_intensity / has_ring / has_time say they are meaningful; `height` > 1
/// writes an organised cloud (the point count must be a multiple of it).
std::vector<std::uint8_t> encode_point_cloud2(const core::PointCloud& cloud,
                                              CloudTimeField time = CloudTimeField::velodyne_time,
                                              std::uint32_t height = 1);

}  // namespace rownav::io
