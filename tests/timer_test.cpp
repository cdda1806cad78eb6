// util/timer.h: fastestOf and BestOfRounds (calibrate's rounds).
#include "util/timer.h"

#include <gtest/gtest.h>

#include <random>

namespace shadetwin {
namespace {

TEST(Timer, FastestOfIsTheMinimumAndMinusOneForNoRuns) {
  EXPECT_EQ(fastestOf({}), -1.0);
  EXPECT_EQ(fastestOf({3.0, 1.5, 2.0}), 1.5);
}

// Each measurement's place in its round is its key: the k-th call of every round is compared with the k-th of the
// others, times keep their lowest, rates their highest, and a key read in one round only keeps that value.
TEST(Timer, BestOfRoundsKeepsEachMeasurementsBestAcrossRounds) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const int rounds = 1 + int(rng() % 5), keys = 1 + int(rng() % 9);
    std::uniform_real_distribution<double> U(0.1, 10.0);
    std::vector<double> lo(size_t(keys), 1e300), hi(size_t(keys), -1e300);
    BestOfRounds b;
    for (int r = 0; r < rounds; ++r) {
      b.nextRound();
      for (int k = 0; k < keys; ++k) {
        const double x = U(rng);
        // even keys are times, odd keys rates
        if (k % 2 == 0) {
          lo[size_t(k)] = std::min(lo[size_t(k)], x);
          EXPECT_EQ(b.low(x), lo[size_t(k)]);
        } else {
          hi[size_t(k)] = std::max(hi[size_t(k)], x);
          EXPECT_EQ(b.high(x), hi[size_t(k)]);
        }
      }
    }
    EXPECT_EQ(b.measurements(), size_t(keys));
  }
}

// A slow spell in one round does not move a value another round read fast; the rounds' order does not matter.
TEST(Timer, BestOfRoundsIgnoresASlowRound) {
  BestOfRounds a, b;
  a.nextRound(), a.low(5.0), a.high(0.75);   // slow: a long time, a low bandwidth
  a.nextRound();
  EXPECT_EQ(a.low(1.0), 1.0);
  EXPECT_EQ(a.high(5.5), 5.5);
  b.nextRound(), b.low(1.0), b.high(5.5);
  b.nextRound();
  EXPECT_EQ(b.low(5.0), 1.0);
  EXPECT_EQ(b.high(0.75), 5.5);
}

}  // namespace
}  // namespace shadetwin
