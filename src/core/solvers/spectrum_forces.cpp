// The element row's forces (spectrum_row.hpp): the contact runs integrated
// over their nodes and the partial cells at their ends; for a profile other
// than the parabola, on either side of the tip, with the part of the pressure
// known in closed form integrated exactly (docs/design.md, "Indenter
// profiles").
#include <algorithm>
#include <cmath>

#include "core/solvers/spectrum_row.hpp"

namespace mdrmap::spectrum {
namespace {

// Integral over [lo, hi] of the cubic through (x_i, f_i), i < 4 (2-point
// Gauss: exact for cubics); 0 for an empty interval.
double cubic_integral(const double* x, const double* f, double lo, double hi) {
  if (!(hi > lo)) return 0.0;
  auto cubic = [&](double t) {
    double s = 0.0;
    for (int i = 0; i < 4; ++i) {
      double l = 1.0;
      for (int k = 0; k < 4; ++k)
        if (k != i) l *= (t - x[k]) / (x[i] - x[k]);
      s += f[i] * l;
    }
    return s;
  };
  const double mid = 0.5 * (lo + hi), off = 0.5 * (hi - lo) / std::sqrt(3.0);
  return 0.5 * (hi - lo) * (cubic(mid - off) + cubic(mid + off));
}

/// Adds to `acc` the integral over [xl, xr] of the function with values f(k)
/// at the nodes x(ja) .. x(jb) (spacing dx) and fl, fr at the ends: the
/// 4th-order Gregory rule over the nodes and the partial cells on the cubic
/// through the end value and the three nearest nodes (few nodes: trapezoid,
/// linear end cells).
template <class X, class F>
void add_piece(long long ja, long long jb, double dx, X x, double xl, double fl, double xr,
               double fr, F f, double& acc) {
  const long long n = jb - ja + 1;
  const double xa = x(ja), xb = x(jb);
  if (n < 8) {
    double s = 0.0;
    for (long long k = ja; k <= jb; ++k)
      s += ((k == ja || k == jb) ? 0.5 : 1.0) * f(k);
    if (n == 1) s = 0.0;
    acc += dx * s + 0.5 * (xa - xl) * (fl + f(ja)) + 0.5 * (xr - xb) * (f(jb) + fr);
    return;
  }
  long double s = 0.0L;
  for (long long k = ja; k <= jb; ++k) {
    double wgt = 1.0;
    const long long r = std::min(k - ja, jb - k);
    if (r == 0) wgt = 3.0 / 8.0;
    if (r == 1) wgt = 7.0 / 6.0;
    if (r == 2) wgt = 23.0 / 24.0;
    s += static_cast<long double>(wgt * f(k));
  }
  acc += dx * static_cast<double>(s);
  const double XL[4] = {xl, xa, xa + dx, xa + 2.0 * dx}, XR[4] = {xb - 2.0 * dx, xb - dx, xb, xr};
  const double FL[4] = {fl, f(ja), f(ja + 1), f(ja + 2)}, FR[4] = {f(jb - 2), f(jb - 1), f(jb), fr};
  acc += cubic_integral(XL, FL, xl, xa) + cubic_integral(XR, FR, xb, xr);
}

} // namespace

// Forces (per 4, as sums of p dx) of the contact run ja..jb; the trailing
// edge e. Another profile's run is integrated on either side of a tip inside
// it (the parabola's force density is smooth there).
void Row::run_forces(long long ja, long long jb, double& FN, double& Fx, double& e,
                     Edge edge) const {
  const bool leading = ja == jlo_ || mode_[slot(ja - 1)] == Mode::Fresh;
  const double a1 = a1_now();
  const double xl = leading ? -a1 : xi(ja) - 0.5 * dx_;
  const double pl = leading ? law_.tau() * law_.G() * (dd_ + lift(a1, w_)) : node_p(ja);
  double pe = 0.0;
  e = trailing_edge(jb, pe, edge);
  if (parab_) return piece_forces(ja, jb, xl, pl, e, pe, FN, Fx);
  const double bl = leading ? 0.0 : node_rest(ja); // fresh material: q_k = 0
  const long long jt = last_before_tip();
  if (ja <= jt && jt < jb) {
    profile_piece_forces(ja, jt, xl, bl, 0.0, tip_rest(jt, -1), FN, Fx);
    profile_piece_forces(jt + 1, jb, 0.0, tip_rest(jt + 1, 1), e, pe - known_p(e, 1), FN, Fx);
    return;
  }
  if (jb == jt && e > 0.0) {            // the edge behind the tip, within the last cell
    const double b0 = tip_rest(jt, -1); // B is continuous through the tip
    profile_piece_forces(ja, jb, xl, bl, 0.0, b0, FN, Fx);
    sliver_forces(e, b0, pe - known_p(e, 1), FN, Fx);
    return;
  }
  const int side = e <= 0.0 ? -1 : 1;
  profile_piece_forces(ja, jb, xl, bl, e, e == 0.0 ? tip_rest(jb, -1) : pe - known_p(e, side), FN,
                       Fx);
}

// The sliver [0, e] behind the tip with no node in it: A exactly, B linear
// from b0 at the tip to be at e (int_0^e x g' = e g(e) - int_0^e g).
void Row::sliver_forces(double e, double b0, double be, double& FN, double& Fx) const {
  const KnownForces k = known_forces(0.0, e);
  const double ge = g(e), Ig = gc_ * std::pow(e, gn_ + 1.0) / (gn_ + 1.0);
  FN += k.N + 0.5 * e * (b0 + be);
  Fx += k.X - (b0 * ge + (be - b0) * (ge - Ig / e));
}

// The last node left of the tip x = 0.
long long Row::last_before_tip() const {
  long long jt = static_cast<long long>(std::ceil(-(theta_ + phase_))) - m_ - 1;
  while (xi(jt + 1) < 0.0)
    ++jt;
  while (!(xi(jt) < 0.0))
    --jt;
  return jt;
}

// The parabola's run: its nodes' pressures and force densities p (-g').
void Row::piece_forces(long long ja, long long jb, double xl, double pl, double xr, double pr,
                       double& FN, double& Fx) const {
  scratch_.resize(static_cast<std::size_t>(jb - ja + 1));
  for (long long k = ja; k <= jb; ++k)
    scratch_[static_cast<std::size_t>(k - ja)] = node_p(k);
  auto x = [&](long long k) { return xi(k); };
  auto p = [&](long long k) { return scratch_[static_cast<std::size_t>(k - ja)]; };
  auto fx = [&](double at, double v) { return v * -lift(at, 1.0); };
  add_piece(ja, jb, dx_, x, xl, pl, xr, pr, p, FN);
  add_piece(
      ja, jb, dx_, x, xl, fx(xl, pl), xr, fx(xr, pr), [&](long long k) { return fx(xi(k), p(k)); },
      Fx);
}

// Another profile's run on one side of the tip (or touching it). The
// pressure in contact is p = A + B: A = G0 h + G tau (dd - w g') is known in
// closed form and is not smooth at the tip (g' jumps at a cone's, g'' is
// singular for n < 2); B = -sum G_k q_k is smooth there (the branches filter
// h). A and A (-g') are integrated exactly; B by the rule, B (-g') as
// B_tip (-g') exactly plus (B - B_tip)(-g') by the rule, where the run
// touches the tip. bl, br: B at the ends.
void Row::profile_piece_forces(long long ja, long long jb, double xl, double bl, double xr,
                               double br, double& FN, double& Fx) const {
  const int side = xr <= 0.0 ? -1 : 1;
  const double b0 = xr == 0.0 ? br : (xl == 0.0 ? bl : 0.0);
  scratch_.resize(static_cast<std::size_t>(jb - ja + 1));
  for (long long k = ja; k <= jb; ++k)
    scratch_[static_cast<std::size_t>(k - ja)] = node_rest(k);
  auto x = [&](long long k) { return xi(k); };
  auto b = [&](long long k) { return scratch_[static_cast<std::size_t>(k - ja)]; };
  auto down = [&](double at) { return -side_slope(at, side); }; // -g'
  const KnownForces k = known_forces(xl, xr);
  FN += k.N;
  add_piece(ja, jb, dx_, x, xl, bl, xr, br, b, FN);
  Fx += k.X - b0 * (g(xr) - g(xl));
  add_piece(
      ja, jb, dx_, x, xl, (bl - b0) * down(xl), xr, (br - b0) * down(xr),
      [&](long long j) { return (b(j) - b0) * down(xi(j)); }, Fx);
}

// g'(x), at the tip its limit from `side`.
double Row::side_slope(double x, int side) const {
  if (x != 0.0) return slope(x);
  return gn_ == 1.0 ? side * gc_ : 0.0;
}

// A(x) = G0 h + G tau (dd - w g') (per 4), at the tip from `side`.
double Row::known_p(double x, int side) const {
  return law_.G0() * depth(x) + law_.G() * law_.tau() * (dd_ - side_slope(x, side) * w_);
}

// The integrals of A and of A (-g') over [l, r]: with the signed
// antiderivatives of g = c|x|^n and g'^2 = c^2 n^2 |x|^(2n-2) (continuous
// through the tip), int g' = g(r) - g(l), int g g' = (g(r)^2 - g(l)^2)/2.
Row::KnownForces Row::known_forces(double l, double r) const {
  const double n = gn_, c = gc_;
  auto G1 = [&](double t) {
    return std::copysign(c * std::pow(std::fabs(t), n + 1.0) / (n + 1.0), t);
  };
  auto G2 = [&](double t) {
    return std::copysign(c * c * n * n * std::pow(std::fabs(t), 2.0 * n - 1.0) / (2.0 * n - 1.0),
                         t);
  };
  const double L = r - l, gl = g(l), gr = g(r);
  const double Ig = G1(r) - G1(l), Igp = gr - gl, Iggp = 0.5 * (gr * gr - gl * gl),
               Igp2 = G2(r) - G2(l);
  const double G0 = law_.G0(), eta = law_.G() * law_.tau();
  return {G0 * (d_ * L - Ig) + eta * (dd_ * L - w_ * Igp),
          -(G0 * (d_ * Igp - Iggp) + eta * (dd_ * Igp - w_ * Igp2))};
}

// B = -sum G_k q_k of a node in contact.
double Row::node_rest(long long j) const {
  return law_.pressure(0.0, 0.0, &y_[slot(j) * stride_]);
}

// B at the tip from one side (-1: left of it, from nodes jt, jt-1, ..; +1:
// right, from jt, jt+1, ..): Lagrange extrapolation through up to four of
// that side's nodes in contact (B is smooth there).
double Row::tip_rest(long long jt, int side) const {
  double x[4], f[4];
  int n = 0;
  for (long long j = jt; n < 4 && j >= jlo_ && j <= jhi_; j += side, ++n) {
    if (mode_[slot(j)] != Mode::Contact) break;
    x[n] = xi(j);
    f[n] = node_rest(j);
  }
  double s = 0.0;
  for (int i = 0; i < n; ++i) {
    double l = 1.0;
    for (int k = 0; k < n; ++k)
      if (k != i) l *= (0.0 - x[k]) / (x[i] - x[k]);
    s += f[i] * l;
  }
  return s;
}

// The pressure at the tip from one side.
double Row::tip_pressure(long long jt, int side) const {
  return known_p(0.0, side) + tip_rest(jt, side);
}

// The pressure just behind the tip from the one just ahead of it: a cone's
// slope jumps from -c to c there, so a parallel dashpot's stress falls by
// 2 G tau c w (the branches' states and u are continuous); other profiles'
// slopes are continuous.
double Row::past_tip(double p_ahead) const {
  if (parab_ || gn_ != 1.0) return p_ahead;
  return p_ahead - 2.0 * law_.tau() * law_.G() * gc_ * w_;
}

State Row::measure(Edge edge) const {
  control_.charge(static_cast<double>(jhi_ - jlo_ + 1), name_);
  ++measures_;
  State st;
  st.a1 = a1_now();
  st.a2 = -st.a1;
  double FN = 0.0, Fx = 0.0;
  for (long long j = jlo_; j <= jhi_; ++j) {
    if (mode_[slot(j)] != Mode::Contact) continue;
    const long long ja = j;
    while (j + 1 <= jhi_ && mode_[slot(j + 1)] == Mode::Contact)
      ++j;
    run_forces(ja, j, FN, Fx, st.a2, edge);
  }
  st.FN = 4.0 * FN;
  st.Fx = 4.0 * Fx;
  st.mu = st.Fx / st.FN;
  st.d = d_;
  return st;
}

} // namespace mdrmap::spectrum
