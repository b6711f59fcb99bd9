#include "core/solvers/load_steps.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/metrics/error_metric.hpp"
#include "core/numerics/run_control.hpp"

namespace mdrmap {

void LoadStepper::begin(double T, TransientTracker* tracker, double w, const State& stationary) {
  undo_side();
  w_ = w;
  stationary_ = stationary;
  watch_.start(w, stationary.FN > 0.0);
  lattice_.T = T;
  // (fixed steps: the grid is the steps of dt_over_tau tau from the change,
  // evened out to end on the segment's end; an order test halves them)
  lattice_.n = s_.dt_over_tau > 0.0 ? 1 : s_.lattice_n;
  j_ = 1;
  h_ = tau_ * 1e-2 * std::cbrt(s_.time_tol);
  tracker_ = tracker;
}

void LoadStepper::reach(double s) {
  undo_side();
  for (;;) {
    if (watch_.frozen()) return keep(s);
    const double t = row_.t();
    if (!(s > t) || LoadLattice::near(s, t)) return;
    while (j_ < lattice_.n && !(lattice_.at(j_) > t))
      ++j_;
    const double point = lattice_.at(j_), left = point - t;
    if (!(left > 0.0)) return side_step(s); // (s past the segment's end)
    // the step control's step, evened out over what is left to the lattice
    // point (no sliver of a step before it)
    const double h0 = s_.dt_over_tau > 0.0 ? s_.dt_over_tau * tau_ : h_;
    const double n = std::ceil(left / h0 * (1.0 - 1e-12));
    const double h = n > 1.0 ? left / n : left, end = n > 1.0 ? t + h : point;
    if (s < end && !LoadLattice::near(s, end)) return side_step(s);
    if (!(t + h > t))
      throw CaseAbandoned("kelvin_load: the time step (" + format_number(h) +
                          ") fell below the resolution of the time " + format_number(t) +
                          " within its segment");
    grid_step(h, !(n > 1.0), point);
  }
}

void LoadStepper::grid_step(double h, bool to_point, double point) {
  const long taken = steps_;
  if (s_.dt_over_tau > 0.0 || (to_point && h <= 1e-12 * (std::abs(point) + tau_))) {
    LoadRow::Trial tr = row_.trial(h, h);
    if (to_point) tr.t_end = point;
    row_.commit(tr);
    track();
    ++steps_;
  } else {
    adaptive_step(h, to_point, point);
  }
  row_.rebase_time();
  if (steps_ > taken) watch(h);
}

// The watch after a grid step of h: the depth and mu against the stationary
// state under load, after each traverse (run_once sets it: load.cpp).
void LoadStepper::watch(double h) {
  watch_.moved(w_ * h);
  if (!watch_.due()) return;
  const double mu = row_.measure().mu;
  watch_.check(row_.d() / stationary_.d - 1.0,
               (mu - stationary_.mu) / std::max(std::abs(stationary_.mu), kNegligibleFriction));
  kept_ = row_.t();
  kept_mu_ = mu;
}

// A frozen segment: the row stays where it froze (its state is every later
// sample's), and the tracker sees that state at the lattice points up to s.
void LoadStepper::keep(double s) {
  for (; j_ <= lattice_.n; ++j_) {
    const double point = lattice_.at(j_);
    if (!(point > kept_) || LoadLattice::near(point, kept_)) continue;
    if (s < point && !LoadLattice::near(s, point)) return;
    if (tracker_ != nullptr) tracker_->add(point, kept_mu_);
    kept_ = point;
  }
}

// A trial outside the window is a rejected step; but when the edge already
// sits at the window's limit, smaller steps only creep closer: the run needs
// a wider window.
void LoadStepper::reject_outside(const LoadRow::Trial& a, const LoadRow::Trial& b) const {
  if (row_.at_window_edge() && (std::isfinite(a.d) || std::isfinite(b.d)))
    throw WindowExceeded("kelvin_load: the leading edge reached the element window's limit");
}

// Step doubling: one step of h against two of h/2; the two-step result is
// kept and the local error taken as their difference / 3, for d, D relative
// to d and e to a1 (cube-root control). A step shortened by the lattice
// (h < h_) grows the next one from h_, not from itself.
void LoadStepper::adaptive_step(double h, bool to_point, double point) {
  // (a trial that leaves the window is a rejected step, e.g. an undeformed
  // start, where D is unbounded as d -> 0)
  const LoadRow::Trial big = row_.trial(h, h), half = row_.trial(0.5 * h, h);
  if (!row_.fits(big) || !row_.fits(half)) {
    reject_outside(big, half);
    h_ = 0.25 * h;
    return;
  }
  row_.checkpoint();
  row_.commit(half);
  const double t_mid = row_.t(), mu_mid = row_.measure().mu;
  LoadRow::Trial two = row_.trial(0.5 * h, h);
  if (!row_.fits(two)) {
    row_.rollback();
    reject_outside(two, two);
    h_ = 0.25 * h;
    return;
  }
  const double err = std::max({std::abs(two.d - big.d) / two.d,
                               std::abs(two.D - big.D) / std::max(two.d, std::abs(two.D)),
                               std::abs(two.e - big.e) / std::sqrt(two.d * row_.R())}) /
                     3.0;
  const double fac = err > 0.0 ? 0.9 * std::cbrt(s_.time_tol / err) : 5.0;
  if (!(err <= s_.time_tol || h < 1e-14 * tau_)) {
    row_.rollback();
    h_ = h * std::clamp(fac, 0.1, 0.9);
    return;
  }
  if (to_point) two.t_end = point;
  row_.commit(two);
  row_.release();
  if (tracker_ != nullptr) tracker_->add(t_mid, mu_mid);
  track();
  ++steps_;
  const double next = h * std::clamp(fac, 0.2, 5.0);
  h_ = h < h_ && fac >= 1.0 ? std::max(h_, next) : next;
}

// Two balanced half steps from the grid's last step end to s (what a grid
// step keeps), no error control; halved further where a trial leaves the
// window.
void LoadStepper::side_step(double s) {
  const double h = s - row_.t();
  row_.checkpoint();
  side_ = true;
  for (int parts = 2;; parts *= 2) {
    const double hp = h / parts;
    int i = 0;
    for (; i < parts; ++i) {
      LoadRow::Trial tr = row_.trial(hp, 2.0 * hp);
      if (!row_.fits(tr)) {
        reject_outside(tr, tr);
        break;
      }
      if (i == parts - 1) tr.t_end = s;
      row_.commit(tr);
    }
    if (i == parts) return;
    row_.rollback();
    if (parts >= 1024)
      throw CaseAbandoned("kelvin_load: no balanced step reaches the sample at " +
                          format_number(s) + " within its segment");
    row_.checkpoint();
  }
}

void LoadStepper::undo_side() {
  if (!side_) return;
  row_.rollback();
  side_ = false;
}

void LoadStepper::track() {
  if (tracker_ != nullptr) tracker_->add(row_.t(), row_.measure().mu);
}

} // namespace mdrmap
