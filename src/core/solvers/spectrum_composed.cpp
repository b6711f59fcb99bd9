// The element row's contact update composed over a step's sub-steps
// (spectrum_row.hpp, Row::Composed). For the parabola, g = c x^2, the
// forcing of a sub-step from t_s is a polynomial in the element's position x
// at the step's start: along the depth path d(t) (rate r(t), curvature k),
//   h0 = d(t_s) - c (x + w t_s)^2,  h1 = r(t_s) - 2 c w (x + w t_s),  h2 = k - c w^2,
// and each branch's update q' = e q + (1 - e) h0 + a h1 + b h2 is affine in q
// with coefficients common to every element. Composed over the sub-steps,
// q(dt) = E q0 + A + B x + C x^2, and the force at the end of sub-step i,
// p = G0 u + G tau u' - sum G_k q_k, is pi_i(x) - sum_k G_k E_ik q0_k: the
// same sub-steps and the same checks of the force at their ends as
// step_material's, in one pass over the branches per check and one per
// update (bit for bit they differ by rounding only). An element whose force
// turns negative at a sub-step's end takes step_material's path, which
// locates the switch.
#include <algorithm>
#include <cmath>

#include "core/solvers/spectrum_row.hpp"

namespace mdrmap::spectrum {
namespace {

/// The most sub-steps of a step that compose() forms (its arrays grow with
/// them; a step with more takes step_material, as before).
constexpr long long kMaxComposed = 256;

/// c[0] + c[1] x + c[2] x^2 - sum_k w_k y_k: an element's force (a free
/// point's gap) at a sub-step's end from its state y at the step's start.
double at_end(const double* c, const double* w, const double* y, std::size_t n, double x) {
  double v = c[0] + (c[1] + c[2] * x) * x;
  for (std::size_t k = 0; k < n; ++k)
    v -= w[k] * y[k];
  return v;
}

} // namespace
// The sub-steps of an element in contact from the step's start (those of
// step_material, whose loop this follows) composed into comp_; false where
// the profile is not the parabola (its sub-steps are cut at the tip, or its
// forcing interpolated).
bool Row::compose(const Grid& g, double dt, double w, const Path& p) {
  comp_.suffix = false;
  // (a stiff case's step can have millions of sub-steps: those go element by
  // element as before, charged to the work budget as they are taken)
  if (!(composed_on_ && smooth_ && exact_force_ && g.K <= kMaxComposed)) return false;
  const std::size_t n = law_.branches(), m = law_.free_dim();
  comp_.n = n;
  comp_.m = m;
  const auto cap = static_cast<std::size_t>(g.K) + 1; // (rounding: g.K + 1 sub-steps)
  for (auto* v : {&comp_.E, &comp_.A, &comp_.B, &comp_.C, &comp_.W})
    if (v->size() < cap * n) v->resize(cap * n);
  for (auto* v : {&comp_.pi, &comp_.hi})
    if (v->size() < cap * 3) v->resize(cap * 3);
  for (auto* v : {&comp_.M, &comp_.V})
    if (v->size() < cap * m) v->resize(cap * m);
  if (comp_.ends.size() < cap) comp_.ends.resize(cap);
  comp_.K = 0;
  std::size_t owned = 0;
  bool suffix = true; // (sub-steps 1.. all take g.full)
  for (double t = 0.0; t < dt;) {
    if (comp_.K >= cap) return false;
    const Grid::Sub sub = g.from(dt, t);
    const double tn = sub.tn, h = tn - t;
    const StepCoef* c = g.set(t, sub.i, h);
    if (c == nullptr) {
      if (comp_.own.size() <= owned) comp_.own.emplace_back();
      law_.coef(h, comp_.own[owned], Part::Both);
      c = &comp_.own[owned++];
    }
    suffix = suffix && (comp_.K == 0 || c == &g.full);
    compose_substep(*c, t, tn, w, p);
    t = tn;
  }
  comp_.suffix = comp_.K > 1 && suffix;
  if (comp_.suffix) compose_powers(g.full);
  return comp_.K > 0;
}

// Sub-step K (from t to tn, set c) appended to comp_: its prefix rows.
void Row::compose_substep(const StepCoef& c, double t, double tn, double w, const Path& p) {
  const std::size_t n = comp_.n, m = comp_.m, K = comp_.K;
  const double cg = g_coefficient(), G0 = law_.G0(), eta = law_.G() * law_.tau(), h = tn - t;
  const Path q = p.from(t);
  // the forcing's coefficients in powers of x
  const double f00 = q.d - cg * w * w * t * t, f01 = -2.0 * cg * w * t, f02 = -cg;
  const double f10 = q.r - 2.0 * cg * w * w * t, f11 = -2.0 * cg * w;
  const double f2 = q.k - cg * w * w;
  // the known part of the force at the sub-step's end, tn
  const double de = q.at(h), re = q.rate(h);
  double p0 = G0 * (de - cg * w * w * tn * tn) + eta * (re - 2.0 * cg * w * w * tn);
  double p1 = G0 * (-2.0 * cg * w * tn) + eta * (-2.0 * cg * w), p2 = -G0 * cg;
  const std::size_t b = K * n, pb = b - n; // this sub-step's row, the last one's (K > 0)
  for (std::size_t k = 0; k < n; ++k) {
    const double e = c.e[k], a = c.a[k], bk = c.b[k], ome = 1.0 - e;
    comp_.E[b + k] = K == 0 ? e : e * comp_.E[pb + k];
    comp_.A[b + k] = (K == 0 ? 0.0 : e * comp_.A[pb + k]) + ome * f00 + a * f10 + bk * f2;
    comp_.B[b + k] = (K == 0 ? 0.0 : e * comp_.B[pb + k]) + ome * f01 + a * f11;
    comp_.C[b + k] = (K == 0 ? 0.0 : e * comp_.C[pb + k]) + ome * f02;
    const double Gk = law_.Gk(k);
    p0 -= Gk * comp_.A[b + k];
    p1 -= Gk * comp_.B[b + k];
    p2 -= Gk * comp_.C[b + k];
    comp_.W[b + k] = Gk * comp_.E[b + k];
  }
  comp_.pi[3 * K] = p0;
  comp_.pi[3 * K + 1] = p1;
  comp_.pi[3 * K + 2] = p2;
  for (std::size_t i = 0; i < m; ++i) {
    comp_.M[K * m + i] = c.modal[i] * (K == 0 ? 1.0 : comp_.M[(K - 1) * m + i]);
    comp_.V[K * m + i] = law_.free_weight(i) * comp_.M[K * m + i];
  }
  // the indenter's depth at the element at tn: de - c (x + w tn)^2
  comp_.hi[3 * K] = de - cg * w * w * tn * tn;
  comp_.hi[3 * K + 1] = -2.0 * cg * w * tn;
  comp_.hi[3 * K + 2] = -cg;
  comp_.ends[K] = tn;
  ++comp_.K;
}

// The powers 0 .. K-1 of the full set's factors (Ep, Wp; Mp, Vp).
void Row::compose_powers(const StepCoef& full) {
  const std::size_t n = comp_.n, m = comp_.m, K = comp_.K;
  comp_.Ep.resize(K * n);
  comp_.Wp.resize(K * n);
  comp_.Mp.resize(K * m);
  comp_.Vp.resize(K * m);
  for (std::size_t r = 0; r < K; ++r) {
    for (std::size_t k = 0; k < n; ++k) {
      comp_.Ep[r * n + k] = r == 0 ? 1.0 : comp_.Ep[(r - 1) * n + k] * full.e[k];
      comp_.Wp[r * n + k] = law_.Gk(k) * comp_.Ep[r * n + k];
    }
    for (std::size_t i = 0; i < m; ++i) {
      comp_.Mp[r * m + i] = r == 0 ? 1.0 : comp_.Mp[(r - 1) * m + i] * full.modal[i];
      comp_.Vp[r * m + i] = law_.free_weight(i) * comp_.Mp[r * m + i];
    }
  }
}

void Row::Composed::prefix(std::size_t l, double x, double* q) const {
  for (std::size_t k = 0, i = l * n; k < n; ++k, ++i)
    q[k] = A[i] + (B[i] + C[i] * x) * x;
}

// Whether a free element at x (the step's start), modal state z, touches at
// the end of sub-step i, its depression's weights V there: as substep's test
// sees it, a gap above psi_tiny_ inside the indenter's reach.
bool Row::touches(std::size_t i, const double* V, const double* z, double x, double w,
                  const Path& p) const {
  const double tn = comp_.ends[i];
  return at_end(&comp_.hi[3 * i], V, z, comp_.m, x) > psi_tiny_ && inside(x + w * tn, p.at(tn));
}

// The composed step of the element in slot sl, at x at the step's start
// (along the depth path p), where it applies: false where the element is
// fresh or switches during the step (step_material takes it, from t: the
// start of the sub-step at whose end it switches, y its state there).
bool Row::composed_step(std::size_t sl, double x, const Path& p, double& t) {
  double* y = &y_[sl * stride_];
  double pe = 0.0;
  std::size_t i = comp_.K + 1; // (the sub-step the element switches in; K: none)
  if (mode_[sl] == Mode::Contact) {
    i = composed_contact(y, x, pe);
    if (i == comp_.K) {
      p_end_[sl] = pe;
      p_gen_[sl] = state_gen_;
    }
  } else if (mode_[sl] == Mode::Free) {
    i = composed_free(y, x, w_, p);
  }
  if (i > comp_.K) return false;
  updates_ += static_cast<long>(i);
  t = i == 0 ? 0.0 : comp_.ends[i - 1];
  if (i < comp_.K) return false;
  ++composed_steps_;
  return true;
}

// The composed step of an element in contact at x (the step's start), state
// y, up to the first sub-step at whose end its force turns negative, as
// substep's switch test sees it (p < -p_tiny_): its index i (K: none), y its
// state at that sub-step's start; pe: its force at the end (i = K).
std::size_t Row::composed_contact(double* y, double x, double& pe) const {
  const std::size_t n = comp_.n;
  const double* W = comp_.W.data();
  std::size_t i = 0;
  for (; i < comp_.K; ++i, W += n) {
    const double p = at_end(&comp_.pi[3 * i], W, y, n, x);
    if (p < -p_tiny_) break;
    pe = p;
  }
  if (i == 0) return 0;
  const std::size_t b = (i - 1) * n; // (the state at the end of sub-step i - 1)
  for (std::size_t k = 0; k < n; ++k)
    y[k] = comp_.E[b + k] * y[k] + comp_.A[b + k] + (comp_.B[b + k] + comp_.C[b + k] * x) * x;
  return i;
}

// The composed step of a free element at x (the step's start), modal state
// y, up to the first sub-step at whose end it touches, as substep's test sees
// it (a gap above psi_tiny_ inside the indenter's reach): its index (K: none),
// y its state at that sub-step's start.
std::size_t Row::composed_free(double* y, double x, double w, const Path& p) const {
  const std::size_t m = comp_.m;
  std::size_t i = 0;
  while (i < comp_.K && !touches(i, comp_.V.data() + i * m, y, x, w, p))
    ++i;
  if (i == 0) return 0;
  for (std::size_t k = 0; k < m; ++k)
    y[k] *= comp_.M[(i - 1) * m + k];
  return i;
}

// An element in contact at the end of sub-step l (state y; x: its position at
// the step's start) carried on through the full sub-steps after it, up to the
// first at whose end its force turns negative: that sub-step's index (K: none),
// y its state at its start.
std::size_t Row::rest_contact(double* y, double x, std::size_t l) const {
  const std::size_t n = comp_.n;
  double r[kMaxBranches + 1], P[kMaxBranches + 1];
  comp_.prefix(l, x, P);
  for (std::size_t k = 0; k < n; ++k)
    r[k] = y[k] - P[k]; // q_i = e^(i - l) r + P_i(x)
  std::size_t i = l + 1;
  for (; i < comp_.K; ++i)
    if (at_end(&comp_.pi[3 * i], comp_.Wp.data() + (i - l) * n, r, n, x) < -p_tiny_) break;
  comp_.prefix(i - 1, x, P);
  for (std::size_t k = 0; k < n; ++k)
    y[k] = comp_.Ep[(i - 1 - l) * n + k] * r[k] + P[k];
  return i;
}

// A free element at the end of sub-step l (modal state y) carried on likewise,
// up to the first sub-step at whose end it touches.
std::size_t Row::rest_free(double* y, double x, double w, const Path& p, std::size_t l) const {
  const std::size_t m = comp_.m;
  std::size_t i = l + 1;
  while (i < comp_.K && !touches(i, comp_.Vp.data() + (i - l) * m, y, x, w, p))
    ++i;
  for (std::size_t k = 0; k < m; ++k)
    y[k] *= comp_.Mp[(i - 1 - l) * m + k];
  return i;
}

} // namespace mdrmap::spectrum
