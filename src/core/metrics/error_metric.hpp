#pragma once
// The error contract (docs/design.md, "Error metric").
#include "core/model/case.hpp"
#include "core/model/state.hpp"

namespace mdrmap {

struct CaseError {
  double FN = 0, Fx = 0, mu = 0, a2 = 0;
  double d = 0; ///< under load control: the depth, by its largest magnitude
  double max() const;
};

/// Per quantity q in FN, Fx, mu: max_k |q_k - ref_k| / max_k |ref_k|;
/// for a2: max_k |a2_k - ref_k| / a1. Series must have equal sizes.
CaseError case_error(const Series& run, const Series& ref, double a1);

/// The same metric where a reference that is identically zero (tau = 0:
/// F_x = mu = 0) is measured on its natural scale (max|F_N| sqrt(d/R) for
/// F_x, sqrt(d/R) for mu; another profile's Scales::friction for sqrt(d/R))
/// instead of dividing by zero. With floor_rel > 0 the
/// F_x and mu denominators are also at least floor_rel times those scales:
/// comparing two runs whose F_x is rounding noise over zero then stays
/// meaningful (each element term carries ~1e-16 of the scale).
///
/// Under load control (c.loading.by_force()) the contract differs: F_N by
/// max_k |F_N,k - F0| / F0 (the run against the prescribed force, not the
/// reference), d, F_x and mu by their largest reference magnitude, a1 and a2
/// (both in `a2`) by the Hertz radius a0.
CaseError case_error(const Series& run, const Series& ref, const Case& c, double floor_rel = 0.0);

/// The case's friction scale: sqrt(d/R) for the parabola (under load with
/// the Hertz depth a0^2/R), another profile's Scales::friction.
double friction_scale(const Case& c);

/// A friction coefficient below this is zero to a tribologist: resolved to
/// rtol times it, not to rtol of itself.
inline constexpr double kNegligibleFriction = 1e-10;

/// mu = F_x / F_N where F_x integrates p g' over both faces of the contact:
/// its rounding error is a few eps times the friction scale, whatever mu is
/// (a needle cone, or v tau/a1 far from 1, gives a mu 1e-15 of its scale).
/// True when |mu| up to `mu_max` is resolved to `rtol` above that floor:
/// max(mu_max, kNegligibleFriction) rtol >= 4 eps friction_scale(c).
bool friction_resolved(const Case& c, double mu_max, double rtol);

} // namespace mdrmap
