#include "core/metrics/profile_branches.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/math/quadrature/tanh_sinh.hpp>

// Derivation: the header and docs/design.md ("Indenter profiles").

namespace mdrmap::profile {
namespace {

constexpr double kLayers = 40.0; // a relaxed branch's kernel dropped below e^-40

/// tanh-sinh over [lo, hi] of f, every evaluation charged to k. Taken over
/// [0, hi - lo]: on an interval far from 0 against its width (a layer's end
/// piece [0.000399995, 0.0004]) Boost's rule drops its abscissas that round to
/// the ends and refines to its last level (tens of thousands of evaluations
/// for a smooth integrand, 74 when shifted).
template <class F> double integral(const BranchContact& k, F f, double lo, double hi) {
  if (!(hi > lo)) return 0.0;
  thread_local boost::math::quadrature::tanh_sinh<double> rule; // grows its tables: per thread
  return rule.integrate(
      [&](double v) {
        k.charge(1.0);
        return f(lo + v);
      },
      0.0, hi - lo, 1e-13);
}

/// The sum of integral(f) over the pieces between consecutive points of
/// `cuts` (sorted, the ends included).
template <class F> double pieces(const BranchContact& k, F f, const std::vector<double>& cuts) {
  double s = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    s += integral(k, f, cuts[i], cuts[i + 1]);
  return s;
}

/// lo, the points of `inner` strictly inside (lo, hi), hi: sorted.
std::vector<double> cuts_of(double lo, double hi, std::initializer_list<double> inner) {
  std::vector<double> c = {lo};
  for (double x : inner)
    if (x > lo && x < hi) c.push_back(x);
  c.push_back(hi);
  std::sort(c.begin(), c.end());
  return c;
}

bool glassy(const BranchContact& k, double lambda) {
  return lambda >= 0.5 * k.a1;
}

/// f = -g' at t: |g'| ahead of the tip, its negative behind.
double f_at(const BranchContact& k, double t) {
  return t < 0.0 ? k.slope_mag(-t) : -k.slope_mag(t);
}

/// h at t in [-a1, a1] (the integrands' h: a1 - |t| is exact near the edges).
double h_at(const BranchContact& k, double t) {
  return k.depth_left(k.a1 - std::fabs(t));
}

/// s(x) = (1/lambda) int_{-a1}^{x} exp(-(x - t)/lambda) h(t) dt.
double remainder(const BranchContact& k, double lambda, double x) {
  auto g = [&](double t) { return std::exp(-(x - t) / lambda) * h_at(k, t); };
  return pieces(k, g, cuts_of(-k.a1, x, {0.0})) / lambda;
}

/// r(x) of a relaxed branch, s = x + a1 (the distance from the leading
/// edge, given where it keeps digits x does not): in u = x - t, exact where
/// the kernel exp(-u/lambda) is large (in t, the rounding of x - t near
/// |t| ~ a1 is a relative 1e-16 a1 / lambda of the exponent, and tanh-sinh
/// refined that noise to its last level), over the last 40 lambda only.
/// The face of the tip at t = x - u is told by the piece, not by the sign of
/// the rounded x - u (at the cut u = x that sign was noise).
double relaxed_stress(const BranchContact& k, double lambda, double x, double s) {
  const double span = std::min(s, kLayers * lambda), tip = std::clamp(x, 0.0, span);
  auto behind = [&](double u) { return -std::exp(-u / lambda) * k.slope_mag(x - u); };
  auto ahead = [&](double u) { return std::exp(-u / lambda) * k.slope_mag(u - x); };
  return integral(k, behind, 0.0, tip) + integral(k, ahead, tip, span);
}

} // namespace

void BranchContact::charge(double k) const {
  budget->evaluations += k;
  if (budget->evaluations > budget->max_evaluations)
    throw std::runtime_error(
        "profile_stationary: the branches' quadrature needs more than " +
        std::to_string(static_cast<long long>(budget->max_evaluations)) +
        " integrand evaluations (a contact the stationary state cannot resolve)");
}

double branch_stress(const BranchContact& k, double lambda, double x, double delta) {
  if (!glassy(k, lambda)) return relaxed_stress(k, lambda, x, x + k.a1);
  const double h = x <= 0.0 ? h_at(k, x) : k.depth_left(delta);
  return h - remainder(k, lambda, x);
}

double branch_normal(const BranchContact& k, double lambda, double a2) {
  // the order of integration swapped: lambda int f(t) (1 - exp(-(a2 - t)/lambda)) dt
  auto g = [&](double t) { return f_at(k, t) * -std::expm1(-(a2 - t) / lambda); };
  if (glassy(k, lambda)) return lambda * pieces(k, g, cuts_of(-k.a1, a2, {0.0}));
  // relaxed: the layer before a2 in u = a2 - t (exact where the kernel varies)
  const double span = std::min(kLayers * lambda, a2 + k.a1);
  // the faces by the pieces (as relaxed_stress), the tip at u = a2
  auto behind = [&](double u) { return -k.slope_mag(a2 - u) * -std::expm1(-u / lambda); };
  auto ahead = [&](double u) { return k.slope_mag(u - a2) * -std::expm1(-u / lambda); };
  const double tip = std::min(a2, span);
  const double layer = integral(k, behind, 0.0, tip) + integral(k, ahead, tip, span);
  return lambda * (layer + pieces(k, g, cuts_of(-k.a1, a2 - span, {0.0})));
}

double branch_friction(const BranchContact& k, double lambda, double a2, double delta) {
  if (!glassy(k, lambda)) {
    // the leading edge's layer in s = x + a1, the rest in x (the tip's layer a piece)
    const double span = std::min(kLayers * lambda, k.a1);
    auto gs = [&](double s) {
      const double x = s - k.a1;
      return relaxed_stress(k, lambda, x, s) * f_at(k, x);
    };
    auto g = [&](double x) { return relaxed_stress(k, lambda, x, x + k.a1) * f_at(k, x); };
    return integral(k, gs, 0.0, span) +
           pieces(k, g, cuts_of(span - k.a1, a2, {0.0, kLayers * lambda}));
  }
  const double h2 = k.depth_left(delta);
  auto g = [&](double x) { return (h_at(k, x) - remainder(k, lambda, x)) * h_at(k, x); };
  const double rh = pieces(k, g, cuts_of(-k.a1, a2, {0.0})) / lambda;
  return h2 * (0.5 * h2 - remainder(k, lambda, a2)) + rh;
}

} // namespace mdrmap::profile
