#include "case/simulation.hpp"

#include <algorithm>
#include <chrono>

#include "core/metrics/error_metric.hpp"
#include "core/solvers/dispatch.hpp"
#include "mdrmap/version.hpp"

namespace mdrmap::cases {
namespace {

constexpr double kExactReferenceRtol = 1e-12;
/// Under load the reference is the load solver at rtol * factor, not below the floor;
/// with a spectrum the spectrum solver likewise.
constexpr double kLoadReferenceFactor = 1e-3;
constexpr double kLoadReferenceFloor = 1e-9;
constexpr double kSpectrumReferenceFactor = 1e-2;
constexpr double kSpectrumReferenceFloor = 1e-7;

/// For a solver other than the default: the case error against a reference.
/// Where the continuum solver takes the case (the Kelvin foundation and the
/// parabola at fixed depth) that solver at 1e-12;
/// under load, or with a spectrum, the default solver at a much tighter rtol
/// (docs/design.md, "Error metric").
void add_reference_error(const CaseInput& a, const RunResult& res, SimulateRecord& rec,
                         const RunControl& control) {
  if (solver_handles(SolverKind::Exact, model_needs(a.c))) {
    if (rec.solver == "exact") return;
    const RunResult ref = run_case(a.c, SolverKind::Exact, kExactReferenceRtol, control.fresh());
    rec.error_vs_exact = case_error(res.series, ref.series, a.c).max();
    return;
  }
  if (a.solver == SolverKind::Auto) return;
  rec.reference_rtol = a.c.rheology.kelvin()
                           ? std::max(a.rtol * kLoadReferenceFactor, kLoadReferenceFloor)
                           : std::max(a.rtol * kSpectrumReferenceFactor, kSpectrumReferenceFloor);
  const RunResult ref = run_case(a.c, SolverKind::Auto, rec.reference_rtol, control.fresh());
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
  rec.events = event_metrics(in.c, res.series, res.transients, res.info.error_estimate, res.probes);
  add_reference_error(in, res, rec, control);
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
      {"mu_max", e.mu_max},
      {"t_max", e.t_max},
      {"slip_max", e.slip_max},
      {"mu_min", e.mu_min},
      {"t_min", e.t_min},
      {"slip_min", e.slip_min},
      {"mu_peak", e.mu_peak},
      {"t_peak", e.t_peak},
      {"slip_peak", e.slip_peak},
      {"mu_end", e.end.mu},
      {"mu_ss_before", e.ss_before.mu},
      {"mu_ss_after", e.ss_after.mu},
      {"D_c", e.d_c},
      {"overshoot", e.overshoot},
      {"a", e.a},
      {"a_minus_b", e.a_minus_b},
      {"b", e.b},
      {"healing", e.healing},
  };
}

std::vector<Field> state_fields(const State& s, bool load) {
  std::vector<Field> f = {{"FN", s.FN}, {"Fx", s.Fx}, {"mu", s.mu}, {"a2", s.a2}};
  if (load) f.insert(f.end(), {{"d", s.d}, {"a1", s.a1}});
  return f;
}

} // namespace mdrmap::cases
