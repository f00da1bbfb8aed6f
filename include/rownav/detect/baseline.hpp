#pragma once
/// @file baseline.hpp The trivial baseline every row detector must beat: the points in a box in
/// front of the robot, split by the sign of y, one least-squares line y = a x + b per side.
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/detect/row_detector.hpp"

namespace rownav::detect {

/// The box the baseline looks at (base frame).
struct BaselineConfig {
  double x_min = 0.0;   ///< [m] nearest point kept along x
  double x_max = 2.5;   ///< [m] farthest point kept along x
  double y_max = 0.75;  ///< [m] points with |y| <= y_max are kept; y > 0 left row, y < 0 right
  int min_points = 3;   ///< [-] fewest points for a side's line

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("x_min", s.x_min);
    v("x_max", s.x_max);
    v("y_max", s.y_max);
    v("min_points", s.min_points);
  }
  void validate() const;
};

/// Baseline detector "baseline": at most two rows, one a side; no outlier handling at all, so
/// weeds between the rows and the far ends of a curved row pull the lines.
class BaselineDetector : public RowDetector {
 public:
  using Config = BaselineConfig;
  explicit BaselineDetector(const BaselineConfig& config = {});
  std::string_view name() const override { return "baseline"; }
  core::RowObservation detect(const DetectorInput& input) override;
  const BaselineConfig& config() const { return config_; }

 private:
  BaselineConfig config_;
  std::vector<Eigen::Vector2f> left_, right_;
};

}  // namespace rownav::detect
