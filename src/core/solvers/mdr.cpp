#include "core/solvers/mdr.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include <boost/math/tools/toms748_solve.hpp>

#include "core/metrics/analytic.hpp"
#include "core/metrics/error_metric.hpp"

// The discrete model. Element j sits at lab position x_j = (j + phase) dx; the
// moving coordinate is xi_j = x_j + s(t), so the indenter occupies [-a1, a1]
// in xi and elements enter at -a1 and leave at +a1 (h < 0 beyond: they can
// never touch again while v >= 0). Only that window is stored (ring buffer):
// memory is independent of the travel distance.
//
// Time integration is exact for piecewise-constant velocity w, so the only
// error left is the spatial one (dx):
//  - an element in contact follows the indenter: u = h(xi), u' = -w g'(xi);
//    its force 4 G dx (h - tau w g') turns negative exactly where xi passes
//    a2(w), the stationary trailing edge, where it detaches with u = h(a2(w));
//  - a free element relaxes as u = u0 exp(-t/tau) (stable for any dt and for
//    tau = 0);
//  - a free element touches again when u <= h(xi). Once touched (with
//    xi < a2(w)) it stays in contact until a2(w), because there its contact
//    force is positive; so "has it touched during the step" is answered by
//    one comparison at the end of the step (or where it reaches a2(w)).
// Untouched material ahead of the indenter is simply free with u = 0.
//
// Forces at a sample are quadratures of the element forces (force per unit
// length p = 4 G (h - tau w g')) over the contact nodes, with the partial
// cells at both ends integrated on the cubic through the nearest nodes: the
// integrands are cubics in xi, so the only error left is the sub-grid location
// of the trailing edge (docs/design.md, "The discrete solvers").
//
// Sub-grid trailing edge. Free material is labelled with the piece it belongs
// to, and the event that freed it fixes the form of its depression u(x):
//  - material that left contact at the cap a2(w) while sliding at w (the tail
//    of stationary sliding included): u = u0 exp(-(x - x0)/(w tau)), ln u
//    linear in x;
//  - material let go at once at a velocity change (beyond the new cap):
//    u = C h(x - D), the indenter depth where it let go, decayed by C and
//    carried a distance D: one parabola in x.
// An element that was free before and touched again keeps its free
// continuation (what u would be had it stayed free), so it is a point of its
// piece's profile too. Each element also carries its gap psi = h - u, updated
// without cancellation: the edge is a root of psi, and where new contact
// grows from a tangency (a hold, a drop) psi is a tiny difference of large
// terms. The edge lies between the last site in contact and the first free
// site after it; between two sites of one piece psi is interpolated in the
// piece's own form (log-linear through the two sites; the parabola through
// three "ghosts" of the piece, free continuations that never touch), which is
// exact, and its root is the edge. So the read-out holds across segments at
// any dx: what is left is rounding.
// Piece boundaries are not on the grid, so tracers mark them: a tracer is one
// more element at a material point, stepped exactly like the nodes, and a
// boundary is a pair of tracers at the same point, one for the material on
// each side (u may jump there). Tracers are placed where boundaries arise:
//  - at a velocity change, at the trailing edge (contact | tail) and, after a
//    rise, at the new cap (contact | material let go);
//  - at the end of a segment whose front reached the cap, where the material
//    that left at the cap meets the older tail: where their two profiles meet
//    (the material that was at the cap when the front got there).
// Contact material that was never free carries no profile (piece kNoPiece).
// MdrSubgrid::Linear interpolates psi linearly between the same two sites
// (second order), MdrSubgrid::None is the paper's last element in contact.

namespace mdrmap {
namespace {

constexpr int kNoPiece = -1; // material without a free profile

/// A piece of free material: how it was freed fixes the form of its profile.
struct Piece {
  /// Left contact at the cap (u log-linear), else let go at a change (a parabola).
  bool at_cap = true;
  double lam = 0.0; ///< at_cap: decay length w tau of the profile
};

/// An element (node or tracer): its free depression u (the free continuation
/// while in contact), the gap psi = h - u, carried along without cancellation
/// (the edge is a root of psi, and psi is a small difference of large terms
/// where new contact grows from a tangency), the piece whose profile u
/// belongs to, and its position (nodes: filled in when read).
struct Site {
  double x = 0.0;
  double u = 0.0;
  double psi = 0.0;
  int piece = kNoPiece;
  bool contact = false;
};

/// The trailing edge as read off the row.
struct Edge {
  double x = 0.0;
  int piece = kNoPiece; ///< piece of the free material just beyond the edge
  bool at_cap = false;  ///< the edge is the cap a2(w)
  bool marked = false;  ///< a pair of tracers already marks it
};

/// Free depression of one piece near an anchor site a, in the piece's form:
/// u = a.u + du(x) with du log-linear (cap pieces) or from a parabola
/// P(x) = c1 (x - x0) + c2 (x - x0)(x - x1) (material let go at a change).
struct Profile {
  Site a;
  bool log_linear = false;
  double k = 0.0; ///< d ln u / dx (log-linear)
  double c1 = 0.0, c2 = 0.0, x0 = 0.0, x1 = 0.0;
  double du(double x) const {
    const double y = x - a.x;
    if (log_linear) return a.u * std::expm1(k * y);
    return y * (c1 + c2 * (x + a.x - x0 - x1)); // P(x) - P(a.x)
  }
  double u(double x) const { return log_linear ? a.u * std::exp(k * (x - a.x)) : a.u + du(x); }
  double log_u(double x) const { // (-inf where u <= 0)
    if (log_linear) return std::log(a.u) + k * (x - a.x);
    const double v = u(x);
    return v > 0.0 ? std::log(v) : -std::numeric_limits<double>::infinity();
  }
};

/// Three free continuations of a piece let go at a change, spread around it. Its depression u = C
/// h(x - D) (the depth where it let go, decayed by C, carried a distance D) is one parabola for all
/// x, and these never touch, so they keep its shape known wherever its material went (sites of the
/// piece leave it as they touch again and reach the cap).
struct Ghosts {
  int piece = kNoPiece;
  double near_end = 0.0; ///< material at the piece's near end: pruned once past the window
  Site g[3];
};

/// One exact time step at constant velocity: decay exp(-dt/tau), 1 - decay,
/// the cap a2(w) and the indenter depth there.
struct Step {
  double dt, dec, omd, a2w, h_a2w;
};

// Root of f on [lo, hi] with f(lo) > 0 > f(hi); the end itself when the sign
// condition fails there (rounding at a tangency).
template <class F> double solve(F f, double lo, double hi) {
  const double flo = f(lo), fhi = f(hi);
  if (!(flo > 0.0)) return lo;
  if (!(fhi < 0.0)) return hi;
  std::uintmax_t iters = 100;
  const auto r = boost::math::tools::toms748_solve(
      f, lo, hi, flo, fhi, boost::math::tools::eps_tolerance<double>(50), iters);
  return 0.5 * (r.first + r.second);
}

class MdrRow {
public:
  MdrRow(const Case& s, double cells_per_a1, double phase, MdrSubgrid subgrid,
         const RunControl& control)
      : s_(s), a1_(analytic::a1(s)), dx_(a1_ / cells_per_a1), phase_(phase), subgrid_(subgrid),
        control_(control) {
    cap_ = static_cast<std::size_t>(std::floor(2.0 * cells_per_a1)) + 5;
    nodes_.assign(cap_, Site{});
  }

  std::size_t capacity() const { return cap_; }
  long updates() const { return updates_; }
  long steps() const { return steps_; }

  /// Stationary state at velocity w at position P = s/dx (cells).
  void init_stationary(double w, long double P) {
    w_ = w;
    set_position(P);
    cap_piece_ = new_piece(true, w * s_.rheology.tau);
    const double a2w = analytic::a2_stationary(s_, w);
    const double L = w * s_.rheology.tau;
    const double h_a2 = h(a2w); // as where elements leave the cap (leave_at_cap)
    for (long long j = jlo_; j <= jhi_; ++j) {
      const double x = xi(j);
      Site& n = nodes_[slot(j)];
      if (x <= a2w) {
        n = Site{x, 0.0, h(x), kNoPiece, true};
      } else { // free tail of stationary sliding: left the cap, relaxed while carried at w
        const double y = x - a2w;
        n = Site{x, h_a2 * std::exp(-y / L), dh(a2w, x) - h_a2 * std::expm1(-y / L), cap_piece_,
                 false};
      }
    }
  }

  /// Indenter pressed into an undeformed foundation at position P, at rest.
  void init_undeformed(long double P) {
    w_ = 0.0;
    set_position(P);
    cap_piece_ = new_piece(true, 0.0);
    for (long long j = jlo_; j <= jhi_; ++j)
      nodes_[slot(j)] = Site{xi(j), 0.0, h(xi(j)), kNoPiece, xi(j) <= a1_};
  }

  /// Instantaneous velocity change to w: contact elements whose force turns
  /// negative (xi > a2(w)) let go at once with u = h(xi). Tracers mark the
  /// trailing edge (and the new cap after a rise); see the header comment.
  void change_velocity(double w) {
    control_.charge(static_cast<double>(jhi_ - jlo_ + 1), "mdr");
    const long long jb = last_contact_node();
    const bool any = jb >= jlo_;
    const Edge e = any ? read_edge(jb) : Edge{};
    if (any && e.at_cap && w_ > 0.0) mark_cap_boundary();
    w_ = w;
    seg_time_ = 0.0;
    cap_piece_ = new_piece(true, w * s_.rheology.tau);
    const double cap = std::min(analytic::a2_stationary(s_, w), a1_);
    if (any && e.x > cap) {
      let_go(cap, e);
    } else if (any && !e.marked) { // contact material | the free piece beyond, at psi = 0
      add_boundary(Site{e.x, 0.0, h(e.x), kNoPiece, true}, Site{e.x, h(e.x), 0.0, e.piece, false});
    }
    prune_tracers();
  }

  /// Advance by dt at the current velocity; exact.
  void advance(double dt) {
    if (dt <= 0.0) return;
    ++steps_;
    seg_time_ += dt;
    rebase();
    const long double P0 = P_;
    const double shift = w_ * dt / dx_; // cells travelled
    const long long jlo0 = jlo_, jhi0 = jhi_;
    const double theta0 = theta_;
    const long long m0 = m_;
    set_position(P0 + static_cast<long double>(shift));
    const double a2w = analytic::a2_stationary(s_, w_);
    const Step st{dt, decay(dt), one_minus_decay(dt), a2w, h(a2w)};
    for (long long j = jlo_; j <= jhi_; ++j) {
      Site& n = nodes_[slot(j)];
      const double xe = xi(j);
      const double xs = (static_cast<double>(j + m0) + theta0 + phase_) * dx_; // at step start
      if (j < jlo0 || j > jhi0) // entered during the step: untouched material, free with u = 0
        n = Site{xs, 0.0, h(xs), kNoPiece, false};
      step_element(n, xs, xe, st);
    }
    updates_ += jhi_ - jlo_ + 1;
    carry_markers(w_ * dt, st);
    // the step's element updates, tracers and ghost sites
    control_.charge(static_cast<double>(jhi_ - jlo_ + 1) +
                        static_cast<double>(tracers_.size() + 3 * ghosts_.size()),
                    "mdr");
  }

  /// Forces and trailing edge of the current state.
  State measure() const {
    control_.charge(static_cast<double>(jhi_ - jlo_ + 1), "mdr");
    // first and last contact node
    long long ja = jhi_ + 1, jb = jlo_ - 1;
    for (long long j = jlo_; j <= jhi_; ++j) {
      if (nodes_[slot(j)].contact) {
        ja = std::min(ja, j);
        jb = j;
      }
    }
    State st;
    if (ja > jb) { // no node in contact (coarser than the contact itself)
      st.a2 = -a1_;
      return st;
    }
    const double xb = xi(jb), xn = xb + dx_;
    const double xr =
        std::clamp(std::min(read_edge(jb).x, a1_), xb, std::max(xb, std::min(xn, a1_)));
    st.FN = integrate(ja, jb, xr, [&](double x) { return pressure(x); });
    st.Fx =
        integrate(ja, jb, xr, [&](double x) { return pressure(x) * (-2.0 * x / s_.indenter.R); });
    st.mu = st.Fx / st.FN;
    st.d = s_.loading.d;
    st.a1 = a1_;
    st.a2 = xr;
    return st;
  }

private:
  // Tracers and ghosts over a step in which the material moves by ds; those
  // past the window are dropped (they can never touch or neighbour the edge).
  void carry_markers(double ds, const Step& st) {
    for (Site& t : tracers_) {
      const double xs = t.x;
      t.x = xs + ds;
      step_element(t, xs, t.x, st);
    }
    for (Ghosts& G : ghosts_) {
      G.near_end += ds;
      for (Site& g : G.g) {
        const double xs = g.x;
        g.x = xs + ds;
        relax(g, xs, g.x, st.dec, st.omd);
      }
    }
    const double far = a1_ + 3.0 * dx_;
    tracers_.erase(
        std::remove_if(tracers_.begin(), tracers_.end(), [&](const Site& t) { return t.x > far; }),
        tracers_.end());
    ghosts_.erase(std::remove_if(ghosts_.begin(), ghosts_.end(),
                                 [&](const Ghosts& G) { return G.near_end > far; }),
                  ghosts_.end());
  }

  // Integral over [-a1, xr] of f sampled at the contact nodes ja..jb: the
  // 4th-order Gregory rule (end-corrected trapezoid, exact for cubics) over
  // the nodes, and the two partial cells [-a1, xi_a] and [xi_b, xr]
  // integrated exactly (2-point Gauss) on the cubic through the four nearest
  // nodes. The contact integrands (p and p * (-g')) are cubics in xi, so the
  // only error left is the sub-grid location of the trailing edge. This
  // matters where F_x is a tiny difference of large contributions (v tau <<
  // a1): a first- or second-order sum would swamp it.
  template <class F> double integrate(long long ja, long long jb, double xr, F f) const {
    const long long n = jb - ja + 1;
    const double xa = xi(ja), xb = xi(jb);
    if (subgrid_ == MdrSubgrid::None) { // the paper's raw element sum
      long double acc = 0.0L;
      for (long long j = ja; j <= jb; ++j)
        acc += static_cast<long double>(f(xi(j)));
      return dx_ * static_cast<double>(acc);
    }
    if (n < 8) { // too few nodes for the high-order rule: trapezoid with flat ends
      double sum = 0.0;
      for (long long j = ja; j <= jb; ++j)
        sum += f(xi(j));
      const double fa = f(xa), fb = f(xb);
      return dx_ * (sum - 0.5 * (fa + fb)) + fa * (xa + a1_) + fb * (xr - xb);
    }
    // long double accumulator: F_x is a small difference of large terms of
    // both signs, and its rounding noise would otherwise grow with the count
    long double acc = 0.0L;
    for (long long j = ja; j <= jb; ++j)
      acc += static_cast<long double>(f(xi(j)));
    double sum = static_cast<double>(acc);
    const double fa[4] = {f(xa), f(xa + dx_), f(xa + 2 * dx_), f(xa + 3 * dx_)};
    const double fb[4] = {f(xb), f(xb - dx_), f(xb - 2 * dx_), f(xb - 3 * dx_)};
    constexpr double c0 = 3.0 / 8.0 - 1.0, c1 = 7.0 / 6.0 - 1.0, c2 = 23.0 / 24.0 - 1.0;
    sum += c0 * (fa[0] + fb[0]) + c1 * (fa[1] + fb[1]) + c2 * (fa[2] + fb[2]);
    const double left = partial_cell(fa, (xa + a1_) / dx_);
    const double right = partial_cell(fb, (xr - xb) / dx_);
    return dx_ * (sum + left + right);
  }

  // Integral over s in [0, len] (in cells, pointing away from the nodes) of the
  // cubic through values g[k] at s = -k, k = 0..3.
  static double partial_cell(const double g[4], double len) {
    if (len <= 0.0) return 0.0;
    auto cubic = [&](double s) { // Lagrange form in r = -s (nodes at r = 0..3)
      const double r = -s;
      return g[0] * (r - 1) * (r - 2) * (r - 3) / -6.0 + g[1] * r * (r - 2) * (r - 3) / 2.0 +
             g[2] * r * (r - 1) * (r - 3) / -2.0 + g[3] * r * (r - 1) * (r - 2) / 6.0;
    };
    const double off = len / (2.0 * std::sqrt(3.0));
    return 0.5 * len * (cubic(0.5 * len - off) + cubic(0.5 * len + off));
  }

  // One element (node or tracer) over a step from xs to xe, exactly. An
  // element that leaves at the cap takes the piece of this segment's cap.
  void step_element(Site& el, double xs, double xe, const Step& st) const {
    if (el.contact) {
      if (xe <= st.a2w) return relax(el, xs, xe, st.dec, st.omd);
      return leave_at_cap(el, xe, (st.a2w - xs) / w_, st); // (w > 0 here since xe > xs)
    }
    if (xs >= st.a2w) return relax(el, xs, xe, st.dec, st.omd); // force would be negative
    if (xe <= st.a2w) {
      relax(el, xs, xe, st.dec, st.omd);
      if (el.psi >= 0.0) el.contact = true; // touched again
      return;
    }
    // crosses a2(w) during the step: touched before iff in contact there
    const double dt_c = (st.a2w - xs) / w_;
    Site at_cap = el;
    relax(at_cap, xs, st.a2w, decay(dt_c), one_minus_decay(dt_c));
    if (at_cap.psi >= 0.0) return leave_at_cap(el, xe, dt_c, st);
    relax(el, xs, xe, st.dec, st.omd);
  }

  // Free relaxation (or the free continuation) while carried from xs to xe:
  // u -> u dec, psi -> psi + h(xe) - h(xs) + u (1 - dec).
  void relax(Site& el, double xs, double xe, double dec, double omd) const {
    el.psi += dh(xs, xe) + el.u * omd;
    el.u *= dec;
  }

  // Left contact at the cap a time dt_c into the step; free since.
  void leave_at_cap(Site& el, double xe, double dt_c, const Step& st) const {
    const double r = st.dt - dt_c;
    el.u = st.h_a2w * decay(r);
    el.psi = dh(st.a2w, xe) + st.h_a2w * one_minus_decay(r);
    el.contact = false;
    el.piece = cap_piece_;
  }

  double decay(double dt) const {
    if (s_.rheology.tau > 0.0) return std::exp(-dt / s_.rheology.tau);
    return dt > 0.0 ? 0.0 : 1.0;
  }
  double one_minus_decay(double dt) const {
    if (s_.rheology.tau > 0.0) return -std::expm1(-dt / s_.rheology.tau);
    return dt > 0.0 ? 1.0 : 0.0;
  }

  double h(double x) const { return (a1_ - x) * (a1_ + x) / s_.indenter.R; }
  double dh(double xa, double xb) const { return (xa - xb) * (xa + xb) / s_.indenter.R; }
  double pressure(double x) const { // contact force per unit length
    return 4.0 * s_.rheology.G * (h(x) - s_.rheology.tau * w_ * 2.0 * x / s_.indenter.R);
  }

  void set_position(long double P) {
    P_ = P;
    const long double fl = std::floor(P);
    m_ = static_cast<long long>(fl);
    theta_ = static_cast<double>(P - fl);
    const double c = a1_ / dx_;
    // xi_j = (j + m + theta + phase) dx in [-a1, a1]
    jlo_ = static_cast<long long>(std::ceil(-c - theta_ - phase_)) - m_;
    // one node past a1 is kept: it can never touch, but its free depression
    // locates a trailing edge that lies between the last node and a1
    jhi_ = static_cast<long long>(std::floor(c - theta_ - phase_)) - m_ + 1;
  }

  // Keeps the travel counter P small: after a long way its rounding would
  // shift the nodes against the tracers. Moving it by a whole number of ring
  // lengths renumbers the elements but keeps every slot.
  void rebase() {
    const long long ring = static_cast<long long>(cap_);
    if (m_ < (1LL << 24)) return;
    const long long K = (m_ / ring) * ring;
    P_ -= static_cast<long double>(K);
    m_ -= K;
    jlo_ += K;
    jhi_ += K;
  }

  double xi(long long j) const { return (static_cast<double>(j + m_) + theta_ + phase_) * dx_; }
  std::size_t slot(long long j) const {
    const auto c = static_cast<long long>(cap_);
    return static_cast<std::size_t>(((j % c) + c) % c);
  }
  Site node(long long j) const {
    Site n = nodes_[slot(j)];
    n.x = xi(j);
    return n;
  }
  long long last_contact_node() const {
    for (long long j = jhi_; j >= jlo_; --j)
      if (nodes_[slot(j)].contact) return j;
    return jlo_ - 1;
  }
  int new_piece(bool at_cap, double lam) {
    pieces_.push_back(Piece{at_cap, lam});
    return static_cast<int>(pieces_.size()) - 1;
  }
  // u(b) - u(a) of two sites, from their gaps: no cancellation.
  double udiff(const Site& a, const Site& b) const { return dh(a.x, b.x) - (b.psi - a.psi); }

  std::vector<Site> sites_in(double x0, double x1) const;
  Edge read_edge(long long jb) const;
  Profile profile(int q, const Site& a, const Site* b) const;
  double root_on(const Profile& p, double lo, double hi) const;
  double cell_root(const Site& c, const Site& f) const;
  void mark_cap_boundary();
  void let_go(double cap, const Edge& e);
  void add_tracer(const Site& t);
  void add_boundary(const Site& left, const Site& right);
  void prune_tracers();

  Case s_;
  double a1_, dx_, phase_;
  MdrSubgrid subgrid_;
  const RunControl& control_;
  std::size_t cap_;
  std::vector<Site> nodes_;      // ring buffer over the window (x filled in by node())
  std::vector<Piece> pieces_;    // every piece made so far
  int cap_piece_ = kNoPiece;     // piece of material leaving at the cap in this segment
  std::vector<Site> tracers_;    // sorted by x; a boundary is a pair at one x
  std::vector<Ghosts> ghosts_;   // of the pieces let go at a change, while in the window
  long double P_ = 0.0L;         // travel s/dx in cells
  long long m_ = 0;              // floor(P)
  double theta_ = 0.0;           // P - m
  long long jlo_ = 0, jhi_ = -1; // element ids in the window
  double w_ = 0.0;
  double seg_time_ = 0.0; // time since the last velocity change
  long updates_ = 0, steps_ = 0;
};

// Nodes and tracers with x in [x0, x1], sorted by x; at the same x a node in
// contact comes first and a free node last (a boundary placed on a node lies
// between the contact and the tail); the tracers of a boundary keep their order.
std::vector<Site> MdrRow::sites_in(double x0, double x1) const {
  std::vector<Site> out;
  long long j = static_cast<long long>(std::ceil(x0 / dx_ - theta_ - phase_)) - m_ - 1;
  j = std::max(j, jlo_);
  while (j <= jhi_ && xi(j) < x0)
    ++j;
  auto t = std::lower_bound(tracers_.begin(), tracers_.end(), x0,
                            [](const Site& a, double x) { return a.x < x; });
  while (true) {
    const bool node_ok = j <= jhi_ && xi(j) <= x1;
    const bool tracer_ok = t != tracers_.end() && t->x <= x1;
    if (!node_ok && !tracer_ok) break;
    const bool node_first =
        node_ok && (!tracer_ok || xi(j) < t->x || (xi(j) == t->x && nodes_[slot(j)].contact));
    if (node_first) {
      out.push_back(node(j++));
    } else {
      out.push_back(*t++);
    }
  }
  return out;
}

// The trailing edge between the last contact node jb and node jb + 1: the cap
// a2(w) where contact forces vanish, the point of a marked boundary where the
// contact ends, or the root of the gap between the last site in contact and
// the first free site after it (see the header comment).
Edge MdrRow::read_edge(long long jb) const {
  const double cap = std::min(analytic::a2_stationary(s_, w_), a1_);
  const Edge at_cap{cap, cap_piece_, true, false};
  const double xb = xi(jb);
  if (subgrid_ == MdrSubgrid::None) { // the paper: last element in contact
    if (xb >= cap) return at_cap;
    return Edge{xb, kNoPiece, false, false};
  }
  // tau = 0: free material has u = 0 at once, the contact reaches the cap
  if (!(s_.rheology.tau > 0.0) || jb >= jhi_) return at_cap;
  const std::vector<Site> s = sites_in(xb, xi(jb + 1));
  std::size_t c = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i].contact) c = i;
  if (c + 1 >= s.size()) return at_cap;
  const Site &C = s[c], &F = s[c + 1];
  // material that left at the cap in this segment: the contact reaches the cap
  if (F.piece == cap_piece_ && w_ > 0.0) return at_cap;
  if (C.x == F.x) { // a marked boundary: the contact ends there
    if (C.x >= cap) return at_cap;
    return Edge{C.x, F.piece, false, true};
  }
  double root = 0.0;
  if (C.piece == F.piece && F.piece != kNoPiece) {
    root = cell_root(C, F);
  } else { // no marked boundary between pieces (should not happen): extend F's piece back
    root = root_on(profile(F.piece, F, nullptr), C.x, F.x);
  }
  if (root >= cap) return at_cap;
  return Edge{root, F.piece, false, false};
}

// Profile of piece q anchored at site a: for a cap piece log-linear through b
// if given (else with its known slope -1/(w tau)), for material let go the
// parabola through its ghosts.
Profile MdrRow::profile(int q, const Site& a, const Site* b) const {
  Profile p;
  p.a = a;
  if (q == kNoPiece) return p; // untouched material: u = 0 (a.u = 0)
  const Piece& piece = pieces_[static_cast<std::size_t>(q)];
  if (piece.at_cap) {
    if (!(a.u > 0.0)) return p; // (u underflowed to 0: stays 0)
    p.log_linear = true;
    p.k = -1.0 / piece.lam;
    if (b && b->u > 0.0 && b->x != a.x) { // ln(u_b/u_a): from the gaps if close, else directly
      const double r = udiff(a, *b) / a.u;
      p.k = (std::abs(r) < 0.5 ? std::log1p(r) : std::log(b->u / a.u)) / (b->x - a.x);
    }
    return p;
  }
  const auto G =
      std::find_if(ghosts_.begin(), ghosts_.end(), [&](const Ghosts& x) { return x.piece == q; });
  if (G == ghosts_.end()) { // (none: linear through a and b)
    if (b && b->x != a.x) p.c1 = udiff(a, *b) / (b->x - a.x);
    return p;
  }
  const Site* g = G->g;
  const double d01 = udiff(g[0], g[1]) / (g[1].x - g[0].x);
  const double d12 = udiff(g[1], g[2]) / (g[2].x - g[1].x);
  p.c1 = d01;
  p.c2 = (d12 - d01) / (g[2].x - g[0].x);
  p.x0 = g[0].x;
  p.x1 = g[1].x;
  return p;
}

// Root in [lo, hi] of the gap psi = h - u along the profile p, written from
// its anchor: psi(x) = psi(a) + h(x) - h(a) - du(x).
double MdrRow::root_on(const Profile& p, double lo, double hi) const {
  return solve([&](double x) { return p.a.psi + dh(p.a.x, x) - p.du(x); }, lo, hi);
}

// Edge between a contact site c and a free site f of the same piece.
double MdrRow::cell_root(const Site& c, const Site& f) const {
  if (!(c.psi > 0.0)) return c.x;
  if (!(f.psi < 0.0)) return f.x;
  if (subgrid_ == MdrSubgrid::Linear) return c.x + (f.x - c.x) * c.psi / (c.psi - f.psi);
  return root_on(profile(f.piece, c, &f), c.x, f.x);
}

// End of a segment (w > 0) whose edge sits at the cap: the material that left
// at the cap in this segment (piece cap_piece_, u = h(cap) exp(-(x - cap)/lam))
// reaches out to the material that was at the cap when the front got there.
// Unless a pair of tracers marks that point, it lies between the last site of
// the cap piece and the first site of the older piece, where their profiles
// meet (the older material there had just touched again: the same depression).
void MdrRow::mark_cap_boundary() {
  const double cap = std::min(analytic::a2_stationary(s_, w_), a1_);
  const double lam = w_ * s_.rheology.tau;
  if (!(lam > 0.0)) return;
  Site prev{cap, h(cap), 0.0, cap_piece_, false};
  for (const Site& s : sites_in(cap, a1_ + 3.0 * dx_)) {
    if (s.contact) continue;
    if (s.piece == cap_piece_) {
      prev = s;
      continue;
    }
    if (s.x == prev.x) return; // marked
    // the cap piece's form holds only for what left the cap in this segment
    const double hi = std::min(s.x, std::max(prev.x, cap + w_ * seg_time_));
    Profile mine;
    mine.a = prev;
    mine.log_linear = true;
    mine.k = -1.0 / lam;
    const Profile older = profile(s.piece, s, nullptr);
    // where the profiles meet (in ln u: they span many decades over a cell)
    const double B = solve(
        [&](double x) { return mine.log_u(x) - std::max(older.log_u(x), -1e300); }, prev.x, hi);
    auto at = [&](const Profile& p, int q) {
      return Site{B, p.u(B), p.a.psi + dh(p.a.x, B) - p.du(B), q, false};
    };
    add_boundary(at(mine, cap_piece_), at(older, s.piece));
    return;
  }
}

// A rise (or a restart after a hold) with the edge e beyond the new cap: the
// contact material in (cap, e] lets go at once (u = h, psi = 0: a new piece),
// marked at both ends, its shape kept by three ghosts.
void MdrRow::let_go(double cap, const Edge& e) {
  const int q = new_piece(false, 0.0);
  auto release = [&](Site& el, double x) {
    if (el.contact && x > cap) el = Site{el.x, h(x), 0.0, q, false};
  };
  for (long long j = jlo_; j <= jhi_; ++j)
    release(nodes_[slot(j)], xi(j));
  for (Site& t : tracers_)
    release(t, t.x);
  if (!e.marked)
    add_boundary(Site{e.x, h(e.x), 0.0, q, false}, Site{e.x, h(e.x), 0.0, e.piece, false});
  add_boundary(Site{cap, 0.0, h(cap), kNoPiece, true}, Site{cap, h(cap), 0.0, q, false});
  Ghosts G;
  G.piece = q;
  G.near_end = cap;
  const double mid = 0.5 * (cap + e.x);
  for (int i = 0; i < 3; ++i) {
    const double x = mid + (i - 1) * 0.25 * a1_; // (any spread: one parabola for all x)
    G.g[i] = Site{x, h(x), 0.0, q, false};
  }
  ghosts_.push_back(G);
}

// Inserted after the tracers at the same x: the pair of a boundary keeps its order.
void MdrRow::add_tracer(const Site& t) {
  const auto at = std::upper_bound(tracers_.begin(), tracers_.end(), t.x,
                                   [](double v, const Site& a) { return v < a.x; });
  tracers_.insert(at, t);
}

void MdrRow::add_boundary(const Site& left, const Site& right) {
  add_tracer(left);
  add_tracer(right);
}

// Tracers that mark nothing any more: in contact behind the last contact node
// (the front has passed them; they stay in contact until the cap), or beyond
// the window.
void MdrRow::prune_tracers() {
  const long long jb = last_contact_node();
  const double xb = jb >= jlo_ ? xi(jb) : -a1_;
  const double far = a1_ + 3.0 * dx_;
  tracers_.erase(
      std::remove_if(tracers_.begin(), tracers_.end(),
                     [&](const Site& t) { return (t.contact && t.x < xb) || t.x > far; }),
      tracers_.end());
}

struct SingleRun {
  Series series;
  long elements = 0, steps = 0, updates = 0;
};

/// Travel over the whole history, in cells: element ids are 64-bit integers
/// counted from it, so absurd scenes (e.g. w tau / a1 = 1e300) are refused.
void check_travel(const Case& c, double cells) {
  const double dx = c.a1() / cells;
  double travel = 2.0 * cells + 4.0;
  for (const auto& seg : c.history.segments)
    travel += seg.w * seg.T / dx;
  if (!(travel < 1e18))
    throw std::runtime_error("mdr: the indenter travels " + format_number(travel) +
                             " cells over the history, more than the element row can count "
                             "(1e18); use the exact solver");
}

// Undeformed foundation, indenter pressed in, then sliding at v0 over
// 2 a1 + 2 dx: every element in the window has then entered fresh at the
// leading edge, so the stationary state must be reproduced. Several uneven
// steps exercise the event handling.
void spin_up(MdrRow& row, const Case& c, double cells) {
  const double a1 = c.a1(), dx = a1 / cells;
  const double travel = 2.0 * a1 + 2.0 * dx;
  row.init_undeformed(static_cast<long double>(-travel / dx));
  row.change_velocity(c.history.v0);
  const int nsteps = 7;
  const double T = travel / c.history.v0;
  double done = 0.0;
  for (int i = 1; i <= nsteps; ++i) {
    const double target = T * (static_cast<double>(i * i) / (nsteps * nsteps));
    row.advance(target - done);
    done = target;
  }
}

SingleRun run_once(const Case& c, double cells, double phase, const MdrOptions& opt,
                   const RunControl& control) {
  check_travel(c, cells);
  MdrRow row(c, cells, phase, opt.subgrid, control);
  if (opt.spinup)
    spin_up(row, c, cells);
  else
    row.init_stationary(c.history.v0, 0.0L);
  SingleRun out;
  out.series.resize(c.total_samples());
  out.series.pre = row.measure();
  std::size_t i = 0;
  for (std::size_t k = 0; k < c.history.size(); ++k) {
    const Segment& seg = c.history.segments[k];
    const double t0 = c.history.start(k);
    row.change_velocity(seg.w);
    double prev = 0.0;
    for (long j = 0; j < c.sampling.samples; ++j, ++i) {
      const double off = c.sampling.offset(j, seg.T);
      row.advance(off - prev); // exact: no steps needed between samples
      prev = off;
      out.series.set(i, t0 + off, static_cast<int>(k), row.measure());
    }
  }
  out.elements = static_cast<long>(row.capacity());
  out.steps = row.steps();
  out.updates = row.updates();
  return out;
}

// Starting resolution. The per-piece sub-grid edge is exact for every history
// at any dx, so start coarse (the error control refines if the companion
// disagrees); the linear edge converges like (dx/a1)^2 and the paper's raw
// sums like dx/a1, with constants ~1 on the hard set.
double initial_cells(const MdrOptions& o) {
  double c = 32.0;
  if (o.subgrid == MdrSubgrid::Linear) c = 1.5 / std::sqrt(o.rtol);
  if (o.subgrid == MdrSubgrid::None) c = 0.7 / o.rtol;
  return std::clamp(std::ceil(c), 16.0, 1e7);
}

// An estimate below this is rounding noise of the two runs, not a resolution error.
constexpr double kRoundingLevel = 1e-11;

} // namespace

RunResult run_mdr(const Case& s, const MdrOptions& opt) {
  validate(s);
  require_depth_control(s, "mdr");
  require_kelvin(s, "mdr");
  RunResult res;
  res.info.solver = "mdr";
  res.info.rtol = opt.rtol;
  double cells = opt.cells_per_a1 > 0.0 ? opt.cells_per_a1 : initial_cells(opt);
  if (!(cells >= 2.0) || cells > 1e8)
    throw InvalidInput("cells-per-a1", "must be between 2 and 1e8");
  const bool adaptive = opt.cells_per_a1 <= 0.0;
  // The companion runs at half the resolution and with its elements shifted by
  // a non-commensurate fraction of a cell, so that an error of the sub-grid
  // read-out that depends on where the grid falls is not shared by both runs.
  const double companion_phase = std::fmod(opt.phase + 0.381966, 1.0);
  const RunControl own;
  const RunControl& control = opt.control != nullptr ? *opt.control : own;
  double prev_est = 0.0;
  for (int attempt = 0;; ++attempt) {
    SingleRun fine = run_once(s, cells, opt.phase, opt, control);
    res.info.steps += fine.steps;
    res.info.element_updates += fine.updates;
    res.info.refinements = attempt + 1;
    double est = 0.0;
    if (opt.estimate_error || adaptive) {
      // with convergence of order p the difference is ~(2^p - 1) times the
      // error of the fine run; report it whole. Where both runs are exact
      // it is rounding noise of either sign: add a rounding floor, as exact does.
      SingleRun coarse = run_once(s, 0.5 * cells, companion_phase, opt, control);
      res.info.steps += coarse.steps;
      res.info.element_updates += coarse.updates;
      est = case_error(coarse.series, fine.series, s, 1e-12).max() +
            64.0 * std::numeric_limits<double>::epsilon();
    }
    res.series = std::move(fine.series);
    res.info.error_estimate = est;
    res.info.cells_per_a1 = cells;
    res.info.elements = fine.elements;
    // refining no longer helps once the estimate is rounding noise (it no
    // longer falls); an estimate above rtol after the last refinement fails
    const bool stagnant = attempt > 0 && est > 0.5 * prev_est && est < kRoundingLevel;
    prev_est = est;
    if (!adaptive || est <= opt.rtol) break;
    if (stagnant || attempt >= 5 || cells >= 1e7)
      throw CaseAbandoned("mdr: the error estimate " + format_number(est) + " stays above rtol " +
                          format_number(opt.rtol) + " after " + std::to_string(attempt + 1) +
                          " resolutions (a1/dx up to " + format_number(cells) +
                          "); the case cannot meet rtol with this solver");
    cells = std::min(1e7, std::ceil(cells * std::max(1.5, 1.2 * std::sqrt(est / opt.rtol))));
  }
  return res;
}

} // namespace mdrmap
