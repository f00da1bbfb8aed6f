/// @file topological_map.cpp The hybrid topological map (Emmi 2021 sec. "The field model").
#include "rownav/map/topological_map.hpp"

namespace rownav::map {

void TopologicalMapConfig::validate() const { core::check_positive(max_entries, "max_entries"); }

TopologicalMap::TopologicalMap(const TopologicalMapConfig& config) : config_(config) {
  config_.validate();
}

void TopologicalMap::start(const core::Pose2& T_odom_field) {
  T_odom_field_ = T_odom_field;
  T_odom_local_ = T_odom_field;
  transitions_.clear();
  started_ = true;
}

KeyLocation TopologicalMap::local_to_field(const KeyLocation& k) const {
  const core::Pose2 T = T_field_local();
  KeyLocation out = k;
  out.p = T * k.p;
  out.v = T.rotation() * k.v;
  return out;
}

void TopologicalMap::add_transition(Place from, Place to, const KeyLocation& key_local,
                                    const core::Pose2& T_odom_base, double stamp) {
  MapTransition t;
  t.from = from;
  t.to = to;
  t.stamp = stamp;
  t.key = local_to_field(key_local);
  t.T_field_base = T_odom_field_.inverse() * T_odom_base;
  if (static_cast<int>(transitions_.size()) >= config_.max_entries)
    transitions_.erase(transitions_.begin());
  transitions_.push_back(t);
  // Emmi 2021: F_l "is relocated whenever a state transition is detected".
  T_odom_local_ = T_odom_base;
}

}  // namespace rownav::map
