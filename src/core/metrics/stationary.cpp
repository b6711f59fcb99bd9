#include "core/metrics/stationary.hpp"

#include "core/metrics/analytic.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/metrics/profile_stationary.hpp"
#include "core/metrics/spectrum_stationary.hpp"

namespace mdrmap {
namespace {

State unshifted_stationary(const Case& c, double w) {
  if (!c.indenter.parabolic()) return profile_stationary(c, w);
  const bool load = c.loading.by_force();
  if (!c.rheology.kelvin())
    return load ? spectrum_stationary_load(c, w) : spectrum_stationary(c, w);
  return load ? stationary_under_load(c, w) : analytic::stationary(c, w);
}

} // namespace

double stationary_load_depth(const Case& c, double w) {
  return c.indenter.parabolic() ? spectrum_stationary_depth(c, w) : profile_stationary_depth(c, w);
}

State stationary_state(const Case& c, double w) {
  if (c.rheology.aT == 1.0) return unshifted_stationary(c, w);
  Case shifted = c;
  shifted.rheology = c.rheology.shifted();
  return unshifted_stationary(shifted, w);
}

} // namespace mdrmap
