#include "cases/case_set.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

namespace mdrmap {

std::vector<NamedCase> hard_case_set() {
  std::vector<NamedCase> out;
  const double zetas[] = {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e8};
  const double ratios[] = {0.0, 1e-4, 0.1, 0.5, 2.0, 100.0};
  const double d_over_r[] = {1e-12, 1e-6, 1e-3, 0.3};
  int i = 0;
  for (double z : zetas) {
    for (double q : ratios) {
      const double R = 1.0 + 0.25 * (i % 3); // vary the absolute scale a little too
      const double d = d_over_r[i % 4] * R;
      const double tau = 0.5 + 0.1 * (i % 5);
      const double v = z * std::sqrt(R * d) / tau;
      char name[96];
      std::snprintf(name, sizeof name, "zeta=%g v1/v=%g d/R=%g", z, q, d / R);
      out.push_back({name, step_case(d, R, tau, v, q * v)});
      ++i;
    }
  }
  auto add = [&](const char* name, double d, double R, double tau, double v, double v1, double G) {
    out.push_back({name, step_case(d, R, tau, v, v1, G)});
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

namespace {

/// A history case: v0 from zeta0 = v0 tau / a1, segments given as
/// (w / v0, T / tau); for tau = 0 durations are in units of a1 / v0.
NamedCase history(const char* name, double zeta0, double d_over_R,
                  std::vector<std::pair<double, double>> segs, double tau = 1.0,
                  long samples = 61) {
  const double R = 2.0, d = d_over_R * R;
  const double a1 = std::sqrt(R * d);
  const double v0 = tau > 0.0 ? zeta0 * a1 / tau : 1.0;
  const double t_unit = tau > 0.0 ? tau : a1 / v0;
  Case c = step_case(d, R, tau, v0, 0.0);
  c.history.segments.clear();
  for (const auto& [w, T] : segs)
    c.history.segments.push_back(Segment{w * v0, T * t_unit});
  c.sampling.samples = samples;
  return {name, c};
}

} // namespace

std::vector<NamedCase> history_case_set(long samples) {
  std::vector<NamedCase> out;
  auto add = [&](NamedCase nc) {
    nc.c.sampling.samples = samples;
    out.push_back(std::move(nc));
  };
  // successive drops, at small, order-one and large zeta
  for (double z : {1e-3, 0.3, 1.0, 30.0, 1e4}) {
    char name[64];
    std::snprintf(name, sizeof name, "two drops zeta=%g", z);
    add(history(name, z, 1e-3, {{0.3, 0.7}, {0.05, 3.0}}));
    std::snprintf(name, sizeof name, "three drops zeta=%g", z);
    add(history(name, z, 1e-3, {{0.3, 0.5}, {0.1, 0.5}, {0.01, 3.0}}));
    std::snprintf(name, sizeof name, "drop-rise-drop zeta=%g", z);
    add(history(name, z, 1e-3, {{0.1, 0.5}, {0.2, 1.0}, {0.05, 3.0}}));
  }
  // holds and reslides (slide-hold-slide), holds from 1e-6 to 1e6 tau
  for (double th : {1e-6, 1e-2, 1.0, 1e2, 1e6}) {
    char name[64];
    std::snprintf(name, sizeof name, "slide-hold-slide hold=%g tau", th);
    add(history(name, 1.0, 1e-3, {{0.0, th}, {1.0, 4.0}}));
  }
  add(history("hold 0.1 tau, restart at 0.2 v0", 1.0, 1e-3, {{0.0, 0.1}, {0.2, 4.0}}));
  add(history("hold inside a transient", 1.0, 1e-3, {{0.1, 0.3}, {0.0, 1.0}, {0.1, 3.0}}));
  add(history("rise inside a transient", 1.0, 1e-3, {{0.1, 0.5}, {0.2, 3.0}}));
  add(history("1 -> 10 -> 1 -> 0.1", 0.5, 1e-3, {{10.0, 2.0}, {1.0, 2.0}, {0.1, 4.0}}));
  // extreme ratios
  add(history("ratio 1e-8 then 1e8", 1e2, 1e-3, {{1e-8, 2.0}, {1.0, 2.0}}));
  add(history("ratio 1e8 then 1e-8", 1e-6, 1e-3, {{1e8, 2.0}, {1.0, 2.0}}));
  // 20 segments alternating up and down
  {
    std::vector<std::pair<double, double>> segs;
    for (int k = 0; k < 20; ++k)
      segs.push_back({k % 2 == 0 ? 0.05 : 1.0, 0.3 + 0.05 * k});
    add(history("20 segments alternating", 1.0, 1e-3, segs));
    std::vector<std::pair<double, double>> segs2;
    for (int k = 0; k < 20; ++k)
      segs2.push_back({k % 4 == 3 ? 0.0 : std::pow(10.0, (k % 4) - 2.0), 0.2 + 0.1 * (k % 3)});
    add(history("20 segments with holds", 3.0, 1e-3, segs2));
  }
  // depth over the hard range, and the elastic limit
  for (double dr : {1e-12, 1e-6, 0.3}) {
    char name[64];
    std::snprintf(name, sizeof name, "drop-hold-reslide d/R=%g", dr);
    add(history(name, 1.0, dr, {{0.1, 1.0}, {0.0, 2.0}, {1.0, 3.0}}));
  }
  add(history("tau=0 drop-hold-rise", 0.0, 1e-3, {{0.1, 2.0}, {0.0, 1.0}, {10.0, 2.0}}, 0.0));
  add(history("long hold 1e4 tau in a sequence", 0.3, 1e-3,
              {{0.1, 1.0}, {0.0, 1e4}, {0.3, 3.0}, {3.0, 2.0}}));
  return out;
}

const NamedCase& named_case(const std::vector<NamedCase>& set, const std::string& name) {
  for (const NamedCase& nc : set)
    if (nc.name == name) return nc;
  throw std::invalid_argument("no case '" + name + "' in the set");
}

} // namespace mdrmap
