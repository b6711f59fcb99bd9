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
  comp_.on = false;
  // (a stiff case's step can have millions of sub-steps: those go element by
  // element as before, charged to the work budget as they are taken)
  if (!(composed_on_ && smooth_ && exact_force_ && g.K <= kMaxComposed)) return false;
  const std::size_t n = law_.branches();
  const double cg = g_coefficient(), G0 = law_.G0(), eta = law_.G() * law_.tau();
  comp_.E.assign(n, 1.0);
  comp_.A.assign(n, 0.0);
  comp_.B.assign(n, 0.0);
  comp_.C.assign(n, 0.0);
  comp_.pi.clear();
  comp_.W.clear();
  comp_.M.assign(law_.free_dim(), 1.0);
  comp_.V.clear();
  comp_.hi.clear();
  comp_.ends.clear();
  comp_.K = 0;
  std::size_t owned = 0;
  for (double t = 0.0; t < dt;) {
    if (comp_.K > static_cast<std::size_t>(kMaxComposed)) return false; // (rounding: g.K + 1)
    const Grid::Sub sub = g.from(dt, t);
    const double tn = sub.tn, h = tn - t;
    const StepCoef* c = g.set(t, sub.i, h);
    if (c == nullptr) {
      if (comp_.own.size() <= owned) comp_.own.emplace_back();
      law_.coef(h, comp_.own[owned], Part::Both);
      c = &comp_.own[owned++];
    }
    const Path q = p.from(t);
    // the forcing's coefficients in powers of x
    const double f00 = q.d - cg * w * w * t * t, f01 = -2.0 * cg * w * t, f02 = -cg;
    const double f10 = q.r - 2.0 * cg * w * w * t, f11 = -2.0 * cg * w;
    const double f2 = q.k - cg * w * w;
    // the known part of the force at the sub-step's end, tn
    const double de = q.at(h), re = q.rate(h);
    double p0 = G0 * (de - cg * w * w * tn * tn) + eta * (re - 2.0 * cg * w * w * tn);
    double p1 = G0 * (-2.0 * cg * w * tn) + eta * (-2.0 * cg * w), p2 = -G0 * cg;
    for (std::size_t k = 0; k < n; ++k) {
      const double e = c->e[k], a = c->a[k], b = c->b[k], ome = 1.0 - e;
      comp_.E[k] *= e;
      comp_.A[k] = e * comp_.A[k] + ome * f00 + a * f10 + b * f2;
      comp_.B[k] = e * comp_.B[k] + ome * f01 + a * f11;
      comp_.C[k] = e * comp_.C[k] + ome * f02;
      const double Gk = law_.Gk(k);
      p0 -= Gk * comp_.A[k];
      p1 -= Gk * comp_.B[k];
      p2 -= Gk * comp_.C[k];
      comp_.W.push_back(Gk * comp_.E[k]);
    }
    comp_.pi.insert(comp_.pi.end(), {p0, p1, p2});
    for (std::size_t m = 0; m < comp_.M.size(); ++m) {
      comp_.M[m] *= c->modal[m];
      comp_.V.push_back(law_.free_weight(m) * comp_.M[m]);
    }
    // the indenter's depth at the element at tn: de - c (x + w tn)^2
    comp_.hi.insert(comp_.hi.end(), {de - cg * w * w * tn * tn, -2.0 * cg * w * tn, -cg});
    comp_.ends.push_back(tn);
    ++comp_.K;
    t = tn;
  }
  comp_.on = comp_.K > 0;
  return comp_.on;
}

// The composed step of the element in slot sl, at x at the step's start
// (along the depth path p), where it applies: false where the element is
// fresh or switches during the step (step_material takes it).
bool Row::composed_step(std::size_t sl, double x, const Path& p) {
  double* y = &y_[sl * stride_];
  double pe = 0.0;
  const bool contact = mode_[sl] == Mode::Contact && composed_contact(y, x, pe);
  const bool done = contact || (mode_[sl] == Mode::Free && composed_free(y, x, w_, p));
  if (contact) {
    p_end_[sl] = pe;
    p_gen_[sl] = state_gen_;
  }
  if (done) {
    updates_ += static_cast<long>(comp_.K);
    ++composed_steps_;
  }
  return done;
}

// The composed step of an element in contact at x (the step's start), state
// y: false (y unchanged) where its force turns negative at a sub-step's end,
// as substep's switch test sees it (p < -p_tiny_); pe: its force at the end.
bool Row::composed_contact(double* y, double x, double& pe) const {
  const std::size_t n = law_.branches();
  const double* W = comp_.W.data();
  for (std::size_t i = 0; i < comp_.K; ++i, W += n) {
    const double p = at_end(&comp_.pi[3 * i], W, y, n, x);
    if (p < -p_tiny_) return false;
    pe = p;
  }
  for (std::size_t k = 0; k < n; ++k)
    y[k] = comp_.E[k] * y[k] + comp_.A[k] + (comp_.B[k] + comp_.C[k] * x) * x;
  return true;
}

// The composed step of a free element at x (the step's start), modal state
// y: false (y unchanged) where it touches at a sub-step's end, as substep's
// test sees it (a gap above psi_tiny_ inside the indenter's reach).
bool Row::composed_free(double* y, double x, double w, const Path& p) const {
  const std::size_t m = law_.free_dim();
  const double* V = comp_.V.data();
  for (std::size_t i = 0; i < comp_.K; ++i, V += m) {
    const double gap = at_end(&comp_.hi[3 * i], V, y, m, x);
    const double tn = comp_.ends[i];
    if (gap > psi_tiny_ && inside(x + w * tn, p.at(tn))) return false;
  }
  for (std::size_t k = 0; k < m; ++k)
    y[k] *= comp_.M[k];
  return true;
}

} // namespace mdrmap::spectrum
