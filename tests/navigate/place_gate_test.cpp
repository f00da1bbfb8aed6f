// The map stage's place as a gate on the navigator's exit and entry (issue 12): the verdicts.
// The navigator driven through them: navigator_states_test.cpp (NavigatorPlaceGate).
#include "rownav/navigate/place_gate.hpp"

#include <gtest/gtest.h>

namespace rownav::navigate {
namespace {

using map::Place;

PlaceGateConfig enabled() {
  PlaceGateConfig c;
  c.enabled = true;
  return c;
}

TEST(PlaceGate, AnExitPassesUnlessTheMapStillSaysLaneThenWaitsUpToExitWait) {
  const PlaceGateConfig c = enabled();
  for (const Place p : {Place::headland, Place::alley, Place::gate, Place::unknown})
    EXPECT_EQ(exit_verdict(p, 0.0, c), GateVerdict::pass) << core::enum_name(p);
  EXPECT_EQ(exit_verdict(Place::lane, 0.0, c), GateVerdict::wait);
  EXPECT_EQ(exit_verdict(Place::lane, 0.99 * c.exit_wait, c), GateVerdict::wait);
  EXPECT_EQ(exit_verdict(Place::lane, c.exit_wait, c), GateVerdict::contradict);
}

TEST(PlaceGate, AnEntryPassesOnALaneWaitsInTheHeadlandAndContradictsAnAlleyOrAGate) {
  const PlaceGateConfig c = enabled();
  EXPECT_EQ(entry_verdict(Place::lane, c), GateVerdict::pass);
  EXPECT_EQ(entry_verdict(Place::unknown, c), GateVerdict::pass);  // no opinion
  EXPECT_EQ(entry_verdict(Place::headland, c), GateVerdict::wait);
  EXPECT_EQ(entry_verdict(Place::alley, c), GateVerdict::contradict);
  EXPECT_EQ(entry_verdict(Place::gate, c), GateVerdict::contradict);
}

TEST(PlaceGate, WithoutTheMapStageOrDisabledEverythingPasses) {
  const PlaceGateConfig off;  // the default (BENCHMARK.md, issue 12: the map errs in orchards)
  EXPECT_FALSE(off.enabled);
  for (const Place p : {Place::headland, Place::lane, Place::alley, Place::gate}) {
    EXPECT_EQ(exit_verdict(p, 10.0, off), GateVerdict::pass);
    EXPECT_EQ(entry_verdict(p, off), GateVerdict::pass);
  }
  const PlaceGateConfig on = enabled();
  EXPECT_EQ(exit_verdict(std::nullopt, 10.0, on), GateVerdict::pass);
  EXPECT_EQ(entry_verdict(std::nullopt, on), GateVerdict::pass);
}

TEST(PlaceGate, ANegativeExitWaitIsRefusedNamingTheField) {
  PlaceGateConfig c;
  c.exit_wait = -0.1;
  try {
    c.validate();
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("exit_wait"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rownav::navigate
