#include "core/solvers/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/metrics/error_metric.hpp"
#include "core/metrics/stationary.hpp"
#include "core/solvers/refine.hpp"
#include "core/solvers/spectrum_law.hpp"
#include "core/solvers/spectrum_row.hpp"
#include "core/solvers/spectrum_runs.hpp"
#include "core/solvers/stationary_watch.hpp"

namespace mdrmap {
using namespace spectrum::detail;
namespace {

/// The first resolution is a1/dx = 1/sqrt(rtol) (the row's error is second
/// order in the cell), but at most kStartCells: a case that needs more is
/// refined from there by its own estimate, and one that needs less (a slow
/// branch's smooth transient) is not run at 1/sqrt(rtol) (the two-term case
/// under load at aT 1e-3 met rtol 1e-6 at a1/dx 100; it started at 1000).
constexpr double kStartCells = 64.0;

/// The stationary state at w > 0 (F_N = 0 where there is none: w = 0, or no
/// closed form at this w; the steps then go on).
State stationary_or_none(const Case& c, double w) {
  if (!(w > 0.0)) return State{};
  try {
    return stationary_state(c, w);
  } catch (const std::exception&) {
    return State{};
  }
}

} // namespace

/// (spectrum_runs.hpp)
const State& spectrum::detail::StationaryStates::at(double w) {
  for (const auto& [v, st] : known_)
    if (v == w) return st;
  known_.emplace_back(w, stationary_or_none(c_, w));
  return known_.back().second;
}

namespace {

/// The quiet tolerance of a skipped start (ProbeSkip): a tenth of rtol of
/// mu(0+) (of the friction a tracker tells from noise, kNegligibleFriction).
constexpr double kQuiet = 0.1;
bool quiet(double mu0, double mu, double rtol) {
  return std::abs(mu - mu0) <= kQuiet * rtol * std::max(std::abs(mu0), kNegligibleFriction);
}
/// The probe rule of a segment, with a quiet start (ProbeSkip) where it
/// starts from a stationary state, up to kFirstProbe of the travel time of
/// its contact at the faster of the two velocities (`travel`).
ProbeRule quiet_start(ProbeRule r, bool steady, double travel) {
  r.quiet_until = steady ? kFirstProbe * travel : 0.0;
  return r;
}

/// The row counts the indenter's travel in cells (up to 1e18 over the
/// history, else the case is abandoned).
void check_travel(const Case& c, double cells) {
  double travel = 2.0 * cells + 8.0;
  for (const auto& seg : c.history.segments)
    travel += seg.w * seg.T / (c.a1() / cells);
  if (!(travel < 1e18))
    throw CaseAbandoned("row: the indenter travels " + format_number(travel) +
                        " cells over the history, more than the element row can count (1e18)");
}

/// A fixed-depth run at a segment's t = 0+, for a quiet start (ProbeSkip):
/// the row, its stationary watch and the last state measured, which a try
/// that is not quiet restores.
struct Checkpoint {
  explicit Checkpoint(const StationaryWatch& w) : watch(w) {}
  void save(spectrum::Row& r, const StationaryWatch& w, const State& now) {
    r.renumber();
    r.save(row);
    watch = w;
    last = now;
  }
  void restore(spectrum::Row& r, StationaryWatch& w, State& now) const {
    r.restore(row);
    w = watch;
    now = last;
  }
  spectrum::Row::Snapshot row;
  StationaryWatch watch;
  State last;
};

/// The row at fixed depth over the history (sample_history's callbacks): a
/// segment that has reached its stationary state keeps it
/// (stationary_watch.hpp).
class DepthRun {
public:
  DepthRun(const Case& c, spectrum::Row& row, StationaryWatch watch, StationaryStates& states)
      : row_(row), watch_(watch), states_(states), at_change_(watch), w_now_(c.history.v0),
        w_before_(w_now_) {}

  void change(double w) {
    steady_ = first_ || watch_.frozen();
    first_ = false;
    row_.change_velocity(w);
    w_before_ = w_now_;
    w_now_ = w;
    watch_.start(w, true);
  }
  void advance(double dt) {
    if (watch_.frozen()) return;
    row_.renumber();
    row_.advance(dt);
    watch_.moved(w_now_ * dt);
  }
  State measure(spectrum::Edge edge) {
    if (watch_.frozen()) return now_;
    now_ = row_.measure(edge);
    if (!watch_.due()) return now_;
    const State& ss = states_.at(w_now_);
    if (!(ss.FN > 0.0)) {
      watch_.stop();
      return now_;
    }
    watch_.check(now_.FN / ss.FN - 1.0,
                 (now_.mu - ss.mu) / std::max(std::abs(ss.mu), kNegligibleFriction));
    // (the state a frozen segment keeps for its samples: at the confirmed edge)
    if (watch_.frozen() && edge != spectrum::Edge::Confirmed) now_ = row_.measure();
    return now_;
  }
  /// The segment's probe rule: `probe`, with a quiet start where it starts
  /// from a stationary state (quiet_start; a1: the contact's width).
  ProbeRule rule(const ProbeRule& probe, double a1) const {
    return quiet_start(probe, steady_, a1 / std::max(w_before_, w_now_));
  }
  /// The quiet start's checkpoint (ProbeSkip): saved at t = 0+, and back.
  void save() { at_change_.save(row_, watch_, now_); }
  void restore() { at_change_.restore(row_, watch_, now_); }

private:
  spectrum::Row& row_;
  StationaryWatch watch_;
  StationaryStates& states_;
  Checkpoint at_change_;
  State now_;
  double w_now_, w_before_;
  // the segment starts from a stationary state (the pre-state, or a frozen
  // segment): its first probes may be skipped where quiet (ProbeSkip)
  bool first_ = true, steady_ = true;
};

ResolutionRun run_once(const Case& c, const spectrum::Law& law, double cells, double phase,
                       double fine, const SpectrumOptions& o, const RunControl& control,
                       StationaryStates& states) {
  check_travel(c, cells);
  spectrum::Row row(c, law, cells, phase, o.sub_travel, kEdgeTol * o.rtol, control, kName);
  row.set_layer_width(c.a1() / fine);
  row.set_composed(o.composed_steps);
  row.start_stationary(c.history.v0);
  ResolutionRun out;
  // (the companions of the estimate, at other phases, are not probed: their
  // series serve the estimate only)
  const ProbeRule probe{kFirstProbe * shortest_time(c, c.a1()), kProbeRatio, phase != o.phase};
  DepthRun run(c, row, StationaryWatch(o.rtol, 2.0 * c.a1(), o.keep_stationary), states);
  const ProbeSkip skip{[&] { run.save(); }, [&] { run.restore(); },
                       [&](double mu0, double mu) { return quiet(mu0, mu, o.rtol); }};
  // The samples measure at the confirmed trailing edge; the probes (the
  // event metrics' instants, most of the steps after a change of a broad
  // spectrum: 24 a decade from 1e-2 of its shortest time) where the contact
  // forces' cubic predicts it, without replays: where that cubic vanishes
  // inside the edge's cell the force there is ~0 and an O(dx^4) shift of the
  // edge moves the forces by O(dx^8); elsewhere (a re-touch front, the tip's
  // cell) the confirmed search runs anyway (Row::predicted_only).
  out.series = sample_history(
      c, control, [&](double w) { run.change(w); }, [&](double dt, double) { run.advance(dt); },
      [&] { return run.measure(spectrum::Edge::Confirmed); },
      [&] { return run.measure(spectrum::Edge::Predicted).mu; },
      [&](std::size_t) { return run.rule(probe, c.a1()); }, out.probes, skip);
  out.elements = static_cast<long>(row.capacity());
  out.steps = row.steps();
  out.updates = row.updates();
  return out;
}

} // namespace

RunResult run_spectrum(const CheckedCase& checked, const SpectrumOptions& o) {
  const Case& given = checked.get();
  const bool adaptive = !(o.cells_per_a1 > 0.0);
  if (adaptive) validate_rtol(o.rtol);
  if (!(o.sub_travel > 0.0) || !(o.sub_travel <= 2.0))
    throw InvalidInput("sub-travel", "must be in (0, 2] (a1 per sub-step)");
  Case c = given;
  c.rheology = given.rheology.shifted();
  const spectrum::Law law(c.rheology);
  double cells =
      adaptive ? std::clamp(std::ceil(1.0 / std::sqrt(o.rtol)), 16.0, kStartCells) : o.cells_per_a1;
  if (!(cells >= 4.0) || cells > kMaxCells)
    throw InvalidInput("cells-per-a1", "must be between 4 and 2e5");
  Refinement r;
  r.solver = kName;
  r.cells = cells;
  r.max_cells = kMaxCells;
  r.rtol = o.rtol;
  r.phase = o.phase;
  r.adaptive = adaptive;
  r.estimate = o.estimate_error;
  r.tolerance_floor = kEdgeFloor * o.rtol;
  r.observed_order = true;
  const RunControl own;
  const RunControl& control = o.control != nullptr ? *o.control : own;
  StationaryStates states(c);
  return refine(c, r, [&](double n, double ph, double fine) {
    return c.loading.by_force() ? run_once_load(c, law, n, ph, fine, o, control, states)
                                : run_once(c, law, n, ph, fine, o, control, states);
  });
}

} // namespace mdrmap
