#include "case/stationary_input.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "case/text.hpp"
#include "core/metrics/stationary.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "core/solvers/checked_case.hpp"

namespace mdrmap::cases {

std::string velocity_count_text() {
  return "at most " + std::to_string(kMaxVelocities) + " velocities";
}

namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> items;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = text.find(sep, start);
    items.push_back(text.substr(start, at == std::string::npos ? at : at - start));
    if (at == std::string::npos) return items;
    start = at + 1;
  }
}

/// A velocity of --v-list or --v-range (`what` names it): the whole text a
/// number in the range of the table's v.
double velocity(const std::string& option, const std::string& what, const std::string& text) {
  const ParamSpec& v = *find_parameter("v");
  const std::string t = trimmed(text);
  char* end = nullptr;
  const double x = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !v.contains(x))
    throw InvalidInput(option, what + " must be a velocity (" + dim_name(v.dim) + "), " +
                                   v.allowed() + ", got " + shown(text));
  return x;
}

/// --v-list as numbers: each in the range of the table's v.
std::vector<double> velocity_numbers(const std::vector<double>& x) {
  if (x.size() > static_cast<std::size_t>(kMaxVelocities))
    throw InvalidInput("v-list", "has " + std::to_string(x.size()) + " items; " +
                                     velocity_count_text() + " are allowed");
  const ParamSpec& v = *find_parameter("v");
  for (std::size_t k = 0; k < x.size(); ++k)
    if (!v.contains(x[k]))
      throw InvalidInput("v-list", "item " + std::to_string(k + 1) + " must be a velocity (" +
                                       dim_name(v.dim) + "), " + v.allowed() + ", got " +
                                       shortest(x[k]));
  if (x.empty()) throw InvalidInput("v-list", "must be one or more velocities, got none");
  return x;
}

/// --v-list V1,V2,...: the velocities in the order given.
std::vector<double> velocity_list(const std::string& text) {
  const std::vector<std::string> items = split(text, ',');
  if (items.size() > static_cast<std::size_t>(kMaxVelocities))
    throw InvalidInput("v-list", "has " + std::to_string(items.size()) + " items; " +
                                     velocity_count_text() + " are allowed");
  std::vector<double> out;
  for (std::size_t k = 0; k < items.size(); ++k)
    out.push_back(velocity("v-list", "item " + std::to_string(k + 1), items[k]));
  return out;
}

/// N of --v-range: an integer from 2 to kMaxVelocities.
long range_count(const std::string& text) {
  const std::string t = trimmed(text);
  const bool digits = !t.empty() && t.size() <= 9 &&
                      std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
  const long n = digits ? std::strtol(t.c_str(), nullptr, 10) : 0;
  if (n < 2 || n > kMaxVelocities)
    throw InvalidInput("v-range", "N (LO:HI:N) must be an integer from 2 to " +
                                      std::to_string(kMaxVelocities) + ", got " + shown(text));
  return n;
}

/// --v-range LO:HI:N: N velocities from LO to HI, equally spaced in log v,
/// the ends exactly LO and HI.
std::vector<double> velocity_range(const std::string& text) {
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() != 3)
    throw InvalidInput("v-range", "must be LO:HI:N, N velocities log-spaced from LO to HI "
                                  "(0 < LO < HI, N >= 2), got " +
                                      shown(text));
  const double lo = velocity("v-range", "LO", parts[0]);
  const double hi = velocity("v-range", "HI", parts[1]);
  if (!(lo < hi))
    throw InvalidInput("v-range", "LO must be below HI (LO:HI:N), got LO = " + format_number(lo) +
                                      ", HI = " + format_number(hi));
  const long n = range_count(parts[2]);
  std::vector<double> v(static_cast<std::size_t>(n));
  // in decades: whole decades (1e-3:1e3:7) come out as the powers of ten
  const double l0 = std::log10(lo), span = std::log10(hi) - l0;
  for (long j = 0; j < n; ++j)
    v[static_cast<std::size_t>(j)] =
        std::pow(10.0, l0 + span * static_cast<double>(j) / static_cast<double>(n - 1));
  v.front() = lo;
  v.back() = hi;
  return v;
}

/// Which of --v, --v-list, --v-range gives the velocities: exactly one.
std::string velocity_option(const OptionValues& texts) {
  std::string given, first;
  for (const char* o : {"v", "v-list", "v-range"}) {
    if (!texts.count(o)) continue;
    given += (given.empty() ? "--" : " and --") + std::string(o);
    if (first.empty()) first = o;
  }
  if (!given.empty() && given.find(" and ") == std::string::npos) return first;
  throw InvalidInput("", "give exactly one of --v V, --v-list V1,V2,... or --v-range LO:HI:N (the "
                         "velocities of the stationary states, length/time); got " +
                             (given.empty() ? std::string("none") : given));
}

/// The case from its option texts, as simulate reads it, with a history of
/// one segment at the case's velocity (its first checks of a velocity blame
/// `vopt`).
CaseInput read_stationary_case(OptionValues texts, const std::string& vopt) {
  const OptionValue& v = texts["v"];
  if (v.is_text())
    texts["history"] = OptionValue::of_text(v.text + ":1");
  else if (v.kind == OptionValue::Kind::Number)
    texts["history"] = OptionValue::of_pairs({{v.number, 1.0}});
  else
    throw InvalidInput(vopt, "must be a velocity, got " + shown(v));
  try {
    return read_case_input(texts);
  } catch (const InvalidInput& e) {
    if (e.option() == "history" || (e.option() == "v" && vopt != "v"))
      throw InvalidInput(vopt, e.what());
    throw;
  }
}

/// The case's checks of a velocity (validate: w tau / a and the stationary
/// contact representable) at w; a problem blames `vopt`.
void check_velocity(const Case& base, double w, const std::string& vopt) {
  Case c = base;
  c.history.v0 = w;
  c.history.segments = {Segment{w, 1.0}};
  try {
    validate(c);
  } catch (const InvalidInput& e) {
    const std::string who = e.option().empty() ? "" : "--" + e.option() + " ";
    throw InvalidInput(vopt, "at v = " + format_number(w) + ": " + who + e.what());
  }
}
} // namespace

StationaryInput read_stationary_input(const OptionTexts& texts) {
  return read_stationary_input(as_values(texts));
}

StationaryInput read_stationary_input(OptionValues texts) {
  StationaryInput a;
  a.velocity_option = velocity_option(texts);
  if (a.velocity_option == "v-list") {
    const OptionValue& list = texts["v-list"];
    if (list.kind == OptionValue::Kind::Numbers)
      a.velocities = velocity_numbers(list.numbers);
    else if (list.is_text())
      a.velocities = velocity_list(list.text);
    else
      throw InvalidInput("v-list", "must be a list of velocities, got " + shown(list));
  }
  if (a.velocity_option == "v-range") {
    if (!texts["v-range"].is_text())
      throw InvalidInput("v-range", "must be LO:HI:N, got " + shown(texts["v-range"]));
    a.velocities = velocity_range(texts["v-range"].text);
  }
  texts.erase("v-list");
  texts.erase("v-range");
  if (!a.velocities.empty()) // the slowest: the case's own checks at v the mildest
    texts["v"] =
        OptionValue::of_number(*std::min_element(a.velocities.begin(), a.velocities.end()));
  a.in = read_stationary_case(texts, a.velocity_option);
  if (a.velocities.empty()) a.velocities = {a.in.c.history.v0};
  for (const double w : a.velocities)
    check_velocity(a.in.c, w, a.velocity_option);
  return a;
}

std::vector<State> stationary_states(const StationaryInput& a, const RunControl& control) {
  std::vector<State> states;
  states.reserve(a.velocities.size());
  for (const double w : a.velocities) {
    control.charge(1.0, "stationary");
    states.push_back(stationary_state(a.in.c, w));
    control.report(states.size(), a.velocities.size());
  }
  return states;
}

} // namespace mdrmap::cases
