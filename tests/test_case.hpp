#pragma once
// Shared by the physics tests: the seed's one-step case (stationary sliding at
// v, then v1 for one segment) from its parameters in one call, and its parts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/model/case.hpp"
#include "core/solvers/spectrum.hpp"

namespace mdrmap::testing {

/// step_case with the tests' argument order: t_end = 0 is the default window
/// (6 tau; 6 a1 / min(v, v1) for tau = 0), `samples` linear samples.
inline Case make_case(double d, double R, double tau, double v, double v1 = 0.0, double G = 1.0,
                      double t_end = 0.0, long samples = 201) {
  return step_case(d, R, tau, v, v1, G, t_end, samples);
}

/// Velocity after the step (the one segment's velocity).
inline double v1_of(const Case& c) {
  return c.history.segments.at(0).w;
}

/// Observation window after the step (the one segment's duration).
inline double t_end_of(const Case& c) {
  return c.history.segments.at(0).T;
}

/// Sets both velocities of a one-step case; the window T is kept.
inline void set_velocities(Case& c, double v, double v1) {
  c.history.v0 = v;
  c.history.segments.at(0).w = v1;
}

/// A history case: d = d_over_R R with R = 2, tau = 1, v0 from
/// zeta0 = v0 tau / a1; segments given as (w / v0, T / tau).
inline Case history_case(double zeta0, const std::vector<std::pair<double, double>>& segs,
                         long samples, double d_over_R = 1e-3) {
  Case c = step_case(2.0 * d_over_R, 2.0, 1.0, 1.0, 0.0);
  c.history.v0 = zeta0 * c.a1() / c.rheology.tau;
  c.history.segments.clear();
  for (const auto& [w, T] : segs)
    c.history.segments.push_back({w * c.history.v0, T});
  c.sampling.samples = samples;
  return c;
}

/// Least-squares slope of log(err) against log(1/dx).
inline double observed_order(const std::vector<double>& cells, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const double x = std::log(cells[i]), y = std::log(err[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Whether every sample (F_N, F_x, mu, a2) and the state before t = 0 are finite.
inline bool all_finite(const Series& x) {
  for (std::size_t k = 0; k < x.size(); ++k)
    if (!std::isfinite(x.FN[k]) || !std::isfinite(x.Fx[k]) || !std::isfinite(x.mu[k]) ||
        !std::isfinite(x.a2[k]))
      return false;
  return std::isfinite(x.pre.FN) && std::isfinite(x.pre.Fx) && std::isfinite(x.pre.a2);
}

/// The element row (row) at rtol, or nothing where it abandons the case: its
/// error contract is a result within rtol or CaseAbandoned. An abandoned case
/// is printed with `what` and counted in `abandoned`.
inline std::optional<RunResult> row_or_abandoned(const Case& c, double rtol,
                                                 const std::string& what, int& abandoned) {
  SpectrumOptions o;
  o.rtol = rtol;
  try {
    return run_spectrum(CheckedCase(c), o);
  } catch (const CaseAbandoned& e) {
    ++abandoned;
    std::printf("[ info ] abandoned at rtol %.0e: %s (%s)\n", rtol, what.c_str(), e.what());
    return std::nullopt;
  }
}

/// The row on an elastic case (tau = 0, no branches) of the parabola at fixed
/// depth: finite, Hertz (F_N = 16/3 G sqrt(R) d^1.5) and mu = 0 at every
/// sample, whatever the history.
inline void expect_row_hertz_throughout(const Case& c) {
  const RunResult r = run_spectrum(CheckedCase(c), SpectrumOptions{});
  const double hertz = 16.0 / 3.0 * c.rheology.G * std::sqrt(c.indenter.as<Parabola>().R) *
                       std::pow(c.loading.d, 1.5);
  for (std::size_t k = 0; k < r.series.size(); ++k) {
    ASSERT_TRUE(std::isfinite(r.series.FN[k]) && std::isfinite(r.series.mu[k])) << k;
    EXPECT_NEAR(r.series.FN[k] / hertz, 1.0, 1e-12);
    EXPECT_NEAR(r.series.mu[k], 0.0, 1e-12);
  }
}

} // namespace mdrmap::testing
