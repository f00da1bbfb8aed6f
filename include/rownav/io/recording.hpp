#pragma once
/// @file recording.hpp A run written to a directory of plain files that other tools can read,
/// and read back bit-identically (numbers in shortest round-trip form).
///
/// Layout:
///  - manifest.yaml: `format: rownav-recording`, `version: 1`, plus the caller's manifest keys;
///  - lidar/frames.csv `index,stamp,file,points` + lidar/NNNNNN.pcd (write_cloud_pcd, binary);
///  - lidar/scans.csv (planar scans, cloud_io.hpp format);
///  - encoders.csv `stamp,left_ticks,right_ticks,steering_angle`;
///  - imu.csv `stamp,gx,gy,gz,ax,ay,az` [rad/s], [m/s^2];
///  - gnss.csv `stamp,valid,east,north,up,horizontal_std` (valid 0 / 1);
///  - ground_truth.csv `stamp,x,y,theta,z,roll,pitch,v,vy,omega,place,block,corridor,left_row,
///    right_row,lateral_error,heading_error,plants_crushed,left_offset,left_heading,right_offset,
///    right_heading`: place by name; the left / right rows' base-frame lines as y at x = 0
///    [m] and heading [rad]; empty cells when that row is not in GroundTruth::rows;
///  - field/rows.csv `row,block,vertex,x,y,half_width,height` (one line a polyline vertex);
///  - field/plants.csv `kind,row,x,y,radius,height` (kind by name).
/// Files that were never written are absent; blank lines and '#' lines are ignored on reading.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rownav/core/point_cloud.hpp"
#include "rownav/core/scan2d.hpp"
#include "rownav/core/sensor_samples.hpp"
#include "rownav/io/safe_output.hpp"
#include "rownav/localize/pose_history.hpp"
#include "rownav/sim/field.hpp"
#include "rownav/sim/ground_truth.hpp"

namespace rownav::io {

/// Streams a run into a hidden staging directory beside `<dir>` and moves it to `<dir>` on
/// commit() (io::OutputDir), so a crash, Ctrl-C or SIGTERM never leaves a half-written output;
/// destroyed without commit() it removes the staging directory. Not thread-safe.
class RecordingWriter {
 public:
  /// Refuses (std::runtime_error) an existing non-empty `dir` unless `overwrite` and `dir` is an
  /// earlier rownav output (io::check_output_dir), which is then replaced on commit().
  /// `manifest` must be a map or null.
  RecordingWriter(const std::filesystem::path& dir, YAML::Node manifest, bool overwrite = false);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  void write_cloud(const core::PointCloud& cloud);
  void write_scan(const core::Scan2D& scan);
  void write_encoders(const core::WheelEncoderSample& s);
  void write_imu(const core::ImuSample& s);
  void write_gnss(const core::GnssFix& s);
  void write_ground_truth(const sim::GroundTruth& gt);
  /// An extra CSV file of the recording (e.g. `inputs.csv`, the order of a live run's inputs);
  /// `header` is written when the file is first opened.
  std::ostream& extra(const std::string& rel, const char* header) { return stream(rel, header); }
  /// Rows and plants (not the mesh). At most once.
  void write_field(const sim::Field& field);

  /// Flushes every file, writes manifest.yaml and renames the directory into place.
  void commit();
  /// Directory being written (the staging directory until commit()).
  const std::filesystem::path& partial_dir() const { return partial_; }

 private:
  std::ofstream& stream(const std::string& rel, const char* header);

  std::unique_ptr<OutputDir> out_;
  std::filesystem::path partial_;
  YAML::Node manifest_;
  bool field_written_ = false;
  std::size_t clouds_ = 0;
  std::vector<std::pair<std::string, std::unique_ptr<std::ofstream>>> streams_;
};

/// A recording read back. Clouds are read lazily from their PCD files.
struct Recording {
  std::filesystem::path dir;
  YAML::Node manifest;
  std::vector<double> cloud_stamps;      ///< [s] from lidar/frames.csv
  std::vector<std::string> cloud_files;  ///< relative to dir/lidar
  std::vector<core::Scan2D> scans;
  std::vector<core::WheelEncoderSample> encoders;
  std::vector<core::ImuSample> imu;
  std::vector<core::GnssFix> gnss;
  /// GroundTruth::rows holds only the left / right rows (row id, line_base through (0, offset)
  /// with the recorded heading, lateral = the line's signed distance, left +); ends and the
  /// corridor centre line are not recorded.
  std::vector<sim::GroundTruth> ground_truth;
  std::vector<sim::Row> rows;      ///< field rows (field/rows.csv)
  std::vector<sim::Plant> plants;  ///< field plants (field/plants.csv)
  /// An external odometry (a bag's nav_msgs/Odometry, io/bag_recording.hpp); a recording
  /// directory has none (its odometry is its encoders + IMU, or the ground truth).
  std::vector<localize::StampedPose> odometry;
  /// Loads cloud i when set (a bag's clouds, read from the bag on demand); else cloud(i) reads
  /// lidar/<cloud_files[i]>.
  std::function<core::PointCloud(std::size_t)> cloud_source;

  std::size_t cloud_count() const { return cloud_stamps.size(); }
  /// Reads cloud i (InputError on a bad file); its stamp is the one in frames.csv.
  core::PointCloud cloud(std::size_t i) const;
};

/// Reads a recording directory. InputError "<file>:<line>: reason" on bad content, or naming
/// manifest.yaml when the directory is not a rownav recording (version 1).
Recording read_recording(const std::filesystem::path& dir);

}  // namespace rownav::io
