#pragma once
// Indentation creep from rest under a step load (Lee-Radok; docs/design.md,
// "Materials with a relaxation spectrum"): d^(3/2)(t) = (3 F0 / (16 sqrt R)) J(t),
// J the creep compliance of the element's rheology, J_bar(s) = 1 / (s^2 G_bar(s)).
//
// With M(s) = s G_bar(s) = G + G tau s + sum_k G_k tau_k s / (1 + s tau_k), the
// poles of J_bar are s = 0 and the zeros of M, all real and negative. In the
// retardation time rho = -1/s they are the roots of the secular equation
//   f(rho) = G - G tau / rho - sum_k G_k tau_k / (rho - tau_k) = 0,
// f increasing between its poles (0 when tau > 0, and the distinct tau_k), from
// -inf to +inf: one retardation time between consecutive relaxation times and
// one above the longest (N of them, N + 1 with the dashpot, which adds one below
// the shortest). By residues
//   J(t) = J(0) + sum_j c_j (1 - exp(-t / rho_j)),   c_j = 1 / (rho_j f'(rho_j)),
// J(0) = 1/G0 without a dashpot, 0 with one; J(inf) = 1/G. The roots are found
// in the offset from their nearer pole, so each keeps its relative precision
// however far apart the times lie.
#include <vector>

#include "core/model/case.hpp"
#include "core/model/rheology.hpp"

namespace mdrmap {

/// The creep compliance as a sum of exponentials.
struct CreepSpectrum {
  double J0 = 0.0;         ///< J(0+): 1/G0, or 0 with a parallel dashpot
  std::vector<double> rho; ///< retardation times, ascending (aT applied)
  std::vector<double> c;   ///< their weights, > 0; J0 + sum c = 1/G
};

/// Retardation spectrum of the element (its shifted times: aT applied).
CreepSpectrum creep_spectrum(const Rheology& r);

/// J(t) for t >= 0, every term non-negative (1 - exp written with expm1).
double creep_compliance(const CreepSpectrum& s, double t);
double creep_compliance(const Rheology& r, double t);

/// Depth at time t >= 0 after the load F0 of the case is applied at t = 0 to
/// the material at rest: d = (3 F0 J(t) / (16 sqrt R))^(2/3). (0 at t = 0 with a
/// parallel dashpot; the Hertz depth of G0 at t = 0+ without.)
double creep_depth(const Case& c, double t);

} // namespace mdrmap
