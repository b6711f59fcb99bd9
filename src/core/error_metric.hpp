#pragma once
// The error contract of DESIGN.md section 2.
#include "core/solver.hpp"

namespace mdrmap {

struct CaseError {
  double FN = 0, Fx = 0, mu = 0, a2 = 0;
  double max() const;
};

/// Per quantity q in FN, Fx, mu: max_k |q_k - ref_k| / max_k |ref_k|;
/// for a2: max_k |a2_k - ref_k| / a1. Series must have equal sizes.
CaseError case_error(const Series& run, const Series& ref, double a1);

/// The same metric, with the denominators of F_x and mu floored at 1e-10 of
/// their natural scales (max|F_N| sqrt(d/R) and sqrt(d/R)). Where the
/// reference is identically zero (tau = 0: F_x = mu = 0) the plain relative
/// error is rounding noise over zero: each element term of F_x carries a
/// rounding error ~1e-16 F_N sqrt(d/R). The floor is far below any physical
/// F_x of the hard set (smallest: ~1e-8 G d^2 at v tau / a1 = 1e-4).
CaseError case_error(const Series& run, const Series& ref, const Scene& s);

} // namespace mdrmap
