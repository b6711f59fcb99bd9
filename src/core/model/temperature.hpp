#pragma once
// Temperatures with their units (issue 33): --T 25C, --T 298.15K, --wlf
// C1:C2:TREF with TREF's unit (8.86:101.6:25C). A bare number keeps its old
// meaning, the unit of the other (or none). A Celsius temperature with a
// Kelvin TREF (or the reverse) is converted to TREF's unit; C2 is a
// difference, the same in both. The shift is refused where it is more than
// kMaxShiftDecades from 1 unless allowed (--allow-large-shift): a unit
// mistake gives shifts of many decades.
#include <string>

#include "core/model/wlf.hpp"

namespace mdrmap {

inline constexpr double kMaxShiftDecades = 12.0; ///< |log10 aT| beyond: refused unless allowed
/// A pair T, TREF of which one is a bare number reads as a Kelvin/Celsius
/// mix-up when they are more than kScaleMixDegrees apart and less than
/// kScaleNearDegrees apart once 273.15 is added to or taken from T - TREF.
inline constexpr double kScaleMixDegrees = 150.0;
inline constexpr double kScaleNearDegrees = 100.0;

enum class TempUnit { None, Celsius, Kelvin };

/// The unit letter ending `text` (C or K after a digit or a point), removed
/// from it; None (and `text` unchanged) without one.
TempUnit take_unit(std::string& text);

/// "" , "C" or "K".
const char* unit_suffix(TempUnit u);

/// A temperature "25", "25C" or "298.15K": finite, not below absolute zero.
/// Throws InvalidInput(option).
struct Temperature {
  double value = 0.0;
  TempUnit unit = TempUnit::None;
};
Temperature parse_temperature(const std::string& option, const std::string& text);

/// "C1:C2:TREF" with an optional unit after TREF. Throws InvalidInput(option).
struct UnitWlf {
  Wlf wlf;
  TempUnit unit = TempUnit::None;
};
UnitWlf parse_unit_wlf(const std::string& option, const std::string& text);

/// T in the unit of `w`'s TREF (a bare one in the other's), and that unit.
Temperature in_wlf_unit(const Temperature& T, const UnitWlf& w);

/// Refuses, naming `option`, a pair T, TREF with a bare number that reads as
/// the other scale (|T - TREF| > kScaleMixDegrees while |T - TREF -+ 273.15|
/// < kScaleNearDegrees): `--T 308.15 --wlf 8.86:101.6:25C` is 35C read as
/// 308.15C, a shift the 12-decade rule misses. Both with units: nothing to check.
void check_scales(const UnitWlf& w, const Temperature& T, const std::string& option);

/// aT at T (in TREF's unit) by check_scales and wlf_shift, refused naming `option` when
/// |log10 aT| > kMaxShiftDecades and not `allow_large`; `allow` says how to
/// allow it (--allow-large-shift, [run] allow_large_shift = true).
double checked_shift(const UnitWlf& w, const Temperature& T, const std::string& option,
                     bool allow_large, const std::string& allow = "--allow-large-shift");

/// "true" (or "True", "1", "": the flag given) or "false" ("False", "0").
/// Throws InvalidInput(option).
bool parse_flag(const std::string& option, const std::string& text);

} // namespace mdrmap
