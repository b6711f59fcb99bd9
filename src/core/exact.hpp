#pragma once
// Continuum (dx -> 0) solution of the MDR model for the velocity step.
//
// After a drop v -> v1 < v the contact set is [-a1, a2(t)], every element in it
// follows the indenter at v1, and a2(t) = min(a2(v1), a2v + y(t)), where y is
// the root of a scalar equation: in the moving frame the free tail left behind
// by stationary sliding is h(a2v) exp(-(x - a2v)/(v tau)) scaled by
// c(t) = exp(-(1 - v1/v) t / tau), and material touches the indenter again
// where that falls below the indenter's depth h(x) = d - x^2/R. The set where
// it does is an interval (log h is concave, log of the tail is linear), so the
// trailing edge is its right end. The forces are the closed-form integrals
// analytic::contact_forces. A rise (v1 > v) or tau = 0 reaches the stationary
// state at v1 at once.
#include "core/solver.hpp"

namespace mdrmap {

class ExactSolution {
public:
  /// `bits`: binary digits the trailing-edge root is solved to (<= 52).
  explicit ExactSolution(const Scene& s, int bits = 50);

  State pre() const { return pre_; }
  /// State at time t >= 0 after the step (t = 0 is just after it).
  State at(double t) const;
  /// Bound on |a2 error| / a1 of the last call to at() (root bracket width).
  double last_bracket() const { return last_bracket_; }
  long root_solves() const { return root_solves_; }

private:
  Scene s_;
  int bits_;
  State pre_, post_;
  double a1_ = 0, a2v_ = 0, a2v1_ = 0, a1_minus_a2v_ = 0, a1_minus_a2v1_ = 0, h_a2v_ = 0, L_ = 0;
  bool transient_ = false;
  mutable double last_bracket_ = 0.0;
  mutable long root_solves_ = 0;
};

/// Samples the continuum solution at the protocol's instants. rtol sets the
/// root tolerance; info.error_estimate bounds the case error.
RunResult run_exact(const Scene& s, const Protocol& p, double rtol = 1e-12);

} // namespace mdrmap
