// The element row's forces (spectrum_row.hpp): the contact runs integrated
// over their nodes and the partial cells at their ends; for a profile other
// than the parabola, on either side of the tip, with the part of the pressure
// known in closed form integrated exactly (docs/design.md, "Indenter
// profiles"); and on either side of the seams inside a run (docs/design.md,
// "Seams").
#include <algorithm>
#include <cmath>

#include "core/solvers/spectrum_row.hpp"

namespace mdrmap::spectrum {
namespace {

// Row::ends_at_rest: the edge cells past the partial one, and the points per cell
constexpr long long kZoneCells = 1, kZoneSplit = 8;

// Integral over [lo, hi] of the polynomial through (x_i, f_i), i < k <= 4
// (2-point Gauss: exact for cubics); 0 for an empty interval.
double poly_integral(const double* x, const double* f, int k, double lo, double hi) {
  if (!(hi > lo)) return 0.0;
  double c[4]; // f_i over the Lagrange basis' denominators (formed once for both points)
  for (int i = 0; i < k; ++i) {
    double den = 1.0;
    for (int j = 0; j < k; ++j)
      if (j != i) den *= x[i] - x[j];
    c[i] = f[i] / den;
  }
  auto poly = [&](double t) {
    double s = 0.0;
    for (int i = 0; i < k; ++i) {
      double l = c[i];
      for (int j = 0; j < k; ++j)
        if (j != i) l *= t - x[j];
      s += l;
    }
    return s;
  };
  const double mid = 0.5 * (lo + hi), off = 0.5 * (hi - lo) / std::sqrt(3.0);
  return 0.5 * (hi - lo) * (poly(mid - off) + poly(mid + off));
}

double cubic_integral(const double* x, const double* f, double lo, double hi) {
  return poly_integral(x, f, 4, lo, hi);
}

/// A piece with fewer than 8 nodes: on each interval between its points (the
/// ends and the nodes; an end within rounding of a node is that node) the
/// cubic through the four nearest points (fewer points: their polynomial).
template <class X, class F>
double few_nodes(long long ja, long long jb, double dx, X x, double xl, double fl, double xr,
                 double fr, F f) {
  double px[10], pf[10];
  int m = 0;
  const double tiny = 1e-9 * dx;
  if (!(x(ja) - xl <= tiny)) {
    px[m] = xl;
    pf[m++] = fl;
  }
  for (long long k = ja; k <= jb; ++k) {
    px[m] = x(k);
    pf[m++] = f(k);
  }
  if (!(xr - x(jb) <= tiny)) {
    px[m] = xr;
    pf[m++] = fr;
  }
  const int k = std::min(m, 4);
  double sum = 0.0;
  for (int i = 0; i + 1 < m; ++i) {
    const int s0 = std::clamp(i - 1, 0, m - k);
    sum += poly_integral(px + s0, pf + s0, k, px[i], px[i + 1]);
  }
  return sum;
}

/// Adds to `acc` the integral over [xl, xr] of the function with values f(k)
/// at the nodes x(ja) .. x(jb) (spacing dx) and fl, fr at the ends: the
/// 4th-order Gregory rule over the nodes and the partial cells on the cubic
/// through the end value and the three nearest nodes (few nodes: few_nodes;
/// none: the trapezoid over the ends).
template <class X, class F>
void add_piece(long long ja, long long jb, double dx, X x, double xl, double fl, double xr,
               double fr, F f, double& acc) {
  const long long n = jb - ja + 1;
  if (n <= 0) { // no node: the trapezoid over the ends
    acc += 0.5 * (xr - xl) * (fl + fr);
    return;
  }
  const double xa = x(ja), xb = x(jb);
  if (n < 8) {
    acc += few_nodes(ja, jb, dx, x, xl, fl, xr, fr, f);
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

// What a part's quadrature takes of material in contact at x with branch
// states y: p, or with `rest` the part B = -sum G_k q_k.
double Row::part_value(const double* y, double x, bool rest) const {
  return rest ? law_.pressure(0.0, 0.0, y) : pressure_at(y, x);
}

// Integrates [xl, xr] (nodes ja..jb, values vl and vr at its ends) by `piece`
// over the parts between the seams inside (in contact), each seam's value
// from its replay. A part has two nodes at least (with its ends a cubic: the
// force density of a quadratic p is one), except the leading one (`leading`:
// xl is the leading edge), which a seam bounds for a few cells' travel after
// a change: there a replayed point at the middle of its widest gap makes up
// the cubic (fresh material: a short replay). A seam nearer an end stays
// inside that end's cells.
// With `layer` (a leading part), the quadrature takes the values less the
// layer, L(x - xl), and leading_forces adds the layer's integrals.
template <class Piece>
void Row::across_seams(long long ja, long long jb, double xl, double vl, double xr, double vr,
                       bool rest, bool leading, const Layer& layer, Piece piece) const {
  auto less_layer = [&](double v, double x) {
    return x - xl < layer.reach ? v - layer.at(x - xl) : v;
  };
  auto value = [&](const double* y, double x) { return less_layer(part_value(y, x, rest), x); };
  auto node_value = [&](long long k) { // (node_p: the force its last step left, if kept)
    return less_layer(rest ? node_rest(k) : node_p(k), xi(k));
  };
  std::pair<double, long double> in[kMaxSeams];
  std::size_t n = 0;
  for (const Seam& m : seams_) {
    const double x = position(m.J);
    if (x > xl && x < xr && n < kMaxSeams) in[n++] = {x, m.J};
  }
  std::sort(in, in + n);
  auto nodes = [&](long long a, long long b) {
    scratch_x_.clear();
    scratch_v_.clear();
    for (long long k = a; k <= b; ++k) {
      scratch_x_.push_back(xi(k));
      scratch_v_.push_back(node_value(k));
    }
  };
  double x0 = xl, v0 = vl;
  long long j0 = ja;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = in[i].first;
    long long j1 = static_cast<long long>(std::floor(x / dx_ - theta_ - phase_)) - m_;
    while (j1 + 1 <= jb && xi(j1 + 1) < x)
      ++j1;
    while (j1 >= j0 && !(xi(j1) < x))
      --j1;
    const bool short_lead = leading && j0 == ja && j1 < j0 + 1;
    if ((j1 < j0 + 1 && !short_lead) || j1 > jb - 2) continue;
    const Material m = replay(in[i].second);
    if (m.mode != Mode::Contact) continue;
    const double v = value(m.y, x);
    nodes(j0, j1);
    if (short_lead) { // the middle of the widest gap between x0, the node and x
      const double a = j1 == j0 ? scratch_x_[0] : x;
      const double mid = j1 == j0 && a - x0 < x - a ? 0.5 * (a + x) : 0.5 * (x0 + a);
      const Material mm = replay(label(mid));
      if (mm.mode != Mode::Contact) continue;
      const auto pos = mid < (j1 == j0 ? scratch_x_[0] : x) ? 0 : scratch_x_.size();
      scratch_x_.insert(scratch_x_.begin() + static_cast<std::ptrdiff_t>(pos), mid);
      scratch_v_.insert(scratch_v_.begin() + static_cast<std::ptrdiff_t>(pos), value(mm.y, mid));
    }
    piece(Points{scratch_x_.data(), scratch_v_.data(), static_cast<long long>(scratch_x_.size())},
          x0, v0, x, v);
    j0 = j1 + 1;
    x0 = x;
    v0 = v;
  }
  if (smooth_ && law_.branches() > 0 && jb - j0 >= 2 * kZoneCells + 8 && resting())
    return ends_at_rest(j0, jb, x0, v0, xr, vr, leading && j0 == ja, value, node_value, piece);
  nodes(j0, jb);
  piece(Points{scratch_x_.data(), scratch_v_.data(), static_cast<long long>(scratch_x_.size())}, x0,
        v0, xr, vr);
}

// Whether the last step was taken at rest (at a change, the step before it:
// the forces at the instant of a change do not depend on the rule).
bool Row::resting() const {
  for (auto e = log_.rbegin(); e != log_.rend(); ++e)
    if (e->dt > 0.0) return e->w == 0.0;
  return false;
}

// At rest, a part of a run from xl (the leading edge where `leading`) to the
// trailing edge xr. Where material touches at an edge (the contact grows
// into fresh material, or free material touches again), its pressure rises
// from 0 over a knee as wide as the edge's travel over the slow branches'
// times (a sum of such layers, one per branch; without branches, a jump at
// the edge or none), often a fraction of a cell:
// the end cell's cubic through the edge and the nodes spread it over the
// cell, an error that jumped as the edge passed a node (the 11-term
// elastomer's hold under load: mu by +-1.5e-3 of its scale from sample to
// sample at a/dx 16, where the same state's forces from dense replays are
// smooth). The edge cells (the partial one and the next kZoneCells) are
// therefore integrated on the replayed material points at the fractions
// i / kZoneSplit of their cells: at rest the same points from trial to trial
// and step to step, so their replays continue from the cache. (Points graded
// towards the edge, 4^-2 .. 4^-7 cells from it, on lattices of a quarter of
// their distance, gave the same errors and cost 1.6 times as much on a 100 s hold:
// they changed with every step of the edge.) A cell's
// points are fewer than 8, so `piece` takes them by local cubics (few_nodes). The nodes between
// take the Gregory rule.
template <class Value, class NodeValue, class Piece>
void Row::ends_at_rest(long long ja, long long jb, double xl, double vl, double xr, double vr,
                       bool leading, Value value, NodeValue node_value, Piece piece) const {
  double px[kZoneSplit], pv[kZoneSplit];
  // the cell from node j: its points strictly inside (lo, hi), by `piece` from lo to hi
  auto cell = [&](long long j, double lo, double flo, double hi, double fhi) {
    long long n = 0;
    for (long long i = 1; i < kZoneSplit; ++i) {
      const long double J = static_cast<long double>(j) +
                            static_cast<long double>(i) / static_cast<long double>(kZoneSplit);
      const double x = position(J), tiny = 1e-6 * dx_;
      if (!(x - lo > tiny && hi - x > tiny)) continue;
      const Material m = replay(J);
      if (m.mode != Mode::Contact) continue;
      px[n] = x;
      pv[n++] = value(m.y, x);
    }
    piece(Points{px, pv, n}, lo, flo, hi, fhi);
  };
  auto node = [&](long long j) { return node_value(j); };
  const long long za = leading ? ja + kZoneCells : ja, zb = jb - kZoneCells;
  if (leading) {
    cell(ja - 1, xl, vl, xi(ja), node(ja));
    for (long long j = ja; j < za; ++j)
      cell(j, xi(j), node(j), xi(j + 1), node(j + 1));
  }
  scratch_x_.clear();
  scratch_v_.clear();
  for (long long k = za; k <= zb; ++k) {
    scratch_x_.push_back(xi(k));
    scratch_v_.push_back(node(k));
  }
  piece(Points{scratch_x_.data(), scratch_v_.data(), static_cast<long long>(scratch_x_.size())},
        leading ? xi(za) : xl, leading ? node(za) : vl, xi(zb), node(zb));
  for (long long j = zb; j < jb; ++j)
    cell(j, xi(j), node(j), xi(j + 1), node(j + 1));
  cell(jb, xi(jb), node(jb), xr, vr);
}

// Forces (per 4, as sums of p dx) of the contact run ja..jb; the trailing
// edge e. Another profile's run is integrated on either side of a tip inside
// it (the parabola's force density is smooth there).
void Row::run_forces(long long ja, long long jb, double& FN, double& Fx, double& e,
                     Edge edge) const {
  const bool leading = ja == jlo_ || mode_[slot(ja - 1)] == Mode::Fresh;
  const double a1 = a1_now();
  const double xl = leading ? -a1 : xi(ja) - 0.5 * dx_;
  const Layer layer = leading ? leading_layer() : Layer{};
  const double lead = layer.at(0.0); // (the values at xl less the layer)
  const double pl = leading ? law_.tau() * law_.G() * (dd_ + lift(a1, w_)) - lead : node_p(ja);
  double pe = 0.0;
  e = trailing_edge(jb, pe, edge);
  if (leading) { // (the layer's force density -g'(xl + s) = g'(a1) - g''(a1) s + ...)
    FN += layer.integral();
    Fx += layer.integral() * -lift(xl, 1.0) - layer.moment() * curvature(a1);
  }
  auto p_piece = [&](const Points& pts, double l, double vl, double r, double vr) {
    piece_forces(pts, l, vl, r, vr, FN, Fx);
  };
  auto b_piece = [&](const Points& pts, double l, double vl, double r, double vr) {
    profile_piece_forces(pts, l, vl, r, vr, FN, Fx);
  };
  const Layer none;
  if (smooth_) return across_seams(ja, jb, xl, pl, e, pe, false, leading, layer, p_piece);
  const double bl = leading ? -lead : node_rest(ja); // fresh material: q_k = 0
  const long long jt = last_before_tip();
  if (ja <= jt && jt < jb) {
    across_seams(ja, jt, xl, bl, 0.0, tip_rest(jt, -1), true, leading, layer, b_piece);
    across_seams(jt + 1, jb, 0.0, tip_rest(jt + 1, 1), e, pe - known_p(e, 1), true, false, none,
                 b_piece);
    return;
  }
  if (jb == jt && e > 0.0) {            // the edge behind the tip, within the last cell
    const double b0 = tip_rest(jt, -1); // B is continuous through the tip
    across_seams(ja, jb, xl, bl, 0.0, b0, true, leading, layer, b_piece);
    sliver_forces(e, b0, pe - known_p(e, 1), FN, Fx);
    return;
  }
  const int side = e <= 0.0 ? -1 : 1;
  across_seams(ja, jb, xl, bl, e, e == 0.0 ? tip_rest(jb, -1) : pe - known_p(e, side), true,
               leading, layer, b_piece);
}

// Fresh material entering at the leading edge at speed c = w + da1/dt sees
// its depth rise at r = dd + w g'(a1) from 0; a branch with tau_k q_k' = u - q_k
// then holds q_k = r (t - tau_k + tau_k exp(-t / tau_k)) at t = s / c behind
// the edge: the smooth r (t - tau_k) plus the layer -G_k q_k's part
// -G_k r tau_k exp(-s / (c tau_k)), of width c tau_k. A layer thinner than a
// cell (the fine run's, for every run of one estimate: set_layer_width; the
// ones no seam resolves, add_seam) is taken out of the values and
// integrated exactly (to a relative (c tau_k / a1)^2: u'' is taken in). Without
// it the rule saw B jump from 0 within the first cell, a first-order error:
// slow steady sliding (v tau_k / a1 = 1e-5) erred by 1.7e-3 at rtol 1e-3 at
// fixed depth, 1.6e-3 under load. Which branches have a layer is decided by
// w alone (w tau_k < the cell), not by c: under load c follows the depth rate, and
// a switch on it made F_N jump in the rate the load balance varies. At rest
// (w = 0) none forms: a hold's edge creeps at a varying rate, the quasi-steady
// form does not hold there, and the slow branches' hold layers, kept into the
// reslide, made the companion disagree (docs/design.md, "Leading-edge layers").
void Row::entry_layers(double w, double dd, BranchLayer* out) const {
  const double a1 = a1_now();
  const double c =
      w + (d_ > 0.0 ? shape([&](const auto& i) { return i.radius_rate(a1, d_); }) * dd : 0.0);
  const double r = dd + lift(a1, w), bend = curvature(a1) * w * w; // u' and -u'' at entry
  for (std::size_t k = 0; k < law_.branches(); ++k) {
    out[k] = BranchLayer{};
    const double tk = law_.tauk(k), width = c * tk;
    if (w > 0.0 && w * tk < layer_dx_ && c > 0.0 &&
        r > 0.0) // (u = r t - bend t^2 / 2: amp r + bend tau_k)
      out[k] = BranchLayer{-law_.Gk(k) * tk * (r + bend * tk), width};
  }
}

// The layers now: the material that entered since the last change (within
// s_c of the edge) formed today's; the material behind it formed those of
// before the change, decayed since (exp(-since / tau_k); dropped once below
// exp(-40)), so that the forces do not jump at a change. Today's layers are
// shifted by a constant that makes L continuous at s_c (B is: the material on
// either side of it entered at the change): at s_c a branch's layer of today
// has fallen to amp exp(-s_c / width), the one before to its decayed
// amplitude, and B - L would jump by their difference inside the contact
// (after a hold, where no layer formed, by the whole of today's amplitude
// while since << tau_k), or at the edge itself as s_c crosses 0 under load.
Row::Layer Row::leading_layer() const {
  Layer l;
  l.n = law_.branches();
  entry_layers(w_, dd_, l.now);
  l.s_c = position(lead_) + a1_now();
  for (std::size_t k = 0; k < l.n; ++k) {
    const double decay = since_ / law_.tauk(k);
    if (k < layers_before_.size() && layers_before_[k].amp != 0.0 && decay < 40.0) {
      l.before[k] = BranchLayer{layers_before_[k].amp * std::exp(-decay), layers_before_[k].width};
      l.reach = std::max(l.reach, std::max(l.s_c, 0.0) + 40.0 * l.before[k].width);
    }
    l.reach = std::max(l.reach, 40.0 * l.now[k].width);
    if (l.s_c > 0.0) {
      const double x = l.now[k].amp != 0.0 ? l.s_c / l.now[k].width : 40.0;
      l.shift += l.before[k].amp - (x < 40.0 ? l.now[k].amp * std::exp(-x) : 0.0);
    }
  }
  if (l.shift != 0.0) l.reach = std::max(l.reach, l.s_c);
  return l;
}

double Row::Layer::at(double s) const {
  double v = s < s_c ? shift : 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (s < s_c && now[i].amp != 0.0) v += now[i].amp * decay(s / now[i].width);
    if (s >= s_c && before[i].amp != 0.0) v += before[i].amp * decay((s - s_c) / before[i].width);
  }
  return v;
}

// (over s >= 0: today's layer up to m = max(s_c, 0), the one before from m)
double Row::Layer::moment() const {
  const double m = std::max(s_c, 0.0);
  double v = 0.5 * shift * m * m;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = now[i].width, b = before[i].width;
    if (now[i].amp != 0.0) {
      const double x = m / w;
      v += now[i].amp * w * w * (x < 40.0 ? 1.0 - std::exp(-x) * (1.0 + x) : 1.0);
    }
    if (before[i].amp != 0.0) v += before[i].amp * std::exp(-(m - s_c) / b) * b * (m + b);
  }
  return v;
}

double Row::Layer::integral() const {
  const double m = std::max(s_c, 0.0);
  double v = shift * m;
  for (std::size_t i = 0; i < n; ++i) {
    if (now[i].amp != 0.0) v += now[i].amp * now[i].width * -std::expm1(-m / now[i].width);
    if (before[i].amp != 0.0)
      v += before[i].amp * before[i].width * std::exp(-(m - s_c) / before[i].width);
  }
  return v;
}

// The sliver [0, e] behind the tip with no node in it: A exactly, B linear
// from b0 at the tip to be at e (int_0^e x g' = e g(e) - int_0^e g).
void Row::sliver_forces(double e, double b0, double be, double& FN, double& Fx) const {
  const KnownForces k = known_forces(0.0, e);
  const double ge = g(e), Ig = shape([e](const auto&i) { return i.integral_g(e); });
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

// The parabola's run: its points' pressures and force densities p (-g').
void Row::piece_forces(const Points& pts, double xl, double pl, double xr, double pr, double& FN,
                       double& Fx) const {
  auto x = [&](long long k) { return pts.x[k]; };
  auto p = [&](long long k) { return pts.v[k]; };
  auto fx = [&](double at, double v) { return v * -lift(at, 1.0); };
  add_piece(0, pts.n - 1, dx_, x, xl, pl, xr, pr, p, FN);
  add_piece(
      0, pts.n - 1, dx_, x, xl, fx(xl, pl), xr, fx(xr, pr),
      [&](long long k) { return fx(pts.x[k], pts.v[k]); }, Fx);
}

// Another profile's run on one side of the tip (or touching it). The
// pressure in contact is p = A + B: A = G0 h + G tau (dd - w g') is known in
// closed form and is not smooth at the tip (g' jumps at a cone's, g'' is
// singular for n < 2); B = -sum G_k q_k is smooth there (the branches filter
// h). A and A (-g') are integrated exactly; B by the rule, B (-g') as
// B_tip (-g') exactly plus (B - B_tip)(-g') by the rule, where the run
// touches the tip. bl, br: B at the ends.
void Row::profile_piece_forces(const Points& pts, double xl, double bl, double xr, double br,
                               double& FN, double& Fx) const {
  const int side = xr <= 0.0 ? -1 : 1;
  const double b0 = xr == 0.0 ? br : (xl == 0.0 ? bl : 0.0);
  auto x = [&](long long k) { return pts.x[k]; };
  auto b = [&](long long k) { return pts.v[k]; };
  auto down = [&](double at) { return -side_slope(at, side); }; // -g'
  const KnownForces k = known_forces(xl, xr);
  FN += k.N;
  add_piece(0, pts.n - 1, dx_, x, xl, bl, xr, br, b, FN);
  Fx += k.X - b0 * (g(xr) - g(xl));
  add_piece(
      0, pts.n - 1, dx_, x, xl, (bl - b0) * down(xl), xr, (br - b0) * down(xr),
      [&](long long j) { return (b(j) - b0) * down(pts.x[j]); }, Fx);
}

// g'(x), at the tip its limit from `side`.
double Row::side_slope(double x, int side) const {
  return shape([&](const auto& i) { return i.side_slope(x, side); });
}

// A(x) = G0 h + G tau (dd - w g') (per 4), at the tip from `side`.
double Row::known_p(double x, int side) const {
  return law_.G0() * depth(x) + law_.G() * law_.tau() * (dd_ - side_slope(x, side) * w_);
}

// The integrals of A and of A (-g') over [l, r]: with the signed
// antiderivatives of g = c|x|^n and g'^2 = c^2 n^2 |x|^(2n-2) (continuous
// through the tip), int g' = g(r) - g(l), int g g' = (g(r)^2 - g(l)^2)/2.
Row::KnownForces Row::known_forces(double l, double r) const {
  auto G1 = [&](double t) { return shape([t](const auto& i) { return i.integral_g(t); }); };
  auto G2 = [&](double t) {
    return shape([t](const auto& i) { return i.integral_slope_squared(t); });
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
  const double kink = shape([](const auto& i) { return i.apex_slope(); });
  if (kink == 0.0) return p_ahead;
  return p_ahead - 2.0 * law_.tau() * law_.G() * kink * w_;
}

State Row::measure(Edge edge) const {
  control_.charge(unit_ * static_cast<double>(jhi_ - jlo_ + 1), name_);
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
