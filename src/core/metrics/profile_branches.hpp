#pragma once
// The Maxwell branches' part of the stationary contact of any indenter's
// image g (core/metrics/profile_stationary.hpp): a branch of length
// lambda = w tau_k carries the stress
//   r(x) = int_{-a1}^{x} exp(-(x - x')/lambda) f(x') dx',  f = -g',
// and adds int r to F_N / 4 and int r f to F_x / 4 over the contact [-a1, a2].
// Integrating by parts with h = d - g (h(-a1) = 0, h' = f) splits r into its
// glassy part and a remainder that decays with lambda:
//   r = h - s,  s(x) = (1/lambda) int_{-a1}^{x} exp(-(x - x')/lambda) h(x') dx' >= 0,
//   int r f = h(a2)^2 / 2 - s(a2) h(a2) + (1/lambda) int r h.
// For lambda >= a1 / 2 (glassy) each term keeps its digits: int r f is
// O(a1 / lambda) of int h f over either face, which cancel (the direct sum
// gave negative friction at lambda / a1 = 1e16, issue 32). Below (relaxed),
// r = O(lambda f) and the direct form int r f (each face positive but for the
// layer behind the tip) is the one without cancellation.
//
// Quadrature: tanh-sinh on pieces split where the integrands are not smooth:
// the tip x = 0, and for a relaxed branch its layers of width lambda behind
// the leading edge and behind the tip (the kernel below e^-40 dropped).
// Every integrand evaluation is counted against a budget; past it the
// quadrature throws std::runtime_error (the caller fails the case).
#include <cstdint>
#include <variant>

#include "core/model/profile.hpp"

namespace mdrmap::profile {

/// The integrand evaluations one stationary state may spend (shared by the
/// contacts a root in a1 tries under load).
struct Budget {
  double max_evaluations = 2e7; ///< 0.1 to 1 s; the slowest state of issue 32 needs 2e6
  double evaluations = 0.0;
};

/// The contact of the image g at leading edge a1 (depth g(a1)), and the
/// budget its branches' quadrature charges.
struct BranchContact {
  ShapeImage img; ///< g (Indenter::image), symmetric
  double a1 = 0.0;
  Budget* budget = nullptr; ///< required
  /// |g'| at distance y >= 0 from the tip (at the tip its limit from y > 0).
  double slope_mag(double y) const {
    return std::visit([y](const auto& i) { return i.side_slope(y, 1); }, img);
  }
  /// h = d - g at x (|x| <= a1), from delta = a1 - |x| without cancellation.
  double depth_left(double delta) const {
    return std::visit([this, delta](const auto& i) { return i.drop(a1, delta); }, img);
  }
  /// Counts k evaluations; throws std::runtime_error past the budget.
  void charge(double k) const;
};

/// r(x) of a branch of length lambda at x in the contact, x = a1 - delta
/// behind the tip (delta = a1 - x given, so that h keeps its digits near
/// the trailing edge); any delta for x <= 0.
double branch_stress(const BranchContact& k, double lambda, double x, double delta);

/// int r over [-a1, a2] of the branch.
double branch_normal(const BranchContact& k, double lambda, double a2);

/// int r f over [-a1, a2] of the branch, a2 = a1 - delta.
double branch_friction(const BranchContact& k, double lambda, double a2, double delta);

} // namespace mdrmap::profile
