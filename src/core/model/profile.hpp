#pragma once
// The indenter: a rigid axisymmetric profile f(r) = A r^n and its MDR image
// g(x) = kappa_n A |x|^n, kappa_n = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2)
// (docs/design.md, "Indenter profiles"). Three kinds:
//   parabola  f = r^2 / 2R (n = 2, A = 1/(2R)): g = x^2 / R, as the seed
//   cone      beta the angle between its surface and the plane (n = 1,
//             A = tan beta): g = (pi/2) tan(beta) |x|
//   power     n >= 1, A > 0
// The parabola's arithmetic is the seed's (x * x / R, sqrt(R) sqrt(d)), bit
// for bit; the other kinds use c = kappa_n A and the exponent n.
#include <cmath>
#include <string>

namespace mdrmap {

enum class Profile { Parabola, Cone, Power };

/// Every kind, in the order of the help text.
inline constexpr Profile kProfiles[] = {Profile::Parabola, Profile::Cone, Profile::Power};

/// "parabola", "cone", "power".
const char* profile_name(Profile p);
/// Parses a profile's name; throws InvalidInput("profile").
Profile parse_profile(const std::string& name);

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

struct Indenter {
  Profile profile = Profile::Parabola;
  double R = 0.0;    ///< parabola: radius of curvature, > 0
  double beta = 0.0; ///< cone: angle of the surface to the plane, degrees, (0, 90)
  double n = 0.0;    ///< power: exponent, >= 1
  double A = 0.0;    ///< power: coefficient of f(r) = A r^n, > 0

  bool parabolic() const { return profile == Profile::Parabola; }
  /// The exponent n of g: 2, 1 or n.
  double exponent() const;
  /// The coefficient c of g = c |x|^n: 1/R, (pi/2) tan(beta), kappa_n A.
  double coefficient() const;
  double g(double x) const {
    if (parabolic()) return x * x / R;
    return coefficient() * profile_pow(std::fabs(x), exponent());
  }
  double slope(double x) const {
    if (parabolic()) return 2.0 * x / R;
    const double m = exponent(), s = m * coefficient() * profile_pow(std::fabs(x), m - 1.0);
    return x < 0.0 ? -s : (x > 0.0 ? s : 0.0);
  }
  /// Half-width a of the MDR contact at depth d: g(a) = d. (Inline: the
  /// solvers ask for it at every sample.)
  double contact_radius(double d) const {
    if (parabolic()) return std::sqrt(R) * std::sqrt(d);
    return profile_pow(d / coefficient(), 1.0 / exponent());
  }
  /// The same as the element-row solvers form it: sqrt(R d) for the parabola
  /// (their arithmetic since the seed, bit for bit), contact_radius otherwise.
  double leading_edge(double d) const { return parabolic() ? std::sqrt(R * d) : contact_radius(d); }
  /// Elastic normal force of the full contact [-a, a] at depth g(a) on a
  /// foundation of modulus G: 4 G int (g(a) - g) = 8 G c n/(n + 1) a^(n + 1)
  /// (the parabola: 16/3 G a^3 / R).
  double elastic_force(double a, double G) const;
  /// The radius a of that force: elastic_force(a, G) = F (the parabola:
  /// cbrt(3 F R / (16 G)), as the seed).
  double hertz_radius(double F, double G) const;
};

} // namespace mdrmap
