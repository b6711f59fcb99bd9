// mdrmap: command-line front end. Dispatches to the subcommands; only this
// layer prints (the core library reports through exceptions).
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/simulate_cmd.hpp"
#include "app/stationary_cmd.hpp"
#include "app/study_cmd.hpp"
#include "mdrmap/version.hpp"

namespace {

using mdrmap::app::kExitBadInput;
using mdrmap::app::kExitOk;
using mdrmap::app::kExitRuntime;

std::string usage() {
  return std::string("mdrmap ") + mdrmap::kVersion + " (" + mdrmap::kGitCommit + R"()
Viscoelastic friction in the method of dimensionality reduction (MDR): the
response of a sliding indenter (a parabola, a cone or a power law) on a
Kelvin foundation or a material with a relaxation spectrum, held at a fixed
depth or pressed with a prescribed normal force, to changes of the sliding
velocity (a step, or a history of steps and holds), for one case or as
parameter maps.

Usage: mdrmap <subcommand> [options]
       mdrmap --help | --version

Subcommands:
  simulate   one case, a velocity step or history: normal force, friction
             force, friction coefficient and trailing edge of the contact
             over time, as CSV, with event metrics of every velocity change
  stationary the stationary sliding states of one case (any profile and
             rheology, fixed depth or load) at one or more velocities, as CSV
  study      parameter maps over many cases in parallel: MPI ranks share
             the cases, results go to one HDF5 friction map

Run 'mdrmap <subcommand> --help' (or 'mdrmap help <subcommand>') for the
options of a subcommand.

Exit codes: 0 success, 1 runtime failure, 2 bad input, 3 interrupted (study;
resume with --resume).
)";
}

int print_stdout(const std::string& text) {
  std::fputs(text.c_str(), stdout);
  return std::fflush(stdout) == 0 ? kExitOk : kExitRuntime;
}

int dispatch(const std::vector<std::string>& args, int argc, char** argv) {
  if (args.empty()) {
    std::fputs("mdrmap: error: missing subcommand; usage: mdrmap <subcommand> [options] "
               "(subcommands: simulate, stationary, study; see mdrmap --help)\n",
               stderr);
    return kExitBadInput;
  }
  const std::string& cmd = args.front();
  const std::vector<std::string> rest(args.begin() + 1, args.end());

  if (cmd == "--help" || cmd == "-h" || (cmd == "help" && rest.empty()))
    return print_stdout(usage());
  if (cmd == "--version" || cmd == "-V")
    return print_stdout(std::string("mdrmap ") + mdrmap::kVersion + " (" + mdrmap::kGitCommit +
                        ")\n");
  if (cmd == "help") {
    if (rest.front() == "simulate") return print_stdout(mdrmap::app::simulate_help());
    if (rest.front() == "study") return print_stdout(mdrmap::app::study_help());
    if (rest.front() == "stationary") return print_stdout(mdrmap::app::stationary_help());
    std::fprintf(stderr,
                 "mdrmap: error: no help for unknown subcommand '%s' (subcommands: simulate, "
                 "stationary, study)\n",
                 rest.front().c_str());
    return kExitBadInput;
  }
  if (cmd == "simulate") return mdrmap::app::simulate_main(rest);
  if (cmd == "study") return mdrmap::app::study_main(rest, argc, argv);
  if (cmd == "stationary") return mdrmap::app::stationary_main(rest);

  if (!cmd.empty() && cmd[0] == '-')
    std::fprintf(stderr,
                 "mdrmap: error: unknown option '%s'; the subcommand comes first: mdrmap "
                 "<subcommand> [options] (see mdrmap --help)\n",
                 cmd.c_str());
  else
    std::fprintf(stderr,
                 "mdrmap: error: unknown subcommand '%s'; available: simulate, stationary, study "
                 "(see mdrmap --help)\n",
                 cmd.c_str());
  return kExitBadInput;
}

} // namespace

int main(int argc, char** argv) {
  // A write past the file-size limit (ulimit -f) must fail with EFBIG and be
  // reported, not kill the process with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  try {
    return dispatch(std::vector<std::string>(argv + 1, argv + argc), argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mdrmap: error: %s\n", e.what());
    return kExitRuntime;
  }
}
