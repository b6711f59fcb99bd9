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
  double exponent() const { return 1.0; }
  double coefficient() const { return image().c; }
  bool quadratic() const { return false; }
  bool linear() const { return true; }
  double g(double x) const { return image().g(x); }
  double slope(double x) const { return image().slope(x); }
  double contact_radius(double d) const { return image().contact_radius(d); }
  double leading_edge(double d) const { return contact_radius(d); }
  double elastic_force(double a, double G) const { return image().elastic_force(a, G); }
  double hertz_radius(double F, double G) const { return image().hertz_radius(F, G); }
};

} // namespace mdrmap
