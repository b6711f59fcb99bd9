// The cases of a study: each checked against the core's parameter table
// (validate_row, case_for), the checks of a whole grid, expanding and
// counting the cases, and the canonical text a resume compares. The INI
// reader, grid axes, case lists and the study schema are in study/ini.cpp,
// study/axes.cpp, study/case_list.cpp and study/study_schema.cpp.
#include "study/config.hpp"

#include <cstdio>

#include "core/params.hpp"
#include "core/solver.hpp"
#include "study/axes.hpp"
#include "study/case_source.hpp"
#include "study/config_detail.hpp"
#include "study/ini.hpp"

namespace mdrmap::study {

using namespace detail;

namespace {

constexpr double kMaxTimeseriesBytes = 64.0 * 1024.0 * 1024.0 * 1024.0;

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

/// Validates every case of a grid without expanding it: each axis value is in
/// range (parse_axis), and the combined checks of validate_row and the
/// window and samples checks are monotone in each parameter, so the corners of the
/// grid (smallest, largest, smallest positive value per axis) decide them.
void check_grid_corners(const StudyConfig& c, const WhereFn& where) {
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

std::vector<StepRow> expand_case_list(const StudyConfig& c) {
  std::vector<StepRow> cases = read_cases_csv(c.cases_file, c.run.G);
  check_case_list_size(c, cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i)
    check_listed_case(c, i, cases[i]);
  return cases;
}

std::vector<StepRow> expand_grid(const StudyConfig& c) {
  check_axes_shape(c);
  const std::size_t count = case_count(c);
  const auto& A = c.axes;
  const bool ratio = A[4].name == "v1_over_v";
  std::vector<StepRow> out;
  out.reserve(count);
  for_each_combination(A[0].values, A[1].values, A[2].values, A[3].values, A[4].values, ratio,
                       c.run.G, [&](const StepRow& s) {
                         check_grid_case(c, out.size(), s);
                         out.push_back(s);
                       });
  return out;
}

std::string canonical_grid(const StudyConfig& c) {
  check_axes_shape(c);
  std::string out = "[grid]\n";
  for (const auto& a : c.axes) {
    out += a.name + " =";
    for (std::size_t i = 0; i < a.values.size(); ++i)
      out += (i == 0 ? " " : ", ") + format_number(a.values[i]);
    out += "\n";
  }
  return out;
}

std::string canonical_run(const RunSettings& r) {
  std::string solver = r.solver;
  try {
    solver = solver_name(parse_solver(r.solver));
  } catch (const InvalidInput&) {
    // keep as is: a hand-made config; the runner will refuse it
  }
  return "[run]\nt_end_over_tau = " + format_number(r.t_end_over_tau) +
         "\nsamples = " + std::to_string(r.samples) + "\nrtol = " + format_number(r.rtol) +
         "\nsolver = " + solver + "\ntimeseries = " + (r.timeseries ? "true" : "false") +
         "\nG = " + format_number(r.G) + "\n";
}

} // namespace

void detail::check_listed_case(const StudyConfig& c, std::size_t i, const StepRow& s) {
  try {
    validate_case(c, s);
  } catch (const InvalidInput& e) {
    const std::string o = e.option() == "t-end" && s.tau > 0.0 ? "run.t_end_over_tau"
                          : e.option() == "samples"            ? "run.samples"
                                                               : "cases." + e.option();
    throw ConfigError(o, c.cases_file + ": case " + std::to_string(i + 1) + ": " +
                             case_problem(e, s, "v1"));
  }
}

void detail::check_case_list_size(const StudyConfig& c, std::size_t n) {
  check_timeseries_memory(c.run, static_cast<double>(n));
}

void detail::check_grid_case(const StudyConfig& c, std::size_t i, const StepRow& s) {
  try {
    validate_case(c, s);
  } catch (const InvalidInput& e) {
    const Where src{c.source_path.empty() ? "config" : c.source_path, 0};
    throw ConfigError(grid_option(e.option(), s, c.axes[4].name),
                      src.prefix() + "case " + std::to_string(i + 1) + ": " +
                          case_problem(e, s, c.axes[4].name));
  }
}

std::string detail::canonical_row(const StepRow& s) {
  return format_number(s.d) + "," + format_number(s.R) + "," + format_number(s.tau) + "," +
         format_number(s.v) + "," + format_number(s.v1) + "\n";
}

std::string detail::canonical_case_list(const StudyConfig& c, std::uint64_t count,
                                        const std::string& sha256) {
  return "mdrmap study 1\n[cases]\ncount = " + std::to_string(count) +
         "\nsha256 of d,R,tau,v,v1 rows = " + sha256 + "\n" + canonical_run(c.run);
}

void detail::check_study(const StudyConfig& c, const WhereFn& where) {
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

std::vector<StepRow> expand_cases(const StudyConfig& c) {
  return c.kind == StudyConfig::Kind::Cases ? expand_case_list(c) : expand_grid(c);
}

std::size_t case_count(const StudyConfig& c) {
  if (c.kind == StudyConfig::Kind::Cases) return scan_case_list(c, false).count;
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
  if (c.kind == StudyConfig::Kind::Cases) {
    const CaseListIndex index = scan_case_list(c, false);
    return canonical_case_list(c, index.count, index.sha256);
  }
  return "mdrmap study 1\n" + canonical_grid(c) + canonical_run(c.run);
}

} // namespace mdrmap::study
