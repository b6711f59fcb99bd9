#include "cases/load_case_set.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>

namespace mdrmap {
namespace {

/// A load-controlled history: R = 2, G = 1, F0 in units of G R^2, v0 from
/// zeta0 = v0 tau / a0, segments as (w / v0, T / tau); for tau = 0 durations
/// are in units of a0 / v0.
NamedCase history(const std::string& name, double zeta0, double F0_over_GR2,
                  const std::vector<std::pair<double, double>>& segs, double tau, long samples) {
  Case c;
  c.indenter.as<Parabola>().R = 2.0;
  c.rheology.G = 1.0;
  c.rheology.tau = tau;
  c.loading.F0 =
      F0_over_GR2 * c.rheology.G * c.indenter.as<Parabola>().R * c.indenter.as<Parabola>().R;
  const double a0 = c.a0();
  c.history.v0 = tau > 0.0 ? zeta0 * a0 / tau : 1.0;
  const double t_unit = tau > 0.0 ? tau : a0 / c.history.v0;
  for (const auto& [w, T] : segs)
    c.history.segments.push_back(Segment{w * c.history.v0, T * t_unit});
  c.sampling.samples = samples;
  return {name, c};
}

std::string fmt(const char* f, double x) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

} // namespace

std::vector<NamedCase> load_case_set(long samples) {
  std::vector<NamedCase> out;
  auto add = [&](const std::string& name, double zeta0, double F0,
                 std::vector<std::pair<double, double>> segs,
                 double tau = 1.0) { out.push_back(history(name, zeta0, F0, segs, tau, samples)); };
  const double F = 1e-3; // F0 / (G R^2) of the ordinary cases: a0 / R ~ 0.08
  for (double z : {0.1, 1.0, 10.0}) {
    add(fmt("3seg up 10x and back, zeta0=%g", z), z, F, {{10.0, 3.0}, {1.0, 3.0}, {10.0, 3.0}});
    add(fmt("3seg down 10x and back, zeta0=%g", z), z, F, {{0.1, 3.0}, {1.0, 3.0}, {0.1, 3.0}});
  }
  for (double th : {0.1, 1.0, 10.0, 100.0, 1000.0})
    add(fmt("3seg slide-hold-slide hold=%g tau", th), 1.0, F, {{1.0, 1.0}, {0.0, th}, {1.0, 4.0}});
  add("3seg hold 1e4 tau (creep)", 0.3, F, {{0.1, 1.0}, {0.0, 1e4}, {1.0, 3.0}});
  add("ratio 1e-6 then back", 1.0, F, {{1e-6, 3.0}, {1.0, 2.0}});
  add("ratio 1e6 from zeta0=1e-4", 1e-4, F, {{1e6, 2.0}, {1.0, 2.0}});
  add("3seg zeta0=1e-4", 1e-4, F, {{0.1, 3.0}, {1.0, 3.0}, {0.0, 3.0}});
  add("zeta0=1e6 drop 1e-6", 1e6, F, {{1e-6, 3.0}, {1e-3, 2.0}});
  add("3seg zeta0=1e6 drop 10x", 1e6, F, {{0.1, 2.0}, {1.0, 2.0}, {0.1, 2.0}});
  add("tau=0 drop-hold-rise", 1.0, F, {{0.1, 2.0}, {0.0, 1.0}, {10.0, 2.0}}, 0.0);
  add("3seg small tau 1e-9", 1.0, F, {{0.1, 3.0}, {0.0, 2.0}, {1.0, 3.0}}, 1e-9);
  {
    std::vector<std::pair<double, double>> segs;
    for (int k = 0; k < 20; ++k)
      segs.push_back({k % 4 == 3 ? 0.0 : std::pow(10.0, (k % 4) - 1.0), 0.3 + 0.05 * k});
    add("twenty segments with holds", 1.0, F, segs);
  }
  add("3seg load 1e-12 G R^2", 1.0, 1e-12, {{0.1, 2.0}, {0.0, 2.0}, {1.0, 3.0}});
  add("3seg load 1e3 G R^2", 1.0, 1e3, {{0.1, 2.0}, {0.0, 2.0}, {1.0, 3.0}});
  // drop to 0.1 v0, a short hold, a rise: the hold's re-touch front starts
  // from the tangency the cap left, where a2 is most sensitive to the depth
  for (const auto& [z, th, up] :
       {std::tuple{10.0, 0.01, 1.0}, std::tuple{10.0, 0.1, 1.0}, std::tuple{3.0, 0.01, 1.0},
        std::tuple{1.0, 0.1, 1.0}, std::tuple{30.0, 0.03, 1.0}, std::tuple{10.0, 0.3, 3.0}})
    add(fmt("drop-hold-rise zeta0=%g", z) + fmt(" hold=%g", th) + fmt(" rise=%gx", up), z, F,
        {{0.1, 1.0}, {0.0, th}, {up, 1.0}});
  // after a long hold (the Hertz rest state), a reslide whose travel is a
  // small fraction of a0 (and of the cells of rtol's resolution), then a
  // hold: the front crosses the narrow pieces the reslide left
  for (const auto& [z, th, T] : {std::tuple{1e-3, 100.0, 0.1}, std::tuple{1e-2, 10.0, 0.01},
                                 std::tuple{1e-3, 100.0, 0.03}, std::tuple{0.1, 10.0, 0.005}})
    add(fmt("sub-grid reslide zeta0=%g", z) + fmt(" travel=%g a0", z * T), z, F,
        {{0.0, th}, {1.0, T}, {0.0, 1.0}});
  return out;
}

} // namespace mdrmap
