#include "app/simulate_cmd.hpp"

#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "app/cli_common.hpp"
#include "app/csv_output.hpp"
#include "app/help_layout.hpp"
#include "app/output_file.hpp"
#include "case/case_input.hpp"
#include "case/simulation.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "core/solvers/result.hpp"

namespace po = boost::program_options;

namespace mdrmap::app {
using namespace mdrmap::cases; // the case library (src/case)
namespace {

constexpr const char* kCommand = "simulate";

/// Every option, in the order of the help text: those of a case
/// (case/case_input.hpp, with the old spellings it takes), then --output.
std::vector<std::string> option_names() {
  std::vector<std::string> names = case_option_spellings();
  names.emplace_back("output");
  return names;
}

// --- Command line --------------------------------------------------------------

struct SimulateArgs {
  CaseInput in;
  std::string output; ///< empty or "-": stdout
};

/// Parses and validates the command line. Throws InvalidInput, or lets
/// boost::program_options errors through for the caller to translate.
SimulateArgs parse_args(const std::vector<std::string>& args) {
  const po::variables_map vm = option_texts(args, kCommand, option_names(), "--d 0.1");
  SimulateArgs a;
  a.in = read_case_input(given_texts(vm, case_option_spellings()));
  a.output = output_option(vm);
  return a;
}

int run(const SimulateArgs& a) {
  OutputFile out(a.output); // opened before the solver runs: a bad path fails fast
  print_notes(kCommand, a.in.notes);
  const Simulation sim = simulate(a.in);
  write_simulate_csv(out.get(), sim.record, sim.series, a.in.temperature,
                     a.in.record ? &*a.in.record : nullptr);
  out.commit();
  return kExitOk;
}

// --- Help ----------------------------------------------------------------------

std::vector<HelpEntry> history_entries() {
  std::vector<HelpEntry> e = parameter_entries(Part::History);
  for (const char* name : {"v1", "t-end", "history", "history-file"})
    e.push_back(option_entry(name));
  return e;
}

std::vector<HelpEntry> output_entries() {
  std::vector<HelpEntry> e = parameter_entries(Part::Sampling);
  e.push_back(option_entry("spacing"));
  e.push_back(output_entry());
  return e;
}

std::vector<HelpEntry> solver_entries() {
  return {option_entry("rtol"), option_entry("solver")};
}

/// The options of simulate, in groups: the short help gives their labels,
/// the full help their entries.
std::vector<HelpSection> sections() {
  const std::vector<HelpEntry> geometry = geometry_entries(true), material = material_entries();
  return {{"geometry", "Case geometry and loading", geometry},
          {"material",
           "Material (no --prony: the Kelvin foundation; --T and --wlf: the temperature)",
           material},
          {"history", "Velocity history: V0 before t = 0, then --v1 or --history (or a lab record)",
           history_entries()},
          {"output", "Output and sampling, per segment", output_entries()},
          {"solver", "Solver", solver_entries()},
          {"help", "Help", {help_option_entry(kCommand), help_all_option_entry(kCommand)}}};
}

/// "  # event k=K t=... w_before=... ...": the CSV's event fields (the output
/// table's), wrapped at 78 columns.
std::string event_line_help() {
  std::string s = "  # event k=K", line = s;
  for (const auto& [name, value] : cases::event_fields(EventMetrics{})) {
    const std::string item = " " + name + "=...";
    if (line.size() + item.size() > 78) {
      s += "\n     ";
      line = "     ";
    }
    s += item;
    line += item;
  }
  return s;
}

std::string output_help() {
  return R"(Output: comment lines starting with '#', then CSV with a header line.
  # mdrmap VERSION (COMMIT) simulate solver=NAME rtol=E error_estimate=...
      cells_per_a1=... elements=... steps=... element_updates=...
      root_solves=... wall_seconds=...            (all on one line)
  # case d=... R=... tau=... G=... v=... history=W1:T1,... spacing=linear
      samples=N log-decades=D zeta0=...           (all on one line: every
                                                   case parameter given, the
                                                   history; under --F0: F0=...
                                                   in place of d=..., and
                                                   a0=... before zeta0; aT=...
                                                   after G where it is not 1,
                                                   prony=G1:TAU1,... after v
                                                   where there are terms,
                                                   then T=... wlf=... where
                                                   --T was given)
  # error_vs_exact=...     (solvers other than exact only: the case error
                            against the continuum solution)
  # error_vs_reference=... reference=NAME reference_rtol=...
                           (under --F0, solvers other than auto only: the
                            case error against the load solver at a 1000x
                            tighter rtol, at least 1e-9)
)" + event_line_help() +
         R"(
                           (one line per segment K = 0, 1, ...: the change at
                            its start, see below; D_c_undefined=WHY where D_c
                            is nan)
  # pre FN=... Fx=... mu=... a2=...   (stationary state at V0 before t = 0;
                                       under --F0 also d=... a1=...)
  )" + csv_header(false) +
         "               (under --F0: " + csv_header(true) + R"()
  ... N rows per segment, segment after segment; segment is 0-based, t is
      measured from the first change (t = 0 is the instant just after it) ...
      (--history-file: one row per row of the record, t measured from its
      first row, and the columns v and slip after the others)
zeta0 = V0 tau / a1 is the dimensionless velocity before t = 0; under --F0
zeta0 = V0 tau / a0, a0 the Hertz contact radius of F0 (F0 = 16/3 G a0^3/R),
and the columns d and a1 give the depth and the leading edge, a1 = sqrt(R d).
The stationary states of the events are then those under the load F0.
Events: the change at time t from w_before to w_after; mu just before it
(mu_before) and just after it (mu_after); the extremum of mu in the segment,
the sample farthest from the stationary mu_ss_after (mu_peak), its time since
the change (t_peak) and the slip w_after t_peak (slip_peak); mu at the
segment's end (mu_end); the stationary mu at both velocities; D_c, the slip
over which |mu - mu_ss_after| falls to 1/e of its value just after the change;
the apparent rate-and-state parameters a = (mu_after - mu_before) /
ln(w_after/w_before), a_minus_b = (mu_ss_after - mu_ss_before) /
ln(w_after/w_before) and b = a - a_minus_b. Where a value is undefined (a
velocity of 0 or equal velocities in the log, no 1/e decay within the segment,
a hold) it is printed as nan.
The case error is the largest of max_k |q_k - q_ref,k| / max_k |q_ref,k| for
q = FN, Fx, mu and max_k |a2_k - a2_ref,k| / a1. Under --F0: max_k |FN_k - F0|
/ F0, d, Fx and mu by their largest magnitude, a1 and a2 by a0.
error_estimate is the solver's own bound on it. Numbers have 17 significant
digits, so they read back to the same double.
)";
}

std::string usage() {
  return "Usage: mdrmap simulate" + case_usage(true) +
         "\n           (--v1 V1 [--t-end T] | --history W1:T1,W2:T2,...) [options]\n"
         "       mdrmap simulate ... --history-file RECORD.csv   (no --v, --v1, --history)\n";
}

std::string examples() {
  return R"(Examples:
  mdrmap simulate --d 0.1 --R 10 --tau 1 --v 2 --v1 0.5 --output step.csv
  mdrmap simulate --d 0.1 --R 10 --tau 1 --v 1 --history 1:2,0:1000,1:5 \
      --samples 101 --spacing log       (slide-hold-slide: a hold of 1000 tau)
  mdrmap simulate --F0 0.1 --R 10 --tau 1 --v 1 --history 0.1:20,1:20
                                        (load control: a step down and up)
)";
}

} // namespace

std::string simulate_help_all() {
  return usage() +
         R"(
Computes the response of a viscoelastic contact to changes of the sliding
velocity, in the method of dimensionality reduction (MDR). A rigid indenter (a
parabola, MDR profile x^2/R; or --profile cone or power) is held at indentation
depth d (--d, depth control) or pressed with the prescribed normal load F0
(--F0, load control: the depth follows; --FN is accepted as its old spelling)
on a Kelvin foundation (shear modulus G, relaxation time tau = eta/G) or a
material with a relaxation spectrum (--prony), its times shifted by aT (--aT,
or --T with --wlf). It slides steadily at velocity V0 until t = 0, then follows
a velocity history: one step to V1 (--v1), or segments of constant velocity,
holds included (--history). The command prints the stationary state before
t = 0, event metrics of every velocity change and, at N instants per segment,
the measured normal force FN, the tangential (friction) force Fx, positive when
it resists the motion, the friction coefficient mu = Fx/FN, and the trailing
edge a2 of the contact. In the frame of the indenter the contact occupies [-a1,
a2], g(a1) = d (a1 = sqrt(R d) for the parabola); at fixed depth the leading
edge stays at -a1, under load the depth d and a1 are printed too.

Any consistent units work (e.g. mm, s, MPa): d, R, a2 are lengths, tau and t
times, velocities length/time; forces come out in units of G * length^2.

)" + full_options(sections()) +
         "\n" + output_help() + "\n" + examples() + R"(
Exit codes:
  0  success
  1  runtime failure (the solver or writing the output failed)
  2  bad input (one line on stderr names the option and what it allows)
)";
}

std::string simulate_help() {
  return usage() + R"(
One case: a rigid indenter slides on a viscoelastic foundation at velocity V0
until t = 0, then follows a velocity step or history; prints FN, Fx, mu and
the contact's trailing edge a2 over time as CSV, with event metrics.

)" + options_summary(sections()) +
         "\n" + examples() + "\n" + full_list_pointer(kCommand);
}

std::string simulate_section_help(const std::string& key) {
  std::vector<HelpSection> one;
  for (const auto& sec : sections())
    if (sec.key == key) one.push_back(sec);
  return full_options(one);
}

int simulate_main(const std::vector<std::string>& args) {
  return command_main(kCommand, args, simulate_help, simulate_help_all, parse_args, run,
                      "try fewer --samples");
}

} // namespace mdrmap::app
