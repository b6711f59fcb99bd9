#include "app/simulation.hpp"

#include <algorithm>
#include <chrono>

#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/solvers/exact.hpp"
#include "mdrmap/version.hpp"

namespace mdrmap::app {
namespace {

constexpr double kExactReferenceRtol = 1e-12;
/// Under load the reference is the load solver at rtol * factor, not below the floor.
constexpr double kLoadReferenceFactor = 1e-3;
constexpr double kLoadReferenceFloor = 1e-9;

/// For a solver other than the default: the case error against a reference.
/// At fixed depth the continuum solver at 1e-12; under load the default (load)
/// solver at a much tighter rtol (docs/design.md, "Error metric").
void add_reference_error(const CaseInput& a, const RunResult& res, SimulateRecord& rec) {
  if (!a.c.loading.by_force()) {
    if (rec.solver == "exact") return;
    const RunResult ref = run_exact(a.c, kExactReferenceRtol);
    rec.error_vs_exact = case_error(res.series, ref.series, a.c).max();
    return;
  }
  if (a.solver == SolverKind::Auto) return;
  rec.reference_rtol = std::max(a.rtol * kLoadReferenceFactor, kLoadReferenceFloor);
  const RunResult ref = run_case(a.c, SolverKind::Auto, rec.reference_rtol);
  rec.reference = ref.info.solver.empty() ? "auto" : ref.info.solver;
  rec.error_vs_exact = case_error(res.series, ref.series, a.c).max();
}

} // namespace

Simulation simulate(const CaseInput& in, const RunControl& control) {
  const auto start = std::chrono::steady_clock::now();
  RunResult res = run_case(in.c, in.solver, in.rtol, control);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  Simulation out;
  SimulateRecord& rec = out.record;
  rec.version = kVersion;
  rec.commit = kGitCommit;
  rec.solver = res.info.solver.empty() ? solver_name(in.solver) : res.info.solver;
  rec.rtol = in.rtol;
  rec.info = res.info;
  rec.wall_seconds = wall;
  rec.c = in.c;
  rec.events = event_metrics(in.c, res.series);
  add_reference_error(in, res, rec);
  out.series = std::move(res.series);
  return out;
}

std::vector<Field> event_fields(const EventMetrics& e) {
  return {
      {"t", e.t},
      {"w_before", e.w_before},
      {"w_after", e.w_after},
      {"mu_before", e.mu_before},
      {"mu_after", e.mu_after},
      {"mu_peak", e.mu_peak},
      {"t_peak", e.t_peak},
      {"slip_peak", e.slip_peak},
      {"mu_end", e.end.mu},
      {"mu_ss_before", e.ss_before.mu},
      {"mu_ss_after", e.ss_after.mu},
      {"D_c", e.d_c},
      {"a", e.a},
      {"a_minus_b", e.a_minus_b},
      {"b", e.b},
  };
}

std::vector<Field> state_fields(const State& s, bool load) {
  std::vector<Field> f = {{"FN", s.FN}, {"Fx", s.Fx}, {"mu", s.mu}, {"a2", s.a2}};
  if (load) f.insert(f.end(), {{"d", s.d}, {"a1", s.a1}});
  return f;
}

State stationary_state(const Case& c, double w) {
  return c.loading.by_force() ? stationary_under_load(c, w) : analytic::stationary(c, w);
}

} // namespace mdrmap::app
