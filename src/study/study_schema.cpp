// The study schema: which sections and keys a study config has, what each
// key's value means, and assembling a StudyConfig from an INI file or a
// command-line override (parse_config, load_config, apply_override).
#include <algorithm>
#include <filesystem>
#include <map>

#include "core/model/params.hpp"
#include "core/solvers/dispatch.hpp"
#include "study/axes.hpp"
#include "study/case_list.hpp"
#include "study/columns.hpp"
#include "study/config.hpp"
#include "study/config_detail.hpp"
#include "study/config_keys.hpp"
#include "study/ini.hpp"
#include "study/material_columns.hpp"
#include "study/temperature_column.hpp"

namespace mdrmap::study {

using namespace detail;

namespace {

std::vector<std::string> grid_keys() {
  std::vector<std::string> k;
  for (const ParamSpec* p : study_parameters())
    k.push_back(p->name);
  k.push_back("temperature"); // aT by [run] wlf
  k.push_back("v1");          // the seed's step: w1
  k.push_back("v1_over_v");
  return k;
}

bool is_history_key(const std::string& key) {
  Column col;
  return key != "v1" && key != "v1_over_v" && parse_column(key, col) && col.history();
}

/// A spectrum's term Gk or tauk (k = 1..32): keys of [grid].
bool is_spectrum_key(const std::string& key) {
  Column col;
  return parse_column(key, col) && col.spectrum();
}

/// An old spelling of a table parameter (FN for F0): a key of [grid] beside
/// the table's names, read as the parameter it names.
bool is_alias_key(const std::string& key) {
  Column col;
  return canonical_parameter_name(key) != key && parse_column(key, col);
}

/// A key like a spectrum's term past the last (G33, tau0, G040): what the
/// terms are; "" for any other key.
std::string spectrum_term_hint(const std::string& key) {
  const std::size_t digits = key[0] == 'G' ? 1 : starts_with(key, "tau") ? 3 : key.size();
  if (digits >= key.size() || key.find_first_not_of("0123456789", digits) != std::string::npos)
    return "";
  const std::string last = std::to_string(kMaxBranches);
  return "a relaxation spectrum has at most " + last + " terms, the keys G1.." + "G" + last +
         " and tau1..tau" + last + " (a term's modulus and relaxation time)";
}

const IniSchema& study_schema() {
  static const IniSchema s{{"grid", "history", "cases", "run"},
                           {grid_keys(), history_names(1), {"file"}, run_key_names()},
                           "[grid], [history], [cases] or [run]",
                           "[grid] or [cases], [history] and [run]",
                           [](const std::string& section, const std::string& key) {
                             return (section == "history" && is_history_key(key)) ||
                                    (section == "grid" &&
                                     (is_spectrum_key(key) || is_alias_key(key)));
                           },
                           [](const std::string& section, const std::string& key) {
                             return section == "grid" ? spectrum_term_hint(key) : "";
                           }};
  return s;
}

} // namespace

std::vector<std::string> override_keys() {
  std::vector<std::string> all;
  for (const auto& s : study_schema().sections)
    for (const auto& key : study_schema().keys_of(s))
      all.push_back(s + "." + key);
  for (std::size_t k = 2; k <= 9; ++k)
    for (const auto& key : history_names(k))
      all.push_back("history." + key);
  all.insert(all.end(), {"grid.G1", "grid.tau1"}); // a spectrum's terms: any k up to 32
  return all;
}

namespace {

/// An override's key is known: a listed one or any history column.
bool known_override(const std::string& key) {
  if (contains(override_keys(), key)) return true;
  if (starts_with(key, "grid.") && (is_spectrum_key(key.substr(5)) || is_alias_key(key.substr(5))))
    return true;
  return starts_with(key, "history.") && is_history_key(key.substr(8));
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

double run_decades(const std::string& option, const std::string& text) {
  const ParamSpec& spec = *find_parameter("log-decades");
  const Num n = to_number(text);
  if (n.err != NumError::None)
    throw ConfigError(option, number_problem(text, n.err) + "; decades must be " + spec.allowed());
  try {
    spec.check(n.x);
  } catch (const InvalidInput& e) {
    throw ConfigError(option, std::string("decades ") + e.what());
  }
  return n.x;
}

double run_rtol(const std::string& option, const std::string& text) {
  const Num n = to_number(text);
  if (n.err != NumError::None)
    throw ConfigError(option, number_problem(text, n.err) + "; rtol must be " + kRtolAllowed);
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
  } catch (const InvalidInput& e) {
    if (text == "mdr") throw ConfigError(option, std::string("solver ") + e.what()); // retired
    std::string names;
    for (const SolverKind k : kSolverKinds)
      names += (names.empty() ? "" : ", ") + std::string(solver_name(k));
    throw ConfigError(option, "unknown solver " + shown(text) + "; solver must be one of " + names);
  }
}

bool run_timeseries(const std::string& option, const std::string& text) {
  const std::string t = lower(text);
  if (t == "true" || t == "yes" || t == "1") return true;
  if (t == "false" || t == "no" || t == "0") return false;
  throw ConfigError(option, shown(text) + " is not a yes/no value; " + option.substr(4) +
                                " must be true or false (also yes/no, 1/0)");
}

Spacing run_spacing(const std::string& option, const std::string& text) {
  const std::string t = lower(text);
  if (t == "linear") return Spacing::Linear;
  if (t == "log") return Spacing::Log;
  throw ConfigError(option, "unknown spacing " + shown(text) + "; spacing must be linear or log");
}

Profile run_profile(const std::string& option, const std::string& text) {
  try {
    return parse_profile(lower(trim(text)));
  } catch (const InvalidInput& e) {
    throw ConfigError(option, std::string("profile ") + e.what());
  }
}

UnitWlf run_wlf(const std::string& option, const std::string& text) {
  try {
    return parse_unit_wlf(option, text);
  } catch (const InvalidInput& e) {
    throw ConfigError(option, std::string("wlf ") + e.what());
  }
}

/// Sets one [run] key from its text. Throws ConfigError("run.<key>") without location.
void set_run_key(RunSettings& r, const std::string& key, const std::string& text) {
  const std::string option = "run." + key;
  if (key == "samples")
    r.samples = run_samples(option, text);
  else if (key == "spacing")
    r.spacing = run_spacing(option, text);
  else if (key == "decades")
    r.decades = run_decades(option, text);
  else if (key == "rtol")
    r.rtol = run_rtol(option, text);
  else if (key == "solver")
    r.solver = run_solver(option, text);
  else if (key == "timeseries")
    r.timeseries = run_timeseries(option, text);
  else if (key == "wlf") {
    refuse_wlf_beside_card(r);
    const UnitWlf w = run_wlf(option, text);
    r.wlf = w.wlf;
    r.wlf_unit = w.unit;
  } else if (key == "allow_large_shift")
    r.allow_large_shift = run_timeseries(option, text);
  else if (key == "profile")
    r.profile = run_profile(option, text);
  else
    throw ConfigError(option, "unknown key " + shown(key) + " in [run]");
}

/// The seed's [run] G and t_end_over_tau: one number, a column of the study
/// (G, and T1_over_tau under its old name).
Axis run_column(const std::string& key, const std::string& text) {
  Axis a;
  a.name = key;
  a.section = "run";
  a.spec = trim(text);
  a.values = {positive_number("run." + key, key, a.spec)};
  if (key == "G") {
    parse_column("G", a.column);
  } else {
    a.column.kind = Column::Kind::DurationOverTau;
    a.column.segment = 1;
  }
  return a;
}

bool is_run_column(const std::string& key) {
  return key == "G" || key == "t_end_over_tau";
}

// --- Columns ------------------------------------------------------------------

/// Puts a column in, replacing one that sets the same thing (an override).
void put_column(StudyConfig& c, Axis a) {
  refuse_beside_card(c, a);
  for (auto it = c.axes.begin(); it != c.axes.end(); ++it)
    if (column_rank(it->column) == column_rank(a.column)) {
      if (it->listed)
        throw ConfigError(a.option(), a.name + " is a column of the case list " +
                                          shown_path(c.cases_file) + "; change it there");
      c.axes.erase(it);
      break;
    }
  c.axes.push_back(std::move(a));
}

/// Adds a column from the config file: one that sets what another sets (a
/// key of the file, or a case list's column) is an error.
void add_column(StudyConfig& c, Axis a) {
  refuse_beside_card(c, a);
  for (const Axis& b : c.axes)
    if (column_rank(b.column) == column_rank(a.column))
      throw ConfigError(a.option(),
                        "both " + b.name + " (" +
                            (b.listed ? "a column of " + shown_path(c.cases_file) : b.option()) +
                            ") and " + a.name +
                            " are given; they set the same "
                            "thing, give only one");
  c.axes.push_back(std::move(a));
}

/// A temperature column takes the WLF constants of [run] wlf, which apply
/// to it only. Throws ConfigError without location.
void check_temperature(const StudyConfig& c) {
  const Axis* temperature = nullptr;
  for (const Axis& a : c.axes)
    if (a.column.kind == Column::Kind::Temperature) temperature = &a;
  if (temperature && !c.run.wlf)
    throw ConfigError(temperature->option(),
                      "temperature needs the WLF constants that shift the times at it: "
                      "[run] wlf = C1:C2:TREF (log10 aT = -C1 (T - TREF) / (C2 + T - TREF)) or a "
                      "[run] material card with *TRS");
  if (!temperature && c.run.wlf && !c.run.card_wlf) // a card's *TRS: none is asked of it
    throw ConfigError("run.wlf", "wlf applies to a temperature column only: give [grid] "
                                 "temperature (or a case list's column), or drop wlf");
}

/// Makes the columns whole: the seed's default window t_end_over_tau = 6
/// after a v1 or v1_over_v without a duration, then column order and the
/// checks of order_columns; a case list's columns from the config take one
/// value. Throws ConfigError without location.
void complete_columns(StudyConfig& c) {
  bool seed_step = false, duration1 = false;
  for (const Axis& a : c.axes) {
    seed_step = seed_step || a.name == "v1" || a.name == "v1_over_v";
    duration1 =
        duration1 || (a.column.segment == 1 && (a.column.kind == Column::Kind::Duration ||
                                                a.column.kind == Column::Kind::DurationOverTau));
  }
  if (seed_step && !duration1) c.axes.push_back(run_column("t_end_over_tau", "6"));
  order_columns(c.axes,
                c.kind == StudyConfig::Kind::Cases ? shown_path(c.cases_file) + " and the config: "
                                                   : std::string(),
                c.run.profile);
  check_temperature(c);
  temperatures_in_wlf_unit(c);
  if (c.kind != StudyConfig::Kind::Cases) return;
  for (const Axis& a : c.axes)
    if (!a.listed && a.values.size() != 1)
      throw ConfigError(a.option(), a.name + " has " + std::to_string(a.values.size()) +
                                        " values; a case list takes one value per column from "
                                        "the config (put the others in a column of " +
                                        shown_path(c.cases_file) + ")");
}

/// A case list's columns: those of its CSV header, then the config's.
void list_columns(StudyConfig& c, std::vector<Axis> from_config) {
  c.axes = read_list_columns(c.cases_file);
  for (Axis& a : from_config)
    put_column(c, std::move(a));
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

/// What a file's values make of a study: the config and its columns.
struct FileValues {
  StudyConfig& c;
  std::vector<Axis> columns;
  std::string base_dir;

  /// One key's value. Throws ConfigError without location.
  void set(const std::string& section, const std::string& key, const std::string& value,
           const IniLines&) {
    if (section == "grid" || section == "history")
      columns.push_back(parse_axis(section, key, value));
    else if (section == "cases")
      c.cases_file = resolve_cases_file(value, base_dir);
    else if (key == "material")
      for (Axis& a : read_material_columns(c, value, base_dir))
        columns.push_back(std::move(a));
    else if (is_run_column(key))
      columns.push_back(run_column(key, value));
    else
      set_run_key(c.run, key, value);
  }
};

/// Where each option was set in a file: its key's line, else its section's
/// header, else [grid]'s or [cases]', else the file.
WhereFn where_in_file(const IniLines& lines, const std::string& source) {
  return [&lines, source](const std::string& option) {
    const auto it = lines.key_line.find(option);
    if (it != lines.key_line.end()) return Where{source, it->second};
    for (const char* s : {"run", "history", "cases", "grid"})
      if (starts_with(option, (std::string(s) + ".").c_str()) && lines.section_line.count(s))
        return Where{source, lines.section_line.at(s)};
    for (const char* s : {"grid", "cases"})
      if (lines.section_line.count(s)) return Where{source, lines.section_line.at(s)};
    return Where{source, 0};
  };
}

// --- The command line -------------------------------------------------------------

/// Sets section.name from an override's value. Throws ConfigError without location.
void set_override(StudyConfig& n, const std::string& key, const std::string& value) {
  const std::size_t dot = key.find('.');
  const std::string section = key.substr(0, dot), name = key.substr(dot + 1);
  if (section == "grid" || section == "history") {
    put_column(n, parse_axis(section, name, value));
  } else if (section == "run" && is_run_column(name)) {
    put_column(n, run_column(name, value));
  } else if (section == "run" && name == "material") {
    n.axes.erase(std::remove_if(n.axes.begin(), n.axes.end(),
                                [](const Axis& a) { return !a.given_by.empty(); }),
                 n.axes.end());
    for (Axis& a : read_material_columns(n, value, ""))
      put_column(n, std::move(a));
  } else if (section == "cases") {
    if (n.kind != StudyConfig::Kind::Cases)
      throw ConfigError(key, "the study is a [grid]; a case list cannot be set");
    n.cases_file = resolve_cases_file(value, "");
    std::vector<Axis> from_config;
    for (Axis& a : n.axes)
      if (!a.listed) from_config.push_back(std::move(a));
    list_columns(n, std::move(from_config));
  } else {
    set_run_key(n.run, name, value);
  }
}

/// A config file read: its values set and its columns in, not yet made
/// whole or checked as a study (overrides may come first).
struct ReadFile {
  StudyConfig c;
  IniLines lines;
};

ReadFile read_file(const std::string& text, const std::string& base_dir,
                   const std::string& source_name) {
  ReadFile r;
  StudyConfig& c = r.c;
  c.source_text = text;
  FileValues values{c, {}, base_dir};
  IniHandlers on;
  on.section = check_one_kind;
  on.value = [&values](const std::string& section, const std::string& key, const std::string& value,
                       const IniLines& seen) { values.set(section, key, value, seen); };
  r.lines = read_ini(text, source_name, study_schema(), on);

  const bool grid = r.lines.section_line.count("grid") > 0;
  const bool cases = r.lines.section_line.count("cases") > 0;
  if (!grid && !cases)
    throw ConfigError("config", Where{source_name, 0}.prefix() +
                                    "no [grid] or [cases] section; a study needs one of them");
  const WhereFn where = where_in_file(r.lines, source_name);
  if (cases) {
    c.kind = StudyConfig::Kind::Cases;
    if (c.cases_file.empty())
      throw ConfigError("cases.file", where("cases.file").prefix() +
                                          "[cases] has no key 'file'; write 'file = cases.csv'");
    c.axes = read_list_columns(c.cases_file); // errors located in the CSV
  }
  try {
    for (Axis& a : values.columns)
      add_column(c, std::move(a));
  } catch (const InvalidInput& e) {
    rethrow_at(e, where(e.option()));
  }
  return r;
}

/// Makes the columns whole and checks the study; errors located by where.
void finish(StudyConfig& c, const WhereFn& where) {
  try {
    complete_columns(c);
  } catch (const InvalidInput& e) {
    rethrow_at(e, where(e.option()));
  }
  check_study(c, where);
}

/// Both spellings of one parameter (grid.F0 and grid.FN) are refused: each
/// would replace the other.
void refuse_two_spellings(const std::vector<std::pair<std::string, std::string>>& settings,
                          const Where& cl) {
  const auto given = [&settings](const std::string& key) {
    for (const auto& kv : settings)
      if (kv.first == key) return true;
    return false;
  };
  for (const ParamAlias& a : parameter_aliases())
    if (given(std::string("grid.") + a.name) && given(std::string("grid.") + a.alias))
      throw ConfigError(std::string("grid.") + a.alias, cl.prefix() + two_spellings(a, "grid."));
}

/// Sets each override in turn (each key's own checks), without finishing.
void set_overrides(StudyConfig& n,
                   const std::vector<std::pair<std::string, std::string>>& settings) {
  const Where cl{"command line", 0};
  refuse_two_spellings(settings, cl);
  for (const auto& [key, value_text] : settings) {
    if (!known_override(key)) {
      const std::string hint = starts_with(key, "grid.") ? spectrum_term_hint(key.substr(5)) : "";
      if (!hint.empty())
        throw ConfigError(key, cl.prefix() + "unknown key " + shown(key) + "; " + hint);
      const std::string near = nearest(key, override_keys());
      throw ConfigError(key, cl.prefix() + "unknown key " + shown(key) + "; " +
                                 (near.empty() ? "the keys are " + join(override_keys())
                                               : "did you mean '" + near + "'?"));
    }
    const std::string value = trim(value_text);
    if (value.empty())
      throw ConfigError(key, cl.prefix() + key + " has no value; give it as in the config file");
    try {
      set_override(n, key, value);
    } catch (const InvalidInput& e) {
      rethrow_at(e, cl);
    }
  }
}

} // namespace

StudyConfig parse_config(const std::string& text, const std::string& base_dir,
                         const std::string& source_name) {
  ReadFile r = read_file(text, base_dir, source_name);
  finish(r.c, where_in_file(r.lines, source_name));
  return r.c;
}

StudyConfig load_config(const std::string& path) {
  return load_config(path, {});
}

StudyConfig load_config(const std::string& path,
                        const std::vector<std::pair<std::string, std::string>>& overrides) {
  const std::string text = read_config_file(path);
  ReadFile r = read_file(text, std::filesystem::path(path).parent_path().string(), path);
  r.c.source_path = path;
  set_overrides(r.c, overrides);
  // checked once, with every override in: a problem of a key the command line
  // set, or of one neither sets in a section the command line added to (a
  // segment without its duration), is located there, any other in the file
  const WhereFn in_file = where_in_file(r.lines, path);
  finish(r.c, [&](const std::string& option) {
    const std::size_t dot = option.find('.');
    const std::string section = option.substr(0, dot == std::string::npos ? 0 : dot + 1);
    const bool elsewhere = !section.empty() && r.lines.key_line.count(option) == 0;
    for (const auto& kv : overrides)
      if (kv.first == option || (elsewhere && starts_with(kv.first, section.c_str())))
        return Where{"command line", 0};
    return in_file(option);
  });
  return r.c;
}

void apply_overrides(StudyConfig& c,
                     const std::vector<std::pair<std::string, std::string>>& settings) {
  const Where cl{"command line", 0};
  StudyConfig n = c;
  set_overrides(n, settings);
  finish(n, [&cl](const std::string&) { return cl; }); // after all: a new segment takes two keys
  c = std::move(n);
}

void apply_override(StudyConfig& c, const std::string& key, const std::string& value) {
  apply_overrides(c, {{key, value}});
}

} // namespace mdrmap::study
