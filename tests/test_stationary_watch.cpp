// The stationary watch (core/solvers/stationary_watch.hpp): when a stepping
// solver may freeze a segment at its stationary state.
#include <gtest/gtest.h>

#include "core/solvers/stationary_watch.hpp"

namespace mdrmap {
namespace {

constexpr double kRtol = 1e-3;

// A watch started at w = 1 whose checks are due at once.
StationaryWatch watching(double traverse = 1.0) {
  StationaryWatch w(kRtol, traverse, true);
  w.start(1.0, true);
  return w;
}

void checked(StationaryWatch& w, double x0, double x1) {
  w.moved(1.0);
  ASSERT_TRUE(w.due());
  w.check(x0, x1);
}

TEST(StationaryWatch, FreezesAfterThreeChecksNearAndAgreeing) {
  StationaryWatch w = watching();
  checked(w, 1e-6, -2e-5);
  checked(w, 1e-6, -2e-5);
  EXPECT_FALSE(w.frozen());
  checked(w, 2e-6, -1e-5);
  EXPECT_TRUE(w.frozen());
  EXPECT_FALSE(w.due()); // (frozen: no further checks)
}

TEST(StationaryWatch, ACheckAwayFromTheStationaryStateStartsTheStreakAgain) {
  StationaryWatch w = watching();
  checked(w, 1e-6, 1e-6);
  checked(w, 1e-6, 1e-6);
  checked(w, 1e-6, 0.6 * kRtol); // (beyond kNear rtol)
  EXPECT_FALSE(w.frozen());
  checked(w, 1e-6, 1e-6);
  checked(w, 1e-6, 1e-6);
  EXPECT_FALSE(w.frozen());
  checked(w, 1e-6, 1e-6);
  EXPECT_TRUE(w.frozen());
}

// A streak that starts while the solution still approaches the stationary
// state (its first check near, but apart from the later ones by more than
// kSpread rtol) freezes once its last three checks agree: the spread is that
// of the last three, not of the streak since its start (which kept the
// first check's extreme, and a segment under load slid to its end unfrozen).
TEST(StationaryWatch, TheSpreadIsThatOfTheLastThreeChecks) {
  StationaryWatch w = watching();
  checked(w, -4.8e-5, -2.74e-4);
  checked(w, 9.5e-7, -2.08e-5);
  checked(w, 1.44e-6, -1.70e-5);
  EXPECT_FALSE(w.frozen()); // (spread 2.6e-4 > kSpread rtol)
  checked(w, 1.49e-6, -1.59e-5);
  EXPECT_TRUE(w.frozen());
}

TEST(StationaryWatch, DoesNotFreezeWhileTheLastThreeSpreadWide) {
  StationaryWatch w = watching();
  for (int i = 0; i < 10; ++i) // (a cycle of 3e-4 about the stationary state)
    checked(w, 0.0, i % 2 == 0 ? 1.5e-4 : -1.5e-4);
  EXPECT_FALSE(w.frozen());
}

TEST(StationaryWatch, ChecksAreDueEveryTraverse) {
  StationaryWatch w = watching(3.0);
  w.moved(2.0);
  EXPECT_FALSE(w.due());
  w.set_traverse(1.5);
  EXPECT_TRUE(w.due());
  w.check(0.0, 0.0);
  w.moved(1.0);
  EXPECT_FALSE(w.due());
  w.moved(0.5);
  EXPECT_TRUE(w.due());
}

TEST(StationaryWatch, AtRestOrOffItNeverChecks) {
  StationaryWatch rest(kRtol, 1.0, true);
  rest.start(0.0, true);
  rest.moved(10.0);
  EXPECT_FALSE(rest.due());
  StationaryWatch off(kRtol, 1.0, false);
  off.start(1.0, true);
  off.moved(10.0);
  EXPECT_FALSE(off.due());
}

} // namespace
} // namespace mdrmap
