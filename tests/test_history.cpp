// The continuum solution for velocity histories at fixed depth: each claim of
// its construction (docs/design.md, "Histories at fixed depth") as its own
// test, checked against closed forms, the independent discrete solver at a
// fine resolution, and quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "cases/case_set.hpp"
#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/metrics/events.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_baseline.hpp"
#include "test_case.hpp"

namespace mdrmap {
namespace {

/// d = 1e-3 R, tau = 1, v0 from zeta0; segments as (w / v0, T / tau).
Case history(double zeta0, const std::vector<std::pair<double, double>>& segs, long samples = 41) {
  return testing::history_case(zeta0, segs, samples);
}

/// The element row at a fixed fine resolution: an independent solver of the
/// same model.
Series fine_row(const Case& c, double cells = 1600) {
  SpectrumOptions o;
  o.cells_per_a1 = cells;
  o.estimate_error = false;
  return run_spectrum(CheckedCase(c), o).series;
}

TEST(HistoryClaims, RiseOutOfStationarySlidingIsStationaryAtOnce) {
  // the contact reached a2(v0) > a2(w): everything beyond a2(w) lets go and
  // every state after the rise is the stationary state at w
  for (double z : {1e-2, 1.0, 1e2}) {
    const Case c = history(z, {{10.0, 3.0}});
    const State ss = analytic::stationary(c, c.history.segments[0].w);
    const RunResult r = run_exact(CheckedCase(c));
    for (std::size_t i = 0; i < r.series.size(); ++i) {
      EXPECT_NEAR(r.series.mu[i], ss.mu, 1e-13 * ss.mu) << "zeta0 " << z;
      EXPECT_NEAR(r.series.a2[i], ss.a2, 1e-13 * c.a1());
    }
  }
}

TEST(HistoryClaims, ReslideAfterAHoldShowsNoPeak) {
  // during a hold the contact grows beyond a2(v0); restarting at v0 cuts it
  // back to a2(v0) at once: stationary forces, for every hold time
  for (double hold : {1e-4, 0.1, 1.0, 10.0, 1e4}) {
    const Case c = history(1.0, {{0.0, hold}, {1.0, 3.0}});
    const State ss = analytic::stationary(c, c.history.v0);
    const RunResult r = run_exact(CheckedCase(c));
    for (std::size_t i = 0; i < r.series.size(); ++i)
      if (r.series.segment[i] == 1) {
        EXPECT_NEAR(r.series.mu[i], ss.mu, 1e-13 * ss.mu) << hold;
      }
  }
}

TEST(HistoryClaims, RiseDuringATransientIsNotStationary) {
  // hold 0.1 tau, then restart at 0.2 v0: the contact had not reached
  // a2(0.2 v0), so mu starts above its stationary value and relaxes to it
  // over about tau (the independent discrete solver agrees)
  const Case c = history(1.0, {{0.0, 0.1}, {0.2, 6.0}}, 121);
  const RunResult r = run_exact(CheckedCase(c));
  const double mu_ss = analytic::stationary(c, c.history.segments[1].w).mu;
  const std::size_t first = 121;
  const double excess = r.series.mu[first] / mu_ss - 1.0;
  EXPECT_GT(excess, 0.05);
  EXPECT_LT(excess, 0.3);
  EXPECT_NEAR(r.series.mu.back(), mu_ss, 1e-9 * mu_ss);
  // the excess falls to 1/e of itself on the relaxation time scale (0.14 tau
  // here: the material next to the edge relaxes as exp(-t/tau) while the
  // edge moves through it)
  const auto ev = event_metrics(c, r.series);
  const double t_1e = ev[1].d_c / c.history.segments[1].w;
  EXPECT_GT(t_1e, 0.05);
  EXPECT_LT(t_1e, 1.0);
  SpectrumOptions o; // the element row agrees within its rtol
  o.rtol = 1e-6;
  EXPECT_LT(case_error(run_spectrum(CheckedCase(c), o).series, r.series, c).max(), o.rtol);
}

TEST(HistoryClaims, HoldGrowsTheContactAndRelaxesFriction) {
  // during a hold nothing moves: the cap is a1, contact elements carry 4 G h
  // (F_x > 0 from the asymmetric contact), free material decays in place and
  // touches again, so the edge only grows and F_x only falls
  const Case c = history(1.0, {{0.1, 0.5}, {0.0, 20.0}}, 81);
  const RunResult r = run_exact(CheckedCase(c));
  double prev_a2 = -1.0, prev_fx = std::numeric_limits<double>::infinity();
  for (std::size_t i = 81; i < r.series.size(); ++i) {
    EXPECT_GE(r.series.a2[i], prev_a2);
    EXPECT_LE(r.series.Fx[i], prev_fx * (1.0 + 1e-14));
    EXPECT_GT(r.series.Fx[i], 0.0);
    EXPECT_LT(r.series.a2[i], c.a1());
    prev_a2 = r.series.a2[i];
    prev_fx = r.series.Fx[i];
    // F_N = integral of 4 G h over [-a1, e], by quadrature
    const double e = r.series.a2[i], a1 = c.a1(), R = c.indenter.as<Parabola>().R;
    const double FN = 4.0 * (a1 * a1 * (e + a1) - (e * e * e + a1 * a1 * a1) / 3.0) / R;
    EXPECT_NEAR(r.series.FN[i], FN, 1e-12 * FN);
  }
  // after 20 tau the free material is within e^-20 of relaxed: e -> a1
  EXPECT_GT(r.series.a2.back(), c.a1() * (1.0 - 1e-6));
}

TEST(HistoryClaims, ContactStaysOneIntervalOnEveryHistory) {
  // the free material behind the edge never touches the indenter (gap < 0 at
  // 64 points per tail piece): the contact set is [-a1, e], one interval
  for (const auto& nc : history_case_set(9)) {
    const ExactSolution ex(nc.c);
    for (std::size_t k = 0; k < nc.c.history.size(); ++k)
      for (long j = 0; j < nc.c.sampling.samples; ++j) {
        const double off = nc.c.sampling.offset(j, nc.c.history.segments[k].T);
        EXPECT_LT(ex.max_gap_beyond_edge(k, off, 64), 1e-12) << nc.name << " segment " << k;
      }
  }
}

TEST(HistoryClaims, SuccessiveDropsLeaveOneExponentialPiecePerEpoch) {
  // after drops the free tail is a sequence of exponential pieces, one per
  // epoch whose edge reached the cap; a rise adds one piece that let go at
  // once (Quad); material carried past a1 is dropped
  const Case c = history(3.0, {{0.3, 0.5}, {0.1, 0.5}, {0.01, 0.5}, {0.5, 0.5}, {0.1, 0.5}});
  const ExactSolution ex(c);
  using K = TailPiece::Kind;
  auto kinds = [&](std::size_t k) {
    std::vector<K> ks;
    for (const auto& p : ex.segment_start(k).tail)
      ks.push_back(p.kind);
    return ks;
  };
  EXPECT_EQ(kinds(0), (std::vector<K>{K::Exp}));                  // tail of v0
  EXPECT_EQ(kinds(1), (std::vector<K>{K::Exp, K::Exp}));          // + epoch at 0.3 v0
  EXPECT_EQ(kinds(2), (std::vector<K>{K::Exp, K::Exp, K::Exp}));  // + epoch at 0.1 v0
  EXPECT_EQ(kinds(3), (std::vector<K>{K::Quad, K::Exp, K::Exp})); // the rise lets go
  // decay lengths are those of the epochs: v0 tau, 0.3 v0 tau, 0.1 v0 tau
  const auto& t2 = ex.segment_start(2).tail;
  EXPECT_DOUBLE_EQ(t2[0].lam, c.history.segments[1].w * c.rheology.tau);
  EXPECT_DOUBLE_EQ(t2[1].lam, c.history.segments[0].w * c.rheology.tau);
  EXPECT_DOUBLE_EQ(t2[2].lam, c.history.v0 * c.rheology.tau);
  // the brute-force fixed-step method converges to it at first order
  const RunResult ref = run_exact(CheckedCase(c));
  double err[2];
  for (int i = 0; i < 2; ++i) {
    SpectrumBaselineOptions o;
    o.cells_per_a1 = 200.0 * (i + 1);
    o.estimate_error = false;
    err[i] = case_error(run_spectrum_baseline(CheckedCase(c), o).series, ref.series, c).max();
  }
  const double order = std::log2(err[0] / err[1]);
  EXPECT_GT(order, 0.8);
  EXPECT_LT(order, 1.2);
  EXPECT_LT(err[1], 4e-3);
}

TEST(HistoryClaims, TailPiecesAreContiguousAndBounded) {
  // on every history: the tail of v0, then at most one new piece per change
  // (a Quad) and one per segment (its epoch at the cap); contiguous, outward,
  // starting inside a1
  for (const auto& nc : history_case_set(5)) {
    const ExactSolution ex(nc.c);
    for (std::size_t k = 0; k < nc.c.history.size(); ++k) {
      const auto& tail = ex.segment_start(k).tail;
      EXPECT_LE(tail.size(), 2 * (k + 1)) << nc.name;
      for (std::size_t i = 0; i < tail.size(); ++i) {
        EXPECT_LT(tail[i].lo, tail[i].hi) << nc.name;
        EXPECT_LT(tail[i].lo, nc.c.a1()) << nc.name;
        if (i > 0) {
          EXPECT_EQ(tail[i].lo, tail[i - 1].hi) << nc.name;
        }
      }
    }
  }
}

TEST(HistoryClaims, AgreesWithTheDiscreteSolverOnTheHistorySet) {
  // the row resolves every history of the set independently (element row, exact
  // time integration); at a1/dx = 1600 it agrees with the continuum solution
  int checked = 0;
  for (const auto& nc : history_case_set(21)) {
    const RunResult ex = run_exact(CheckedCase(nc.c));
    const double err = case_error(fine_row(nc.c), ex.series, nc.c, 1e-12).max();
    EXPECT_LT(err, 1e-4) << nc.name;
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

TEST(HistoryReduction, OneSegmentHistoryIsTheStep) {
  // the seed's closed forms: the state just after the step (corrected
  // (15)/(16)) and the stationary state at v1 long after it
  for (const auto& nc : hard_case_set()) {
    const Case& c = nc.c;
    const double v = c.history.v0, w = c.history.segments[0].w;
    const ExactSolution ex(c);
    const State j = ex.at(0, 0.0), jump = analytic::jump(c, v, w);
    EXPECT_NEAR(j.FN, jump.FN, 1e-13 * jump.FN) << nc.name;
    EXPECT_NEAR(j.Fx, jump.Fx, 1e-12 * std::max(jump.Fx, 1e-300)) << nc.name;
    if (c.rheology.tau > 0.0) {
      const State late = ex.at(0, 200.0 * c.rheology.tau), ss = analytic::stationary(c, w);
      EXPECT_NEAR(late.FN, ss.FN, 1e-12 * ss.FN) << nc.name;
    }
  }
}

TEST(HistorySampling, StatesDoNotDependOnTheSampling) {
  // each sample is an independent evaluation: the same instant sampled in two
  // runs with different sample counts gives the same state, bit for bit
  Case a = history(1.0, {{0.1, 1.0}, {0.0, 2.0}, {0.5, 2.0}}, 11);
  Case b = a;
  b.sampling.samples = 21; // every second sample of b is a sample of a
  const RunResult ra = run_exact(CheckedCase(a)), rb = run_exact(CheckedCase(b));
  for (std::size_t k = 0; k < 3; ++k)
    for (long j = 0; j < 11; ++j) {
      const std::size_t ia = k * 11 + static_cast<std::size_t>(j);
      const std::size_t ib = k * 21 + static_cast<std::size_t>(2 * j);
      EXPECT_EQ(ra.series.mu[ia], rb.series.mu[ib]);
      EXPECT_EQ(ra.series.t[ia], rb.series.t[ib]);
    }
}

TEST(HistorySampling, LogSpacingResolvesLongHoldsAndShortReslides) {
  Case c = history(1.0, {{0.0, 1e4}, {0.2, 2.0}}, 9);
  c.sampling.spacing = Spacing::Log;
  c.sampling.decades = 4.0;
  const RunResult r = run_exact(CheckedCase(c));
  EXPECT_EQ(r.series.t[0], 0.0);
  EXPECT_DOUBLE_EQ(r.series.t[1], 1.0); // 1e4 * 1e-4
  EXPECT_DOUBLE_EQ(r.series.t[8], 1e4); // end of the hold
  EXPECT_DOUBLE_EQ(r.series.t[10], 1e4 + 2e-4);
  for (std::size_t i = 1; i < r.series.size(); ++i)
    EXPECT_GE(r.series.t[i], r.series.t[i - 1]);
}

TEST(HistorySimilarity, ScaledVariablesCollapse) {
  // mu/sqrt(d/R), F_N/(G a1 d), a2/a1 depend on zeta0, the ratios w_k/v0 and
  // T_k/tau only: rescale length, time and stress by unrelated factors
  const Case c = history(0.7, {{0.1, 0.4}, {0.0, 1.0}, {0.3, 1.5}, {3.0, 1.0}}, 17);
  const RunResult r = run_exact(CheckedCase(c));
  Case s = c;
  const double L = 37.0, T = 1e-3, S = 4e6;
  s.loading.d *= L;
  s.indenter.as<Parabola>().R *= L;
  s.rheology.tau *= T;
  s.rheology.G *= S;
  s.history.v0 *= L / T;
  for (auto& seg : s.history.segments) {
    seg.w *= L / T;
    seg.T *= T;
  }
  const RunResult q = run_exact(CheckedCase(s));
  for (std::size_t i = 0; i < r.series.size(); ++i) {
    EXPECT_NEAR(q.series.mu[i], r.series.mu[i], 1e-12 * r.series.mu[i]);
    EXPECT_NEAR(q.series.FN[i] / (S * L * L), r.series.FN[i], 1e-12 * r.series.FN[i]);
    EXPECT_NEAR(q.series.a2[i] / L, r.series.a2[i], 1e-12 * c.a1());
  }
}

TEST(HistoryHardCases, NoNaNAndStatesInRange) {
  for (const auto& nc : history_case_set(31)) {
    const RunResult r = run_exact(CheckedCase(nc.c));
    const double a1 = nc.c.a1();
    for (std::size_t i = 0; i < r.series.size(); ++i) {
      ASSERT_TRUE(std::isfinite(r.series.mu[i])) << nc.name << " sample " << i;
      EXPECT_GT(r.series.FN[i], 0.0) << nc.name;
      EXPECT_GE(r.series.Fx[i], 0.0) << nc.name;
      EXPECT_GT(r.series.a2[i], 0.0) << nc.name;
      EXPECT_LE(r.series.a2[i], a1 * (1.0 + 1e-15)) << nc.name;
    }
    EXPECT_LT(r.info.error_estimate, 1e-10) << nc.name;
  }
}

TEST(HistoryEvents, RateAndStateParametersOfStepsFromStationarySliding) {
  // a rise out of stationary sliding is stationary at once: mu(t_k+) =
  // mu_ss(w), so the direct effect equals a - b and b = 0; a drop gives a
  // direct effect of the other sign than the later evolution
  const Case c = history(1.0, {{10.0, 5.0}, {1.0, 8.0}}, 201);
  const RunResult r = run_exact(CheckedCase(c));
  const auto ev = event_metrics(c, r.series);
  ASSERT_EQ(ev.size(), 2U);
  EXPECT_NEAR(ev[0].a, ev[0].a_minus_b, 1e-12 * std::abs(ev[0].a));
  EXPECT_NEAR(ev[0].b, 0.0, 1e-12 * std::abs(ev[0].a));
  EXPECT_TRUE(std::isnan(ev[0].d_c)); // nothing to relax
  // the drop back to v0: the contact set is still the one of 10 v0, so mu
  // falls part of the way at once, then evolves on down to mu_ss(v0)
  EXPECT_LT(ev[1].mu_after, ev[1].mu_before);
  EXPECT_GT(ev[1].mu_after, ev[1].ss_after.mu);
  // the evolution goes on in the direction of the direct effect and ends
  // farther than the jump: a > 0 and a - b > a, so b < 0 (at fixed depth the
  // model is velocity-strengthening with no opposing state effect)
  EXPECT_GT(ev[1].a, 0.0);
  EXPECT_GT(ev[1].a_minus_b, ev[1].a);
  EXPECT_LT(ev[1].b, 0.0);
  // (the largest mu is the state just after the jump; the peak on the side
  // of the drop, mu_min, is where the evolution ends)
  EXPECT_NEAR(ev[1].mu_after, ev[1].mu_max, 0.0);
  EXPECT_EQ(ev[1].mu_peak, ev[1].mu_min);
  EXPECT_LE(ev[1].mu_min, ev[1].end.mu);
  EXPECT_TRUE(std::isfinite(ev[1].d_c));
  EXPECT_GT(ev[1].d_c, 0.0);
  EXPECT_NEAR(ev[1].end.mu, ev[1].ss_after.mu, 1e-6 * ev[1].ss_after.mu);
  EXPECT_NEAR(ev[1].mu_before, ev[0].end.mu, 0.0);
}

TEST(HistoryEvents, UndefinedWhereALogOfZeroAppears) {
  const Case c = history(1.0, {{0.0, 1.0}, {1.0, 2.0}}, 11);
  const auto ev = event_metrics(c, run_exact(CheckedCase(c)).series);
  EXPECT_TRUE(std::isnan(ev[0].a)); // into a hold
  EXPECT_TRUE(std::isnan(ev[0].b));
  EXPECT_TRUE(std::isnan(ev[0].d_c));
  EXPECT_TRUE(std::isnan(ev[1].a_minus_b)); // out of a hold
}

} // namespace
} // namespace mdrmap
