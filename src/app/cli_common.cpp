#include "app/cli_common.hpp"

#include <cstdio>
#include <exception>
#include <new>

#include <boost/program_options.hpp>

#include "app/exit_codes.hpp"
#include "case/case_input.hpp"

namespace po = boost::program_options;

namespace mdrmap::app {
using namespace mdrmap::cases; // the case library (src/case)

// --- Messages ------------------------------------------------------------------

std::string one_line(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else if (c == '\t')
      out += "\\t";
    else if (static_cast<unsigned char>(c) < 0x20)
      out += '?';
    else
      out += c;
  }
  return out;
}

int report_error(const std::string& command, int code, const std::string& what) {
  std::fprintf(stderr, "mdrmap %s: error: %s\n", command.c_str(), one_line(what).c_str());
  return code;
}

int report_invalid_input(const std::string& command, const InvalidInput& e) {
  if (e.option().empty()) return report_error(command, kExitBadInput, e.what());
  return report_error(command, kExitBadInput, "--" + e.option() + ": " + e.what());
}

namespace {

/// What a boost::program_options syntax error means, in words.
std::string syntax_problem(const po::invalid_command_line_syntax& e) {
  const std::string name = e.get_option_name();
  switch (e.kind()) {
  case po::invalid_syntax::missing_parameter:
    return "needs a value, e.g. " + name + " 1.5";
  case po::invalid_syntax::empty_adjacent_parameter:
    return "needs a value after '=', e.g. " + name + "=1.5";
  case po::invalid_syntax::extra_parameter:
    return "takes no value";
  default:
    return e.what();
  }
}

} // namespace

int report_parse_error(const std::string& command) {
  try {
    throw;
  } catch (const InvalidInput& e) {
    return report_invalid_input(command, e);
  } catch (const po::multiple_occurrences& e) {
    return report_error(command, kExitBadInput, e.get_option_name() + ": may be given only once");
  } catch (const po::invalid_command_line_syntax& e) {
    return report_error(command, kExitBadInput, e.get_option_name() + ": " + syntax_problem(e));
  } catch (const po::error_with_option_name& e) {
    const std::string name = e.get_option_name();
    return report_error(command, kExitBadInput, name.empty() ? e.what() : name + ": " + e.what());
  } catch (const po::error& e) {
    return report_error(command, kExitBadInput, e.what());
  }
}

int report_run_error(const std::string& command, const std::string& hint) {
  try {
    throw;
  } catch (const InvalidInput& e) {
    return report_invalid_input(command, e);
  } catch (const std::bad_alloc&) {
    return report_error(command, kExitRuntime, "out of memory (" + hint + ")");
  } catch (const std::exception& e) {
    return report_error(command, kExitRuntime, e.what());
  }
}

// --- Command line --------------------------------------------------------------

std::string all_option_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& o : names)
    s += "--" + o + ", ";
  return s + "--help, --help-all";
}

std::string beyond_last_term(const std::string& name) {
  const std::size_t digits = name.find_first_of("0123456789");
  const std::string stem = name.substr(0, digits);
  if (digits == std::string::npos || (stem != "G" && stem != "tau") || name[digits] == '0' ||
      name.find_first_not_of("0123456789", digits) != std::string::npos ||
      name.size() - digits > 6 || std::stoul(name.substr(digits)) <= kMaxBranches)
    return "";
  const std::string n = std::to_string(kMaxBranches);
  return "a spectrum has at most " + n + " terms, the options --G1..--G" + n +
         " and --tau1..--tau" + n + " of mdrmap study, or --prony G1:TAU1,... with at most " + n +
         " pairs; got --" + name;
}

po::variables_map option_texts(const std::vector<std::string>& args, const std::string& command,
                               const std::vector<std::string>& names, const std::string& example) {
  po::options_description desc;
  for (const auto& name : names)
    if (name == "allow-large-shift") // a flag
      desc.add_options()(name.c_str(), po::value<std::string>()->implicit_value("true"));
    else
      desc.add_options()(name.c_str(), po::value<std::string>());
  desc.add_options()("help", "");

  const int style = po::command_line_style::unix_style & ~po::command_line_style::allow_guessing;
  const po::parsed_options parsed =
      po::command_line_parser(args).options(desc).style(style).allow_unregistered().run();

  // Unknown options and stray positional arguments.
  const std::vector<std::string> stray =
      po::collect_unrecognized(parsed.options, po::include_positional);
  if (!stray.empty()) {
    const std::string& tok = stray.front();
    if (tok.size() > 1 && tok[0] == '-') {
      std::string name = tok.substr(0, tok.find('='));
      name.erase(0, name.find_first_not_of('-'));
      if (const std::string why = beyond_last_term(name); !why.empty())
        throw InvalidInput(name, why);
      throw InvalidInput(name, "not an option of mdrmap " + command +
                                   " (options are case-sensitive: " + all_option_names(names) +
                                   "), got " + tok);
    }
    throw InvalidInput("", "unexpected argument " + shown(tok) +
                               "; every value must follow its option, e.g. " + example);
  }
  po::variables_map vm;
  po::store(parsed, vm);
  po::notify(vm);
  return vm;
}

OptionTexts given_texts(const po::variables_map& vm, const std::vector<std::string>& names) {
  OptionTexts texts;
  for (const auto& name : names)
    if (vm.count(name)) texts.emplace(name, vm[name].as<std::string>());
  return texts;
}

std::string output_option(const po::variables_map& vm) {
  if (!vm.count("output")) return "";
  const std::string path = vm["output"].as<std::string>();
  if (path.empty())
    throw InvalidInput("output", "must be a file path (or - for stdout), got an empty string");
  return path;
}

bool asks_for_help(const std::vector<std::string>& args) {
  for (const auto& arg : args) {
    if (arg == "--") return false;
    if (arg == "--help" || arg == "-h") return true;
  }
  return false;
}

bool asks_for_help_all(const std::vector<std::string>& args) {
  for (const auto& arg : args) {
    if (arg == "--") return false;
    if (arg == "--help-all") return true;
  }
  return false;
}

int print_help(const std::string& text) {
  std::fputs(text.c_str(), stdout);
  return std::fflush(stdout) == 0 ? kExitOk : kExitRuntime;
}

void print_notes(const std::string& command, const std::vector<std::string>& notes) {
  for (const std::string& n : notes)
    std::fprintf(stderr, "mdrmap %s: note: %s\n", command.c_str(), n.c_str());
}

} // namespace mdrmap::app
