#pragma once
/// @file cone_rect.hpp Corridor from a free cone and two side rectangles (Bertoglio 2023,
/// 003_25dc0df51a1e5faf.txt sec. II-B, adapted from Kamaro's FRE 2021 in-row navigation): a
/// cone centred on the robot heading is grown by moving its two sides independently (enlarging
/// the apex angle) until N points fall inside; the angle of its centre line is the heading
/// correction. Two rectangles beside the robot grow outwards until N points fall inside; they
/// give the distances to the left and right rows, hence the corridor-centre offset.
#include <string_view>

#include "rownav/core/config_fields.hpp"
#include "rownav/detect/nearest_row.hpp"
#include "rownav/detect/row_detector.hpp"
#include "rownav/detect/row_direction.hpp"

namespace rownav::detect {

/// Parameters of ConeRectDetector. Bertoglio 2023 gives no values; the defaults suit a
/// vineyard corridor (1.5-3 m) seen by a 2D scanner. Row crops: side_length 1.2,
/// rect_x_max 1.0, max_rect_width 0.8, max_cone_half_angle_deg 40 (used on corn_rows_2d).
struct ConeRectConfig {
  /// [m] length of each cone side (Bertoglio 2023: configurable). It bounds the heading error
  /// the cone can measure: a side stops where it meets the row, near asin(d / side_length) from
  /// the row direction (d: distance to the row's inner edge), so heading errors beyond that angle
  /// put the far row inside the wrong half of the cone (Bertoglio 2023: "the maximum angle that
  /// can be recovered depends on ... the length of the cone sides").
  double side_length = 2.0;
  int cone_points = 3;  ///< [-] points inside the cone that stop a side from growing (N)
  double max_cone_half_angle_deg = 75.0;  ///< [deg] a side that reaches this finds no row
  double rect_x_min = -0.5;               ///< [m] rectangles' extent along x (robot frame)
  double rect_x_max = 1.5;                ///< [m]
  int rect_points = 3;  ///< [-] points inside a rectangle that stop it from growing (N)
  /// [m] a rectangle with no return at all in its window (a robot started in the headland has
  /// no row beside it: the closed-loop runner's lead-in is 1.5 m, and Bertoglio 2023's robot
  /// started inside the row) starts its window at its side's first return ahead, when that lies
  /// at most this far beyond rect_x_min (rownav, issue 11); twice that lead-in. On a planar scan
  /// only when both windows are empty: there a gap beside the robot with its near row hidden
  /// ahead would reach the row behind. 0: the paper's fixed window
  double rect_slide_ahead = 3.0;
  double max_rect_width = 2.5;  ///< [m] a rectangle that reaches this finds no row
  /// [m] both sides found closer together than this is clutter (weeds, open field), no row
  double min_width = 0.3;
  /// Rectangles aligned with the cone's heading instead of the robot's x axis (ours: removes
  /// the bias of a tilted row's nearest corner when the robot is not parallel to the rows).
  bool align_rectangles = true;
  /// Removes from the cone angle the part due to an off-centre robot: with side length L and
  /// row distances d_l, d_r, each side stops near asin(d / L) from the row direction, so the
  /// centre line is biased by (asin(d_l / L) - asin(d_r / L)) / 2 (ours, from the geometry).
  bool compensate_offset = true;
  /// [m] returns from a side's inner edge to this far behind it are that side's row: its
  /// reported extent (x_min / x_max) and support. The rectangles measure only the first N returns
  /// in [rect_x_min, rect_x_max]; reported as the row's extent, that window read as a row ending
  /// 1.5 m ahead and the end of row fired at the corridor's start (every closed-loop run failed,
  /// BENCHMARK.md issue 11). Half the 0.3-0.6 m canopy wall of a VSP vineyard plus its shoots;
  /// capped at half the corridor width measured in the frame
  double row_depth = 0.4;
  /// 2D scans: the heading is the rows' sharpest projection direction (row_direction.hpp), not
  /// the cone's (ours, issue 11). The cone stops at its N-th return: where the near row is
  /// sparse within side_length it finds no side (no heading, 0 is taken) or stops on a weed
  /// (25-35 deg off), 55 of the 57 gross errors of tests/detect/nearest_row_2d_test.cpp. The
  /// cone stays the heading of projected 3D clouds and the fallback when no direction is sharp.
  RowDirectionConfig row_direction;
  /// 2D scans: a row band between the robot and a rectangle's hit, over the whole visible row
  /// (not only the rectangle's x window), sets that side (issue 11). The rectangles see x in
  /// [rect_x_min, rect_x_max] only: a near row with fewer than N returns there (a gap, a sparse
  /// canopy) lets them grow on to the row behind.
  NearestRowConfig nearest_row;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("side_length", s.side_length);
    v("cone_points", s.cone_points);
    v("max_cone_half_angle_deg", s.max_cone_half_angle_deg);
    v("rect_x_min", s.rect_x_min);
    v("rect_x_max", s.rect_x_max);
    v("rect_points", s.rect_points);
    v("rect_slide_ahead", s.rect_slide_ahead);
    v("max_rect_width", s.max_rect_width);
    v("min_width", s.min_width);
    v("row_depth", s.row_depth);
    v("align_rectangles", s.align_rectangles);
    v("compensate_offset", s.compensate_offset);
    v("row_direction", s.row_direction);
    v("nearest_row", s.nearest_row);
  }
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};

/// Cone + rectangles corridor detector. The observation's corridor holds offset
/// (d_left - d_right) / 2, heading (the cone centre angle) and width d_left + d_right, measured
/// to the inner edges of the rows' canopies (what the rectangles touch), not to row centres.
/// rows holds the found sides as lines through the rectangle hits along the corridor heading
/// (inner canopy edges; extent and support: the returns up to row_depth behind that edge); status
/// ok with both sides, degraded with one side or without a cone (no corridor with one side),
/// no_rows with none or when the sides are closer than min_width. Confidence: 0.5 a side found,
/// halved without the cone.
class ConeRectDetector : public RowDetector {
 public:
  /// Validates the config (throws std::invalid_argument).
  explicit ConeRectDetector(const ConeRectConfig& config = {});
  std::string_view name() const override { return "cone_rect"; }
  core::RowObservation detect(const DetectorInput& input) override;
  const ConeRectConfig& config() const { return config_; }

 private:
  ConeRectConfig config_;
  std::vector<float> buf_;
};

}  // namespace rownav::detect
