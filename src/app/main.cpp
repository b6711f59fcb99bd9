// mdrmap: command-line front end. Dispatches to the subcommands (study and
// fit run as the programs mdrmap-study and mdrmap-fit beside it: sibling.hpp);
// only this layer prints (the core library reports through exceptions).
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/help_topics.hpp"
#include "app/sibling.hpp"
#include "app/simulate_cmd.hpp"
#include "app/stationary_cmd.hpp"
#include "mdrmap/version.hpp"

namespace {

using mdrmap::app::kExitBadInput;
using mdrmap::app::kExitOk;
using mdrmap::app::kExitRuntime;

int print_stdout(const std::string& text) {
  std::fputs(text.c_str(), stdout);
  return std::fflush(stdout) == 0 ? kExitOk : kExitRuntime;
}

int dispatch(const std::vector<std::string>& args, char** argv) {
  if (args.empty()) {
    std::fputs("mdrmap: error: missing subcommand; usage: mdrmap <subcommand> [options] "
               "(subcommands: simulate, stationary, study, fit; see mdrmap --help)\n",
               stderr);
    return kExitBadInput;
  }
  const std::string& cmd = args.front();
  const std::vector<std::string> rest(args.begin() + 1, args.end());

  if (cmd == "--help" || cmd == "-h") return print_stdout(mdrmap::app::top_help());
  if (cmd == "--version" || cmd == "-V")
    return print_stdout(std::string("mdrmap ") + mdrmap::kVersion + " (" + mdrmap::kGitCommit +
                        ")\n");
  if (cmd == "help") return mdrmap::app::help_main(rest);
  if (cmd == "simulate") return mdrmap::app::simulate_main(rest);
  if (cmd == "study") return mdrmap::app::run_sibling("mdrmap-study", argv);
  if (cmd == "stationary") return mdrmap::app::stationary_main(rest);
  if (cmd == "fit") return mdrmap::app::run_sibling("mdrmap-fit", argv);

  if (!cmd.empty() && cmd[0] == '-')
    std::fprintf(stderr,
                 "mdrmap: error: unknown option '%s'; the subcommand comes first: mdrmap "
                 "<subcommand> [options] (see mdrmap --help)\n",
                 cmd.c_str());
  else
    std::fprintf(stderr,
                 "mdrmap: error: unknown subcommand '%s'; available: simulate, stationary, study, "
                 "fit (see mdrmap --help)\n",
                 cmd.c_str());
  return kExitBadInput;
}

} // namespace

int main(int argc, char** argv) {
  // A write past the file-size limit (ulimit -f) must fail with EFBIG and be
  // reported, not kill the process with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  try {
    return dispatch(std::vector<std::string>(argv + 1, argv + argc), argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mdrmap: error: %s\n", e.what());
    return kExitRuntime;
  }
}
