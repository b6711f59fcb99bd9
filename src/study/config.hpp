#pragma once
// A parameter study: which cases to run and how. Read from an INI file,
// overridden from the command line, expanded to a case list. Pure C++: no
// MPI, no HDF5, no printing.
//
//   [grid]                  ; cartesian product, case order: last axis fastest
//   d   = 1e-3              ; a number,
//   R   = 1, 2, 5           ; a comma list,
//   tau = linspace:0.5:2:4  ; n evenly spaced values from lo to hi (inclusive),
//   v   = logspace:1e-2:1e2:5 ; n geometrically spaced values from lo to hi (values, not exponents)
//   v1_over_v = 0, 1e-4     ; or v1 = ... (absolute); exactly one of the two
//
//   [cases]                 ; instead of [grid]
//   file = cases.csv        ; columns d,R,tau,v,v1 (header line required), relative to the INI
//
//   [run]
//   t_end_over_tau = 6      ; window after the step, in units of tau
//                           ; (tau = 0: mdrmap::default_step_duration)
//   samples = 201
//   rtol = 1e-4
//   solver = auto           ; auto | exact | mdr | baseline
//   timeseries = false      ; store the full time series of every case
//   G = 1
//
// Every case is the seed's one-step history (stationary sliding at v, then
// v1 from t = 0; a StepRow) until the study is generated from the parameter
// table (issue 12).
//
// Comments start with ';' or '#'. Keys are case-sensitive.
#include <string>
#include <vector>

#include "core/case.hpp"

namespace mdrmap::study {

/// Bad config: InvalidInput whose option() is "section.key" (or "config"),
/// and whose message starts with "FILE:LINE: " when it comes from a file.
using ConfigError = InvalidInput;

struct Axis {
  std::string name; ///< d, R, tau, v, v1 or v1_over_v
  std::string spec; ///< as written
  std::vector<double> values;
  bool logarithmic = false; ///< from logspace (plots use log axes)
};

/// One case of the study, the seed's one-step experiment: d, R, tau, v, v1
/// from the grid or the case list, G from [run]. This is the study's row (and
/// the /cases columns of its map) until the study is generated from the
/// parameter table; case_for() turns it into a Case.
struct StepRow {
  double d = 0.0;   ///< indentation depth
  double R = 0.0;   ///< radius of curvature of the indenter
  double tau = 0.0; ///< relaxation time
  double v = 0.0;   ///< sliding velocity before the step (the history's v0)
  double v1 = 0.0;  ///< sliding velocity after the step (its one segment)
  double G = 1.0;   ///< shear modulus, from [run]
};

struct RunSettings {
  double t_end_over_tau = 6.0;
  long samples = 201;
  double rtol = 1e-4;
  std::string solver = "auto";
  bool timeseries = false;
  double G = 1.0;
};

struct StudyConfig {
  enum class Kind { Grid, Cases };
  Kind kind = Kind::Grid;
  std::vector<Axis> axes; ///< grid only: d, R, tau, v, v1|v1_over_v, in this order
  std::string cases_file; ///< cases only: path as resolved against the INI's directory
  RunSettings run;
  std::string source_path; ///< the INI file ("" when parsed from text)
  std::string source_text; ///< the INI file's text, for provenance
};

/// Parses INI text. base_dir resolves [cases] file. Unknown sections or keys
/// are errors that name the nearest known key ("did you mean 'samples'?").
StudyConfig parse_config(const std::string& text, const std::string& base_dir,
                         const std::string& source_name = "config");

/// Reads and parses a file; errors name the file and line.
StudyConfig load_config(const std::string& path);

/// Overrides one setting, as from the command line: key is "section.key"
/// (e.g. "run.samples", "grid.v1_over_v") and value as in the INI.
void apply_override(StudyConfig& c, const std::string& key, const std::string& value);

/// Parses one grid axis value: number, comma list, linspace:lo:hi:n,
/// logspace:lo:hi:n. Throws ConfigError("grid.<name>").
Axis parse_axis(const std::string& name, const std::string& spec);

/// The cases in study order, each validated (case_for); G from [run].
/// Throws ConfigError naming the axis, or the CSV file, line and column.
/// Holds every case: for tests and small uses (the runner takes them by
/// index from a CaseSource, study/case_source.hpp).
std::vector<StepRow> expand_cases(const StudyConfig& c);

/// Number of cases without building them (grid: product of axis sizes; a
/// case list is read through).
std::size_t case_count(const StudyConfig& c);

/// Checks a row as the seed's scene was checked, in its order: d, R, tau, v,
/// v1, G, then the derived scales. Throws InvalidInput whose option() is the
/// row's field (d, R, tau, v, v1, G).
void validate_row(const StepRow& r);

/// Observation window of a row: t_end_over_tau * tau (tau = 0:
/// default_step_duration).
double step_duration(const StudyConfig& c, const StepRow& r);

/// The case a row runs: step_case(d, R, tau, v, v1, G, step_duration,
/// run.samples), validated. Throws InvalidInput naming d, R, tau, v, v1, G,
/// t-end (the window) or samples, as the seed's scene and protocol did.
Case case_for(const StudyConfig& c, const StepRow& r);

/// Canonical text of everything that determines the results (axes values or
/// the case list's contents, and the [run] settings), normalized so that
/// formatting, comments and key order do not matter. Resume compares it. A
/// case list's contents are its number of cases and the SHA-256 of its rows
/// in normalized text (every value, in order): its size does not grow with
/// the list.
std::string canonical(const StudyConfig& c);

/// Reads a CSV case list (header d,R,tau,v,v1 in any column order; extra
/// columns are an error). Throws ConfigError naming file, line and column.
std::vector<StepRow> read_cases_csv(const std::string& path, double G);

} // namespace mdrmap::study
