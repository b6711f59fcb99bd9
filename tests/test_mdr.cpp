// The discrete MDR simulator against the continuum solution, the paper's
// formulas and the brute-force fixed-step method.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "cases/case_set.hpp"
#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/baseline.hpp"
#include "core/solvers/dispatch.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/mdr.hpp"
#include "test_case.hpp"

namespace mdrmap {
namespace {

using testing::v1_of;

// The case with `samples` linear samples over its window (the one-step cases
// here keep the default window: 6 tau; 6 a1 / min(v, v1) for tau = 0).
Case sampled(Case c, long samples) {
  c.sampling.samples = samples;
  return c;
}

double zeta0(const Case& c) {
  return zeta(c, c.history.v0);
}
double zeta1(const Case& c) {
  return zeta(c, v1_of(c));
}

bool all_finite(const Series& x) {
  for (std::size_t k = 0; k < x.size(); ++k)
    if (!std::isfinite(x.FN[k]) || !std::isfinite(x.Fx[k]) || !std::isfinite(x.mu[k]) ||
        !std::isfinite(x.a2[k]))
      return false;
  return std::isfinite(x.pre.FN) && std::isfinite(x.pre.Fx) && std::isfinite(x.pre.a2);
}

// One step v -> v1 = ratio v with zeta = v tau / a1 (R = 1, tau = 1, G = 1),
// default window, 201 samples.
Case scene(double zeta, double ratio, double d_over_r = 1e-3) {
  const double R = 1.0, d = d_over_r, tau = 1.0;
  const double v = zeta * std::sqrt(R * d) / tau;
  return step_case(d, R, tau, v, ratio * v);
}

TEST(MdrCaseSet, SetSpansTheHardRanges) {
  const auto set = hard_case_set();
  ASSERT_GE(set.size(), 30u);
  double zmin = 1e300, zmax = 0, qmax = 0, drmin = 1e300, drmax = 0, mu_drop = 1.0;
  bool tau0 = false, v1zero = false;
  for (const auto& nc : set) {
    const Case& c = nc.c;
    ASSERT_EQ(c.history.size(), 1u) << nc.name;
    ASSERT_EQ(c.sampling.samples, 201) << nc.name; // the default protocol
    const double dr = c.loading.d / c.indenter.as<Parabola>().R;
    if (c.rheology.tau == 0)
      tau0 = true;
    else
      zmin = std::min(zmin, zeta0(c)), zmax = std::max(zmax, zeta0(c));
    if (v1_of(c) == 0) v1zero = true;
    qmax = std::max(qmax, v1_of(c) / c.history.v0);
    drmin = std::min(drmin, dr), drmax = std::max(drmax, dr);
    const auto ex = run_exact(c);
    if (ex.series.pre.mu > 0) mu_drop = std::min(mu_drop, ex.series.mu.back() / ex.series.pre.mu);
  }
  EXPECT_LE(zmin, 1e-4);
  EXPECT_GE(zmax, 1e8);
  EXPECT_GE(qmax, 1e2);
  EXPECT_LE(drmin, 1e-12);
  EXPECT_GE(drmax, 0.3);
  EXPECT_TRUE(tau0);
  EXPECT_TRUE(v1zero);
  EXPECT_LE(mu_drop, 1e-6) << "some scene must take mu below 1e-6 of its value before the step";
}

// Done-criterion of the simulator issue: at defaults (auto, rtol 1e-4) within
// 1e-4, and the discrete simulator at rtol 1e-3 within 1e-3, of the continuum
// solution on every scene of the set; the error estimate is honest (never
// below the true error by more than a factor 3).
TEST(MdrCaseSet, MeetsTolerancesOnTheHardSet) {
  for (const auto& nc : hard_case_set()) {
    SCOPED_TRACE(nc.name);
    const Case& c = nc.c;
    const auto ref = run_exact(c, 1e-12);
    const auto def = run_case(c, SolverKind::Auto, 1e-4);
    EXPECT_LE(case_error(def.series, ref.series, c).max(), 1e-4);
    for (double rtol : {1e-2, 1e-3, 1e-4}) {
      MdrOptions o;
      o.rtol = rtol;
      const auto r = run_mdr(c, o);
      ASSERT_TRUE(all_finite(r.series));
      const double err = case_error(r.series, ref.series, c).max();
      EXPECT_LE(err, rtol) << "rtol " << rtol << " cells " << r.info.cells_per_a1;
      EXPECT_GE(3.0 * r.info.error_estimate, err - 1e-13) << "rtol " << rtol;
    }
  }
}

// Independent of the sub-grid model, the discrete sums must converge to the
// continuum solution at the order the quadrature promises: the paper's raw
// sums at first order, the high-order quadrature with a linearly
// interpolated gap at second order. The log-linear edge (default) is exact
// for the step protocol, so its error must stay at rounding level.
TEST(MdrConvergence, ObservedOrderInDx) {
  const std::vector<double> cells = {50, 100, 200, 400, 800, 1600};
  const Case scenes[] = {scene(1.0, 0.01), scene(1e4, 0.0), scene(0.5, 0.4, 0.3),
                         scene(3.0, 1e-3, 1e-6)};
  for (const Case& c : scenes) {
    const auto ref = run_exact(c, 1e-12);
    for (MdrSubgrid mode : {MdrSubgrid::None, MdrSubgrid::Linear, MdrSubgrid::Piecewise}) {
      std::vector<double> err;
      for (double n : cells) {
        MdrOptions o;
        o.cells_per_a1 = n;
        o.subgrid = mode;
        o.estimate_error = false;
        err.push_back(case_error(run_mdr(c, o).series, ref.series, c).max());
      }
      std::printf("zeta=%-6g v1/v=%-6g ", zeta0(c), v1_of(c) / c.history.v0);
      testing::expect_readout_order(mode, cells, err, 1e-10);
    }
  }
}

// The stationary state before the step: discrete sums against eqs. (7),
// (9), (10) (corrected). The high-order quadrature integrates the cubic
// contact integrands exactly, so it agrees to rounding; the paper's raw sums
// converge to it at first order.
TEST(MdrStationary, DiscreteRunMatchesEquations7To10) {
  for (double z : {1e-3, 0.1, 1.0, 10.0, 1e5}) {
    const Case c = sampled(scene(z, 0.5), 3);
    const State an = analytic::stationary(c, c.history.v0);
    MdrOptions o;
    o.cells_per_a1 = 64;
    o.estimate_error = false;
    const State pre = run_mdr(c, o).series.pre;
    EXPECT_NEAR(pre.FN / an.FN, 1.0, 1e-12) << z;
    EXPECT_NEAR(pre.Fx / an.Fx, 1.0, 1e-9) << z;
    EXPECT_NEAR(pre.a2 / analytic::a1(c), an.a2 / analytic::a1(c), 1e-14) << z;
    o.subgrid = MdrSubgrid::None;
    o.phase = 0.2137; // not aligned with the cells: the generic first-order case
    std::vector<double> ns, es;
    for (double n : {100.0, 200.0, 400.0, 800.0, 1600.0}) {
      o.cells_per_a1 = n;
      const State raw = run_mdr(c, o).series.pre;
      const double e = std::abs(raw.FN / an.FN - 1.0);
      EXPECT_LT(e, 4.0 / n) << "first-order raw sum, z=" << z;
      ns.push_back(n), es.push_back(e);
    }
    EXPECT_LT(es.back(), es.front() / 4.0);
  }
}

// Starting from an undeformed foundation and sliding 2 a1 must reproduce
// the stationary start exactly (every element then entered fresh).
TEST(MdrSpinup, ReproducesTheStationaryStart) {
  for (const Case& c0 : {scene(1.0, 0.01), scene(1e3, 0.0), scene(0.01, 2.0), scene(1e-4, 0.5)}) {
    const Case c = sampled(c0, 41);
    MdrOptions o;
    o.cells_per_a1 = 100;
    o.estimate_error = false;
    const auto direct = run_mdr(c, o);
    o.spinup = true;
    const auto spun = run_mdr(c, o);
    // Same state up to rounding: the spun-up tail is built by stepping
    // (products of exp(-dt/tau)), the direct one from the closed form.
    EXPECT_NEAR(spun.series.pre.FN / direct.series.pre.FN, 1.0, 1e-12);
    EXPECT_LE(case_error(spun.series, direct.series, c).max(), 1e-10);
  }
}

// The state reported at t = 0+ is the jump of eqs. (15)/(16) for a drop, the
// stationary state at v1 for a rise.
TEST(MdrStep, StateJustAfterTheStep) {
  for (const Case& c0 : {scene(1.0, 0.1), scene(50.0, 0.0), scene(1.0, 3.0), scene(1e-2, 1e-3)}) {
    const Case c = sampled(c0, 5);
    MdrOptions o;
    o.cells_per_a1 = 40;
    o.estimate_error = false;
    const auto r = run_mdr(c, o);
    const State j = analytic::jump(c, c.history.v0, v1_of(c));
    EXPECT_NEAR(r.series.FN[0] / j.FN, 1.0, 1e-12);
    EXPECT_NEAR(r.series.Fx[0] / j.Fx, 1.0, 1e-9);
    EXPECT_NEAR(r.series.a2[0] / analytic::a1(c), j.a2 / analytic::a1(c), 1e-13);
  }
}

// Memory is the moving window only: the same for a travel of 6 tau v1 =
// 6e8 a1 as for 6e-6 a1, and for v1/v = 1e-8.
TEST(MdrMemory, IndependentOfTravelAndVelocityRatio) {
  MdrOptions o;
  o.cells_per_a1 = 200;
  o.estimate_error = false;
  long elements = -1;
  for (const Case& c : {scene(1e8, 1.0), scene(1e-6, 1.0), scene(1e3, 1e-8), scene(1.0, 100.0)}) {
    const auto r = run_mdr(c, o);
    ASSERT_TRUE(all_finite(r.series));
    if (elements < 0) elements = r.info.elements;
    EXPECT_EQ(r.info.elements, elements);
    EXPECT_LE(r.info.elements, 2 * 200 + 5);
  }
}

// Similarity: (mu / sqrt(d/R), F_N/(G a1 d), F_x/(G d^2), a2/a1) depend on
// (zeta, zeta1, t/tau) only. The discrete run at the same a1/dx and phase is
// a function of the same variables.
TEST(MdrSimilarity, DimensionlessResultsDependOnZetaOnly) {
  const Case base = scene(2.0, 0.05);
  MdrOptions o;
  o.cells_per_a1 = 60;
  o.estimate_error = false;
  const auto r0 = run_mdr(base, o);
  const double d0 = base.loading.d, R0 = base.indenter.as<Parabola>().R, G0 = base.rheology.G;
  const double tau0 = base.rheology.tau, a10 = analytic::a1(base);
  const double scales[][4] = {{1e-4, 3.0, 7.0, 1e3}, {1e3, 1e-2, 1e6, 1e-3}, {0.3, 20.0, 2.0, 5.0}};
  for (const auto& k : scales) {
    // d scaled by k0, R by k1, G by k2, tau by k3 (the window stays 6 tau),
    // velocities keep zeta and zeta1
    const double d = d0 * k[0], R = R0 * k[1], G = G0 * k[2], tau = tau0 * k[3];
    Case c = step_case(d, R, tau, 1.0, 1.0, G);
    const double a1 = analytic::a1(c);
    testing::set_velocities(c, zeta0(base) * a1 / tau, zeta1(base) * a1 / tau);
    const auto r = run_mdr(c, o);
    for (std::size_t i = 0; i < r.series.size(); ++i) {
      EXPECT_NEAR(r.series.t[i] / tau, r0.series.t[i] / tau0, 1e-12);
      EXPECT_NEAR(r.series.FN[i] / (G * a1 * d), r0.series.FN[i] / (G0 * a10 * d0),
                  1e-10 * r0.series.FN[0] / (G0 * a10 * d0));
      EXPECT_NEAR(r.series.Fx[i] / (G * d * d), r0.series.Fx[i] / (G0 * d0 * d0),
                  1e-10 * r0.series.Fx[0] / (G0 * d0 * d0));
      EXPECT_NEAR(r.series.mu[i] / std::sqrt(d / R), r0.series.mu[i] / std::sqrt(d0 / R0), 1e-10);
      EXPECT_NEAR(r.series.a2[i] / a1, r0.series.a2[i] / a10, 1e-12);
    }
  }
}

// Hard cases: no NaN, no blow-up, F_N > 0 and a2 in [0, a1].
TEST(MdrHardCases, NoNaNNoBlowUp) {
  for (double z : {1e-4, 1e-3, 1e-1, 1.0, 1e2, 1e4, 1e6, 1e8}) {
    for (double q : {0.0, 1e-8, 1e-4, 0.3, 1.0, 2.0, 1e2}) {
      for (double dr : {1e-12, 1e-3, 0.3}) {
        const Case c = sampled(scene(z, q, dr), 51);
        MdrOptions o;
        o.rtol = 1e-3;
        const auto r = run_mdr(c, o);
        ASSERT_TRUE(all_finite(r.series)) << z << " " << q << " " << dr;
        for (std::size_t k = 0; k < r.series.size(); ++k) {
          EXPECT_GT(r.series.FN[k], 0.0);
          EXPECT_GE(r.series.a2[k], 0.0);
          EXPECT_LE(r.series.a2[k], analytic::a1(c) * (1 + 1e-15));
        }
      }
    }
  }
  const Case base = scene(1.0, 0.5);
  for (double v1 : {0.0, 0.01, 10.0}) {
    // elastic limit (tau = 0): valid, Hertz; window 6 a1 / min(v, v1)
    const Case c = step_case(base.loading.d, base.indenter.as<Parabola>().R, 0.0, base.history.v0,
                             v1, base.rheology.G, 0.0, 11);
    const auto r = run_mdr(c, MdrOptions{});
    ASSERT_TRUE(all_finite(r.series));
    const double hertz = 16.0 / 3.0 * c.rheology.G * std::sqrt(c.indenter.as<Parabola>().R) *
                         std::pow(c.loading.d, 1.5);
    for (std::size_t k = 0; k < r.series.size(); ++k) {
      EXPECT_NEAR(r.series.FN[k] / hertz, 1.0, 1e-12);
      EXPECT_NEAR(r.series.mu[k], 0.0, 1e-12);
    }
  }
}

// The continuum solver against a brute-force fine discrete run (the paper's
// fixed-step method, written independently: every element, fixed dt, contact
// decided at step ends, raw sums). That run converges at first order, so its
// own accuracy at N cells is about |b(N/4) - b(N)| / 3; the continuum
// solution must agree with b(N) to within that, and b must approach it.
TEST(MdrBruteForce, ContinuumSolutionWithinTheDiscreteRunsOwnAccuracy) {
  const Case scenes[] = {scene(0.5, 0.1), scene(2.0, 0.0), scene(1.0, 3.0), scene(0.2, 0.5, 0.1),
                         scene(1.0, 1e-3, 1e-6)};
  for (const Case& c0 : scenes) {
    const Case c = sampled(c0, 61);
    const auto ex = run_exact(c, 1e-12);
    // the fine brute-force run needs more than the default work budget
    RunControl budget_coarse, budget_fine;
    budget_coarse.max_work = budget_fine.max_work = 1e11;
    BaselineOptions b;
    b.cells_per_a1 = 400;
    b.control = &budget_coarse;
    const auto coarse = run_baseline(c, b);
    b.cells_per_a1 = 1600;
    b.control = &budget_fine;
    const auto fine = run_baseline(c, b);
    const double own = case_error(coarse.series, fine.series, c).max();
    const double e_fine = case_error(fine.series, ex.series, c).max();
    const double e_coarse = case_error(coarse.series, ex.series, c).max();
    std::printf("zeta=%-5g v1/v=%-6g brute force: err(400)=%.2e err(1600)=%.2e |b400-b1600|=%.2e\n",
                zeta0(c), v1_of(c) / c.history.v0, e_coarse, e_fine, own);
    // first order: err(1600) ~ |b400 - b1600| / 3; allow the phase noise of
    // raw sums a factor 3 on top of that
    EXPECT_LE(e_fine, own);
    EXPECT_LT(e_fine, e_coarse);
    EXPECT_LT(e_fine, 2e-3);
  }
}

} // namespace
} // namespace mdrmap
