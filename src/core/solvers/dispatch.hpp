#pragma once
// The solver dispatch: which solver handles which case, and run_case.
#include <string>

#include "core/model/case.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/checked_case.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

/// The solvers a user picks: auto; exact, the continuum oracle and the Kelvin
/// fast path at fixed depth; row, the element row of every case (any
/// rheology, N = 0 branches too, any profile, depth or load); baseline, the
/// fixed-step brute-force check of every case. Auto also runs kelvin_load
/// (the Kelvin foundation under load, core/solvers/load.hpp), which is not
/// picked by name.
enum class SolverKind { Auto, Exact, Row, Baseline };

/// Every kind, in the order of the help text.
inline constexpr SolverKind kSolverKinds[] = {SolverKind::Auto, SolverKind::Exact, SolverKind::Row,
                                              SolverKind::Baseline};

/// Parses "auto", "exact", "row", "baseline", and "spectrum" as the old name
/// of row; throws InvalidInput("solver") for anything else, with a line of its
/// own for the retired "mdr" saying what to use.
SolverKind parse_solver(const std::string& name);
/// The solver's name as parse_solver takes it and RunInfo::solver reports it.
const char* solver_name(SolverKind k);

/// What a case asks of a solver: its loading, whether its rheology has
/// Maxwell branches (a relaxation spectrum) beyond the Kelvin element, and
/// its indenter profile.
struct ModelNeeds {
  bool by_force = false;                     ///< load control (else a fixed depth)
  bool spectrum = false;                     ///< Maxwell branches (else the Kelvin foundation)
  Profile profile = Profile::of<Parabola>(); ///< the indenter's profile
};
ModelNeeds model_needs(const Case& c);

/// Whether run_case solves cases with these needs with `kind`: exact the
/// Kelvin foundation under the parabola at fixed depth only; auto, row and
/// baseline every case. run_case refuses the others with InvalidInput naming
/// "profile" (the indenter), "solver" (the loading) or "prony" (the spectrum).
bool solver_handles(SolverKind kind, const ModelNeeds& needs);
/// The same for a loading alone, on the Kelvin foundation.
inline bool solver_handles(SolverKind kind, bool by_force) {
  return solver_handles(kind, ModelNeeds{by_force, false, Profile::of<Parabola>()});
}

/// Runs one case (its relaxation times shifted by aT). `Auto` picks the
/// cheapest solver that handles the case and meets rtol: on the Kelvin
/// parabola exact at fixed depth and kelvin_load under load; row otherwise.
/// Every solver charges its work to `control`: throws CaseAbandoned when the
/// case needs more than its budget (or, for baseline, cannot meet rtol at its
/// fixed resolution), Interrupted when its stop flag is set.
RunResult run_case(const CheckedCase& c, SolverKind kind, double rtol,
                   const RunControl& control = RunControl{});

} // namespace mdrmap
