// Issue 11, "2D scans: the nearest row": on simulated 2D scans (SICK LMS111 / LMS1xx presets) of
// vineyards, with the robot off-centre (up to +-0.3 m) and yawed (up to +-10 deg), every detector
// with a left / right choice must report the nearest row on each side, not the one a spacing
// farther out. Measured per detector: gross errors (corridor centre at x = 0 off by > 0.3 m) and
// skipped near rows (a reported corridor row that lies nearer to another true row than to the
// nearest one on its side; the target applies to the gross rate). Detectors that do not meet the
// target are listed in kKnownMisses with their measured rate; the test checks that list is still
// accurate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "rownav/io/detection_eval.hpp"
#include "rownav/io/detector_registry.hpp"

namespace rownav::test {
namespace {

constexpr double kGross = 0.3;         // [m] corridor-centre error counted as gross (the issue)
constexpr double kTargetRate = 0.005;  // [-] at most 0.5 % gross errors (the issue's target)

struct Rates {
  int frames = 0, gross = 0, skipped = 0, no_corridor = 0;
  double gross_rate() const { return frames ? double(gross) / frames : 0.0; }
  double skipped_rate() const { return frames ? double(skipped) / frames : 0.0; }
};

// A detector that misses the target, with its measured rates on these frames (kept accurate: the
// test fails when a rate moves by more than kMissTolerance, or when the detector meets the target).
struct KnownMiss {
  const char* detector;
  double gross_rate;    // [-] measured by this test
  double skipped_rate;  // [-]
  const char* why;
};
constexpr double kMissTolerance = 0.006;  // [-] about 4 of the 640 frames
constexpr KnownMiss kKnownMisses[] = {
    {"baseline", 0.0156, 0.0141, "fixed |y| <= 0.75 m box, no corridor in 91 % of the frames"},
};

// Every scenario: 2 presets x 4 spacings x thin / thick canopy, seeded (the frames are the same
// on every run).
std::vector<io::EvalScenario> scenarios() {
  std::vector<io::EvalScenario> out;
  std::uint64_t seed = 1100;
  for (const char* lidar : {"lms_1081", "sick_lms111"})
    for (const double spacing : {1.5, 1.7, 2.2, 3.0})
      for (const bool thick : {false, true}) {
        io::EvalScenario s;
        s.name = std::string(lidar) + (thick ? "_thick_" : "_thin_") + std::to_string(spacing);
        s.field.kind = sim::FieldKind::vineyard;
        s.field.name = s.name;
        s.field.seed = ++seed;
        s.field.vineyard.rows = 6;
        s.field.vineyard.row_length = 30.0;
        s.field.vineyard.row_spacing = spacing;
        s.field.vineyard.stage = thick ? sim::GrowthStage::high : sim::GrowthStage::low;
        s.field.vineyard.canopy_width = thick ? 0.6 : 0.3;
        s.field.vineyard.weeds = sim::WeedLevel::some;
        s.lidar_preset = lidar;
        s.seed = seed;
        s.frames = 40;
        s.max_lateral = 0.3;
        s.max_heading_deg = 10.0;
        s.crop = "vineyard";
        out.push_back(s);
      }
  return out;
}

const std::vector<io::SimulatedFrames>& frames_of_all() {
  static const std::vector<io::SimulatedFrames> f = [] {
    std::vector<io::SimulatedFrames> v;
    for (const auto& s : scenarios()) v.push_back(io::simulate_frames(s));
    return v;
  }();
  return f;
}

const sim::RowTruth* row_truth(const sim::GroundTruth& gt, int row) {
  for (const auto& r : gt.rows)
    if (r.row == row) return &r;
  return nullptr;
}

// True row nearest (at x = 0) to a detected row line.
int nearest_truth_row(const sim::GroundTruth& gt, double y0) {
  int best = -1;
  double d = 1e9;
  for (const auto& r : gt.rows)
    if (std::abs(r.line_base.y_at(0.0) - y0) < d)
      d = std::abs(r.line_base.y_at(0.0) - y0), best = r.row;
  return best;
}

void score(const core::RowObservation& obs, const sim::GroundTruth& gt, Rates& r, bool verbose) {
  const sim::RowTruth* tl = row_truth(gt, gt.left_row);
  const sim::RowTruth* tr = row_truth(gt, gt.right_row);
  if (!tl || !tr) return;
  ++r.frames;
  const double centre = 0.5 * (tl->line_base.y_at(0.0) + tr->line_base.y_at(0.0));
  bool skipped = false;
  for (const auto& [idx, truth] :
       {std::pair{obs.left, gt.left_row}, std::pair{obs.right, gt.right_row}})
    if (idx >= 0 && nearest_truth_row(gt, obs.rows[std::size_t(idx)].line.y_at(0.0)) != truth)
      skipped = true;
  r.skipped += skipped;
  if (!obs.corridor) {
    ++r.no_corridor;
    return;
  }
  const bool gross = std::abs(obs.corridor->offset - centre) > kGross;
  r.gross += gross;
  if (verbose && (gross || skipped)) {
    std::printf("    miss: lateral %+.2f heading %+.1f deg; truth l %+.2f r %+.2f; rows:",
                gt.lateral_error, gt.heading_error * 180.0 / std::numbers::pi,
                tl->line_base.y_at(0.0), tr->line_base.y_at(0.0));
    for (std::size_t i = 0; i < obs.rows.size(); ++i)
      std::printf(" %s%+.2f(%d, x %.1f..%.1f, %+.1f deg)",
                  int(i) == obs.left    ? "L"
                  : int(i) == obs.right ? "R"
                                        : "",
                  obs.rows[i].line.y_at(0.0), obs.rows[i].support, obs.rows[i].x_min,
                  obs.rows[i].x_max, obs.rows[i].heading * 180.0 / std::numbers::pi);
    std::printf("\n");
  }
}

Rates measure(const std::string& detector, bool verbose) {
  Rates total;
  const auto sc = scenarios();
  const auto& all = frames_of_all();
  const auto config = std::filesystem::path(ROWNAV_SOURCE_DIR) / "config/detect/vineyard.yaml";
  for (std::size_t k = 0; k < sc.size(); ++k) {
    auto pipeline = io::make_pipeline(detector, config, all[k].T_base_lidar);
    Rates r;
    for (const auto& f : all[k].frames) {
      const auto obs = pipeline.process(f.scan);
      score(obs, f.truth, r, verbose);
    }
    if (verbose)
      std::printf("  [%s %s] %d frames, gross %d, skipped %d, no corridor %d\n", detector.c_str(),
                  sc[k].name.c_str(), r.frames, r.gross, r.skipped, r.no_corridor);
    total.frames += r.frames, total.gross += r.gross, total.skipped += r.skipped;
    total.no_corridor += r.no_corridor;
  }
  return total;
}

TEST(NearestRow2d, EveryCorridorDetectorPicksTheNearestRow) {
  const bool verbose = std::getenv("ROWNAV_NEAREST_VERBOSE") != nullptr;
  std::map<std::string, KnownMiss> misses;
  for (const auto& m : kKnownMisses) misses[m.detector] = m;
  // ROWNAV_NEAREST_ONLY=name: that detector alone (while working on it; the rest is skipped).
  const char* only = std::getenv("ROWNAV_NEAREST_ONLY");
  for (const auto& d : io::detector_names()) {
    if (only && d != only) continue;
    const Rates r = measure(d, verbose);
    std::printf(
        "[%s 2D nearest row] %d frames: gross %.2f %%, skipped near row %.2f %%, "
        "no corridor %.2f %%\n",
        d.c_str(), r.frames, 100 * r.gross_rate(), 100 * r.skipped_rate(),
        100.0 * r.no_corridor / std::max(1, r.frames));
    SCOPED_TRACE(d);
    ASSERT_GT(r.frames, 500);
    const auto it = misses.find(d);
    if (it == misses.end()) {
      EXPECT_LE(r.gross_rate(), kTargetRate);
    } else {  // listed: still missing, and by the listed amount
      std::printf("  known miss (%s)\n", it->second.why);
      EXPECT_GT(r.gross_rate(), kTargetRate) << "meets the target now: remove it from kKnownMisses";
      EXPECT_NEAR(r.gross_rate(), it->second.gross_rate, kMissTolerance) << "update kKnownMisses";
      EXPECT_NEAR(r.skipped_rate(), it->second.skipped_rate, kMissTolerance)
          << "update kKnownMisses";
    }
  }
}

}  // namespace
}  // namespace rownav::test
