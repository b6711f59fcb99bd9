#pragma once
// Stationary sliding under a prescribed normal force (docs/design.md, "Load
// control"): the fixed-depth stationary state with the depth d the root of
// F_N(d, w) = F0.
//
// In the Hertz scales of F0 (a0 from F0 = 16/3 G a0^3 / R, d0 = a0^2 / R,
// zeta0 = w tau / a0) the leading edge alpha = a1 / a0 solves one equation,
//   (alpha + beta)^2 (2 alpha - beta) / 3 + zeta0 (alpha^2 - beta^2) = 4/3,
// beta = a2 / a0 = alpha^2 / (sqrt(zeta0^2 + alpha^2) + zeta0), every term
// non-negative and the left side increasing in alpha: one root, found to
// rounding for any zeta0 and load. Limits: alpha -> 1 (Hertz) as zeta0 -> 0,
// alpha -> sqrt(4 / (3 zeta0)) as zeta0 -> infinity.
#include "core/model/case.hpp"
#include "core/model/state.hpp"

namespace mdrmap {

/// a1 / a0 of stationary sliding at zeta0 = w tau / a0 under load.
double stationary_alpha(double zeta0);

/// Depth d of stationary sliding at w under the case's load F0.
double stationary_depth(const Case& c, double w);

/// The stationary state at w under F0 (F_N = F0 to rounding), d and a1 filled.
State stationary_under_load(const Case& c, double w);

/// The case at fixed depth d (F0 cleared): what the fixed-depth formulas take.
Case at_depth(const Case& c, double d);

} // namespace mdrmap
