#pragma once
// What the command lines of `mdrmap simulate` and `mdrmap stationary` share:
// reading the options as texts (boost::program_options, unknown options and
// stray arguments refused), the one-line messages on stderr with their exit
// codes (kExitBadInput for bad input, kExitRuntime for a failed run), and
// --help and --help-all (their texts: app/help_layout.hpp). Every message starts with
// "mdrmap COMMAND: error: ", COMMAND the subcommand's name.
#include <string>
#include <vector>

#include <boost/program_options/variables_map.hpp>

#include "case/case_input.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"

namespace mdrmap::app {

/// Keeps a message on one line: control characters become visible escapes
/// (\n, \r, \t; any other one '?').
std::string one_line(const std::string& text);

/// Writes "mdrmap COMMAND: error: WHAT" (one_line) to stderr; returns `code`.
int report_error(const std::string& command, int code, const std::string& what);

/// An InvalidInput as one line: "--OPTION: what", or what alone where no
/// option is named. Returns kExitBadInput.
int report_invalid_input(const std::string& command, const InvalidInput& e);

/// The one line of the exception being handled (call it in a catch block)
/// from reading the command line: InvalidInput or a boost::program_options
/// error. Returns kExitBadInput; any other exception is rethrown.
int report_parse_error(const std::string& command);

/// The one line of the exception being handled (call it in a catch block)
/// from a run: InvalidInput (kExitBadInput), std::bad_alloc as "out of
/// memory (HINT)" and any other std::exception (kExitRuntime); anything
/// else is rethrown.
int report_run_error(const std::string& command, const std::string& hint);

/// "--a, --b, ..., --help, --help-all": the options `names` (without dashes)
/// and the two help options.
std::string all_option_names(const std::vector<std::string>& names);

/// For an option name G<k> or tau<k> with k past the spectrum's last term
/// (kMaxBranches), why it is refused (the 32-term limit); else "".
std::string beyond_last_term(const std::string& name);

/// Reads the command line of `command`: each of `names` takes one value (a
/// text), --help none. An unknown option throws InvalidInput naming it and
/// listing all_option_names(names); a stray argument throws InvalidInput("")
/// whose message shows `example` ("--d 0.1") as the way to give a value.
/// boost::program_options errors are let through (report_parse_error).
boost::program_options::variables_map option_texts(const std::vector<std::string>& args,
                                                   const std::string& command,
                                                   const std::vector<std::string>& names,
                                                   const std::string& example);

/// The texts of those of `names` that were given (their spellings as keys).
cases::OptionTexts given_texts(const boost::program_options::variables_map& vm,
                               const std::vector<std::string>& names);

/// The text of --output: "" (stdout) when not given. Throws
/// InvalidInput("output") when it was given empty.
std::string output_option(const boost::program_options::variables_map& vm);

/// Whether `args` ask for help: --help or -h before any "--".
bool asks_for_help(const std::vector<std::string>& args);

/// Prints `text` to stdout: kExitOk, or kExitRuntime if it could not be written.
int print_help(const std::string& text);

/// Whether `args` ask for every option: --help-all before any "--".
bool asks_for_help_all(const std::vector<std::string>& args);

/// Writes each note (what an input gave that does not enter, e.g. a material
/// card's bulk terms) to stderr as "mdrmap COMMAND: note: ...".
void print_notes(const std::string& command, const std::vector<std::string>& notes);

/// The frame of a subcommand's main: with --help-all (asks_for_help_all)
/// prints help_all(), with --help (asks_for_help) help(); else parses `args` (parse: Args or
/// throws, report_parse_error) and runs the result (run: the exit code or throws, report_run_error
/// with `out_of_memory_hint`).
template <class Args>
int command_main(const std::string& command, const std::vector<std::string>& args,
                 std::string (*help)(), std::string (*help_all)(),
                 Args (*parse)(const std::vector<std::string>&), int (*run)(const Args&),
                 const std::string& out_of_memory_hint) {
  if (asks_for_help_all(args)) return print_help(help_all());
  if (asks_for_help(args)) return print_help(help());
  Args a;
  try {
    a = parse(args);
  } catch (...) {
    return report_parse_error(command);
  }
  try {
    return run(a);
  } catch (...) {
    return report_run_error(command, out_of_memory_hint);
  }
}

} // namespace mdrmap::app
