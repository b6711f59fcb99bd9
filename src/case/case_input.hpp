#pragma once
// A case of `mdrmap simulate` from named option texts: the table's parameters
// (core/model/params.hpp), the history (--history or --v1 [--t-end]), the sampling
// (--spacing and the table's sampling parameters) and how to run it (--rtol,
// --solver). Shared by the command line and the Python module (src/python),
// so that both accept, refuse and build the same cases with the same
// messages: a value that is not allowed throws InvalidInput naming the option
// as the CLI spells it (without dashes), or an empty option where no single
// option is at fault (e.g. neither or both of --d and --F0). The old
// spellings of the table's parameters (--FN for --F0) are read as theirs.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "case/lab_record.hpp"
#include "case/option_value.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "core/model/temperature.hpp"
#include "core/model/wlf.hpp"
#include "core/solvers/dispatch.hpp"
#include "material/text.hpp"

namespace mdrmap::cases {

inline constexpr double kDefaultRtol = 1e-4;

/// Option name (as the CLI spells it, without dashes) -> its text as typed.
using OptionTexts = std::map<std::string, std::string>;

/// A temperature and the WLF constants that made the case's aT (--T, --wlf).
struct TemperatureInput {
  double T = 0.0; ///< in the unit of wlf.Tref (converted from --T's)
  Wlf wlf;
  TempUnit unit = TempUnit::None; ///< of T and Tref, where either was given one
};

/// A checked case and how to run it.
struct CaseInput {
  Case c;
  SolverKind solver = SolverKind::Auto;
  double rtol = kDefaultRtol;
  std::optional<TemperatureInput> temperature; ///< given: c.rheology.aT is its WLF shift
  std::optional<LabRecord> record;             ///< --history-file: the record that made the history
  std::vector<std::string> notes; ///< what an input gave that does not enter (a card's k_i)
};

/// Every option read_case_input knows, in the order of simulate's help: the
/// table's case parameters, the spectrum and temperature (prony, prony-file,
/// T, wlf), v1, t-end, history, the table's sampling parameters, spacing,
/// rtol, solver.
std::vector<std::string> case_option_names();

/// case_option_names() and the old spellings of the table's parameters
/// (parameter_aliases(): FN), which read_case_input takes as theirs.
std::vector<std::string> case_option_spellings();

/// Builds and checks a case from the texts of its options, in the CLI's
/// order of checks; an alias's text (FN) is its parameter's (F0), and an
/// error about it names the option as spelled. Both spellings of one
/// parameter are refused (option ""). Throws InvalidInput.
CaseInput read_case_input(const OptionTexts& texts);

/// read_case_input of typed values (case/option_value.hpp): a number given as
/// a number is that double (a count must be whole), pairs are the history's
/// segments or the spectrum's terms, three numbers the WLF constants, a flag
/// allow-large-shift; a text is read as the command line reads it. The
/// checks, their order and their messages are the texts'.
CaseInput read_case_input(const OptionValues& values);

/// One part of a case alone, read and checked as read_case_input reads it
/// (the same messages), without the checks that need the other parts (the
/// scales, the default window): Part::Indenter (profile and its
/// parameters), Part::Material (the table's material parameters, the
/// spectrum, the temperature), Part::History (history, or history-file).
/// The part is set in the result's case, the other parts are defaults.
/// Throws InvalidInput; an option of another part is refused.
CaseInput read_case_part(const OptionValues& values, Part part);

/// The option a material file goes under: "material" for an Abaqus card
/// (its first line that is not blank or a comment ** is a keyword *...)
/// or pyvisco's CSV, "prony-file" for a spectrum file (columns by name).
/// Throws InvalidInput("material") where the file cannot be read.
std::string material_file_option(const std::string& path);

/// The members of the table's one_of group `group`, in the table's order.
std::vector<const ParamSpec*> group_members(const std::string& group);

/// "--d D or --F0 F0": the members with their symbols, `sep` between all
/// but the last two, `last_sep` between those.
std::string group_usage(const std::vector<const ParamSpec*>& members, const char* sep,
                        const char* last_sep);

/// The value as typed, quoted (material/text.hpp).
using material::shown;

/// A value as given, for a message: a text as shown(text), a number as its
/// shortest text, pairs as W:T,W:T,..., numbers as A:B:C, a flag true or false.
std::string shown(const OptionValue& v);

/// A parameter's entry in simulate's help: "(unit) meaning. Allowed range",
/// then ", required", ". Default: X" or its one_of group's usage.
std::string parameter_help_text(const ParamSpec& p);

/// What the table says about a parameter: "meaning (unit), allowed range".
std::string describe(const ParamSpec& p);

} // namespace mdrmap::cases
