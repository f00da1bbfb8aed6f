// Allowed transitions of the field model (Emmi 2021 Fig. 1b).
#include "rownav/map/place.hpp"

#include <gtest/gtest.h>

namespace rownav::map {
namespace {

TEST(Place, HeadlandConnectsToLaneAlleyAndGate) {
  for (Place p : {Place::lane, Place::alley, Place::gate}) {
    EXPECT_TRUE(transition_allowed(Place::headland, p));
    EXPECT_TRUE(transition_allowed(p, Place::headland));
  }
}

TEST(Place, LaneAndAlleyAreNotAdjacent) {
  EXPECT_FALSE(transition_allowed(Place::lane, Place::alley));
  EXPECT_FALSE(transition_allowed(Place::alley, Place::lane));
  EXPECT_FALSE(transition_allowed(Place::lane, Place::gate));
}

TEST(Place, AnyPlaceCanBeLostAndFound) {
  for (Place p : {Place::headland, Place::lane, Place::alley, Place::gate}) {
    EXPECT_TRUE(transition_allowed(p, Place::unknown));
    EXPECT_TRUE(transition_allowed(Place::unknown, p));
  }
}

TEST(Place, FilteredIndicesRoundTrip) {
  for (int i = 0; i < kFilteredPlaces; ++i) EXPECT_EQ(filtered_index(filtered_place(i)), i);
  EXPECT_EQ(filtered_index(Place::gate), -1);
  EXPECT_EQ(filtered_place(7), Place::unknown);
}

}  // namespace
}  // namespace rownav::map
