#pragma once
// The spectrum solver: the MDR element row for any relaxation spectrum
// (core/model/rheology.hpp: long-term G, parallel dashpot tau >= 0, Maxwell
// branches G_k, tau_k), at fixed depth. Every element moves exactly (an
// exponential per branch in contact, the free system in its modes), its
// contact switches located in time; the window [-a1, a1] moves with the
// indenter (memory independent of travel); the resolution a1/dx is refined
// until a half-resolution companion run agrees within rtol. Under load control
// the depth is the unknown of each step. Runs N = 0
// (Kelvin) cases too, as a check of the specialised solvers. Expects a
// shifted case (aT folded in; an unshifted one is shifted here).
#include "core/model/case.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/checked_case.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

struct SpectrumOptions {
  double rtol = 1e-3;         ///< target case error; sets dx when cells_per_a1 == 0, and
                              ///< the trailing edge is located to 1e-2 rtol a1 always
  double cells_per_a1 = 0.0;  ///< fixed resolution a1/dx (0: chosen from rtol, refined)
  double phase = 0.5;         ///< element offset at t = 0, in cells
  double sub_travel = 0.25;   ///< largest travel of a sub-step, in a1 (switch detection)
  bool estimate_error = true; ///< run the half-resolution companion for error_estimate
  /// Under load, a segment that has reached its stationary state keeps it
  /// without further steps (spectrum_load_run.cpp, LoadRun::Watch); false: steps on.
  bool keep_stationary = true;
  /// The parabola's element updates composed over each step's sub-steps
  /// (spectrum_composed.cpp); false: sub-step by sub-step (the tests compare
  /// the two).
  bool composed_steps = true;
  /// Work budget and stop flag (nullptr: the default budget, no stop flag).
  const RunControl* control = nullptr;
};

/// Under load control (c.loading.by_force()) the depth is free: each time step
/// ends at the depth that balances F_N = F0 (spectrum_load_run.cpp, "load control"),
/// the run starts from stationary sliding at v0 under F0, and Series d, a1
/// are filled. Throws CaseAbandoned when the estimate stays above rtol or past
/// the work budget. The case was checked where it was made (CheckedCase);
/// only the options are checked here (rtol, sub-travel, cells-per-a1).
RunResult run_spectrum(const CheckedCase& c, const SpectrumOptions& o);

} // namespace mdrmap
