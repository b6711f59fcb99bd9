// The keys of a study config: the columns' from the core's parameter table
// and the study's column specs, the [cases] and [run] keys declared here.
#include "study/config_keys.hpp"

#include <cstring>
#include <utility>

#include "core/model/params.hpp"
#include "core/model/profile.hpp"
#include "core/solvers/dispatch.hpp"
#include "study/columns.hpp"
#include "study/config.hpp"

namespace mdrmap::study {

using namespace detail;

namespace {

constexpr const char* kSpec = "SPEC";

/// "a | b | c" of names.
template <class Kinds, class Name> std::string choices(const Kinds& kinds, Name name) {
  std::string s;
  for (const auto k : kinds)
    s += (s.empty() ? "" : " | ") + std::string(name(k));
  return s;
}

/// A meaning of the core's table in the config's words: the command line's
/// "--profile cone" is "profile = cone", its "--prony" spectrum the columns
/// Gk, tauk.
std::string config_words(std::string text) {
  const std::pair<const char*, const char*> words[] = {{"--profile ", "profile = "},
                                                       {"with --prony", "with a spectrum"},
                                                       {"of --prony", "of the spectrum"}};
  for (const auto& [cli, config] : words)
    for (std::size_t i = text.find(cli); i != std::string::npos; i = text.find(cli, i))
      text.replace(i, std::strlen(cli), config);
  return text;
}

/// Whether a table parameter is required, optional, one of a group or a
/// profile's own.
std::string given(const ParamSpec& p) {
  if (p.one_of) {
    std::string group;
    for (const ParamSpec* q : study_parameters())
      if (q->one_of && std::string(q->one_of) == p.one_of)
        group += (group.empty() ? "" : " or ") + std::string(q->name);
    return "required: one of " + group;
  }
  if (p.profile) return std::string("required with profile = ") + p.profile + ", else not given";
  if (p.required) return "required";
  if (only_where_given(p)) return "optional (default " + format_number(p.fallback) + ")";
  return "default " + format_number(p.fallback);
}

/// A column's key: its spec's unit, range and meaning.
ConfigKey column_key(const char* section, const std::string& key, const std::string& column,
                     const std::string& given_text, const std::string& note = "") {
  Column col;
  parse_column(column, col);
  const ParamSpec& spec = column_spec(col);
  return {section, key, kSpec, dim_name(spec.dim), spec.allowed(), given_text, spec.meaning + note};
}

void grid_keys(std::vector<ConfigKey>& out) {
  for (const ParamSpec* p : study_parameters()) {
    out.push_back({"grid", p->name, kSpec, dim_name(p->dim), p->allowed(), given(*p),
                   config_words(p->meaning)});
    if (const ParamAlias* a = alias_of(p->name))
      out.push_back({"grid", a->alias, kSpec, dim_name(p->dim), p->allowed(),
                     std::string("instead of ") + a->name,
                     std::string("the old spelling of ") + a->name + ", read as " + a->name});
  }
  const std::string last = std::to_string(kMaxBranches);
  const std::string term =
      "optional: terms k = 1.." + last + ", each with Gk and tauk; with them G is required";
  out.push_back(column_key("grid", "Gk", "G1", term, " (term k)"));
  out.push_back(column_key("grid", "tauk", "tau1", term, " (term k)"));
  out.push_back(column_key("grid", "temperature", "temperature",
                           "optional, instead of aT; needs [run] wlf (or a card's *TRS)",
                           "; with an optional unit, one for all values (25C, 35C)"));
  out.push_back(column_key("grid", "v1", "v1", "the seed's one step: instead of [history]",
                           " (the seed's v1: history.w1)"));
  out.push_back(column_key("grid", "v1_over_v", "v1_over_v",
                           "the seed's one step: instead of [history]",
                           " (the seed's v1 / v: history.w1_over_v)"));
}

void history_keys(std::vector<ConfigKey>& out) {
  const char* const keys[][3] = {{"wK", "w1", "one of wK, wK_over_v for every segment K"},
                                 {"wK_over_v", "w1_over_v", ""},
                                 {"TK", "T1", "one of TK, TK_over_tau for every segment K"},
                                 {"TK_over_tau", "T1_over_tau", ""}};
  for (const auto& k : keys)
    out.push_back(column_key("history", k[0], k[1], k[2][0] ? k[2] : "instead of the one above",
                             " (segment K = 1, 2, ...)"));
}

/// The [run] keys: key, value, allowed, default, meaning.
std::vector<ConfigKey> run_keys() {
  const RunSettings d{};
  const ParamSpec& decades = *find_parameter("log-decades");
  const ParamSpec& G = *find_parameter("G");
  const std::string solvers = choices(kSolverKinds, solver_name);
  const std::string profiles = choices(all_profiles(), profile_name);
  return {
      {"run", "samples", "N", "count", "an integer from 2 to " + format_number(kMaxRunSamples),
       "default " + std::to_string(d.samples), "output instants per segment"},
      {"run", "spacing", "linear | log", "", "linear or log",
       std::string("default ") + (d.spacing == Spacing::Log ? "log" : "linear"),
       "where a segment's samples lie: evenly in time, or evenly in the log of the time since "
       "the segment's start"},
      {"run", "decades", "D", dim_name(decades.dim), decades.allowed(),
       "default " + format_number(d.decades),
       "with spacing = log: the first instant after a segment's start is T 10^-decades"},
      {"run", "rtol", "E", "number", kRtolAllowed, "default " + format_number(d.rtol),
       "target accuracy: bound on each case's error estimate"},
      {"run", "solver", solvers, "", solvers, "default " + d.solver,
       "the solver of every case; auto takes the cheapest that solves the case and meets rtol"},
      {"run", "timeseries", "true | false", "", "true or false (also yes/no, 1/0)",
       std::string("default ") + (d.timeseries ? "true" : "false"),
       "store every sample of every case in /timeseries (at most 64 GiB)"},
      {"run", "wlf", "C1:C2:TREF", "", "C1 > 0, C2 > 0; TREF with an optional unit (25C, 298.15K)",
       "required with a temperature column (unless a material card's *TRS gives it), else not "
       "given",
       "the WLF constants that give aT at a temperature column: log10 aT = -C1 (T - TREF) / "
       "(C2 + T - TREF); bare values of the column are in TREF's unit, values with another "
       "unit converted to it"},
      {"run", "allow_large_shift", "true | false", "", "true or false (also yes/no, 1/0)",
       std::string("default ") + (d.allow_large_shift ? "true" : "false"),
       "take a temperature's WLF shift of more than 12 decades (refused otherwise: most often a "
       "C/K mix-up)"},
      {"run", "profile", profiles, "", profiles, std::string("default ") + profile_name(d.profile),
       "the indenter of every case: a parabola (column R), a cone (beta), a power law (n, A) "
       "or the exact sphere (radius)"},
      {"run", "material", "FILE", "",
       "an Abaqus card or pyvisco's CSV, relative to the config's "
       "directory",
       "optional, instead of [grid] G, Gk, tauk (and [run] wlf where it has *TRS)",
       "the material from a file: G, the spectrum's terms (columns of one value) and the WLF "
       "constants of its *TRS; the map records its text (/provenance/material_card)"},
      {"run", "t_end_over_tau", "X", "number", "a finite number > 0",
       "the seed's form: default 6 with [grid] v1 or v1_over_v",
       "the seed's window: history.T1_over_tau under its old name"},
      {"run", "G", "G", dim_name(G.dim), G.allowed(), "the seed's form: instead of [grid] G",
       config_words(G.meaning) + ": [grid] G under its old place, one number"}};
}

} // namespace

const std::vector<ConfigKey>& config_keys() {
  static const std::vector<ConfigKey> all = [] {
    std::vector<ConfigKey> out;
    grid_keys(out);
    history_keys(out);
    out.push_back({"cases", "file", "PATH", "", "a CSV file, relative to the config's directory",
                   "required in [cases] (instead of [grid])",
                   "the case list: a header naming its columns (the [grid] and [history] keys "
                   "with absolute wK, TK, or the seed's v1), one case per line"});
    for (ConfigKey& k : run_keys())
      out.push_back(std::move(k));
    return out;
  }();
  return all;
}

std::vector<std::string> run_key_names() {
  std::vector<std::string> names;
  for (const ConfigKey& k : config_keys())
    if (k.section == "run") names.push_back(k.key);
  return names;
}

} // namespace mdrmap::study
