#pragma once
/// @file pearl.hpp PEARL multi-line fitting and its crop-row refinements OPAL and RUBY
/// (Malavazi et al. 2018, "LiDAR-only based navigation algorithm for an autonomous agricultural
/// robot", sec. 2; PEARL itself: Isack & Boykov 2012).
///
/// Every variant minimises the energy of eq. (1) / (4) over a labelling of the points (one label
/// per line model plus the outlier label L_0) by real alpha-expansion (alpha_expansion.hpp),
/// then re-fits the models (eq. (3)), samples new models from the outliers and merges close
/// models, iterating while the energy decreases.
///  - pearl: the original algorithm of sec. 2.1.2 (steps 1-5, with the optional step 5).
///  - opal:  + outlier penalty phi of eq. (4), model elimination after each expansion
///           (sec. 2.2.2), new-model search right after the expansion (sec. 2.2.3, Fig. 5 order).
///  - ruby:  opal + the parallelism constraint R_j = omega D_j / psi_j (sec. 2.2.4).
/// Deviations from the paper (documented at the fields): label costs (Isack & Boykov's energy,
/// absent from eq. (1)) are applied greedily after each expansion, not inside the cut; the loop
/// stops after `stall_iterations` iterations without an energy decrease (the paper: 1) and
/// returns the lowest-energy set after one more deterministic pass (elimination, label cost,
/// eq. (3), merge; no parallelism); eq. (3) is solved by iteratively reweighted TLS; models
/// sampled in this iteration are not judged by the parallelism test until they hold points;
/// reported rows need `min_support` points and a heading within `max_row_heading_deg`.
#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <utility>

#include "rownav/core/config_fields.hpp"
#include "rownav/detect/nearest_row.hpp"
#include "rownav/detect/row_detector.hpp"
#include "rownav/detect/row_direction.hpp"

namespace rownav::detect {

/// Which of Malavazi 2018's algorithms runs (sec. 2.2.5).
enum class PearlVariant : std::uint8_t {
  pearl,  ///< original PEARL (sec. 2.1.2)
  opal,   ///< refined PEARL without the parallelism constraint
  ruby    ///< refined PEARL with every refinement
};

/// Parameters of PEARL / OPAL / RUBY. The paper gives no numbers ("heuristically chosen"); the
/// defaults are one row-crop / vineyard configuration (rows 0.7 - 3 m apart, 2D points after a
/// crop box), used unchanged on the synthetic scenes, the simulated vineyard and corn_rows_2d.
struct PearlConfig {
  PearlVariant variant = PearlVariant::ruby;
  /// [m] cost of the outlier label L_0 = the distance threshold beyond which a point is an
  /// outlier (Malavazi 2018 sec. 2.1.2 step 2 "further than a threshold").
  double outlier_cost = 0.18;
  /// [m] phi of eq. (4): extra energy per outlier point (sec. 2.2.1); opal / ruby only.
  double outlier_penalty = 0.03;
  /// [m] lambda of eq. (1): weight of the Potts smoothness term.
  double smoothness = 0.04;
  /// [m] zeta of eq. (2), w_pq = exp(-|p - q|^2 / zeta^2).
  double zeta = 0.08;
  /// [-] neighbours per point of the neighbourhood system N (k nearest, nanoflann).
  int neighbours = 6;
  /// [m] pairs farther apart than this are not neighbours.
  double neighbour_radius = 0.3;
  /// [m] label cost h per line model (Isack & Boykov 2012; not in Malavazi's eq. (1)): after
  /// each expansion a model is dropped when moving its points to their best other label raises
  /// the data cost by less than h (about 20 points of a 1 m row segment keep their model).
  double label_cost = 1.5;
  /// [m] the label cost on one planar scan (DetectorInput::planar_scan, issue 11): a 2D scanner
  /// gives a corridor row only 8-12 returns after the voxel grid, and at label_cost a model with
  /// min_support points lost its label (no rows for > 0.5 s: perception_lost in 2 of 16 seeded
  /// quick-bench runs); at 1.0 a model that min_support would report keeps it. Projected 3D
  /// clouds keep label_cost: there the lower cost turned weeds into extra rows
  /// (BENCHMARK.md issue 11, 2026-12-04).
  double planar_label_cost = 1.0;
  /// [-] models sampled at initialisation (sec. 2.1.2 step 1, "number of initial models").
  int initial_models = 12;
  /// [-] models sampled from the outliers per iteration (sec. 2.1.2 step 5 / sec. 2.2.3).
  int new_models = 4;
  /// [-] cap on simultaneous models, keeps the expansion cheap.
  int max_models = 16;
  /// [m] a model is sampled from two points p, q with |p - q| in [sample_min, sample_max].
  double sample_min = 0.25;
  double sample_max = 2.0;  ///< [m]
  /// [-] PEARL iterations (expansion + re-fit) at most; stops earlier when E does not decrease.
  int max_iterations = 12;
  /// [-] iterations without an energy decrease before stopping. 1 is the paper's rule (sec.
  /// 2.1.2 step 3); the model elimination / parallelism steps often raise E once before the
  /// new models lower it, so the default waits 3 and returns the lowest-energy model set.
  int stall_iterations = 3;
  /// [-] alpha-expansion sweeps over the labels per iteration at most.
  int expansion_cycles = 2;
  /// [-] minimal inliers of a model: fewer after an expansion and the model is eliminated
  /// (sec. 2.2.2, opal / ruby); also the support a reported row needs (all variants).
  int min_support = 8;
  /// [deg] models closer than this in angle and `merge_distance` across are merged (step 5).
  double merge_angle_deg = 6.0;
  double merge_distance = 0.3;  ///< [m] also applied to the returned models
  /// [-] |a_j - a_k| below this makes two models parallel, a = slope (eq. (5)); ruby only.
  /// Loose (about 17 deg) because on real rows (corn_rows_2d) the two visible rows often
  /// disagree by 5-10 deg; 0.1 removed half of the labelled rows there.
  double parallel_slope = 0.3;
  /// [-] omega of R_j = omega D_j / psi_j (sec. 2.2.4); ruby only.
  double parallel_omega = 1.0;
  /// [m] models with R_j above this are excluded (sec. 2.2.4); ruby only.
  double parallel_max_ratio = 0.15;
  /// [deg] rows heading farther than this from the robot's x axis are not reported (rownav).
  double max_row_heading_deg = 60.0;
  /// [m] x at which the corridor rows are picked (finalize_observation).
  double lookahead = 0.5;
  /// 2D scans: a row band between the robot and a corridor row becomes that side's row (issue 11)
  NearestRowConfig nearest_row;
  /// 2D scans: rows off the frame's sharpest direction are dropped before the pick (issue 11)
  RowDirectionConfig row_direction;
  std::uint64_t seed = 1;  ///< random sampling seed: same seed, same result

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("variant", s.variant);
    v("outlier_cost", s.outlier_cost);
    v("outlier_penalty", s.outlier_penalty);
    v("smoothness", s.smoothness);
    v("zeta", s.zeta);
    v("neighbours", s.neighbours);
    v("neighbour_radius", s.neighbour_radius);
    v("label_cost", s.label_cost);
    v("planar_label_cost", s.planar_label_cost);
    v("initial_models", s.initial_models);
    v("new_models", s.new_models);
    v("max_models", s.max_models);
    v("sample_min", s.sample_min);
    v("sample_max", s.sample_max);
    v("max_iterations", s.max_iterations);
    v("stall_iterations", s.stall_iterations);
    v("expansion_cycles", s.expansion_cycles);
    v("min_support", s.min_support);
    v("merge_angle_deg", s.merge_angle_deg);
    v("merge_distance", s.merge_distance);
    v("parallel_slope", s.parallel_slope);
    v("parallel_omega", s.parallel_omega);
    v("parallel_max_ratio", s.parallel_max_ratio);
    v("max_row_heading_deg", s.max_row_heading_deg);
    v("lookahead", s.lookahead);
    v("seed", s.seed);
    v("nearest_row", s.nearest_row);
    v("row_direction", s.row_direction);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

struct PearlState;

/// PEARL / OPAL / RUBY as a RowDetector. Every surviving line model is a row.
class PearlDetector : public RowDetector {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit PearlDetector(const PearlConfig& config = {});
  ~PearlDetector() override;
  PearlDetector(const PearlDetector&) = delete;
  PearlDetector& operator=(const PearlDetector&) = delete;

  /// "pearl", "opal" or "ruby".
  std::string_view name() const override;
  core::RowObservation detect(const DetectorInput& input) override;
  const PearlConfig& config() const { return config_; }
  /// Iterations and final energy of the last detect() (diagnostics, tests).
  int last_iterations() const { return last_iterations_; }
  double last_energy() const { return last_energy_; }

 private:
  PearlConfig config_;
  PearlConfig planar_config_;  // config_ with planar_label_cost as its label cost
  std::unique_ptr<PearlState> state_;
  int last_iterations_ = 0;
  double last_energy_ = 0.0;
};

}  // namespace rownav::detect

template <>
struct rownav::core::EnumNames<rownav::detect::PearlVariant> {
  using E = rownav::detect::PearlVariant;
  static constexpr std::array<std::pair<E, std::string_view>, 3> values{
      {{E::pearl, "pearl"}, {E::opal, "opal"}, {E::ruby, "ruby"}}};
};
