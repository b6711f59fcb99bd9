// The element row of mdr: its states, the exact time step and the forces
// (core/solvers/mdr_row.hpp describes the model).
#include "core/solvers/mdr_row.hpp"

#include <algorithm>
#include <cmath>

#include "core/metrics/analytic.hpp"

namespace mdrmap::mdr {

Row::Row(const Case& s, double cells_per_a1, double phase, MdrSubgrid subgrid,
         const RunControl& control)
    : s_(s), a1_(analytic::a1(s)), dx_(a1_ / cells_per_a1), phase_(phase), subgrid_(subgrid),
      control_(control) {
  cap_ = static_cast<std::size_t>(std::floor(2.0 * cells_per_a1)) + 5;
  nodes_.assign(cap_, Site{});
}

void Row::init_stationary(double w, long double P) {
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
    } else { // free tail of stationary sliding: left the cap, relaxed while
             // carried at w
      const double y = x - a2w;
      n = Site{x, h_a2 * std::exp(-y / L), dh(a2w, x) - h_a2 * std::expm1(-y / L), cap_piece_,
               false};
    }
  }
}

void Row::init_undeformed(long double P) {
  w_ = 0.0;
  set_position(P);
  cap_piece_ = new_piece(true, 0.0);
  for (long long j = jlo_; j <= jhi_; ++j)
    nodes_[slot(j)] = Site{xi(j), 0.0, h(xi(j)), kNoPiece, xi(j) <= a1_};
}

void Row::change_velocity(double w) {
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
  } else if (any && !e.marked) { // contact material | the free piece beyond, at
                                 // psi = 0
    add_boundary(Site{e.x, 0.0, h(e.x), kNoPiece, true}, Site{e.x, h(e.x), 0.0, e.piece, false});
  }
  prune_tracers();
}

void Row::advance(double dt) {
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
    if (j < jlo0 || j > jhi0) // entered during the step: untouched material,
                              // free with u = 0
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

// Integral over [-a1, xr] of f sampled at the contact nodes ja..jb: the
// 4th-order Gregory rule (end-corrected trapezoid, exact for cubics) over
// the nodes, and the two partial cells [-a1, xi_a] and [xi_b, xr]
// integrated exactly (2-point Gauss) on the cubic through the four nearest
// nodes. The contact integrands (p and p * (-g')) are cubics in xi, so the
// only error left is the sub-grid location of the trailing edge. This
// matters where F_x is a tiny difference of large contributions (v tau <<
// a1): a first- or second-order sum would swamp it.
template <class F> double Row::integrate(long long ja, long long jb, double xr, F f) const {
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

State Row::measure() const {
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
  const double xr = std::clamp(std::min(read_edge(jb).x, a1_), xb, std::max(xb, std::min(xn, a1_)));
  st.FN = integrate(ja, jb, xr, [&](double x) { return pressure(x); });
  st.Fx = integrate(ja, jb, xr, [&](double x) {
    return pressure(x) * (-2.0 * x / s_.indenter.as<Parabola>().R);
  });
  st.mu = st.Fx / st.FN;
  st.d = s_.loading.d;
  st.a1 = a1_;
  st.a2 = xr;
  return st;
}

// Tracers and ghosts over a step in which the material moves by ds; those
// past the window are dropped (they can never touch or neighbour the edge).
void Row::carry_markers(double ds, const Step& st) {
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

// Integral over s in [0, len] (in cells, pointing away from the nodes) of the
// cubic through values g[k] at s = -k, k = 0..3.
double Row::partial_cell(const double g[4], double len) {
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
void Row::step_element(Site& el, double xs, double xe, const Step& st) const {
  if (el.contact) {
    if (xe <= st.a2w) return relax(el, xs, xe, st.dec, st.omd);
    return leave_at_cap(el, xe, (st.a2w - xs) / w_,
                        st); // (w > 0 here since xe > xs)
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
void Row::relax(Site& el, double xs, double xe, double dec, double omd) const {
  el.psi += dh(xs, xe) + el.u * omd;
  el.u *= dec;
}

// Left contact at the cap a time dt_c into the step; free since.
void Row::leave_at_cap(Site& el, double xe, double dt_c, const Step& st) const {
  const double r = st.dt - dt_c;
  el.u = st.h_a2w * decay(r);
  el.psi = dh(st.a2w, xe) + st.h_a2w * one_minus_decay(r);
  el.contact = false;
  el.piece = cap_piece_;
}

void Row::set_position(long double P) {
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
void Row::rebase() {
  const long long ring = static_cast<long long>(cap_);
  if (m_ < (1LL << 24)) return;
  const long long K = (m_ / ring) * ring;
  P_ -= static_cast<long double>(K);
  m_ -= K;
  jlo_ += K;
  jhi_ += K;
}
} // namespace mdrmap::mdr
