#include "core/model/row_limits.hpp"

#include <string>

namespace mdrmap {
namespace {

constexpr double kMinSquare = 1e-280, kMaxSquare = 1e300; // w^2, c w^2
constexpr double kMinTime = 1e-150, kMaxTime = 1e150;     // aT tau_k, aT tau
constexpr double kMinModulusRatio = 1e-12;                // G_k / G0 without a dashpot
constexpr double kMinCoefficient = 1e-100, kMaxCoefficient = 1e100;

bool within(double x, double lo, double hi) {
  return x >= lo && x <= hi; // (false for NaN)
}

/// A shifted time out of range: blamed on aT where it shifts, else on `own`.
void check_time(double tau, double aT, const std::string& own, const std::string& what) {
  const double shifted = aT * tau;
  if (within(shifted, kMinTime, kMaxTime)) return;
  const std::string range = " outside [1e-150, 1e150], the range of the element row's times";
  if (aT != 1.0)
    throw InvalidInput("aT", "times " + what + " = " + format_number(tau) +
                                 " gives a shifted time " + format_number(shifted) + range +
                                 "; rescale the units");
  throw InvalidInput(own,
                     what + " = " + format_number(tau) + " is" + range + "; rescale the units");
}

/// w^2 and c w^2 of a velocity w > 0 in range ("" if they are).
std::string velocity_problem(double w, double c) {
  const double w2 = w * w, cw2 = c * w2;
  if (within(w2, kMinSquare, kMaxSquare) && within(cw2, kMinSquare, kMaxSquare)) return "";
  return "= " + format_number(w) + " gives w^2 = " + format_number(w2) +
         " and c w^2 = " + format_number(cw2) + " (c = " + format_number(c) +
         ", the profile's coefficient); the element row (row, baseline, and auto for a spectrum or a profile other "
         "than the parabola) needs both within [1e-280, 1e300]; rescale the units";
}

} // namespace

bool uses_element_row(const Case& c) {
  return !c.rheology.kelvin() || !c.indenter.parabolic();
}

void check_spectrum_limits(const Rheology& r) {
  const double G0 = r.G0();
  for (std::size_t k = 0; k < r.branches.size(); ++k) {
    const std::string i = std::to_string(k + 1);
    const Branch& b = r.branches[k];
    check_time(b.tau, r.aT, "prony", "tau" + i);
    if (r.tau == 0.0 && !(b.G >= kMinModulusRatio * G0))
      throw InvalidInput("prony",
                         "term " + i + ": G" + i + " = " + format_number(b.G) +
                             " is below 1e-12 of the glassy modulus G0 = " + format_number(G0) +
                             "; without a dashpot (tau = 0) the element row's modes "
                             "cannot resolve it: drop the term or give tau > 0");
  }
  if (r.tau > 0.0) check_time(r.tau, r.aT, "tau", "tau");
}

void check_profile_limits(const Indenter& i) {
  i.visit([](const auto& s) {
    if (!s.coefficient_option) return; // (checked through the scales)
    const double c = s.image().coefficient();
    if (within(c, kMinCoefficient, kMaxCoefficient)) return;
    throw InvalidInput(s.coefficient_option,
                       std::string("gives the profile's coefficient c = ") + s.coefficient_words +
                           format_number(c) +
                           ", outside [1e-100, 1e100] where the contact's lengths stay "
                           "representable; rescale the units");
  });
}

void check_element_row(const Case& c) {
  check_spectrum_limits(c.rheology); // (the dashpot's time also for the Kelvin element)
  const double coef = c.indenter.coefficient();
  if (const std::string p = velocity_problem(c.history.v0, coef); !p.empty())
    throw InvalidInput("v", "v0 " + p);
  const std::vector<Segment>& s = c.history.segments;
  for (std::size_t k = 0; k < s.size(); ++k)
    if (s[k].w > 0.0)
      if (const std::string p = velocity_problem(s[k].w, coef); !p.empty())
        throw InvalidInput("history", "segment " + std::to_string(k + 1) + ": W " + p);
}

} // namespace mdrmap
