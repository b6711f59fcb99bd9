#pragma once
// The power law f(r) = A r^n (n >= 1, A > 0), MDR image g(x) = kappa_n A |x|^n.
// n = 2 is the parabola of R = 1/(2A) (its stationary states are the
// parabola's); n = 1 is a cone's image, n < 2 makes g'' singular at x = 0.
#include <array>
#include <limits>

#include "core/model/shapes/power_law.hpp"
#include "core/model/shapes/shape_param.hpp"

namespace mdrmap {

struct Power {
  double n = 0.0; ///< exponent, >= 1
  double A = 0.0; ///< coefficient of f(r) = A r^n, > 0

  static constexpr const char* name = "power";
  static constexpr std::array<ShapeParam<Power>, 2> parameters() {
    return {{{"n", "N", Dim::Number, 1.0, true, 100.0, true,
              "exponent of the power-law profile f(r) = A r^n (--profile power)", &Power::n},
             {"A", "A", Dim::Number, 0.0, false, std::numeric_limits<double>::infinity(), true,
              "coefficient of the power-law profile f(r) = A r^n, in length^(1-n) (--profile "
              "power)",
              &Power::A}}};
  }
  static constexpr const char* depth_radius_words =
      "with the profile's n and A gives a contact radius a1 = ";
  static constexpr const char* load_radius_words =
      "with G and the profile's n and A gives a Hertz radius a0 = ";
  static constexpr const char* coefficient_option = "A";
  static constexpr const char* coefficient_words = "kappa_n A = ";

  PowerImage image() const { return {mdr_kappa(n) * A, n}; }
  /// g = c x^2: n = 2 (the stationary states take the parabola's closed forms).
  bool quadratic() const { return n == 2.0; }
  /// The cone's closed-form edge under load (not taken for n = 1).
  bool linear() const { return false; }
};

} // namespace mdrmap
