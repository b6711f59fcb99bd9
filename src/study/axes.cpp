#include "study/axes.hpp"

#include <algorithm>
#include <cmath>

#include "study/columns.hpp"
#include "study/config_detail.hpp"
#include "study/ini.hpp"
#include "study/temperature_column.hpp"

namespace mdrmap::study::detail {
namespace {

constexpr double kMaxGridCases = 1e9;
constexpr long long kMaxAxisValues = 10'000'000;

const char* const kAxisForms = "a number, a comma list, linspace:lo:hi:n or logspace:lo:hi:n";

void fill_linspace(std::vector<double>& v, double lo, double hi, long long n) {
  v.resize(static_cast<std::size_t>(n));
  const double diff = hi - lo;
  for (long long i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    v[static_cast<std::size_t>(i)] = std::isfinite(diff) ? lo + diff * t : lo * (1.0 - t) + hi * t;
  }
  v.front() = lo;
  v.back() = hi;
}

void fill_logspace(std::vector<double>& v, double lo, double hi, long long n) {
  v.resize(static_cast<std::size_t>(n));
  const double ratio = hi / lo;
  const bool plain = std::isfinite(ratio) && ratio > 0.0;
  const double llo = std::log(lo), lhi = std::log(hi);
  for (long long i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    v[static_cast<std::size_t>(i)] =
        plain ? lo * std::pow(ratio, t) : std::exp(llo * (1.0 - t) + lhi * t);
  }
  v.front() = lo;
  v.back() = hi;
}

/// Fills a from its spec linspace:lo:hi:n or logspace:lo:hi:n.
void parse_spaced(Axis& a, const std::string& option) {
  const std::string& spec = a.spec;
  const bool lin = starts_with(spec, "linspace:");
  const std::string form = lin ? "linspace:lo:hi:n" : "logspace:lo:hi:n";
  const std::string form_rule = "; write " + form +
                                " with numbers lo, hi and an integer n from 1 to " +
                                std::to_string(kMaxAxisValues);
  const auto parts = split(spec, ':');
  if (parts.size() != 4)
    throw ConfigError(option, shown(spec) + " has " + std::to_string(parts.size() - 1) +
                                  " fields after '" + parts[0] + ":', not 3" + form_rule);
  const std::string lo_text = trim(parts[1]), hi_text = trim(parts[2]), n_text = trim(parts[3]);
  const Num lo = to_number(lo_text), hi = to_number(hi_text);
  if (lo.err != NumError::None)
    throw ConfigError(option, "lo: " + number_problem(lo_text, lo.err) + form_rule);
  if (hi.err != NumError::None)
    throw ConfigError(option, "hi: " + number_problem(hi_text, hi.err) + form_rule);
  long long n = 0;
  if (!to_integer(n_text, n))
    throw ConfigError(option, "n: " + shown(n_text) + " is not an integer" + form_rule);
  if (n < 1 || n > kMaxAxisValues)
    throw ConfigError(option, "n = " + digits_shown(n_text) + " is out of range" + form_rule);
  if (n == 1 && lo.x != hi.x)
    throw ConfigError(option, "n = 1 needs lo == hi, got lo = " + format_number(lo.x) +
                                  " and hi = " + format_number(hi.x) +
                                  "; use n >= 2 or a single number");
  if (!lin && !(lo.x > 0.0 && hi.x > 0.0))
    throw ConfigError(option, "logspace needs lo > 0 and hi > 0, got lo = " + format_number(lo.x) +
                                  " and hi = " + format_number(hi.x) +
                                  "; use linspace or a list for values that include 0");
  if (lin)
    fill_linspace(a.values, lo.x, hi.x, n);
  else
    fill_logspace(a.values, lo.x, hi.x, n);
  a.logarithmic = !lin;
}

/// Fills a from its spec: a number or a comma list. `allowed` is the range rule.
void parse_list(Axis& a, const std::string& option, const std::string& allowed) {
  const std::string& spec = a.spec;
  if (spec.find(':') != std::string::npos)
    throw ConfigError(option, shown(spec) + " is not " + kAxisForms);
  const auto items = split(spec, ',');
  if (static_cast<long long>(items.size()) > kMaxAxisValues)
    throw ConfigError(option, "the list has " + std::to_string(items.size()) +
                                  " values; an axis takes at most " +
                                  std::to_string(kMaxAxisValues));
  a.values.reserve(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string item = trim(items[i]);
    const std::string which = items.size() > 1 ? "value " + std::to_string(i + 1) + " of " +
                                                     std::to_string(items.size()) + ": "
                                               : "";
    if (item.empty())
      throw ConfigError(option, which + "empty item in " + shown(spec) +
                                    "; separate numbers by single commas");
    const Num x = to_number(item);
    if (x.err != NumError::None)
      throw ConfigError(option, which + number_problem(item, x.err) + "; " + allowed);
    a.values.push_back(x.x);
  }
}

/// Checks every value of a against its column's range.
void check_range(const Axis& a, const std::string& option, const ParamSpec& spec) {
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    try {
      spec.check(a.values[i]);
    } catch (const InvalidInput& e) {
      throw ConfigError(option, a.name + " " + e.what() +
                                    (a.values.size() > 1 ? " (value " + std::to_string(i + 1) +
                                                               " of " + shown(a.spec) + ")"
                                                         : std::string()));
    }
  }
}

} // namespace

double grid_size(const StudyConfig& c) {
  double n = 1.0;
  for (const auto& a : c.axes)
    n *= static_cast<double>(a.values.size());
  return n;
}

void check_grid_size(const StudyConfig& c) {
  const double n = grid_size(c);
  if (n > kMaxGridCases)
    throw ConfigError("config", "the grid has " + format_number(n) + " cases (" + grid_shape(c) +
                                    "), more than 1e9; use fewer axis values");
}

std::vector<double> extremes(const std::vector<double>& v) {
  double lo = v.front(), hi = v.front(), pos = 0.0;
  for (const double x : v) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    if (x > 0.0 && (pos == 0.0 || x < pos)) pos = x;
  }
  std::vector<double> out = {lo};
  if (hi != lo) out.push_back(hi);
  if (pos != 0.0 && pos != lo && pos != hi) out.push_back(pos);
  return out;
}

} // namespace mdrmap::study::detail

namespace mdrmap::study {

using namespace detail;

Axis parse_axis(const std::string& section, const std::string& name, const std::string& spec_text) {
  const std::string option = section + "." + name;
  Axis a;
  if (!parse_column(name, a.column))
    throw ConfigError(option, "unknown column " + shown(name) +
                                  "; the columns are d or F0, R, tau, G, v, optionally a "
                                  "spectrum's Gk, tauk (k = 1..32) and aT or temperature, and "
                                  "the history's wK, wK_over_v, TK, TK_over_tau");
  a.name = name;
  a.section = section;
  a.spec = trim(spec_text);
  const ParamSpec& range = column_spec(a.column);
  const std::string allowed = name + " must be " + range.allowed();
  if (a.spec.empty()) throw ConfigError(option, name + " is empty; give " + kAxisForms);
  const std::string as_written = a.spec;
  if (a.column.kind == Column::Kind::Temperature) // 25C, 40C: the unit apart
    a.spec = without_temperature_units(option, a.spec, a.unit);
  if (starts_with(a.spec, "linspace:") || starts_with(a.spec, "logspace:"))
    parse_spaced(a, option);
  else
    parse_list(a, option, allowed);
  a.spec = as_written;
  check_range(a, option, range);
  return a;
}

} // namespace mdrmap::study
