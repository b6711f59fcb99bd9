// The cases of a study: each row made a Case and checked against the core's
// parameter table (case_for), the checks of a whole grid, expanding and
// counting the cases, and the canonical text a resume compares. The INI
// reader, grid axes, columns, case lists and the study schema are in
// study/ini.cpp, study/axes.cpp, study/columns.cpp, study/case_list.cpp and
// study/study_schema.cpp.
#include "study/config.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/model/params.hpp"
#include "core/model/scales.hpp"
#include "core/solvers/dispatch.hpp"
#include "study/axes.hpp"
#include "study/case_source.hpp"
#include "study/columns.hpp"
#include "study/config_detail.hpp"
#include "study/ini.hpp"

namespace mdrmap::study {

using namespace detail;

namespace {

constexpr double kMaxTimeseriesBytes = 64.0 * 1024.0 * 1024.0 * 1024.0;
/// Grids whose corners (extremes of every axis) are more cases than this are
/// checked case by case only (the runner's preflight checks every case).
constexpr double kMaxCorners = 4096;

/// Checks x against its column's range. Throws InvalidInput(option).
void check_value(const Axis& a, double x) {
  try {
    column_spec(a.column).check(x);
  } catch (const InvalidInput& e) {
    throw InvalidInput(a.option(), a.name + " " + e.what());
  }
}

/// Checks a resolved history value against the segment's own range; `how`
/// (called on failure only) says how it was resolved.
template <class How> void check_resolved(const Axis& a, const ParamSpec& spec, double x, How how) {
  try {
    spec.check(x);
  } catch (const InvalidInput& e) {
    throw InvalidInput(a.option(), how() + " " + e.what());
  }
}

/// Segment k's (0-based) velocity from its column's value.
void set_velocity(Case& c, const Axis& a, double x) {
  Segment& s = c.history.segments[a.column.segment - 1];
  if (a.column.kind == Column::Kind::Velocity) {
    s.w = x;
    return;
  }
  s.w = x * c.history.v0;
  check_resolved(a, segment_velocity_spec(), s.w,
                 [&] { return "w" + std::to_string(a.column.segment) + " = " + a.name + " * v"; });
}

/// Segment k's duration from its column's value (velocities already set).
/// Relative to the case's time scale (scales(c).time: aT max(tau, tauk), tau
/// for Kelvin at aT = 1); with a time scale of 0, six contact half-widths
/// at the slower moving velocity of the segment and the one before it.
void set_duration(Case& c, const Axis& a, double x) {
  const std::size_t k = a.column.segment - 1;
  Segment& s = c.history.segments[k];
  const auto T_name = [&] { return "T" + std::to_string(a.column.segment); };
  const double time = scales(c).time;
  if (a.column.kind == Column::Kind::Duration) {
    s.T = x;
  } else if (time > 0.0) {
    s.T = x * time;
    check_resolved(a, segment_duration_spec(), s.T, [&] {
      return T_name() + " = " + a.name + " * " +
             (c.rheology.kelvin() && c.rheology.aT == 1.0 ? "tau"
                                                          : "aT max(tau, tauk) (the time scale)");
    });
  } else {
    const double w0 = c.history.before(k), w1 = s.w;
    const double slow = (w0 > 0.0 && w1 > 0.0) ? std::min(w0, w1) : std::max(w0, w1);
    if (!(slow > 0.0))
      throw InvalidInput(a.option(), a.name +
                                         " is relative to tau, and with tau = 0 a hold after "
                                         "a hold has no time scale; give " +
                                         T_name() + " instead");
    s.T = 6.0 * c.edge_scale() / slow;
    check_resolved(a, segment_duration_spec(), s.T, [&] {
      return "with tau = 0 the default duration " + T_name() +
             " = 6 a / min(w) (a = " + (c.loading.by_force() ? "a0" : "a1 = sqrt(R d)") + ")";
    });
  }
}

/// The option of the column a core option (a table name, a term's G3 or
/// tau3, "history") names; aT is the temperature's where it gave aT.
std::string column_option(const StudyConfig& c, const std::string& core) {
  for (const Axis& a : c.axes) {
    const Column& col = a.column;
    const std::string name =
        col.history() ? "history"
                      : (col.kind == Column::Kind::Temperature ? "aT" : column_name(col));
    if (core == name) return a.option();
  }
  if (core == "samples") return "run.samples";
  if (core == "log-decades") return "run.decades";
  return "config";
}

/// Rethrows a failed case check located: "SOURCE: case i: <what> (case ...)".
[[noreturn]] void case_problem(const StudyConfig& c, const InvalidInput& e, const Row& r,
                               const std::string& prefix) {
  throw ConfigError(e.option(), prefix + e.what() + " (case " + describe(c, r) + ")");
}

/// Refuses time series that would not fit in 64 GiB. Throws ConfigError("run.timeseries").
void check_timeseries_memory(const StudyConfig& c, double cases) {
  if (!c.run.timeseries) return;
  const double series = c.by_force() ? 7.0 : 5.0;
  const double samples = static_cast<double>(c.run.samples) * static_cast<double>(c.segments());
  const double bytes = samples * cases * series * 8.0;
  if (bytes > kMaxTimeseriesBytes) {
    char gib[64];
    std::snprintf(gib, sizeof gib, "%.1f", bytes / (1024.0 * 1024.0 * 1024.0));
    throw ConfigError("run.timeseries",
                      "timeseries = true needs " + format_number(samples) + " samples x " +
                          format_number(cases) + " cases x " + format_number(series) +
                          " series x 8 bytes = " + gib +
                          " GiB, more than 64 GiB; lower samples, use fewer cases or set "
                          "timeseries = false");
  }
}

/// Checks the corners of a grid (smallest, largest, smallest positive value
/// of every axis): the core's checks are monotone in each parameter, so they
/// fail there first. A located error without a case number.
void check_grid_corners(const StudyConfig& c, const WhereFn& where) {
  std::vector<std::vector<double>> ext;
  double n = 1.0;
  for (const Axis& a : c.axes) {
    ext.push_back(extremes(a.values));
    n *= static_cast<double>(ext.back().size());
  }
  if (n > kMaxCorners) return;
  Row r(c.axes.size());
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
    std::size_t rest = i;
    for (std::size_t j = c.axes.size(); j-- > 0;) {
      r[j] = ext[j][rest % ext[j].size()];
      rest /= ext[j].size();
    }
    try {
      case_for(c, r);
    } catch (const InvalidInput& e) {
      case_problem(c, e, r, where(e.option()).prefix());
    }
  }
}

/// The solvers that take a study's loading and spectrum, "a, b or c".
std::string solvers_taking(const ModelNeeds& needs) {
  std::vector<std::string> names;
  for (const SolverKind k : kSolverKinds)
    if (solver_handles(k, needs)) names.emplace_back(solver_name(k));
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return out;
}

/// Refuses a solver that does not solve the study's loading or its spectrum
/// (the core says which do; auto picks among those that do: run_case refuses
/// a case none handles). Throws ConfigError("run.solver") without location.
void check_solver(const StudyConfig& c) {
  SolverKind kind = SolverKind::Auto;
  try {
    kind = parse_solver(c.run.solver);
  } catch (const InvalidInput& e) {
    throw ConfigError("run.solver", std::string("solver ") + e.what());
  }
  std::string terms;
  for (const Axis& a : c.axes)
    if (a.column.spectrum()) terms += (terms.empty() ? "" : ", ") + a.name;
  const ModelNeeds needs{c.by_force(), !terms.empty()};
  if (solver_handles(kind, needs)) return;
  const std::string why =
      !solver_handles(kind, ModelNeeds{c.by_force(), false})
          ? (c.by_force() ? "load control (the study prescribes the normal load F0)"
                          : "depth control (the study prescribes the depth d)")
          : "a relaxation spectrum (the study has " + terms + ")";
  throw ConfigError("run.solver", std::string("solver ") + solver_name(kind) + " does not solve " +
                                      why + "; give solver = " + solvers_taking(needs));
}

std::string canonical_values(const Axis& a) {
  const std::string name = stored_name(a); // FN and F0: one study
  if (a.listed) return name + " = (listed)\n";
  std::string out = name + " =";
  for (std::size_t i = 0; i < a.values.size(); ++i)
    out += (i == 0 ? " " : ", ") + format_number(a.values[i]) + unit_suffix(a.unit);
  return out + "\n";
}

/// A material card's text, each line behind "| " (a resume compares the
/// text: a changed card is another study); "" without one.
std::string canonical_card(const std::string& text) {
  if (text.empty()) return "";
  std::string out = "[material card]\n| ";
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') continue;
    out += text[i];
    if (text[i] == '\n' && i + 1 < text.size()) out += "| ";
  }
  return out.back() == '\n' ? out : out + "\n";
}

std::string canonical_run(const RunSettings& r) {
  std::string solver = r.solver;
  try {
    solver = solver_name(parse_solver(r.solver));
  } catch (const InvalidInput&) {
    // keep as is: a hand-made config; the runner will refuse it
  }
  return "[run]\nsamples = " + std::to_string(r.samples) +
         "\nspacing = " + (r.spacing == Spacing::Log ? "log" : "linear") +
         "\ndecades = " + format_number(r.decades) + "\nrtol = " + format_number(r.rtol) +
         "\nsolver = " + solver + "\ntimeseries = " + (r.timeseries ? "true" : "false") + "\n" +
         (r.wlf ? "wlf = " + format_wlf(*r.wlf) + unit_suffix(r.wlf_unit) + "\n"
                : std::string()) + // where given only
         (r.allow_large_shift ? "allow_large_shift = true\n" : std::string()) +
         (r.profile != Profile::of<Parabola>()
              ? std::string("profile = ") + profile_name(r.profile) + "\n"
              : std::string()) + // the parabola's config as before
         canonical_card(r.material_text);
}

std::string canonical_columns(const StudyConfig& c) {
  std::string out = "[columns]\n";
  for (const Axis& a : c.axes)
    out += canonical_values(a);
  return out;
}

} // namespace

std::size_t StudyConfig::segments() const {
  std::size_t k = 0;
  for (const Axis& a : axes)
    k = std::max(k, a.column.segment);
  return k;
}

bool StudyConfig::by_force() const {
  for (const Axis& a : axes)
    if (a.column.kind == Column::Kind::Param && a.column.param->part == Part::Loading)
      return a.column.param->dim == Dim::Force;
  return false;
}

namespace {

/// The number of terms of the study's spectrum (the highest k of Gk, tauk).
std::size_t spectrum_terms(const StudyConfig& c) {
  std::size_t n = 0;
  for (const Axis& a : c.axes)
    n = std::max(n, a.column.branch);
  return n;
}

/// Sets a column that is not of the history: a table parameter, a term's
/// modulus or time, or aT from the temperature by [run] wlf.
void set_column_value(const StudyConfig& c, Case& out, const Axis& a, double x) {
  if (a.column.kind == Column::Kind::BranchModulus)
    out.rheology.branches[a.column.branch - 1].G = x;
  else if (a.column.kind == Column::Kind::BranchTime)
    out.rheology.branches[a.column.branch - 1].tau = x;
  else if (a.column.kind == Column::Kind::Temperature) {
    if (!c.run.wlf) // complete_columns refuses it: a hand-made config
      throw ConfigError(a.option(), "temperature needs [run] wlf = C1:C2:TREF");
    try {
      out.rheology.aT =
          checked_shift(UnitWlf{*c.run.wlf, c.run.wlf_unit}, Temperature{x, a.unit}, a.option(),
                        c.run.allow_large_shift, "[run] allow_large_shift = true");
    } catch (const InvalidInput& e) {
      const std::string what = e.what(); // the large shift's message says its WLF
      throw InvalidInput(a.option(), "temperature " + what +
                                         (what.find("(WLF ") != std::string::npos
                                              ? std::string()
                                              : " (WLF " + format_wlf(*c.run.wlf) +
                                                    unit_suffix(c.run.wlf_unit) + ")"));
    }
  } else
    a.column.param->set(out, x);
}

} // namespace

Case case_for(const StudyConfig& c, const Row& r) {
  return checked_case_for(c, r).take();
}

CheckedCase checked_case_for(const StudyConfig& c, const Row& r) {
  if (r.size() != c.axes.size()) // a caller's bug, not an input's
    throw std::invalid_argument("case_for: a row of " + std::to_string(r.size()) +
                                " values for a study of " + std::to_string(c.axes.size()) +
                                " columns");
  Case out;
  out.history.segments.assign(c.segments(), Segment{});
  out.rheology.branches.assign(spectrum_terms(c), Branch{});
  for (std::size_t i = 0; i < c.axes.size(); ++i) {
    check_value(c.axes[i], r[i]);
    if (!c.axes[i].column.history()) set_column_value(c, out, c.axes[i], r[i]);
  }
  for (std::size_t i = 0; i < c.axes.size(); ++i) {
    const Column::Kind k = c.axes[i].column.kind;
    if (k == Column::Kind::Velocity || k == Column::Kind::VelocityOverV)
      set_velocity(out, c.axes[i], r[i]);
  }
  out.indenter.profile = c.run.profile;
  out.sampling.samples = c.run.samples;
  out.sampling.spacing = c.run.spacing;
  out.sampling.decades = c.run.decades;
  try {
    Case probe = out; // the derived scales (a, 16 G d^2) before the durations use them
    for (Segment& s : probe.history.segments)
      s.T = 1.0;
    CheckedCase checked(std::move(probe));
    for (std::size_t i = 0; i < c.axes.size(); ++i)
      if (c.axes[i].column.history() && !(c.axes[i].column.kind == Column::Kind::Velocity ||
                                          c.axes[i].column.kind == Column::Kind::VelocityOverV))
        set_duration(out, c.axes[i], r[i]);
    return std::move(checked).with_durations(out.history.segments); // (the history checked again)
  } catch (const InvalidInput& e) {
    if (e.option().find('.') != std::string::npos) throw; // a column's own message
    const std::string option = column_option(c, e.option());
    const std::string name = option.substr(option.find('.') + 1);
    if (name == "temperature" && e.option() == "aT") // the shift the temperature gave
      throw InvalidInput(option, "temperature gives aT = " + format_number(out.rheology.aT) +
                                     ", and aT " + e.what());
    throw InvalidInput(option, name + " " + e.what());
  }
}

std::string describe(const StudyConfig& c, const Row& r) {
  std::string s;
  for (std::size_t i = 0; i < c.axes.size() && i < r.size(); ++i)
    s += (i ? ", " : "") + c.axes[i].name + " = " + format_number(r[i]);
  return s;
}

void detail::check_listed_case(const StudyConfig& c, std::size_t i, const Row& r) {
  try {
    case_for(c, r);
  } catch (const InvalidInput& e) {
    case_problem(c, e, r, c.cases_file + ": case " + std::to_string(i + 1) + ": ");
  }
}

void detail::check_case_list_size(const StudyConfig& c, std::size_t n) {
  check_timeseries_memory(c, static_cast<double>(n));
}

void detail::check_grid_case(const StudyConfig& c, std::size_t i, const Row& r) {
  try {
    case_for(c, r);
  } catch (const InvalidInput& e) {
    const Where src{c.source_path.empty() ? "config" : c.source_path, 0};
    case_problem(c, e, r, src.prefix() + "case " + std::to_string(i + 1) + ": ");
  }
}

std::string detail::canonical_row(const StudyConfig& c, const Row& r) {
  std::string out;
  for (std::size_t i = 0; i < c.axes.size(); ++i)
    if (c.axes[i].listed) out += (out.empty() ? "" : ",") + format_number(r[i]);
  return out + "\n";
}

std::string detail::canonical_case_list(const StudyConfig& c, std::uint64_t count,
                                        const std::string& sha256) {
  return "mdrmap study 2\n" + canonical_columns(c) + "[cases]\ncount = " + std::to_string(count) +
         "\nsha256 of the listed columns' rows = " + sha256 + "\n" + canonical_run(c.run);
}

void detail::check_study(const StudyConfig& c, const WhereFn& where) {
  try {
    check_solver(c);
  } catch (const InvalidInput& e) {
    rethrow_at(e, where(e.option()));
  }
  if (c.kind != StudyConfig::Kind::Grid) return; // case lists: checked when read
  try {
    check_grid_size(c);
    check_timeseries_memory(c, grid_size(c));
  } catch (const InvalidInput& e) {
    rethrow_at(e, where(e.option()));
  }
  check_grid_corners(c, where);
}

std::vector<Row> expand_cases(const StudyConfig& c) {
  const CaseSource source(c);
  std::vector<Row> out;
  source.rows(0, source.size(), out);
  if (c.kind == StudyConfig::Kind::Cases) {
    check_case_list_size(c, out.size());
    for (std::size_t i = 0; i < out.size(); ++i)
      check_listed_case(c, i, out[i]);
  } else {
    for (std::size_t i = 0; i < out.size(); ++i)
      check_grid_case(c, i, out[i]);
  }
  return out;
}

std::size_t case_count(const StudyConfig& c) {
  if (c.kind == StudyConfig::Kind::Cases) return scan_case_list(c, false).count;
  check_grid_size(c);
  std::size_t n = 1;
  for (const auto& a : c.axes)
    n *= a.values.size(); // <= 1e9: no overflow
  return n;
}

std::string canonical(const StudyConfig& c) {
  if (c.kind == StudyConfig::Kind::Cases) {
    const CaseListIndex index = scan_case_list(c, false);
    return canonical_case_list(c, index.count, index.sha256);
  }
  return "mdrmap study 2\n" + canonical_columns(c) + canonical_run(c.run);
}

} // namespace mdrmap::study
