#pragma once
// A parameter study: which cases to run and how. Read from an INI file,
// overridden from the command line, expanded to cases. Pure C++: no MPI, no
// HDF5, no printing. Every key: docs/reference/config.md
// (generated from study/config_keys.hpp); the syntax:
//
//   [grid]                  ; the case parameters of the core's table
//   F0  = 1e-3              ; d (depth control) or F0 (load control), one of them
//   R   = 1, 2, 5           ; a number, a comma list,
//   tau = linspace:0.5:2:4  ; n evenly spaced values from lo to hi (inclusive),
//   v   = logspace:1e-2:1e2:5 ; n geometrically spaced values (values, not exponents)
//   G   = 1                 ; optional (default 1; required with a spectrum)
//   G1 = 2                  ; optional: a relaxation spectrum's terms Gk, tauk
//   tau1 = 0.01             ;   (k = 1..N, N <= 32, both of each term)
//   aT = 1e-3               ; optional: the shift factor, or instead
//   temperature = 20, 40    ;   a temperature, with [run] wlf (or 20C, 40C; 293.15K, ...)
//
//   [history]               ; segments k = 1..K after stationary sliding at v
//   w1_over_v   = 0         ; velocity: wk, or wk_over_v (times v)
//   T1_over_tau = 1, 10     ; duration: Tk, or Tk_over_tau (times the time scale)
//
//   [cases]                 ; instead of [grid]
//   file = cases.csv        ; columns d|F0, R, tau, v, [G], w1, T1, ... (or the seed's v1)
//
//   [run]                   ; one value per key; every key, its values and default:
//   samples = 101           ;   study/config_keys.cpp (mdrmap help config)
//
// Every key of [grid] and [history] is a column of the study; in a grid each
// column is an axis (case order: C order over the columns in column order, the
// last fastest). The optional columns aT (or temperature), Gk and tauk are
// columns, and /cases datasets of the map, only where the study gives them;
// G always is (default 1, none with a spectrum). Relative durations (TK_over_tau) are in units of
// the case's time scale, scales(c).time: the longest relaxation time shifted
// by aT, aT max(tau, tauk) (tau for a Kelvin material at aT = 1). The seed's one-step form is still
// read: [grid] v1 or v1_over_v is the column w1 or w1_over_v, [run] t_end_over_tau the column
// T1_over_tau and [run] G the column G.
//
// FN, the old spelling of F0 (the prescribed normal load), is read as F0 as a
// key, an override or a case list's column; giving both is an error.
//
// Comments start with ';' or '#'. Keys are case-sensitive.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <optional>

#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "core/model/temperature.hpp"
#include "core/model/wlf.hpp"
#include "core/solvers/checked_case.hpp"

namespace mdrmap::study {

/// Bad config: InvalidInput whose option() is "section.key" (or "config"),
/// and whose message starts with "FILE:LINE: " when it comes from a file.
using ConfigError = InvalidInput;

/// What a study column sets in a case: a parameter of the core's table, a
/// term of the relaxation spectrum (Gk, tauk), the temperature (the shift aT
/// by [run] wlf), or a history segment's velocity or duration, absolute or
/// relative.
struct Column {
  enum class Kind {
    Param,
    Velocity,
    VelocityOverV,
    Duration,
    DurationOverTau,
    BranchModulus,
    BranchTime,
    Temperature
  };
  Kind kind = Kind::Param;
  const ParamSpec* param = nullptr; ///< Param: the table's entry
  std::size_t segment = 0;          ///< history columns: the segment, from 1
  std::size_t branch = 0;           ///< Gk, tauk: the term k, from 1
  bool history() const {
    return kind == Kind::Velocity || kind == Kind::VelocityOverV || kind == Kind::Duration ||
           kind == Kind::DurationOverTau;
  }
  bool spectrum() const { return kind == Kind::BranchModulus || kind == Kind::BranchTime; }
};

/// One column of a study: its values (a grid axis), or, in a case list, the
/// values of a CSV column (`listed`) or the one value the config gives it.
struct Axis {
  std::string name;    ///< the key as written: d, F0 (or FN), R, tau, G, v, w1, T1_over_tau, ...
  std::string section; ///< where it is set: grid, history or run (the seed's G, t_end_over_tau)
  std::string spec;    ///< as written
  std::vector<double> values;
  bool logarithmic = false; ///< from logspace (plots use log axes)
  bool listed = false;      ///< case list: the values are a CSV column
  bool by_default = false;  ///< not given: the table's default (G = 1)
  Column column;
  TempUnit unit = TempUnit::None; ///< temperature: the values' unit (25C: C; bare: TREF's)
  std::string given_by;           ///< "run.material": a value of the card, not a key of its own
  /// "grid.R", "history.T1_over_tau", "run.G" (or given_by): the option that sets it.
  std::string option() const { return given_by.empty() ? section + "." + name : given_by; }
};

/// A study's case as written: one value per column (StudyConfig::axes), in
/// column order. case_for() makes it a Case.
using Row = std::vector<double>;

struct RunSettings {
  long samples = 201;
  Spacing spacing = Spacing::Linear;
  double decades = 4.0;
  double rtol = 1e-4;
  std::string solver = "auto";
  bool timeseries = false;
  std::optional<Wlf> wlf;             ///< the WLF constants of a temperature column
  TempUnit wlf_unit = TempUnit::None; ///< TREF's (and the temperature column's) unit
  bool allow_large_shift = false;     ///< take |log10 aT| > 12 of a temperature
  Profile profile =
      Profile::of<Parabola>(); ///< the indenter of every case; its parameters are columns
  std::string material;        ///< [run] material: the card's path, resolved ("" without one)
  std::string material_text;   ///< the card's text (the map's /provenance/material_card)
  bool card_wlf = false;       ///< wlf is the card's *TRS (no [run] wlf of its own)
};

struct StudyConfig {
  enum class Kind { Grid, Cases };
  Kind kind = Kind::Grid;
  /// The study's columns in column order: the loading, R, tau, G, [G1, tau1,
  /// G2, tau2, ...], [aT or temperature], v, then w1, T1, w2, T2, ... (each
  /// velocity and duration absolute or relative).
  std::vector<Axis> axes;
  std::string cases_file; ///< cases only: path as resolved against the INI's directory
  RunSettings run;
  std::string source_path; ///< the INI file ("" when parsed from text)
  std::string source_text; ///< the INI file's text, for provenance

  /// Number of history segments K.
  std::size_t segments() const;
  /// Load control (an F0 column) or depth control (d).
  bool by_force() const;
};

/// Parses INI text. base_dir resolves [cases] file. Unknown sections or keys
/// are errors that name the nearest known key ("did you mean 'samples'?").
StudyConfig parse_config(const std::string& text, const std::string& base_dir,
                         const std::string& source_name = "config");

/// Reads and parses a file; errors name the file and line.
StudyConfig load_config(const std::string& path);

/// Reads a file, sets the command-line overrides (as apply_overrides), then
/// makes the study whole and checks it once: the overrides may supply what
/// the file lacks (a file without [history] takes its segments from
/// "history.w1", "history.T1_over_tau", ...). A problem is located at the
/// command line when an override set its key, else in the file.
StudyConfig load_config(const std::string& path,
                        const std::vector<std::pair<std::string, std::string>>& overrides);

/// Overrides one setting, as from the command line: key is "section.key"
/// (e.g. "run.samples", "grid.F0", "history.T1_over_tau") and value as in the
/// INI. A [grid] or [history] key the config does not have adds the column.
void apply_override(StudyConfig& c, const std::string& key, const std::string& value);

/// Several overrides, in order, checked together at the end (a new segment
/// takes its velocity and its duration: "history.w3", "history.T3").
void apply_overrides(StudyConfig& c,
                     const std::vector<std::pair<std::string, std::string>>& settings);

/// The keys apply_override takes, as "section.key" (history keys for
/// segments 1 to 9; any segment is accepted).
std::vector<std::string> override_keys();

/// What a column name means: a parameter of the core's table (not the
/// sampling), a spectrum's Gk, tauk (k = 1..32), temperature, wK, wK_over_v,
/// TK, TK_over_tau (K >= 1), or the seed's v1 and v1_over_v. False for
/// anything else.
bool parse_column(const std::string& name, Column& out);

/// Parses one column's values (a number, comma list, linspace:lo:hi:n or
/// logspace:lo:hi:n) and checks each against the column's range. Throws
/// ConfigError(section.name).
Axis parse_axis(const std::string& section, const std::string& name, const std::string& spec);

/// The cases in study order, each validated (case_for). Holds every case:
/// for tests and small uses (the runner takes them by index from a
/// CaseSource, study/case_source.hpp).
std::vector<Row> expand_cases(const StudyConfig& c);

/// Number of cases without building them (grid: product of axis sizes; a
/// case list is read through).
std::size_t case_count(const StudyConfig& c);

/// The case a row runs, validated: each column's value against its range,
/// the spectrum's terms, aT from the temperature (WLF), relative values
/// resolved (wK_over_v * v, TK_over_tau * the time scale aT max(tau, tauk);
/// with a time scale of 0, six contact half-widths at the slower moving
/// velocity), the sampling of [run], then the whole case. Throws InvalidInput whose option() is the
/// column's option ("grid.R", "history.T1_over_tau", ...) or "run.samples".
Case case_for(const StudyConfig& c, const Row& r);
/// The same, marked as checked: what the solvers take without checking again.
CheckedCase checked_case_for(const StudyConfig& c, const Row& r);

/// "F0 = 0.001, R = 1, ...": a row for a message.
std::string describe(const StudyConfig& c, const Row& r);

/// Canonical text of everything that determines the results (columns and
/// their values or the case list's contents, and the [run] settings),
/// normalized so that formatting, comments and key order do not matter.
/// Resume compares it. A case list's contents are its columns, its number
/// of cases and the SHA-256 of its rows in normalized text.
std::string canonical(const StudyConfig& c);

} // namespace mdrmap::study
