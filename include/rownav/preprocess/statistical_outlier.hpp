#pragma once
/// @file statistical_outlier.hpp Statistical outlier removal (as pcl::StatisticalOutlierRemoval;
/// Bertoglio 2023 sec. II-A outlier filtering): a point whose mean distance to its k nearest
/// neighbours exceeds mean + std_mul * std (over all points) is dropped. k-NN by nanoflann.
#include <Eigen/Core>
#include <memory>
#include <span>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/point_cloud.hpp"

namespace rownav::preprocess {

/// Statistical outlier parameters.
struct StatisticalOutlierConfig {
  bool enabled = false;  ///< run the filter (off by default: Nehme 2021 does not use it)
  int k = 8;             ///< [-] neighbours whose mean distance is scored (PCL setMeanK)
  double std_mul = 1.0;  ///< [-] threshold = mean + std_mul * std (PCL setStddevMulThresh)

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("k", s.k);
    v("std_mul", s.std_mul);
  }
  void validate() const;
};

/// Statistical outlier filter, 3D or 2D. Keeps everything with fewer than 2 points. The k-d tree
/// is rebuilt every call (nanoflann's pool allocates). Never throws after construction.
class StatisticalOutlier {
 public:
  explicit StatisticalOutlier(const StatisticalOutlierConfig& config = {});
  ~StatisticalOutlier();
  StatisticalOutlier(StatisticalOutlier&&) noexcept;
  StatisticalOutlier& operator=(StatisticalOutlier&&) noexcept;
  /// `out` is cleared first; `in` and `out` must not alias.
  void filter(std::span<const core::PointXYZIRT> in, std::vector<core::PointXYZIRT>& out);
  void filter(std::span<const Eigen::Vector2f> in, std::vector<Eigen::Vector2f>& out);
  const StatisticalOutlierConfig& config() const { return config_; }

 private:
  struct Impl;
  StatisticalOutlierConfig config_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rownav::preprocess
