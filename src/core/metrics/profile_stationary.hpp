#pragma once
// Stationary sliding of any indenter's image g (core/model/profile.hpp, a
// shape of core/model/shapes/) on the Kelvin foundation and on a relaxation
// spectrum, at fixed depth and under load (docs/design.md, "Indenter
// profiles"). The shapes whose g = c x^2 (the parabola, the power law with
// n = 2) take the closed form of analytic.hpp / load_stationary.hpp /
// spectrum_stationary.hpp, on a parabola of radius 1/c; the others work in x
// with what the shape gives (g, g', g(a1) - g(a1 - delta) without
// cancellation, the integrals of g and g'^2):
//
//   Kelvin   p = 4G (h - L g'), h = d - g, L = w tau; the trailing edge a2 is
//            the root of g(a1) - g(a2) = L g'(a2) in [0, a1] (the cone:
//            a2 = max(a1 - L, 0), the contact ends at the tip once L >= a1),
//            and with D = g(a1) - g(a2), I = int_0 g, J = int_0 g'^2
//              F_N = 4 G [ d (a1 + a2) - I(a1) - I(a2) + L D ]
//              F_x = 4 G [ D^2/2 + L (J(a1) + J(a2)) ]
//            (for g = c |x|^n: F_N = 4 G c [ n/(n+1) a1^(n+1)
//            + a2 (a1^n - a2^n/(n+1)) + L D ], F_x = 4 G c^2 [ D^2/2
//            + L n^2 (a1^(2n-1) + a2^(2n-1)) / (2n-1) ] with D/c)
//   spectrum p = 4 [ G (h - L g') + sum_k G_k r_k ], the branch stress
//            r_k(x) = int_{-a1}^{x} exp(-(x - x')/lambda_k) (-g'(x')) dx',
//            lambda_k = w tau_k: tanh-sinh quadrature (split at the tip x = 0,
//            where g' is not smooth), a2 the zero of p in [0, a1]
//   load     the one root a1 of F_N = F0 (the cone on the Kelvin foundation:
//            closed form)
//
// Frame and conventions as analytic.hpp: contact [-a1, a2] in the indenter's
// frame, F_x = integral of p (-g'), positive when it resists.
#include "core/model/case.hpp"
#include "core/model/state.hpp"

namespace mdrmap {

/// Stationary state at velocity w >= 0 of any profile, any rheology, at the
/// case's fixed depth or under its load (d and a1 filled): what
/// stationary_state (stationary.hpp) asks for a profile other than the
/// parabola. Relaxation times as given (the caller shifts them).
State profile_stationary(const Case& c, double w);

/// The depth of stationary sliding at w under the case's load F0.
double profile_stationary_depth(const Case& c, double w);

namespace profile_detail {
/// profile_stationary at fixed depth through the general path only (no
/// parabola closed form, the spectrum by quadrature even with no branches'
/// closed form available): exposed for its test against the parabola.
State general_stationary(const Case& c, double w);
} // namespace profile_detail

} // namespace mdrmap
