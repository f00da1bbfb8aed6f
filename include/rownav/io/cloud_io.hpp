#pragma once
/// @file cloud_io.hpp Point-cloud and scan files: PCD, PLY and CSV.
///
/// Field mapping when reading PCD / PLY (any field order, any numeric type, PCD ascii / binary /
/// binary_compressed):
///  - `x y z` (required); points with a NaN / Inf coordinate are dropped;
///  - `intensity` -> intensity (has_intensity);
///  - `ring` -> ring, `column` -> column (has_ring);
///  - per-point time (has_time): `t` (Ouster, integer nanoseconds since the sweep start ->
///    seconds; a float `t` is taken as seconds), `time` (Velodyne / rownav, seconds relative to
///    the stamp), `timestamp` (Hesai / Livox, seconds; absolute values > 1e6 s become relative to
///    the earliest point, whose time is the cloud stamp).
/// Files written by write_cloud_pcd carry a `# rownav stamp=... frame_id=... flags=...` header
/// comment (PCL ignores comments) so that read_cloud gives back the stamp, frame and flags.
#include <filesystem>
#include <ostream>
#include <string_view>
#include <vector>

#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"

namespace rownav::io {

/// Reads a .pcd or .ply cloud (by extension). InputError on a missing, empty or malformed file,
/// or one without x / y / z.
core::PointCloud read_cloud(const std::filesystem::path& file);

/// Writes fields `x y z intensity` (float), `ring column` (uint16), `time` (float): read_cloud
/// gives back bit-identical points, stamp, frame_id and has_* flags. ascii uses shortest
/// round-trip numbers. std::runtime_error when the file cannot be written.
void write_cloud_pcd(const std::filesystem::path& file, const core::PointCloud& cloud,
                     bool binary = true);

/// Reads CSV points, one cloud per distinct frame in order of first appearance.
/// Header (detected when a cell of the first line is not a number): columns named `x`, `y`,
/// optional `z`, `intensity`, `frame`, `stamp` in any order. Headerless: 2 columns = x,y;
/// 3 = x,y,z; 4 = frame,x,y,z. Cloud stamp = the `stamp` column of its first row if present,
/// else the frame number (0 without a frame column). InputError "<file>:<line>: ..." on a bad
/// cell or a wrong column count.
std::vector<core::PointCloud> read_points_csv(const std::filesystem::path& file);

/// Reads planar scans: header `stamp,angle_min,angle_increment,range_min,range_max,ranges`, then
/// one scan a line: those five numbers followed by every range [m] ("inf" = no return, "nan" =
/// invalid). Angles in radians. frame_id, time_increment and intensities are not stored.
std::vector<core::Scan2D> read_scans_csv(const std::filesystem::path& file);

/// First line of a scans CSV.
inline constexpr std::string_view kScansCsvHeader =
    "stamp,angle_min,angle_increment,range_min,range_max,ranges";
/// Appends one scan line (for streaming writers).
void write_scan_csv_row(std::ostream& out, const core::Scan2D& scan);

/// Writes scans in the format read_scans_csv reads, numbers in shortest round-trip form.
void write_scans_csv(const std::filesystem::path& file, const std::vector<core::Scan2D>& scans);

}  // namespace rownav::io
