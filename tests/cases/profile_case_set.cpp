#include "cases/profile_case_set.hpp"

#include <string>
#include <utility>

#include "cases/spectrum_case_set.hpp"

namespace mdrmap {
namespace {

using Pairs = std::vector<std::pair<double, double>>;

constexpr double kContact = 1e-2; // a1 at fixed depth, a0 under load

struct NamedProfile {
  std::string name;
  Indenter ind;
};

std::vector<NamedProfile> profiles() {
  return {{"cone 10deg", Cone{10.0}},
          {"cone 45deg", Cone{45.0}},
          {"power n=1.5", Power{1.5, 1.0}},
          {"power n=3", Power{3.0, 1.0}},
          {"sphere a/R=0.5", Sphere{2.0 * kContact}}};
}

/// The history (w / v0, T / t_ref) at zeta0 on the profile and material.
Case profile_history(const Indenter& ind, const Rheology& r, bool load, double zeta0,
                     const Pairs& segs, long samples) {
  Case c;
  c.indenter = ind;
  c.rheology = r;
  if (load)
    c.loading.F0 = ind.elastic_force(kContact, r.G);
  else
    c.loading.d = ind.g(kContact);
  const double t_ref = r.longest_time();
  c.history.v0 = zeta0 * kContact / t_ref;
  for (const auto& [w, T] : segs)
    c.history.segments.push_back(Segment{w * c.history.v0, T * t_ref});
  c.sampling.samples = samples;
  return c;
}

} // namespace

std::vector<NamedCase> profile_case_set(long samples) {
  const Rheology kelvin = material(1.0, 1.0, {});
  const Rheology sls = material(1.0, 0.0, {{9.0, 1.0}});
  const Rheology dash = material(1.0, 0.3, {{2.0, 1.0}, {2.0, 0.05}});
  const Pairs three = {{0.1, 1.0}, {0.0, 2.0}, {1.0, 1.0}}; // drop, hold, reslide
  std::vector<NamedCase> out;
  for (const bool load : {false, true})
    for (const auto& [pname, ind] : profiles()) {
      const std::string at = (load ? "load " : "depth ") + pname + " ";
      auto add = [&](const std::string& name, const Rheology& r, double zeta0, const Pairs& segs) {
        out.push_back({at + name, profile_history(ind, r, load, zeta0, segs, samples)});
      };
      add("Kelvin step down 10x", kelvin, 0.3, {{0.1, 3.0}});
      add("Kelvin step up 10x", kelvin, 0.03, {{10.0, 2.0}});
      add("Kelvin drop-hold-reslide", kelvin, 0.3, three);
      add("SLS G0/G=10 drop-hold-reslide", sls, 0.3, three);
      if (ind.is<Cone>() && ind.as<Cone>().beta == 10.0) {
        // across v tau = a1: the rear face in contact at 0.3, free at 3
        add("Kelvin step down 10x across v tau = a", kelvin, 3.0, {{0.1, 3.0}});
        add("Kelvin step up 10x across v tau = a", kelvin, 0.3, {{10.0, 2.0}});
        add("Kelvin slide-hold-slide hold=10", kelvin, 3.0, {{0.0, 10.0}, {1.0, 2.0}});
        add("dashpot and two terms up 10x, back, down 10x", dash, 0.3,
            {{10.0, 1.0}, {1.0, 1.0}, {0.1, 1.0}});
      }
    }
  return out;
}

} // namespace mdrmap
