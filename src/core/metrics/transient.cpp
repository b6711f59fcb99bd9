#include "core/metrics/transient.hpp"

#include <algorithm>
#include <cmath>

namespace mdrmap {
namespace {

/// The parabola through three points at t.
double parabola(const double* t, const double* f, double x) {
  const double l0 = (x - t[1]) * (x - t[2]) / ((t[0] - t[1]) * (t[0] - t[2]));
  const double l1 = (x - t[0]) * (x - t[2]) / ((t[1] - t[0]) * (t[1] - t[2]));
  const double l2 = (x - t[0]) * (x - t[1]) / ((t[2] - t[0]) * (t[2] - t[1]));
  return f[0] * l0 + f[1] * l1 + f[2] * l2;
}

} // namespace

TransientTracker::TransientTracker(double mu_ss, double mu0, Reference ref, double direction)
    : mu_ss_(mu_ss), ref_(ref), direction_(direction >= 0.0 ? 1.0 : -1.0) {
  add(0.0, mu0);
}

// x holds the extremum of s * (mu - offset) over the points before the newest
// one: complete its right neighbour, or take the newest point.
bool TransientTracker::offer(Extremum& x, double s, double offset) const {
  const P& now = last_[2];
  if (x.n == 2) {
    x.at[2] = now;
    x.n = 3;
  }
  if (!(s * (now.mu - offset) > x.value)) return false;
  x.value = s * (now.mu - offset);
  x.at[0] = last_[1];
  x.at[1] = now;
  x.n = count_ == 1 ? 1 : 2;
  return true;
}

void TransientTracker::new_reference() {
  ref_point_ = last_[2];
  side_ = ref_point_.mu >= mu_ss_ ? 1.0 : -1.0;
  dev_ = std::abs(ref_point_.mu - mu_ss_);
  beyond_ = Extremum{};
  t_decay_ = Transient::kNaN;
}

void TransientTracker::add(double t, double mu) {
  last_[0] = last_[1];
  last_[1] = last_[2];
  last_[2] = P{t, mu};
  ++count_;
  const bool new_max = offer(max_, 1.0, 0.0), new_min = offer(min_, -1.0, 0.0);
  if (count_ == 1 || (ref_ == Reference::Peak && (direction_ > 0.0 ? new_max : new_min))) {
    new_reference();
    return;
  }
  offer(beyond_, -side_, mu_ss_);
  find_crossing();
}

// The first point at or below 1/e of the reference's deviation: the crossing
// lies after the previous one (on the parabola through the three latest
// points once there are three).
void TransientTracker::find_crossing() {
  const double level = dev_ / std::exp(1.0);
  const P a = last_[1], b = last_[2];
  const double ya = side_ * (a.mu - mu_ss_), yb = side_ * (b.mu - mu_ss_);
  if (!std::isnan(t_decay_) || !(dev_ > 0.0) || yb > level) return;
  double lo = a.t, hi = b.t;
  if (count_ >= 3) {
    const double ts[3] = {last_[0].t, a.t, b.t};
    const double fs[3] = {side_ * (last_[0].mu - mu_ss_), ya, yb};
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (parabola(ts, fs, mid) > level ? lo : hi) = mid;
    }
    t_decay_ = 0.5 * (lo + hi);
  } else {
    t_decay_ = a.t + (ya - level) / (ya - yb) * (b.t - a.t);
  }
}

// The extremum's value s * (mu - offset), at the vertex of the parabola
// through it and its neighbours where that lies beyond it.
double TransientTracker::vertex(const Extremum& x, double s, double offset, double* t) {
  *t = x.at[1].t;
  if (x.n < 3) return x.value;
  const double ts[3] = {x.at[0].t, x.at[1].t, x.at[2].t};
  const double fs[3] = {s * (x.at[0].mu - offset), x.value, s * (x.at[2].mu - offset)};
  const double d0 = ts[1] - ts[0], d2 = ts[1] - ts[2];
  const double den = d0 * (fs[1] - fs[2]) - d2 * (fs[1] - fs[0]);
  if (!(den > 0.0)) return x.value; // flat or not concave: the point itself
  const double tv = std::clamp(
      ts[1] - 0.5 * (d0 * d0 * (fs[1] - fs[2]) - d2 * d2 * (fs[1] - fs[0])) / den, ts[0], ts[2]);
  const double fv = parabola(ts, fs, tv);
  if (!(fv > x.value)) return x.value;
  *t = tv;
  return fv;
}

Transient TransientTracker::result() const {
  Transient r;
  r.mu_max = vertex(max_, 1.0, 0.0, &r.t_max);
  r.mu_min = -vertex(min_, -1.0, 0.0, &r.t_min);
  if (ref_ == Reference::Peak) r.t_ref = direction_ > 0.0 ? r.t_max : r.t_min;
  r.dev_ref = dev_;
  r.ref_at_end = ref_ == Reference::Peak && count_ > 1 && ref_point_.t == last_[2].t;
  r.t_decay = t_decay_;
  double t_beyond = 0.0;
  const double beyond = beyond_.n > 0 ? vertex(beyond_, -side_, mu_ss_, &t_beyond) : 0.0;
  r.overshoot = dev_ > 0.0 && beyond > 0.0 ? beyond / dev_ : 0.0;
  return r;
}

} // namespace mdrmap
