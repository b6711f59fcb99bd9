// Stationary states of a cone or power law with a relaxation spectrum at the
// ends of the velocity range (issue 32): the friction integral int p (-g')
// cancels over the two faces, and was negative at v tau_k / a1 = 1e16 (the
// glassy limit keeps mu v constant); a slow branch's layers took a minute a
// state. Checked against the physics' limits and the parabola's closed form.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <variant>
#include <vector>

#include "core/metrics/profile_branches.hpp"
#include "core/metrics/profile_stationary.hpp"
#include "core/metrics/spectrum_stationary.hpp"
#include "core/model/case.hpp"

namespace {

using mdrmap::Branch;
using mdrmap::Case;
using mdrmap::Profile;
using mdrmap::State;

const std::vector<Branch> kTwoBranches = {{1.0, 1.0}, {10.0, 0.01}}; // issue 32's spectrum

Case profile_case(Profile p, double beta_or_A, double n, double d) {
  Case c;
  c.indenter.profile = p;
  (p == Profile::of<mdrmap::Cone>() ? c.indenter.as<mdrmap::Cone>().beta
                                    : c.indenter.as<mdrmap::Power>().A) = beta_or_A;
  c.indenter.as<mdrmap::Power>().n = p == Profile::of<mdrmap::Power>() ? n : 0.0;
  c.loading.d = d;
  c.rheology.G = 1.0;
  c.rheology.tau = 0.0;
  c.rheology.branches = kTwoBranches;
  c.history.v0 = 1.0;
  c.history.segments = {{1.0, 1.0}};
  return c;
}

double rel(double a, double b) {
  return std::fabs(a - b) / std::fmax(std::fabs(a), std::fabs(b));
}

/// The glassy limit of g = c |x|^n at leading edge a1: each branch a spring
/// of G_k less (1/lambda_k) of its stress, F_N -> 8 G0 c n/(n+1) a1^(n+1),
/// F_x -> 4 sum_k G_k / (w tau_k) int h^2, int h^2 = 2 c^2 a1^(2n+1)
/// (1 - 2/(n+1) + 1/(2n+1)): mu w -> the ratio of the two without w.
double glassy_mu_v(const Case& c) {
  const auto img = std::get<mdrmap::PowerImage>(c.indenter.image()); // (a cone or a power law)
  const double n = img.exponent(), k = img.coefficient(), a1 = c.a1();
  double G0 = c.rheology.G, rate = 0.0;
  for (const Branch& b : c.rheology.branches) {
    G0 += b.G;
    rate += b.G / b.tau;
  }
  const double h2 =
      2.0 * k * k * std::pow(a1, 2.0 * n + 1.0) * (1.0 - 2.0 / (n + 1.0) + 1.0 / (2.0 * n + 1.0));
  const double FN = 8.0 * G0 * k * n / (n + 1.0) * std::pow(a1, n + 1.0);
  return 4.0 * rate * h2 / FN;
}

// Issue 32: mu v of the cone of 10 degrees went 0.556, 0.556, 0.553, -0.250,
// -50.05 over v = 1e8 .. 1e18; n = 1.5 to -71.9; a cone of 89.99999999999
// degrees gave mu = 0.0024 at v = 100 (0.0056) and -0.0024 at v = 1e4.
TEST(ProfileStationaryLimits, GlassyLimitKeepsMuTimesVelocity) {
  const struct {
    const char* label;
    Case c;
    std::vector<double> v;
  } rows[] = {
      {"cone 10 deg",
       profile_case(Profile::of<mdrmap::Cone>(), 10.0, 0.0, 0.01),
       {1e8, 1e12, 1e14, 1e16, 1e18}},
      {"power n = 1.5",
       profile_case(Profile::of<mdrmap::Power>(), 0.05, 1.5, 0.01),
       {1e8, 1e12, 1e16, 1e18}},
      {"power n = 3",
       profile_case(Profile::of<mdrmap::Power>(), 0.5, 3.0, 0.01),
       {1e8, 1e12, 1e16, 1e18}},
      {"cone 89.99999999999 deg",
       profile_case(Profile::of<mdrmap::Cone>(), 89.99999999999, 0.0, 0.01),
       {100.0, 1e4, 1e10}},
  };
  for (const auto& r : rows) {
    const double limit = glassy_mu_v(r.c), a1 = r.c.a1();
    for (double v : r.v) {
      SCOPED_TRACE(std::string(r.label) + " v=" + std::to_string(v));
      const State st = mdrmap::profile_stationary(r.c, v);
      // corrections of order a1 / lambda of the fastest-relaxing branch
      const double order = a1 / (v * 0.01);
      EXPECT_GT(st.mu, 0.0);
      EXPECT_LT(rel(st.mu * v, limit), 2.0 * order + 1e-12);
    }
  }
}

// v -> 0: each branch relaxes within lambda_k = v tau_k << a1 and acts as a
// dashpot of G_k tau_k: the Kelvin contact of tau = sum G_k tau_k / G, to
// order lambda / a1. Issue 32's slow states (65 s and more than 120 s).
TEST(ProfileStationaryLimits, RelaxedLimitIsTheKelvinContactAndFast) {
  const struct {
    const char* label;
    Case c;
    std::vector<double> v;
  } rows[] = {
      {"cone 0.01 deg", profile_case(Profile::of<mdrmap::Cone>(), 0.01, 0.0, 0.01), {1e-6}},
      {"cone 1e-6 deg",
       profile_case(Profile::of<mdrmap::Cone>(), 1e-6, 0.0, 0.01),
       {1e-6, 1e-2, 1.0}},
      {"power n = 1.5", profile_case(Profile::of<mdrmap::Power>(), 0.05, 1.5, 0.01), {1e-6, 1e-4}},
      {"power n = 3", profile_case(Profile::of<mdrmap::Power>(), 0.5, 3.0, 0.01), {1e-6, 1e-4}},
  };
  const auto start = std::chrono::steady_clock::now();
  for (const auto& r : rows) {
    Case kelvin = r.c;
    kelvin.rheology.branches.clear();
    for (const Branch& b : r.c.rheology.branches)
      kelvin.rheology.tau += b.G * b.tau / r.c.rheology.G;
    for (double v : r.v) {
      SCOPED_TRACE(std::string(r.label) + " v=" + std::to_string(v));
      const State st = mdrmap::profile_stationary(r.c, v),
                  k = mdrmap::profile_stationary(kelvin, v);
      const double order = v * 1.0 / r.c.a1(); // the slowest branch's lambda / a1
      EXPECT_LT(rel(st.FN, k.FN), 10.0 * order);
      EXPECT_LT(rel(st.Fx, k.Fx), 10.0 * order);
      EXPECT_LT(rel(r.c.a1() - st.a2, r.c.a1() - k.a2), 10.0 * order);
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0); // 0.1 s now; the first row alone took 65 s
}

// The general path at n = 2 (a power law with A = 1/(2R)) against the
// parabola's closed form with the same spectrum, across the whole range: at
// v = 1e16 and beyond the direct friction integral had lost every digit.
TEST(ProfileStationaryLimits, PowerTwoIsTheParabolaAtEveryVelocity) {
  Case par = profile_case(Profile::of<mdrmap::Power>(), 0.0, 0.0, 0.05);
  par.indenter = mdrmap::Indenter{};
  par.indenter.as<mdrmap::Parabola>().R = 2.0;
  Case pow2 = profile_case(Profile::of<mdrmap::Power>(), 1.0 / (2.0 * 2.0), 2.0, 0.05);
  for (double v : {1e-6, 1e-3, 1.0, 1e3, 1e8, 1e12, 1e16, 1e18}) {
    SCOPED_TRACE("v=" + std::to_string(v));
    const State p = mdrmap::spectrum_stationary(par, v);
    const State g = mdrmap::profile_detail::general_stationary(pow2, v);
    EXPECT_LT(rel(g.FN, p.FN), 1e-12);
    EXPECT_LT(rel(g.Fx, p.Fx), 1e-10);
    EXPECT_LT(std::fabs(g.a2 - p.a2), 1e-12 * p.a1);
  }
}

// The branches' quadrature has a budget: past it one clear error, never an
// unbounded loop.
TEST(ProfileStationaryLimits, QuadratureStopsAtItsBudget) {
  mdrmap::profile::BranchContact k;
  k.img = mdrmap::PowerImage{0.1, 1.5};
  k.a1 = 1.0;
  mdrmap::profile::Budget budget;
  budget.max_evaluations = 1000;
  k.budget = &budget;
  try {
    mdrmap::profile::branch_friction(k, 1e-6, 0.9, 0.1);
    ADD_FAILURE() << "no error past the budget";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 1000"), std::string::npos) << e.what();
  }
}

} // namespace
