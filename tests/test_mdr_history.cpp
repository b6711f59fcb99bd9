// The discrete MDR simulator on velocity histories (docs/design.md, "The
// discrete solvers"): against the continuum solution on the history set, its
// observed order in dx per history type, the brute-force fixed-step method
// converging to the continuum, the state across a velocity change, the
// contact growing from a tangency after a detachment, and hard histories.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cases/case_set.hpp"
#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/baseline.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/mdr.hpp"
#include "test_case.hpp"

namespace mdrmap {
namespace {

Case history(double zeta0, const std::vector<std::pair<double, double>>& segs, long samples = 61,
             double d_over_R = 1e-3) {
  return testing::history_case(zeta0, segs, samples, d_over_R);
}

Case from_set(const std::string& name) {
  for (const auto& nc : history_case_set())
    if (nc.name == name) return nc.c;
  ADD_FAILURE() << "no case '" << name << "' in history_case_set()";
  return history(1.0, {{0.1, 1.0}});
}

/// mdr at a fixed resolution, without the error estimate.
Series mdr_at(const Case& c, double cells, MdrSubgrid mode = MdrSubgrid::Piecewise,
              double phase = 0.5) {
  MdrOptions o;
  o.cells_per_a1 = cells;
  o.subgrid = mode;
  o.phase = phase;
  o.estimate_error = false;
  return run_mdr(c, o).series;
}

bool all_finite(const Series& x) {
  for (std::size_t k = 0; k < x.size(); ++k)
    if (!std::isfinite(x.FN[k]) || !std::isfinite(x.Fx[k]) || !std::isfinite(x.mu[k]) ||
        !std::isfinite(x.a2[k]))
      return false;
  return std::isfinite(x.pre.FN) && std::isfinite(x.pre.Fx) && std::isfinite(x.pre.a2);
}

// Done-criterion of the history issue: on every history of the set, mdr at
// rtol 1e-2, 1e-3, 1e-4 is within rtol of the continuum solution, and its
// error estimate is honest (at least a third of the true error).
TEST(MdrHistorySet, WithinRtolWithAnHonestEstimate) {
  for (const auto& nc : history_case_set()) {
    SCOPED_TRACE(nc.name);
    const RunResult ref = run_exact(nc.c, 1e-13);
    for (double rtol : {1e-2, 1e-3, 1e-4}) {
      MdrOptions o;
      o.rtol = rtol;
      const RunResult r = run_mdr(nc.c, o);
      ASSERT_TRUE(all_finite(r.series));
      const double err = case_error(r.series, ref.series, nc.c).max();
      EXPECT_LE(err, rtol) << "rtol " << rtol << " cells " << r.info.cells_per_a1;
      EXPECT_GE(r.info.error_estimate, err / 3.0) << "rtol " << rtol;
    }
  }
}

// The read-out is exact in every piece of free material at any dx, so what
// is left is rounding, for every history of the set, at coarse resolutions
// and with the grid at any phase: in particular where a piece is narrower
// than a cell (after two drops, zeta0 = 0.3: 0.0075 a1; zeta0 = 1e-3: the
// whole transient within 3e-4 a1 of a1), where the previous read-out (one
// tracer, log-linear across epochs) was off by up to 7e-3 until dx resolved it.
TEST(MdrHistorySet, ExactToRoundingAtCoarseResolutions) {
  for (const auto& nc : history_case_set()) {
    SCOPED_TRACE(nc.name);
    const RunResult ref = run_exact(nc.c, 1e-13);
    for (double cells : {16.0, 37.0})
      for (double phase : {0.5, 0.2137}) {
        const double err =
            case_error(mdr_at(nc.c, cells, MdrSubgrid::Piecewise, phase), ref.series, nc.c).max();
        EXPECT_LE(err, 1e-11) << "cells " << cells << " phase " << phase;
      }
  }
}

// Observed order in dx per history type, for each read-out: the paper's raw
// sums first order, the linearly interpolated gap second order, the default
// per-piece read-out exact (rounding) at every resolution.
TEST(MdrHistoryConvergence, ObservedOrderPerHistoryType) {
  const std::vector<double> cells = {50, 100, 200, 400, 800, 1600};
  const std::pair<const char*, Case> types[] = {
      {"two drops", from_set("two drops zeta=1")},
      {"three drops", from_set("three drops zeta=0.3")},
      {"hold then reslide", from_set("slide-hold-slide hold=1 tau")},
      {"drop, hold, reslide", from_set("drop-hold-reslide d/R=1e-06")},
      {"drop-rise-drop", from_set("drop-rise-drop zeta=1")},
      // the front runs into material let go at the rise (a parabola)
      {"hold, rise, hold", history(1.0, {{0.0, 2.0}, {1.0, 0.1}, {0.0, 5.0}})},
  };
  for (const auto& [type, c] : types) {
    SCOPED_TRACE(type);
    const RunResult ref = run_exact(c, 1e-13);
    for (MdrSubgrid mode : {MdrSubgrid::None, MdrSubgrid::Linear, MdrSubgrid::Piecewise}) {
      std::vector<double> err;
      for (double n : cells)
        err.push_back(case_error(mdr_at(c, n, mode), ref.series, c).max());
      std::printf("%-20s ", type);
      testing::expect_readout_order(mode, cells, err, 1e-12);
    }
  }
}

// A change of velocity takes no time: just after a drop or the start of a
// hold the contact is the one just before; just after a rise it is cut back
// to the new stationary edge a2(w) if it reached beyond.
TEST(MdrHistoryChange, TrailingEdgeAcrossEachChange) {
  for (const auto& nc : history_case_set()) {
    SCOPED_TRACE(nc.name);
    const Case& c = nc.c;
    const Series s = mdr_at(c, 32.0, MdrSubgrid::Piecewise, 0.2137);
    const auto N = static_cast<std::size_t>(c.sampling.samples);
    for (std::size_t k = 0; k < c.history.size(); ++k) {
      const double before = k == 0 ? s.pre.a2 : s.a2[k * N - 1];
      const double after = s.a2[k * N];
      const double w = c.history.segments[k].w;
      const double expect =
          w <= c.history.before(k) ? before : std::min(before, analytic::a2_stationary(c, w));
      EXPECT_NEAR(after / c.a1(), expect / c.a1(), 1e-12) << "change " << k;
    }
  }
}

// The trap of sub-grid edges: right after a detachment (here the start of a
// hold, out of stationary sliding) the gap next to the edge is of order dx^2,
// so a linear interpolation of u invents a re-touch there. The contact then
// grows from a tangency: the tail u = h(a2) exp(-y/L) (L = v0 tau) relaxes in
// place and touches where h(a2 + y) = h(a2) exp(-y/L) exp(-t/tau), so the edge
// moves like sqrt(t) at first. Checked from 1e-8 tau on, at 32 cells, against
// that scalar equation solved here in long double.
TEST(MdrHistoryTangency, ContactGrowsFromTheTangencyAfterAHoldStarts) {
  Case c = history(1.0, {{0.0, 1.0}}, 41);
  c.sampling.spacing = Spacing::Log;
  c.sampling.decades = 8.0;
  const long double R = c.indenter.as<Parabola>().R, a1 = c.a1(), tau = c.rheology.tau;
  const long double L = c.history.v0 * c.rheology.tau;
  const long double a2 = analytic::a2_stationary(c, c.history.v0), ha2 = (a1 - a2) * (a1 + a2) / R;
  const Series s = mdr_at(c, 32.0);
  const Series lin = mdr_at(c, 32.0, MdrSubgrid::Linear);
  double worst = 0.0, worst_linear = 0.0;
  for (std::size_t i = 1; i < s.size(); ++i) {
    const long double t = s.t[i];
    auto psi = [&](long double y) {
      return ((a1 - a2 - y) * (a1 + a2 + y)) / R - ha2 * std::exp(-y / L - t / tau);
    };
    long double lo = 0.0L, hi = a1 - a2; // psi(lo) > 0 > psi(hi)
    for (int it = 0; it < 200; ++it) {
      const long double mid = 0.5L * (lo + hi);
      if (psi(mid) > 0.0L)
        lo = mid;
      else
        hi = mid;
    }
    const double edge = static_cast<double>(a2 + lo);
    EXPECT_NEAR(s.a2[i] / c.a1(), edge / c.a1(), 1e-13) << "t/tau " << s.t[i];
    worst = std::max(worst, std::abs(s.a2[i] - edge) / c.a1());
    worst_linear = std::max(worst_linear, std::abs(lin.a2[i] - edge) / c.a1());
  }
  std::printf("[ info ] edge after a hold starts, t/tau in [1e-8, 1], 32 cells: per-piece "
              "read-out off by %.1e a1, linear gap by %.1e a1\n",
              worst, worst_linear);
}

// The brute-force method (every element, a fixed step, contact decided at
// step ends, raw sums) converges to the continuum solution at first order on
// histories too: an independent check of the continuum construction.
TEST(MdrHistoryBruteForce, BaselineConvergesAtFirstOrder) {
  const std::vector<double> cells = {200, 400, 800};
  for (const char* name : {"two drops zeta=1", "slide-hold-slide hold=1 tau",
                           "drop-rise-drop zeta=1", "hold inside a transient"}) {
    SCOPED_TRACE(name);
    Case c = from_set(name);
    c.sampling.samples = 21;
    const RunResult ref = run_exact(c, 1e-13);
    std::vector<double> err;
    for (double n : cells) {
      BaselineOptions b;
      b.cells_per_a1 = n;
      b.estimate_error = false;
      const RunResult r = run_baseline(c, b);
      ASSERT_TRUE(all_finite(r.series));
      err.push_back(case_error(r.series, ref.series, c).max());
    }
    const double order = testing::observed_order(cells, err);
    std::printf("[ info ] baseline %-28s errors %.2e %.2e %.2e  order %.2f\n", name, err[0], err[1],
                err[2], order);
    EXPECT_GE(order, 0.7);
    EXPECT_LE(order, 1.5);
    EXPECT_LT(err.back(), err.front());
  }
}

// Hard histories beyond the set: holds of 1e-6 and 1e6 tau in one history,
// velocity ratios 1e-8 and 1e8 back to back, 20 alternating segments with
// holds, zeta0 from 1e-4 to 1e6, d/R from 1e-12 to 0.3, and tau = 0 (the
// elastic limit: Hertz at every instant). No NaN, no blow-up, contact inside
// [-a1, a1], and within rtol of the continuum solution.
TEST(MdrHistoryHardCases, NoNaNNoBlowUp) {
  std::vector<std::pair<double, double>> alternating;
  for (int k = 0; k < 20; ++k)
    alternating.push_back({k % 3 == 2 ? 0.0 : (k % 2 == 0 ? 1e-8 : 1.0), 0.05 + 0.1 * (k % 4)});
  const std::vector<std::vector<std::pair<double, double>>> patterns = {
      {{1e-8, 1e-6}, {0.0, 1e6}, {1.0, 2.0}, {0.0, 1e-6}, {1e-4, 3.0}},
      {{1e-8, 0.5}, {1.0, 1e-3}, {0.0, 0.2}, {1e4, 0.01}, {1e-4, 2.0}},
      alternating,
  };
  for (double z : {1e-4, 1.0, 1e6})
    for (double dr : {1e-12, 0.3})
      for (std::size_t p = 0; p < patterns.size(); ++p) {
        const Case c = history(z, patterns[p], 21, dr);
        SCOPED_TRACE("zeta0 " + std::to_string(z) + " d/R " + std::to_string(dr) + " pattern " +
                     std::to_string(p));
        const RunResult ref = run_exact(c, 1e-13);
        MdrOptions o;
        o.rtol = 1e-3;
        const RunResult r = run_mdr(c, o);
        ASSERT_TRUE(all_finite(r.series));
        for (std::size_t k = 0; k < r.series.size(); ++k) {
          EXPECT_GT(r.series.FN[k], 0.0);
          EXPECT_GE(r.series.a2[k], -c.a1());
          EXPECT_LE(r.series.a2[k], c.a1() * (1 + 1e-15));
        }
        EXPECT_LE(case_error(r.series, ref.series, c).max(), 1e-3);
      }
  Case c = history(1.0, {{0.1, 2.0}, {0.0, 1.0}, {10.0, 2.0}, {0.0, 1e6}}, 11);
  c.rheology.tau = 0.0; // elastic: valid, Hertz whatever the history
  const RunResult r = run_mdr(c, MdrOptions{});
  ASSERT_TRUE(all_finite(r.series));
  const double hertz = 16.0 / 3.0 * c.rheology.G * std::sqrt(c.indenter.as<Parabola>().R) *
                       std::pow(c.loading.d, 1.5);
  for (std::size_t k = 0; k < r.series.size(); ++k) {
    EXPECT_NEAR(r.series.FN[k] / hertz, 1.0, 1e-12);
    EXPECT_NEAR(r.series.mu[k], 0.0, 1e-12);
  }
}

// Cost of the done-criterion: median over the three-segment histories of the
// set (61 samples per segment) at rtol 1e-3, error estimate included. Asserted
// only in an optimised build without sanitizers.
TEST(MdrHistoryCost, ThreeSegmentHistoriesAtRtol1e3) {
  std::vector<double> ms;
  for (const auto& nc : history_case_set(61)) {
    if (nc.c.history.size() != 3) continue;
    double best = std::numeric_limits<double>::infinity();
    for (int rep = 0; rep < 3; ++rep) { // best of three: the machine is shared
      MdrOptions o;
      o.rtol = 1e-3;
      const auto t0 = std::chrono::steady_clock::now();
      const RunResult r = run_mdr(nc.c, o);
      const auto t1 = std::chrono::steady_clock::now();
      best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
      ASSERT_TRUE(all_finite(r.series));
    }
    ms.push_back(best);
  }
  ASSERT_GE(ms.size(), 10u);
  std::sort(ms.begin(), ms.end());
  const double median = ms[ms.size() / 2];
  std::printf("[ info ] mdr rtol 1e-3, %zu three-segment histories: median %.2f ms, max %.2f ms\n",
              ms.size(), median, ms.back());
#if defined(NDEBUG) && !defined(__SANITIZE_ADDRESS__)
  EXPECT_LE(median, 5.0);
#endif
}

} // namespace
} // namespace mdrmap
