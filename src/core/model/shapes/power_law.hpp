#pragma once
// The MDR image g(x) = c |x|^n of a power-law profile f(r) = A r^n, with
// c = kappa_n A (docs/design.md, "Indenter profiles"): the arithmetic the cone
// and the power law share (shapes/cone.hpp, shapes/power.hpp).
#include <cmath>
#include <limits>

namespace mdrmap {

/// kappa_n = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2): 2 for n = 2, pi/2 for n = 1.
double mdr_kappa(double n);

/// x^n (x >= 0) for the profiles' exponents: exact forms where they exist
/// (the cone's n = 1 and its slope's 0, 2, 1/2 and 3/2), pow otherwise (it
/// was half the time of a cone's or a power law's case). The indenter and
/// the element row both use it, so they agree bit for bit.
inline double profile_pow(double x, double n) {
  if (n == 1.0) return x;
  if (n == 0.0) return 1.0;
  if (n == 2.0) return x * x;
  if (n == 0.5) return std::sqrt(x);
  if (n == 1.5) return x * std::sqrt(x);
  return std::pow(x, n);
}

/// a^n - (a - delta)^n (0 <= delta <= a) without cancellation.
inline double pow_diff(double a, double delta, double n) {
  return std::pow(a, n) * -std::expm1(n * std::log1p(-delta / a));
}

/// g = c |x|^n and what is formed from it: what the shapes of such an image
/// (the cone, the power law) answer, and what the element row asks of a shape
/// (core/solvers/spectrum_row.hpp; the parabola answers it in its own file).
struct PowerImage {
  double c; ///< coefficient of g
  double n; ///< exponent of g, >= 1

  /// The one-sided |g'| at the tip x = 0, where g' jumps from -it to it: the
  /// cone's c (its kink); 0 where g' is continuous (n > 1).
  double apex_slope() const { return n == 1.0 ? c : 0.0; }
  /// Whether g is smooth through the tip (no sub-step or run is cut there).
  bool smooth_apex() const { return false; }
  /// Whether u = d - g(x0 + w t) is quadratic in t on either side of the tip
  /// (n = 1, 2): the row's forcing is exact.
  bool exact_forcing() const { return n == 1.0 || n == 2.0; }
  double depth(double x, double d) const { return d - g(x); }
  /// g(a) - g(a - delta) (0 <= delta <= a) without cancellation.
  double drop(double a, double delta) const { return c * pow_diff(a, delta, n); }
  /// g'(x) w.
  double lift(double x, double w) const { return slope(x) * w; }
  bool inside(double x, double d) const { return g(x) <= d; }
  /// g''(x) (x != 0).
  double curvature(double x) const {
    return n * (n - 1.0) * c * profile_pow(std::fabs(x), n - 2.0);
  }
  /// g'(x), at the tip its limit from `side` (-1, +1).
  double side_slope(double x, int side) const {
    if (x != 0.0) return slope(x);
    return side * apex_slope();
  }
  /// da/dd of the contact radius a at depth d (a / (n d)).
  double radius_rate(double a, double d) const { return a / (n * d); }
  /// Signed antiderivatives from the tip: int_0^t g and int_0^t g'^2.
  double integral_g(double t) const {
    return std::copysign(c * profile_pow(std::fabs(t), n + 1.0) / (n + 1.0), t);
  }
  double integral_slope_squared(double t) const {
    return std::copysign(c * c * n * n * profile_pow(std::fabs(t), 2.0 * n - 1.0) / (2.0 * n - 1.0),
                         t);
  }
  /// The forcing {u, u', u''/2} at t = 0 of a point at x moving at w over a
  /// sub-step of h along the depth path q (q.d, q.r, q.k, q.at(t)): exact on
  /// the sub-step's side of the tip for n = 1 and 2, else the quadratic
  /// through u at 0, h/2 and h.
  template <class Out, class Path> Out forcing(double x, double w, double h, const Path& q) const {
    if (!(w > 0.0)) return {depth(x, q.d), q.r, q.k};
    if (exact_forcing() && n == 1.0)
      return {depth(x, q.d), q.r - (x + 0.5 * w * h < 0.0 ? -c : c) * w, q.k};
    if (exact_forcing()) return {depth(x, q.d), q.r - 2.0 * c * x * w, q.k - c * w * w};
    const double u0 = depth(x, q.d), um = depth(x + 0.5 * w * h, q.at(0.5 * h)),
                 u1 = depth(x + w * h, q.at(h));
    return {u0, (4.0 * um - 3.0 * u0 - u1) / h, 2.0 * (u0 - 2.0 * um + u1) / (h * h)};
  }

  double exponent() const { return n; }
  double coefficient() const { return c; }
  double g(double x) const { return c * profile_pow(std::fabs(x), n); }
  double slope(double x) const {
    const double s = n * c * profile_pow(std::fabs(x), n - 1.0);
    return x < 0.0 ? -s : (x > 0.0 ? s : 0.0);
  }
  /// g(a) = d.
  double contact_radius(double d) const { return profile_pow(d / c, 1.0 / n); }
  double leading_edge(double d) const { return contact_radius(d); }
  /// 4 G int_{-a}^{a} (g(a) - g) = 8 G c n/(n + 1) a^(n + 1).
  double elastic_force(double a, double G) const {
    return 8.0 * G * c * n / (n + 1.0) * std::pow(a, n + 1.0);
  }
  /// d ln F / d ln d of the elastic force: F ~ d^((n + 1)/n).
  double force_exponent(double) const { return (n + 1.0) / n; }
  /// No bound on the contact radius.
  double max_radius() const { return std::numeric_limits<double>::infinity(); }
  /// elastic_force(a, G) = F.
  double hertz_radius(double F, double G) const {
    return std::pow(F * (n + 1.0) / (8.0 * G * c * n), 1.0 / (n + 1.0));
  }
};

} // namespace mdrmap
