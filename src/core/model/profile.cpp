#include "core/model/profile.hpp"

#include <cmath>

#include <boost/math/constants/constants.hpp>

#include "core/model/case.hpp"

namespace mdrmap {
namespace {

template <std::size_t... I> std::array<const char*, kShapeCount> names(std::index_sequence<I...>) {
  return {std::tuple_element_t<I, Shapes>::name...};
}

} // namespace

std::array<Profile, kShapeCount> all_profiles() {
  std::array<Profile, kShapeCount> all;
  for (std::size_t i = 0; i < kShapeCount; ++i)
    all[i] = Profile::at(i);
  return all;
}

const char* profile_name(Profile p) {
  static const std::array<const char*, kShapeCount> n =
      names(std::make_index_sequence<kShapeCount>());
  return n[p.index()];
}

Profile parse_profile(const std::string& name) {
  std::string all;
  for (const Profile p : all_profiles()) {
    if (name == profile_name(p)) return p;
    all += (all.empty() ? "" : ", ") + std::string(profile_name(p));
  }
  throw InvalidInput("profile", "must be one of " + all + "; got '" + name + "'");
}

double mdr_kappa(double n) {
  const double root_pi = boost::math::constants::root_pi<double>();
  // Gamma(n/2 + 1) / Gamma(n/2 + 1/2) as exp of the lgamma difference: finite for any n >= 1
  return root_pi * std::exp(std::lgamma(0.5 * n + 1.0) - std::lgamma(0.5 * n + 0.5));
}

} // namespace mdrmap
