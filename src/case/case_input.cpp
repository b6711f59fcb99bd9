#include "case/case_input.hpp"
#include "case/text.hpp"
#include "material/card.hpp"
#include "material/prony_file.hpp"
#include "material/pyvisco.hpp"
#include "material/small_file.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <optional>
#include <stdexcept>

#include "case/prony_input.hpp"
#include "core/model/row_limits.hpp"
#include "core/model/scales.hpp"
#include "core/solvers/checked_case.hpp"

namespace mdrmap::cases {

using material::is_pyvisco_csv;
using material::MaterialCard;
using material::read_material;
using material::read_prony_file;
using material::read_small_file;
using material::SpectrumFile;
namespace {

/// Options that are not case parameters of the table (core/model/params.hpp): the
/// indenter's profile, the history's two forms, the sampling's spacing and how to run.
constexpr const char* kIndenterOptions[] = {"profile"};
constexpr const char* kRheologyOptions[] = {"material", "prony", "prony-file",       "nu",
                                            "T",        "wlf",   "allow-large-shift"};
constexpr const char* kHistoryOptions[] = {"v1", "t-end", "history", "history-file"};
constexpr const char* kRunOptions[] = {"spacing", "rtol", "solver"};

/// The option values with the questions the checks ask of them; `spelled`
/// the old spelling (FN) an option of the table's name (F0) was given as.
class Values {
public:
  Values(const OptionValues& v, const std::map<std::string, std::string>& spelled)
      : v_(v), spelled_(spelled) {}
  bool has(const std::string& name) const { return v_.count(name) != 0; }
  const OptionValue& operator[](const std::string& name) const { return v_.at(name); }
  /// The text of an option whose value is text (a name, a path).
  const std::string& text(const std::string& name) const {
    const OptionValue& v = v_.at(name);
    if (!v.is_text()) throw InvalidInput(name, "must be a text, got " + shown(v));
    return v.text;
  }
  /// The option `name` as the user spelled it.
  std::string as_given(const std::string& name) const {
    const auto it = spelled_.find(name);
    return it == spelled_.end() ? name : it->second;
  }

private:
  const OptionValues& v_;
  const std::map<std::string, std::string>& spelled_;
};

// --- Numbers -------------------------------------------------------------------

/// Strict decimal (or hex) floating-point number, the whole text. "nan" and
/// "inf" parse; the range checks then reject them with the allowed range.
double parse_double(const std::string& option, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  const bool whole = !text.empty() && end != begin && *end == '\0' &&
                     std::strchr(" \t\n\r\f\v", text.front()) == nullptr;
  if (!whole) throw InvalidInput(option, "must be a number, got " + shown(text));
  if (errno == ERANGE && std::isinf(x))
    throw InvalidInput(option,
                       "must be a finite number, got " + text + " (too large for a double)");
  return x;
}

/// Strict integer for a count parameter: optional sign and decimal digits.
double parse_integer(const ParamSpec& spec, const std::string& text) {
  const std::string allowed = "must be " + spec.allowed() + ", got " + shown(text);
  std::size_t i = (!text.empty() && (text[0] == '+' || text[0] == '-')) ? 1 : 0;
  if (i >= text.size()) throw InvalidInput(spec.name, allowed);
  for (; i < text.size(); ++i)
    if (text[i] < '0' || text[i] > '9') throw InvalidInput(spec.name, allowed);
  errno = 0;
  const long long n = std::strtoll(text.c_str(), nullptr, 10);
  if (errno == ERANGE) throw InvalidInput(spec.name, allowed);
  return static_cast<double>(n);
}

/// The number of an option given as a number (itself) or as a text (parsed).
double number_of(const std::string& option, const OptionValue& v) {
  if (v.kind == OptionValue::Kind::Number) return v.number;
  if (v.is_text()) return parse_double(option, v.text);
  throw InvalidInput(option, "must be a number, got " + shown(v));
}

/// A table parameter's value, checked against its range: a number as it is
/// (a count must be a whole number), a text parsed as the command line does.
double parse_parameter(const ParamSpec& spec, const OptionValue& v) {
  const double x =
      spec.integer() && v.is_text() ? parse_integer(spec, v.text) : number_of(spec.name, v);
  spec.check(x);
  return x;
}

/// Checks x against a spec, blaming `option` (e.g. the segment spec "w" is
/// given as --v1 in the one-step shorthand).
void check_as(const std::string& option, const ParamSpec& spec, double x) {
  try {
    spec.check(x);
  } catch (const InvalidInput& e) {
    throw InvalidInput(option, e.what());
  }
}

// --- History -------------------------------------------------------------------

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? comma : comma - start));
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

/// W or T of one segment: a number in its spec's range. `where` names the segment.
double segment_number(const std::string& where, const ParamSpec& spec, const std::string& text) {
  try {
    const double x = parse_double(spec.symbol, trimmed(text));
    spec.check(x);
    return x;
  } catch (const InvalidInput& e) {
    throw InvalidInput("history", where + ": " + spec.symbol + " " + e.what());
  }
}

/// One segment "W:T"; k is 1-based.
Segment parse_segment(std::size_t k, const std::string& item) {
  const std::string where = "segment " + std::to_string(k) + " '" + item + "'";
  const std::string form = "a segment is W:T, its velocity W then its duration T";
  const std::string tok = trimmed(item);
  if (tok.empty())
    throw InvalidInput("history", "segment " + std::to_string(k) +
                                      " is empty; segments W:T are separated by single commas, "
                                      "e.g. 0.1:10,0:100,1:10");
  const std::size_t colon = tok.find(':');
  if (colon == std::string::npos) throw InvalidInput("history", where + " has no ':'; " + form);
  if (tok.find(':', colon + 1) != std::string::npos)
    throw InvalidInput("history", where + " has more than one ':'; " + form);
  Segment s;
  s.w = segment_number(where, segment_velocity_spec(), tok.substr(0, colon));
  s.T = segment_number(where, segment_duration_spec(), tok.substr(colon + 1));
  return s;
}

/// "W1:T1,W2:T2,...": every token checked; throws InvalidInput("history").
std::vector<Segment> parse_history(const std::string& text) {
  if (trimmed(text).empty())
    throw InvalidInput("history", "must be one or more segments W:T separated by commas, e.g. "
                                  "0.1:10,0:100,1:10; got " +
                                      shown(text));
  const std::size_t n = static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1;
  if (n > kMaxSegments)
    throw InvalidInput("history", "has " + std::to_string(n) + " segments; at most " +
                                      std::to_string(kMaxSegments) + " are allowed");
  std::vector<Segment> segments;
  const auto items = split_commas(text);
  for (std::size_t k = 0; k < items.size(); ++k)
    segments.push_back(parse_segment(k + 1, items[k]));
  return segments;
}

/// The history given as (W, T) pairs: each checked as a token of --history
/// is (the message shows the pair as W:T). Throws InvalidInput("history").
std::vector<Segment> history_of_pairs(const std::vector<std::pair<double, double>>& pairs) {
  if (pairs.empty())
    throw InvalidInput("history", "must be one or more segments (W, T), its velocity W then its "
                                  "duration T; got none");
  if (pairs.size() > kMaxSegments)
    throw InvalidInput("history", "has " + std::to_string(pairs.size()) + " segments; at most " +
                                      std::to_string(kMaxSegments) + " are allowed");
  std::vector<Segment> segments;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto [w, T] = pairs[k];
    const std::string where =
        "segment " + std::to_string(k + 1) + " '" + shortest(w) + ":" + shortest(T) + "'";
    for (const auto& [spec, x] :
         {std::pair{&segment_velocity_spec(), w}, std::pair{&segment_duration_spec(), T}})
      if (!spec->contains(x))
        throw InvalidInput("history", where + ": " + spec->symbol + " must be " + spec->allowed() +
                                          ", got " + format_number(x));
    segments.push_back(Segment{w, T});
  }
  return segments;
}

// --- The case --------------------------------------------------------------------

/// The parameters of the profile: each required one given, none of another
/// profile's (--R with a cone, --beta with a parabola).
void require_profile_options(const Values& o, Profile profile) {
  for (const auto& p : case_parameters()) {
    if (p.applies_to(profile)) continue;
    if (o.has(p.name))
      throw InvalidInput(p.name, std::string("applies to --profile ") + p.profile +
                                     " only; this case's profile is " + profile_name(profile) +
                                     (o.has("profile") ? "" : " (the default; give --profile)"));
  }
}

/// --history-file gives V0 and the whole history: none of --v, --v1,
/// --t-end, --history with it.
void require_record_alone(const Values& o) {
  for (const char* other : {"v", "v1", "t-end", "history"})
    if (o.has(other))
      throw InvalidInput("history-file",
                         std::string("cannot be combined with --") + other +
                             ": the record gives V0 (its first row's v) and the whole history");
  for (const char* other : {"samples", "spacing", "log-decades"})
    if (o.has(other))
      throw InvalidInput("history-file", std::string("cannot be combined with --") + other +
                                             ": the output rows are at the record's times");
}

void require_options(const Values& o, Profile profile) {
  require_profile_options(o, profile);
  const bool record = o.has("history-file");
  if (record) require_record_alone(o);
  for (const auto& p : case_parameters())
    if (p.required && p.applies_to(profile) && !o.has(p.name) &&
        !(record && std::string(p.name) == "v"))
      throw InvalidInput(p.name, "is required: " + describe(p) + ", got nothing");
  if (record) return;
  if (o.has("v1") && o.has("history"))
    throw InvalidInput("history", "cannot be combined with --v1: give either --history "
                                  "W1:T1,W2:T2,... or its one-segment shorthand --v1 V1 "
                                  "[--t-end T]");
  if (!o.has("v1") && !o.has("history"))
    throw InvalidInput("v1", "is required: the sliding velocity after t = 0 (length/time), " +
                                 segment_velocity_spec().allowed() +
                                 "; or give a whole history with --history W1:T1,W2:T2,...; "
                                 "got nothing");
  if (o.has("t-end") && o.has("history"))
    throw InvalidInput("t-end", "belongs to the shorthand --v1 V1 [--t-end T]; with --history "
                                "each segment W:T has its own duration");
}

/// Sets every table parameter from its option, or from the table's default
/// (0 for the members of a one_of group that are not given). An explicitly
/// given value is checked against its own range here, before the groups.
void read_case_parameters(const Values& o, Case& c) {
  for (const auto& p : case_parameters()) {
    const double x = o.has(p.name) ? parse_parameter(p, o[p.name]) : p.fallback;
    p.set(c, x);
  }
}

/// Exactly one option of each one_of group (e.g. --d or --F0, the loading)
/// is given; otherwise one line naming the whole group. Raw message: no single
/// option is at fault.
void require_one_of_each_group(const Values& o) {
  for (const auto& p : case_parameters()) {
    if (!p.one_of || group_members(p.one_of).front() != &p) continue; // each group once
    const auto members = group_members(p.one_of);
    std::string given;
    int n = 0;
    for (const ParamSpec* q : members) {
      if (!o.has(q->name)) continue;
      given += (n++ ? " and --" : "--") + o.as_given(q->name);
    }
    if (n == 1) continue;
    std::string what;
    for (const ParamSpec* q : members)
      what += std::string(what.empty() ? "" : ", ") + "--" + q->name + " " + q->meaning;
    throw InvalidInput("", "give exactly one of " + group_usage(members, ", ", " or ") + " (the " +
                               p.one_of + ": " + what + "); got " +
                               (n == 0 ? std::string("none") : given));
  }
}

/// default_step_duration of any profile: 6 tau, or for tau = 0 six contact
/// half-widths a at the slower speed (the parabola's arithmetic as the seed's).
double default_window(const Indenter& ind, double a, double d, double tau, double v, double v1) {
  if (ind.parabolic()) return default_step_duration(d, ind.as<Parabola>().R, tau, v, v1);
  if (tau > 0.0) return 6.0 * tau;
  return 6.0 * a / ((v1 > 0.0) ? std::min(v, v1) : v);
}

/// The one segment of --v1 V1 [--t-end T], the shorthand's values reported as
/// --v1 / --t-end. Needs the case parameters set (the default window).
Segment one_step(const Values& o, Case& c) {
  const double v1 = number_of("v1", o["v1"]);
  check_as("v1", segment_velocity_spec(), v1);
  std::optional<double> t_end;
  if (o.has("t-end")) {
    t_end = number_of("t-end", o["t-end"]);
    check_as("t-end", segment_duration_spec(), *t_end);
  }
  // the scales first (as for any case), then the window they give
  c.history.segments = {Segment{v1, 1.0}};
  validate(c);
  // the window's length scale: a1 = sqrt(R d) at fixed depth, the Hertz
  // radius a0 = sqrt(R d0) of F0 under load (tau = 0: Hertz at once, a1 = a0);
  // its time scale the element's longest shifted time (tau for Kelvin)
  const double a = c.edge_scale(), tau = scales(c).time, v = c.history.v0;
  const double d = c.loading.by_force() ? c.indenter.g(a) : c.loading.d;
  const double T = t_end ? *t_end : default_window(c.indenter, a, d, tau, v, v1);
  if (!t_end) {
    try {
      segment_duration_spec().check(T);
    } catch (const InvalidInput& e) {
      throw InvalidInput("t-end", std::string("the default window ") + e.what() +
                                      "; give --t-end or rescale the units");
    }
  }
  return Segment{v1, T};
}

/// The history from --history, or the one segment of --v1 V1 [--t-end T];
/// every value is checked with the segment specs.
void read_history(const Values& o, CaseInput& in) {
  Case& c = in.c;
  if (o.has("history-file")) {
    in.record = read_lab_record(o.text("history-file"));
    apply_lab_record(*in.record, c);
    try { // what validate() says about the history is about the record
      validate(c);
    } catch (const InvalidInput& e) {
      if (e.option() != "history") throw;
      throw InvalidInput("history-file", o.text("history-file") + ": " + e.what());
    }
  } else if (o.has("history"))
    c.history.segments = o["history"].kind == OptionValue::Kind::Pairs
                             ? history_of_pairs(o["history"].pairs)
                             : parse_history(o.text("history"));
  else
    c.history.segments = {one_step(o, c)};
}

// --- Rheology ------------------------------------------------------------------

/// --nu, Poisson's ratio of the Young's moduli of a spectrum file: -1 < nu <= 0.5.
double read_nu(const Values& o) {
  if (!o.has("nu")) return 0.5;
  const double nu = number_of("nu", o["nu"]);
  if (!(nu > -1.0 && nu <= 0.5))
    throw InvalidInput("nu", "must be a finite number > -1 and <= 0.5 (Poisson's ratio; 0.5: "
                             "incompressible), got " +
                                 shown(o["nu"]));
  return nu;
}

/// The terms of --prony-file and, for normalised moduli (column g), the
/// long-term modulus G = G0 (1 - sum g) instead of --G (then true).
bool read_spectrum_file(const Values& o, Case& c) {
  const double nu = read_nu(o);
  SpectrumFile f = read_prony_file(o.text("prony-file"), nu);
  if (o.has("nu") && !f.uses_nu)
    throw InvalidInput("nu", "applies to Young's moduli (a column E or '# E0 = ...') of "
                             "--prony-file only; the file gives shear moduli");
  c.rheology.branches = std::move(f.branches);
  if (!f.G) return false;
  if (o.has("G"))
    throw InvalidInput("G", "cannot be combined with a spectrum file of normalised moduli g: "
                            "it gives G = G0 (1 - sum g) = " +
                                format_number(*f.G) + "; drop --G");
  c.rheology.G = *f.G;
  return true;
}

/// The Maxwell branches of --prony or --prony-file (at most one of them).
void read_spectrum(const Values& o, Case& c) {
  if (o.has("prony") && o.has("prony-file"))
    throw InvalidInput("prony-file", "cannot be combined with --prony: give the spectrum once, "
                                     "as --prony G1:TAU1,... or as a file");
  if (o.has("nu") && !o.has("prony-file"))
    throw InvalidInput("nu", "applies to a spectrum file's Young's moduli (--prony-file with a "
                             "column E) only");
  if (o.has("prony"))
    c.rheology.branches = o["prony"].kind == OptionValue::Kind::Pairs
                              ? prony_of_pairs(o["prony"].pairs)
                              : parse_prony(o.text("prony"));
  const bool file_G = o.has("prony-file") && read_spectrum_file(o, c);
  if (!c.rheology.branches.empty() && !o.has("G") && !file_G)
    throw InvalidInput("G", "must be given with a spectrum (--" +
                                std::string(o.has("prony") ? "prony" : "prony-file") +
                                "): the long-term (rubbery) modulus G > 0, in the unit of the "
                                "terms' moduli; it has no default beside a spectrum");
}

/// --material FILE: the long-term modulus, the spectrum and the WLF
/// constants of an Abaqus card; the options it sets are refused beside it.
std::optional<MaterialCard> read_card(const Values& o, Case& c) {
  if (!o.has("material")) return std::nullopt;
  for (const char* other : {"G", "prony", "prony-file", "nu"})
    if (o.has(other))
      throw InvalidInput(other, std::string("cannot be combined with --material: the card gives ") +
                                    (std::string(other) == "G"
                                         ? "the long-term modulus G = G0 (1 - sum g_i)"
                                         : "the spectrum (*VISCOELASTIC) and E, nu (*ELASTIC)"));
  MaterialCard m = read_material(o.text("material"));
  c.rheology.G = m.G;
  c.rheology.branches = m.branches;
  return m;
}

/// --T as a number (in the unit of TREF) or a text with an optional unit (25C).
Temperature temperature_of(const OptionValue& v) {
  if (v.is_text()) return parse_temperature("T", v.text);
  const double x = number_of("T", v);
  if (!std::isfinite(x))
    throw InvalidInput("T", "must be a finite temperature, got '" + shortest(x) + "'");
  return Temperature{x, TempUnit::None};
}

/// --wlf as three numbers (C1, C2, TREF) or its text C1:C2:TREF[unit].
UnitWlf wlf_of(const OptionValue& v) {
  if (v.is_text()) return parse_unit_wlf("wlf", v.text);
  const std::string given = shown(v);
  if (v.kind != OptionValue::Kind::Numbers || v.numbers.size() != 3)
    throw InvalidInput("wlf", "must be " + wlf_form(given));
  return UnitWlf{checked_wlf("wlf", v.numbers[0], v.numbers[1], v.numbers[2], given),
                 TempUnit::None};
}

/// A flag given as a flag or as its text (true, false).
bool flag_of(const std::string& option, const OptionValue& v) {
  if (v.kind == OptionValue::Kind::Flag) return v.flag;
  if (v.is_text()) return parse_flag(option, v.text);
  throw InvalidInput(option, "must be true or false (a flag), got " + shown(v));
}

/// Which of --T, --wlf (or the card's *TRS) and --allow-large-shift go together.
void check_temperature_options(const Values& o, bool card_wlf) {
  if (o.has("T") && o.has("aT"))
    throw InvalidInput("T", "cannot be combined with --aT: give the shift factor --aT or the "
                            "temperature --T with its --wlf constants, not both");
  if (o.has("wlf") && card_wlf)
    throw InvalidInput("wlf", "cannot be combined with the WLF constants of --material (its *TRS, "
                              "DEFINITION=WLF)");
  if (o.has("T") && !o.has("wlf") && !card_wlf)
    throw InvalidInput("T", "needs --wlf C1:C2:TREF, the WLF constants that give the shift "
                            "factor aT at the temperature T");
  if (o.has("wlf") && !o.has("T"))
    throw InvalidInput("wlf", "applies with --T TEMP only: give the temperature whose shift "
                              "factor aT it gives (or drop --wlf)");
  if (o.has("allow-large-shift") && !o.has("T"))
    throw InvalidInput("allow-large-shift", "applies with --T TEMP only (a shift --aT is taken "
                                            "as given)");
}

/// --T TEMP with --wlf C1:C2:TREF (or the card's): the shift aT at T (instead of --aT).
std::optional<TemperatureInput> read_temperature(const Values& o, Case& c,
                                                 const std::optional<UnitWlf>& card_wlf) {
  check_temperature_options(o, card_wlf.has_value());
  if (!o.has("T")) return std::nullopt;
  const Temperature T = temperature_of(o["T"]);
  const UnitWlf w = card_wlf ? *card_wlf : wlf_of(o["wlf"]);
  const bool allow =
      o.has("allow-large-shift") && flag_of("allow-large-shift", o["allow-large-shift"]);
  c.rheology.aT = checked_shift(w, T, "T", allow);
  const Temperature in_tref = in_wlf_unit(T, w);
  return TemperatureInput{in_tref.value, w.wlf, in_tref.unit};
}

/// The spectrum and the shift, checked as a whole (validate(Rheology)): a
/// shift that takes a time out of range names --T where the temperature gave it.
void read_rheology(const Values& o, CaseInput& in) {
  Case& c = in.c;
  const auto card = read_card(o, c);
  if (card)
    in.notes = card->notes;
  else
    read_spectrum(o, c);
  const auto t = read_temperature(o, c, card ? card->wlf : std::nullopt);
  in.temperature = t;
  try {
    validate(c.rheology);
  } catch (const InvalidInput& e) {
    if (!t || e.option() != "aT") throw;
    throw InvalidInput("T", "gives aT = " + format_number(c.rheology.aT) + " (WLF " +
                                format_wlf(t->wlf) + unit_suffix(t->unit) + "), and aT " +
                                e.what());
  }
}

Spacing parse_spacing(const std::string& text) {
  if (text == "linear") return Spacing::Linear;
  if (text == "log") return Spacing::Log;
  throw InvalidInput("spacing", "must be linear or log, got " + shown(text));
}

/// Refuses outputs beyond kMaxSamples rows in all.
void check_total_samples(const Case& c) {
  if (!c.sampling.at.empty()) return; // a record's rows, as many as it has
  const double rows =
      static_cast<double>(c.sampling.samples) * static_cast<double>(c.history.size());
  if (rows > static_cast<double>(kMaxSamples))
    throw InvalidInput("samples", std::to_string(c.sampling.samples) + " per segment x " +
                                      std::to_string(c.history.size()) +
                                      " segments = " + format_number(rows) + " rows, more than " +
                                      std::to_string(kMaxSamples) + "; lower --samples");
}

} // namespace

std::vector<std::string> case_option_names() {
  std::vector<std::string> names(std::begin(kIndenterOptions), std::end(kIndenterOptions));
  for (const auto& p : case_parameters())
    if (p.part != Part::Sampling) names.emplace_back(p.name);
  names.insert(names.end(), std::begin(kRheologyOptions), std::end(kRheologyOptions));
  names.insert(names.end(), std::begin(kHistoryOptions), std::end(kHistoryOptions));
  for (const auto& p : case_parameters())
    if (p.part == Part::Sampling) names.emplace_back(p.name);
  names.insert(names.end(), std::begin(kRunOptions), std::end(kRunOptions));
  return names;
}

namespace {

/// The texts under the table's names: an alias's text (--FN) moved to its
/// parameter (--F0); both spellings given is refused. `spelled` gets the
/// alias each moved text was given under, by the table's name.
OptionValues canonical_values(const OptionValues& values,
                              std::map<std::string, std::string>& spelled) {
  OptionValues out = values;
  for (const ParamAlias& a : parameter_aliases()) {
    const auto it = out.find(a.alias);
    if (it == out.end()) continue;
    if (out.count(a.name)) throw InvalidInput("", two_spellings(a, "--"));
    out.emplace(a.name, it->second);
    out.erase(it);
    spelled.emplace(a.name, a.alias);
  }
  return out;
}

CaseInput read_canonical(const Values& o) {
  const Profile profile =
      o.has("profile") ? parse_profile(o.text("profile")) : Profile::of<Parabola>();
  require_options(o, profile);
  CaseInput in;
  in.c.indenter.profile = profile;
  read_case_parameters(o, in.c);
  require_one_of_each_group(o);
  read_rheology(o, in);
  if (o.has("spacing")) in.c.sampling.spacing = parse_spacing(o.text("spacing"));
  if (o.has("log-decades") && in.c.sampling.spacing != Spacing::Log)
    throw InvalidInput("log-decades", "applies to --spacing log only; add --spacing log or "
                                      "drop --log-decades");
  read_history(o, in);
  validate(in.c);
  check_total_samples(in.c);
  if (o.has("rtol")) in.rtol = number_of("rtol", o["rtol"]);
  if (o.has("solver")) in.solver = parse_solver(o.text("solver"));
  validate_rtol(in.rtol);
  return in;
}

// --- One part alone --------------------------------------------------------------

/// Whether option `name` is one of the part's (read_case_part).
bool of_part(const std::string& name, Part part) {
  const std::vector<std::string> extra =
      part == Part::Indenter
          ? std::vector<std::string>(std::begin(kIndenterOptions), std::end(kIndenterOptions))
      : part == Part::Material
          ? std::vector<std::string>(std::begin(kRheologyOptions), std::end(kRheologyOptions))
          : std::vector<std::string>{"history", "history-file"};
  if (std::find(extra.begin(), extra.end(), name) != extra.end()) return true;
  const ParamSpec* p = find_parameter(name);
  return p != nullptr && p->part == part && part != Part::History;
}

/// The history alone: --history (pairs or text) or --history-file.
void read_part_history(const Values& o, CaseInput& in) {
  if (o.has("history-file")) {
    require_record_alone(o);
    in.record = read_lab_record(o.text("history-file"));
    apply_lab_record(*in.record, in.c);
  } else if (o.has("history")) {
    in.c.history.segments = o["history"].kind == OptionValue::Kind::Pairs
                                ? history_of_pairs(o["history"].pairs)
                                : parse_history(o.text("history"));
  } else
    throw InvalidInput("history", "is required: one or more segments (W, T), or a lab record "
                                  "(history-file); got nothing");
}

CaseInput read_part(const Values& o, const OptionValues& given, Part part) {
  for (const auto& [name, value] : given)
    if (!of_part(name, part)) throw InvalidInput(name, "is not an option of this part of a case");
  CaseInput in;
  Case& c = in.c;
  if (part == Part::Indenter) {
    c.indenter.profile =
        o.has("profile") ? parse_profile(o.text("profile")) : Profile::of<Parabola>();
    require_profile_options(o, c.indenter.profile);
  }
  const auto in_part = [&](const ParamSpec& p) {
    return p.part == part && part != Part::History && p.applies_to(c.indenter.profile);
  };
  for (const auto& p : case_parameters())
    if (in_part(p) && p.required && !o.has(p.name))
      throw InvalidInput(p.name, "is required: " + describe(p) + ", got nothing");
  for (const auto& p : case_parameters())
    if (in_part(p)) p.set(c, o.has(p.name) ? parse_parameter(p, o[p.name]) : p.fallback);
  if (part == Part::Material) read_rheology(o, in);
  if (part == Part::Indenter) check_profile_limits(c.indenter);
  if (part == Part::History) read_part_history(o, in);
  return in;
}

} // namespace

CaseInput read_case_input(const OptionTexts& texts) {
  return read_case_input(as_values(texts));
}

CaseInput read_case_input(const OptionValues& values) {
  std::map<std::string, std::string> spelled;
  const OptionValues canonical = canonical_values(values, spelled);
  try {
    return read_canonical(Values(canonical, spelled));
  } catch (const InvalidInput& e) { // blame the option as the user spelled it
    const auto it = spelled.find(e.option());
    if (it == spelled.end()) throw;
    throw InvalidInput(it->second, e.what());
  }
}

CaseInput read_case_part(const OptionValues& values, Part part) {
  if (part != Part::Indenter && part != Part::Material && part != Part::History)
    throw std::logic_error("read_case_part: the indenter, the material or the history");
  return read_part(Values(values, {}), values, part);
}

std::string material_file_option(const std::string& path) {
  const std::string text = read_small_file("material", path, "a material file is a few lines");
  if (is_pyvisco_csv(text)) return "material";
  std::size_t at = 0;
  while (at < text.size()) { // the first line that is not blank or an Abaqus comment (**)
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string line = trimmed(text.substr(at, end - at));
    if (!line.empty() && line != "\r" && line.rfind("**", 0) != 0)
      return line[0] == '*' ? "material" : "prony-file";
    at = end + 1;
  }
  return "prony-file";
}

std::vector<std::string> case_option_spellings() {
  std::vector<std::string> names = case_option_names();
  for (const ParamAlias& a : parameter_aliases())
    names.emplace_back(a.alias);
  return names;
}

std::vector<const ParamSpec*> group_members(const std::string& group) {
  std::vector<const ParamSpec*> members;
  for (const auto& q : case_parameters())
    if (q.one_of && group == q.one_of) members.push_back(&q);
  return members;
}

std::string group_usage(const std::vector<const ParamSpec*>& members, const char* sep,
                        const char* last_sep) {
  std::string s;
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (i > 0) s += i + 1 == members.size() ? last_sep : sep;
    s += std::string("--") + members[i]->name + " " + members[i]->symbol;
  }
  return s;
}

std::string shown(const OptionValue& v) {
  if (v.kind == OptionValue::Kind::Number || v.kind == OptionValue::Kind::Flag) return text_of(v);
  return shown(text_of(v)); // (text, pairs, numbers: quoted or cut as a text)
}

std::string parameter_help_text(const ParamSpec& p) {
  std::string allowed = p.allowed();
  allowed[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(allowed[0])));
  std::string text = "(" + std::string(dim_name(p.dim)) + ") " + p.meaning + ". " + allowed;
  if (p.one_of)
    text += ". The " + std::string(p.one_of) + ": give exactly one of " +
            group_usage(group_members(p.one_of), ", ", " or ");
  else if (p.profile)
    text += std::string(p.required ? ", required" : "") + " with --profile " + p.profile + " only";
  else
    text += p.required ? ", required" : ". Default: " + format_number(p.fallback);
  if (const ParamAlias* a = alias_of(p.name))
    text += ". --" + std::string(a->alias) + " is accepted as its old spelling";
  return text;
}

std::string describe(const ParamSpec& p) {
  return std::string(p.meaning) + " (" + dim_name(p.dim) + "), " + p.allowed();
}

} // namespace mdrmap::cases
