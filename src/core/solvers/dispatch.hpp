#pragma once
// The solver dispatch: which solver handles which case, and run_case.
#include <string>

#include "core/model/case.hpp"
#include "core/solvers/result.hpp"
#include "core/solvers/run_control.hpp"

namespace mdrmap {

enum class SolverKind { Auto, Exact, Mdr, Baseline, Spectrum };

/// Every kind, in the order of the help text.
inline constexpr SolverKind kSolverKinds[] = {SolverKind::Auto, SolverKind::Exact, SolverKind::Mdr,
                                              SolverKind::Baseline, SolverKind::Spectrum};

/// Parses "auto", "exact", "mdr", "baseline", "spectrum"; throws
/// InvalidInput("solver").
SolverKind parse_solver(const std::string& name);
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

/// Whether run_case solves cases with these needs with `kind`. exact solves
/// depth control only; exact, mdr and baseline (and the load solvers they
/// dispatch to) the Kelvin foundation only; spectrum (the element row of any
/// rheology) every case, at fixed depth and under load, with or without
/// branches; auto every case. Only spectrum (and auto, which picks it) takes
/// the cone and power profiles; the others the parabola only. run_case
/// refuses the others with InvalidInput naming "profile" (the indenter),
/// "solver" (the loading) or "prony" (the spectrum).
bool solver_handles(SolverKind kind, const ModelNeeds& needs);
/// The same for a loading alone, on the Kelvin foundation.
inline bool solver_handles(SolverKind kind, bool by_force) {
  return solver_handles(kind, ModelNeeds{by_force, false, Profile::of<Parabola>()});
}

/// Runs one case (its relaxation times shifted by aT). `Auto` picks the
/// cheapest solver that handles the case and meets rtol: on the Kelvin
/// foundation the continuum solver at fixed depth and the load solver under
/// load; with a spectrum the spectrum solver. Every solver charges its work to
/// `control`: throws CaseAbandoned when the case needs more than its budget
/// (or, for mdr, cannot meet rtol), Interrupted when its stop flag is set.
RunResult run_case(const CheckedCase& c, SolverKind kind, double rtol,
                   const RunControl& control = RunControl{});
/// The same for a case not yet checked: validates it first (InvalidInput).
RunResult run_case(const Case& c, SolverKind kind, double rtol,
                   const RunControl& control = RunControl{});

} // namespace mdrmap
