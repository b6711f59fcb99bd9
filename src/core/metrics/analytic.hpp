#pragma once
// The seed paper's estimates, with its errata corrected (docs/design.md, "Errata").
//
// Sign convention: F_x = integral of p(x) * (-g'(x)), positive when it resists
// the motion. Every formula is written in a cancellation-free form; the
// comments give the paper's equation it replaces.
#include "core/model/case.hpp"
#include "core/model/state.hpp"

namespace mdrmap {

namespace analytic {

/// Leading edge a1 = sqrt(R d).
inline double a1(const Case& c) {
  return c.a1();
}

/// Stationary trailing edge at velocity w, eq. (7) in the form
/// a2 = R d / (sqrt(w^2 tau^2 + R d) + w tau), which keeps every digit.
double a2_stationary(const Case& c, double w);

/// a1 - a2_stationary(w) without cancellation: 2 a1 L / (a1 + L + sqrt(L^2 + a1^2)), L = w tau.
double a1_minus_a2_stationary(const Case& c, double w);

/// Forces of the contact set [-a1, a2] whose elements all follow the indenter
/// at velocity w: corrected eqs. (9) and (10),
///   F_N = 4G/R [ 2/3 a1^3 + a1^2 a2 - a2^3/3 + w tau (a1^2 - a2^2) ],
///   F_x = 8G/R^2 [ (a1^2 - a2^2)^2 / 4 + 2 w tau/3 (a1^3 + a2^3) ].
/// (a1^2 = R d turns the paper's d-terms into these; both brackets are sums of
/// non-negative terms for 0 <= a2 <= a1.) `a1_minus_a2` is passed separately so
/// callers that know it accurately do not lose digits.
State contact_forces(const Case& c, double a2, double a1_minus_a2, double w);

/// Stationary state at velocity w: eq. (7) with corrected (9), (10).
State stationary(const Case& c, double w);

/// Limits for v -> infinity (a2 -> 0) at velocity w: eqs. (12), (13).
double FN_inf(const Case& c, double w);
double Fx_inf(const Case& c, double w);
/// Eq. (14): mu -> (4/3) sqrt(d/R) as v tau / a1 -> infinity.
double mu_inf(const Case& c);
/// Right after a drop v -> infinity to v1 -> 0: mu -> (3/4) sqrt(d/R).
double mu_post_drop_limit(const Case& c);

/// State just after a change out of stationary sliding at v into w (the seed's
/// step, t = 0+). For a decrease (w < v) the contact set is still the one at v
/// and its elements move at w: corrected eqs. (15), (16). For an increase the
/// elements between a2(w) and a2(v) detach at once: the state is the
/// stationary state at w.
State jump(const Case& c, double v, double w);

/// Start-stop limit (v -> infinity, v1 -> 0): a2(t) = a1 sqrt(1 - exp(-t/tau)).
double a2_start_stop(const Case& c, double t);

/// Depth of the indenter surface below the undeformed foundation at x in
/// the indenter's frame: h(x) = d - g(x), written (a1 - x)(a1 + x)/R.
double depth_at(const Case& c, double x);

} // namespace analytic
} // namespace mdrmap
