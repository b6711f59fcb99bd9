// The trailing edge of the mdr element row (core/solvers/mdr_row.hpp), read
// to sub-grid accuracy, and the pieces, tracers and ghosts that carry what it
// needs.
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
#include "core/solvers/mdr_row.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <boost/math/tools/toms748_solve.hpp>

#include "core/metrics/analytic.hpp"

namespace mdrmap::mdr {
namespace {

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

} // namespace

// Nodes and tracers with x in [x0, x1], sorted by x; at the same x a node in
// contact comes first and a free node last (a boundary placed on a node lies
// between the contact and the tail); the tracers of a boundary keep their
// order.
std::vector<Site> Row::sites_in(double x0, double x1) const {
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
// the first free site after it (see the comment at the top).
Edge Row::read_edge(long long jb) const {
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
  } else { // no marked boundary between pieces (should not happen): extend F's
           // piece back
    root = root_on(profile(F.piece, F, nullptr), C.x, F.x);
  }
  if (root >= cap) return at_cap;
  return Edge{root, F.piece, false, false};
}

// Profile of piece q anchored at site a: for a cap piece log-linear through b
// if given (else with its known slope -1/(w tau)), for material let go the
// parabola through its ghosts.
Profile Row::profile(int q, const Site& a, const Site* b) const {
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
double Row::root_on(const Profile& p, double lo, double hi) const {
  return solve([&](double x) { return p.a.psi + dh(p.a.x, x) - p.du(x); }, lo, hi);
}

// Edge between a contact site c and a free site f of the same piece.
double Row::cell_root(const Site& c, const Site& f) const {
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
void Row::mark_cap_boundary() {
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
void Row::let_go(double cap, const Edge& e) {
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

// Inserted after the tracers at the same x: the pair of a boundary keeps its
// order.
void Row::add_tracer(const Site& t) {
  const auto at = std::upper_bound(tracers_.begin(), tracers_.end(), t.x,
                                   [](double v, const Site& a) { return v < a.x; });
  tracers_.insert(at, t);
}

void Row::add_boundary(const Site& left, const Site& right) {
  add_tracer(left);
  add_tracer(right);
}

// Tracers that mark nothing any more: in contact behind the last contact node
// (the front has passed them; they stay in contact until the cap), or beyond
// the window.
void Row::prune_tracers() {
  const long long jb = last_contact_node();
  const double xb = jb >= jlo_ ? xi(jb) : -a1_;
  const double far = a1_ + 3.0 * dx_;
  tracers_.erase(
      std::remove_if(tracers_.begin(), tracers_.end(),
                     [&](const Site& t) { return (t.contact && t.x < xb) || t.x > far; }),
      tracers_.end());
}

} // namespace mdrmap::mdr
