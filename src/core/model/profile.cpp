#include "core/model/profile.hpp"

#include <boost/math/constants/constants.hpp>

#include "core/model/case.hpp"

namespace mdrmap {

const char* profile_name(Profile p) {
  switch (p) {
  case Profile::Parabola:
    return "parabola";
  case Profile::Cone:
    return "cone";
  case Profile::Power:
    return "power";
  }
  return "?";
}

Profile parse_profile(const std::string& name) {
  for (const Profile p : kProfiles)
    if (name == profile_name(p)) return p;
  throw InvalidInput("profile", "must be one of parabola, cone, power; got '" + name + "'");
}

double mdr_kappa(double n) {
  const double root_pi = boost::math::constants::root_pi<double>();
  // Gamma(n/2 + 1) / Gamma(n/2 + 1/2) as exp of the lgamma difference: finite for any n >= 1
  return root_pi * std::exp(std::lgamma(0.5 * n + 1.0) - std::lgamma(0.5 * n + 0.5));
}

double Indenter::exponent() const {
  switch (profile) {
  case Profile::Parabola:
    return 2.0;
  case Profile::Cone:
    return 1.0;
  case Profile::Power:
    return n;
  }
  return 0.0;
}

double Indenter::coefficient() const {
  switch (profile) {
  case Profile::Parabola:
    return 1.0 / R;
  case Profile::Cone:
    return boost::math::constants::half_pi<double>() *
           std::tan(beta * boost::math::constants::degree<double>());
  case Profile::Power:
    return mdr_kappa(n) * A;
  }
  return 0.0;
}

double Indenter::elastic_force(double a, double G) const {
  if (parabolic()) return 16.0 / 3.0 * G * a * a * a / R;
  const double m = exponent();
  return 8.0 * G * coefficient() * m / (m + 1.0) * std::pow(a, m + 1.0);
}

double Indenter::hertz_radius(double F, double G) const {
  if (parabolic()) return std::cbrt(3.0 * F * R / (16.0 * G));
  const double m = exponent();
  return std::pow(F * (m + 1.0) / (8.0 * G * coefficient() * m), 1.0 / (m + 1.0));
}

} // namespace mdrmap
