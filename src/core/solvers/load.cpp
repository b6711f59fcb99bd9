#include "core/solvers/load.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/solvers/load_steps.hpp"

namespace mdrmap {
namespace {

struct SingleRun {
  Series series;
  std::vector<Transient> transients; ///< one per segment, from every grid step
  long steps = 0, updates = 0, elements = 0;
  LoadChecks checks;
  double dx = 0.0;
  double min_piece = std::numeric_limits<double>::infinity(); ///< LoadRow::min_piece
  double max_unresolved = 0.0;                                ///< LoadRow::max_unresolved
};

struct RunSettings {
  double cells, phase, time_tol, dt_over_tau;
  LoadStart start;
  long lattice_n = LoadLattice::kFine; ///< lattice points per segment (load_steps.hpp)
  double window_a = 0.0;               ///< the window is 1.6 window_a (+ 4 dx) on either side
  double piece_floor = 0.0;            ///< free-material pieces this wide and wider are recorded
  double watch_rtol = 0.0; ///< a segment this close to its stationary state is frozen (0: never)
};

/// The deepest stationary contact of the history (its slowest velocity; a0
/// for a hold or a rest start), and the start: the window is sized for it. A
/// transient that goes deeper is caught (WindowExceeded) and rerun with the
/// window of the Hertz contact, the deepest state under load.
double history_radius(const Case& c, LoadStart start) {
  const double a0 = c.a0();
  if (start != LoadStart::Stationary) return a0;
  double wmin = c.history.v0;
  for (const auto& seg : c.history.segments)
    wmin = std::min(wmin, seg.w);
  return stationary_alpha(wmin * c.rheology.tau / a0) * a0;
}

/// The shallowest contact the history reaches in a stationary state: the
/// stationary a1 at its largest velocity (a0 at rest). Sets dx.
double reference_radius(const Case& c, LoadStart start) {
  double wmax = start == LoadStart::Stationary ? c.history.v0 : 0.0;
  for (const auto& s : c.history.segments)
    wmax = std::max(wmax, s.w);
  return stationary_alpha(wmax * c.rheology.tau / c.a0()) * c.a0();
}

State hertz(const Case& c) {
  const double a0 = c.a0();
  State st;
  st.FN = c.loading.F0;
  st.a2 = a0;
  st.a1 = a0;
  st.d = a0 * (a0 / c.indenter.as<Parabola>().R);
  return st;
}

// tau = 0: nothing has memory; every state is the Hertz contact of F0.
SingleRun run_elastic(const Case& c) {
  SingleRun out;
  out.series.resize(c.total_samples());
  out.series.pre = hertz(c);
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k)
    for (long j = 0; j < c.sampling.count(k); ++j, ++i)
      out.series.set(i, c.history.start(k) + c.sampling.offset(k, j, c.history.segments[k].T),
                     static_cast<int>(k), hertz(c));
  out.checks.max_a1_over_a0 = 1.0;
  return out;
}

// Resolutions tried at most. Pieces of free material (LoadRow::min_piece)
// narrower than kPieceFloor rtol a0 do not matter (they move the edge by less
// than their width); a wider one with fewer than kPieceCells cells (the
// companion: half as many) is not seen by the companion and gets
// kCellsPerPiece cells, up to kMaxPieceElements elements in the window.
constexpr int kAttempts = 5;
// The run stops once its estimate is within kSafety rtol: the estimate is
// the difference to a companion that shares part of the error (a trailing
// edge that re-touches during a hold moves by cells, at first order), so an
// estimate just below rtol let the error pass it (drop-hold-rise at zeta0 = 3,
// hold 0.3 tau: error 1.0e-3, estimate 8.8e-4 at rtol 1e-3). A run within
// rtol is kept where the margin cannot be had: past the last resolution, or
// where a finer run would pass the element or work limits.
constexpr double kSafety = 0.5;
constexpr double kPieceFloor = 0.3;
constexpr double kPieceCells = 2.0;
constexpr double kCellsPerPiece = 8.0;
constexpr double kMaxPieceElements = 2e7;
constexpr double kMaxElements = 2e7;

SingleRun run_once(const Case& c, const RunSettings& s, const RunControl& control) {
  if (!(c.rheology.tau > 0.0)) return run_elastic(c);
  const double dx = reference_radius(c, s.start) / s.cells;
  const double A = 1.6 * s.window_a + 4.0 * dx;
  // (a window of kMaxElements elements is 320 MB of row; at zeta0 = 1e12 after
  // sliding at zeta0 = 1 it would need 4e7 and a step refreshes all of them)
  if (!(2.0 * A / dx <= kMaxElements))
    throw CaseAbandoned("kelvin_load: the element window would hold " +
                        format_number(2.0 * A / dx) + " elements (more than " +
                        format_number(kMaxElements) +
                        "): the velocities of the history differ too much for this solver");
  LoadRow row(c, dx, A, s.phase, control);
  row.set_pieces(s.piece_floor, kPieceCells * dx);
  if (s.start == LoadStart::Stationary)
    row.start_stationary(c.history.v0);
  else if (s.start == LoadStart::Rest)
    row.start_rest();
  else
    row.start_undeformed(1e-12);
  SingleRun out;
  out.series.resize(c.total_samples());
  out.series.pre = row.measure();
  // a segment within rtol of its stationary state keeps it (load_steps.hpp);
  // checked after each traverse of the window the history's contacts need,
  // whatever window the run has (a run rerun in a wider window freezes where
  // it did)
  const StationaryWatch watch(s.watch_rtol, 3.2 * history_radius(c, s.start),
                              s.watch_rtol > 0.0 && !(s.dt_over_tau > 0.0));
  LoadStepper stepper(row, {s.time_tol, s.dt_over_tau, s.lattice_n}, c.rheology.tau, watch);
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const Segment& seg = c.history.segments[k];
    const double t0 = c.history.start(k);
    row.change_velocity(seg.w); // (the row's clock restarts: it runs within the segment)
    const State ss = stationary_under_load(c, seg.w);
    TransientTracker tracker(ss.mu, row.measure().mu);
    stepper.begin(seg.T, &tracker, seg.w, ss);
    for (long j = 0; j < c.sampling.count(k); ++j, ++i) {
      const double off = c.sampling.offset(k, j, seg.T);
      stepper.reach(off); // (a sample off the step grid: a side step, undone by the next reach)
      row.check_one_interval();
      out.series.set(i, t0 + off, static_cast<int>(k), row.measure()); // (t: output only)
      control.report(i + 1, out.series.size());
    }
    stepper.reach(seg.T); // (on the grid at the segment's end, whatever its last sample)
    out.transients.push_back(tracker.result());
  }
  out.steps = stepper.steps();
  out.updates = row.updates();
  out.elements = static_cast<long>(row.capacity());
  out.checks = row.checks();
  out.dx = dx;
  out.min_piece = row.min_piece();
  out.max_unresolved = row.max_unresolved();
  return out;
}

// The local step tolerance, as a fraction of rtol. An edge that starts to
// move from a tangency (a hold or a drop after the edge sat at the cap) moves
// by ~sqrt(depth error): on a drop-hold-rise at zeta0 = 10 the depth error of
// 1e-6 left by a tolerance of 0.05 rtol (rtol 1e-4) put a2 1.5 rtol off at the
// hold's first sample, and the companion (4x the tolerance) shared most of it
// (est/err 0.64). 0.02 rtol keeps it within rtol.
constexpr double kTimeTol = 0.02;

// Starting resolution and local time tolerance from rtol (refined below if
// the companion disagrees by more than rtol).
RunSettings initial_settings(const LoadOptions& o) {
  RunSettings s{o.cells, o.phase, o.time_tol, o.dt_over_tau, o.start, LoadLattice::kFine, 0.0, 0.0};
  if (!(s.cells > 0.0)) s.cells = std::clamp(std::ceil(0.5 / std::sqrt(o.rtol)), 16.0, 1e6);
  if (!(s.time_tol > 0.0)) s.time_tol = kTimeTol * o.rtol;
  return s;
}

// run_once; if the edge leaves a window sized below the Hertz contact, again
// with the Hertz contact's window (s.window_a then says which was used).
SingleRun run_widening(const Case& c, RunSettings& s, const RunControl& control) {
  try {
    return run_once(c, s, control);
  } catch (const WindowExceeded&) {
    if (!(s.window_a < c.a0())) throw;
    s.window_a = c.a0();
    return run_once(c, s, control);
  }
}

// Refines s so that a piece `width` wide gets kCellsPerPiece cells (run at
// spacing dx); false if that needs more than kMaxPieceElements elements.
bool resolve_piece(RunSettings& s, double dx, double width) {
  const double cells = std::ceil(s.cells * kCellsPerPiece * dx / width);
  const double elements = 3.2 * s.window_a / (dx * s.cells / cells);
  if (!(elements <= kMaxPieceElements)) return false;
  s.cells = cells;
  return true;
}

// The companion: half the resolution at a shifted phase (a read-out error
// that depends on where the grid falls is not shared), four times the local
// step error and half the lattice's points (where the lattice limits the
// steps, the companion's longer steps show the time error it leaves: on one
// lattice both runs would share it).
// The estimate is floored at the local step tolerance: below it the two runs'
// difference no longer measures the error (it is within the scatter over grid
// phases of an unresolved tail, ~1e-6 at zeta0 = 1e-4).
double companion_estimate(const Case& c, RunSettings& s, const Series& fine, RunResult& res,
                          const RunControl& control) {
  RunSettings cs = s;
  cs.cells = 0.5 * s.cells;
  cs.phase = std::fmod(s.phase + 0.381966, 1.0);
  cs.time_tol = 4.0 * s.time_tol;
  cs.lattice_n = LoadLattice::points(cs.cells, s.cells);
  if (cs.dt_over_tau > 0.0) cs.dt_over_tau *= 2.0;
  const SingleRun coarse = run_widening(c, cs, control);
  s.window_a = cs.window_a;
  res.info.steps += coarse.steps;
  res.info.element_updates += coarse.updates;
  return std::max(case_error(coarse.series, fine, c, 1e-12).max(), s.time_tol) +
         64.0 * std::numeric_limits<double>::epsilon();
}

void merge(LoadChecks& a, const LoadChecks& b) {
  a.leading_edge_detached += b.leading_edge_detached;
  a.second_contact += b.second_contact;
  a.max_a1_over_a0 = std::max(a.max_a1_over_a0, b.max_a1_over_a0);
}

} // namespace

RunResult run_load(const CheckedCase& checked, const LoadOptions& opt, LoadChecks* checks) {
  const Case& c = checked.get();
  if (!c.loading.by_force())
    throw InvalidInput("solver", "the load solver needs a prescribed normal load (--F0)");
  require_kelvin(c, "the load solver");
  require_parabola(c, "the load solver");
  validate_rtol(opt.rtol);
  RunResult res;
  res.info.solver = "kelvin_load";
  res.info.rtol = opt.rtol;
  RunSettings s = initial_settings(opt);
  s.window_a = opt.window_a0 > 0.0 ? opt.window_a0 * c.a0() : history_radius(c, s.start);
  s.piece_floor = kPieceFloor * opt.rtol * c.a0();
  const bool adaptive = !(opt.cells > 0.0);
  s.watch_rtol = opt.keep_stationary && adaptive ? opt.rtol : 0.0;
  const RunControl own;
  const RunControl& control = opt.control != nullptr ? *opt.control : own;
  LoadChecks all;
  bool met = false; // res holds a run whose estimate is within rtol
  for (int attempt = 0;; ++attempt) {
    SingleRun fine;
    try {
      fine = run_widening(c, s, control);
    } catch (const CaseAbandoned&) {
      if (met) break;
      throw;
    }
    res.info.steps += fine.steps;
    res.info.element_updates += fine.updates;
    res.info.refinements = attempt + 1;
    merge(all, fine.checks);
    // a piece of free material that matters but has fewer than kPieceCells
    // cells: resolve it first (the companion would share the error)
    const bool unresolved = fine.min_piece < kPieceCells * fine.dx;
    if (adaptive && unresolved && attempt < kAttempts - 1 &&
        resolve_piece(s, fine.dx, fine.min_piece))
      continue;
    double est = 0.0;
    try {
      if (opt.estimate_error || adaptive) est = companion_estimate(c, s, fine.series, res, control);
    } catch (const CaseAbandoned&) {
      if (met) break;
      throw;
    }
    // (a piece left unresolved, the narrow ones below the floor included, can
    // move the edge by up to its width, unseen by the companion)
    if (opt.estimate_error || adaptive) est = std::max(est, fine.max_unresolved / c.a0());
    res.series = std::move(fine.series);
    res.transients = std::move(fine.transients);
    res.info.error_estimate = est;
    res.info.cells_per_a1 = s.cells;
    res.info.elements = fine.elements;
    if (!adaptive || est <= kSafety * opt.rtol) break;
    met = est <= opt.rtol;
    if (attempt >= kAttempts - 1 && met) break;
    if (attempt >= kAttempts - 1)
      throw CaseAbandoned("kelvin_load: the error estimate " + format_number(est) +
                          " stays above rtol " + format_number(opt.rtol) + " after " +
                          std::to_string(attempt + 1) + " resolutions (a_ref/dx up to " +
                          format_number(s.cells) + ")");
    const double f = std::clamp(std::sqrt(est / (kSafety * opt.rtol)), 1.5, 4.0);
    s.cells = std::ceil(s.cells * f);
    s.time_tol /= f * f;
  }
  if (checks) *checks = all;
  return res;
}

} // namespace mdrmap
