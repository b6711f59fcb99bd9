#pragma once
// The contact state at one instant, and a time series of it.
#include <cstddef>
#include <vector>

namespace mdrmap {

/// Contact forces, friction coefficient and trailing edge at one instant.
/// F_x is positive when it resists the motion; mu = F_x / F_N; the contact
/// occupies [-a1, a2] in the frame of the indenter.
struct State {
  double FN = 0.0;
  double Fx = 0.0;
  double mu = 0.0;
  double a2 = 0.0;
};

/// The states at a case's sample instants, segment after segment, and the
/// stationary state before t = 0.
struct Series {
  State pre;
  std::vector<double> t;    ///< time since the first change
  std::vector<int> segment; ///< 0-based segment of each sample
  std::vector<double> FN, Fx, mu, a2;
  void resize(std::size_t n);
  void set(std::size_t k, double time, int seg, const State& st);
  State at(std::size_t k) const { return State{FN[k], Fx[k], mu[k], a2[k]}; }
  std::size_t size() const { return t.size(); }
};

} // namespace mdrmap
