// The element row (row, core/solvers/spectrum.hpp) at N = 0 branches on
// velocity histories of the Kelvin foundation: against the continuum solution
// on the history set, the fixed-step brute-force row (baseline) converging to
// the continuum, the state across a velocity change, the contact growing from
// a tangency after a detachment, and hard histories. These were the tests of
// the retired Kelvin row (mdr) and of the Kelvin baseline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "cases/case_set.hpp"
#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_baseline.hpp"
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

/// The row at a fixed resolution, without the error estimate, its trailing
/// edge located to 1e-14 a1.
Series row_at(const Case& c, double cells, double phase = 0.5) {
  SpectrumOptions o;
  o.cells_per_a1 = cells;
  o.rtol = 1e-12;
  o.phase = phase;
  o.estimate_error = false;
  return run_spectrum(CheckedCase(c), o).series;
}

// Done-criterion of the history issue, for the row at N = 0: on every
// history of the set, at rtol 1e-2, 1e-3, 1e-4, it is within rtol of the
// continuum solution with an honest error estimate (at least a third of the
// true error), or abandons the case (its error contract); at rtol 1e-2 and
// 1e-3 it solves every history.
TEST(RowKelvinHistorySet, WithinRtolWithAnHonestEstimate) {
  for (double rtol : {1e-2, 1e-3, 1e-4}) {
    int abandoned = 0;
    for (const auto& nc : history_case_set()) {
      SCOPED_TRACE(nc.name);
      const auto r = testing::row_or_abandoned(nc.c, rtol, nc.name, abandoned);
      if (!r) continue;
      ASSERT_TRUE(testing::all_finite(r->series));
      const double err =
          case_error(r->series, run_exact(CheckedCase(nc.c), 1e-13).series, nc.c).max();
      EXPECT_LE(err, rtol) << "rtol " << rtol << " cells " << r->info.cells_per_a1;
      EXPECT_GE(r->info.error_estimate, err / 3.0) << "rtol " << rtol;
    }
    std::printf("[ info ] rtol %.0e: %d of %zu histories abandoned\n", rtol, abandoned,
                history_case_set().size());
    if (rtol >= 1e-3) {
      EXPECT_EQ(abandoned, 0) << "rtol " << rtol;
    }
  }
}

// A change of velocity takes no time: just after a drop or the start of a
// hold the contact is the one just before; just after a rise it is cut back
// to the new stationary edge a2(w) if it reached beyond.
TEST(RowKelvinHistoryChange, TrailingEdgeAcrossEachChange) {
  for (const auto& nc : history_case_set()) {
    SCOPED_TRACE(nc.name);
    const Case& c = nc.c;
    const Series s = row_at(c, 32.0, 0.2137);
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
// moves like sqrt(t) at first. Checked from 1e-8 tau on (the edge has moved
// 1e-4 a1 by then), the row at rtol 1e-6 (its contract bounds the error of a2
// by rtol a1), against that scalar equation solved here in long double.
TEST(RowKelvinHistoryTangency, ContactGrowsFromTheTangencyAfterAHoldStarts) {
  Case c = history(1.0, {{0.0, 1.0}}, 41);
  c.sampling.spacing = Spacing::Log;
  c.sampling.decades = 8.0;
  const long double R = c.indenter.as<Parabola>().R, a1 = c.a1(), tau = c.rheology.tau;
  const long double L = c.history.v0 * c.rheology.tau;
  const long double a2 = analytic::a2_stationary(c, c.history.v0), ha2 = (a1 - a2) * (a1 + a2) / R;
  SpectrumOptions o;
  o.rtol = 1e-6;
  const Series s = run_spectrum(CheckedCase(c), o).series;
  double worst = 0.0;
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
    EXPECT_NEAR(s.a2[i] / c.a1(), edge / c.a1(), o.rtol) << "t/tau " << s.t[i];
    worst = std::max(worst, std::abs(s.a2[i] - edge) / c.a1());
  }
  std::printf("[ info ] edge after a hold starts, t/tau in [1e-8, 1], rtol 1e-6: off by %.1e a1\n",
              worst);
}

// The brute-force method (every element, a fixed step, contact decided at
// step ends, raw sums) converges to the continuum solution at first order on
// histories too: an independent check of the continuum construction.
TEST(RowKelvinHistoryBruteForce, BaselineConvergesAtFirstOrder) {
  const std::vector<double> cells = {200, 400, 800};
  for (const char* name : {"two drops zeta=1", "slide-hold-slide hold=1 tau",
                           "drop-rise-drop zeta=1", "hold inside a transient"}) {
    SCOPED_TRACE(name);
    Case c = from_set(name);
    c.sampling.samples = 21;
    const RunResult ref = run_exact(CheckedCase(c), 1e-13);
    std::vector<double> err;
    for (double n : cells) {
      SpectrumBaselineOptions b;
      b.cells_per_a1 = n;
      b.estimate_error = false;
      const RunResult r = run_spectrum_baseline(CheckedCase(c), b);
      ASSERT_TRUE(testing::all_finite(r.series));
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
// [-a1, a1], and within rtol of the continuum solution, or the history
// abandoned (the error contract; counted and printed).
TEST(RowKelvinHistoryHardCases, NoNaNNoBlowUp) {
  std::vector<std::pair<double, double>> alternating;
  for (int k = 0; k < 20; ++k)
    alternating.push_back({k % 3 == 2 ? 0.0 : (k % 2 == 0 ? 1e-8 : 1.0), 0.05 + 0.1 * (k % 4)});
  const std::vector<std::vector<std::pair<double, double>>> patterns = {
      {{1e-8, 1e-6}, {0.0, 1e6}, {1.0, 2.0}, {0.0, 1e-6}, {1e-4, 3.0}},
      {{1e-8, 0.5}, {1.0, 1e-3}, {0.0, 0.2}, {1e4, 0.01}, {1e-4, 2.0}},
      alternating,
  };
  int abandoned = 0;
  for (double z : {1e-4, 1.0, 1e6})
    for (double dr : {1e-12, 0.3})
      for (std::size_t p = 0; p < patterns.size(); ++p) {
        const Case c = history(z, patterns[p], 21, dr);
        SCOPED_TRACE("zeta0 " + std::to_string(z) + " d/R " + std::to_string(dr) + " pattern " +
                     std::to_string(p));
        const std::string what = "zeta0 " + std::to_string(z) + " d/R " + std::to_string(dr) +
                                 " pattern " + std::to_string(p);
        const auto r = testing::row_or_abandoned(c, 1e-3, what, abandoned);
        if (!r) continue;
        ASSERT_TRUE(testing::all_finite(r->series));
        for (std::size_t k = 0; k < r->series.size(); ++k) {
          EXPECT_GT(r->series.FN[k], 0.0);
          EXPECT_GE(r->series.a2[k], -c.a1());
          EXPECT_LE(r->series.a2[k], c.a1() * (1 + 1e-15));
        }
        EXPECT_LE(case_error(r->series, run_exact(CheckedCase(c), 1e-13).series, c).max(), 1e-3);
      }
  std::printf("[ info ] %d of 18 hard histories abandoned at rtol 1e-3\n", abandoned);
  Case c = history(1.0, {{0.1, 2.0}, {0.0, 1.0}, {10.0, 2.0}, {0.0, 1e6}}, 11);
  c.rheology.tau = 0.0; // elastic: valid, Hertz whatever the history
  testing::expect_row_hertz_throughout(c);
}

} // namespace
} // namespace mdrmap
