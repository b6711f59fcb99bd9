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

/// A deviation |mu(0+) - mu_ss| at or below this fraction of |mu_ss| is the
/// rounding of a solver that lands on the stationary state (a rise out of
/// stationary sliding at fixed depth, a cone's plateau on the Kelvin
/// foundation): no transient, whatever the noise after it shows.
constexpr double kRoundingDeviation = 1e-12;

TransientTracker::TransientTracker(double mu_ss, double mu0)
    : mu_ss_(mu_ss), side_(mu0 >= mu_ss ? 1.0 : -1.0), dev0_(std::abs(mu0 - mu_ss)) {
  if (dev0_ <= kRoundingDeviation * std::abs(mu_ss)) dev0_ = 0.0;
  add(0.0, mu0);
}

// x holds the extremum of s * y over the points before the newest one (their
// count: last_n): complete its right neighbour, or take the newest point.
void TransientTracker::offer(Extremum& x, double s, int last_n) {
  const P& now = last_[2];
  if (x.n == 2) {
    x.at[2] = now;
    x.n = 3;
  }
  if (s * now.y > x.value) {
    x.value = s * now.y;
    x.at[0] = last_[1];
    x.at[1] = now;
    x.n = last_n == 0 ? 1 : 2;
  }
}

void TransientTracker::add(double t, double mu) {
  const int before = count_;
  last_[0] = last_[1];
  last_[1] = last_[2];
  last_[2] = P{t, (mu - mu_ss_) * side_};
  ++count_;
  offer(peak_near_, 1.0, before);
  offer(peak_far_, -1.0, before);
  const double level = dev0_ / std::exp(1.0);
  if (!std::isnan(t_decay_) || before == 0 || !(dev0_ > 0.0) || last_[2].y > level) return;
  // the first point at or below 1/e: the crossing lies after the previous one
  // (on the parabola through the three latest points once there are three)
  const P a = last_[1], b = last_[2];
  double lo = a.t, hi = b.t;
  if (before >= 2) {
    const double ts[3] = {last_[0].t, a.t, b.t}, fs[3] = {last_[0].y, a.y, b.y};
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (parabola(ts, fs, mid) > level ? lo : hi) = mid;
    }
    t_decay_ = 0.5 * (lo + hi);
  } else {
    t_decay_ = a.t + (a.y - level) / (a.y - b.y) * (b.t - a.t);
  }
}

double TransientTracker::vertex(const Extremum& x, double s, double* t) {
  *t = x.at[1].t;
  if (x.n < 3) return x.value;
  const double ts[3] = {x.at[0].t, x.at[1].t, x.at[2].t};
  const double fs[3] = {s * x.at[0].y, x.value, s * x.at[2].y};
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
  double t_near = 0.0, t_far = 0.0;
  const double near = vertex(peak_near_, 1.0, &t_near), far = vertex(peak_far_, -1.0, &t_far);
  const bool far_wins = far > near;
  r.mu_peak = mu_ss_ + side_ * (far_wins ? -far : near);
  r.t_peak = far_wins ? t_far : t_near;
  r.t_decay = t_decay_;
  r.overshoot = dev0_ > 0.0 && far > 0.0 ? far / dev0_ : 0.0;
  return r;
}

} // namespace mdrmap
