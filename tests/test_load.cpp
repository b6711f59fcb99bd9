// The load-control solver (docs/design.md, "Load control"): stationary sliding
// under load against the fixed-depth stationary state at its root, Hertz and
// the large-zeta limits; run_load keeping F_N = F0, reaching the stationary
// state under load, Hertz at once for tau -> 0; its observed orders in dt and
// dx; and on the load case set, within rtol of a reference built by refining
// it, with an honest error estimate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cases/load_case_set.hpp"
#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/metrics/events.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/solvers/dispatch.hpp"
#include "core/solvers/load.hpp"
#include "core/solvers/spectrum_baseline.hpp"
#include "test_case.hpp"

namespace mdrmap {
namespace {

/// R = 2, G = 1, tau = 1, F0 in G R^2, v0 from zeta0 = v0 tau / a0; segments (w / v0, T / tau).
Case load_case(double zeta0, const std::vector<std::pair<double, double>>& segs, long samples = 21,
               double F0 = 4e-3, double tau = 1.0) {
  Case c;
  c.indenter.as<Parabola>().R = 2.0;
  c.rheology.tau = tau;
  c.loading.F0 = F0;
  c.history.v0 = zeta0 * c.a0() / tau;
  for (const auto& [w, T] : segs)
    c.history.segments.push_back({w * c.history.v0, T * tau});
  c.sampling.samples = samples;
  return c;
}

double d0_of(const Case& c) {
  return c.a0() * c.a0() / c.indenter.as<Parabola>().R;
}

Series at(const Case& c, double cells, double time_tol, double dt_over_tau = 0.0) {
  LoadOptions o;
  o.cells = cells;
  o.time_tol = time_tol;
  o.dt_over_tau = dt_over_tau;
  o.estimate_error = false;
  return run_load(CheckedCase(c), o).series;
}

TEST(StationaryUnderLoad, RootOfTheFixedDepthStationaryForce) {
  for (double F0 : {1e-12, 4e-3, 1e3}) {
    for (double z : {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6}) {
      const Case c = load_case(z, {{1.0, 1.0}}, 3, F0);
      const double w = c.history.v0;
      const double d = stationary_depth(c, w);
      const State fixed = analytic::stationary(at_depth(c, d), w);
      EXPECT_NEAR(fixed.FN / F0, 1.0, 4e-15) << "F0=" << F0 << " zeta0=" << z;
      const State st = stationary_under_load(c, w);
      EXPECT_EQ(st.d, d);
      EXPECT_NEAR(st.a1, std::sqrt(c.indenter.as<Parabola>().R * d), 1e-15 * st.a1);
      EXPECT_NEAR(st.mu, fixed.mu, 1e-14 * fixed.mu);
      EXPECT_NEAR(st.a2, fixed.a2, 1e-14 * st.a1);
    }
  }
}

TEST(StationaryUnderLoad, HertzAsTauGoesToZero) {
  Case c = load_case(1.0, {{1.0, 1.0}}, 3);
  const double d0 = d0_of(c);
  for (double tau : {1e-3, 1e-6, 1e-9, 1e-12}) {
    c.rheology.tau = tau; // zeta0 = v0 tau / a0 falls with tau at fixed v0
    const double z = c.history.v0 * tau / c.a0();
    const double d = stationary_depth(c, c.history.v0);
    EXPECT_LT(std::abs(d / d0 - 1.0), 4.0 * z) << tau;
    EXPECT_LT(stationary_under_load(c, c.history.v0).mu / (c.a0() / c.indenter.as<Parabola>().R),
              4.0 * z);
  }
  c.rheology.tau = 0.0;
  EXPECT_NEAR(stationary_depth(c, c.history.v0) / d0, 1.0, 1e-15);
}

// zeta0 -> infinity: the viscous term carries the load on a contact of
// length ~a1: alpha^2 zeta0 -> 4/3 (d/d0 -> 4/(3 zeta0)) and mu -> 4/3 sqrt(d/R).
TEST(StationaryUnderLoad, LargeZetaLimits) {
  double prev_dev = 1.0;
  for (double z : {1e2, 1e4, 1e6}) {
    const Case c = load_case(z, {{1.0, 1.0}}, 3);
    const State st = stationary_under_load(c, c.history.v0);
    const double dev_d = std::abs(st.d / d0_of(c) * 0.75 * z - 1.0);
    const double dev_mu =
        std::abs(st.mu / (4.0 / 3.0 * std::sqrt(st.d / c.indenter.as<Parabola>().R)) - 1.0);
    EXPECT_LT(dev_d, 2.0 / std::sqrt(z)) << z; // corrections ~ alpha/zeta0 ~ zeta0^-3/2
    EXPECT_LT(dev_mu, 2.0 / std::sqrt(z)) << z;
    EXPECT_LT(dev_d, 0.2 * prev_dev);
    prev_dev = dev_d;
  }
  const Case c = load_case(1e6, {{1.0, 1.0}}, 3);
  EXPECT_NEAR(stationary_under_load(c, c.history.v0).d / d0_of(c) * 0.75e6, 1.0, 1e-6);
}

TEST(RunLoad, NormalForceIsF0AtEverySample) {
  for (const auto& nc : load_case_set(11)) {
    if (nc.name.find("zeta0=1e6") != std::string::npos) continue; // (slow; in the set test)
    LoadOptions o;
    o.rtol = 1e-3;
    const RunResult r = run_load(CheckedCase(nc.c), o);
    double dev = std::abs(r.series.pre.FN / nc.c.loading.F0 - 1.0);
    for (std::size_t k = 0; k < r.series.size(); ++k)
      dev = std::max(dev, std::abs(r.series.FN[k] / nc.c.loading.F0 - 1.0));
    EXPECT_LT(dev, o.rtol) << nc.name;
    EXPECT_LT(dev, 1e-12) << nc.name; // by construction: D follows from F0 and the contact
  }
}

// A long segment after a drop, after a rise and after a hold ends in the
// stationary state under load at its velocity (item 1).
TEST(RunLoad, LongSegmentReachesTheStationaryStateUnderLoad) {
  for (const auto& segs : std::vector<std::vector<std::pair<double, double>>>{
           {{0.1, 40.0}}, {{10.0, 40.0}}, {{0.0, 2.0}, {1.0, 40.0}}, {{0.3, 1.0}, {3.0, 40.0}}}) {
    for (double z : {0.1, 1.0, 10.0}) {
      const Case c = load_case(z, segs, 5);
      LoadOptions o;
      o.rtol = 1e-4;
      const RunResult r = run_load(CheckedCase(c), o);
      const State st = stationary_under_load(c, c.history.segments.back().w);
      const std::size_t k = r.series.size() - 1;
      EXPECT_NEAR(r.series.d[k] / st.d, 1.0, 1e-6) << z;
      EXPECT_NEAR(r.series.a1[k] / st.a1, 1.0, 1e-6) << z;
      EXPECT_NEAR(r.series.a2[k] / st.a1, st.a2 / st.a1, 1e-6) << z;
      EXPECT_NEAR(r.series.mu[k] / st.mu, 1.0, 1e-6) << z;
    }
  }
}

// Event metrics under load measure against the stationary states under F0
// (not at some depth): before the first change the run starts in it, at the
// end of a long segment it has reached the new one; F_N of both is F0.
TEST(RunLoad, EventsUseTheStationaryStatesUnderLoad) {
  const Case c = load_case(0.1, {{10.0, 40.0}, {100.0, 40.0}, {1000.0, 40.0}}, 9);
  LoadOptions o;
  o.rtol = 1e-4;
  const RunResult r = run_load(CheckedCase(c), o);
  const auto ev = event_metrics(c, r.series);
  ASSERT_EQ(ev.size(), 3u);
  for (const auto& e : ev) {
    EXPECT_NEAR(e.ss_before.FN / c.loading.F0, 1.0, 1e-12);
    EXPECT_NEAR(e.ss_after.FN / c.loading.F0, 1.0, 1e-12);
    EXPECT_NEAR(e.end.mu / e.ss_after.mu, 1.0, 1e-6);
  }
  EXPECT_NEAR(ev[0].ss_before.mu / r.series.pre.mu, 1.0, 1e-12);
  EXPECT_NEAR(ev[1].ss_before.mu / ev[0].ss_after.mu, 1.0, 1e-15);
  // mu_ss has one maximum, at zeta0* = 1.398: velocity strengthening below
  // it (0.1 -> 1: a - b > 0), weakening above it (10 -> 100: a - b < 0)
  EXPECT_GT(ev[0].a_minus_b, 0.0);
  EXPECT_LT(ev[2].a_minus_b, 0.0);
}

// Indentation creep at rest under a step load (undeformed start): the
// contact is full and d = d0 (1 - exp(-t/tau))^(2/3) (tests/test_load_checks
// has it against quadrature); the solver at rtol 1e-6 from rtol alone.
TEST(RunLoad, IndentationCreepUnderAStepLoad) {
  for (double F0 : {1e-12, 4e-3, 1e3}) {
    Case c = load_case(1.0, {{0.0, 20.0}}, 81, F0);
    c.sampling.spacing = Spacing::Log;
    c.sampling.decades = 6;
    LoadOptions o;
    o.rtol = 1e-6;
    o.start = LoadStart::Undeformed;
    const RunResult r = run_load(CheckedCase(c), o);
    const double d0 = d0_of(c);
    double worst = 0.0;
    for (std::size_t k = 0; k < r.series.size(); ++k) {
      const double t = r.series.t[k];
      const double exact = d0 * std::pow(-std::expm1(-t / c.rheology.tau), 2.0 / 3.0);
      worst = std::max(worst, std::abs(r.series.d[k] - exact) / d0);
      EXPECT_NEAR(r.series.a1[k], std::sqrt(c.indenter.as<Parabola>().R * r.series.d[k]),
                  1e-15 * c.a0());
      EXPECT_NEAR(r.series.a2[k], r.series.a1[k], 1e-12 * c.a0()) << t; // full contact
      EXPECT_NEAR(r.series.FN[k] / F0, 1.0, 1e-12);
    }
    EXPECT_LT(worst, 1e-6) << F0;
    EXPECT_GE(r.info.error_estimate, worst / 3.0) << F0;
    EXPECT_LT(r.info.steps, 20000);
  }
}

TEST(RunLoad, TauZeroIsHertzAtOnce) {
  Case c = load_case(1.0, {{0.1, 2.0}, {0.0, 1.0}, {10.0, 2.0}}, 11);
  c.rheology.tau = 0.0;
  c.history.v0 = 1.0;
  const RunResult r = run_load(CheckedCase(c), LoadOptions{});
  const double d0 = d0_of(c), a0 = c.a0();
  for (std::size_t k = 0; k < r.series.size(); ++k) {
    EXPECT_NEAR(r.series.d[k] / d0, 1.0, 1e-15);
    EXPECT_NEAR(r.series.a1[k] / a0, 1.0, 1e-15);
    EXPECT_NEAR(r.series.a2[k] / a0, 1.0, 1e-15);
    EXPECT_EQ(r.series.mu[k], 0.0);
  }
  // tiny tau at the same velocities (zeta0 = 1e-9): no stiff trap; Hertz to
  // O(zeta0) from the first sample after each change on
  Case s = load_case(1.0, {{0.1, 3.0}, {0.0, 2.0}, {1.0, 3.0}}, 11);
  s.rheology.tau = 1e-9;
  const RunResult q = run_load(CheckedCase(s), LoadOptions{});
  EXPECT_LT(q.info.steps, 20000);
  for (std::size_t k = 0; k < q.series.size(); ++k) {
    if (k % 11 == 0) continue; // (the instant of a change)
    EXPECT_NEAR(q.series.d[k] / d0_of(s), 1.0, 1e-6) << k;
    EXPECT_NEAR(q.series.a1[k] / s.a0(), 1.0, 1e-6) << k;
  }
}

// Second order in time where nothing switches: after a rise the edge sits at
// the force-zero point throughout (no element matters), fixed steps dt.
TEST(RunLoadOrder, SecondOrderInTime) {
  const Case c = load_case(1.0, {{10.0, 2.0}}, 9);
  const Series ref = at(c, 16, 1e-12);
  double e[3];
  const double dts[3] = {0.04, 0.02, 0.01};
  for (int i = 0; i < 3; ++i)
    e[i] = case_error(at(c, 16, 0.0, dts[i]), ref, c, 1e-12).max();
  const double p1 = testing::observed_order({1.0 / dts[0], 1.0 / dts[1]}, {e[0], e[1]});
  const double p2 = testing::observed_order({1.0 / dts[1], 1.0 / dts[2]}, {e[1], e[2]});
  EXPECT_GT(p1, 1.8) << e[0] << " " << e[1];
  EXPECT_GT(p2, 1.8) << e[1] << " " << e[2];
}

// In space: the edge read-out is exact where the front advances through one
// piece of free material (a drop out of stationary sliding: any dx gives the
// converged answer) and converges where pieces meet (drop, hold, reslide: the
// front crosses the boundary between the tail left at the cap after the drop
// and the older stationary tail; no tracer marks it, observed order ~1).
TEST(RunLoadOrder, ConvergesInSpace) {
  const Case d = load_case(1.0, {{0.1, 3.0}}, 21);
  EXPECT_LT(case_error(at(d, 16, 1e-9), at(d, 256, 1e-9), d, 1e-12).max(), 1e-7);
  const Case c = load_case(1.0, {{0.1, 2.0}, {0.0, 2.0}, {1.0, 3.0}}, 31);
  const Series ref = at(c, 2048, 1e-9);
  std::vector<double> cells = {32.0, 64.0, 128.0, 256.0}, err;
  for (double n : cells)
    err.push_back(case_error(at(c, n, 1e-9), ref, c, 1e-12).max());
  const double order = testing::observed_order(cells, err);
  EXPECT_GT(order, 0.8) << err[0] << " " << err[3];
}

// Done-criterion: on every load-controlled history of the set the solver at
// rtol 1e-3 and 1e-4 (and 1e-2) is within rtol of a reference built by
// refining it (4x the resolution, local step error 1e-9) and its estimate is
// at least a third of its error; the set includes drop-hold-rise histories (a
// re-touch front from a tangency) and reslides whose travel is below the grid
// of rtol's resolution. The two zeta0 = 1e6 histories against a local step
// error of 1e-8: D ~ 2 L a1 / R carries rounding of ~1e-16 L / a1 relative
// to d, which the step control sees at 1e-9 (docs/design.md, "Load control").
TEST(RunLoadSet, WithinRtolWithAnHonestEstimate) {
  const auto set = load_case_set();
  ASSERT_GE(set.size(), 32u);
  for (const auto& nc : set) {
    const bool heavy = nc.name.find("zeta0=1e6") != std::string::npos;
    LoadOptions o;
    o.rtol = 1e-4;
    const RunResult finest = run_load(CheckedCase(nc.c), o);
    const Series ref = at(nc.c, 4.0 * finest.info.cells_per_a1, heavy ? 1e-8 : 1e-9);
    for (double rtol : {1e-2, 1e-3, 1e-4}) { // (1e-2: long trial steps)
      o.rtol = rtol;
      const RunResult r = rtol == finest.info.rtol ? finest : run_load(CheckedCase(nc.c), o);
      const double err = case_error(r.series, ref, nc.c, 1e-12).max();
      EXPECT_LE(err, rtol) << nc.name << " rtol " << rtol;
      EXPECT_GE(r.info.error_estimate, err / 3.0) << nc.name << " rtol " << rtol;
    }
  }
}

// Held-out drop-hold-rise histories (issue 32): at zeta0 = 3 the edge that
// re-touches during a hold of 0.3 tau was off by 1.0e-3 a0 at rtol 1e-3 with
// the estimate at 8.8e-4 (the companion shares part of that error); a hold of
// 0.003 tau before a threefold rise was abandoned after five resolutions. The
// run stops with its estimate within half of rtol.
TEST(RunLoadSet, HeldOutDropHoldRiseWithinRtol) {
  for (const auto& [th, up] : {std::pair{0.3, 1.0}, std::pair{0.003, 3.0}}) {
    const Case c = load_case(3.0, {{0.1, 1.0}, {0.0, th}, {up, 1.0}}, 61);
    LoadOptions o;
    o.rtol = 1e-3;
    const RunResult r = run_load(CheckedCase(c), o);
    const Series ref = at(c, 4.0 * r.info.cells_per_a1, 1e-9);
    const double err = case_error(r.series, ref, c, 1e-12).max();
    EXPECT_LE(err, o.rtol) << "hold " << th << " rise " << up;
    EXPECT_GE(r.info.error_estimate, err / 3.0) << "hold " << th << " rise " << up;
  }
}

// The reference confirmed independently: the fixed-step row (baseline, no
// shared code, first order in dx and dt, dt = dx / v_max; a1/dx 25 .. 200)
// converges to the load solver at
// rtol 1e-6 on transients of the set: a rise and back, a drop and back, a
// slide-hold-slide.
TEST(RunLoadSet, TheFixedStepSolverConvergesToIt) {
  const auto set = load_case_set(21);
  for (const char* name : {"3seg up 10x and back, zeta0=1", "3seg down 10x and back, zeta0=1",
                           "3seg slide-hold-slide hold=1 tau"}) {
    const auto it =
        std::find_if(set.begin(), set.end(), [&](const NamedCase& nc) { return nc.name == name; });
    ASSERT_NE(it, set.end()) << name;
    LoadOptions o;
    o.rtol = 1e-6;
    const RunResult ref = run_load(CheckedCase(it->c), o);
    std::vector<double> cells = {25.0, 50.0, 100.0, 200.0}, err;
    for (double n : cells) {
      SpectrumBaselineOptions b;
      b.cells_per_a1 = n;
      b.estimate_error = false;
      err.push_back(
          case_error(run_spectrum_baseline(CheckedCase(it->c), b).series, ref.series, it->c, 1e-12)
              .max());
    }
    const double order = testing::observed_order(cells, err);
    EXPECT_GT(order, 0.7) << name << ": " << err[0] << " .. " << err[3];
    EXPECT_LT(order, 1.4) << name;
    EXPECT_LT(err[3], err[0]) << name;
  }
}

// The window is sized for the deepest stationary contact of the history; a
// run whose edge leaves it is rerun with the Hertz contact's window. Forced
// here (a window for 0.3 a0 on a slide-hold-slide, where the hold creeps
// towards a0): the same series as with the window sized for it (to
// rounding), and a
// zeta0 = 1e6 history holds ~100x fewer elements than a0 would need.
TEST(RunLoad, WindowFromTheHistoryWidensWhenLeft) {
  const Case c = load_case(1.0, {{1.0, 1.0}, {0.0, 10.0}, {1.0, 3.0}}, 11);
  LoadOptions o;
  o.rtol = 1e-4;
  const RunResult ref = run_load(CheckedCase(c), o);
  o.window_a0 = 0.3;
  const RunResult r = run_load(CheckedCase(c), o);
  EXPECT_LT(case_error(r.series, ref.series, c, 1e-12).max(), 1e-14); // (a0 vs alpha(0) a0)
  EXPECT_EQ(r.info.elements, ref.info.elements);
  const Case fast = load_case(1e6, {{0.1, 0.2}, {1.0, 0.2}}, 5);
  o.window_a0 = 0.0;
  const RunResult f = run_load(CheckedCase(fast), o);
  o.window_a0 = 1.0;
  const RunResult g = run_load(CheckedCase(fast), o);
  EXPECT_LT(100 * f.info.elements, g.info.elements);
  EXPECT_LT(case_error(f.series, g.series, fast, 1e-12).max(), 1e-12);
}

TEST(RunLoad, DispatchAndRefusals) {
  const Case c = load_case(1.0, {{0.1, 1.0}}, 5);
  EXPECT_EQ(run_case(CheckedCase(c), SolverKind::Auto, 1e-3).info.solver, "kelvin_load");
  EXPECT_EQ(run_case(CheckedCase(c), SolverKind::Row, 1e-3).info.solver, "row");
  EXPECT_THROW(run_case(CheckedCase(c), SolverKind::Exact, 1e-3), InvalidInput);
  Case fixed = step_case(1e-3, 1.0, 1.0, 1.0, 0.1);
  EXPECT_THROW(run_load(CheckedCase(fixed), LoadOptions{}), InvalidInput);
}

} // namespace
} // namespace mdrmap
