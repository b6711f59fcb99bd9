#pragma once
// Shared by the physics tests: a Scene from its parameters in one call.
#include "core/scene.hpp"

namespace mdrmap::testing {

inline Scene make_scene(double d, double R, double tau, double v, double v1 = 0.0, double G = 1.0) {
  Scene s;
  s.d = d;
  s.R = R;
  s.tau = tau;
  s.v = v;
  s.v1 = v1;
  s.G = G;
  return s;
}

} // namespace mdrmap::testing
