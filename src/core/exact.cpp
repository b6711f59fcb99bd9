#include "core/exact.hpp"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mdrmap {
namespace {

// phi2(z) = (exp(-z) - 1 + z) / z^2, evaluated without cancellation.
// For small z the direct form loses digits (numerator ~ z^2/2), so use the
// series sum_{n>=0} (-z)^n / (n+2)!; truncation error < 1e-20 for z < 0.1.
double phi2(double z) {
  if (z < 0.1) {
    double term = 0.5, sum = 0.5; // n = 0: 1/2!
    for (int n = 1; n <= 10; ++n) {
      term *= -z / static_cast<double>(n + 2);
      sum += term;
    }
    return sum;
  }
  return (std::expm1(-z) + z) / (z * z);
}

} // namespace

ExactSolution::ExactSolution(const Scene& s, int bits) : s_(s), bits_(std::clamp(bits, 8, 52)) {
  a1_ = analytic::a1(s);
  a2v_ = analytic::a2_stationary(s, s.v);
  a2v1_ = analytic::a2_stationary(s, s.v1);
  a1_minus_a2v_ = analytic::a1_minus_a2_stationary(s, s.v);
  a1_minus_a2v1_ = analytic::a1_minus_a2_stationary(s, s.v1);
  pre_ = analytic::stationary(s, s.v);
  post_ = analytic::stationary(s, s.v1);
  L_ = s.v * s.tau;
  // h(a2v) = 2 a2v L / R: the force-zero condition at the trailing edge,
  // free of the cancellation in d - a2v^2/R when a2v is close to a1.
  h_a2v_ = 2.0 * a2v_ * L_ / s.R;
  transient_ = (s.tau > 0.0) && (s.v1 < s.v);
}

State ExactSolution::at(double t) const {
  last_bracket_ = 0.0;
  if (!transient_) return post_; // rise, no change, or tau = 0: stationary at v1 at once
  if (!(t > 0.0)) return analytic::jump(s_);

  // Gap function along the moving frame, x = a2v + y, z = y / L:
  //   h(x) - c(t) h(a2v) exp(-z) = h(a2v)(1 - c) e^{-z} - y^2 [h(a2v) phi2(z)/L^2 + 1/R].
  // Multiplied by R/a1^2 and written in Y = y/a1 it is G(Y) below: increasing in
  // Y, negative at 0, so the trailing edge is its unique root (or the cap a2v1).
  const double one_minus_c = -std::expm1(-t * (1.0 - s_.v1 / s_.v) / s_.tau);
  const double a1_minus_a2v = a1_minus_a2v_; // (constant: cached, it costs a hypot and two sqrt)
  const double ratio_a = 2.0 * (a2v_ / a1_) * (L_ / a1_) * one_minus_c; // R h(a2v)(1-c)/a1^2
  const double ratio_b = 2.0 * a2v_ / L_;                               // R h(a2v)/L^2
  const double scale = a1_ / L_;
  auto G = [&](double Y) {
    const double z = Y * scale;
    return Y * Y * (ratio_b * phi2(z) + 1.0) - ratio_a * std::exp(-z);
  };
  // The cap: a2 never passes a2(v1), where elements moving at v1 lose force.
  const double y_cap = (a1_minus_a2v - a1_minus_a2v1_) / a1_;
  const double g_cap = G(y_cap);
  if (g_cap <= 0.0) return post_;

  std::uintmax_t iters = 200;
  const auto tol = boost::math::tools::eps_tolerance<double>(static_cast<unsigned>(bits_));
  const auto r = boost::math::tools::toms748_solve(G, 0.0, y_cap, -ratio_a, g_cap, tol, iters);
  ++root_solves_;
  const double Y = 0.5 * (r.first + r.second);
  last_bracket_ = r.second - r.first;
  const double y = Y * a1_;
  return analytic::contact_forces(s_, a2v_ + y, a1_minus_a2v - y, s_.v1);
}

RunResult run_exact(const Scene& s, const Protocol& p, double rtol) {
  validate(s);
  validate(p);
  // Solve the root to ~10 bits beyond what rtol asks, 52 bits at most.
  const int bits = std::clamp(static_cast<int>(std::ceil(-std::log2(rtol))) + 12, 24, 52);
  ExactSolution ex(s, bits);
  RunResult res;
  res.info.solver = "exact";
  res.info.rtol = rtol;
  const auto n = static_cast<std::size_t>(p.samples);
  res.series.resize(n);
  res.series.pre = ex.pre();
  double bracket = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = p.time(static_cast<long>(k));
    res.series.set(k, t, ex.at(t));
    bracket = std::max(bracket, ex.last_bracket());
  }
  res.info.root_solves = ex.root_solves();
  res.info.steps = 0;
  // The a2 error is at most half the final bracket (in units of a1). F_N
  // responds to it with relative sensitivity <= 1.5; F_x and mu, measured on
  // the scale of their largest value (the jump), with at most
  // S = 4 a1^2 / (a1^2 - a2(v)^2): dF_x/da2 = -8 G a2 p(a2) / R with
  // 0 <= p(a2) <= (a1^2 - a2v^2)/R, and F_x(jump) >= 2 G (a1^2 - a2v^2)^2 / R^2.
  // S ~ 2/zeta for zeta << 1. Plus a rounding floor.
  double sens = 0.0;
  if (bracket > 0.0) { // (no root was solved for tau = 0, where S is infinite)
    const double a1 = analytic::a1(s);
    const double S =
        4.0 * a1 * a1 /
        (analytic::a1_minus_a2_stationary(s, s.v) * (a1 + analytic::a2_stationary(s, s.v)));
    sens = 0.5 * (S + 1.5);
  }
  res.info.error_estimate = sens * bracket + 64.0 * std::numeric_limits<double>::epsilon();
  return res;
}

} // namespace mdrmap
