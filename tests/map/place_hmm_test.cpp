// HMM place filter (Emmi 2021 eq. (8), (10)).
#include "rownav/map/place_hmm.hpp"

#include <gtest/gtest.h>

#include <random>

namespace rownav::map {
namespace {

using Obs = std::array<double, kFilteredPlaces>;
const Obs kLane{0.05, 0.95, 0.0};
const Obs kHeadland{1.0, 0.0, 0.0};

TEST(PlaceHmm, SingleFrameFlipsAreRemoved) {
  PlaceHmm hmm;
  hmm.reset(Place::lane);
  std::mt19937_64 rng(11);
  std::bernoulli_distribution flip(0.1);
  int wrong = 0;
  for (int k = 0; k < 500; ++k) {
    // 10 % of the frames alone say headland, never two in a row.
    const bool f = flip(rng) && k % 2 == 0;
    const auto r = hmm.update(0.05, f ? &kHeadland : &kLane);
    wrong += r.place != Place::lane ? 1 : 0;
  }
  EXPECT_EQ(wrong, 0);
}

TEST(PlaceHmm, SustainedEvidenceWhileMovingChangesThePlace) {
  PlaceHmm hmm;
  hmm.reset(Place::lane);
  int frames = 0;
  while (hmm.update(0.05, &kHeadland).place != Place::headland && frames < 100) ++frames;
  EXPECT_LT(frames, 20);  // within 1 m of travel
  EXPECT_GT(frames, 1);   // but not on the first frame
}

TEST(PlaceHmm, WithoutMotionThePlaceDoesNotChange) {
  PlaceHmm hmm;
  hmm.reset(Place::lane);
  for (int k = 0; k < 200; ++k) EXPECT_EQ(hmm.update(0.0, &kHeadland).place, Place::lane);
  for (int k = 0; k < 200; ++k) EXPECT_EQ(hmm.update(-0.05, &kHeadland).place, Place::lane);
}

TEST(PlaceHmm, MotionModelStepsFollowTheTravelledDistance) {
  PlaceHmm hmm;
  EXPECT_EQ(hmm.update(0.25, nullptr).motion_steps, 2);  // step 0.1 m: 0.05 m carried over
  EXPECT_EQ(hmm.update(0.05, nullptr).motion_steps, 1);
  EXPECT_EQ(hmm.update(0.0, nullptr).motion_steps, 0);
}

TEST(PlaceHmm, PosteriorStaysNormalisedWithBadObservations) {
  PlaceHmm hmm;
  hmm.reset(Place::headland);
  const Obs bad{std::numeric_limits<double>::quiet_NaN(), 1.0, 0.0};
  const auto r = hmm.update(0.1, &bad);
  EXPECT_NEAR(r.posterior[0] + r.posterior[1] + r.posterior[2], 1.0, 1e-12);
  EXPECT_EQ(r.place, Place::headland);
}

TEST(PlaceHmm, TransitionRowsMustSumToOne) {
  PlaceHmmConfig cfg;
  cfg.motion_transitions[0] = 0.5;
  EXPECT_THROW(cfg.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rownav::map
