#include "core/solvers/spectrum_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/numerics/phi.hpp"

namespace mdrmap::spectrum {
namespace {

// phi_a(z) = 1 - (1 - e^-z)/z and phi_b(z) = 1 - 2/z + 2 (1 - e^-z)/z^2: the
// response of tau q' = u - q (q(0) = 0) to u = t and u = t^2, over dt, in
// units of dt and dt^2 (z = dt/tau, e = e^-z): z phi_2(z) and 2 z phi_3(z) of
// numerics/phi.hpp, taken from there below z = 0.5, where the closed form
// cancels (phi_3 by its series, phi_2 = 1/2 - z phi_3).
void phis(double z, double e, double& pa, double& pb) {
  if (z < 0.5) {
    double p[4];
    numerics::phi_all(z, e, p);
    pa = z * p[2];
    pb = 2.0 * z * p[3];
    return;
  }
  const double omd = 1.0 - e; // (e <= 0.61: no cancellation)
  pa = 1.0 - omd / z;
  pb = 1.0 - 2.0 / z + 2.0 * omd / (z * z);
}

} // namespace

void jacobi_eigen(std::vector<double>& a, std::size_t n, std::vector<double>& lam,
                  std::vector<double>& v) {
  v.assign(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    v[i * n + i] = 1.0;
  const double eps = std::numeric_limits<double>::epsilon();
  for (int sweep = 0; sweep < 100; ++sweep) {
    bool rotated = false;
    for (std::size_t p = 0; p + 1 < n; ++p) {
      for (std::size_t q = p + 1; q < n; ++q) {
        const double apq = a[p * n + q], app = a[p * n + p], aqq = a[q * n + q];
        if (!(std::abs(apq) > eps * std::sqrt(std::abs(app * aqq)))) continue;
        rotated = true;
        const double theta = (aqq - app) / (2.0 * apq);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::hypot(theta, 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (std::size_t r = 0; r < n; ++r) { // columns p, q
          const double arp = a[r * n + p], arq = a[r * n + q];
          a[r * n + p] = c * arp - s * arq;
          a[r * n + q] = s * arp + c * arq;
        }
        for (std::size_t r = 0; r < n; ++r) { // rows p, q
          const double apr = a[p * n + r], aqr = a[q * n + r];
          a[p * n + r] = c * apr - s * aqr;
          a[q * n + r] = s * apr + c * aqr;
        }
        a[p * n + q] = a[q * n + p] = 0.0;
        for (std::size_t r = 0; r < n; ++r) {
          const double vrp = v[r * n + p], vrq = v[r * n + q];
          v[r * n + p] = c * vrp - s * vrq;
          v[r * n + q] = s * vrp + c * vrq;
        }
      }
    }
    if (!rotated) break;
  }
  lam.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    lam[i] = a[i * n + i];
}

Law::Law(const Rheology& r) : G_(r.G), tau_(r.tau), G0_(r.G0()) {
  n_ = r.branches.size();
  for (const Branch& b : r.branches) {
    Gk_.push_back(b.G);
    tk_.push_back(b.tau);
  }
  const bool dash = tau_ > 0.0;
  m_ = n_ + (dash ? 1 : 0);
  const std::size_t o = dash ? 1 : 0; // index of q_1 in y
  // S = B M (symmetric) and the weights B
  std::vector<double> S(m_ * m_, 0.0), B(m_, 0.0);
  if (dash) {
    B[0] = G_ * tau_;
    S[0] = -G0_;
    for (std::size_t k = 0; k < n_; ++k) {
      S[k + 1] = S[(k + 1) * m_] = Gk_[k];
      S[(k + 1) * m_ + k + 1] = -Gk_[k];
    }
  } else {
    for (std::size_t k = 0; k < n_; ++k)
      for (std::size_t l = 0; l < n_; ++l)
        S[k * m_ + l] = Gk_[k] * Gk_[l] / G0_ - (k == l ? Gk_[k] : 0.0);
  }
  for (std::size_t k = 0; k < n_; ++k)
    B[k + o] = Gk_[k] * tk_[k];
  std::vector<double> A(m_ * m_), Q, lam;
  for (std::size_t i = 0; i < m_; ++i)
    for (std::size_t j = 0; j < m_; ++j)
      A[i * m_ + j] = S[i * m_ + j] / std::sqrt(B[i] * B[j]);
  jacobi_eigen(A, m_, lam, Q);
  rate_.resize(m_);
  P_.assign(m_ * m_, 0.0);
  Pinv_.assign(m_ * m_, 0.0);
  for (std::size_t i = 0; i < m_; ++i) {
    rate_[i] = -lam[i];
    if (!(rate_[i] > 0.0))
      throw std::logic_error("spectrum: a free mode does not decay (rounding in the modes)");
    for (std::size_t j = 0; j < m_; ++j) {
      P_[i * m_ + j] = Q[i * m_ + j] / std::sqrt(B[i]);
      Pinv_[j * m_ + i] = Q[i * m_ + j] * std::sqrt(B[i]);
    }
  }
  cu_.assign(m_, 0.0);
  for (std::size_t j = 0; j < m_; ++j) {
    if (dash) {
      cu_[j] = P_[j];
    } else {
      double s = 0.0;
      for (std::size_t k = 0; k < n_; ++k)
        s += Gk_[k] * P_[k * m_ + j];
      cu_[j] = s / G0_;
    }
  }
}

void Law::coef(double dt, StepCoef& c, Part part) const {
  if (c.dt == dt && c.part == part) return;
  c.dt = dt;
  c.part = part;
  if (part != Part::Free) {
    c.e.resize(n_);
    c.a.resize(n_);
    c.b.resize(n_);
    for (std::size_t k = 0; k < n_; ++k) {
      const double z = dt / tk_[k], e = decay(z);
      double pa = 0.0, pb = 0.0;
      phis(z, e, pa, pb);
      c.e[k] = e;
      c.a[k] = dt * pa;
      c.b[k] = dt * dt * pb;
    }
  }
  if (part != Part::Contact) {
    c.modal.resize(m_);
    for (std::size_t i = 0; i < m_; ++i)
      c.modal[i] = decay(rate_[i] * dt);
  }
}

double Law::pressure_rate(double u, double du, double ddu, const double* q) const {
  double s = G0_ * du + G_ * tau_ * ddu;
  for (std::size_t k = 0; k < n_; ++k)
    s -= Gk_[k] * (u - q[k]) / tk_[k];
  return s;
}

double Law::free_span(const double* z0, double* z, double T) const {
  double floor = 0.0;
  for (std::size_t i = 0; i < m_; ++i) {
    z[i] = z0[i] * decay(rate_[i] * T);
    floor += std::min(cu_[i] * z0[i], cu_[i] * z[i]);
  }
  return floor;
}

double Law::free_rate(const double* z) const {
  double r = 0.0;
  for (std::size_t i = 0; i < m_; ++i)
    r -= cu_[i] * rate_[i] * z[i];
  return r;
}

void Law::to_modal(double h, const double* q, double* z) const {
  const std::size_t o = m_ - n_;
  for (std::size_t i = 0; i < m_; ++i) {
    double s = o ? Pinv_[i * m_] * h : 0.0;
    for (std::size_t k = 0; k < n_; ++k)
      s += Pinv_[i * m_ + k + o] * q[k];
    z[i] = s;
  }
}

void Law::from_modal(const double* z, double* q) const {
  const std::size_t o = m_ - n_;
  for (std::size_t k = 0; k < n_; ++k) {
    double s = 0.0;
    for (std::size_t i = 0; i < m_; ++i)
      s += P_[(k + o) * m_ + i] * z[i];
    q[k] = s;
  }
}

double Law::shortest_time() const {
  double t = std::numeric_limits<double>::infinity();
  for (const double tk : tk_)
    t = std::min(t, tk);
  return t;
}

} // namespace mdrmap::spectrum
