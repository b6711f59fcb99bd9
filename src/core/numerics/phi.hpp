#pragma once
// The phi functions of exponential integrators (docs/design.md, "Numerics
// floor"): phi_n(z) = sum_j (-z)^j / (j + n)!, so phi_0 = exp(-z),
// phi_1 = (1 - exp(-z)) / z, phi_2 = (exp(-z) - 1 + z) / z^2, and
// phi_(n+1) = (1/n! - phi_n) / z. They weigh a forcing polynomial of degree
// n - 1 over a step of an exponential decay: the response of tau q' = u - q,
// q(0) = 0, to u = t over a step dt is dt z phi_2(z), to u = t^2 it is
// 2 dt^2 z phi_3(z) (z = dt / tau).
// Evaluated without cancellation for any real z: for |z| <= 2 the highest
// one wanted by its series (Horner's rule: smallest terms first, truncated
// below 1e-17 of the sum) and the others downward, phi_n = 1/n! - z phi_(n+1);
// above, phi_1 = (1 - exp(-z)) / z and the recurrence upward (its error factor
// phi_n / (z phi_(n+1)) is below 2.5 for |z| > 2, n < 6). One exp: phi_all
// gives phi_0 = exp(-z) with the others at the cost of the highest.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>

namespace mdrmap::numerics {

namespace phi_detail {

constexpr int kMaxTerms = 28; ///< series terms for |z| <= 2 (2^28/28! e^2 < 1e-20)
constexpr int kMaxN = 5;      ///< highest n of the family

constexpr std::array<double, kMaxTerms + kMaxN + 1> inverse_factorials() {
  std::array<double, kMaxTerms + kMaxN + 1> f{};
  double x = 1.0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (k > 0) x /= static_cast<double>(k);
    f[k] = x;
  }
  return f;
}
inline constexpr auto kInvFact = inverse_factorials();

/// Terms of the series that reach 1e-17 of phi_n at |z| (the first term left
/// out is below that: |z|^J / J! e^|z| < 1e-17).
inline int series_terms(double az) {
  if (az <= 1e-3) return 6;
  if (az <= 0.1) return 11;
  if (az <= 0.5) return 16;
  return kMaxTerms;
}

/// sum_{j < terms} (-z)^j / (j + n)! by Horner's rule.
inline double series(int n, double z, int terms) {
  const double* c = kInvFact.data() + n; // (n >= 0)
  double s = c[terms - 1];
  for (int j = terms - 2; j >= 0; --j)
    s = c[j] - z * s;
  return s;
}

/// phi_1..phi_top for |z| <= 2: phi_top by its series, the others downward,
/// phi_n = 1/n! - z phi_(n+1) (for n >= 1 the factor z phi_(n+1) / phi_n
/// that carries an error down is below 1.4 there).
inline void series_down(double z, double* out, int top) {
  out[top] = series(top, z, series_terms(std::abs(z)));
  for (int n = top - 1; n >= 1; --n)
    out[n] = kInvFact[static_cast<std::size_t>(n)] - z * out[n + 1];
}

/// phi_1..phi_top for |z| > 2 from e = exp(-z): phi_1 = (1 - e) / z (1 - e
/// does not cancel there) and upward, phi_(n+1) = (1/n! - phi_n) / z.
inline void recurrence_up(double z, double e, double* out, int top) {
  out[1] = (1.0 - e) / z;
  for (int n = 1; n < top; ++n)
    out[n + 1] = (kInvFact[static_cast<std::size_t>(n)] - out[n]) / z;
}

} // namespace phi_detail

/// phi_0(z), ..., phi_(N-1)(z) at once from e = exp(-z), for a caller that
/// has it (1 <= N <= 6; out[0] = e).
template <std::size_t N> void phi_all(double z, double e, double (&out)[N]) {
  static_assert(N >= 1 && N <= phi_detail::kMaxN + 1, "phi_all: 1 to 6 functions");
  out[0] = e;
  if (N == 1) return;
  constexpr int top = static_cast<int>(N) - 1;
  if (std::abs(z) <= 2.0)
    phi_detail::series_down(z, out, top);
  else
    phi_detail::recurrence_up(z, e, out, top);
}

/// phi_0(z), ..., phi_(N-1)(z) at once (1 <= N <= 6; out[0] = exp(-z)).
template <std::size_t N> void phi_all(double z, double (&out)[N]) {
  phi_all(z, std::exp(-z), out);
}

/// phi_n(z) for 0 <= n <= 5 and any real z (exp(-z) overflows for z < -709).
inline double phi(int n, double z) {
  double out[phi_detail::kMaxN + 1];
  if (n == 0) return std::exp(-z);
  if (std::abs(z) <= 2.0)
    phi_detail::series_down(z, out, n);
  else
    phi_detail::recurrence_up(z, std::exp(-z), out, n);
  return out[n];
}

} // namespace mdrmap::numerics
