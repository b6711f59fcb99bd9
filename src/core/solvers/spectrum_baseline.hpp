#pragma once
// The brute-force counterpart of the spectrum solver, deliberately plain and
// first order (a generalisation of baseline.hpp): elements laid over the whole
// travel path, one fixed step dt = dx / (largest velocity), starting from an
// undeformed foundation, contact decided at step ends, raw element sums. Each
// branch relaxes towards the element's depression at the step end,
// q_k <- u + (q_k - u) exp(-dt/tau_k); a free element's u solves its
// force balance implicitly, G u + G tau (u - u_old)/dt + sum G_k (u - q_k) = 0
// with those q_k: stable for any dt, tau_k and tau. Any indenter profile
// (core/model/profile.hpp): an element in contact follows h = d - g(x), the
// contact spans [-a1, a1] at most, g(a1) = d.
#include "core/model/case.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/checked_case.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

struct SpectrumBaselineOptions {
  double cells_per_a1 = 100;      ///< a1/dx
  double spinup_travel = 4.0;     ///< travel before t = 0, in a1 (>= 2.5)
  double steps_per_cell = 1.0;    ///< dt = dx / (steps_per_cell * largest velocity)
  long max_elements = 20'000'000; ///< refuse scenes that would need more
  bool estimate_error = true;     ///< run a half-resolution companion for error_estimate
  /// Work budget and stop flag (nullptr: the default budget, no stop flag).
  const RunControl* control = nullptr;
};

/// Under load control (c.loading.by_force()) each fixed step solves its end
/// depth from F_N = F0 (the dashpot sees the backward difference of d), the
/// spin-up starts at the stationary depth under load and balances the load too.
/// The case was checked where it was made (CheckedCase), not again here.
RunResult run_spectrum_baseline(const CheckedCase& c, const SpectrumBaselineOptions& o);

} // namespace mdrmap
