#include "core/case_set.hpp"

#include <cmath>
#include <cstdio>

namespace mdrmap {

std::vector<NamedScene> hard_case_set() {
  std::vector<NamedScene> out;
  const double zetas[] = {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e8};
  const double ratios[] = {0.0, 1e-4, 0.1, 0.5, 2.0, 100.0};
  const double d_over_r[] = {1e-12, 1e-6, 1e-3, 0.3};
  int i = 0;
  for (double z : zetas) {
    for (double q : ratios) {
      Scene s;
      s.R = 1.0 + 0.25 * (i % 3); // vary the absolute scale a little too
      s.d = d_over_r[i % 4] * s.R;
      s.tau = 0.5 + 0.1 * (i % 5);
      s.G = 1.0;
      const double a1 = std::sqrt(s.R * s.d);
      s.v = z * a1 / s.tau;
      s.v1 = q * s.v;
      char name[96];
      std::snprintf(name, sizeof name, "zeta=%g v1/v=%g d/R=%g", z, q, s.d / s.R);
      out.push_back({name, s});
      ++i;
    }
  }
  auto add = [&](const char* name, double d, double R, double tau, double v, double v1, double G) {
    Scene s;
    s.d = d, s.R = R, s.tau = tau, s.v = v, s.v1 = v1, s.G = G;
    out.push_back({name, s});
  };
  add("tau=0 drop", 1e-3, 1.0, 0.0, 1.0, 0.1, 1.0);
  add("tau=0 rise", 1e-3, 1.0, 0.0, 1.0, 10.0, 1.0);
  add("v1=v", 1e-3, 1.0, 1.0, 0.05, 0.05, 1.0);
  // SI: d = 10 nm, R = 1 mm, G = 1 MPa, tau = 1 ms, v = 1 m/s -> 1 mm/s
  add("SI start-stop", 1e-8, 1e-3, 1e-3, 1.0, 1e-3, 1e6);
  // mu falls to ~1e-7 of its value before the step: zeta = 1e4, zeta1 = 1e-7
  add("mu falls 1e-7", 1e-3, 1.0, 1.0, 1e4 * std::sqrt(1e-3), 1e-7 * std::sqrt(1e-3), 1.0);
  // paper's start-stop test: v1 = 1e-4 v with zeta = 1e3
  add("paper start-stop", 1e-2, 1.0, 1.0, 100.0, 1e-2, 1.0);
  return out;
}

} // namespace mdrmap
