#include "core/model/temperature.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace mdrmap {
namespace {

constexpr double kZeroCelsius = 273.15; ///< 0 C in K

/// The text quoted, cut to 60 characters.
std::string shown(const std::string& text) {
  return "'" + (text.size() > 60 ? text.substr(0, 60) + "...'" : text + "'");
}

/// Refuses a temperature below absolute zero in its unit.
void check_absolute(const std::string& option, const std::string& what, double x, TempUnit u) {
  if (u == TempUnit::Kelvin && x < 0.0)
    throw InvalidInput(option,
                       what + " must be >= 0K (absolute zero), got " + format_number(x) + "K");
  if (u == TempUnit::Celsius && x < -kZeroCelsius)
    throw InvalidInput(option, what + " must be >= -273.15C (absolute zero), got " +
                                   format_number(x) + "C");
}

/// A difference of temperatures with 6 significant digits (283.15, not 283.14999999999998).
std::string degrees(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

} // namespace

TempUnit take_unit(std::string& text) {
  if (text.size() < 2) return TempUnit::None;
  const char last = text.back(), before = text[text.size() - 2];
  if ((last != 'C' && last != 'K') ||
      !(std::isdigit(static_cast<unsigned char>(before)) || before == '.'))
    return TempUnit::None;
  text.pop_back();
  return last == 'C' ? TempUnit::Celsius : TempUnit::Kelvin;
}

const char* unit_suffix(TempUnit u) {
  return u == TempUnit::Celsius ? "C" : u == TempUnit::Kelvin ? "K" : "";
}

Temperature parse_temperature(const std::string& option, const std::string& text) {
  std::string t = text;
  const TempUnit unit = take_unit(t);
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0' || std::strchr(" \t\n\r\f\v", t.front()) != nullptr)
    throw InvalidInput(option, "must be a temperature, a number with an optional unit C or K "
                               "(25C, 298.15K; a bare number is in the unit of TREF), got " +
                                   shown(text));
  if (!std::isfinite(x))
    throw InvalidInput(option, "must be a finite temperature, got " + shown(text));
  check_absolute(option, "the temperature", x, unit);
  return Temperature{x, unit};
}

UnitWlf parse_unit_wlf(const std::string& option, const std::string& text) {
  std::string t = text;
  UnitWlf out;
  out.unit = take_unit(t);
  out.wlf = parse_wlf(option, t);
  check_absolute(option, "TREF", out.wlf.Tref, out.unit);
  return out;
}

Temperature in_wlf_unit(const Temperature& T, const UnitWlf& w) {
  if (T.unit == TempUnit::None || w.unit == TempUnit::None || T.unit == w.unit)
    return Temperature{T.value, T.unit == TempUnit::None ? w.unit : T.unit};
  return Temperature{w.unit == TempUnit::Kelvin ? T.value + kZeroCelsius : T.value - kZeroCelsius,
                     w.unit};
}

void check_scales(const UnitWlf& w, const Temperature& T, const std::string& option) {
  if (T.unit != TempUnit::None && w.unit != TempUnit::None) return; // converted exactly
  const double dT = T.value - w.wlf.Tref;
  const double other = std::fmin(std::fabs(dT - kZeroCelsius), std::fabs(dT + kZeroCelsius));
  if (!(std::fabs(dT) > kScaleMixDegrees && other < kScaleNearDegrees)) return;
  const std::string t = degrees(T.value), tref = degrees(w.wlf.Tref);
  const std::string apart = degrees(std::fabs(dT)) + " degrees apart, but " + degrees(other) +
                            " if one is in K and the other in C (a Kelvin/Celsius mix-up?); ";
  if (T.unit == TempUnit::None && w.unit == TempUnit::None)
    throw InvalidInput(option, "T = " + t + " and TREF = " + tref + " are bare numbers: " + apart +
                                   "give T and TREF their units (C or K; a bare TREF, as a "
                                   "card's, is read in T's)");
  const bool T_bare = T.unit == TempUnit::None;
  const TempUnit u = T_bare ? w.unit : T.unit;
  throw InvalidInput(option, (T_bare ? "T = " + t : "TREF = " + tref) +
                                 " is a bare number, read in " + unit_suffix(u) + " beside " +
                                 (T_bare ? "TREF = " + tref : "T = " + t) + unit_suffix(u) + ": " +
                                 apart + "give " + (T_bare ? "T" : "TREF") + " its unit (" +
                                 (T_bare ? t : tref) + "K or " + (T_bare ? t : tref) + "C)" +
                                 (T_bare ? "" : ", or T in TREF's scale (a card's TREF is bare)"));
}

double checked_shift(const UnitWlf& w, const Temperature& T, const std::string& option,
                     bool allow_large, const std::string& allow) {
  check_scales(w, T, option);
  const Temperature t = in_wlf_unit(T, w);
  const double aT = wlf_shift(w.wlf, t.value, option);
  const double decades = std::log10(aT);
  if (allow_large || std::fabs(decades) <= kMaxShiftDecades) return aT;
  throw InvalidInput(option, "T = " + format_number(t.value) + unit_suffix(t.unit) +
                                 " gives log10 aT = " + format_number(decades) + " (WLF " +
                                 format_wlf(w.wlf) + unit_suffix(w.unit) +
                                 "), more than 12 decades from 1: check the units of T and TREF "
                                 "(C or K), or allow it with " +
                                 allow);
}

bool parse_flag(const std::string& option, const std::string& text) {
  if (text.empty() || text == "true" || text == "True" || text == "1") return true;
  if (text == "false" || text == "False" || text == "0") return false;
  throw InvalidInput(option, "must be true or false (a flag), got " + shown(text));
}

} // namespace mdrmap
