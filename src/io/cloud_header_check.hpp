#pragma once
// Private to rownav_io: PCD and PLY headers checked before PCL reads the file. PCL 1.13 trusts
// its headers: an unknown first keyword makes PCDReader crash, an element count of 2^32 wraps to
// 0 and trips an assertion in PLYReader, and a huge count makes it allocate what the file cannot
// hold. So the header is read here first, and every count must fit the bytes that follow it.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>

#include "rownav/core/point_cloud.hpp"

namespace rownav::io::detail {

/// Largest point / element count accepted: PCL holds counts in 32-bit ints (uindex_t, int).
inline constexpr std::int64_t kMaxCloudElements = std::numeric_limits<std::int32_t>::max();

/// Checks a PCD header: only known keywords (VERSION FIELDS SIZE TYPE COUNT WIDTH HEIGHT
/// VIEWPOINT POINTS DATA), FIELDS / SIZE / TYPE / COUNT agree, WIDTH x HEIGHT = POINTS <=
/// kMaxCloudElements, and the data after the header can hold POINTS points. Reads rownav's own
/// comment "# rownav stamp=<s> flags=<irt|-> frame_id=<id>" into `meta`; true if found.
/// @throws InputError "<file>[:line N]: not a valid PCD file (<why>)"
bool check_pcd_header(const std::filesystem::path& file, const std::string& name,
                      core::PointCloud& meta);

/// Checks a PLY header: `ply`, a known format, elements with known property types and counts
/// <= kMaxCloudElements that the data after `end_header` can hold (binary: every element's
/// smallest size; ascii: one character and one separator per value).
/// @throws InputError "<file>[:line N]: not a valid PLY file (<why>)"
void check_ply_header(const std::filesystem::path& file, const std::string& name);

}  // namespace rownav::io::detail
