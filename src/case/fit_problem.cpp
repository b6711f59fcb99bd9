#include "case/fit_problem.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <set>
#include <sstream>
#include <thread>

#include "case/text.hpp"
#include "core/model/params.hpp"
#include "core/model/temperature.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/dispatch.hpp"

namespace mdrmap::cases {
namespace {

constexpr long kMaxStarts = 25;
/// The largest rtol a fit takes: its difference step, 100 rtol, at most 0.1.
constexpr double kMaxRtol = 1e-3;

const std::vector<std::string> kMeasured = {"mu", "Fx", "FN", "d", "sd"};

std::string full(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

/// The comma-separated items of `text`, trimmed.
std::vector<std::string> items(const std::string& text, char sep = ',') {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string f;
  while (std::getline(in, f, sep))
    out.push_back(trimmed(f));
  return out;
}

/// The spectrum term k (1-based) and its field (0: modulus, 1: time) of a
/// name Gk or tauk; {0, 0} for any other name.
std::pair<std::size_t, int> term_of(const std::string& name) {
  for (const auto& [prefix, field] : {std::pair<std::string, int>{"G", 0}, {"tau", 1}}) {
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string k = name.substr(prefix.size());
    if (k.find_first_not_of("0123456789") != std::string::npos || k[0] == '0') continue;
    return {static_cast<std::size_t>(std::stoul(k)), field};
  }
  return {0, 0};
}

/// Rethrows an InvalidInput of the record (--history-file) as one of --data.
template <class F> auto as_data(F f) {
  try {
    return f();
  } catch (const InvalidInput& e) {
    if (e.option() == "history-file") throw InvalidInput("data", e.what());
    throw;
  }
}

/// The measured columns of a record that a fit uses, their scales and
/// whether an sd column weights them. Throws InvalidInput("data").
void read_columns(FitScene& s, bool load, const std::string& path) {
  const std::string at = path + ": ";
  for (const std::string q : {"mu", "Fx", "FN", "d"}) {
    const auto it = s.record.measured.find(q);
    if (it == s.record.measured.end()) continue;
    if (q == (load ? "FN" : "d"))
      throw InvalidInput(
          "data",
          at + "column " + q +
              (load ? " is the prescribed load --F0 under load control; fit mu, Fx or d"
                    : " is measured under load (--F0) only; at fixed depth fit mu, Fx or FN"));
    double big = 0.0;
    for (const double y : it->second)
      if (std::isfinite(y)) big = std::fmax(big, std::fabs(y));
    if (!(big > 0.0))
      throw InvalidInput(
          "data",
          at + "column " + q +
              " has no value other than nan or 0; give the measured values or drop the column");
    s.columns.push_back(q);
    s.scale[q] = big;
  }
  if (s.columns.empty())
    throw InvalidInput(
        "data", at + "no measured column: the header must name at least one of " +
                    std::string(load ? "mu, Fx, d (under --F0)" : "mu, Fx, FN (at fixed depth)"));
  s.has_sd = s.record.measured.count("sd") > 0;
  if (s.has_sd && s.columns.size() != 1)
    throw InvalidInput("data", at + "an sd column weights one measured column; this record has " +
                                   std::to_string(s.columns.size()));
}

/// The number of measured values of a record; checks its sd column.
std::size_t count_values(FitScene& s, const std::string& path) {
  std::size_t m = 0;
  for (std::size_t i = 0; i < s.record.t.size(); ++i) {
    const double y = s.record.measured[s.columns.front()][i];
    if (!std::isfinite(y)) continue;
    ++m;
    if (s.has_sd && !(s.record.measured["sd"][i] > 0.0))
      throw InvalidInput("data", path + ":" + std::to_string(s.record.line[i]) +
                                     ": sd must be a number > 0 where " + s.columns.front() +
                                     " is measured");
  }
  for (std::size_t c = 1; c < s.columns.size(); ++c)
    for (const double y : s.record.measured[s.columns[c]])
      m += std::isfinite(y) ? 1u : 0u;
  return m;
}

/// The free parameter a whole-spectrum modulus scale is fitted as: it
/// multiplies --G and every --prony term's modulus (start 1).
constexpr const char* kScale = "Gscale";

/// A free parameter of the table (R, beta, n, A, d, F0, G, tau, aT).
fit::FreeParameter table_parameter(const ParamSpec& q, const OptionTexts& texts,
                                   const CaseInput& start) {
  const std::string name = q.name;
  if (!q.applies_to(start.c.indenter.profile))
    throw InvalidInput("free", name + " is not a parameter of this case's indenter (--profile " +
                                   std::string(profile_name(start.c.indenter.profile)) + ")");
  const ParamAlias* alias = alias_of(name);
  if (q.one_of && !texts.count(name) && !(alias && texts.count(alias->alias)))
    throw InvalidInput("free", name + " is not this case's loading; free the one given (" +
                                   group_usage(group_members(q.one_of), ", ", " or ") + ")");
  if (name == "aT" && texts.count("T"))
    throw InvalidInput("free", "aT comes from --T and --wlf here; free T instead");
  fit::FreeParameter p;
  p.name = name;
  p.start = q.get(start.c);
  p.log = q.lo >= 0.0;
  if (p.log && !(p.start > 0.0))
    throw InvalidInput("free", name + " starts at " + format_number(p.start) +
                                   "; give it a start > 0 (--" + name + ")");
  return p;
}

/// A free term Gk (field 0) or tauk (field 1) of --prony.
fit::FreeParameter term_parameter(const std::string& name, std::size_t term, int field,
                                  const OptionTexts& texts) {
  if (!texts.count("prony"))
    throw InvalidInput("free", name + ": the case has no spectrum (--prony, --prony-file or "
                                      "--material)");
  const auto terms = items(texts.at("prony"));
  if (term > terms.size())
    throw InvalidInput("free", name + ": --prony has " + std::to_string(terms.size()) + " term(s)");
  fit::FreeParameter p;
  p.name = name;
  p.start =
      std::strtod(items(terms[term - 1], ':').at(static_cast<std::size_t>(field)).c_str(), nullptr);
  return p;
}

/// A spectrum from a file (--material: a card or pyvisco's CSV;
/// --prony-file) as the options it amounts to: --G, --prony and the card's
/// WLF as --wlf, read and checked as simulate reads them (with the first
/// record as the history), so that its terms and Gscale can be free like
/// those of a --prony spectrum.
OptionTexts explicit_spectrum(const OptionTexts& texts, const std::string& record) {
  if (!texts.count("material") && !texts.count("prony-file")) return texts;
  OptionTexts t = texts;
  t["history-file"] = record;
  const CaseInput in = as_data([&] { return read_case_input(t); });
  t = texts;
  for (const char* gone : {"material", "prony-file", "nu"})
    t.erase(gone);
  t["G"] = full(in.c.rheology.G);
  std::string terms;
  for (const Branch& b : in.c.rheology.branches)
    terms += (terms.empty() ? "" : ",") + full(b.G) + ":" + full(b.tau);
  t["prony"] = terms;
  if (in.temperature && !texts.count("wlf")) {
    const Wlf& w = in.temperature->wlf;
    t["wlf"] =
        full(w.C1) + ":" + full(w.C2) + ":" + full(w.Tref) + unit_suffix(in.temperature->unit);
  }
  return t;
}

/// The free parameter `name` (as typed: `raw`) with its start.
fit::FreeParameter free_parameter(const std::string& name, const std::string& raw,
                                  const OptionTexts& texts, const CaseInput& start) {
  const ParamSpec* q = find_parameter(name);
  const auto [term, field] = term_of(name);
  if (q && (q->part == Part::Indenter || q->part == Part::Material || q->part == Part::Loading))
    return table_parameter(*q, texts, start);
  if (!q && term > 0) return term_parameter(name, term, field, texts);
  fit::FreeParameter p;
  p.name = name;
  if (name == "T") {
    if (!texts.count("T")) throw InvalidInput("free", "T needs a start: give --T (and --wlf)");
    p.start = parse_temperature("T", texts.at("T")).value;
    p.log = false;
    return p;
  }
  if (name == kScale) {
    p.start = 1.0;
    return p;
  }
  throw InvalidInput("free", shown(raw) + " is not a parameter that can be fitted; free ones are "
                                          "the case's R (or beta, n, A), d or F0, G, tau, aT or "
                                          "T, a spectrum's Gk, tauk, and Gscale (every "
                                          "modulus times it)");
}

/// --prony's text with term k's field set to `value`, or (k = 0) every
/// modulus times `value`.
std::string prony_with(const std::string& text, std::size_t k, int field, double value) {
  auto terms = items(text);
  std::string joined;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    auto parts = items(terms[i], ':');
    if (k == 0) parts.at(0) = full(std::strtod(parts.at(0).c_str(), nullptr) * value);
    if (k == i + 1) parts.at(static_cast<std::size_t>(field)) = full(value);
    joined += (i ? "," : "") + parts.at(0) + ":" + parts.at(1);
  }
  return joined;
}

} // namespace

FitProblem::FitProblem(const FitSpec& spec) {
  if (spec.data.empty())
    throw InvalidInput("data", "is required: at least one lab record (--data FILE)");
  texts_ = explicit_spectrum(spec.texts, spec.data.front());
  CaseInput start;
  for (const auto& path : spec.data) {
    FitScene s;
    s.record = as_data([&] { return read_lab_record(path, kMeasured); });
    OptionTexts t = texts_;
    t["history-file"] = path;
    start = as_data([&] { return read_case_input(t); });
    load_ = start.c.loading.by_force();
    read_columns(s, load_, path);
    if (!scenes_.empty() && s.has_sd != scenes_.front().has_sd)
      throw InvalidInput("data", path + ": every record or none must have an sd column");
    m_ += count_values(s, path);
    scenes_.push_back(std::move(s));
  }
  rtol_ = start.rtol;
  if (rtol_ > kMaxRtol)
    throw InvalidInput("rtol", "a fit's model must be accurate well below its difference step "
                               "(100 rtol in ln(parameter), at most 0.1): rtol at most 0.001, "
                               "got " +
                                   format_number(rtol_));
  read_free(spec, start);
  read_bounds(spec);
  if (!spec.starts.empty()) {
    char* end = nullptr;
    const long n = std::strtol(spec.starts.c_str(), &end, 10);
    if (*end != '\0' || n < 1 || n > kMaxStarts)
      throw InvalidInput("starts", "must be an integer from 1 to " + std::to_string(kMaxStarts) +
                                       ", got " + shown(spec.starts));
    starts_ = static_cast<int>(n);
  }
  if (m_ <= params_.size())
    throw InvalidInput("data", std::to_string(m_) + " measured values for " +
                                   std::to_string(params_.size()) +
                                   " free parameters; a fit needs more values than parameters");
}

void FitProblem::read_free(const FitSpec& spec, const CaseInput& start) {
  std::set<std::string> seen;
  for (const auto& text : spec.free)
    for (const auto& raw : items(text)) {
      const std::string name = canonical_parameter_name(raw);
      if (name.empty()) throw InvalidInput("free", "an empty name in " + shown(text));
      if (!seen.insert(name).second) throw InvalidInput("free", name + " is named twice");
      params_.push_back(free_parameter(name, raw, texts_, start));
    }
  if (params_.empty())
    throw InvalidInput("free", "is required: the parameters to fit, e.g. --free R,aT");
  if (seen.count(kScale))
    for (const auto& name : seen)
      if (name == "G" || (term_of(name).first > 0 && term_of(name).second == 0))
        throw InvalidInput("free", std::string(kScale) + " scales every modulus; free it or " +
                                       name + ", not both");
}

void FitProblem::read_bounds(const FitSpec& spec) {
  for (const auto& text : spec.bounds) {
    const auto eq = text.find('='), colon = text.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos)
      throw InvalidInput("bounds", "must be NAME=LO:HI, got " + shown(text));
    const std::string name = canonical_parameter_name(trimmed(text.substr(0, eq)));
    fit::FreeParameter* p = nullptr;
    for (auto& q : params_)
      if (q.name == name) p = &q;
    if (!p) throw InvalidInput("bounds", name + " is not a free parameter (--free)");
    char* end = nullptr;
    const std::string lo = trimmed(text.substr(eq + 1, colon - eq - 1)),
                      hi = trimmed(text.substr(colon + 1));
    p->lo = std::strtod(lo.c_str(), &end);
    const bool lo_ok = !lo.empty() && *end == '\0';
    p->hi = std::strtod(hi.c_str(), &end);
    const bool hi_ok = !hi.empty() && *end == '\0';
    if (!lo_ok || !hi_ok || !std::isfinite(p->lo) || !std::isfinite(p->hi) || !(p->lo < p->hi) ||
        (p->log && !(p->lo > 0.0)))
      throw InvalidInput("bounds",
                         name + ": LO:HI must be finite numbers, LO < HI" +
                             std::string(p->log ? ", LO > 0 (a positive parameter)" : "") +
                             ", got " + shown(text));
    if (!(p->start >= p->lo && p->start <= p->hi))
      throw InvalidInput("bounds", name + ": the start " + format_number(p->start) +
                                       " is outside " + lo + ":" + hi);
  }
}

fit::Options FitProblem::options() const {
  fit::Options o;
  o.step = kStepPerRtol * rtol_;
  o.known_sd = scenes_.front().has_sd;
  o.starts = starts_;
  return o;
}

OptionTexts FitProblem::texts_at(const std::vector<double>& x, std::size_t k) const {
  OptionTexts t = texts_;
  t["history-file"] = scenes_.at(k).record.path;
  for (std::size_t i = 0; i < params_.size(); ++i) {
    const std::string& name = params_[i].name;
    const auto [term, field] = term_of(name);
    if (name == "T") {
      t["T"] = full(x[i]) + unit_suffix(parse_temperature("T", texts_.at("T")).unit);
    } else if (name == kScale) {
      const double G = texts_.count("G") ? std::strtod(texts_.at("G").c_str(), nullptr)
                                         : find_parameter("G")->fallback;
      t["G"] = full(G * x[i]);
      if (t.count("prony")) t["prony"] = prony_with(t.at("prony"), 0, 0, x[i]);
    } else if (term > 0 && !find_parameter(name)) {
      t["prony"] = prony_with(t.at("prony"), term, field, x[i]);
    } else {
      if (const ParamAlias* a = alias_of(name)) t.erase(a->alias);
      t[name] = full(x[i]);
    }
  }
  return t;
}

std::vector<std::map<std::string, std::vector<double>>>
FitProblem::run(const std::vector<double>& x) const {
  std::vector<std::map<std::string, std::vector<double>>> out;
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    const CaseInput in = read_case_input(texts_at(x, k));
    const RunResult res = run_case(CheckedCase(in.c), in.solver, rtol_);
    const std::vector<std::size_t> rows = record_rows(in.c);
    std::map<std::string, std::vector<double>> v;
    for (const auto& q : scenes_[k].columns) {
      const std::vector<double>& s = q == "mu"   ? res.series.mu
                                     : q == "Fx" ? res.series.Fx
                                     : q == "FN" ? res.series.FN
                                                 : res.series.d;
      for (const std::size_t r : rows)
        v[q].push_back(s.at(r));
    }
    out.push_back(std::move(v));
  }
  return out;
}

std::vector<std::map<std::string, std::vector<double>>>
FitProblem::model_values(const std::vector<double>& x) const {
  try {
    return run(x);
  } catch (const InvalidInput&) {
    return {};
  }
}

std::vector<double> FitProblem::residuals(const std::vector<double>& x) const {
  std::vector<std::map<std::string, std::vector<double>>> model;
  try {
    model = run(x);
  } catch (const InvalidInput&) {
    return {};
  } catch (const CaseAbandoned&) {
    return {};
  }
  std::vector<double> r;
  r.reserve(m_);
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    const FitScene& s = scenes_[k];
    for (const auto& q : s.columns) {
      const std::vector<double>& y = s.record.measured.at(q);
      for (std::size_t i = 0; i < y.size(); ++i) {
        if (!std::isfinite(y[i])) continue;
        const double w = s.has_sd ? s.record.measured.at("sd")[i] : s.scale.at(q);
        const double e = (model[k].at(q).at(i) - y[i]) / w;
        if (!std::isfinite(e)) return {};
        r.push_back(e);
      }
    }
  }
  return r;
}

std::vector<std::vector<double>>
SerialEvaluator::evaluate(const std::vector<std::vector<double>>& points) {
  std::vector<std::vector<double>> out;
  for (const auto& x : points)
    out.push_back(p_.residuals(x));
  return out;
}

std::vector<std::vector<double>>
ThreadEvaluator::evaluate(const std::vector<std::vector<double>>& points) {
  std::vector<std::vector<double>> out(points.size());
  std::vector<std::exception_ptr> errors(threads_);
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < threads_ && w < points.size(); ++w)
    pool.emplace_back([&, w] {
      try {
        for (std::size_t k = w; k < points.size(); k += threads_)
          out[k] = p_.residuals(points[k]);
      } catch (...) {
        errors[w] = std::current_exception();
      }
    });
  for (auto& t : pool)
    t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return out;
}

} // namespace mdrmap::cases
