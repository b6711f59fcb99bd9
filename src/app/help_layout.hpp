#pragma once
// The layout of the help texts: an option's entry (its label, then its text
// wrapped at 79 columns), the sections of a subcommand's options, and the two
// views of one list of sections: the full list (--help-all, mdrmap help
// COMMAND) and the short summary of --help (the labels only, one group a
// few lines). Each option's text is declared once, in its section.
#include <string>
#include <vector>

#include "core/model/params.hpp"

namespace mdrmap::app {

/// One option of a help text.
struct HelpEntry {
  std::string label;      ///< "--profile P": the option and its value's placeholder
  std::string text;       ///< what it means, wrapped by help_entry
  std::string tail = "";  ///< verbatim lines printed after the entry (a small table)
  bool summarized = true; ///< listed by the short summary (false: an old spelling)
};

/// A group of options: the full list prints "TITLE:" and the entries, the
/// summary "  KEY  LABEL, LABEL, ..." (KEY: geometry, material, history,
/// output, solver, ...).
struct HelpSection {
  std::string key;
  std::string title;
  std::vector<HelpEntry> entries;
  std::string note = ""; ///< verbatim lines after the entries (full list only)
};

/// A help entry: "  OPTION" padded to column 17 (on a line of its own when
/// longer), then `text` wrapped at spaces to 79 columns, indented to 17.
std::string help_entry(const std::string& option, const std::string& text);

/// The entry of a table parameter: "--NAME SYMBOL" and parameter_help_text
/// (its unit, meaning, range and default).
HelpEntry parameter_entry(const ParamSpec& p);

/// The entries of the table's parameters of `part`, in the table's order.
std::vector<HelpEntry> parameter_entries(Part part);

/// The usage of a case from the table: its required options (without the
/// history's unless `history`), each one_of group as "(--d D | --F0 F0)",
/// then on a line of its own, indented to column 11, the profiles'
/// alternatives "(--R R | --profile cone --beta DEG | ...)".
std::string case_usage(bool history);

/// The entry of a case option outside the table (case/option_help.hpp):
/// "--NAME PLACEHOLDER", its text, `extra` (a sentence), its default, its tail.
HelpEntry option_entry(const std::string& name, const std::string& extra = "");

/// --profile, for simulate and stationary: the indenter profiles and their
/// parameters; `solvers` adds which solvers take which profile.
HelpEntry profile_entry(bool solvers);

/// --output FILE of simulate and stationary: how the file is replaced.
HelpEntry output_entry();

/// The entries of the relaxation spectrum and the temperature: --prony,
/// --prony-file, --T, --wlf, with the ranges of the table's branch specs.
std::vector<HelpEntry> rheology_entries();

/// A case's geometry and loading entries: --profile (profile_entry), then
/// the table's loading and indenter parameters.
std::vector<HelpEntry> geometry_entries(bool solvers);
/// A case's material entries: the table's material parameters, then
/// rheology_entries().
std::vector<HelpEntry> material_entries();

/// --help and --help-all of the subcommand `command`.
HelpEntry help_option_entry(const std::string& command);
HelpEntry help_all_option_entry(const std::string& command);

/// The entries of `entries`, each with its tail.
std::string render_entries(const std::vector<HelpEntry>& entries);

/// Every section: "TITLE:", its entries, its note; a blank line between two.
std::string full_options(const std::vector<HelpSection>& sections);

/// "Options:" and one group a line (wrapped at 79 columns, indented): the
/// key, then the labels of its entries.
std::string options_summary(const std::vector<HelpSection>& sections);

/// `text` wrapped at spaces to 79 columns.
std::string paragraph(const std::string& text);

/// The last lines of a short help: where the full list is.
std::string full_list_pointer(const std::string& command);

} // namespace mdrmap::app
