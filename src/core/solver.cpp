#include "core/solver.hpp"

#include <algorithm>
#include <cmath>

#include "core/baseline.hpp"
#include "core/exact.hpp"
#include "core/load.hpp"
#include "core/load_baseline.hpp"
#include "core/mdr.hpp"

namespace mdrmap {

void Series::resize(std::size_t n) {
  t.assign(n, 0.0);
  segment.assign(n, 0);
  FN.assign(n, 0.0);
  Fx.assign(n, 0.0);
  mu.assign(n, 0.0);
  a2.assign(n, 0.0);
  d.assign(n, 0.0);
  a1.assign(n, 0.0);
}

void Series::set(std::size_t k, double time, int seg, const State& st) {
  t[k] = time;
  segment[k] = seg;
  FN[k] = st.FN;
  Fx[k] = st.Fx;
  mu[k] = st.mu;
  a2[k] = st.a2;
  d[k] = st.d;
  a1[k] = st.a1;
}

SolverKind parse_solver(const std::string& name) {
  if (name == "auto") return SolverKind::Auto;
  if (name == "exact") return SolverKind::Exact;
  if (name == "mdr") return SolverKind::Mdr;
  if (name == "baseline") return SolverKind::Baseline;
  throw InvalidInput("solver", "must be one of auto, exact, mdr, baseline; got '" + name + "'");
}

const char* solver_name(SolverKind k) {
  switch (k) {
  case SolverKind::Auto:
    return "auto";
  case SolverKind::Exact:
    return "exact";
  case SolverKind::Mdr:
    return "mdr";
  case SolverKind::Baseline:
    return "baseline";
  }
  return "?";
}

void validate_rtol(double rtol) {
  if (!std::isfinite(rtol) || !(rtol > 0.0) || !(rtol <= 0.1))
    throw InvalidInput("rtol", "must be a number in (0, 0.1], got " + format_number(rtol));
}

bool solver_handles(SolverKind kind, bool by_force) {
  return !(by_force && kind == SolverKind::Exact); // exact: depth control only
}

namespace {

// Load control (docs/design.md, "Load control"): auto and mdr run the load
// solver; exact refuses (it solves depth control only).
RunResult run_load_case(const Case& c, SolverKind kind, double rtol, const RunControl& control) {
  switch (kind) {
  case SolverKind::Auto:
  case SolverKind::Mdr: {
    LoadOptions o;
    o.rtol = rtol;
    o.control = &control;
    return run_load(c, o);
  }
  case SolverKind::Baseline: {
    // the fixed-step check solver at its default resolution (rtol does not set it)
    LoadBaselineOptions o;
    o.control = &control;
    return run_load_baseline(c, o);
  }
  case SolverKind::Exact:
    break;
  }
  return run_exact(c, rtol, control); // refuses a force-controlled case
}

} // namespace

RunResult run_case(const CheckedCase& checked, SolverKind kind, double rtol,
                   const RunControl& control) {
  validate_rtol(rtol);
  const Case& c = checked.get();
  if (c.loading.by_force()) return run_load_case(c, kind, rtol, control);
  switch (kind) {
  case SolverKind::Auto:
  case SolverKind::Exact:
    return run_exact(checked, rtol, control);
  case SolverKind::Mdr: {
    MdrOptions o;
    o.rtol = rtol;
    o.control = &control;
    return run_mdr(c, o);
  }
  case SolverKind::Baseline: {
    BaselineOptions o; // first order: a1/dx ~ 1/rtol, within what a fixed-step run can afford
    o.cells_per_a1 = std::clamp(std::ceil(0.7 / rtol), 16.0, 4000.0);
    o.control = &control;
    return run_baseline(c, o);
  }
  }
  return run_exact(checked, rtol, control);
}

RunResult run_case(const Case& c, SolverKind kind, double rtol, const RunControl& control) {
  return run_case(CheckedCase(c), kind, rtol, control);
}

} // namespace mdrmap
