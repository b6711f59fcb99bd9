#include "app/stationary_cmd.hpp"
#include "case/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "app/cli_common.hpp"
#include "app/csv_output.hpp"
#include "app/exit_codes.hpp"
#include "app/help_layout.hpp"
#include "app/output_file.hpp"
#include "case/case_input.hpp"
#include "case/prony_input.hpp"
#include "case/stationary_input.hpp"
#include "core/metrics/stationary.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "mdrmap/version.hpp"

namespace po = boost::program_options;

namespace mdrmap::app {
using namespace mdrmap::cases; // the case library (src/case)
namespace {

constexpr const char* kCommand = "stationary";
constexpr const char* kColumns = "v,d,a1,a2,FN,Fx,mu";

// --- Options -------------------------------------------------------------------

/// Whether an option of simulate's case (case_option_spellings) describes the
/// stationary case: the table's parameters but the sampling (with --v, the
/// velocity), the profile, the spectrum and the temperature. The history,
/// the spacing and how to run (rtol, solver) are simulate's only.
bool stationary_case_option(const std::string& name) {
  if (const ParamSpec* p = find_parameter(name)) return p->part != Part::Sampling;
  return name == "profile" || name == "material" || name == "prony" || name == "prony-file" ||
         name == "nu" || name == "T" || name == "allow-large-shift" || name == "wlf";
}

/// The case options, in the order of simulate's help (old spellings last).
std::vector<std::string> case_options() {
  std::vector<std::string> names;
  for (const auto& n : case_option_spellings())
    if (stationary_case_option(n)) names.push_back(n);
  return names;
}

std::vector<std::string> option_names() {
  std::vector<std::string> names = case_options();
  names.insert(names.end(), {"v-list", "v-range", "output"});
  return names;
}

// --- Command line --------------------------------------------------------------

struct StationaryArgs {
  StationaryInput input;
  std::string output; ///< empty or "-": stdout
};

/// Parses and validates the command line. Throws InvalidInput, or lets
/// boost::program_options errors through.
StationaryArgs parse_args(const std::vector<std::string>& args) {
  const po::variables_map vm = option_texts(args, kCommand, option_names(), "--v 0.1");
  std::vector<std::string> given = case_options();
  given.insert(given.end(), {"v-list", "v-range"});
  StationaryArgs a;
  a.input = read_stationary_input(given_texts(vm, given));
  a.output = output_option(vm);
  return a;
}

// --- Output --------------------------------------------------------------------

/// The `# case` line without the history and the sampling: the profile
/// (other than the parabola), every table parameter of the case that is
/// shown as simulate shows it (of a one_of group the member given, aT where
/// it is not 1), the spectrum, the temperature, and a0 under load.
std::string stationary_case_line(const Case& c, const std::optional<TemperatureInput>& t) {
  std::string s = "# case";
  if (!c.indenter.parabolic()) s += std::string(" profile=") + profile_name(c.indenter.profile);
  for (const auto& p : case_parameters()) {
    if (p.part == Part::Sampling || p.part == Part::History) continue;
    if (!p.applies_to(c.indenter.profile) || (p.one_of && p.get(c) == 0.0)) continue;
    if (std::strcmp(p.name, "aT") == 0 && p.get(c) == 1.0) continue;
    s += std::string(" ") + p.name + "=" + format_double(p.get(c));
  }
  if (!c.rheology.branches.empty()) s += " prony=" + format_prony(c.rheology.branches);
  if (t)
    s += " T=" + format_double(t->T) + unit_suffix(t->unit) + " wlf=" + format_wlf(t->wlf) +
         unit_suffix(t->unit);
  if (c.loading.by_force()) s += " a0=" + format_double(c.a0());
  return s;
}

void write_csv(std::FILE* out, const StationaryInput& a, const std::vector<State>& states) {
  std::fprintf(out, "# mdrmap %s (%s) stationary\n", kVersion, kGitCommit);
  std::fprintf(out, "%s\n%s\n", stationary_case_line(a.in.c, a.in.temperature).c_str(), kColumns);
  for (std::size_t k = 0; k < states.size(); ++k) {
    const State& s = states[k];
    const double row[] = {a.velocities[k], s.d, s.a1, s.a2, s.FN, s.Fx, s.mu};
    write_csv_line(out, row, sizeof row / sizeof row[0]);
  }
}

int run(const StationaryArgs& a) {
  OutputFile out(a.output); // opened first: a bad path fails before any work
  print_notes(kCommand, a.input.in.notes);
  write_csv(out.get(), a.input, stationary_states(a.input));
  out.commit();
  return kExitOk;
}

// --- Help ----------------------------------------------------------------------

std::vector<HelpEntry> velocity_entries() {
  const ParamSpec& v = *find_parameter("v");
  const std::string unit = std::string("(") + dim_name(v.dim) + ") ", range = v.allowed();
  return {{"--v V", unit + "one velocity, " + range},
          {"--v-list V1,V2,...",
           unit + "velocities in the order given, each " + range + "; " + velocity_count_text()},
          {"--v-range LO:HI:N", unit +
                                    "N velocities equally spaced in log v from LO to HI, the "
                                    "ends exactly LO and HI: LO and HI each " +
                                    range + ", LO < HI; N an integer from 2 to " +
                                    std::to_string(kMaxVelocities)}};
}

/// The options of stationary, in groups: the short help gives their labels,
/// the full help their entries.
std::vector<HelpSection> sections() {
  return {{"geometry", "Case geometry and loading", geometry_entries(false)},
          {"material",
           "Material (no --prony: the Kelvin foundation; --T and --wlf: the temperature)",
           material_entries()},
          {"velocity", "Velocities (exactly one of --v, --v-list, --v-range)", velocity_entries(),
           "Each velocity must pass the checks of --v in mdrmap simulate: v tau / a1 (a0\n"
           "under --F0) and the stationary contact at v representable in doubles.\n"},
          {"output", "Output", {output_entry()}},
          {"help", "Help", {help_option_entry(kCommand), help_all_option_entry(kCommand)}}};
}

std::string usage() {
  return "Usage: mdrmap stationary" + case_usage(false) +
         "\n           (--v V | --v-list V1,V2,... | --v-range LO:HI:N) [options]\n";
}

std::string output_help() {
  return R"(Output: comment lines starting with '#', then CSV with one row per velocity.
  # mdrmap VERSION (COMMIT) stationary
  # case profile=P d=... R=... tau=... G=...
                          (every case parameter given, as in simulate's
                           # case line: profile=P where it is not the
                           parabola, F0=... in place of d=... under --F0,
                           aT=... where it is not 1, then prony=G1:TAU1,...,
                           T=... wlf=C1:C2:TREF and, under --F0, a0=...)
  v,d,a1,a2,FN,Fx,mu
v is the velocity, FN the normal force, Fx the tangential (friction) force,
positive when it resists the motion, and mu = Fx/FN. In the frame of the
indenter the contact occupies [-a1, a2]: a1 is the leading edge, a2 the
trailing edge (0 where the rear face of a cone has let go). At fixed depth d
is the given depth; under --F0, d and a1 are the stationary depth and leading
edge under the load, a0 its Hertz contact radius. Numbers have 17
significant digits, so they read back to the same double.
)";
}

std::string examples() {
  return R"(Examples:
  mdrmap stationary --d 0.1 --R 10 --tau 1 --v-range 1e-3:1e3:61
  mdrmap stationary --profile cone --beta 10 --d 0.01 --tau 1 --v-list 0.01,1
  mdrmap stationary --profile power --n 1.5 --A 1 --F0 0.01 --tau 0 \
      --prony 1:0.1,2:10 --v 1 --output power.csv
)";
}

std::string exit_codes() {
  return R"(
Exit codes:
  0  success
  1  runtime failure (computing a state or writing the output failed)
  2  bad input (one line on stderr names the option and what it allows;
     nothing is written)
)";
}

} // namespace

std::string stationary_help_all() {
  return usage() + R"(
Prints the stationary sliding states of one case at one or more velocities,
in the method of dimensionality reduction (MDR): the state that the contact
reaches after sliding steadily at the velocity v for long enough, from the
closed forms (or by quadrature) of the core, with no time stepping. Any
indenter profile (parabola, cone, power law, sphere), the Kelvin foundation
or a relaxation spectrum (--prony), at fixed depth (--d) or under the normal
load F0 (--F0: the depth follows). The case is given as to mdrmap simulate,
without its velocity history and sampling.

Any consistent units work (e.g. mm, s, MPa): d, R, a1, a2 are lengths, tau a
time, velocities length/time; forces come out in units of G * length^2.

)" + full_options(sections()) +
         "\n" + output_help() + "\n" + examples() + exit_codes();
}

std::string stationary_help() {
  return usage() + R"(
The stationary sliding states of one case (any profile and rheology, fixed
depth or load) at one or more velocities, as CSV: v,d,a1,a2,FN,Fx,mu.

)" + options_summary(sections()) +
         "\n" + examples() + "\n" + full_list_pointer(kCommand);
}

int stationary_main(const std::vector<std::string>& args) {
  return command_main(kCommand, args, stationary_help, stationary_help_all, parse_args, run,
                      "try fewer velocities");
}

} // namespace mdrmap::app
