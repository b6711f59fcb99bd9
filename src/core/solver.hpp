#pragma once
// Common result types and the solver dispatch.
#include <string>
#include <vector>

#include "core/analytic.hpp"
#include "core/case.hpp"
#include "core/run_control.hpp"
#include "core/state.hpp"

namespace mdrmap {

/// What a run cost and how accurate it believes it is.
struct RunInfo {
  std::string solver;          ///< "exact", "mdr" or "baseline"
  double rtol = 0.0;           ///< requested tolerance
  double error_estimate = 0.0; ///< estimated case error (docs/design.md, "Error metric")
  double cells_per_a1 = 0.0;   ///< resolution a1/dx of the final run (0 for exact)
  long elements = 0;           ///< elements held in memory at once (peak, final run)
  long steps = 0;              ///< time steps taken, all runs included
  long element_updates = 0;    ///< element state updates, all runs included
  long root_solves = 0;        ///< scalar root solves (exact solver)
  int refinements = 0;         ///< resolutions tried by the error control
};

struct RunResult {
  Series series;
  RunInfo info;
};

enum class SolverKind { Auto, Exact, Mdr, Baseline };

/// Parses "auto", "exact", "mdr", "baseline"; throws InvalidInput("solver").
SolverKind parse_solver(const std::string& name);
const char* solver_name(SolverKind k);

/// Throws InvalidInput("rtol") unless 0 < rtol <= 0.1.
void validate_rtol(double rtol);

/// Whether run_case solves cases of this loading with `kind`: under a
/// prescribed normal force (by_force) or at a fixed depth. It refuses the
/// others (InvalidInput("solver")): exact solves depth control only.
bool solver_handles(SolverKind kind, bool by_force);

/// Runs one case. `Auto` picks the cheapest solver that meets rtol: at fixed
/// depth that is always the continuum solver. Every solver charges its work to
/// `control`: throws CaseAbandoned when the case needs more than its budget
/// (or, for mdr, cannot meet rtol), Interrupted when its stop flag is set.
RunResult run_case(const CheckedCase& c, SolverKind kind, double rtol,
                   const RunControl& control = RunControl{});
/// The same for a case not yet checked: validates it first (InvalidInput).
RunResult run_case(const Case& c, SolverKind kind, double rtol,
                   const RunControl& control = RunControl{});

} // namespace mdrmap
