#pragma once
// The exact sphere of radius R, f(r) = R - sqrt(R^2 - r^2), MDR image
// g(x) = |x| artanh(|x|/R) for |x| < R (x^2/R + x^4/(3 R^3) + ...: the
// parabola's x^2/R at the tip), infinite from R on: no contact reaches R.
// With u = |x|/R and A = artanh(u) (docs/design.md, "Indenter profiles"):
//   g'  = A + u/(1 - u^2),   g'' = 2 R^3 / (R^2 - x^2)^2,
//   int_0^a g    = R^2 [u/2 - (1 - u^2) A/2]     = R^2 sum_k u^(2k+1) / (4k^2 - 1),
//   int_0^a g'^2 = R [u A^2 + u/(2(1 - u^2)) - A/2]
//                = R sum_k u^(2k+1) [k/(2k+1) + (1/k) sum_{i<k} 1/(2i+1)],
//   F = 4 G int_{-a}^{a} (g(a) - g) = 4 G R^2 [(1 + u^2) A - u]
//     = 4 G R^2 sum_k 4k u^(2k+1) / (4k^2 - 1)    (k >= 1),
// the exact Hertz force of the sphere, (E*/2) [(a^2 + R^2) ln((R + a)/(R - a))
// - 2 a R] with E* = 4 G. The sums below u = 1/2 (where the closed forms lose
// (R/a)^2 of their digits), the closed forms above.
#include <array>
#include <cmath>
#include <limits>

#include "core/model/shapes/shape_param.hpp"

namespace mdrmap {

struct Sphere {
  double R = 0.0; ///< radius, > 0

  static constexpr const char* name = "sphere";
  static constexpr std::array<ShapeParam<Sphere>, 1> parameters() {
    return {{{"radius", "R", Dim::Length, 0.0, false, std::numeric_limits<double>::infinity(), true,
              "radius of the spherical indenter, exact (--profile sphere)", &Sphere::R}}};
  }
  static constexpr const char* depth_radius_words =
      "with the profile's radius gives a contact radius a1 = ";
  static constexpr const char* load_radius_words =
      "with G and the profile's radius gives a Hertz radius a0 = ";
  static constexpr const char* coefficient_option = nullptr; // (checked through the scales)
  static constexpr const char* coefficient_words = "";

  /// The tip's g = x^2 / R: its scale 1/R (the row's range checks).
  double coefficient() const { return 1.0 / R; }
  bool quadratic() const { return false; }
  bool linear() const { return false; }
  /// No contact reaches R (g is infinite there).
  double max_radius() const { return R; }

  double g(double x) const {
    const double y = std::fabs(x);
    return y < R ? y * std::atanh(y / R) : std::numeric_limits<double>::infinity();
  }
  double slope(double x) const {
    const double y = std::fabs(x), u = y / R;
    if (!(y < R)) return std::copysign(std::numeric_limits<double>::infinity(), x);
    return std::copysign(std::atanh(u) + u / ((1.0 - u) * (1.0 + u)), x);
  }
  double curvature(double x) const {
    const double y = std::fabs(x);
    if (!(y < R)) return std::numeric_limits<double>::infinity();
    const double s = (R - y) * (R + y);
    return 2.0 * R * R * R / (s * s);
  }
  /// g(a) - g(a - delta) = delta artanh(a/R) + b artanh(delta R / (R^2 - a b)),
  /// b = a - delta: both terms >= 0.
  double drop(double a, double delta) const {
    const double b = a - delta;
    return delta * std::atanh(a / R) + b * std::atanh(delta * R / (R * R - a * b));
  }
  /// g(a) = d: Newton from above (g is convex).
  double contact_radius(double d) const {
    const double D = d / R;
    return R * descend(
                   D, std::fmin(std::sqrt(D), std::tanh(D / std::tanh(D))),
                   [](double u) { return u * std::atanh(u); },
                   [](double u) { return std::atanh(u) + u / ((1.0 - u) * (1.0 + u)); });
  }
  double leading_edge(double d) const { return contact_radius(d); }
  double elastic_force(double a, double G) const { return 4.0 * G * R * R * psi(a / R); }
  /// d ln F / d ln d of the elastic force at depth d: 8 a d / F(a) at G = 1
  /// (3/2 at the tip, growing towards R).
  double force_exponent(double d) const {
    const double a = contact_radius(d);
    return 8.0 * a * d / elastic_force(a, 1.0);
  }
  /// elastic_force(a, G) = F: Newton from above (the force is convex in a).
  double hertz_radius(double F, double G) const {
    const double T = F / (4.0 * G * R * R);
    return R * descend(T, std::fmin(std::cbrt(0.75 * T), std::tanh(T + 1.0)), psi, [](double u) {
             return 2.0 * u * (std::atanh(u) + u / ((1.0 - u) * (1.0 + u)));
           });
  }
  double integral_g(double t) const {
    const double u = std::fabs(t) / R;
    const double I = u < 0.5 ? series(u, [](int k) { return 1.0 / (4.0 * k * k - 1.0); })
                             : 0.5 * u - 0.5 * (1.0 - u) * (1.0 + u) * std::atanh(u);
    return std::copysign(R * R * I, t);
  }
  double integral_slope_squared(double t) const {
    const double u = std::fabs(t) / R, A = std::atanh(u);
    double odd = 0.0; // sum_{i<k} 1/(2i+1), the terms taken in order of k
    const double J = u < 0.5 ? series(u,
                                      [&odd](int k) {
                                        odd += 1.0 / (2.0 * k - 1.0);
                                        return k / (2.0 * k + 1.0) + odd / k;
                                      })
                             : u * A * A + 0.5 * u / ((1.0 - u) * (1.0 + u)) - 0.5 * A;
    return std::copysign(R * J, t);
  }

  // What the element row asks (core/model/shapes/power_law.hpp tells each).
  const Sphere& image() const { return *this; }
  double apex_slope() const { return 0.0; }
  bool smooth_apex() const { return true; }
  bool exact_forcing() const { return false; }
  double depth(double x, double d) const { return d - g(x); }
  double lift(double x, double w) const { return slope(x) * w; }
  bool inside(double x, double d) const { return g(x) <= d; }
  double side_slope(double x, int) const { return slope(x); }
  double radius_rate(double a, double) const { return 1.0 / slope(a); }
  /// The quadratic through u at 0, h/2 and h (as the power law's).
  template <class Out, class Path> Out forcing(double x, double w, double h, const Path& q) const {
    if (!(w > 0.0)) return {depth(x, q.d), q.r, q.k};
    const double u0 = depth(x, q.d), um = depth(x + 0.5 * w * h, q.at(0.5 * h)),
                 u1 = depth(x + w * h, q.at(h));
    return {u0, (4.0 * um - 3.0 * u0 - u1) / h, 2.0 * (u0 - 2.0 * um + u1) / (h * h)};
  }

private:
  /// F / (4 G R^2) at u = a / R: (1 + u^2) artanh(u) - u.
  static double psi(double u) {
    if (u < 0.5) return series(u, [](int k) { return 4.0 * k / (4.0 * k * k - 1.0); });
    return (1.0 + u * u) * std::atanh(u) - u;
  }
  /// sum_{k >= 1} b(k) u^(2k+1) for u < 1/2, to rounding (b called for k = 1, 2, ...).
  template <class B> static double series(double u, B b) {
    const double u2 = u * u;
    double p = u * u2, s = 0.0;
    for (int k = 1; k < 60; ++k, p *= u2) {
      const double term = b(k) * p;
      s += term;
      if (term <= 1e-17 * s) break;
    }
    return s;
  }
  /// The root u in (0, 1) of f(u) = y, f convex and increasing, by Newton
  /// from u0 >= the root; 1 where u0 rounds to it (the contact reaches R).
  template <class F, class DF> static double descend(double y, double u0, F f, DF df) {
    if (!(y > 0.0)) return 0.0;
    if (!(u0 < 1.0)) return 1.0;
    double u = u0;
    for (int i = 0; i < 100; ++i) {
      const double step = (f(u) - y) / df(u);
      if (!(step > 0.0)) break;
      u -= step;
    }
    return u;
  }
};

} // namespace mdrmap
