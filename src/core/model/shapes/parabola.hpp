#pragma once
// The parabola f(r) = r^2 / 2R, MDR image g(x) = x^2 / R: the seed's indenter.
// Its arithmetic is the seed's (x * x / R, sqrt(R) sqrt(d)), bit for bit: the
// seed's results are compared so.
#include <array>
#include <cmath>
#include <limits>

#include "core/model/shapes/shape_param.hpp"

namespace mdrmap {

struct Parabola {
  double R = 0.0; ///< radius of curvature, > 0

  static constexpr const char* name = "parabola";
  static constexpr std::array<ShapeParam<Parabola>, 1> parameters() {
    return {{{"R", "R", Dim::Length, 0.0, false, std::numeric_limits<double>::infinity(), true,
              "radius of curvature of the parabolic indenter (--profile parabola)", &Parabola::R}}};
  }
  /// Validation's words before a contact radius it refuses.
  static constexpr const char* depth_radius_words = "with R gives a contact radius sqrt(R d) = ";
  static constexpr const char* load_radius_words = "with R and G gives a Hertz radius a0 = ";
  /// The option blamed for a coefficient of g outside the row's range (none:
  /// the parabola's is checked through its scales).
  static constexpr const char* coefficient_option = nullptr;
  static constexpr const char* coefficient_words = "";

  double exponent() const { return 2.0; }
  double coefficient() const { return 1.0 / R; }
  /// g = c x^2 (the stationary states take the parabola's closed forms).
  bool quadratic() const { return true; }
  /// The cone's closed-form edge under load on the Kelvin foundation.
  bool linear() const { return false; }
  double g(double x) const { return x * x / R; }
  double slope(double x) const { return 2.0 * x / R; }
  double contact_radius(double d) const { return std::sqrt(R) * std::sqrt(d); }
  /// The element-row solvers' contact radius: sqrt(R d) (theirs since the seed).
  double leading_edge(double d) const { return std::sqrt(R * d); }
  double elastic_force(double a, double G) const { return 16.0 / 3.0 * G * a * a * a / R; }

  // What the element row asks (core/model/shapes/power_law.hpp tells each).
  const Parabola& image() const { return *this; }
  double apex_slope() const { return 0.0; }
  bool smooth_apex() const { return true; }
  bool exact_forcing() const { return true; }
  double depth(double x, double d) const { return d - x * x / R; }
  /// g(a) - g(a - delta) (0 <= delta <= a) without cancellation.
  double drop(double a, double delta) const { return delta * (2.0 * a - delta) / R; }
  double lift(double x, double w) const { return 2.0 * x * w / R; }
  bool inside(double x, double d) const { return x * x <= R * d; }
  double curvature(double) const { return 2.0 / R; }
  double side_slope(double x, int) const { return slope(x); }
  double radius_rate(double a, double d) const { return a / (2.0 * d); }
  double integral_g(double t) const { return t * t * t / (3.0 * R); }
  double integral_slope_squared(double t) const { return 4.0 * t * t * t / (3.0 * R * R); }
  /// The Taylor form, exact.
  template <class Out, class Path> Out forcing(double x, double w, double, const Path& q) const {
    return {depth(x, q.d), q.r - lift(x, w), q.k - w * w / R};
  }
  /// d ln F / d ln d of the elastic force: F ~ d^(3/2).
  double force_exponent(double) const { return 1.5; }
  /// No bound on the contact radius.
  double max_radius() const { return std::numeric_limits<double>::infinity(); }
  double hertz_radius(double F, double G) const { return std::cbrt(3.0 * F * R / (16.0 * G)); }
};

} // namespace mdrmap
