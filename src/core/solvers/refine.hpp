#pragma once
// The error control of the discrete solvers (docs/design.md, "The discrete
// solvers"): run at a resolution a1/dx, run a half-resolution companion with
// its elements at another phase, take the case error between the two as the
// estimate, and refine until it is below rtol. Shared by the element-row
// solvers (the row, spectrum.cpp): they differ only in how
// one run goes, where they start and how fine they may go.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/model/case.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

/// One run of a solver at one resolution and element phase.
struct ResolutionRun {
  Series series;
  std::vector<Probes> probes; ///< one per segment where the solver probes (sample_history)
  long elements = 0;          ///< elements held at once
  long steps = 0;             ///< time steps taken
  long updates = 0;           ///< element state updates
};

/// The samples of one run of an element-row solver over the case's history:
/// measure() before t = 0 (pre), then for each segment change(w) at its
/// start and, to each output instant, advance(dt, w) by the time since the
/// last one and measure() there; reports each sample to `control`.
template <class Change, class Advance, class Measure>
Series sample_history(const Case& c, const RunControl& control, Change change, Advance advance,
                      Measure measure) {
  Series s;
  s.resize(c.total_samples());
  s.pre = measure();
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const Segment& seg = c.history.segments[k];
    const double t0 = c.history.start(k);
    change(seg.w);
    double prev = 0.0;
    for (long j = 0; j < c.sampling.count(k); ++j, ++i) {
      const double off = c.sampling.offset(k, j, seg.T);
      advance(off - prev, seg.w);
      prev = off;
      s.set(i, t0 + off, static_cast<int>(k), measure());
      control.report(i + 1, s.size());
    }
  }
  return s;
}

/// The shortest time scale of a case at fixed depth a1 (the travel time
/// a1 / w of its sliding segments, tau and the branches' tau_k): the first
/// probe at kFirstProbe of it, then ratio kProbeRatio (parabolas through three
/// probes place an extremum's value to ~1e-4 of its rise).
inline constexpr double kFirstProbe = 1e-2, kProbeRatio = 0.1;
double shortest_time(const Case& c, double a1);

/// The instants after a change at which a stepping solver probes its
/// solution for the event metrics (RunResult::probes): t_1 = first, then
/// t_(i+1) = t_i + max(ratio t_i, first) to the segment's end, fixed by the
/// segment and not by the output instants (docs/design.md, "Event metrics").
struct ProbeRule {
  double first = 0.0;
  double ratio = 0.0;
  bool off = false; ///< no probes (a segment without a change)
  /// The latest probe a quiet start may jump to (ProbeSkip; 0: none).
  double quiet_until = 0.0;
  double next(double t) const { return t + std::max(ratio * t, first); }
};

/// A segment's first probes skipped where the solution is quiet. Right after
/// a change from a stationary state, every branch's stress leaves its old
/// path as G_k tau_k (1 - exp(-t/tau_k)) times the element's change of rate,
/// and while the indenter has moved by much less than the contact's width
/// that change is fixed: F_x and F_N move by one increasing function of t
/// times two constants, so mu is monotone. If mu at a probe time t_m is within the
/// quiet tolerance of mu(0+), so is every probe before t_m, and none holds an
/// extremum: the run jumps to t_m. A rule sets quiet_until only where this
/// holds (a stationary state before the change; t_m far below the contact's
/// travel time). The latest probe at or below it is tried first, then one a
/// decade earlier, and so on; a try that is not quiet is undone.
struct ProbeSkip {
  std::function<void()> save, restore;       ///< the solver's state at t = 0+, and back
  std::function<bool(double, double)> quiet; ///< quiet(mu(0+), mu(t_m))
  bool on() const { return static_cast<bool>(quiet); }
};

/// The probe times of `r` up to `until` and before `before`.
inline std::vector<double> probe_times(const ProbeRule& r, double until, double before) {
  std::vector<double> ts;
  for (double t = r.next(0.0); t <= until && t < before; t = r.next(t))
    ts.push_back(t);
  return ts;
}

namespace probe_detail {

/// Where the probes of sample_history (below) stand: the segment's probes
/// and rule, the offset reached in it and its next probe.
struct ProbeCursor {
  Probes* p = nullptr; // the segment's (none before the first change: pre)
  std::size_t k = 0;
  double prev = 0.0, next = 0.0, T = 0.0;
  ProbeRule r;
  bool try_skip = false; ///< a quiet start (ProbeSkip) still to try
};

/// A change to w starts the next segment k (after the solver's change(w):
/// `rule(k)` may depend on it): its probes go to probes[k].
template <class Rule>
void start_segment(ProbeCursor& s, const Case& c, double w, Rule& rule, std::vector<Probes>& probes,
                   const ProbeSkip& skip) {
  if (s.p != nullptr) ++s.k;
  s.p = &probes[s.k];
  s.r = rule(s.k);
  if (c.history.before(s.k) == w) s.r.off = true; // no change: the samples suffice
  s.T = c.history.segments[s.k].T;
  s.prev = 0.0;
  s.next = s.r.next(0.0);
  s.try_skip = skip.on() && !s.r.off && s.r.quiet_until > 0.0;
}

/// The quiet start (see ProbeSkip; at the segment's first advance, mu(0+)
/// probed, to before `target`): jumps to the latest quiet probe tried, if any.
template <class Advance, class Probe>
void skip_quiet(ProbeCursor& s, double target, double w, Advance& advance, Probe& probe,
                const ProbeSkip& skip) {
  const std::vector<double> ts = probe_times(s.r, s.r.quiet_until, target);
  const auto decade = static_cast<std::size_t>(std::log(10.0) / std::log1p(s.r.ratio));
  for (std::size_t m = ts.size(); m > 0; m = m > decade ? m - decade : 0) {
    const double t = ts[m - 1];
    skip.save();
    advance(t, w);
    const double mu = probe();
    if (skip.quiet(s.p->mu.front(), mu)) {
      s.p->t.push_back(t);
      s.p->mu.push_back(mu);
      s.prev = t;
      s.next = s.r.next(t);
      return;
    }
    skip.restore();
  }
}

/// advance(dt, w) to the next output instant, through the segment's probes
/// before it (probe() at each), trying the quiet start first.
template <class Advance, class Probe>
void advance_probing(ProbeCursor& s, double dt, double w, Advance& advance, Probe& probe,
                     const ProbeSkip& skip) {
  const double target = s.prev + dt;
  if (s.try_skip && dt > 0.0) { // (the first advance past t = 0: mu(0+) is the probe there)
    s.try_skip = false;
    if (s.prev == 0.0 && s.p->t.size() == 1) skip_quiet(s, target, w, advance, probe, skip);
  }
  for (; !s.r.off && s.next < target; s.next = s.r.next(s.next)) {
    advance(s.next - s.prev, w);
    s.prev = s.next;
    s.p->t.push_back(s.next);
    s.p->mu.push_back(probe());
  }
  advance(target - s.prev, w);
  s.prev = target;
}

/// The mu of a measure() as a probe where the instant is one: mu(0+), a
/// probe's instant or the segment's end (not an output instant only).
inline void probe_measured(ProbeCursor& s, double mu) {
  if (s.p == nullptr || s.r.off) return;
  if (s.prev == s.next)
    s.next = s.r.next(s.next);
  else if (s.prev != 0.0 && s.prev != s.T)
    return;                                               // an output instant only
  if (!s.p->t.empty() && s.p->t.back() == s.prev) return; // (the end twice: no samples between)
  s.p->t.push_back(s.prev);
  s.p->mu.push_back(mu);
}

} // namespace probe_detail

/// sample_history, and between the output instants the probes of `rule(k)`
/// for segment k: advance to each, probe() there into probes[k] (with the
/// measure() of mu(0+) and of the segment's end, which every sampling has).
/// probe() returns mu; it may measure more cheaply than measure() where the
/// event metrics need less than the series.
template <class Change, class Advance, class Measure, class Probe, class Rule>
Series sample_history(const Case& c, const RunControl& control, Change change, Advance advance,
                      Measure measure, Probe probe, Rule rule, std::vector<Probes>& probes,
                      const ProbeSkip& skip = {}) {
  probes.assign(c.history.size(), Probes{});
  probe_detail::ProbeCursor s;
  auto change_k = [&](double w) {
    change(w);
    probe_detail::start_segment(s, c, w, rule, probes, skip);
  };
  auto advance_k = [&](double dt, double w) {
    probe_detail::advance_probing(s, dt, w, advance, probe, skip);
  };
  auto measure_k = [&] {
    const State st = measure();
    probe_detail::probe_measured(s, st.mu);
    return st;
  };
  return sample_history(c, control, change_k, advance_k, measure_k);
}

/// Runs the solver once at resolution `cells` (a1/dx) with element phase
/// `phase`, for the estimate of a run at `fine` (cells for the run itself; a
/// solver whose discretisation changes form at a cell's width, as the element
/// row's leading-edge layers, takes the fine run's cell in all of them, so the
/// companion does not switch where the fine run does not).
using RunAtResolution = std::function<ResolutionRun(double cells, double phase, double fine)>;

/// How the error control proceeds.
struct Refinement {
  const char* solver = "";       ///< names the solver in RunInfo and in messages
  double cells = 0.0;            ///< starting resolution a1/dx
  double max_cells = 0.0;        ///< no refinement past it (the case is abandoned there)
  double rtol = 0.0;             ///< target case error
  double phase = 0.5;            ///< element phase of the fine runs
  bool adaptive = true;          ///< refine until the estimate is <= rtol (else one resolution)
  bool estimate = true;          ///< run the companion for an estimate even when not adaptive
  double rounding_level = 1e-11; ///< an estimate below this is rounding noise, not resolution
  /// Added to every estimate: the error the solver's own tolerances leave,
  /// which the companion shares (0: none).
  double tolerance_floor = 0.0;
  /// Where the difference to the companion lies in (rtol, 2 rtol], run a
  /// third resolution (a quarter, another phase) and credit the order the
  /// three show: with r the ratio of the coarser pair's difference to the
  /// finer pair's, the estimate is the difference over min(2, r - 1)
  /// (Richardson: at order p the fine run errs by the difference over
  /// 2^p - 1), unchanged where r <= 2 (order 1 or less observed).
  bool observed_order = false;
};

/// Phase of the companion: shifted by a non-commensurate fraction of a cell,
/// so that an error of a read-out that depends on where the grid falls is not
/// shared by both runs.
double companion_phase(double phase);

/// Runs `once` at r.cells (and the companion at r.cells / 2, companion_phase;
/// with observed_order, where it decides, a third at r.cells / 4) and refines
/// while adaptive and the estimate is above r.rtol: the series and probes of
/// the finest run and its RunInfo (solver, rtol, error_estimate,
/// cells_per_a1, elements; steps, element_updates of all runs; refinements).
/// `c` is the case the estimate measures the series on (case_error). Throws
/// CaseAbandoned when the estimate stays above rtol: after 6 resolutions, at
/// max_cells, or once it stagnates as rounding noise.
RunResult refine(const Case& c, const Refinement& r, const RunAtResolution& once);

} // namespace mdrmap
