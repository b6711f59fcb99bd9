// The driver of the discrete MDR simulator: one run of the element row
// (core/solvers/mdr_row.hpp) over the case's history, and the error control
// around it (core/solvers/refine.hpp).
#include "core/solvers/mdr.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/solvers/mdr_row.hpp"
#include "core/solvers/refine.hpp"

namespace mdrmap {
namespace {

/// Travel over the whole history, in cells: element ids are 64-bit integers
/// counted from it, so absurd scenes (e.g. w tau / a1 = 1e300) are refused.
void check_travel(const Case& c, double cells) {
  const double dx = c.a1() / cells;
  double travel = 2.0 * cells + 4.0;
  for (const auto& seg : c.history.segments)
    travel += seg.w * seg.T / dx;
  if (!(travel < 1e18))
    throw std::runtime_error("mdr: the indenter travels " + format_number(travel) +
                             " cells over the history, more than the element row can count "
                             "(1e18); use the exact solver");
}

// Undeformed foundation, indenter pressed in, then sliding at v0 over
// 2 a1 + 2 dx: every element in the window has then entered fresh at the
// leading edge, so the stationary state must be reproduced. Several uneven
// steps exercise the event handling.
void spin_up(mdr::Row& row, const Case& c, double cells) {
  const double a1 = c.a1(), dx = a1 / cells;
  const double travel = 2.0 * a1 + 2.0 * dx;
  row.init_undeformed(static_cast<long double>(-travel / dx));
  row.change_velocity(c.history.v0);
  const int nsteps = 7;
  const double T = travel / c.history.v0;
  double done = 0.0;
  for (int i = 1; i <= nsteps; ++i) {
    const double target = T * (static_cast<double>(i * i) / (nsteps * nsteps));
    row.advance(target - done);
    done = target;
  }
}

ResolutionRun run_once(const Case& c, double cells, double phase, const MdrOptions& opt,
                       const RunControl& control) {
  check_travel(c, cells);
  mdr::Row row(c, cells, phase, opt.subgrid, control);
  if (opt.spinup)
    spin_up(row, c, cells);
  else
    row.init_stationary(c.history.v0, 0.0L);
  ResolutionRun out;
  // (every run is probed: the row's sub-grid edge reads its steps, so a
  // companion without the fine run's steps would widen the estimate)
  const ProbeRule probe{kFirstProbe * shortest_time(c, c.a1()), kProbeRatio};
  out.series = sample_history(
      c, control, [&](double w) { row.change_velocity(w); },
      [&](double dt, double) { row.advance(dt); }, // exact: no steps needed between samples
      [&] { return row.measure(); }, [&](std::size_t) { return probe; }, out.probes);
  out.elements = static_cast<long>(row.capacity());
  out.steps = row.steps();
  out.updates = row.updates();
  return out;
}

// Starting resolution. The per-piece sub-grid edge is exact for every history
// at any dx, so start coarse (the error control refines if the companion
// disagrees); the linear edge converges like (dx/a1)^2 and the paper's raw
// sums like dx/a1, with constants ~1 on the hard set.
double initial_cells(const MdrOptions& o) {
  double c = 32.0;
  if (o.subgrid == MdrSubgrid::Linear) c = 1.5 / std::sqrt(o.rtol);
  if (o.subgrid == MdrSubgrid::None) c = 0.7 / o.rtol;
  return std::clamp(std::ceil(c), 16.0, 1e7);
}

} // namespace

RunResult run_mdr(const Case& s, const MdrOptions& opt) {
  validate(s);
  require_depth_control(s, "mdr");
  require_kelvin(s, "mdr");
  require_parabola(s, "mdr");
  Refinement r;
  r.solver = "mdr";
  r.cells = opt.cells_per_a1 > 0.0 ? opt.cells_per_a1 : initial_cells(opt);
  if (!(r.cells >= 2.0) || r.cells > 1e8)
    throw InvalidInput("cells-per-a1", "must be between 2 and 1e8");
  r.max_cells = 1e7;
  r.rtol = opt.rtol;
  r.phase = opt.phase;
  r.adaptive = opt.cells_per_a1 <= 0.0;
  r.estimate = opt.estimate_error;
  r.rounding_level = 1e-11; // an estimate below it is rounding noise of the two runs
  const RunControl own;
  const RunControl& control = opt.control != nullptr ? *opt.control : own;
  return refine(s, r, [&](double cells, double phase, double) {
    return run_once(s, cells, phase, opt, control);
  });
}

} // namespace mdrmap
