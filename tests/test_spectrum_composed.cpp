// The element row's composed steps (src/core/solvers/spectrum_composed.cpp):
// for the parabola an element that does not switch during a step takes the
// step's sub-steps composed into one affine update, its force (gap) checked
// at each sub-step's end from the composed form. Against the same row
// stepping every element sub-step by sub-step: the forces agree to rounding
// over velocity steps, a hold, a reslide and depth paths as the load control
// takes them, with and without a parallel dashpot; and a case under load run
// through the solver gives the same series.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cases/spectrum_case_set.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_law.hpp"
#include "core/solvers/spectrum_row.hpp"
#include "test_case.hpp"

namespace mdrmap {
namespace {

/// One operation of the scenario both rows go through: a velocity change to
/// w (dt < 0), or a step of dt with the depth ending at d1 times the start's
/// depth (1: fixed) at rate dd1.
struct Op {
  double w, dt, d1 = 1.0, dd1 = 0.0;
};

std::vector<Op> scenario() {
  return {{2.0, -1.0},
          {0.0, 1e-4},
          {0.0, 1e-3},
          {0.0, 0.02},
          {0.0, 0.3},
          {0.1, -1.0},
          {0.0, 1e-3},
          {0.0, 0.5},
          {0.0, -1.0},
          {0.0, 0.2, 1.002},
          {0.0, 2.0, 1.004},
          {1.0, -1.0},
          {0.0, 0.01, 0.999, -0.1},
          {0.0, 0.1, 0.995, -0.01},
          {0.0, 0.4, 0.99}};
}

/// Runs the scenario on two rows, composed and not, comparing F_N, F_x and
/// the trailing edge after every step; returns the composed row's composed
/// element steps.
long compare_rows(const Case& c, double d) {
  const spectrum::Law law(c.rheology);
  const RunControl control;
  const double dx = 1.0 / 32.0;
  spectrum::Row a(c, law, d, dx, 1.5, 0.3, 0.25, 1e-9, control, "test");
  spectrum::Row b(c, law, d, dx, 1.5, 0.3, 0.25, 1e-9, control, "test");
  b.set_composed(false);
  for (spectrum::Row* r : {&a, &b})
    r->start_stationary(0.5, d);
  const double scale = std::abs(a.measure().FN);
  for (const Op& op : scenario()) {
    for (spectrum::Row* r : {&a, &b}) {
      if (op.dt < 0.0)
        r->change_velocity(op.w);
      else
        r->advance(op.dt, op.d1 * r->depth_now(), op.dd1 * d);
    }
    const State sa = a.measure(), sb = b.measure();
    // (rounding, but where the edge search, to 1e-9 a1, stops at another
    // point of its bracket: with a dashpot p jumps at the edge at a change)
    EXPECT_NEAR(sa.FN, sb.FN, 1e-9 * scale) << "dt " << op.dt;
    EXPECT_NEAR(sa.Fx, sb.Fx, 1e-9 * scale) << "dt " << op.dt;
    EXPECT_NEAR(sa.a2, sb.a2, 1e-8) << "dt " << op.dt;
  }
  EXPECT_EQ(b.composed_steps(), 0);
  return a.composed_steps();
}

TEST(SpectrumComposed, AgreesWithTheSubStepsOverAHistory) {
  Case c = step_case(0.1, 10.0, 0.0, 1.0, 1.0); // a1 = 1
  c.rheology.branches = {{5.0, 0.05}, {4.0, 2.0}, {3.0, 1e-4}};
  EXPECT_GT(compare_rows(c, 0.1), 500);
}

TEST(SpectrumComposed, AgreesWithTheSubStepsWithADashpot) {
  Case c = step_case(0.1, 10.0, 0.3, 1.0, 1.0);
  c.rheology.branches = {{2.0, 1.0}, {2.0, 0.05}};
  EXPECT_GT(compare_rows(c, 0.1), 500);
}

// Through the solver, under load: a slide-hold-slide of three terms, at a
// fixed resolution with the load balance's tolerance (1e-3 rtol) far below
// the rounding the composition changes (at rtol 1e-3 the two runs' balances
// stop at different trials, within 1e-6 of each other).
TEST(SpectrumComposed, TheSolverUnderLoadGivesTheSameSeries) {
  Case c;
  c.indenter.as<Parabola>().R = 2.0;
  c.rheology = material(1.0, 0.0, {{1.0, 1e-3}, {1.0, 0.1}, {1.0, 10.0}});
  c.loading.F0 = 4e-3;
  c.history.v0 = c.a0();
  c.history.segments = {{c.history.v0, 1.0}, {0.0, 5.0}, {c.history.v0, 2.0}};
  c.sampling.samples = 21;
  SpectrumOptions on;
  on.cells_per_a1 = 16;
  on.rtol = 1e-9;
  on.estimate_error = false;
  SpectrumOptions off = on;
  off.composed_steps = false;
  const RunResult a = run_spectrum(CheckedCase(c), on), b = run_spectrum(CheckedCase(c), off);
  EXPECT_LE(case_error(a.series, b.series, c).max(), 1e-9);
}

} // namespace
} // namespace mdrmap
