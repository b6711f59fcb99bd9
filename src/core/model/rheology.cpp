#include "core/model/rheology.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "core/model/row_limits.hpp"

namespace mdrmap {

double Rheology::G0() const {
  double g = G;
  for (const Branch& b : branches)
    g += b.G;
  return g;
}

double Rheology::longest_time() const {
  double t = tau;
  for (const Branch& b : branches)
    t = std::max(t, b.tau);
  return aT * t;
}

Rheology Rheology::shifted() const {
  Rheology r = *this;
  r.tau *= aT;
  for (Branch& b : r.branches)
    b.tau *= aT;
  r.aT = 1.0;
  return r;
}

double Rheology::relaxation_modulus(double t) const {
  double g = G;
  for (const Branch& b : branches)
    g += b.G * std::exp(-t / (aT * b.tau));
  return g;
}

void validate(const Rheology& r) {
  if (r.branches.size() > kMaxBranches)
    throw InvalidInput("prony", "has " + std::to_string(r.branches.size()) + " terms; at most " +
                                    std::to_string(kMaxBranches) + " are allowed");
  for (std::size_t k = 0; k < r.branches.size(); ++k) {
    const std::string i = std::to_string(k + 1);
    const ParamSpec &g = branch_modulus_spec(), &t = branch_time_spec();
    if (!g.contains(r.branches[k].G))
      throw InvalidInput(g.name + i,
                         "must be " + g.allowed() + ", got " + format_number(r.branches[k].G));
    if (!t.contains(r.branches[k].tau))
      throw InvalidInput(t.name + i,
                         "must be " + t.allowed() + ", got " + format_number(r.branches[k].tau));
    const double shifted = r.aT * r.branches[k].tau;
    if (!std::isfinite(shifted) || !(shifted >= 1e-300))
      throw InvalidInput("aT", "times tau" + i + " = " + format_number(r.branches[k].tau) + " is " +
                                   format_number(shifted) +
                                   "; a shifted time must be finite and at least 1e-300");
  }
  if (!std::isfinite(r.aT * r.tau))
    throw InvalidInput("aT", "times tau = " + format_number(r.tau) +
                                 " overflows; a shifted time must be finite");
  if (!std::isfinite(r.G0()))
    throw InvalidInput("prony", "gives a glassy modulus G + sum Gk that overflows");
  if (!r.branches.empty()) check_spectrum_limits(r); // a spectrum: the element row solves it
}

} // namespace mdrmap
