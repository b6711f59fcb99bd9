#pragma once
// Stationary sliding of a material with a relaxation spectrum (core/model/rheology.hpp):
// the long-term spring G, a parallel dashpot of time tau and Maxwell branches
// (G_k, tau_k), every time shifted by aT. Closed forms; the derivation is in
// docs/design.md ("Materials with a relaxation spectrum").
//
// Frame and conventions as analytic.hpp: contact [-a1, a2] in the indenter's
// frame, leading edge -a1 = -sqrt(R d), material entering there undeformed and
// moving towards +x at w; F_x = integral of p (-g'), positive when it resists.
// With s = x + a1 the distance from the leading edge and lambda_k = w tau_k,
// the branch stress in contact is
//   u - q_k = (2 lambda_k / R) [ (a1 + lambda_k)(1 - exp(-s/lambda_k)) - s ],
// the pressure p(x) = 4 [ G h - 2 G w tau x / R + sum_k G_k (u - q_k) ] is
// concave in x, positive at -a1 (zero there with tau = 0, rising), positive at
// x = 0 and negative at x = a1 for w > 0: a2 is its one zero in (0, a1].
// Behind a2 the free surface never touches the indenter again (see the .cpp).
#include "core/model/case.hpp"
#include "core/model/state.hpp"

namespace mdrmap {

/// Stationary state at velocity w >= 0 at the case's fixed depth d: FN, Fx,
/// mu, a2, d, a1. w = 0 is the elastic contact of the long-term modulus G
/// (a2 = a1, Fx = 0); N = 0 is analytic::stationary.
State spectrum_stationary(const Case& c, double w);

/// Depth d of stationary sliding at w under the case's load F0: the one root
/// of FN(d) = F0 (FN increases strictly with d).
double spectrum_stationary_depth(const Case& c, double w);

/// The stationary state at w under F0 (FN = F0 to rounding), d and a1 filled.
State spectrum_stationary_load(const Case& c, double w);

} // namespace mdrmap
