#include "core/solvers/exact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/numerics/phi.hpp"
#include "core/numerics/root.hpp"

namespace mdrmap {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// phi2(z) = (exp(-z) - 1 + z) / z^2 (numerics/phi.hpp).
double phi2(double z) {
  return numerics::phi(2, z);
}

/// Geometry and material the tail arithmetic needs.
struct Frame {
  double a1, R, tau;
  double h(double x) const { return (a1 - x) * (a1 + x) / R; }
};

// The piece `p` (valid at a segment start) after a time dt at velocity w: the
// material moves by w dt in the frame and relaxes by exp(-dt/tau).
TailPiece advanced(const TailPiece& p, const Frame& f, double w, double dt) {
  if (!(dt > 0.0)) return p;
  TailPiece q = p;
  const double s = dt / f.tau, E = std::exp(-s), om = -std::expm1(-s), delta = w * dt;
  q.lo += delta;
  q.hi += delta;
  if (p.kind == TailPiece::Kind::Quad) {
    q.C = p.C * E;
    q.one_minus_C = p.one_minus_C + p.C * om;
    q.D = p.D + delta;
    return q;
  }
  // c0 = h(xa) - A and c1 = g'(xa) - A/lam at the moved anchor, from
  // h(xa + delta) = h(xa) - g'(xa) delta - delta^2/R; r s = delta/lam.
  const double r = w * f.tau / p.lam;
  const double relax = s < 1.0 ? (1.0 - r) * s - s * s * phi2(s) : om - r * s; // (1-E) - r s
  q.c0 = p.c0 - p.c1 * delta - delta * delta / f.R + p.A * relax;
  q.c1 = p.c1 + 2.0 * delta / f.R + p.A / p.lam * om;
  q.xa = p.xa + delta;
  q.a1_minus_xa = p.a1_minus_xa - delta;
  q.A = p.A * E;
  return q;
}

/// Gap h - u of an (advanced) Exp piece at y = x - xa.
double exp_gap(const TailPiece& p, const Frame& f, double y) {
  return p.c0 - p.c1 * y - y * y * (1.0 / f.R + p.A * phi2(y / p.lam) / (p.lam * p.lam));
}

/// Gap h - u of the (advanced) piece at x: >= 0 where the material touches.
double gap(const TailPiece& p, const Frame& f, double x) {
  if (p.kind == TailPiece::Kind::Quad)
    return (p.one_minus_C * (f.a1 - x) * (f.a1 + x) - p.C * p.D * (2.0 * x - p.D)) / f.R;
  return exp_gap(p, f, x - p.xa);
}

/// Outer root of the Quad gap: (1-C)(a1^2 - x^2) = C D (2x - D), cancellation-free.
double quad_root(const TailPiece& p, const Frame& f) {
  const double CD = p.C * p.D;
  const double K = p.one_minus_C * f.a1 * f.a1 + CD * p.D;
  return K / (CD + std::sqrt(CD * CD + p.one_minus_C * K));
}

struct Root {
  double x, a1_minus_x, bracket;
  double iterations; ///< gap evaluations of the root solve
};

/// The front inside piece p, between lo (gap >= 0) and end (gap < 0).
Root piece_root(const TailPiece& p, const Frame& f, double lo, double end, double g_lo,
                double g_end, int bits) {
  if (p.kind == TailPiece::Kind::Quad) {
    const double x = std::clamp(quad_root(p, f), lo, end);
    return {x, f.a1 - x, 4.0 * std::numeric_limits<double>::epsilon() * f.a1, 1.0};
  }
  // in y = x - xa (never through x: xa + y would round y away when y << xa),
  // so that a1 - x = (a1 - xa) - y keeps its digits
  auto g = [&](double y) { return exp_gap(p, f, y); };
  const numerics::Bracket r = numerics::toms748(g, lo - p.xa, end - p.xa, g_lo, g_end,
                                                numerics::bits_tolerance(bits), {"exact: front"});
  const double y = r.mid();
  return {p.xa + y, p.a1_minus_xa - y, r.width(), static_cast<double>(r.evaluations)};
}

} // namespace

ExactSolution::ExactSolution(const Case& c, int bits, const RunControl* control)
    : c_(c), bits_(std::clamp(bits, 8, 52)), control_(control) {
  a1_ = c.a1();
  const double v0 = c.history.v0;
  pre_ = analytic::stationary(c, v0);
  // The free tail of stationary sliding at v0: left contact at a2(v0) with
  // u = h(a2) = g'(a2) v0 tau (force zero), relaxed while carried at v0.
  std::vector<TailPiece> tail;
  if (c.rheology.tau > 0.0) {
    TailPiece p;
    const double a2 = analytic::a2_stationary(c, v0), L = v0 * c.rheology.tau;
    p.lo = a2;
    p.hi = kInf;
    p.xa = a2;
    p.a1_minus_xa = analytic::a1_minus_a2_stationary(c, v0);
    p.A = 2.0 * a2 * L / c.indenter.as<Parabola>().R;
    p.lam = L;
    tail.push_back(p);
  }
  double edge = analytic::a2_stationary(c, v0);
  const auto& segs = c.history.segments;
  t_start_.resize(segs.size());
  double t = 0.0;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    if (k == 0) {
      starts_.push_back(make_start(segs[0].w, std::move(tail), edge));
    } else {
      starts_.push_back(next_start(starts_[k - 1], segs[k - 1].T, segs[k].w));
    }
    t_start_[k] = t;
    t += segs[k].T;
  }
}

// Start of a segment at velocity w with the edge at `edge` and free material
// `tail` behind it: contact beyond the new cap lets go at once (a Quad piece).
SegmentStart ExactSolution::make_start(double w, std::vector<TailPiece> tail, double edge) const {
  SegmentStart seg;
  seg.w = w;
  seg.cap = analytic::a2_stationary(c_, w);
  seg.a1_minus_cap = analytic::a1_minus_a2_stationary(c_, w);
  seg.at_cap = analytic::stationary(c_, w);
  if (c_.rheology.tau > 0.0 && edge > seg.cap) {
    TailPiece q;
    q.kind = TailPiece::Kind::Quad;
    q.lo = seg.cap;
    q.hi = edge;
    tail.insert(tail.begin(), q);
  }
  // material at or beyond a1 can never touch again while w >= 0
  while (!tail.empty() && tail.back().lo >= a1_)
    tail.pop_back();
  seg.tail = std::move(tail);
  seg.at_cap_throughout = seg.tail.empty() || seg.tail.front().lo >= seg.cap;
  if (seg.tail.size() == 1) {
    const TailPiece& p = seg.tail.front();
    seg.gap_at_cap_grows =
        p.kind == TailPiece::Kind::Exp && p.hi == kInf && w * c_.rheology.tau <= p.lam;
    // gap = c0 - c1 y - y^2 (1/R + A phi2(y/lam)/lam^2), y <= Y: |c0| <= |c0| + |A| at the start
    // (h falls outward, A decays), |c1 y| <= (g'(a1) + A/lam) Y, y^2 A phi2/lam^2 <= A Y/lam
    const double Y = std::max(0.0, seg.cap - p.xa), R = c_.indenter.as<Parabola>().R,
                 A = std::abs(p.A);
    seg.cap_margin =
        1e-9 * (std::abs(p.c0) + A + (2.0 * a1_ / R + 2.0 * A / p.lam) * Y + Y * Y / R);
  }
  return seg;
}

ExactSolution::Edge ExactSolution::front(const SegmentStart& seg, double offset) const {
  const Frame f{a1_, c_.indenter.as<Parabola>().R, c_.rheology.tau};
  const Edge at_cap{seg.cap, seg.a1_minus_cap, true};
  last_bracket_ = 0.0;
  // the walk below would stop at the first piece
  if (seg.at_cap_throughout || offset >= seg.at_cap_from) {
    if (!seg.tail.empty()) charge(1.0);
    return at_cap;
  }
  for (const TailPiece& p0 : seg.tail) {
    charge(1.0);
    const TailPiece p = advanced(p0, f, seg.w, offset);
    if (p.lo >= seg.cap) { // the edge material has reached the cap
      // (p.lo only grows with the offset: the walk stops here from now on)
      if (&p0 == &seg.tail.front()) seg.at_cap_from = std::min(seg.at_cap_from, offset);
      return at_cap;
    }
    const double end = std::min(p.hi, seg.cap);
    const double g_end = gap(p, f, end);
    if (g_end >= 0.0) {
      if (end != seg.cap) continue; // the whole piece touches again
      // the gap at any later offset is larger, and positive as computed too
      // (its rounding is far below the margin)
      if (seg.gap_at_cap_grows && g_end >= seg.cap_margin)
        seg.at_cap_from = std::min(seg.at_cap_from, offset);
      return at_cap;
    }
    const double g_lo = gap(p, f, p.lo);
    if (!(g_lo > 0.0)) { // the edge sits on the piece's first material
      const bool anchor = p.kind == TailPiece::Kind::Exp && p.lo == p.xa;
      return {p.lo, anchor ? p.a1_minus_xa : a1_ - p.lo, false};
    }
    ++root_solves_;
    const Root r = piece_root(p, f, p.lo, end, g_lo, g_end, bits_);
    charge(r.iterations);
    last_bracket_ = r.bracket;
    return {r.x, r.a1_minus_x, false};
  }
  return at_cap;
}

double ExactSolution::edge(std::size_t k, double offset) const {
  if (!(c_.rheology.tau > 0.0)) return starts_[k].cap;
  return front(starts_[k], offset).e;
}

double ExactSolution::max_gap_beyond_edge(std::size_t k, double offset, int points) const {
  const SegmentStart& seg = starts_[k];
  const Frame f{a1_, c_.indenter.as<Parabola>().R, c_.rheology.tau};
  const Edge fr = front(seg, offset);
  const bool at_cap = fr.at_cap;
  const double e = fr.e;
  // at the cap, the material that touched again and let go at the cap since
  // it got there is no longer described by the pieces (it relaxes from h(cap))
  const double start = at_cap ? seg.cap + seg.w * (offset - cap_time(seg, offset)) : e;
  double worst = -std::numeric_limits<double>::infinity();
  for (const TailPiece& p0 : seg.tail) {
    const TailPiece p = advanced(p0, f, seg.w, offset);
    const double lo = std::max(p.lo, start), hi = std::min(p.hi, a1_);
    for (int i = 1; i <= points && lo < hi; ++i) {
      const double x = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(points);
      if (x > start + 1e-12 * a1_) worst = std::max(worst, gap(p, f, x));
    }
  }
  return worst / c_.loading.d;
}

// Time in [0, T] at which the front reached x (<= the cap; the cap_time when
// x is the cap, w > 0): the gap at x of the material passing it changes sign
// once, there. Material that was in contact at the segment start counts as
// touching (gap h(x) > 0): the sign changes where it arrives, if the front
// sat on it.
double ExactSolution::arrival(const SegmentStart& seg, double x, double T, int bits) const {
  const Frame f{a1_, c_.indenter.as<Parabola>().R, c_.rheology.tau};
  if (seg.tail.empty() || seg.tail.front().lo >= x) return 0.0;
  auto gap_at_x = [&](double dt) {
    for (const TailPiece& p0 : seg.tail) {
      const TailPiece p = advanced(p0, f, seg.w, dt);
      if (p.hi >= x) return p.lo >= x ? f.h(x) : gap(p, f, x);
    }
    return f.h(x);
  };
  const double g0 = gap_at_x(0.0), gT = gap_at_x(T);
  if (g0 >= 0.0) return 0.0;
  if (gT < 0.0) return T; // (rounding: the front is at x only just)
  return numerics::toms748(gap_at_x, 0.0, T, g0, gT, numerics::bits_tolerance(bits),
                           {"exact", 200, control_})
      .mid();
}

// One Exp piece reaching to infinity: the material at x at time t left its
// place x - w t of the start, so its gap is h(x) - (h(x) - g0(x)) exp(-k t),
// k = 1/tau - w/lam (g0: the gap at t = 0). It touches at
// t = log1p(-g0/h) / k, unless the piece's first material has passed x
// before (the material there was in contact at the start: gap h > 0).
double ExactSolution::arrival_time(const SegmentStart& seg, double x, double T, int bits) const {
  const TailPiece* p = seg.tail.size() == 1 ? &seg.tail.front() : nullptr;
  if (p == nullptr || p->kind != TailPiece::Kind::Exp || p->hi != kInf)
    return arrival(seg, x, T, bits);
  if (p->lo >= x) return 0.0;
  const Frame f{a1_, c_.indenter.as<Parabola>().R, c_.rheology.tau};
  const double g0 = exp_gap(*p, f, x - p->xa);
  if (g0 >= 0.0) return 0.0;
  const double h = (p->a1_minus_xa - (x - p->xa)) * (a1_ + x) / f.R;
  const double k = 1.0 / f.tau - seg.w / p->lam;
  const double t_piece = k > 0.0 ? std::log1p(-g0 / h) / k : kInf;
  const double t_lo = seg.w > 0.0 ? (x - p->lo) / seg.w : kInf;
  return std::min({t_piece, t_lo, T});
}

// The start of the next segment (velocity w_next) from the end of `seg`.
SegmentStart ExactSolution::next_start(const SegmentStart& seg, double T, double w_next) const {
  if (!(c_.rheology.tau > 0.0)) return make_start(w_next, {}, seg.cap);
  const Frame f{a1_, c_.indenter.as<Parabola>().R, c_.rheology.tau};
  const Edge fr = front(seg, T);
  const bool at_cap = fr.at_cap;
  const double e = fr.e;
  const double t_cap = (at_cap && seg.w > 0.0) ? cap_time(seg, T) : T;
  // material that touched again (or is still in contact) is no longer free
  const double consumed = at_cap ? seg.cap + seg.w * (T - t_cap) : e;
  std::vector<TailPiece> tail;
  for (const TailPiece& p0 : seg.tail) {
    TailPiece p = advanced(p0, f, seg.w, T);
    if (p.hi <= consumed) continue;
    p.lo = std::max(p.lo, consumed);
    tail.push_back(p);
  }
  if (at_cap && consumed > seg.cap) { // left contact at the cap since t_cap
    TailPiece p;
    const double L = seg.w * c_.rheology.tau;
    p.lo = p.xa = seg.cap;
    p.a1_minus_xa = seg.a1_minus_cap;
    p.hi = consumed;
    p.A = 2.0 * seg.cap * L / c_.indenter.as<Parabola>().R; // h(cap) by the force-zero condition
    p.lam = L;
    tail.insert(tail.begin(), p);
  }
  return make_start(w_next, std::move(tail), at_cap ? seg.cap : e);
}

State ExactSolution::at(std::size_t k, double offset) const {
  const SegmentStart& seg = starts_[k];
  if (!(c_.rheology.tau > 0.0)) return seg.at_cap; // no memory: stationary at once
  const Edge fr = front(seg, offset);
  if (offset == 0.0) {
    seg.start_edge = fr.e;
    seg.start_a1_minus_edge = fr.a1_minus_e;
    seg.start_at_cap = fr.at_cap;
  }
  if (fr.at_cap) return seg.at_cap;
  return analytic::contact_forces(c_, fr.e, fr.a1_minus_e, seg.w);
}

State ExactSolution::at(double t) const {
  std::size_t k = 0;
  while (k + 1 < t_start_.size() && t >= t_start_[k + 1])
    ++k;
  return at(k, std::max(0.0, t - t_start_[k]));
}

namespace {

/// Error bound of the edge (length): half the root bracket, and the rounding
/// of a1 - e (carried to a few ulps, see TailPiece).
double edge_error(const State& st, double a1, double bracket) {
  return 0.5 * bracket + 8.0 * std::numeric_limits<double>::epsilon() * std::abs(a1 - st.a2);
}

/// Error of the edge `de` carried into F_N, F_x and mu at one sample:
/// dF_N/de = p(e), dF_x/de = p(e) g'(e) with p the edge's force per length.
void add_edge_error(const Case& c, const State& st, double w, double de, State& err) {
  const double p = 4.0 * c.rheology.G * analytic::depth_at(c, st.a2) -
                   4.0 * c.rheology.G * c.rheology.tau * w * c.indenter.slope(st.a2);
  const double dFN = std::abs(p) * de, dFx = std::abs(p * c.indenter.slope(st.a2)) * de;
  err.FN = std::max(err.FN, dFN);
  err.Fx = std::max(err.Fx, dFx);
  err.mu = std::max(err.mu, (dFx + std::abs(st.mu) * dFN) / st.FN);
  err.a2 = std::max(err.a2, de);
}

/// The error bounds of a series in the units of the error metric
/// (docs/design.md, "Error metric": by the largest reference magnitude, or
/// the natural scale where a reference is identically zero).
double relative_error(const Case& c, const Series& s, const State& err) {
  double fn = 0.0, fx = 0.0, mu = 0.0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    fn = std::max(fn, std::abs(s.FN[k]));
    fx = std::max(fx, std::abs(s.Fx[k]));
    mu = std::max(mu, std::abs(s.mu[k]));
  }
  const double scale_mu = std::sqrt(c.loading.d / c.indenter.as<Parabola>().R);
  if (fx == 0.0) fx = fn * scale_mu;
  if (mu == 0.0) mu = scale_mu;
  return std::max({err.FN / fn, err.Fx / fx, err.mu / mu, err.a2 / c.a1()});
}

} // namespace

RunResult run_exact(const CheckedCase& checked, double rtol, const RunControl& control) {
  const Case& c = checked.get();
  require_depth_control(c, "exact");
  require_kelvin(c, "exact");
  require_parabola(c, "exact");
  // Solve the roots to ~10 bits beyond what rtol asks, 52 bits at most.
  const int bits = std::clamp(static_cast<int>(std::ceil(-std::log2(rtol))) + 12, 24, 52);
  ExactSolution ex(c, bits, &control);
  RunResult res;
  res.info.solver = "exact";
  res.info.rtol = rtol;
  res.series.resize(c.total_samples());
  res.series.pre = ex.pre();
  State err; // largest absolute error bound per quantity
  const double a1 = c.a1();
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const double T = c.history.segments[k].T, t0 = c.history.start(k);
    for (long j = 0; j < c.sampling.count(k); ++j, ++i) {
      const double off = c.sampling.offset(k, j, T);
      control.charge(1.0, "exact");
      const State st = ex.at(k, off);
      res.series.set(i, t0 + off, static_cast<int>(k), st);
      control.report(i + 1, res.series.size());
      if (ex.last_bracket() > 0.0)
        add_edge_error(c, st, c.history.segments[k].w, edge_error(st, a1, ex.last_bracket()), err);
    }
  }
  res.transients.reserve(c.history.size());
  for (std::size_t k = 0; k < c.history.size(); ++k)
    res.transients.push_back(ex.transient(k, c.history.segments[k].T));
  res.info.root_solves = ex.root_solves();
  res.info.error_estimate =
      relative_error(c, res.series, err) + 64.0 * std::numeric_limits<double>::epsilon();
  return res;
}

} // namespace mdrmap
