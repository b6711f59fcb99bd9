// The element row under load control (spectrum_runs.hpp): the depth that
// balances F_N = F0 at every step's end; run_spectrum (spectrum.cpp)
// dispatches here when c.loading.by_force().
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "core/metrics/error_metric.hpp"
#include "core/metrics/stationary.hpp"
#include "core/numerics/root.hpp"
#include "core/solvers/load_lattice.hpp"
#include "core/solvers/spectrum_row.hpp"
#include "core/solvers/spectrum_runs.hpp"
#include "core/solvers/stationary_watch.hpp"

namespace mdrmap {
using namespace spectrum::detail;
namespace {

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
  void start_watch(double w) {
    watch_.start(w, true);
    if (!(w > 0.0)) return;
    const State& ss = states_.at(w);
    if (ss.FN > 0.0) watch_.set_traverse(2.0 * ss.a1);
  }
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

} // namespace

ResolutionRun spectrum::detail::run_once_load(const Case& c, const spectrum::Law& law, double cells,
                                              double phase, double fine, const SpectrumOptions& o,
                                              const RunControl& control, StationaryStates& states) {
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

} // namespace mdrmap
