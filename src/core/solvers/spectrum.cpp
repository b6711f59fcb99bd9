#include "core/solvers/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/metrics/error_metric.hpp"
#include "core/metrics/stationary.hpp"
#include "core/numerics/root.hpp"
#include "core/solvers/load_lattice.hpp"
#include "core/solvers/refine.hpp"
#include "core/solvers/spectrum_law.hpp"
#include "core/solvers/spectrum_row.hpp"
#include "core/solvers/stationary_watch.hpp"

namespace mdrmap {
namespace {

/// The trailing edge is located to kEdgeTol rtol a1. Where the pressure jumps
/// there (a re-touch front) the forces err by about that times the jump
/// relative to the mean pressure, up to kEdgeFloor / kEdgeTol = 4 times it
/// (the cone's Kelvin drops: 3): both runs of the estimate share it, so it is
/// added to the estimate.
constexpr double kEdgeTol = 1e-3, kEdgeFloor = 4e-3;

constexpr const char* kName = "row";
constexpr double kMaxCells = 2e5; // window memory: 4e5 elements of up to 33 doubles
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

/// The stationary states the watches compare with (stationary_watch.hpp),
/// each formed once per velocity for every run of a case, and only when a
/// check first needs it: a cone's or a power law's with a spectrum is a
/// quadrature (75 ms with 11 terms), which per segment and run made a cone's
/// velocity steps twice as dear.
class StationaryStates {
public:
  explicit StationaryStates(const Case& c) : c_(c) {}
  const State& at(double w) {
    for (const auto& [v, st] : known_)
      if (v == w) return st;
    known_.emplace_back(w, stationary_or_none(c_, w));
    return known_.back().second;
  }

private:
  const Case& c_;
  std::deque<std::pair<double, State>> known_; // (references stay valid)
};

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

// ---- load control ---------------------------------------------------------
// The depth is the unknown that balances F_N = F0 at every step's end. The
// parallel dashpot sees the depth rate of BDF2 over the last two steps (BE on
// a segment's first step): L-stable, second order; within a step the depth is
// the parabola ending at that rate (linear without a dashpot), so the branch
// updates are exact for the path and the dashpot's force inside the step (it
// decides where a point lets go) is second order too. Steps grow geometrically
// from each velocity change (relative step eps falling with the cells, see
// StepRule: the companion at half the cells has longer steps, so its
// difference sees the time error).
// The balance's root: numerics::increasing_root (each evaluation runs the row,
// which charges its own work).
const numerics::RootSearch kBalance{"row: the load balance", 100};

// Time steps. The relative step eps = factor / (a_ref/dx) after a change,
// starting at first eps t_min, whatever the travel (a cap of 16 dx of travel
// per step made a long segment's cost grow with its travel: docs/design.md). The depth rate at a
// step's end is the cubic's through the segment's last three depths and the new one (BDF3), and
// within the step the depth is the parabola to that rate (within O(h^3) of the cubic): the branch
// states see a third-order path error and the dashpot a third-order rate
// error. Without a parallel dashpot the force depends on the path only through
// the branches' kernel averages; with one, the rate enters the force directly
// and a change starts a boundary layer in the rate: the steps are smaller
// there and start smaller. Where the depth turns faster than the rule expects
// (a rear that lets go, a reslide after a hold) the predictor misses: a step
// whose converged depth is further than eps^3 d from the extrapolation is
// taken again shorter, and the next steps stay below the length that would
// have met it (exponent 1/3). Measured on the work-precision scenes
// (tools/bench/spectrum.cpp) and the case set: the time error then stays
// below the space error of both runs of the estimate; the first step of a
// reslide after a hold needs first <= 0.1 (at 1: 2.0e-4 at a/dx 32 on the
// SLS G0/G = 100 case, estimate 7.8e-5).
//
// Above kGrowthCells the growth eps falls as 1 / sqrt(a_ref/dx), not
// 1 / (a_ref/dx): the miss bound (and the first step) keep eps_acc =
// factor / (a_ref/dx), so the path's error is held where it matters while
// smooth stretches take fewer, longer steps. (With the miss bound at the
// growth eps too, the SLS G0/G = 100 drop and rise under load erred by
// 1.06e-6 at rtol 1e-6; with it at eps_acc 3.5e-7, as with eps = eps_acc.
// The two-term case at aT 37, rtol 1e-6: 3.6e8 -> 7.6e7 element updates,
// within 4.6e-8 of the run with eps = eps_acc everywhere.)
//
// Under load the steps are also cut at a lattice of each segment, never at
// the samples (LoadRun::reach).
struct StepRule {
  double factor, first;
};
StepRule step_rule(const Rheology& r) {
  return r.tau > 0.0 ? StepRule{2.0, 1e-2} : StepRule{8.0, 0.1};
}
constexpr double kGrowthCells = 32.0;
/// The growth eps of the step rule at resolution `cells` (a_ref/dx).
double growth_eps(const StepRule& rule, double cells) {
  return rule.factor / (cells <= kGrowthCells ? cells : std::sqrt(kGrowthCells * cells));
}
// The load balance's tolerance on F_N and the depth, relative to rtol: 1e-3
// of the case's error budget. (At 1e-4 the secant needed 17% more trials for
// the same results: 6-term spectrum under load at rtol 1e-3, 32 -> 29 ms,
// errors and estimates unchanged.)
constexpr double kBalanceTol = 1e-3;

struct LoadGeometry {
  double d_pre = 0.0, a_ref = 0.0, a_win = 0.0, t_min = 0.0;
};

LoadGeometry load_geometry(const Case& c) {
  LoadGeometry g;
  g.d_pre = stationary_load_depth(c, c.history.v0);
  g.a_ref = c.indenter.leading_edge(g.d_pre);
  double amax = std::max(c.a0(), g.a_ref);
  g.t_min = g.a_ref / c.history.v0;
  for (const auto& seg : c.history.segments) {
    if (!(seg.w > 0.0)) continue;
    const double a = c.indenter.leading_edge(stationary_load_depth(c, seg.w));
    g.a_ref = std::min(g.a_ref, a);
    amax = std::max(amax, a);
    g.t_min = std::min(g.t_min, a / seg.w);
  }
  if (c.rheology.tau > 0.0) g.t_min = std::min(g.t_min, c.rheology.tau);
  for (const Branch& b : c.rheology.branches)
    g.t_min = std::min(g.t_min, b.tau);
  g.a_win = 1.1 * amax;
  return g;
}

class LoadRun {
public:
  LoadRun(const Case& c, spectrum::Row& row, double cells, double tol, StationaryWatch watch,
          StationaryStates& states)
      : c_(c), row_(row), cells_(cells), eps_(growth_eps(step_rule(c.rheology), cells)),
        acc_(step_rule(c.rheology).factor / cells), first_(step_rule(c.rheology).first), tol_(tol),
        ftol_(tol), watch_(watch), states_(states) {}

  /// The depth rate just after a change to w (the dashpot's balance at the instant).
  void change(double w) {
    restart();
    watch_w_ = w;
    start_watch(w);
    if (!(c_.rheology.tau > 0.0)) {
      row_.change_velocity(w, 0.0);
      return;
    }
    row_.renumber();
    row_.save(snap_);
    const double F0 = c_.loading.F0, d = row_.depth_now();
    bool saved = true; // (as in step())
    auto f = [&](double dd) {
      if (!saved) row_.restore(snap_);
      saved = false;
      row_.change_velocity(w, dd);
      return row_.measure().FN - F0;
    };
    double k = 4.0 * c_.rheology.G * c_.rheology.tau * row_.a1_now(); // dF_N/dd, one interval
    const double dd = numerics::increasing_root(f, row_.rate_now(), k, 1e-9 * d / c_.rheology.tau,
                                                -1e300, kBalance);
    row_.restore(snap_);
    row_.change_velocity(w, dd);
  }

  /// The segment's step grid (its duration T): the step rule's steps cut at
  /// the lattice T j / n, j = 1 .. n, and at nothing else.
  void begin(double T) {
    undo_side();
    lattice.T = T;
    j_ = 0;
    left_ = 0.0;
    t_seg_ = 0.0;
  }

  /// The row at offset s of the segment (from the offset reached last): the
  /// grid's steps up to s and, where s falls strictly inside one, a side step
  /// to it from the grid's last step end (balanced as the grid's steps are;
  /// the next reach() or begin() returns to the grid as if it never
  /// happened). A segment that has reached its stationary state keeps it
  /// (see Watch).
  void reach(double s) {
    walk(s);
    check_window();
  }
  double t_min = 0.0;
  /// The segment's lattice (its points: LoadLattice::points).
  LoadLattice lattice;
  double a_max = 0.0; ///< the largest leading edge the row's window holds
  /// Where every grid step's end and its mu go (the event metrics' probes:
  /// the grid does not depend on the samples), or nowhere.
  Probes* probes = nullptr;

private:
  /// reach() but for the window.
  void walk(double s) {
    undo_side();
    for (;;) {
      const double pos = lattice.at(j_) - left_;
      if (LoadLattice::near(s, pos) || (j_ == lattice.n && !(left_ > 0.0))) return;
      if (!(left_ > 0.0)) {
        check_window(); // (at every lattice point, whatever the samples)
        ++j_;
        left_ = lattice.at(j_) - lattice.at(j_ - 1);
        continue;
      }
      if (watch_.frozen()) { // (the state stays)
        if (s < lattice.at(j_) && !LoadLattice::near(s, lattice.at(j_))) return;
        t_seg_ += left_;
        left_ = 0.0;
        probe(t_seg_);
        continue;
      }
      double h = std::min(std::max(eps_ * t_seg_, first_ * acc_ * t_min), h_err_);
      const double n = std::ceil(left_ / h);
      h = n > 1.0 ? left_ / n : left_;
      const double end = n > 1.0 ? pos + h : lattice.at(j_);
      if (s < end && !LoadLattice::near(s, end)) return side_step(s - pos);
      if (!step(h)) continue;
      t_seg_ += h;
      probe(t_seg_);
      left_ = n > 1.0 ? left_ - h : 0.0;
      watch(h);
    }
  }
  /// The row's contact within its window, else the run is abandoned.
  void check_window() const {
    if (row_.a1_now() > a_max)
      throw CaseAbandoned("row: under load the contact grew past its window (a1 = " +
                          format_number(row_.a1_now()) + ")");
  }
  /// One balanced step of h off the grid (no error control, no node pushed).
  void side_step(double h) {
    side_k_ = k_;
    side_at_ = at_;
    side_ = true;
    step(h, true);
  }
  /// Back to the grid's last step end (step() saved it in snap_).
  void undo_side() {
    if (!side_) return;
    row_.restore(snap_);
    k_ = side_k_;
    at_ = side_at_;
    side_ = false;
  }

  void probe(double t) {
    if (probes == nullptr) return; // (the state the balance accepted: measured last)
    probes->t.push_back(t);
    probes->mu.push_back(at_.mu);
  }

  /// The segment's stationary state under F0 (watch_ decides when it holds).
  void start_watch(double w) { watch_.start(w, true); }
  void watch(double h) {
    watch_.moved(watch_w_ * h);
    if (!watch_.due()) return;
    const State& ss = states_.at(watch_w_);
    if (!(ss.FN > 0.0)) return watch_.stop();
    watch_.check(row_.depth_now() / ss.d - 1.0,
                 (at_.mu - ss.mu) / std::max(std::abs(ss.mu), kNegligibleFriction));
  }

  bool step(double h, bool side = false) {
    row_.renumber();
    row_.save(snap_);
    if (n_ == 0) restart();
    const double F0 = c_.loading.F0, d0 = row_.depth_now();
    const Slope slope = end_slope(h);
    // trials measure the edge where the nodes predict it (no replays); the
    // accepted depth balances the forces with the confirmed edge
    spectrum::Edge edge = spectrum::Edge::Predicted;
    bool saved = true; // the row is at snap_ (the first trial need not restore it)
    auto f = [&](double d1) {
      if (!saved) row_.restore(snap_);
      saved = false;
      row_.advance(h, d1, slope.a * d1 + slope.b);
      at_ = row_.measure(edge);
      return at_.FN - F0;
    };
    // (on a segment's first step from the rate just after the change: a
    // dashpot's balance there; from d0 alone the cone at zeta0 2.3 after a
    // tenfold step up found no balance, F_N 0.75% over F0)
    const double pred = extrapolated(h);
    const double guess = std::max(0.5 * d0, n_ > 1 ? pred : d0 + h * row_.rate_now());
    if (!(k_ > 0.0)) k_ = 2.0 * c_.loading.F0 / d0; // Hertz: F ~ d^1.5
    double x = guess, fx = f(x);
    balance(f, x, fx, guess, d0);
    edge = spectrum::Edge::Confirmed;
    at_ = row_.measure(edge);
    fx = at_.FN - F0;
    balance(f, x, fx, x, d0);
    if (side) return true;
    if (n_ >= kOrder) { // the predictor's miss against eps^3 d (see StepRule)
      // (at least 100 times the balance's own noise, and never below the
      // shortest step: a miss made of the secant's tolerance shortens nothing)
      const double miss = std::abs(x - pred) / x, h_min = 1e-6 * t_min;
      const double r = miss / std::max(acc_ * acc_ * acc_, 100.0 * ftol_);
      h_err_ = std::max(h_min, h * std::clamp(0.9 / std::cbrt(r), 0.2, 2.0));
      if (r > 1.0 && h > h_min) {
        row_.restore(snap_);
        return false;
      }
    }
    push(h, x);
    return true;
  }

  /// Secant iterations on f from x (f(x) = fx, the row advanced to x); the row
  /// is left at the accepted depth (|F_N - F0| <= ftol), else at a bracketed
  /// root from `from`.
  template <class F> void balance(F& f, double& x, double& fx, double from, double d0) {
    const double ftol = ftol_ * c_.loading.F0;
    for (int n = 0; n < 6 && std::abs(fx) > ftol; ++n) {
      const double xn = std::max(0.5 * x, x - fx / k_), fn = f(xn);
      if (xn != x && (fn - fx) / (xn - x) > 0.0) k_ = (fn - fx) / (xn - x);
      x = xn;
      fx = fn;
    }
    if (std::abs(fx) > ftol) {
      x = numerics::increasing_root(f, from, k_, tol_ * d0, 0.0, kBalance);
      fx = f(x);
    }
  }

  /// The depth rate at the step's end is a d1 + b: the derivative there of the
  /// polynomial through the segment's last kOrder depths and d1 (BDF of that
  /// order; backward Euler on a segment's first step).
  struct Slope {
    double a, b;
  };
  Slope end_slope(double h) const {
    const double tn = t_[0] + h; // nodes t_[0] (latest) .. t_[n_-1]
    Slope s{0.0, 0.0};
    for (std::size_t j = 0; j < n_; ++j) {
      s.a += 1.0 / (tn - t_[j]);
      s.b += basis(j, tn) / (t_[j] - tn) * d_[j];
    }
    return s;
  }
  /// The depth at the step's end extrapolated from the segment's last depths.
  double extrapolated(double h) const {
    double sum = 0.0;
    for (std::size_t j = 0; j < n_; ++j)
      sum += basis(j, t_[0] + h) * d_[j];
    return sum;
  }
  /// The Lagrange basis polynomial of node j over the segment's last nodes, at t.
  double basis(std::size_t j, double t) const {
    double l = 1.0;
    for (std::size_t i = 0; i < n_; ++i)
      if (i != j) l *= (t - t_[i]) / (t_[j] - t_[i]);
    return l;
  }
  void push(double h, double d1) {
    const double t1 = t_[0] + h;
    n_ = std::min(n_ + 1, kOrder);
    for (std::size_t i = n_ - 1; i > 0; --i) {
      t_[i] = t_[i - 1];
      d_[i] = d_[i - 1];
    }
    t_[0] = t1;
    d_[0] = d1;
  }
  void restart() {
    h_err_ = std::numeric_limits<double>::infinity();
    n_ = 1;
    t_[0] = 0.0;
    d_[0] = row_.depth_now();
  }

  const Case& c_;
  spectrum::Row& row_;
  double cells_, eps_, acc_, first_, tol_, ftol_; ///< eps_ grows the steps, acc_ bounds the miss
  spectrum::Row::Snapshot snap_;
  State at_; ///< the row measured at the last depth tried
  static constexpr std::size_t kOrder = 3;
  std::size_t n_ = 0;
  double t_[4] = {}, d_[4] = {}, k_ = 0.0;
  double h_err_ = std::numeric_limits<double>::infinity();
  StationaryWatch watch_;
  StationaryStates& states_;
  double watch_w_ = 0.0;
  double left_ = 0.0, t_seg_ = 0.0; ///< left_: to the lattice point j_
  long j_ = 0;
  bool side_ = false; ///< the row is at a side step's end
  double side_k_ = 0.0;
  State side_at_;
};

// The pre-state: stationary sliding at the depth where the row's F_N is F0
// (the closed-form depth d_pre, corrected by the discretisation: secant steps).
void start_under_load(spectrum::Row& row, const Case& c, double d_pre, double rtol) {
  const double F0 = c.loading.F0;
  // the first secant slope: the elastic contact's F ~ d^m near d_pre
  const double m = c.indenter.force_exponent(d_pre);
  double d = d_pre, slope = m * F0 / d;
  row.start_stationary(c.history.v0, d);
  double f = row.measure().FN - F0;
  for (int n = 0; n < 8 && std::abs(f) > 1e-4 * rtol * F0; ++n) {
    const double dn = d - f / slope;
    row.start_stationary(c.history.v0, dn);
    const double fn = row.measure().FN - F0;
    if (fn != f) slope = (fn - f) / (dn - d);
    d = dn;
    f = fn;
  }
}

ResolutionRun run_once_load(const Case& c, const spectrum::Law& law, double cells, double phase,
                            double fine, const SpectrumOptions& o, const RunControl& control,
                            StationaryStates& states) {
  const LoadGeometry geo = load_geometry(c);
  const double dx = geo.a_ref / cells, a_win = geo.a_win + 4.0 * dx;
  if (!(a_win / dx < 4.0 * kMaxCells))
    throw CaseAbandoned("row: the window under load would hold " + format_number(2.0 * a_win / dx) +
                        " elements (at most 8e5)");
  spectrum::Row row(c, law, geo.d_pre, dx, a_win, phase, o.sub_travel, kEdgeTol * o.rtol, control,
                    kName);
  row.set_layer_width(geo.a_ref / fine);
  row.set_composed(o.composed_steps);
  start_under_load(row, c, geo.d_pre, o.rtol);
  LoadRun run(c, row, cells, kBalanceTol * o.rtol,
              StationaryWatch(o.rtol, 2.0 * a_win, o.keep_stationary), states);
  run.t_min = geo.t_min;
  run.lattice.n = LoadLattice::points(cells, fine);
  run.a_max = a_win - 2.0 * dx;
  ResolutionRun out;
  out.probes.assign(c.history.size(), Probes{});
  std::size_t k = 0; // the segment's (after its change)
  long j = 0;        // its next sample
  out.series = sample_history(
      c, control,
      [&](double w) {
        run.begin(c.history.segments[k].T);
        run.change(w);
        run.probes = nullptr; // (no change: the samples suffice)
        if (c.history.before(k) != w) {
          run.probes = &out.probes[k];
          run.probes->t.push_back(0.0);
          run.probes->mu.push_back(row.measure().mu);
        }
        ++k;
        j = 0;
      },
      [&](double, double) {
        run.reach(c.sampling.offset(k - 1, j++, c.history.segments[k - 1].T));
      },
      [&] { return row.measure(); });
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
