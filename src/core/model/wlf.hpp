#pragma once
// The WLF time-temperature shift (Williams, Landel, Ferry 1955):
//
//   log10 aT = -C1 (T - Tref) / (C2 + T - Tref),   defined for T > Tref - C2,
//
// the shift factor aT of the rheology (rheology.hpp) at temperature T.
// Shared by `mdrmap simulate` (--T TEMP --wlf C1:C2:TREF) and the studies (a
// `temperature` column with [run] wlf = C1:C2:TREF). Header only: the app and
// the study layers both take it, and the core's solvers never do (they see aT).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/model/case.hpp"

namespace mdrmap {

struct Wlf {
  double C1 = 0.0;   ///< > 0
  double C2 = 0.0;   ///< > 0, in the temperature's unit
  double Tref = 0.0; ///< reference temperature (aT = 1 there)
};

/// "C1:C2:TREF (log10 aT = ...), e.g. 17.44:51.6:-70, got 'GIVEN'": the form
/// a message about the WLF constants ends with.
inline std::string wlf_form(const std::string& given) {
  return "C1:C2:TREF (log10 aT = -C1 (T - TREF) / (C2 + T - TREF)), e.g. 17.44:51.6:-70, got '" +
         given + "'";
}

/// Constant i (0: C1, 1: C2, 2: TREF) of the WLF constants: finite, C1 and C2
/// > 0. `given` is the constants as the caller wrote them, for the message.
/// Throws InvalidInput(option).
inline void check_wlf_constant(const std::string& option, int i, double x,
                               const std::string& given) {
  const char* names[3] = {"C1", "C2", "TREF"};
  if (!std::isfinite(x))
    throw InvalidInput(option,
                       std::string(names[i]) + " must be a finite number; give " + wlf_form(given));
  if (i < 2 && !(x > 0.0))
    throw InvalidInput(option, std::string(names[i]) + " must be > 0; give " + wlf_form(given));
}

/// The WLF constants given as numbers C1, C2, TREF (`given` as above),
/// checked in order. Throws InvalidInput(option).
inline Wlf checked_wlf(const std::string& option, double C1, double C2, double Tref,
                       const std::string& given) {
  check_wlf_constant(option, 0, C1, given);
  check_wlf_constant(option, 1, C2, given);
  check_wlf_constant(option, 2, Tref, given);
  return Wlf{C1, C2, Tref};
}

/// "C1:C2:TREF", three finite numbers, C1 > 0 and C2 > 0. Throws
/// InvalidInput(option) saying which of the three is wrong.
inline Wlf parse_wlf(const std::string& option, const std::string& text) {
  double x[3] = {0.0, 0.0, 0.0};
  const char* names[3] = {"C1", "C2", "TREF"};
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t colon = text.find(':', start);
    if ((i < 2) == (colon == std::string::npos))
      throw InvalidInput(option, "must be " + wlf_form(text));
    const std::string part = text.substr(start, i < 2 ? colon - start : std::string::npos);
    char* end = nullptr;
    errno = 0;
    x[i] = std::strtod(part.c_str(), &end);
    if (part.empty() || std::strchr(" \t\n\r\f\v", part.front()) != nullptr || *end != '\0')
      throw InvalidInput(option,
                         std::string(names[i]) + " is not a number; give " + wlf_form(text));
    check_wlf_constant(option, i, x[i], text);
    start = colon + 1;
  }
  return Wlf{x[0], x[1], x[2]};
}

/// "C1:C2:TREF" with 17 significant digits.
inline std::string format_wlf(const Wlf& w) {
  return format_number(w.C1) + ":" + format_number(w.C2) + ":" + format_number(w.Tref);
}

/// aT at temperature T. Throws InvalidInput(option) unless T is finite and
/// above TREF - C2 and aT is a finite double > 0.
inline double wlf_shift(const Wlf& w, double T, const std::string& option) {
  const std::string lowest = format_number(w.Tref - w.C2);
  if (!std::isfinite(T))
    throw InvalidInput(option, "must be a finite number > TREF - C2 = " + lowest + ", got " +
                                   format_number(T));
  const double dT = T - w.Tref;
  if (!std::isfinite(dT) || !(w.C2 + dT > 0.0))
    throw InvalidInput(option, "must be > TREF - C2 = " + lowest +
                                   " (where the WLF shift is defined), got " + format_number(T));
  const double log10_aT = -w.C1 * dT / (w.C2 + dT);
  const double aT = std::pow(10.0, log10_aT);
  if (!std::isfinite(aT) || !(aT > 0.0))
    throw InvalidInput(option, format_number(T) + " gives aT = 10^" + format_number(log10_aT) +
                                   ", beyond the range of a double; the WLF shift is " +
                                   "representable for log10 aT in about (-307, 308)");
  return aT;
}

} // namespace mdrmap
