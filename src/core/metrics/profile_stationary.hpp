#pragma once
// Stationary sliding of any indenter profile g(x) = c |x|^n (core/model/profile.hpp)
// on the Kelvin foundation and on a relaxation spectrum, at fixed depth and
// under load (docs/design.md, "Indenter profiles"). The parabola (and the
// power law with n = 2) is the closed form of analytic.hpp / load_stationary.hpp /
// spectrum_stationary.hpp, on a parabola of radius 1/c; the others:
//
//   Kelvin   p = 4G (h - L g'), h = d - g, L = w tau; the trailing edge a2 is
//            the root of a1^n - a2^n = L n a2^(n-1) in [0, a1] (the cone:
//            a2 = max(a1 - L, 0), the contact ends at the tip once L >= a1),
//            and with D = a1^n - a2^n
//              F_N = 4 G c [ n/(n+1) a1^(n+1) + a2 (a1^n - a2^n/(n+1)) + L D ]
//              F_x = 4 G c^2 [ D^2/2 + L n^2 (a1^(2n-1) + a2^(2n-1)) / (2n-1) ]
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
