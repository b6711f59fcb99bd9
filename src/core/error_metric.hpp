#pragma once
// The error contract (docs/design.md, "Error metric").
#include "core/solver.hpp"

namespace mdrmap {

struct CaseError {
  double FN = 0, Fx = 0, mu = 0, a2 = 0;
  double max() const;
};

/// Per quantity q in FN, Fx, mu: max_k |q_k - ref_k| / max_k |ref_k|;
/// for a2: max_k |a2_k - ref_k| / a1. Series must have equal sizes.
CaseError case_error(const Series& run, const Series& ref, double a1);

/// The same metric where a reference that is identically zero (tau = 0:
/// F_x = mu = 0) is measured on its natural scale (max|F_N| sqrt(d/R) for
/// F_x, sqrt(d/R) for mu) instead of dividing by zero. With floor_rel > 0 the
/// F_x and mu denominators are also at least floor_rel times those scales:
/// comparing two runs whose F_x is rounding noise over zero then stays
/// meaningful (each element term carries ~1e-16 of the scale).
CaseError case_error(const Series& run, const Series& ref, const Case& c, double floor_rel = 0.0);

} // namespace mdrmap
