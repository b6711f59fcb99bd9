#pragma once
// The cone: beta the angle between its surface and the plane, f(r) =
// tan(beta) r (n = 1), MDR image g(x) = (pi/2) tan(beta) |x|. Its slope jumps
// at the apex x = 0 (the element row integrates on either side of it).
#include <array>

#include <boost/math/constants/constants.hpp>

#include "core/model/shapes/power_law.hpp"
#include "core/model/shapes/shape_param.hpp"

namespace mdrmap {

struct Cone {
  double beta = 0.0; ///< angle of the surface to the plane, degrees, (0, 90)

  static constexpr const char* name = "cone";
  static constexpr std::array<ShapeParam<Cone>, 1> parameters() {
    return {{{"beta", "DEG", Dim::Number, 0.0, false, 90.0, false,
              "angle between the cone's surface and the plane, in degrees (--profile cone)",
              &Cone::beta}}};
  }
  static constexpr const char* depth_radius_words =
      "with the profile's beta gives a contact radius a1 = ";
  static constexpr const char* load_radius_words =
      "with G and the profile's beta gives a Hertz radius a0 = ";
  static constexpr const char* coefficient_option = "beta";
  static constexpr const char* coefficient_words = "(pi/2) tan(beta) = ";

  PowerImage image() const {
    return {boost::math::constants::half_pi<double>() *
                std::tan(beta * boost::math::constants::degree<double>()),
            1.0};
  }
  /// g = c x^2 (the stationary states take the parabola's closed forms).
  bool quadratic() const { return false; }
  /// g = c |x|: the closed-form edge under load on the Kelvin foundation.
  bool linear() const { return true; }
};

} // namespace mdrmap
