#pragma once
// The lattice that cuts the time steps of a load-controlled run
// (docs/design/spectrum.md, "Time steps"; docs/design/events.md): a run's
// step grid in a segment of duration T is its step control's steps cut at
// T j / n, j = 1 .. n, and at nothing else, so the grid, and the event
// metrics read off its step ends, do not depend on the output samples. A
// sample strictly inside a grid step is a side step from the grid's last
// step end, after which the grid carries on as if it never happened. Shared
// by the element row under load (spectrum_load_run.cpp, LoadRun) and kelvin_load
// (load.cpp, Stepper).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/model/case.hpp"

namespace mdrmap {

struct LoadLattice {
  /// Points per segment of the fine run of the error control.
  static constexpr long kFine = 200;

  double T = 0.0; ///< the segment's duration
  long n = kFine; ///< points j = 1 .. n (j = 0: the segment's start)

  /// Points per segment of a run at resolution `cells` whose estimate's fine
  /// run is at `fine`: kFine in the fine run, fewer in proportion in the
  /// coarser runs (100 in the half-resolution companion), at least 25. Where
  /// the lattice binds the steps, the companion's coarser lattice shows the
  /// time error it leaves (on a lattice shared by both runs the estimate did
  /// not see it).
  static long points(double cells, double fine) {
    return std::max(25L, std::lround(static_cast<double>(kFine) * cells / fine));
  }
  /// Point j: the offset of sample j of n + 1 linear samples (the same
  /// formula: on the fine run's 200 points such samples fall, and those of 5,
  /// 21, 41 or 101).
  double at(long j) const {
    Sampling s;
    s.samples = n + 1; // (linear)
    return s.offset(j, T);
  }
  /// a and b the same instant (a few ulps apart: the lattice's points as
  /// other samplings compute them).
  static bool near(double a, double b) {
    return std::abs(a - b) <=
           4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(a), std::abs(b));
  }
};

} // namespace mdrmap
