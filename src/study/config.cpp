#include "study/config.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string_view>

#include "core/params.hpp"
#include "core/solver.hpp"

namespace mdrmap::study {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxGridCases = 1e9;
constexpr long kMaxRunSamples = 1'000'000;
constexpr long long kMaxAxisValues = 10'000'000;
constexpr double kMaxTimeseriesBytes = 64.0 * 1024.0 * 1024.0 * 1024.0;
constexpr std::size_t kMaxConfigBytes = std::size_t{16} * 1024 * 1024;

const std::vector<std::string>& sections() {
  static const std::vector<std::string> s = {"grid", "cases", "run"};
  return s;
}
const std::vector<std::string>& grid_keys() {
  static const std::vector<std::string> k = {"d", "R", "tau", "v", "v1", "v1_over_v"};
  return k;
}
const std::vector<std::string>& cases_keys() {
  static const std::vector<std::string> k = {"file"};
  return k;
}
const std::vector<std::string>& run_keys() {
  static const std::vector<std::string> k = {"t_end_over_tau", "samples",    "rtol",
                                             "solver",         "timeseries", "G"};
  return k;
}
const std::vector<std::string>& keys_of(const std::string& section) {
  if (section == "grid") return grid_keys();
  if (section == "cases") return cases_keys();
  return run_keys();
}
const std::vector<std::string>& override_keys() {
  static const std::vector<std::string> k = [] {
    std::vector<std::string> all;
    for (const auto& s : sections())
      for (const auto& key : keys_of(s))
        all.push_back(s + "." + key);
    return all;
  }();
  return k;
}

/// Grid axes in study order; the fifth is v1 or v1_over_v.
constexpr const char* kAxisOrder[4] = {"d", "R", "tau", "v"};
/// Columns of a case list, in StepRow field order.
constexpr const char* kColumns[5] = {"d", "R", "tau", "v", "v1"};

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string join(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) out += sep;
    out += v[i];
  }
  return out;
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && is_space(s[b]))
    ++b;
  while (e > b && is_space(s[e - 1]))
    --e;
  return std::string(s.substr(b, e - b));
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t p = s.find(sep, start);
    if (p == std::string::npos) {
      out.push_back(s.substr(start));
      return out;
    }
    out.push_back(s.substr(start, p - start));
    start = p + 1;
  }
}

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

/// User text quoted for a one-line message: control bytes escaped, long text cut.
std::string shown(std::string_view s, std::size_t max_chars = 60) {
  std::string out = "'";
  std::size_t n = 0;
  for (const char ch : s) {
    if (n == max_chars) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {
      static const char* const hex = "0123456789ABCDEF";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xf];
    } else {
      out += ch;
    }
    ++n;
  }
  return out + "'";
}

/// An integer's digits (already checked) for a message: long ones cut.
std::string digits_shown(const std::string& digits) {
  return digits.size() <= 30 ? digits : digits.substr(0, 30) + "...";
}

std::string shown_path(const std::string& p) {
  return shown(p, 4096);
}

char lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

std::string lower(std::string s) {
  for (char& c : s)
    c = lower(c);
  return s;
}

/// Edit distance in half units: a change of case costs 1, any other
/// substitution, insertion or deletion 2.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    prev[j] = 2 * j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = 2 * i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const char x = a[i - 1], y = b[j - 1];
      const std::size_t sub = x == y ? 0 : (lower(x) == lower(y) ? 1 : 2);
      cur[j] = std::min({prev[j] + 2, cur[j - 1] + 2, prev[j - 1] + sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

/// The candidate nearest to word, or "" when none is plausibly meant.
std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = static_cast<std::size_t>(-1);
  for (const auto& c : candidates) {
    const std::size_t dist = edit_distance(word, c);
    if (dist < best_d) {
      best_d = dist;
      best = c;
    }
  }
  if (best.empty()) return best;
  // Near enough: a few edits, and not a rewrite of the whole word ("G" is not "d").
  const std::size_t allowed = 2 * std::max<std::size_t>(2, best.size() / 3);
  if (best_d <= allowed && best_d < 2 * std::min(word.size(), best.size())) return best;
  // A known key that contains the word, or is contained in it ("end_over_tau", "run.samples").
  for (const auto& c : candidates)
    if (word.size() >= 2 &&
        (c.find(word) != std::string::npos || word.find(c) != std::string::npos) &&
        std::min(c.size(), word.size()) * 2 >= std::max(c.size(), word.size()))
      return c;
  return "";
}

/// Where a setting came from: "FILE:LINE: ", "FILE: " or "command line: ".
struct Where {
  std::string source;
  int line = 0;
  std::string prefix() const {
    return line > 0 ? source + ":" + std::to_string(line) + ": " : source + ": ";
  }
};

/// Adds the location to an error thrown without one.
[[noreturn]] void rethrow_at(const InvalidInput& e, const Where& w) {
  throw ConfigError(e.option(), w.prefix() + e.what());
}

// --- Numbers ------------------------------------------------------------

enum class NumError { None, Empty, NotNumber, NotFinite, TooLarge };

struct Num {
  double x = 0.0;
  NumError err = NumError::None;
};

/// Strict: the whole text is one decimal (or hex) floating-point number.
Num to_number(const std::string& s) {
  if (s.empty()) return {0.0, NumError::Empty};
  if (is_space(s.front())) return {0.0, NumError::NotNumber};
  const char* begin = s.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  const int err = errno;
  if (end == begin || end != begin + s.size()) return {0.0, NumError::NotNumber};
  if (std::isnan(x)) return {0.0, NumError::NotFinite};
  if (std::isinf(x)) return {0.0, err == ERANGE ? NumError::TooLarge : NumError::NotFinite};
  return {x == 0.0 ? 0.0 : x, NumError::None}; // -0 is 0
}

/// "'abc' is not a number" and the like.
std::string number_problem(const std::string& text, NumError e) {
  switch (e) {
  case NumError::Empty:
    return "the value is empty";
  case NumError::NotNumber:
    return shown(text) + " is not a number";
  case NumError::NotFinite:
    return shown(text) + " is not a finite number";
  case NumError::TooLarge:
    return shown(text) + " is too large for a double";
  case NumError::None:
    break;
  }
  return "";
}

/// Strict integer: optional sign and decimal digits; huge values clamp near 1e18.
bool to_integer(const std::string& s, long long& out) {
  std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  if (i >= s.size()) return false;
  const bool negative = s[0] == '-';
  long long v = 0;
  for (; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    if (v < 100'000'000'000'000'000LL) v = v * 10 + (s[i] - '0');
  }
  out = negative ? -v : v;
  return true;
}

// --- Axes -----------------------------------------------------------------

bool allows_zero(const std::string& axis) {
  return axis == "tau" || axis == "v1" || axis == "v1_over_v";
}

std::string range_text(const std::string& axis) {
  return allows_zero(axis) ? "a finite number >= 0" : "a finite number > 0";
}

bool in_range(const std::string& axis, double x) {
  return std::isfinite(x) && (allows_zero(axis) ? x >= 0.0 : x > 0.0);
}

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

// --- Cases ------------------------------------------------------------------

std::string describe(const StepRow& s) {
  return "d = " + format_number(s.d) + ", R = " + format_number(s.R) +
         ", tau = " + format_number(s.tau) + ", v = " + format_number(s.v) +
         ", v1 = " + format_number(s.v1);
}

/// The table's specs of a row's fields, looked up once (rows are checked by
/// the million).
struct RowSpecs {
  const ParamSpec &d, &R, &tau, &v, &v1, &G, &t_end, &samples;
};
const RowSpecs& row_specs() {
  static const RowSpecs s{*find_parameter("d"),    *find_parameter("R"),
                          *find_parameter("tau"),  *find_parameter("v"),
                          segment_velocity_spec(), *find_parameter("G"),
                          segment_duration_spec(), *find_parameter("samples")};
  return s;
}

/// Checks `x` against a parameter spec, blaming `option` (a row field or the
/// seed's t-end) instead of the spec's own name.
void check_as(const char* option, const ParamSpec& spec, double x) {
  try {
    spec.check(x);
  } catch (const InvalidInput& e) {
    throw InvalidInput(option, e.what());
  }
}

/// Checks a valid row's sampling as the seed's protocol was checked: the
/// window (as "t-end"), then the samples. Returns the window.
double check_sampling(const StudyConfig& c, const StepRow& r) {
  const double T = step_duration(c, r);
  check_as("t-end", row_specs().t_end, T);
  check_as("samples", row_specs().samples, static_cast<double>(c.run.samples));
  return T;
}

/// Validates one case as the runner will run it, without building it. Throws
/// InvalidInput with the seed's option names (d, R, tau, v, v1, G, t-end, samples).
void validate_case(const StudyConfig& c, const StepRow& s) {
  validate_row(s);
  check_sampling(c, s);
}

/// The message for a failed case check, for whichever key gets the blame.
std::string case_problem(const InvalidInput& e, const StepRow& s, const std::string& v1_name) {
  const std::string& o = e.option();
  std::string what;
  if (o == "t-end") {
    what = s.tau > 0.0 ? "t_end = t_end_over_tau * tau " + std::string(e.what()) +
                             "; change t_end_over_tau or rescale the units"
                       : "with tau = 0 the default window 6 sqrt(R d) / min(v, v1) " +
                             std::string(e.what()) + "; rescale the units";
  } else if (o == "v1" && v1_name == "v1_over_v") {
    what = "v1 = v1_over_v * v " + std::string(e.what());
  } else {
    what = (o == "v1" ? v1_name : o) + " " + e.what();
  }
  return what + " (case " + describe(s) + ")";
}

/// Config key that answers for a core option, in a grid.
std::string grid_option(const std::string& core_option, const StepRow& s,
                        const std::string& v1_name) {
  if (core_option == "v1") return "grid." + v1_name;
  if (core_option == "G") return "run.G";
  if (core_option == "samples") return "run.samples";
  if (core_option == "t-end") return s.tau > 0.0 ? "run.t_end_over_tau" : "grid.tau";
  for (const char* a : kAxisOrder)
    if (core_option == a) return "grid." + core_option;
  return "config";
}

/// Checks that c.axes is d, R, tau, v, v1|v1_over_v, each non-empty.
void check_axes_shape(const StudyConfig& c) {
  const std::string want = "a grid needs the axes d, R, tau, v and v1 or v1_over_v, in this order";
  if (c.axes.size() != 5)
    throw ConfigError("config", "the grid has " + std::to_string(c.axes.size()) + " axes; " + want);
  for (std::size_t i = 0; i < 5; ++i) {
    const std::string& n = c.axes[i].name;
    const bool ok = i < 4 ? n == kAxisOrder[i] : (n == "v1" || n == "v1_over_v");
    if (!ok)
      throw ConfigError("config",
                        "axis " + std::to_string(i + 1) + " is " + shown(n) + "; " + want);
    if (c.axes[i].values.empty())
      throw ConfigError("grid." + n, "axis " + n + " has no values; give at least one");
  }
}

double grid_size(const StudyConfig& c) {
  double n = 1.0;
  for (const auto& a : c.axes)
    n *= static_cast<double>(a.values.size());
  return n;
}

std::string grid_shape(const StudyConfig& c) {
  std::string s;
  for (const auto& a : c.axes) {
    if (!s.empty()) s += " x ";
    s += a.name + " " + std::to_string(a.values.size());
  }
  return s;
}

/// Refuses grids over kMaxGridCases. Throws ConfigError("config") without location.
void check_grid_size(const StudyConfig& c) {
  const double n = grid_size(c);
  if (n > kMaxGridCases)
    throw ConfigError("config", "the grid has " + format_number(n) + " cases (" + grid_shape(c) +
                                    "), more than 1e9; use fewer axis values");
}

/// Refuses time series that would not fit in 64 GiB. Throws ConfigError("run.timeseries").
void check_timeseries_memory(const RunSettings& r, double cases) {
  if (!r.timeseries) return;
  const double bytes = static_cast<double>(r.samples) * cases * 5.0 * 8.0;
  if (bytes > kMaxTimeseriesBytes) {
    char gib[64];
    std::snprintf(gib, sizeof gib, "%.1f", bytes / (1024.0 * 1024.0 * 1024.0));
    throw ConfigError("run.timeseries",
                      "timeseries = true needs " + std::to_string(r.samples) + " samples x " +
                          format_number(cases) + " cases x 5 series x 8 bytes = " + gib +
                          " GiB, more than 64 GiB; lower samples, use fewer cases or set "
                          "timeseries = false");
  }
}

/// The smallest, largest and smallest positive value (the cases where the
/// core's checks, each monotone in each parameter, can fail first).
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

/// Calls f(row) for every combination of the five axis value lists, in C
/// order (last axis fastest); v1 is v1_over_v * v when `ratio`.
template <class F>
void for_each_combination(const std::vector<double>& D, const std::vector<double>& R,
                          const std::vector<double>& T, const std::vector<double>& V,
                          const std::vector<double>& V1, bool ratio, double G, F f) {
  for (const double d : D)
    for (const double r : R)
      for (const double tau : T)
        for (const double v : V)
          for (const double x : V1) {
            StepRow s;
            s.d = d;
            s.R = r;
            s.tau = tau;
            s.v = v;
            s.v1 = ratio ? x * v : x;
            s.G = G;
            f(s);
          }
}

/// Validates every case of a grid without expanding it: each axis value is in
/// range (parse_axis), and the combined checks of validate_row and the
/// window and samples checks are monotone in each parameter, so the corners of the
/// grid (smallest, largest, smallest positive value per axis) decide them.
template <class WhereFn> void check_grid_corners(const StudyConfig& c, const WhereFn& where) {
  const std::string& v1_name = c.axes[4].name;
  const bool ratio = v1_name == "v1_over_v";
  const auto D = extremes(c.axes[0].values), R = extremes(c.axes[1].values),
             T = extremes(c.axes[2].values), V = extremes(c.axes[3].values),
             V1 = extremes(c.axes[4].values);
  for_each_combination(D, R, T, V, V1, ratio, c.run.G, [&](const StepRow& s) {
    try {
      validate_case(c, s);
    } catch (const InvalidInput& e) {
      const std::string option = grid_option(e.option(), s, v1_name);
      throw ConfigError(option, where(option).prefix() + case_problem(e, s, v1_name));
    }
  });
}

/// Every check that involves more than one setting.
template <class WhereFn> void check_study(const StudyConfig& c, const WhereFn& where) {
  if (c.kind != StudyConfig::Kind::Grid) return; // case lists: checked when read
  try {
    check_axes_shape(c);
    check_grid_size(c);
    check_timeseries_memory(c.run, grid_size(c));
  } catch (const InvalidInput& e) {
    rethrow_at(e, where(e.option()));
  }
  check_grid_corners(c, where);
}

// --- [run] ------------------------------------------------------------------

double positive_number(const std::string& option, const std::string& key, const std::string& text) {
  const Num n = to_number(text);
  const std::string allowed = key + " must be a finite number > 0";
  if (n.err != NumError::None)
    throw ConfigError(option, number_problem(text, n.err) + "; " + allowed);
  if (!(n.x > 0.0)) throw ConfigError(option, allowed + ", got " + format_number(n.x));
  return n.x;
}

/// Sets one [run] key from its text. Throws ConfigError("run.<key>") without location.
void set_run_key(RunSettings& r, const std::string& key, const std::string& text) {
  const std::string option = "run." + key;
  if (key == "t_end_over_tau") {
    r.t_end_over_tau = positive_number(option, key, text);
  } else if (key == "G") {
    r.G = positive_number(option, key, text);
  } else if (key == "samples") {
    long long n = 0;
    const std::string allowed =
        "samples must be an integer from 2 to " + std::to_string(kMaxRunSamples);
    if (!to_integer(text, n))
      throw ConfigError(option, shown(text) + " is not an integer; " + allowed);
    if (n < 2 || n > kMaxRunSamples)
      throw ConfigError(option, allowed + ", got " + digits_shown(text));
    r.samples = static_cast<long>(n);
  } else if (key == "rtol") {
    const Num n = to_number(text);
    if (n.err != NumError::None)
      throw ConfigError(option,
                        number_problem(text, n.err) + "; rtol must be a number in (0, 0.1]");
    try {
      validate_rtol(n.x);
    } catch (const InvalidInput& e) {
      throw ConfigError(option, std::string("rtol ") + e.what());
    }
    r.rtol = n.x;
  } else if (key == "solver") {
    try {
      r.solver = solver_name(parse_solver(text));
    } catch (const InvalidInput&) {
      throw ConfigError(option, "unknown solver " + shown(text) +
                                    "; solver must be one of auto, exact, mdr, baseline");
    }
  } else if (key == "timeseries") {
    const std::string t = lower(text);
    if (t == "true" || t == "yes" || t == "1") {
      r.timeseries = true;
    } else if (t == "false" || t == "no" || t == "0") {
      r.timeseries = false;
    } else {
      throw ConfigError(option, shown(text) + " is not a yes/no value; timeseries must be true "
                                              "or false (also yes/no, 1/0)");
    }
  } else {
    throw ConfigError(option, "unknown key " + shown(key) + " in [run]");
  }
}

/// Resolves a [cases] file against the INI's directory and checks it can be read.
std::string resolve_cases_file(const std::string& file, const std::string& base_dir) {
  const fs::path p(file);
  const std::string resolved =
      (p.is_absolute() || base_dir.empty()) ? p.string() : (fs::path(base_dir) / p).string();
  std::error_code ec;
  if (fs::is_directory(resolved, ec))
    throw ConfigError("cases.file", "cannot read " + shown_path(resolved) + ": " +
                                        std::strerror(EISDIR) + "; file must name a CSV case list");
  std::FILE* f = std::fopen(resolved.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    throw ConfigError("cases.file", "cannot read " + shown_path(resolved) + ": " +
                                        std::strerror(err) + "; file must name a CSV case list");
  }
  std::fclose(f);
  return resolved;
}

std::string unknown_key_message(const std::string& section, const std::string& key) {
  for (const auto& other : sections())
    if (other != section && contains(keys_of(other), key))
      return "key " + shown(key) + " belongs in [" + other + "], not [" + section +
             "]; move it there";
  const std::string near = nearest(key, keys_of(section));
  if (!near.empty())
    return "unknown key " + shown(key) + " in [" + section + "]; did you mean '" + near + "'?";
  return "unknown key " + shown(key) + " in [" + section + "]; the keys of [" + section + "] are " +
         join(keys_of(section));
}

/// Strips a trailing comment: ';' or '#' at the start or after whitespace.
std::string strip_comment(const std::string& s) {
  for (std::size_t i = 0; i < s.size(); ++i)
    if ((s[i] == ';' || s[i] == '#') && (i == 0 || is_space(s[i - 1]))) return s.substr(0, i);
  return s;
}

} // namespace

// --- Public API ---------------------------------------------------------------

Axis parse_axis(const std::string& name, const std::string& spec_text) {
  const std::string option = "grid." + name;
  if (!contains(grid_keys(), name))
    throw ConfigError(option,
                      "unknown axis " + shown(name) + "; the axes are " + join(grid_keys()));
  Axis a;
  a.name = name;
  a.spec = trim(spec_text);
  const std::string& spec = a.spec;
  const std::string allowed = name + " must be " + range_text(name);
  if (spec.empty()) throw ConfigError(option, name + " is empty; give " + kAxisForms);

  const bool lin = starts_with(spec, "linspace:"), log = starts_with(spec, "logspace:");
  if (lin || log) {
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
    if (log && !(lo.x > 0.0 && hi.x > 0.0))
      throw ConfigError(option, "logspace needs lo > 0 and hi > 0, got lo = " +
                                    format_number(lo.x) + " and hi = " + format_number(hi.x) +
                                    "; use linspace or a list for values that include 0");
    if (lin)
      fill_linspace(a.values, lo.x, hi.x, n);
    else
      fill_logspace(a.values, lo.x, hi.x, n);
    a.logarithmic = log;
  } else {
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
  for (std::size_t i = 0; i < a.values.size(); ++i)
    if (!in_range(name, a.values[i]))
      throw ConfigError(option, allowed + ", got " + format_number(a.values[i]) +
                                    (a.values.size() > 1 ? " (value " + std::to_string(i + 1) +
                                                               " of " + shown(spec) + ")"
                                                         : std::string()));
  return a;
}

StudyConfig parse_config(const std::string& text, const std::string& base_dir,
                         const std::string& source_name) {
  StudyConfig c;
  c.source_text = text;
  std::map<std::string, int> section_line; // section -> header line
  std::map<std::string, int> key_line;     // "section.key" -> line
  std::map<std::string, Axis> axes;
  std::string section;
  const auto at = [&](int line) { return Where{source_name, line}; };

  int line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    std::string raw = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (line_no == 1 && starts_with(raw, "\xEF\xBB\xBF")) raw.erase(0, 3); // UTF-8 BOM
    const std::string line = trim(raw);
    if (line.empty() || line[0] == ';' || line[0] == '#') continue;
    const Where here = at(line_no);

    if (line[0] == '[') {
      const std::size_t close = line.find(']');
      if (close == std::string::npos)
        throw ConfigError("config", here.prefix() + "malformed section header " + shown(line) +
                                        "; write [grid], [cases] or [run]");
      const std::string rest = trim(line.substr(close + 1));
      if (!rest.empty() && rest[0] != ';' && rest[0] != '#')
        throw ConfigError("config", here.prefix() + "unexpected " + shown(rest) +
                                        " after the section header; only a comment may follow");
      const std::string name = trim(line.substr(1, close - 1));
      if (!contains(sections(), name)) {
        const std::string near = nearest(name, sections());
        throw ConfigError("config",
                          here.prefix() + "unknown section " + shown("[" + name + "]") + "; " +
                              (near.empty() ? std::string("the sections are ")
                                            : "did you mean [" + near + "]? The sections are ") +
                              "[grid] or [cases], and [run]");
      }
      if (section_line.count(name))
        throw ConfigError("config", here.prefix() + "section [" + name +
                                        "] appears twice (first at line " +
                                        std::to_string(section_line[name]) + "); merge them");
      const std::string other = name == "grid" ? "cases" : name == "cases" ? "grid" : "";
      if (!other.empty() && section_line.count(other))
        throw ConfigError("config", here.prefix() + "[" + name + "] cannot be combined with [" +
                                        other + "] (line " + std::to_string(section_line[other]) +
                                        "); a study has either a [grid] or a [cases] list");
      section_line[name] = line_no;
      section = name;
      continue;
    }

    const std::size_t eq = line.find('=');
    if (eq == std::string::npos)
      throw ConfigError("config", here.prefix() + "cannot read " + shown(line) +
                                      "; expected 'key = value', a [section] header or a comment");
    const std::string key = trim(line.substr(0, eq));
    if (key.empty())
      throw ConfigError("config", here.prefix() + "no key before '=' in " + shown(line) +
                                      "; expected 'key = value'");
    if (section.empty())
      throw ConfigError("config",
                        here.prefix() + "key " + shown(key) +
                            " is outside a section; put it under [grid], [cases] or [run]");
    const std::string option = section + "." + key;
    if (!contains(keys_of(section), key))
      throw ConfigError(option, here.prefix() + unknown_key_message(section, key));
    if (key_line.count(option))
      throw ConfigError(option, here.prefix() + "duplicate key '" + key + "' in [" + section +
                                    "] (first set at line " + std::to_string(key_line[option]) +
                                    "); give each key once");
    key_line[option] = line_no;
    const std::string value = trim(strip_comment(line.substr(eq + 1)));
    if (value.empty())
      throw ConfigError(option, here.prefix() + key + " has no value; write '" + key + " = value'");
    try {
      if (section == "grid") {
        if (key == "v1" || key == "v1_over_v") {
          const std::string other = key == "v1" ? "grid.v1_over_v" : "grid.v1";
          if (key_line.count(other))
            throw ConfigError(option, "both v1 and v1_over_v are set (the other at line " +
                                          std::to_string(key_line[other]) + "); give only one");
        }
        axes[key] = parse_axis(key, value);
      } else if (section == "cases") {
        c.cases_file = resolve_cases_file(value, base_dir);
      } else {
        set_run_key(c.run, key, value);
      }
    } catch (const InvalidInput& e) {
      rethrow_at(e, here);
    }
  }

  const bool grid = section_line.count("grid") > 0, cases = section_line.count("cases") > 0;
  if (!grid && !cases)
    throw ConfigError("config", Where{source_name, 0}.prefix() +
                                    "no [grid] or [cases] section; a study needs one of them");
  if (cases) {
    c.kind = StudyConfig::Kind::Cases;
    if (c.cases_file.empty())
      throw ConfigError("cases.file", at(section_line["cases"]).prefix() +
                                          "[cases] has no key 'file'; write 'file = cases.csv'");
    return c;
  }

  c.kind = StudyConfig::Kind::Grid;
  const Where grid_at = at(section_line["grid"]);
  for (const char* name : kAxisOrder) {
    if (!axes.count(name))
      throw ConfigError(std::string("grid.") + name,
                        grid_at.prefix() + "[grid] has no key '" + name +
                            "'; a grid needs d, R, tau, v and one of v1, v1_over_v");
    c.axes.push_back(axes[name]);
  }
  if (axes.count("v1"))
    c.axes.push_back(axes["v1"]);
  else if (axes.count("v1_over_v"))
    c.axes.push_back(axes["v1_over_v"]);
  else
    throw ConfigError("grid.v1",
                      grid_at.prefix() + "[grid] has no key 'v1' or 'v1_over_v'; give one of them");

  check_study(c, [&](const std::string& option) {
    const auto it = key_line.find(option);
    if (it != key_line.end()) return at(it->second);
    if (starts_with(option, "run."))
      return section_line.count("run") ? at(section_line["run"]) : at(0);
    return grid_at;
  });
  return c;
}

StudyConfig load_config(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw ConfigError("config", "cannot read " + shown_path(path) + ": " + std::strerror(EISDIR));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    const int err = errno;
    throw ConfigError("config", "cannot read " + shown_path(path) + ": " + std::strerror(err));
  }
  std::string text;
  char buf[65536];
  for (;;) {
    const std::size_t n = std::fread(buf, 1, sizeof buf, f);
    text.append(buf, n);
    if (text.size() > kMaxConfigBytes) {
      std::fclose(f);
      throw ConfigError("config", "cannot read " + shown_path(path) +
                                      ": larger than 16 MiB; a study config is a short text file");
    }
    if (n < sizeof buf) {
      if (std::ferror(f)) {
        const int err = errno;
        std::fclose(f);
        throw ConfigError("config", "cannot read " + shown_path(path) + ": " + std::strerror(err));
      }
      break;
    }
  }
  std::fclose(f);
  StudyConfig c = parse_config(text, fs::path(path).parent_path().string(), path);
  c.source_path = path;
  return c;
}

void apply_override(StudyConfig& c, const std::string& key, const std::string& value_text) {
  const Where cl{"command line", 0};
  if (!contains(override_keys(), key)) {
    const std::string near = nearest(key, override_keys());
    throw ConfigError(key, cl.prefix() + "unknown key " + shown(key) + "; " +
                               (near.empty() ? "the keys are " + join(override_keys())
                                             : "did you mean '" + near + "'?"));
  }
  const std::size_t dot = key.find('.');
  const std::string section = key.substr(0, dot), name = key.substr(dot + 1);
  const std::string value = trim(value_text);
  if (value.empty())
    throw ConfigError(key, cl.prefix() + key + " has no value; give it as in the config file");
  StudyConfig n = c;
  try {
    if (section == "grid") {
      if (n.kind != StudyConfig::Kind::Grid)
        throw ConfigError(key, "the study reads its cases from " + shown_path(n.cases_file) +
                                   " ([cases]); grid axes cannot be set");
      check_axes_shape(n);
      Axis a = parse_axis(name, value);
      std::size_t i = 4;
      for (std::size_t k = 0; k < 4; ++k)
        if (name == kAxisOrder[k]) i = k;
      n.axes[i] = std::move(a);
    } else if (section == "cases") {
      if (n.kind != StudyConfig::Kind::Cases)
        throw ConfigError(key, "the study is a [grid]; a case list cannot be set");
      n.cases_file = resolve_cases_file(value, "");
    } else {
      set_run_key(n.run, name, value);
    }
  } catch (const InvalidInput& e) {
    rethrow_at(e, cl);
  }
  check_study(n, [&](const std::string&) { return cl; });
  c = std::move(n);
}

std::vector<StepRow> expand_cases(const StudyConfig& c) {
  const Where src{c.source_path.empty() ? "config" : c.source_path, 0};
  if (c.kind == StudyConfig::Kind::Cases) {
    std::vector<StepRow> cases = read_cases_csv(c.cases_file, c.run.G);
    check_timeseries_memory(c.run, static_cast<double>(cases.size()));
    for (std::size_t i = 0; i < cases.size(); ++i) {
      try {
        validate_case(c, cases[i]);
      } catch (const InvalidInput& e) {
        const std::string o = e.option() == "t-end" && cases[i].tau > 0.0 ? "run.t_end_over_tau"
                              : e.option() == "samples"                   ? "run.samples"
                                                                          : "cases." + e.option();
        throw ConfigError(o, c.cases_file + ": case " + std::to_string(i + 1) + ": " +
                                 case_problem(e, cases[i], "v1"));
      }
    }
    return cases;
  }
  check_axes_shape(c);
  const std::size_t count = case_count(c);
  const auto& A = c.axes;
  const bool ratio = A[4].name == "v1_over_v";
  std::vector<StepRow> out;
  out.reserve(count);
  for_each_combination(A[0].values, A[1].values, A[2].values, A[3].values, A[4].values, ratio,
                       c.run.G, [&](const StepRow& s) {
                         try {
                           validate_case(c, s);
                         } catch (const InvalidInput& e) {
                           throw ConfigError(grid_option(e.option(), s, A[4].name),
                                             src.prefix() + "case " +
                                                 std::to_string(out.size() + 1) + ": " +
                                                 case_problem(e, s, A[4].name));
                         }
                         out.push_back(s);
                       });
  return out;
}

std::size_t case_count(const StudyConfig& c) {
  if (c.kind == StudyConfig::Kind::Cases) return read_cases_csv(c.cases_file, c.run.G).size();
  check_axes_shape(c);
  check_grid_size(c);
  std::size_t n = 1;
  for (const auto& a : c.axes)
    n *= a.values.size(); // <= 1e9: no overflow
  return n;
}

void validate_row(const StepRow& r) {
  // the seed's scene order; each field against its parameter's range
  const RowSpecs& spec = row_specs();
  check_as("d", spec.d, r.d);
  check_as("R", spec.R, r.R);
  check_as("tau", spec.tau, r.tau);
  check_as("v", spec.v, r.v);
  check_as("v1", spec.v1, r.v1);
  check_as("G", spec.G, r.G);
  // Every field is in range: only the derived scales (a1, 16 G d^2,
  // v tau / a1) can fail the whole case, over any valid window.
  validate(step_case(r.d, r.R, r.tau, r.v, r.v1, r.G, 1.0, 2));
}

double step_duration(const StudyConfig& c, const StepRow& r) {
  return r.tau > 0.0 ? c.run.t_end_over_tau * r.tau
                     : default_step_duration(r.d, r.R, r.tau, r.v, r.v1);
}

Case case_for(const StudyConfig& c, const StepRow& r) {
  validate_row(r);
  const double T = check_sampling(c, r); // > 0: step_case takes it as given
  Case out = step_case(r.d, r.R, r.tau, r.v, r.v1, r.G, T, c.run.samples);
  validate(out);
  return out;
}

std::string canonical(const StudyConfig& c) {
  std::string out = "mdrmap study 1\n";
  if (c.kind == StudyConfig::Kind::Grid) {
    check_axes_shape(c);
    out += "[grid]\n";
    for (const auto& a : c.axes) {
      out += a.name + " =";
      for (std::size_t i = 0; i < a.values.size(); ++i)
        out += (i == 0 ? " " : ", ") + format_number(a.values[i]);
      out += "\n";
    }
  } else {
    const std::vector<StepRow> cases = read_cases_csv(c.cases_file, c.run.G);
    out += "[cases]\ncount = " + std::to_string(cases.size()) + "\nd,R,tau,v,v1\n";
    for (const StepRow& s : cases)
      out += format_number(s.d) + "," + format_number(s.R) + "," + format_number(s.tau) + "," +
             format_number(s.v) + "," + format_number(s.v1) + "\n";
  }
  std::string solver = c.run.solver;
  try {
    solver = solver_name(parse_solver(c.run.solver));
  } catch (const InvalidInput&) {
    // keep as is: a hand-made config; the runner will refuse it
  }
  out += "[run]\nt_end_over_tau = " + format_number(c.run.t_end_over_tau) +
         "\nsamples = " + std::to_string(c.run.samples) + "\nrtol = " + format_number(c.run.rtol) +
         "\nsolver = " + solver + "\ntimeseries = " + (c.run.timeseries ? "true" : "false") +
         "\nG = " + format_number(c.run.G) + "\n";
  return out;
}

std::vector<StepRow> read_cases_csv(const std::string& path, double G) {
  if (!std::isfinite(G) || !(G > 0.0))
    throw ConfigError("run.G", "G must be a finite number > 0, got " + format_number(G));
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw ConfigError("cases.file",
                      "cannot read " + shown_path(path) + ": " + std::strerror(EISDIR));
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno != 0 ? errno : ENOENT;
    throw ConfigError("cases.file", "cannot read " + shown_path(path) + ": " + std::strerror(err));
  }
  const std::string all_columns = "d, R, tau, v, v1";
  int field_of_column[5] = {-1, -1, -1, -1, -1}; // StepRow field -> CSV column index
  std::vector<int> column_field;                 // CSV column -> StepRow field
  std::vector<StepRow> cases;
  bool have_header = false;
  int line_no = 0;
  std::string raw;
  while (std::getline(in, raw)) {
    ++line_no;
    if (line_no == 1 && starts_with(raw, "\xEF\xBB\xBF")) raw.erase(0, 3);
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::string at = path + ":" + std::to_string(line_no);
    const auto fields = split(line, ',');
    if (!have_header) {
      for (std::size_t k = 0; k < fields.size(); ++k) {
        const std::string name = trim(fields[k]);
        const std::string here = at + ":" + std::to_string(k + 1) + ": ";
        int f = -1;
        for (int j = 0; j < 5; ++j)
          if (name == kColumns[j]) f = j;
        if (f < 0) {
          const std::string near = nearest(name, {"d", "R", "tau", "v", "v1"});
          throw ConfigError("cases.file",
                            here + "unknown column " + shown(name) + "; " +
                                (near.empty() ? "" : "did you mean '" + near + "'? ") +
                                "the header must name the columns " + all_columns +
                                ", each once, in any order");
        }
        if (field_of_column[f] >= 0)
          throw ConfigError("cases.file", here + "column '" + name +
                                              "' appears twice (also column " +
                                              std::to_string(field_of_column[f] + 1) +
                                              "); give each of " + all_columns + " once");
        field_of_column[f] = static_cast<int>(k);
        column_field.push_back(f);
      }
      for (int j = 0; j < 5; ++j)
        if (field_of_column[j] < 0)
          throw ConfigError("cases.file", at + ": missing column '" + kColumns[j] +
                                              "'; the header must name the columns " + all_columns +
                                              " (in any order)");
      have_header = true;
      continue;
    }
    if (fields.size() != 5)
      throw ConfigError("cases.file", at + ": " + std::to_string(fields.size()) +
                                          " fields, the header has 5; give one value per column");
    double x[5] = {0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < 5; ++k) {
      const int f = column_field[k];
      const std::string cell = trim(fields[k]);
      const Num n = to_number(cell);
      if (n.err != NumError::None)
        throw ConfigError(std::string("cases.") + kColumns[f],
                          at + ":" + std::to_string(k + 1) + ": " + kColumns[f] +
                              (n.err == NumError::Empty ? std::string(" is empty")
                                                        : " value " + number_problem(cell, n.err)) +
                              "; " + kColumns[f] + " must be " + range_text(kColumns[f]));
      x[f] = n.x;
    }
    StepRow s;
    s.d = x[0];
    s.R = x[1];
    s.tau = x[2];
    s.v = x[3];
    s.v1 = x[4];
    s.G = G;
    try {
      validate_row(s);
    } catch (const InvalidInput& e) {
      int f = -1;
      for (int j = 0; j < 5; ++j)
        if (e.option() == kColumns[j]) f = j;
      if (f < 0) throw ConfigError("run.G", at + ": G " + e.what());
      throw ConfigError(std::string("cases.") + kColumns[f],
                        at + ":" + std::to_string(field_of_column[f] + 1) + ": " + kColumns[f] +
                            " " + e.what());
    }
    cases.push_back(s);
  }
  if (in.bad()) throw ConfigError("cases.file", "cannot read " + shown_path(path) + ": read error");
  if (!have_header)
    throw ConfigError("cases.file", path + ": no header; the first line must name the columns " +
                                        all_columns + " (in any order)");
  if (cases.empty())
    throw ConfigError("cases.file",
                      path + ": no cases after the header; add one line of values per case");
  return cases;
}

} // namespace mdrmap::study
