#pragma once
// The contact state at one instant, and a time series of it.
#include <cstddef>
#include <vector>

namespace mdrmap {

/// Contact forces, friction coefficient and contact edges at one instant.
/// F_x is positive when it resists the motion; mu = F_x / F_N; the contact
/// occupies [-a1, a2] in the frame of the indenter, the indenter's depth is d
/// (fixed under depth control, free under load control).
struct State {
  double FN = 0.0;
  double Fx = 0.0;
  double mu = 0.0;
  double a2 = 0.0;
  double d = 0.0;
  double a1 = 0.0;
};

/// The states at a case's sample instants, segment after segment, and the
/// stationary state before t = 0.
struct Series {
  State pre;
  std::vector<double> t;    ///< time since the first change
  std::vector<int> segment; ///< 0-based segment of each sample
  std::vector<double> FN, Fx, mu, a2, d, a1;
  void resize(std::size_t n);
  void set(std::size_t k, double time, int seg, const State& st);
  State at(std::size_t k) const { return State{FN[k], Fx[k], mu[k], a2[k], d[k], a1[k]}; }
  std::size_t size() const { return t.size(); }
};

} // namespace mdrmap
