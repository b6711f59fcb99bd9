#pragma once
// Shared by the physics tests: the seed's one-step case (stationary sliding at
// v, then v1 for one segment) from its parameters in one call, and its parts.
#include "core/case.hpp"

namespace mdrmap::testing {

/// step_case with the tests' argument order: t_end = 0 is the default window
/// (6 tau; 6 a1 / min(v, v1) for tau = 0), `samples` linear samples.
inline Case make_case(double d, double R, double tau, double v, double v1 = 0.0, double G = 1.0,
                      double t_end = 0.0, long samples = 201) {
  return step_case(d, R, tau, v, v1, G, t_end, samples);
}

/// Velocity after the step (the one segment's velocity).
inline double v1_of(const Case& c) {
  return c.history.segments.at(0).w;
}

/// Observation window after the step (the one segment's duration).
inline double t_end_of(const Case& c) {
  return c.history.segments.at(0).T;
}

/// Sets both velocities of a one-step case; the window T is kept.
inline void set_velocities(Case& c, double v, double v1) {
  c.history.v0 = v;
  c.history.segments.at(0).w = v1;
}

} // namespace mdrmap::testing
