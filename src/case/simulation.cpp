#include "case/simulation.hpp"

#include <algorithm>
#include <chrono>

#include "core/metrics/error_metric.hpp"
#include "core/outputs/output_table.hpp"
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
void add_reference_error(const CaseInput& a, const CheckedCase& checked, const RunResult& res,
                         SimulateRecord& rec, const RunControl& control) {
  if (solver_handles(SolverKind::Exact, model_needs(a.c))) {
    if (rec.solver == "exact") return;
    const RunResult ref =
        run_case(checked, SolverKind::Exact, kExactReferenceRtol, control.fresh());
    rec.error_vs_exact = case_error(res.series, ref.series, a.c).max();
    return;
  }
  if (a.solver == SolverKind::Auto) return;
  rec.reference_rtol = a.c.rheology.kelvin()
                           ? std::max(a.rtol * kLoadReferenceFactor, kLoadReferenceFloor)
                           : std::max(a.rtol * kSpectrumReferenceFactor, kSpectrumReferenceFloor);
  const RunResult ref = run_case(checked, SolverKind::Auto, rec.reference_rtol, control.fresh());
  rec.reference = ref.info.solver.empty() ? "auto" : ref.info.solver;
  rec.error_vs_exact = case_error(res.series, ref.series, a.c).max();
}

} // namespace

Simulation simulate(const CaseInput& in, const RunControl& control) {
  const auto start = std::chrono::steady_clock::now();
  const CheckedCase checked(in.c); // the one check of this case: both runs take it
  RunResult res = run_case(checked, in.solver, in.rtol, control);
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
  add_reference_error(in, checked, res, rec, control);
  out.series = std::move(res.series);
  return out;
}

std::vector<Field> event_fields(const EventMetrics& e) {
  const OutputSpec& mu = output(OutputGroup::Series, "mu");
  std::vector<Field> f;
  for (const OutputSpec& o : output_table()) {
    if ((o.where & kInCsv) == 0) continue;
    if (o.group == OutputGroup::Event) f.emplace_back(o.name, e.*(o.event));
    if (o.group == OutputGroup::EventState)
      f.emplace_back(event_state_name(mu, o), (e.*(o.event_state)).mu);
  }
  return f;
}

std::string d_c_undefined_key() {
  return std::string(output(OutputGroup::Event, "D_c").name) + "_undefined";
}

std::vector<Field> state_fields(const State& s, bool load) {
  std::vector<Field> f;
  for (const OutputSpec* q : state_outputs(load))
    f.emplace_back(q->name, s.*(q->state));
  return f;
}

std::vector<Field> result_fields(const RunInfo& info, double wall_seconds) {
  std::vector<Field> f;
  for (const OutputSpec& o : output_table())
    if (o.group == OutputGroup::Result && (o.where & kInCsv) != 0)
      f.emplace_back(o.name, o.result(info, wall_seconds));
  return f;
}

} // namespace mdrmap::cases
