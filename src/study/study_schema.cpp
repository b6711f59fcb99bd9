// The study schema: which sections and keys a study config has, what each
// key's value means, and assembling a StudyConfig from an INI file or a
// command-line override (parse_config, load_config, apply_override).
#include <filesystem>
#include <map>

#include "core/params.hpp"
#include "core/solver.hpp"
#include "study/axes.hpp"
#include "study/case_list.hpp"
#include "study/config.hpp"
#include "study/config_detail.hpp"
#include "study/ini.hpp"

namespace mdrmap::study {

using namespace detail;

namespace {

constexpr long kMaxRunSamples = 1'000'000;

const IniSchema& study_schema() {
  static const IniSchema s{
      {"grid", "cases", "run"},
      {axis_names(), {"file"}, {"t_end_over_tau", "samples", "rtol", "solver", "timeseries", "G"}},
      "[grid], [cases] or [run]",
      "[grid] or [cases], and [run]"};
  return s;
}

/// Every key as "section.key", as the command line names them.
const std::vector<std::string>& override_keys() {
  static const std::vector<std::string> k = [] {
    std::vector<std::string> all;
    for (const auto& s : study_schema().sections)
      for (const auto& key : study_schema().keys_of(s))
        all.push_back(s + "." + key);
    return all;
  }();
  return k;
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

long run_samples(const std::string& option, const std::string& text) {
  long long n = 0;
  const std::string allowed =
      "samples must be an integer from 2 to " + std::to_string(kMaxRunSamples);
  if (!to_integer(text, n))
    throw ConfigError(option, shown(text) + " is not an integer; " + allowed);
  if (n < 2 || n > kMaxRunSamples)
    throw ConfigError(option, allowed + ", got " + digits_shown(text));
  return static_cast<long>(n);
}

double run_rtol(const std::string& option, const std::string& text) {
  const Num n = to_number(text);
  if (n.err != NumError::None)
    throw ConfigError(option, number_problem(text, n.err) + "; rtol must be a number in (0, 0.1]");
  try {
    validate_rtol(n.x);
  } catch (const InvalidInput& e) {
    throw ConfigError(option, std::string("rtol ") + e.what());
  }
  return n.x;
}

std::string run_solver(const std::string& option, const std::string& text) {
  try {
    return solver_name(parse_solver(text));
  } catch (const InvalidInput&) {
    throw ConfigError(option, "unknown solver " + shown(text) +
                                  "; solver must be one of auto, exact, mdr, baseline");
  }
}

bool run_timeseries(const std::string& option, const std::string& text) {
  const std::string t = lower(text);
  if (t == "true" || t == "yes" || t == "1") return true;
  if (t == "false" || t == "no" || t == "0") return false;
  throw ConfigError(option, shown(text) + " is not a yes/no value; timeseries must be true "
                                          "or false (also yes/no, 1/0)");
}

/// Sets one [run] key from its text. Throws ConfigError("run.<key>") without location.
void set_run_key(RunSettings& r, const std::string& key, const std::string& text) {
  const std::string option = "run." + key;
  if (key == "t_end_over_tau")
    r.t_end_over_tau = positive_number(option, key, text);
  else if (key == "G")
    r.G = positive_number(option, key, text);
  else if (key == "samples")
    r.samples = run_samples(option, text);
  else if (key == "rtol")
    r.rtol = run_rtol(option, text);
  else if (key == "solver")
    r.solver = run_solver(option, text);
  else if (key == "timeseries")
    r.timeseries = run_timeseries(option, text);
  else
    throw ConfigError(option, "unknown key " + shown(key) + " in [run]");
}

// --- The file -------------------------------------------------------------------

/// A study reads [grid] or [cases], not both. Throws ConfigError("config") without location.
void check_one_kind(const std::string& section, const IniLines& seen) {
  const std::string other = section == "grid" ? "cases" : section == "cases" ? "grid" : "";
  if (!other.empty() && seen.section_line.count(other))
    throw ConfigError("config", "[" + section + "] cannot be combined with [" + other + "] (line " +
                                    std::to_string(seen.section_line.at(other)) +
                                    "); a study has either a [grid] or a [cases] list");
}

/// What a file's values make of a study: the config and its grid axes by name.
struct FileValues {
  StudyConfig& c;
  std::map<std::string, Axis> axes;
  std::string base_dir;

  /// One key's value. Throws ConfigError without location.
  void set(const std::string& section, const std::string& key, const std::string& value,
           const IniLines& seen) {
    if (section == "grid") {
      if (key == "v1" || key == "v1_over_v") {
        const std::string other = key == "v1" ? "grid.v1_over_v" : "grid.v1";
        if (seen.key_line.count(other))
          throw ConfigError(section + "." + key,
                            "both v1 and v1_over_v are set (the other at line " +
                                std::to_string(seen.key_line.at(other)) + "); give only one");
      }
      axes[key] = parse_axis(key, value);
    } else if (section == "cases") {
      c.cases_file = resolve_cases_file(value, base_dir);
    } else {
      set_run_key(c.run, key, value);
    }
  }
};

/// Where each option was set in a file: its key's line, else its section's
/// header ([run], or [grid] for anything else), else the file.
WhereFn where_in_file(const IniLines& lines, const std::string& source) {
  const Where grid_at{source, lines.section_line.at("grid")};
  return [&lines, source, grid_at](const std::string& option) {
    const auto it = lines.key_line.find(option);
    if (it != lines.key_line.end()) return Where{source, it->second};
    if (starts_with(option, "run.")) {
      const auto run = lines.section_line.find("run");
      return Where{source, run != lines.section_line.end() ? run->second : 0};
    }
    return grid_at;
  };
}

/// The grid's axes in study order, then every check of the whole study.
void assemble_grid(StudyConfig& c, std::map<std::string, Axis>& axes, const IniLines& lines,
                   const std::string& source) {
  c.kind = StudyConfig::Kind::Grid;
  const Where grid_at{source, lines.section_line.at("grid")};
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
  check_study(c, where_in_file(lines, source));
}

// --- The command line -------------------------------------------------------------

/// Sets section.name from an override's value. Throws ConfigError without location.
void set_override(StudyConfig& n, const std::string& key, const std::string& value) {
  const std::size_t dot = key.find('.');
  const std::string section = key.substr(0, dot), name = key.substr(dot + 1);
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
}

} // namespace

StudyConfig parse_config(const std::string& text, const std::string& base_dir,
                         const std::string& source_name) {
  StudyConfig c;
  c.source_text = text;
  FileValues values{c, {}, base_dir};
  IniHandlers on;
  on.section = check_one_kind;
  on.value = [&values](const std::string& section, const std::string& key, const std::string& value,
                       const IniLines& seen) { values.set(section, key, value, seen); };
  const IniLines lines = read_ini(text, source_name, study_schema(), on);

  const bool grid = lines.section_line.count("grid") > 0;
  const bool cases = lines.section_line.count("cases") > 0;
  if (!grid && !cases)
    throw ConfigError("config", Where{source_name, 0}.prefix() +
                                    "no [grid] or [cases] section; a study needs one of them");
  if (cases) {
    c.kind = StudyConfig::Kind::Cases;
    if (c.cases_file.empty())
      throw ConfigError("cases.file", Where{source_name, lines.section_line.at("cases")}.prefix() +
                                          "[cases] has no key 'file'; write 'file = cases.csv'");
    return c;
  }
  assemble_grid(c, values.axes, lines, source_name);
  return c;
}

StudyConfig load_config(const std::string& path) {
  const std::string text = read_config_file(path);
  StudyConfig c = parse_config(text, std::filesystem::path(path).parent_path().string(), path);
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
  const std::string value = trim(value_text);
  if (value.empty())
    throw ConfigError(key, cl.prefix() + key + " has no value; give it as in the config file");
  StudyConfig n = c;
  try {
    set_override(n, key, value);
  } catch (const InvalidInput& e) {
    rethrow_at(e, cl);
  }
  check_study(n, [&cl](const std::string&) { return cl; });
  c = std::move(n);
}

} // namespace mdrmap::study
