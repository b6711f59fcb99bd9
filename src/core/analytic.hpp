#pragma once
// The seed paper's estimates, with the errata of DESIGN.md corrected.
//
// Sign convention: F_x = integral of p(x) * (-g'(x)), positive when it resists
// the motion. Every formula is written in a cancellation-free form; the
// comments give the paper's equation it replaces.
#include "core/scene.hpp"

namespace mdrmap {

/// Contact forces, friction coefficient and trailing edge at one instant.
struct State {
  double FN = 0.0;
  double Fx = 0.0;
  double mu = 0.0;
  double a2 = 0.0;
};

namespace analytic {

/// Leading edge a1 = sqrt(R d).
double a1(const Scene& s);

/// Stationary trailing edge at velocity w, eq. (7) in the form
/// a2 = R d / (sqrt(w^2 tau^2 + R d) + w tau), which keeps every digit.
double a2_stationary(const Scene& s, double w);

/// a1 - a2_stationary(w) without cancellation: 2 a1 L / (a1 + L + sqrt(L^2 + a1^2)), L = w tau.
double a1_minus_a2_stationary(const Scene& s, double w);

/// Forces of the contact set [-a1, a2] whose elements all follow the indenter
/// at velocity w: corrected eqs. (9) and (10),
///   F_N = 4G/R [ 2/3 a1^3 + a1^2 a2 - a2^3/3 + w tau (a1^2 - a2^2) ],
///   F_x = 8G/R^2 [ (a1^2 - a2^2)^2 / 4 + 2 w tau/3 (a1^3 + a2^3) ].
/// (a1^2 = R d turns the paper's d-terms into these; both brackets are sums of
/// non-negative terms for 0 <= a2 <= a1.) `a1_minus_a2` is passed separately so
/// callers that know it accurately do not lose digits.
State contact_forces(const Scene& s, double a2, double a1_minus_a2, double w);

/// Stationary state at velocity w: eq. (7) with corrected (9), (10).
State stationary(const Scene& s, double w);

/// Limits for v -> infinity (a2 -> 0): eqs. (12), (13) and their ratio.
double FN_inf(const Scene& s);
double Fx_inf(const Scene& s);
/// Eq. (14): mu -> (4/3) sqrt(d/R) as v tau / a1 -> infinity.
double mu_inf(const Scene& s);
/// Right after a drop v -> infinity to v1 -> 0: mu -> (3/4) sqrt(d/R).
double mu_post_drop_limit(const Scene& s);

/// State just after the step (t = 0+). For a decrease (v1 < v) the contact set
/// is still the one at v and its elements move at v1: corrected eqs. (15), (16).
/// For an increase the elements between a2(v1) and a2(v) detach at once: the
/// state is the stationary state at v1.
State jump(const Scene& s);

/// Start-stop limit (v -> infinity, v1 -> 0): a2(t) = a1 sqrt(1 - exp(-t/tau)).
double a2_start_stop(const Scene& s, double t);

} // namespace analytic
} // namespace mdrmap
