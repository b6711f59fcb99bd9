// The exact solver's transients (exact.hpp, ExactSolution::transient): the
// event metrics of a segment from the continuum solution itself, found by
// root finding, whatever the output instants (docs/design.md, "Event metrics").
//
// Within segment k the state is contact_forces(e, w) of the edge e alone, and
// the edge only moves outward (contact material is carried outward at w >= 0
// and stays in contact below the cap; free material only joins), from its
// value just after the change to the cap, which it reaches at the cap time
// (or never, during a hold). So mu(t) = M(e(t)) with M closed form: the
// extremum and the 1/e level are found on M over the edges the segment
// reaches, and timed by when the front arrives there (ExactSolution::arrival_time: in
// closed form after a drop or a hold out of stationary sliding).
// The edges are scanned on a grid fixed by the segment's start and its cap
// (not by its duration or its samples), then refined by Brent's method or a
// bracketed root to ~40 bits.
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>

#include "core/numerics/root.hpp"
#include "core/solvers/exact.hpp"

namespace mdrmap {
namespace {

// Edges scanned between the start's edge and the cap: M is a ratio of a
// quartic and a cubic in e, with a handful of extrema at most.
constexpr int kGrid = 16;
// Binary digits of the refined edges and times: ~6e-8, far below what the
// metrics are asked to agree to (1e-3), and cheap (the seed's path).
constexpr int kBits = 24;

} // namespace

std::pair<double, double> ExactSolution::refine_extremum(const SegmentStart& seg, double s,
                                                         double lo, double hi,
                                                         double a1_minus_lo) const {
  auto minus = [&](double e) {
    return -s * analytic::contact_forces(c_, e, a1_minus_lo - (e - lo), seg.w).mu;
  };
  std::uintmax_t iters = 100;
  const auto r = boost::math::tools::brent_find_minima(minus, lo, hi, kBits / 2 + 4, iters);
  charge(static_cast<double>(iters));
  return {r.first, -r.second};
}

Transient ExactSolution::transient(std::size_t k, double T) const {
  const SegmentStart& seg = starts_[k];
  const double mu_ss = seg.at_cap.mu;
  Transient r;
  r.mu_max = r.mu_min = mu_ss; // stationary throughout
  if (!(c_.rheology.tau > 0.0) || seg.at_cap_throughout) return r;
  if (std::isnan(seg.start_edge)) at(k, 0.0); // (fills the cache: the first sample did)
  const Edge e0{seg.start_edge, seg.start_a1_minus_edge, seg.start_at_cap};
  const double mu0 =
      e0.at_cap ? mu_ss : analytic::contact_forces(c_, e0.e, e0.a1_minus_e, seg.w).mu;
  r.mu_max = r.mu_min = mu0;
  const double dev0 = mu0 - mu_ss;
  if (e0.at_cap || dev0 == 0.0) return r;
  r.dev_ref = std::abs(dev0);
  // the edges reached within the segment: up to the edge at its end (the cap
  // once the front got there; w > 0)
  // (the walks of the samples may have found the cap earlier: a tighter bracket)
  const double t_end = std::min(T, seg.at_cap_from);
  const Edge fe = front(seg, t_end);
  const double s = dev0 > 0.0 ? 1.0 : -1.0, h = (seg.cap - e0.e) / kGrid;
  double E[kGrid + 1], Y[kGrid + 1]; // edge, s (mu - mu_ss)
  int n = 0;
  for (; n < kGrid && e0.e + n * h < fe.e; ++n) {
    E[n] = e0.e + n * h;
    Y[n] = s * (analytic::contact_forces(c_, E[n], e0.a1_minus_e - n * h, seg.w).mu - mu_ss);
  }
  E[n] = fe.e;
  Y[n] =
      fe.at_cap ? 0.0 : s * (analytic::contact_forces(c_, fe.e, fe.a1_minus_e, seg.w).mu - mu_ss);
  ++n;
  charge(n);
  // the time at which the edge reaches e (the segment's end for its last edge)
  auto time_of = [&](int i, double e) {
    if (i == 0) return 0.0;
    if (i == n - 1 && !fe.at_cap) return t_end;
    return arrival_time(seg, e, t_end, kBits);
  };
  // an extremum of sign * Y: at a grid edge, or refined between its neighbours
  auto extremum = [&](double sign, double* t) {
    const int i = static_cast<int>(
        std::max_element(Y, Y + n, [&](double a, double b) { return sign * a < sign * b; }) - Y);
    if (i == 0 || i == n - 1) {
      *t = time_of(i, E[i]);
      return sign * Y[i];
    }
    const double sg = s * sign; // sign * Y = sg mu - sg mu_ss
    const auto [e, v] =
        refine_extremum(seg, sg, E[i - 1], E[i + 1], e0.a1_minus_e - (E[i - 1] - e0.e));
    if (!(v - sg * mu_ss > sign * Y[i])) {
      *t = time_of(i, E[i]);
      return sign * Y[i];
    }
    *t = time_of(i, e);
    return v - sg * mu_ss;
  };
  double t_near = 0.0, t_far = 0.0;
  const double near = extremum(1.0, &t_near), far = extremum(-1.0, &t_far);
  // (near: the extremum on mu(0+)'s side of mu_ss; far: on the other side)
  const double mu_near = mu_ss + s * near, mu_far = mu_ss - s * far;
  r.mu_max = s > 0.0 ? mu_near : mu_far;
  r.t_max = s > 0.0 ? t_near : t_far;
  r.mu_min = s > 0.0 ? mu_far : mu_near;
  r.t_min = s > 0.0 ? t_far : t_near;
  // (an excursion beyond mu_ss above the rounding of mu)
  const double floor = 1e-12 * std::max(std::abs(mu_ss), std::abs(mu0));
  r.overshoot = far > floor ? far / std::abs(dev0) : 0.0;
  // the first grid edge at or below 1/e, and the crossing before it
  const double level = std::abs(dev0) / std::exp(1.0);
  const int i = static_cast<int>(std::find_if(Y, Y + n, [&](double y) { return y <= level; }) - Y);
  if (i == n) return r;
  auto above = [&](double e) {
    return s * (analytic::contact_forces(c_, e, e0.a1_minus_e - (e - e0.e), seg.w).mu - mu_ss) -
           level;
  };
  const numerics::Bracket root =
      numerics::toms748(above, E[i - 1], E[i], Y[i - 1] - level, Y[i] - level,
                        numerics::bits_tolerance(kBits), {"exact", 100, control_});
  r.t_decay = arrival_time(seg, root.mid(), t_end, kBits);
  return r;
}

} // namespace mdrmap
