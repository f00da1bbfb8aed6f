// Emmi 2021 Table 1: transitions need the estimate and the key location.
#include "rownav/map/transition_table.hpp"

#include <gtest/gtest.h>

namespace rownav::map {
namespace {

KeyLocation key_at(double x, KeyType t) {
  KeyLocation k;
  k.type = t;
  k.p = {x, 0.0};
  return k;
}

const TransitionTableConfig kCfg;

TEST(TransitionTable, LeavingALaneNeedsTheExitReached) {
  const auto exit = key_at(5.0, KeyType::exit);
  EXPECT_FALSE(evaluate_transition(Place::lane, Place::headland, {}, exit, {4.0, 0.0, 0.0}, kCfg)
                   .transition);
  const auto d = evaluate_transition(Place::lane, Place::headland, {}, exit, {5.1, 0.0, 0.0}, kCfg);
  EXPECT_TRUE(d.transition);
  EXPECT_EQ(d.next, Place::headland);
  EXPECT_FALSE(
      evaluate_transition(Place::lane, Place::headland, {}, {}, {5.1, 0.0, 0.0}, kCfg).transition);
}

TEST(TransitionTable, EnteringNeedsTheEntryReached) {
  const auto entry = key_at(0.0, KeyType::entry);
  EXPECT_FALSE(
      evaluate_transition(Place::headland, Place::lane, entry, {}, {-0.3, 0.0, 0.0}, kCfg)
          .transition);
  EXPECT_TRUE(evaluate_transition(Place::headland, Place::alley, entry, {}, {0.005, 0.0, 0.0},
                                  kCfg)
                  .transition);
}

TEST(TransitionTable, PassingANeighbouringLanesEndIsNotReachingIt) {
  const auto exit = key_at(5.0, KeyType::exit);
  EXPECT_FALSE(evaluate_transition(Place::lane, Place::headland, {}, exit, {5.5, 1.0, 0.0}, kCfg)
                   .transition);
}

TEST(TransitionTable, LaneToAlleyIsRefused) {
  const auto entry = key_at(0.0, KeyType::entry);
  const auto exit = key_at(0.0, KeyType::exit);
  EXPECT_FALSE(
      evaluate_transition(Place::lane, Place::alley, entry, exit, {1.0, 0.0, 0.0}, kCfg).transition);
}

TEST(TransitionTable, UnclearEstimatesKeepThePlace) {
  const auto d = evaluate_transition(Place::lane, Place::unknown, {}, {}, {}, kCfg);
  EXPECT_FALSE(d.transition);
  EXPECT_EQ(d.next, Place::lane);
}

}  // namespace
}  // namespace rownav::map
