// The spectrum solver (src/core/solvers/spectrum.hpp) and its brute-force
// counterpart (spectrum_baseline.hpp): the Kelvin history set against the
// continuum solution, the limits of a spectrum, a set of spectrum histories
// against a refined run, the error estimate, the fixed-step method's order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "cases/case_set.hpp"
#include "cases/spectrum_case_set.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/dispatch.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_baseline.hpp"
#include "core/solvers/spectrum_law.hpp"
#include "test_case.hpp"

namespace mdrmap {
namespace {

using Segs = std::vector<std::pair<double, double>>;

/// A history (velocities relative to v0 = zeta0 a1 / t_ref, durations in t_ref)
/// on the material r, d/R = 1e-3.
Case spectrum_case(const Rheology& r, double zeta0, const Segs& segs, long samples = 21) {
  Case c = testing::history_case(zeta0, segs, samples); // Kelvin, tau = 1 = t_ref
  c.rheology = r;
  return c;
}

/// Equal-weight terms `per_decade` per decade from 10^lo to 10^hi.
Rheology prony(double G, double tau, double lo, double hi, double per_decade, double Gk) {
  std::vector<std::pair<double, double>> t;
  for (double e = lo; e <= hi + 1e-9; e += 1.0 / per_decade)
    t.emplace_back(Gk, std::pow(10.0, e));
  return material(G, tau, t);
}

struct SpectrumNamedCase {
  std::string name;
  Case c;
};

std::vector<SpectrumNamedCase> spectrum_case_set() {
  const Rheology sls = material(1.0, 0.0, {{3.0, 1.0}});
  const Rheology six = prony(1.0, 0.0, -3.0, 2.0, 1.0, 1.0);
  const Rheology wide = prony(1.0, 0.0, -6.0, 6.0, 0.5, 1.0); // 12 decades
  const Rheology stiff = material(1.0, 0.0, {{1e4, 1.0}});    // G0/G = 1e4
  const Rheology dash = material(1.0, 0.3, {{2.0, 1.0}, {2.0, 0.05}});
  return {
      {"SLS drop and rise", spectrum_case(sls, 1.0, {{0.1, 1.5}, {1.0, 1.5}})},
      {"SLS slide-hold-slide", spectrum_case(sls, 1.0, {{0.0, 3.0}, {1.0, 2.0}})},
      {"SLS long hold, re-touch", spectrum_case(sls, 0.3, {{0.0, 100.0}, {0.3, 2.0}})},
      {"SLS rise inside a transient", spectrum_case(sls, 1.0, {{0.1, 0.5}, {0.2, 2.0}})},
      {"six terms drop", spectrum_case(six, 1.0, {{0.1, 2.0}, {0.01, 2.0}})},
      {"six terms step up", spectrum_case(six, 0.1, {{10.0, 1.0}})},
      {"six terms slide-hold-slide", spectrum_case(six, 1.0, {{0.0, 10.0}, {1.0, 2.0}})},
      {"12 decades drop-rise", spectrum_case(wide, 1.0, {{0.01, 1.0}, {1.0, 1.0}})},
      {"G0/G = 1e4 drop-hold", spectrum_case(stiff, 1.0, {{0.1, 1.0}, {0.0, 1.0}})},
      {"dashpot and two terms", spectrum_case(dash, 1.0, {{0.3, 1.0}, {0.03, 2.0}, {1.0, 1.0}})},
  };
}

double max_error(const RunResult& r, const RunResult& ref, const Case& c) {
  return case_error(r.series, ref.series, c).max();
}

/// A fixed-resolution run without the companion; the edge located to 1e-3 rtol a1.
RunResult fixed(const Case& c, double cells, double rtol = 1e-9) {
  SpectrumOptions o;
  o.cells_per_a1 = cells;
  o.rtol = rtol;
  o.estimate_error = false;
  return run_spectrum(CheckedCase(c), o);
}

// y' = f(y) by classical RK4 with n steps: the plain check of the exact updates.
template <class F> std::vector<double> rk4(F f, std::vector<double> y, double T, int n) {
  const double h = T / n;
  auto axpy = [](const std::vector<double>& a, double s, const std::vector<double>& b) {
    std::vector<double> r(a);
    for (std::size_t i = 0; i < r.size(); ++i)
      r[i] += s * b[i];
    return r;
  };
  double t = 0.0;
  for (int i = 0; i < n; ++i, t += h) {
    const auto k1 = f(t, y), k2 = f(t + h / 2, axpy(y, h / 2, k1));
    const auto k3 = f(t + h / 2, axpy(y, h / 2, k2)), k4 = f(t + h, axpy(y, h, k3));
    for (std::size_t j = 0; j < y.size(); ++j)
      y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
  }
  return y;
}

// A free element's depression and modal state after t from modal state z.
std::pair<double, std::vector<double>> free_after(const spectrum::Law& law, std::vector<double> z,
                                                  double t) {
  spectrum::StepCoef c;
  law.coef(t, c, spectrum::Part::Free);
  law.free_step(z.data(), c);
  return std::make_pair(law.free_u(z.data()), z);
}

// The free element: exact modal propagation (the claim: W D M symmetric
// negative definite, so real decaying modes) against RK4 of the element law
// itself, with and without the dashpot; and the contact update under a
// quadratic depression against RK4 of tau_k q' = u - q.
TEST(SpectrumLaw, FreeAndContactUpdatesMatchAFineIntegration) {
  for (const Rheology& r :
       {prony(1.0, 0.0, -1.0, 1.0, 1.0, 2.0), material(1.0, 0.4, {{3.0, 0.2}, {1.0, 2.0}}),
        prony(0.1, 0.0, -3.0, 2.0, 1.0, 1.0)}) {
    const spectrum::Law law(r);
    const std::size_t N = r.branches.size(), m = law.free_dim();
    for (double rate : law.rates())
      EXPECT_GT(rate, 0.0);
    // free: state (u, q) with a dashpot, q without; the ODE written out
    std::vector<double> q0(N);
    for (std::size_t k = 0; k < N; ++k)
      q0[k] = 0.3 + 0.2 * static_cast<double>(k);
    const double G0 = r.G0(), h0 = 0.9;
    auto u_of = [&](const std::vector<double>& y) {
      if (r.tau > 0.0) return y[0];
      double s = 0.0;
      for (std::size_t k = 0; k < N; ++k)
        s += r.branches[k].G * y[k];
      return s / G0;
    };
    auto f = [&](double, const std::vector<double>& y) {
      const std::size_t o = r.tau > 0.0 ? 1 : 0;
      const double u = u_of(y);
      std::vector<double> d(y.size());
      if (o) { // G tau u' = -G0 u + sum G_k q_k
        double s = -G0 * u;
        for (std::size_t k = 0; k < N; ++k)
          s += r.branches[k].G * y[k + 1];
        d[0] = s / (r.G * r.tau);
      }
      for (std::size_t k = 0; k < N; ++k)
        d[k + o] = (u - y[k + o]) / r.branches[k].tau;
      return d;
    };
    std::vector<double> y0 = q0;
    if (r.tau > 0.0) y0.insert(y0.begin(), h0);
    const double T = 0.7;
    const auto want = rk4(f, y0, T, 20000);
    std::vector<double> z(m), got(N);
    law.to_modal(h0, q0.data(), z.data());
    spectrum::StepCoef c;
    law.coef(T, c);
    law.free_step(z.data(), c);
    law.from_modal(z.data(), got.data());
    const std::size_t o = r.tau > 0.0 ? 1 : 0;
    if (o) {
      EXPECT_NEAR(law.free_u(z.data()), want[0], 1e-12);
    }
    for (std::size_t k = 0; k < N; ++k)
      EXPECT_NEAR(got[k], want[k + o], 1e-12) << "free branch " << k;
    // contact: u = 0.5 + 0.3 t - 0.2 t^2 prescribed
    auto g = [&](double t, const std::vector<double>& y) {
      std::vector<double> d(N);
      for (std::size_t k = 0; k < N; ++k)
        d[k] = (0.5 + 0.3 * t - 0.2 * t * t - y[k]) / r.branches[k].tau;
      return d;
    };
    const auto wantc = rk4(g, q0, T, 20000);
    std::vector<double> qc = q0;
    law.contact_step(qc.data(), 0.5, 0.3, -0.2, c);
    for (std::size_t k = 0; k < N; ++k)
      EXPECT_NEAR(qc[k], wantc[k], 1e-12) << "contact branch " << k;
  }
}

// The rates that steer the switch location (Row::locate's Newton): the
// contact force's rate along a quadratic path and the free depression's rate,
// against central differences of the exact updates over +-1e-5.
TEST(SpectrumLaw, ForceAndFreeRatesAreTheUpdatesDerivatives) {
  for (const Rheology& r :
       {material(1.0, 0.4, {{3.0, 0.2}, {1.0, 2.0}}), prony(0.1, 0.0, -3.0, 2.0, 1.0, 1.0)}) {
    const spectrum::Law law(r);
    const std::size_t N = law.branches(), m = law.free_dim();
    const double h0 = 0.9, h1 = -0.7, h2 = 0.3, t = 0.05, e = 1e-5;
    std::vector<double> q0(N), z0(m);
    for (std::size_t k = 0; k < N; ++k)
      q0[k] = 0.3 + 0.2 * static_cast<double>(k);
    for (std::size_t i = 0; i < m; ++i)
      z0[i] = 0.5 - 0.1 * static_cast<double>(i);
    auto force = [&](double s) { // the contact force after s along u = h0 + h1 s + h2 s^2
      std::vector<double> q = q0;
      spectrum::StepCoef c;
      law.coef(s, c, spectrum::Part::Contact);
      law.contact_step(q.data(), h0, h1, h2, c);
      return std::make_pair(law.pressure(h0 + (h1 + h2 * s) * s, h1 + 2.0 * h2 * s, q.data()), q);
    };
    auto free_u = [&](double s) { return free_after(law, z0, s); };
    const std::vector<double> q = force(t).second;
    const double dp = (force(t + e).first - force(t - e).first) / (2.0 * e);
    const double u = h0 + (h1 + h2 * t) * t, du = h1 + 2.0 * h2 * t;
    EXPECT_NEAR(law.pressure_rate(u, du, 2.0 * h2, q.data()), dp, 1e-7 * (std::abs(dp) + 1.0));
    const std::vector<double> z = free_u(t).second;
    const double duf = (free_u(t + e).first - free_u(t - e).first) / (2.0 * e);
    EXPECT_NEAR(law.free_rate(z.data()), duf, 1e-7 * (std::abs(duf) + 1.0));
  }
}

// Law::free_span (Row::free_until lets a free point at rest cross a span of
// steps in one where its gap stays below zero by it): the state after T is
// free_step's over T, bit for bit, and the floor bounds u over all of [0, T],
// also where the modes' terms have both signs and u dips below its ends.
TEST(SpectrumLaw, FreeSpanFloorsTheDepressionOverTheSpan) {
  const spectrum::Law law(material(1.0, 0.0, {{3.0, 0.01}, {2.0, 0.3}, {1.0, 5.0}}));
  const std::size_t m = law.free_dim();
  const double T = 2.0;
  std::vector<double> z0(m);
  for (std::size_t i = 0; i < m; ++i) // mixed signs: u falls, then recovers
    z0[i] = (i % 2 == 0 ? 1.0 : -1.0) * (1.0 + static_cast<double>(i));
  auto u_at = [&](double t) { return free_after(law, z0, t); };
  std::vector<double> z(m);
  const double floor = law.free_span(z0.data(), z.data(), T);
  EXPECT_EQ(z, u_at(T).second);
  double lowest = u_at(0.0).first;
  for (int i = 1; i <= 2000; ++i)
    lowest = std::min(lowest, u_at(T * i / 2000.0).first);
  EXPECT_LT(lowest, std::min(u_at(0.0).first, u_at(T).first)) << "u dips inside (the case tests)";
  EXPECT_LE(floor, lowest);
}

// A branch far faster than the step: the exact update is its quasi-static
// limit, q = u - tau_k u' + tau_k^2 u'' (no instability, no overshoot).
TEST(SpectrumLaw, StiffBranchesAreStableAndExact) {
  const spectrum::Law law(material(1.0, 0.0, {{5.0, 1e-9}}));
  spectrum::StepCoef c;
  law.coef(1.0, c);
  double q = 7.0;
  law.contact_step(&q, 0.5, 0.3, -0.2, c);
  const double t = 1.0, u = 0.5 + 0.3 * t - 0.2 * t * t, du = 0.3 - 0.4 * t;
  EXPECT_NEAR(q, u - 1e-9 * du + 1e-18 * -0.4, 1e-15);
  double z[1];
  law.to_modal(0.0, &q, z);
  law.free_step(z, c);
  EXPECT_EQ(law.free_u(z), 0.0); // relaxed: exp(-1e9 G/G0) underflows
}

// Done-criterion 1: N = 0 through the spectrum solver agrees with the
// continuum solution on the Kelvin history set at rtol 1e-3, its estimate at
// least a third of its true error.
TEST(SpectrumKelvin, AgreesWithExactOnTheHistorySet) {
  for (const auto& nc : history_case_set(21)) {
    const RunResult ref = run_exact(CheckedCase(nc.c), 1e-12);
    SpectrumOptions o;
    o.rtol = 1e-3;
    const RunResult r = run_spectrum(CheckedCase(nc.c), o);
    const double err = max_error(r, ref, nc.c);
    EXPECT_LE(err, o.rtol) << nc.name;
    EXPECT_GE(r.info.error_estimate, err / 3.0) << nc.name;
    EXPECT_EQ(r.info.solver, "row");
  }
}

// Done-criterion 2: a spectrum whose branches never relax over the case is
// the elastic foundation of the glassy modulus G0; one whose branches relax
// within far less than a cell's time is the Kelvin foundation of G and tau
// (or the elastic one of G). Relative 1e-8 against the continuum solution.
TEST(SpectrumLimits, SlowAndFastBranchesGiveTheElasticAndKelvinFoundations) {
  const Segs segs = {{0.1, 1.0}, {0.0, 0.5}, {1.0, 1.0}};
  for (double tau : {0.0, 1.0}) {
    Case kelvin = testing::history_case(1.0, segs, 11);
    const double T = kelvin.history.end(), a1 = kelvin.a1(), v0 = kelvin.history.v0;
    // slow: tau = 0, three terms 1e12 times the case's duration
    if (tau == 0.0) {
      Case slow = kelvin;
      slow.rheology = material(1.0, 0.0, {{2.0, 1e12 * T}, {0.5, 3e12 * T}, {1.5, 1e13 * T}});
      Case glassy = kelvin;
      glassy.rheology = material(slow.rheology.G0(), 0.0, {});
      const double err = max_error(fixed(slow, 64), run_exact(CheckedCase(glassy), 1e-14), glassy);
      EXPECT_LE(err, 1e-8) << "tau_k >> t: elastic with G0";
    }
    // fast: every tau_k 1e-12 of the time an element takes to cross a cell
    const double cell_time = a1 / 64.0 / v0;
    Case fast = kelvin;
    fast.rheology = material(1.0, tau, {{2.0, 1e-12 * cell_time}, {4.0, 3e-13 * cell_time}});
    Case base = kelvin;
    base.rheology = material(1.0, tau, {});
    const double err = max_error(fixed(fast, 64), run_exact(CheckedCase(base), 1e-14), base);
    EXPECT_LE(err, 1e-8) << "tau_k << dx/w: Kelvin with G, tau = " << tau;
  }
}

// Seams: at a reslide after a hold, fresh material enters at the glassy
// modulus beside material that relaxed through the hold, so p(x) has a kink
// at the material point that sat at the leading edge. The forces are
// integrated on either side of it: the reslide's F_N converges past second
// order and whatever the grid's phase. SLS, G0/G = 10, the work-precision
// scene (tenfold step up, hold of 100 tau, reslide at v0): at a/dx 64 and
// three element phases within 1e-6 of a/dx 512 (integrated across the kink:
// 3.5e-5 to 1.1e-4), at a/dx 16 within 3e-4 (3.6e-4 to 2.3e-3).
TEST(SpectrumSeams, TheReslideConvergesPastTheKinkAtAnyPhase) {
  Case c = spectrum_case(material(1.0, 0.0, {{9.0, 1.0}}), 1.0,
                         {{10.0, 2.0}, {0.0, 100.0}, {1.0, 4.0}}, 61);
  auto run = [&](double cells, double phase) {
    SpectrumOptions o;
    o.cells_per_a1 = cells;
    o.phase = phase;
    o.rtol = 1e-9;
    o.estimate_error = false;
    return run_spectrum(CheckedCase(c), o).series;
  };
  const Series ref = run(512, 0.5);
  for (const auto& [cells, tol] : {std::pair{16.0, 3e-4}, std::pair{64.0, 1e-6}})
    for (double phase : {0.5, 0.881966, 0.263932}) {
      const Series s = run(cells, phase);
      double err = 0.0;
      for (std::size_t k = 0; k < s.size(); ++k)
        if (s.segment[k] == 2) err = std::max(err, std::abs(s.FN[k] / ref.FN[k] - 1.0));
      EXPECT_LE(err, tol) << "a/dx " << cells << ", phase " << phase;
    }
}

/// The reference of a spectrum case: a fine fixed-resolution run.
RunResult reference(const Case& c) {
  return fixed(c, 3200, 1e-7);
}

// Done-criterion 3: on the spectrum histories the adaptive solver meets rtol
// 1e-3 and 1e-4 against a refined run, and its estimate is at least a third
// of its true error.
TEST(SpectrumCaseSet, MeetsRtolWithAnHonestEstimate) {
  for (const auto& nc : spectrum_case_set()) {
    const RunResult ref = reference(nc.c);
    for (double rtol : {1e-3, 1e-4}) {
      SpectrumOptions o;
      o.rtol = rtol;
      const RunResult r = run_spectrum(CheckedCase(nc.c), o);
      const double err = max_error(r, ref, nc.c);
      EXPECT_LE(err, rtol) << nc.name << " at rtol " << rtol;
      EXPECT_GE(r.info.error_estimate, err / 3.0) << nc.name << " at rtol " << rtol;
      EXPECT_LE(r.info.error_estimate, rtol) << nc.name;
    }
  }
}

// The fixed-step brute-force method converges to the same answer at first
// order: an independent check that the exact updates, the located switches
// and the replayed edge solve the model (and not just agree with themselves).
TEST(SpectrumCaseSet, BruteForceConvergesToTheReferenceAtFirstOrder) {
  for (const auto& nc : spectrum_case_set()) {
    const RunResult ref = fixed(nc.c, 1600, 1e-7);
    std::vector<double> cells = {50, 100, 200}, err;
    for (double n : cells) {
      SpectrumBaselineOptions b;
      b.cells_per_a1 = n;
      b.estimate_error = false;
      const RunResult r = run_spectrum_baseline(CheckedCase(nc.c), b);
      EXPECT_EQ(r.info.solver, "baseline");
      err.push_back(max_error(r, ref, nc.c));
    }
    const double order = testing::observed_order(cells, err);
    EXPECT_GT(order, 0.8) << nc.name << ": observed order " << order << ", errors " << err[0] << " "
                          << err[1] << " " << err[2];
    EXPECT_LT(order, 1.3) << nc.name << ": observed order " << order;
    EXPECT_LT(err[2], 2e-2) << nc.name;
  }
}

// The window: memory does not grow with the travel (2 a1/dx, 5 nodes past it
// whose gaps predict an edge near a1, and a ring margin of 8).
TEST(SpectrumWindow, MemoryIsIndependentOfTravel) {
  const Rheology six = prony(1.0, 0.0, -3.0, 2.0, 1.0, 1.0);
  const RunResult a = fixed(spectrum_case(six, 1.0, {{0.1, 2.0}}), 64, 1e-6);
  const RunResult b = fixed(spectrum_case(six, 1.0, {{0.1, 2.0}, {1.0, 200.0}}), 64, 1e-6);
  EXPECT_EQ(a.info.elements, b.info.elements);
  EXPECT_LE(a.info.elements, 2 * 64 + 13);
}

// Done-criterion 4: inputs the solvers do not take (load control they take:
// test_spectrum_load.cpp).
TEST(SpectrumInputs, BadOptionsAreRefusedNamingTheOption) {
  Case c = spectrum_case(material(1.0, 0.0, {{3.0, 1.0}}), 1.0, {{0.1, 1.0}});
  auto option_of = [](auto&& f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return e.option();
    }
    return std::string("(none)");
  };
  SpectrumOptions o;
  o.sub_travel = 0.0;
  EXPECT_EQ(option_of([&] { run_spectrum(CheckedCase(c), o); }), "sub-travel");
  o = SpectrumOptions{};
  o.cells_per_a1 = 1e9;
  EXPECT_EQ(option_of([&] { run_spectrum(CheckedCase(c), o); }), "cells-per-a1");
  o = SpectrumOptions{};
  o.rtol = 0.5;
  EXPECT_EQ(option_of([&] { run_spectrum(CheckedCase(c), o); }), "rtol");
}

// Work is charged: a small budget stops the case with CaseAbandoned naming
// the solver, a stop request with Interrupted.
TEST(SpectrumBudget, StopsAtItsWorkBudgetAndOnAStopRequest) {
  const Case c = spectrum_case(prony(1.0, 0.0, -3.0, 2.0, 1.0, 1.0), 1.0, {{0.1, 2.0}});
  RunControl small;
  small.max_work = 1e3;
  SpectrumOptions o;
  o.control = &small;
  try {
    run_spectrum(CheckedCase(c), o);
    ADD_FAILURE() << "no CaseAbandoned";
  } catch (const CaseAbandoned& e) {
    EXPECT_EQ(std::string(e.what()).rfind("row", 0), 0U) << e.what();
  }
  SpectrumBaselineOptions b;
  b.control = &small;
  EXPECT_THROW(run_spectrum_baseline(CheckedCase(c), b), CaseAbandoned);
  volatile std::sig_atomic_t flag = 1;
  RunControl stop;
  stop.stop = &flag;
  o.control = &stop;
  EXPECT_THROW(run_spectrum(CheckedCase(c), o), Interrupted);
}

// Not a test (no timed unit tests): the figures of the report.
//   ./tests/test_core --gtest_also_run_disabled_tests --gtest_filter='DISABLED_SpectrumBench*'
TEST(DISABLED_SpectrumBench, MillisecondsPerCase) {
  const Segs three = {{0.1, 1.0}, {0.0, 2.0}, {1.0, 1.0}};
  const std::vector<SpectrumNamedCase> cases = {
      {"six terms, three segments",
       spectrum_case(prony(1.0, 0.0, -3.0, 2.0, 1.0, 1.0), 1.0, three)},
      {"SLS, three segments", spectrum_case(material(1.0, 0.0, {{3.0, 1.0}}), 1.0, three)}};
  auto ms_of = [](auto&& f) { // median CPU time of 7 runs (the machine is shared)
    std::vector<double> t;
    for (int i = 0; i < 7; ++i) {
      const std::clock_t t0 = std::clock();
      f();
      t.push_back(1e3 * static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC);
    }
    std::sort(t.begin(), t.end());
    return t[3];
  };
  for (const auto& nc : cases) {
    const RunResult ref = reference(nc.c);
    SpectrumOptions o;
    o.rtol = 1e-3;
    RunResult r;
    const double ms = ms_of([&] { r = run_spectrum(CheckedCase(nc.c), o); });
    const double err = max_error(r, ref, nc.c);
    // the brute-force method at 400 cells, and the adaptive one at that accuracy
    SpectrumBaselineOptions b;
    b.cells_per_a1 = 400;
    b.estimate_error = false;
    RunResult br;
    const double bms = ms_of([&] { br = run_spectrum_baseline(CheckedCase(nc.c), b); });
    const double berr = max_error(br, ref, nc.c);
    SpectrumOptions same;
    same.rtol = std::min(0.1, berr);
    RunResult sr;
    const double sms = ms_of([&] { sr = run_spectrum(CheckedCase(nc.c), same); });
    std::printf(
        "%s: spectrum rtol 1e-3: %.2f ms CPU (median of 7), error %.2e, estimate %.2e, a1/dx "
        "%g\n  baseline a1/dx 400: %.1f ms, error %.2e; spectrum at rtol %.2e: %.2f ms, "
        "error %.2e: %.0f times cheaper\n  baseline extrapolated to error %.2e (error ~ "
        "dx, cost ~ dx^-2): %.0f ms, %.0f times the spectrum solver\n",
        nc.name.c_str(), ms, err, r.info.error_estimate, r.info.cells_per_a1, bms, berr, same.rtol,
        sms, max_error(sr, ref, nc.c), bms / sms, err, bms * (berr / err) * (berr / err),
        bms * (berr / err) * (berr / err) / ms);
  }
}

/// The material of `c` shifted by aT, and the unshifted material's twin run at
/// aT times every velocity for 1/aT of every duration (DESIGN: the response of
/// the shifted material to w(t) is the unshifted one's to aT w(t / aT), at t / aT).
std::pair<Case, Case> shifted_and_twin(const Case& c, double aT) {
  Case shifted = c, twin = c;
  shifted.rheology.aT = aT;
  twin.history.v0 *= aT;
  for (Segment& seg : twin.history.segments) {
    seg.w *= aT;
    seg.T /= aT;
  }
  return {shifted, twin};
}

// Time-temperature superposition holds for the transients too: for a shift
// of 1e-6 and 1e4 (1e-2 and 1e2 under load, where a segment of 1e6 relaxation
// times at slow sliding goes past the solver's work budget), every sample of
// a spectrum history (at fixed depth and under load) and of a Kelvin one
// (exact) equals its twin's within rtol.
TEST(SpectrumShift, TheShiftedMaterialIsTheTwinAtScaledVelocities) {
  const double rtol = 1e-3;
  const auto set = spectrum_case_set();
  std::vector<Case> cases = {set[1].c, set[6].c, testing::history_case(1.0, {{0.1, 2.0}}, 21)};
  Case load = set[0].c;
  load.loading.F0 =
      16.0 / 3.0 * load.rheology.G * std::pow(load.a1(), 3) / load.indenter.as<Parabola>().R;
  load.loading.d = 0.0;
  cases.push_back(load);
  for (const Case& c : cases)
    for (const double aT :
         c.loading.by_force() ? std::vector<double>{1e-2, 1e2} : std::vector<double>{1e-6, 1e4}) {
      SCOPED_TRACE(std::to_string(c.rheology.branches.size()) + " terms, load " +
                   std::to_string(c.loading.by_force()) + ", aT " + std::to_string(aT));
      const auto [shifted, twin] = shifted_and_twin(c, aT);
      const RunResult a = run_case(CheckedCase(shifted), SolverKind::Auto, rtol);
      const RunResult b = run_case(CheckedCase(twin), SolverKind::Auto, rtol);
      ASSERT_EQ(a.series.size(), b.series.size());
      for (std::size_t k = 0; k < a.series.size(); ++k)
        EXPECT_NEAR(a.series.t[k], b.series.t[k] * aT, 1e-12 * std::abs(a.series.t[k]));
      EXPECT_LE(max_error(a, b, c), rtol);
    }
}

// A segment that has reached its stationary state costs no further steps
// (core/solvers/stationary_watch.hpp): a step down and a step up, each
// followed by 200 a1 of sliding with 201 samples, take at most half the
// steps of the same run stepping on (measured 0.35 and 0.26), within rtol of
// a fine run, the estimate at least a third of the error.
TEST(SpectrumLongSegments, AStationarySegmentTakesNoFurtherSteps) {
  for (const Rheology& r : {material(1.0, 0.0, {{3.0, 1.0}}), prony(1.0, 0.0, -3, 2, 1, 1.0)}) {
    const Case c = spectrum_case(r, 1.0, {{0.1, 2000.0}, {1.0, 200.0}}, 201);
    SpectrumOptions o;
    o.rtol = 1e-3;
    const RunResult run = run_spectrum(CheckedCase(c), o), ref = reference(c);
    o.keep_stationary = false;
    const RunResult stepping = run_spectrum(CheckedCase(c), o);
    const double err = max_error(run, ref, c);
    std::printf("N = %zu: %ld steps (stepping on: %ld); error %.2e, estimate %.2e\n",
                r.branches.size(), run.info.steps, stepping.info.steps, err,
                run.info.error_estimate);
    EXPECT_LE(2 * run.info.steps, stepping.info.steps);
    EXPECT_LE(err, o.rtol);
    EXPECT_GE(run.info.error_estimate, err / 3.0);
  }
}

} // namespace
} // namespace mdrmap
