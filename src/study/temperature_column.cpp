#include "study/temperature_column.hpp"

#include "study/config_detail.hpp"
#include "study/ini.hpp"

namespace mdrmap::study::detail {

namespace {

/// The temperature `item` (as written) without its unit letter; its unit
/// joins `unit` (that of `first`, the first item; set by it) or is refused as another one.
std::string one_temperature(const std::string& option, const std::string& item, TempUnit& unit,
                            std::string& first) {
  const std::size_t e = item.find_last_not_of(" \t");
  std::string t = trim(item);
  if (t.empty()) return item; // the axis's reader says what an empty item is
  const TempUnit u = take_unit(t);
  if (first.empty()) unit = u, first = trim(item);
  if (u != unit)
    throw ConfigError(option, "temperature takes one unit for all its values, C or K (or none: "
                              "TREF's), got " +
                                  first + " and " + trim(item));
  if (u == TempUnit::None) return item;
  try {
    parse_temperature(option, trim(item));
  } catch (const InvalidInput& err) {
    throw ConfigError(option, std::string("temperature ") + err.what());
  }
  return item.substr(0, e) + item.substr(e + 1);
}

} // namespace

std::string without_temperature_units(const std::string& option, const std::string& spec,
                                      TempUnit& unit) {
  unit = TempUnit::None;
  const bool spaced = starts_with(spec, "linspace:") || starts_with(spec, "logspace:");
  const char sep = spaced ? ':' : ',';
  std::string out, first;
  std::size_t start = 0;
  for (std::size_t i = 0;; ++i) {
    const std::size_t end = spec.find(sep, start);
    const std::string item = spec.substr(start, end == std::string::npos ? end : end - start);
    const bool temperature = !spaced || i == 1 || i == 2; // lo and hi of a spaced form
    out += temperature ? one_temperature(option, item, unit, first) : item;
    if (end == std::string::npos) return out;
    out += sep;
    start = end + 1;
  }
}

TempUnit listed_temperature_unit(const StudyConfig& c, const std::string& option,
                                 const std::string& here, std::string& cell) {
  const std::string as_written = cell;
  const TempUnit u = take_unit(cell);
  if (u == TempUnit::None) return u;
  if (!c.run.wlf || c.run.wlf_unit == TempUnit::None)
    throw ConfigError(option, here + "temperature " + as_written +
                                  " has a unit and TREF none: give TREF its unit ([run] wlf = "
                                  "C1:C2:TREF with C or K), or the temperatures bare (in TREF's "
                                  "unit)");
  try {
    parse_temperature(option, as_written);
  } catch (const InvalidInput& e) {
    throw ConfigError(option, here + "temperature " + e.what());
  }
  return u;
}

double listed_in_wlf_unit(const StudyConfig& c, double x, TempUnit unit) {
  return in_wlf_unit(Temperature{x, unit}, UnitWlf{*c.run.wlf, c.run.wlf_unit}).value;
}

void temperatures_in_wlf_unit(StudyConfig& c) {
  if (!c.run.wlf || c.run.wlf_unit == TempUnit::None) return;
  const UnitWlf w{*c.run.wlf, c.run.wlf_unit};
  for (Axis& a : c.axes) {
    if (a.column.kind != Column::Kind::Temperature || a.unit == TempUnit::None ||
        a.unit == c.run.wlf_unit)
      continue;
    for (double& x : a.values)
      x = in_wlf_unit(Temperature{x, a.unit}, w).value;
    a.unit = c.run.wlf_unit;
  }
}

} // namespace mdrmap::study::detail
