// Independent checks of load control (docs/design.md, "Load control"): the depth root of
// stationary sliding under load, the friction curve mu(zeta0) against its
// closed-form similarity parametrization (one maximum, at v tau = sqrt(3) a1),
// its limits and their approach, indentation creep at rest against the closed
// form of the one-dimensional creep equation (checked by quadrature), and the
// element row (row) at N = 0 under load: the stationary states reached after
// a change, tau -> 0 giving Hertz at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/toms748_solve.hpp>

#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/solvers/spectrum.hpp"

namespace mdrmap {
namespace {

constexpr double kR = 2.0, kA0 = 0.05; // a0 / R = 0.025

// The stationary depth under load by a root of the fixed-depth stationary
// force (an independent route to core/metrics/load_stationary.hpp).
namespace load_check {

/// Normal force of stationary sliding at velocity w at fixed depth d.
double stationary_force(const Case& c, double d, double w) {
  Case cd = c;
  cd.loading.d = d;
  cd.loading.F0 = 0.0;
  return analytic::stationary(cd, w).FN;
}

/// The depth of stationary sliding at w under c.loading.F0: the root of
/// stationary_force(c, d, w) = F0, bracketed from d0 = a0^2/R downwards.
double stationary_depth(const Case& c, double w) {
  const double F0 = c.loading.F0, a0 = c.a0(), d0 = a0 * a0 / c.indenter.as<Parabola>().R;
  auto f = [&](double d) { return stationary_force(c, d, w) - F0; };
  double hi = d0, fhi = f(hi);
  for (int k = 0; fhi < 0.0 && k < 200; ++k) // rounding at tau = 0 only
    fhi = f(hi *= 1.0 + 1e-12);
  if (fhi == 0.0) return hi;
  double lo = hi, flo = fhi;
  for (int k = 0; flo > 0.0 && k < 2000; ++k) { // F_N(d) >= 4G/R (2/3 a1^3 + w tau a1^2 / 2)
    hi = lo;
    fhi = flo;
    flo = f(lo *= 0.25);
  }
  if (flo == 0.0) return lo;
  if (!(flo < 0.0 && fhi > 0.0))
    throw std::runtime_error("load_check::stationary_depth: no bracket for the depth root");
  std::uintmax_t iters = 200;
  const auto r = boost::math::tools::toms748_solve(
      f, lo, hi, flo, fhi, boost::math::tools::eps_tolerance<double>(53), iters);
  return std::abs(f(r.first)) <= std::abs(f(r.second)) ? r.first : r.second;
}

/// The stationary state at w under load.
State stationary_state(const Case& c, double w) {
  Case cd = c;
  cd.loading.d = stationary_depth(c, w);
  cd.loading.F0 = 0.0;
  return analytic::stationary(cd, w);
}

} // namespace load_check

double force_of(double a0, double R = kR, double G = 1.0) {
  return 16.0 / 3.0 * G * a0 * a0 * a0 / R;
}

/// Load-controlled case: R = 2, G = 1, Hertz radius a0, tau = 1, v0 from
/// zeta0 = v0 tau / a0; segments as (w / v0, T / tau).
Case load_case(double zeta0, const std::vector<std::pair<double, double>>& segs, long samples = 21,
               double a0 = kA0) {
  Case c;
  c.indenter.as<Parabola>().R = kR;
  c.rheology.tau = 1.0;
  c.loading.F0 = force_of(a0);
  c.history.v0 = zeta0 * a0;
  for (const auto& [w, T] : segs)
    c.history.segments.push_back({w * c.history.v0, T});
  c.sampling.samples = samples;
  return c;
}

/// Stationary sliding under load in scaled variables, from the depth root.
struct Scaled {
  double zeta0, mu, d, a2; ///< v tau / a0, mu / (a0/R), d / d0, a2 / a0
};

Scaled stationary_scaled(double zeta0) {
  Case c = load_case(zeta0, {{1.0, 1.0}});
  const State st = load_check::stationary_state(c, c.history.v0);
  return {zeta0, st.mu / (kA0 / kR), st.d / (kA0 * kA0 / kR), st.a2 / kA0};
}

/// The same curve in closed form, parametrized by the fixed-depth similarity
/// variable zeta = v tau / a1 (docs/design.md, "Load control", the second
/// route): beta = a2/a1, P = 2/3 + beta - beta^3/3 + 2 zeta^2 beta,
/// F0 = (16/3) G a0^3 / R = 4 G a1^3 P / R, so alpha = a1/a0 = (4/(3P))^(1/3).
Scaled curve(double zeta) {
  const double b = 1.0 / (std::hypot(1.0, zeta) + zeta);
  const double P = 2.0 / 3.0 + b - b * b * b / 3.0 + 2.0 * zeta * zeta * b;
  const double M = 2.0 * (zeta * zeta * b * b + 2.0 * zeta / 3.0 * (1.0 + b * b * b)) / P;
  const double alpha = std::cbrt(4.0 / (3.0 * P));
  return {zeta * alpha, M * alpha, alpha * alpha, b * alpha};
}

std::vector<double> logspace(double lo, double hi, int n) {
  std::vector<double> x;
  for (int i = 0; i < n; ++i)
    x.push_back(lo * std::pow(hi / lo, i / static_cast<double>(n - 1)));
  return x;
}

// The depth root balances the load to 1e-14 relative over zeta0 = 1e-4..1e6
// and loads 1e-12..1e3 G R^2; tau = 0 (and a hold) is Hertz, d = d0.
TEST(LoadStationary, DepthRootBalancesTheLoad) {
  double worst = 0.0;
  for (double F0 : {1e-12, 1e-6, 1e-2, 1.0, 1e3})
    for (double zeta0 : logspace(1e-4, 1e6, 41)) {
      Case c = load_case(1.0, {{1.0, 1.0}});
      c.loading.F0 = F0;
      c.history.v0 = zeta0 * c.a0() / c.rheology.tau;
      const double d = load_check::stationary_depth(c, c.history.v0);
      const double r = std::abs(load_check::stationary_force(c, d, c.history.v0) - F0) / F0;
      worst = std::max(worst, r);
      EXPECT_LE(r, 1e-14) << "F0 " << F0 << " zeta0 " << zeta0;
    }
  std::printf("[ info ] depth root: worst |F_N(d) - F0| / F0 = %.1e\n", worst);
  for (double F0 : {1e-12, 1.0, 1e3}) {
    Case c = load_case(1.0, {{1.0, 1.0}});
    c.loading.F0 = F0;
    const double d0 = c.a0() * c.a0() / c.indenter.as<Parabola>().R;
    c.rheology.tau = 0.0;
    // d0 = a0^2 / R with a0 from a cube root carries a few ulp of its own
    EXPECT_NEAR(load_check::stationary_depth(c, c.history.v0) / d0, 1.0, 2e-15);
    c.rheology.tau = 1.0;
    EXPECT_NEAR(load_check::stationary_depth(c, 0.0) / d0, 1.0, 2e-15);
    EXPECT_EQ(load_check::stationary_state(c, 0.0).mu, 0.0);
  }
}

// The root agrees with the closed-form parametrization: two routes to the
// same curve (a root of F_N(d, v) = F0 against F0 = G a1 d N(zeta) solved for
// a1), and zeta0 grows monotonically with zeta so the curve is a function.
TEST(LoadStationary, RootAgreesWithTheSimilarityParametrization) {
  double prev = 0.0, worst = 0.0;
  for (double zeta : logspace(1e-5, 1e9, 57)) {
    const Scaled p = curve(zeta), r = stationary_scaled(p.zeta0);
    EXPECT_GT(p.zeta0, prev);
    prev = p.zeta0;
    for (auto [a, b] : {std::pair{p.mu, r.mu}, {p.d, r.d}, {p.a2, r.a2}}) {
      worst = std::max(worst, std::abs(a - b) / std::abs(b));
      EXPECT_NEAR(a / b, 1.0, 1e-12) << "zeta " << zeta;
    }
  }
  std::printf("[ info ] root vs parametrization: worst relative difference %.1e\n", worst);
}

/// d ln(mu) / d ln(zeta0) of the root-based curve, by 4th-order central
/// differences in ln(zeta0).
double log_slope(double zeta0) {
  const double h = 1e-3;
  auto f = [&](double k) { return std::log(stationary_scaled(zeta0 * std::exp(k * h)).mu); };
  return (8.0 * (f(1) - f(-1)) - (f(2) - f(-2))) / (12.0 * h);
}

// mu(zeta0) has one maximum. Located as the root of d mu / d zeta0 on the
// root-based curve, it lies where the derivation puts it: zeta = v tau / a1 =
// sqrt(3) (beta = 2 - sqrt(3) is the root of beta^2 - 4 beta + 1), so
// alpha^3 = (3 + sqrt(3))/9, zeta0* = sqrt(3) alpha, mu* / (a0/R) = 3/2
// (sqrt(3) - 1) alpha, d*/d0 = alpha^2, a2*/a0 = (2 - sqrt(3)) alpha.
TEST(LoadStationary, FrictionHasOneMaximum) {
  const std::vector<double> z = logspace(1e-4, 1e6, 201);
  int maxima = 0;
  for (std::size_t i = 1; i + 1 < z.size(); ++i) {
    const double m = stationary_scaled(z[i]).mu;
    maxima += (m > stationary_scaled(z[i - 1]).mu && m > stationary_scaled(z[i + 1]).mu) ? 1 : 0;
  }
  EXPECT_EQ(maxima, 1);
  std::uintmax_t iters = 100;
  const auto r = boost::math::tools::toms748_solve(
      log_slope, 0.5, 5.0, boost::math::tools::eps_tolerance<double>(45), iters);
  const double zs = 0.5 * (r.first + r.second), s3 = std::sqrt(3.0);
  const double alpha = std::cbrt((3.0 + s3) / 9.0);
  const Scaled at = stationary_scaled(zs);
  std::printf("[ info ] max of mu: zeta0 %.12f (closed form %.12f), mu/(a0/R) %.12f, d/d0 %.12f, "
              "a2/a0 %.12f\n",
              zs, s3 * alpha, at.mu, at.d, at.a2);
  EXPECT_NEAR(zs / (s3 * alpha), 1.0, 1e-8);
  EXPECT_NEAR(at.mu / (1.5 * (s3 - 1.0) * alpha), 1.0, 1e-13);
  EXPECT_NEAR(at.d / (alpha * alpha), 1.0, 1e-8);
  EXPECT_NEAR(at.a2 / ((2.0 - s3) * alpha), 1.0, 1e-8);
  // in the fixed-depth variable: v tau / a1 = sqrt(3)
  EXPECT_NEAR(zs / std::sqrt(at.d) / s3, 1.0, 1e-8);
  // a maximum: the slope changes sign across it
  EXPECT_GT(log_slope(zs * (1.0 - 1e-6)), 0.0);
  EXPECT_LT(log_slope(zs * (1.0 + 1e-6)), 0.0);
}

/// Observed power p and coefficient C of a deviation dev(z) ~ C z^p from two
/// points a decade apart.
std::pair<double, double> power_law(double z1, double e1, double z2, double e2) {
  const double p = std::log(e2 / e1) / std::log(z2 / z1);
  return {p, e2 / std::pow(z2, p)};
}

// The limits and how the curve approaches them (series of the closed-form
// parametrization, docs/design.md, "Load control"): zeta0 -> 0: mu/(a0/R) = 2 zeta0 (1 -
// 3/4 zeta0), d/d0 = 1 - zeta0^2/2, a2/a0 = 1 - zeta0; zeta0 -> infinity
// (1/zeta = a1/(v tau) ~ (2/sqrt 3) zeta0^-3/2 is the small parameter): the
// contact shrinks to [-a1, a2 -> 0] with a2/a0 = 2/3 zeta0^-2 (1 - c),
// d/d0 = 4/(3 zeta0) (1 - c), c = 4/(3 sqrt 3) zeta0^-3/2, and mu/(a0/R) =
// 8/(3 sqrt 3) zeta0^-1/2 (1 - 5/(4 sqrt 3) zeta0^-3/2) (mu -> (4/3) sqrt(d/R)
// with d -> 0, so friction falls as v^-1/2).
TEST(LoadStationary, LimitsAndTheirApproach) {
  const double s3 = std::sqrt(3.0);
  struct Limit {
    const char* what;
    double z_far, z_near; ///< the limit is approached from z_far towards z_near
    double (*dev)(double);
    double p, C; ///< derived: dev = C zeta0^p + higher order
  };
  const Limit limits[] = {
      {"mu, small", 1e-3, 1e-4, [](double z) { return stationary_scaled(z).mu / (2.0 * z) - 1.0; },
       1.0, -0.75},
      {"d, small", 1e-3, 1e-4, [](double z) { return stationary_scaled(z).d - 1.0; }, 2.0, -0.5},
      {"a2, small", 1e-3, 1e-4, [](double z) { return stationary_scaled(z).a2 - 1.0; }, 1.0, -1.0},
      {"mu, large", 1e3, 1e4,
       [](double z) {
         return stationary_scaled(z).mu / (8.0 / (3.0 * std::sqrt(3.0)) / std::sqrt(z)) - 1.0;
       },
       -1.5, -5.0 / (4.0 * s3)},
      {"d, large", 1e3, 1e4,
       [](double z) { return stationary_scaled(z).d / (4.0 / (3.0 * z)) - 1.0; }, -1.5,
       -4.0 / (3.0 * s3)},
      {"a2, large", 1e3, 1e4,
       [](double z) { return stationary_scaled(z).a2 * z * z / (2.0 / 3.0) - 1.0; }, -1.5,
       -4.0 / (3.0 * s3)},
  };
  for (const Limit& l : limits) {
    const double ef = l.dev(l.z_far), en = l.dev(l.z_near);
    const auto [p, C] = power_law(l.z_far, std::abs(ef), l.z_near, std::abs(en));
    std::printf("[ info ] %-10s deviation %.3e at %.0e, %.3e at %.0e: power %.4f (derived %.1f) "
                "coefficient %.5f (derived %.5f)\n",
                l.what, ef, l.z_far, en, l.z_near, p, l.p, std::copysign(C, en), l.C);
    EXPECT_LT(std::abs(en), std::abs(ef)); // the limit is approached
    EXPECT_NEAR(p, l.p, 2e-3);
    EXPECT_NEAR(std::copysign(C, en) / l.C, 1.0, 5e-3);
  }
}

/// Indentation creep at rest under a step load (docs/design.md, "Load control"):
/// full contact [-a, a], a = sqrt(R d), F0 / (4 G) = (4/3) a d + 2 a tau d',
/// d(0) = 0. With y = (d/d0)^(3/2) it is y' = (1 - y)/tau, so
/// d(t) = d0 (1 - exp(-t/tau))^(2/3).
double creep_depth(const Case& c, double t) {
  const double a0 = c.a0(), d0 = a0 * a0 / c.indenter.as<Parabola>().R;
  if (c.rheology.tau == 0.0) return d0;
  const double y = -std::expm1(-t / c.rheology.tau);
  return d0 * std::cbrt(y * y);
}

/// The time the creep equation needs to reach depth d, by quadrature of the
/// separated form dt = tau dd / (F0 / (8 G sqrt(R d)) - (2/3) d); with d' = d x^2
/// the integrand 2 tau d x^2 / (F0 / (8 G sqrt(R d)) - (2/3) d x^3) is smooth on
/// [0, 1]; its pole just beyond x = 1 (d near d0) is met by panels graded
/// geometrically towards 1.
double creep_time_by_quadrature(const Case& c, double d) {
  const double F0 = c.loading.F0, G = c.rheology.G, tau = c.rheology.tau;
  const double A = F0 / (8.0 * G * std::sqrt(c.indenter.as<Parabola>().R * d));
  auto f = [&](double x) { return 2.0 * tau * d * x * x / (A - (2.0 / 3.0) * d * x * x * x); };
  double t = 0.0, lo = 0.0, width = 0.5;
  for (int k = 0; k < 60; ++k, width *= 0.5) {
    t += boost::math::quadrature::gauss<double, 20>::integrate(f, lo, lo + width);
    lo += width;
  }
  return t + boost::math::quadrature::gauss<double, 20>::integrate(f, lo, 1.0);
}

// The closed form solves the creep equation: the time the separated equation
// needs to reach d(t), by quadrature, is t. Near d0 the time is ill-conditioned
// (dt/dd ~ 1/(d0 - d)), so the check is on the depth: the quadrature's time
// error moved to the depth through d'(t) is below 1e-12 d, from 1e-3 tau to
// 20 tau (where d0 - d is 1.4e-9 d0).
TEST(LoadCreep, ClosedFormAgainstQuadrature) {
  const Case c = load_case(1.0, {{0.0, 1.0}});
  double worst = 0.0;
  for (double t : {1e-3, 0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0}) {
    const double d = creep_depth(c, t), tq = creep_time_by_quadrature(c, d);
    // d'/d = (2/3) exp(-t/tau) / (1 - exp(-t/tau)) / tau
    const double rate = (2.0 / 3.0) / std::expm1(t / c.rheology.tau) / c.rheology.tau;
    const double err = std::abs(tq - t) * rate;
    worst = std::max(worst, err);
    EXPECT_LE(err, 1e-12) << "t " << t << " time error " << (tq - t) / t;
  }
  std::printf("[ info ] creep closed form vs quadrature: worst relative depth error %.1e\n", worst);
}

/// The row at rtol on a case under load.
Series row_at(const Case& c, double rtol) {
  SpectrumOptions o;
  o.rtol = rtol;
  return run_spectrum(CheckedCase(c), o).series;
}

/// Error of the last segment's samples against the stationary state under
/// load at its velocity: d, a1 by d0 and a0; mu by its stationary value, a2
/// by a0.
double end_error(const Case& c, const Series& s) {
  const double a0 = c.a0(), d0 = a0 * a0 / c.indenter.as<Parabola>().R;
  const State ss = load_check::stationary_state(c, c.history.segments.back().w);
  double e = 0.0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s.segment[k] + 1 != static_cast<int>(c.history.size())) continue;
    e = std::max({e, std::abs(s.d[k] - ss.d) / d0, std::abs(s.a1[k] - ss.a1) / a0,
                  std::abs(s.mu[k] - ss.mu) / ss.mu, std::abs(s.a2[k] - ss.a2) / a0});
  }
  return e;
}

// On a long segment the row at N = 0 reaches the stationary state under load
// at the new velocity (the root above, not the row's own start), after a
// drop and after a rise (16 tau, then 4.1 tau sampled), within rtol.
TEST(LoadRowKelvin, ReachesTheStationaryStateUnderLoad) {
  const std::pair<double, double> runs[] = {{1.0, 0.3}, {0.3, 3.0}};
  for (const auto& [zeta0, ratio] : runs) {
    // sqrt(17) tau sampled 101 times
    const Case c = load_case(zeta0, {{ratio, 16.0}, {ratio, std::sqrt(17.0)}}, 101);
    for (double rtol : {1e-3, 1e-5}) {
      const double e = end_error(c, row_at(c, rtol));
      std::printf("[ info ] zeta0 %.1f -> x%.1f, rtol %.0e: end error %.2e\n", zeta0, ratio, rtol,
                  e);
      EXPECT_LE(e, rtol) << zeta0 << " " << ratio;
    }
  }
}

// tau = 0 is Hertz at once: every sample has d = d0, a1 = a0, mu = 0 within
// rtol, across a drop, a hold and a rise. (tau = 1e-9, far below the step, is
// kelvin_load's: RunLoad.TauZeroIsHertzAtOnce; the row abandons it past its
// work budget.)
TEST(LoadRowKelvin, TauZeroIsHertzAtOnce) {
  Case c = load_case(1.0, {{0.1, 2.0}, {0.0, 1.0}, {3.0, 2.0}}, 11);
  c.rheology.tau = 0.0;
  const double a0 = c.a0(), d0 = a0 * a0 / c.indenter.as<Parabola>().R, rtol = 1e-3;
  const Series s = row_at(c, rtol);
  double e = 0.0;
  for (std::size_t k = 0; k < s.size(); ++k)
    e = std::max({e, std::abs(s.d[k] / d0 - 1.0), std::abs(s.a1[k] / a0 - 1.0),
                  std::abs(s.mu[k]) / (a0 / c.indenter.as<Parabola>().R)});
  std::printf("[ info ] Hertz, tau 0: largest deviation %.2e\n", e);
  EXPECT_LE(e, rtol);
}

} // namespace
} // namespace mdrmap
