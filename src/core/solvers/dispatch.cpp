#include "core/solvers/dispatch.hpp"

#include <algorithm>
#include <cmath>

#include "core/metrics/error_metric.hpp"
#include "core/model/row_limits.hpp"
#include "core/solvers/exact.hpp"
#include "core/solvers/load.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_baseline.hpp"

namespace mdrmap {

SolverKind parse_solver(const std::string& name) {
  for (const SolverKind k : kSolverKinds)
    if (name == solver_name(k)) return k;
  if (name == "spectrum") return SolverKind::Row; // its name before row
  if (name == "mdr")
    throw InvalidInput("solver", "mdr was retired: use row (the element row, which solves the "
                                 "Kelvin cases mdr solved) or auto");
  throw InvalidInput("solver", "must be one of auto, exact, row, baseline; got '" + name + "'");
}

const char* solver_name(SolverKind k) {
  switch (k) {
  case SolverKind::Auto:
    return "auto";
  case SolverKind::Exact:
    return "exact";
  case SolverKind::Row:
    return "row";
  case SolverKind::Baseline:
    return "baseline";
  }
  return "?";
}

void validate_rtol(double rtol) {
  if (!std::isfinite(rtol) || !(rtol > 0.0) || !(rtol <= 0.1))
    throw InvalidInput("rtol",
                       std::string("must be ") + kRtolAllowed + ", got " + format_number(rtol));
}

ModelNeeds model_needs(const Case& c) {
  return ModelNeeds{c.loading.by_force(), !c.rheology.kelvin(), c.indenter.profile};
}

bool solver_handles(SolverKind kind, const ModelNeeds& needs) {
  if (kind != SolverKind::Exact) return true; // auto, row and baseline: every case
  return !needs.by_force && !needs.spectrum && needs.profile == Profile::of<Parabola>();
}

namespace {

// The fixed-step baseline runs at one resolution and reports its estimate:
// like the adaptive solvers, it refuses a case whose estimate is above rtol
// (it was reported done with an estimate of 18 times rtol).
RunResult within_rtol(RunResult r, double rtol) {
  if (!(r.info.error_estimate <= rtol))
    throw CaseAbandoned(r.info.solver + ": the error estimate " +
                        format_number(r.info.error_estimate) + " is above rtol " +
                        format_number(rtol) +
                        " at its fixed resolution; the case cannot meet rtol with this solver "
                        "(use --solver auto or row)");
  return r;
}

// The brute-force check (core/solvers/spectrum_baseline.hpp) at a resolution
// from rtol: first order, its estimate is ~4/(a1/dx) on a step, so a1/dx =
// 5/rtol, within what a fixed-step run can afford.
RunResult run_baseline_check(const CheckedCase& c, double rtol, const RunControl& control) {
  SpectrumBaselineOptions o;
  o.cells_per_a1 = std::clamp(std::ceil(5.0 / rtol), 16.0, 4000.0);
  o.control = &control;
  return within_rtol(run_spectrum_baseline(c, o), rtol);
}

} // namespace

namespace {

/// Throws InvalidInput unless `kind` handles the case: "profile" for a
/// profile no solver takes, "prony" where the solver takes the Kelvin
/// foundation only, "solver" for the loading.
void require_handled(SolverKind kind, const Case& c) {
  const ModelNeeds needs = model_needs(c);
  if (solver_handles(kind, needs)) return;
  if (needs.profile != Profile::of<Parabola>())
    throw InvalidInput("profile", std::string("solver ") + solver_name(kind) +
                                      " solves the parabola only; this case's profile is " +
                                      profile_name(needs.profile) +
                                      ": use --solver auto, row or baseline");
  if (needs.spectrum)
    throw InvalidInput("prony", std::string("solver ") + solver_name(kind) +
                                    " solves the Kelvin foundation only (no Maxwell branches); "
                                    "this case has " +
                                    std::to_string(c.rheology.branches.size()) +
                                    ": use --solver auto, row or baseline");
  require_depth_control(c, solver_name(kind));
}

} // namespace

namespace {

// A stepping solver's mu carries the rounding of its friction integral (a few
// eps of the friction scale): a mu far below that scale is not within rtol of
// itself (a needle cone at v tau/a1 1e15 gave mu -2.2e-7 for 5.6e-5, with an
// estimate of 2.4e-4). The continuum solver's closed forms are not limited so.
RunResult friction_within_rounding(RunResult r, const Case& c, double rtol) {
  const bool elastic = c.rheology.kelvin() && c.rheology.tau == 0.0; // mu = 0 exactly
  if (elastic || r.info.solver == "exact") return r;
  double mu_max = std::abs(r.series.pre.mu);
  for (const double mu : r.series.mu)
    mu_max = std::max(mu_max, std::abs(mu));
  if (!friction_resolved(c, mu_max, rtol))
    throw CaseAbandoned(r.info.solver + ": |mu| reaches only " + format_number(mu_max) +
                        ", within the rounding of its friction integral (4 eps x the friction "
                        "scale " +
                        format_number(friction_scale(c)) + " / rtol " + format_number(rtol) +
                        "); a looser --rtol, or v tau/a1 nearer 1 (--v, --aT), resolves it");
  return r;
}

RunResult run_solver(const CheckedCase& checked, SolverKind kind, double rtol,
                     const RunControl& control);

} // namespace

RunResult run_case(const CheckedCase& given, SolverKind kind, double rtol,
                   const RunControl& control) {
  validate_rtol(rtol);
  require_handled(kind, given.get());
  // the Kelvin parabola asked of a row: its limits too (validate checked them
  // where the case needs the row anyway)
  if ((kind == SolverKind::Row || kind == SolverKind::Baseline) && !uses_element_row(given.get()))
    check_element_row(given.get());
  const CheckedCase& checked = given.get().rheology.aT != 1.0 ? given.shifted() : given;
  return friction_within_rounding(run_solver(checked, kind, rtol, control), checked.get(), rtol);
}

namespace {

RunResult run_solver(const CheckedCase& checked, SolverKind kind, double rtol,
                     const RunControl& control) {
  const Case& c = checked.get();
  if (kind == SolverKind::Baseline) return run_baseline_check(checked, rtol, control);
  if (kind == SolverKind::Row || (kind == SolverKind::Auto && uses_element_row(c))) {
    SpectrumOptions o;
    o.rtol = rtol;
    o.control = &control;
    return run_spectrum(checked, o);
  }
  if (c.loading.by_force()) { // auto on the Kelvin parabola under load: kelvin_load
    LoadOptions o;
    o.rtol = rtol;
    o.control = &control;
    return run_load(checked, o);
  }
  return run_exact(checked, rtol, control); // auto or exact, at fixed depth
}

} // namespace

} // namespace mdrmap
