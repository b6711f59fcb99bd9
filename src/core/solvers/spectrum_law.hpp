#pragma once
// The element law of a relaxation spectrum (core/model/rheology.hpp), per unit 4 dx:
//
//   p = G u + G tau u' + sum_k G_k (u - q_k),   tau_k q_k' = u - q_k,
//
// with exact updates over a time step (never explicit Euler):
//  - in contact u is prescribed, u(t) = h0 + h1 t + h2 t^2 along a step at
//    constant velocity (the parabola's depth at the moving material point), and
//    each branch is updated in closed form with phi functions (stable and
//    exact for tau_k << dt);
//  - free (p = 0) the state y = (u, q_1..q_N) (tau > 0) or y = q (tau = 0, u =
//    sum G_k q_k / G0 algebraic) obeys y' = M y with B M symmetric negative
//    definite, B = diag(G tau, G_k tau_k) (or diag(G_k tau_k)): with
//    S = B M, x^T S x = -G u^2 - sum G_k (u - q_k)^2 (tau > 0) or
//    (sum G_k q_k)^2 / G0 - sum G_k q_k^2 < 0 (tau = 0, Cauchy-Schwarz and
//    G > 0). So A = B^-1/2 S B^-1/2 = Q L Q^T (Jacobi, once per case) and
//    y = P z, P = B^-1/2 Q, z_i(t) = z_i(0) exp(L_i t): every free element
//    moves exactly in modal coordinates z.
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/model/rheology.hpp"

namespace mdrmap::spectrum {

// exp(-z) for z >= 0, without the call where it underflows to 0 (z >= 746:
// below half the least subnormal), as it does for the fast branches and modes
// over most steps (of 11 terms 1e-9 .. 10, the four fastest over a step of
// 1e-3) and for their layers a cell behind the leading edge: glibc's exp takes
// its slow path there. Bit for bit std::exp(-z).
inline double decay(double z) {
  return z >= 746.0 ? 0.0 : std::exp(-z);
}

/// Per-step coefficients of a contact update over dt: for branch k,
/// q(dt) = e q0 + (1 - e) h0 + a h1 + b h2 (e = exp(-dt/tau_k),
/// a = dt phi_a(dt/tau_k), b = dt^2 phi_b(dt/tau_k)); and the modal factors
/// exp(L_i dt) of a free update.
/// Which coefficients a StepCoef holds.
enum class Part { Both, Contact, Free };

struct StepCoef {
  double dt = -1.0;
  Part part = Part::Both;
  std::vector<double> e, a, b, modal;
};

class Law {
public:
  explicit Law(const Rheology& r);

  std::size_t branches() const { return n_; }
  /// Dimension of the free state (N + 1 with a dashpot, else N).
  std::size_t free_dim() const { return m_; }
  double G() const { return G_; }
  double tau() const { return tau_; }
  double G0() const { return G0_; }
  double Gk(std::size_t k) const { return Gk_[k]; }
  double tauk(std::size_t k) const { return tk_[k]; }
  /// The shortest branch time (infinity without branches).
  double shortest_time() const;
  /// Decay rates -L_i of the free modes (> 0).
  const std::vector<double>& rates() const { return rate_; }

  /// Coefficients of a step of dt (both parts, or the one a caller needs).
  void coef(double dt, StepCoef& c, Part part = Part::Both) const;

  /// Contact update of the branch states q over a step (coefficients c).
  void contact_step(double* q, double h0, double h1, double h2, const StepCoef& c) const {
    contact_step(q, q, h0, h1, h2, c);
  }
  /// The same from q0 into q (q may be q0): a caller that may still need
  /// the state before the step keeps it without copying it first.
  void contact_step(const double* q0, double* q, double h0, double h1, double h2,
                    const StepCoef& c) const;
  /// The contact update of q in place (its state before kept in q0) and the
  /// force after it: bit for bit contact_step and pressure(u, du, q), in one
  /// pass.
  double contact_step_pressure(double* q, double* q0, double u, double du, double h0, double h1,
                               double h2, const StepCoef& c) const;
  /// Contact force per 4 dx for depth u, rate du, branch states q.
  double pressure(double u, double du, const double* q) const;
  /// The contact force's rate along a path with depth u, rate du and
  /// acceleration ddu (the branches' rates (u - q_k) / tau_k).
  double pressure_rate(double u, double du, double ddu, const double* q) const;
  /// Free update in modal coordinates: z_i *= exp(L_i dt).
  void free_step(double* z, const StepCoef& c) const { free_step(z, z, c); }
  /// The same from z0 into z (z may be z0).
  void free_step(const double* z0, double* z, const StepCoef& c) const;
  /// The free update of z in place (its state before kept in z0) and the
  /// depression after it: bit for bit free_step and free_u(z), in one pass.
  double free_step_u(double* z, double* z0, const StepCoef& c) const;
  /// The free update over T from z0 into z (z_i = z0_i exp(L_i T), no
  /// coefficient set formed) and a floor of the depression u over [0, T]:
  /// each mode's term cu_i z_i(t) of u is monotone in t, so the lesser of its
  /// ends bounds it (Row::free_until).
  double free_span(const double* z0, double* z, double T) const;
  /// Free depression u of modal state z.
  double free_u(const double* z) const;
  /// Its weights: u = sum_i free_weight(i) z_i.
  double free_weight(std::size_t i) const { return cu_[i]; }
  /// Its rate (each mode decays at its rate).
  double free_rate(const double* z) const;

  /// Contact (u = h, branch states q) -> free modal state z.
  void to_modal(double h, const double* q, double* z) const;
  /// Free modal state z -> branch states q.
  void from_modal(const double* z, double* q) const;

private:
  /// Branch k's state after a contact update of q0 (contact_step's one term).
  double stepped(std::size_t k, const double* q0, double h0, double h1, double h2,
                 const StepCoef& c) const;

  std::size_t n_ = 0, m_ = 0;
  double G_, tau_, G0_;
  std::vector<double> Gk_, tk_;
  std::vector<double> rate_;     // -L_i
  std::vector<double> P_, Pinv_; // m x m, row-major
  std::vector<double> cu_;       // u = cu . z
};

// The per-sub-step operations, inline: a replay or step makes several calls
// of a few operations each per sub-step (the same arithmetic, in order).
inline double Law::stepped(std::size_t k, const double* q0, double h0, double h1, double h2,
                           const StepCoef& c) const {
  return h0 + c.e[k] * (q0[k] - h0) + c.a[k] * h1 + c.b[k] * h2;
}

inline void Law::contact_step(const double* q0, double* q, double h0, double h1, double h2,
                              const StepCoef& c) const {
  for (std::size_t k = 0; k < n_; ++k)
    q[k] = stepped(k, q0, h0, h1, h2, c);
}

inline double Law::pressure(double u, double du, const double* q) const {
  double s = G0_ * u + G_ * tau_ * du;
  for (std::size_t k = 0; k < n_; ++k)
    s -= Gk_[k] * q[k];
  return s;
}

inline double Law::contact_step_pressure(double* q, double* q0, double u, double du, double h0,
                                         double h1, double h2, const StepCoef& c) const {
  double s = G0_ * u + G_ * tau_ * du;
  for (std::size_t k = 0; k < n_; ++k) {
    q0[k] = q[k];
    q[k] = stepped(k, q0, h0, h1, h2, c);
    s -= Gk_[k] * q[k];
  }
  return s;
}

inline double Law::free_step_u(double* z, double* z0, const StepCoef& c) const {
  double u = 0.0;
  for (std::size_t i = 0; i < m_; ++i) {
    z0[i] = z[i];
    z[i] = z0[i] * c.modal[i];
    u += cu_[i] * z[i];
  }
  return u;
}

inline void Law::free_step(const double* z0, double* z, const StepCoef& c) const {
  for (std::size_t i = 0; i < m_; ++i)
    z[i] = z0[i] * c.modal[i];
}

inline double Law::free_u(const double* z) const {
  double u = 0.0;
  for (std::size_t i = 0; i < m_; ++i)
    u += cu_[i] * z[i];
  return u;
}

/// Eigen-decomposition of a symmetric matrix a (n x n, row-major, destroyed)
/// by cyclic Jacobi with the relative stopping test |a_pq| <= eps
/// sqrt(|a_pp a_qq|) (high relative accuracy for scaled definite matrices):
/// eigenvalues in `lam`, eigenvectors the columns of v.
void jacobi_eigen(std::vector<double>& a, std::size_t n, std::vector<double>& lam,
                  std::vector<double>& v);

} // namespace mdrmap::spectrum
