#pragma once
/// @file topological_map.hpp The hybrid topological map: the places visited and the validated
/// key locations in the field frame F_f, plus the local frame F_l reset at each validated
/// transition (Emmi 2021, 002_806e72d300173f73.txt, sec. "The field model", "Guidance control
/// and map update").
#include <optional>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/core/pose2.hpp"
#include "rownav/map/key_location.hpp"
#include "rownav/map/place.hpp"

namespace rownav::map {

/// Configuration of the map.
struct TopologicalMapConfig {
  /// [entries] oldest transitions are forgotten beyond this (bounded memory on long missions)
  int max_entries = 100000;

  template <class S, class V>
  static void fields(S& s, V& v) {
    v("max_entries", s.max_entries);
  }
  void validate() const;
};

/// One validated transition and its key location.
struct MapTransition {
  Place from = Place::unknown;
  Place to = Place::unknown;
  double stamp = 0.0;          ///< [s]
  KeyLocation key;             ///< in F_f
  core::Pose2 T_field_base;    ///< robot pose at validation, F_f
};

/// The map. F_f is the odometry pose of the first update (Emmi 2021: "the initial position of
/// the system" when there is no gate); F_l is moved to the robot at every transition.
class TopologicalMap {
 public:
  explicit TopologicalMap(const TopologicalMapConfig& config = {});
  /// Sets F_f and F_l at `T_odom_field` (the first pose) and forgets the transitions.
  void start(const core::Pose2& T_odom_field);
  bool started() const { return started_; }
  /// Records a validated transition (key location given in F_l) and moves F_l to the robot.
  void add_transition(Place from, Place to, const KeyLocation& key_local,
                      const core::Pose2& T_odom_base, double stamp);
  /// F_l -> F_f and back for key locations.
  KeyLocation local_to_field(const KeyLocation& k) const;
  const core::Pose2& T_odom_field() const { return T_odom_field_; }
  const core::Pose2& T_odom_local() const { return T_odom_local_; }
  core::Pose2 T_field_local() const { return T_odom_field_.inverse() * T_odom_local_; }
  const std::vector<MapTransition>& transitions() const { return transitions_; }

 private:
  TopologicalMapConfig config_;
  bool started_ = false;
  core::Pose2 T_odom_field_, T_odom_local_;
  std::vector<MapTransition> transitions_;
};

}  // namespace rownav::map
