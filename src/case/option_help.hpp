#pragma once
// The help of the case options that are not parameters of the table
// (core/model/params.hpp): the profile, the spectrum and the temperature,
// the history's other forms, the spacing of the samples, the solver. Each
// option's text is declared here once: the command line's help (src/app)
// and the Python module's docstrings (src/python) both take it from here.
#include <string>
#include <vector>

namespace mdrmap::cases {

/// One option's help, in the command line's words (--NAME for an option).
struct OptionHelp {
  std::string name;        ///< "prony": the option as the command line spells it
  std::string placeholder; ///< "G1:TAU1,G2:TAU2,...": its value's; empty for a flag
  std::string text;        ///< what it means, without its default
  std::string fallback;    ///< its default ("parabola"), empty when there is none
  std::string tail;        ///< verbatim lines after the command line's entry (a small table)

  /// The text, then `extra` (a sentence), then "Default: FALLBACK".
  std::string full(const std::string& extra = "") const;
};

/// Every case option outside the table, in the order of simulate's help.
const std::vector<OptionHelp>& case_option_help();

/// The help of the option `name` (one of case_option_help()); throws
/// std::out_of_range for another name.
const OptionHelp& option_help(const std::string& name);

} // namespace mdrmap::cases
