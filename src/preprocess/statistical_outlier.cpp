// Statistical outlier removal: mean k-NN distance per point (nanoflann), global mean / std cut.
#include "rownav/preprocess/statistical_outlier.hpp"

#include <cmath>
#include <cstdint>
#include <nanoflann.hpp>

namespace rownav::preprocess {

namespace {

/// nanoflann dataset over a flat float buffer of D coordinates per point.
template <int D>
struct FlatCloud {
  const std::vector<float>* xyz = nullptr;
  std::size_t kdtree_get_point_count() const { return xyz->size() / D; }
  float kdtree_get_pt(std::size_t i, std::size_t d) const { return (*xyz)[i * D + d]; }
  template <class B>
  bool kdtree_get_bbox(B&) const {
    return false;
  }
};

template <int D>
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, FlatCloud<D>>,
                                                 FlatCloud<D>, D, std::uint32_t>;

}  // namespace

struct StatisticalOutlier::Impl {
  std::vector<float> xyz;
  std::vector<double> mean_dist;
  std::vector<std::uint32_t> idx;
  std::vector<float> d2;
  std::vector<std::uint8_t> keep;
  std::vector<std::uint32_t> src;  // index in the input of each finite point

  /// Fills `keep` for xyz (D coordinates per point), PCL semantics.
  template <int D>
  void mark(int k, double std_mul) {
    const std::size_t n = xyz.size() / D;
    keep.assign(n, 1);
    if (n < 2) return;
    FlatCloud<D> cloud{&xyz};
    Tree<D> tree(D, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    const std::size_t want = std::min<std::size_t>(static_cast<std::size_t>(k) + 1, n);
    idx.resize(want);
    d2.resize(want);
    mean_dist.resize(n);
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t got = tree.knnSearch(&xyz[i * D], want, idx.data(), d2.data());
      double s = 0.0;  // the first result is the point itself (PCL skips it too)
      for (std::size_t j = 1; j < got; ++j) s += std::sqrt(static_cast<double>(d2[j]));
      mean_dist[i] = got > 1 ? s / static_cast<double>(got - 1) : 0.0;
      sum += mean_dist[i];
      sum2 += mean_dist[i] * mean_dist[i];
    }
    const double mean = sum / static_cast<double>(n);
    const double var = (sum2 - sum * sum / static_cast<double>(n)) / static_cast<double>(n - 1);
    const double cut = mean + std_mul * std::sqrt(std::max(0.0, var));
    for (std::size_t i = 0; i < n; ++i) keep[i] = mean_dist[i] <= cut;
  }
};

void StatisticalOutlierConfig::validate() const {
  core::check_positive(k, "k");
  core::check(std::isfinite(std_mul), "std_mul", "must be finite");
}

StatisticalOutlier::StatisticalOutlier(const StatisticalOutlierConfig& config)
    : config_(config), impl_(std::make_unique<Impl>()) {
  config_.validate();
}
StatisticalOutlier::~StatisticalOutlier() = default;
StatisticalOutlier::StatisticalOutlier(StatisticalOutlier&&) noexcept = default;
StatisticalOutlier& StatisticalOutlier::operator=(StatisticalOutlier&&) noexcept = default;

void StatisticalOutlier::filter(std::span<const core::PointXYZIRT> in,
                                std::vector<core::PointXYZIRT>& out) {
  impl_->xyz.clear();
  impl_->src.clear();
  for (std::uint32_t i = 0; i < in.size(); ++i) {
    if (!in[i].finite()) continue;  // NaN / Inf dropped
    impl_->xyz.insert(impl_->xyz.end(), {in[i].x, in[i].y, in[i].z});
    impl_->src.push_back(i);
  }
  impl_->mark<3>(config_.k, config_.std_mul);
  out.clear();
  for (std::size_t i = 0; i < impl_->src.size(); ++i)
    if (impl_->keep[i]) out.push_back(in[impl_->src[i]]);
}

void StatisticalOutlier::filter(std::span<const Eigen::Vector2f> in,
                                std::vector<Eigen::Vector2f>& out) {
  impl_->xyz.clear();
  impl_->src.clear();
  for (std::uint32_t i = 0; i < in.size(); ++i) {
    if (!in[i].allFinite()) continue;  // NaN / Inf dropped
    impl_->xyz.insert(impl_->xyz.end(), {in[i].x(), in[i].y()});
    impl_->src.push_back(i);
  }
  impl_->mark<2>(config_.k, config_.std_mul);
  out.clear();
  for (std::size_t i = 0; i < impl_->src.size(); ++i)
    if (impl_->keep[i]) out.push_back(in[impl_->src[i]]);
}

}  // namespace rownav::preprocess
