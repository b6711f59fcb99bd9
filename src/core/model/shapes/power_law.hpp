#pragma once
// The MDR image g(x) = c |x|^n of a power-law profile f(r) = A r^n, with
// c = kappa_n A (docs/design.md, "Indenter profiles"): the arithmetic the cone
// and the power law share (shapes/cone.hpp, shapes/power.hpp).
#include <cmath>

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

/// g = c |x|^n and what is formed from it.
struct PowerImage {
  double c; ///< coefficient of g
  double n; ///< exponent of g, >= 1

  double g(double x) const { return c * profile_pow(std::fabs(x), n); }
  double slope(double x) const {
    const double s = n * c * profile_pow(std::fabs(x), n - 1.0);
    return x < 0.0 ? -s : (x > 0.0 ? s : 0.0);
  }
  /// g(a) = d.
  double contact_radius(double d) const { return profile_pow(d / c, 1.0 / n); }
  /// 4 G int_{-a}^{a} (g(a) - g) = 8 G c n/(n + 1) a^(n + 1).
  double elastic_force(double a, double G) const {
    return 8.0 * G * c * n / (n + 1.0) * std::pow(a, n + 1.0);
  }
  /// elastic_force(a, G) = F.
  double hertz_radius(double F, double G) const {
    return std::pow(F * (n + 1.0) / (8.0 * G * c * n), 1.0 / (n + 1.0));
  }
};

} // namespace mdrmap
