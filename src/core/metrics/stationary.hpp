#pragma once
// Stationary sliding of any case, whatever its model: the one place that
// picks the closed form for the case's loading and rheology (with its
// relaxation times shifted by aT). Events, maps and the CLI ask here.
#include "core/model/case.hpp"
#include "core/model/state.hpp"

namespace mdrmap {

/// The stationary state at velocity w >= 0: at the case's fixed depth, or
/// under its load F0 (d and a1 filled); the Kelvin closed forms
/// (analytic.hpp, load_stationary.hpp) for the Kelvin foundation, those of
/// spectrum_stationary.hpp for a spectrum; for the cone and power profiles
/// those of profile_stationary.hpp.
State stationary_state(const Case& c, double w);

/// The depth of stationary sliding at w > 0 under the case's load F0:
/// spectrum_stationary_depth for the parabola (the Kelvin foundation its
/// N = 0 case), profile_stationary_depth for the other profiles; the times as
/// the case gives them (a solver passes its shifted case).
double stationary_load_depth(const Case& c, double w);

} // namespace mdrmap
