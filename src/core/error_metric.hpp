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

} // namespace mdrmap
