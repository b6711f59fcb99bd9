#include "app/simulate_cmd.hpp"

#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "app/case_input.hpp"
#include "app/cli_common.hpp"
#include "app/csv_output.hpp"
#include "app/output_file.hpp"
#include "app/simulation.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"

namespace po = boost::program_options;

namespace mdrmap::app {
namespace {

constexpr const char* kCommand = "simulate";

/// Every option, in the order of the help text: those of a case
/// (app/case_input.hpp, with the old spellings it takes), then --output.
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
  write_simulate_csv(out.get(), sim.record, sim.series, a.in.temperature);
  out.commit();
  return kExitOk;
}

// --- Help ----------------------------------------------------------------------

std::string profile_help() {
  return help_entry("--profile P",
                    "the indenter: parabola (f = r^2/2R, --R), cone (--beta, the angle of its "
                    "surface to the plane) or power (f = A r^n, --n --A); MDR image g(x) = "
                    "kappa_n A |x|^n. The cone and power profiles are solved by the spectrum "
                    "solver (auto picks it); the other solvers take the parabola only. Their "
                    "stationary states: mdrmap stationary. Default: parabola");
}

/// One help entry per table parameter of the sampling part or of the others.
std::string parameter_help(bool sampling) {
  std::string s;
  for (const auto& p : case_parameters()) {
    if ((p.part == Part::Sampling) != sampling) continue;
    s += parameter_entry(p);
  }
  return s;
}

/// The required options of the table, as the usage line gives them: each
/// one_of group as "(--d D | --F0 F0)" where its first member stands.
std::string required_usage() {
  std::string s;
  for (const auto& p : case_parameters()) {
    if (p.required && p.profile == nullptr) s += std::string(" --") + p.name + " " + p.symbol;
    if (!p.one_of) continue;
    const auto members = group_members(p.one_of);
    if (members.front() == &p) s += " (" + group_usage(members, " | ", " | ") + ")";
  }
  return s + "\n           (--R R | --profile cone --beta DEG | --profile power --n N --A A)";
}

std::string history_help() {
  const ParamSpec &w = segment_velocity_spec(), &T = segment_duration_spec();
  return help_entry("--v1 V1", "one step: the sliding velocity from t = 0 on (" +
                                   std::string(dim_name(w.dim)) + "), " + w.allowed() +
                                   "; 0 stops the indenter, V1 > V0 is a speed-up") +
         help_entry("--t-end T", "with --v1: how long the step is followed (" +
                                     std::string(dim_name(T.dim)) + "), " + T.allowed() +
                                     ". Default: 6 tau (with a spectrum: 6 times the longest "
                                     "shifted time aT max(tau, tauk)); for a purely elastic "
                                     "foundation, 6 a1/min(V0,V1) (6 a1/V0 if V1 = 0), a0 in "
                                     "place of a1 under --F0") +
         help_entry("--history W1:T1,W2:T2,...",
                    "segments one after another from t = 0: sliding velocity Wk (" +
                        std::string(dim_name(w.dim)) + "), " + w.allowed() + ", 0 is a hold; " +
                        "duration Tk (" + dim_name(T.dim) + "), " + T.allowed() + "; at most " +
                        std::to_string(kMaxSegments) +
                        " segments. --v1 V1 --t-end T is --history V1:T; give one of the two "
                        "forms, not both");
}

std::string sampling_help() {
  return parameter_help(true) +
         help_entry("--spacing S",
                    "linear or log: where the N instants of a segment k (start t_k, duration "
                    "T_k) lie. Default: linear") +
         "                   linear  t_k + j T_k/(N-1), j = 0..N-1\n"
         "                   log     t_k, then t_k + T_k 10^(-D (N-1-j)/(N-2)),\n"
         "                           j = 1..N-1 (D = --log-decades): a long hold and\n"
         "                           the transient at its start both resolved\n";
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
  # event k=K t=... w_before=... w_after=... mu_before=... mu_after=...
      mu_peak=... t_peak=... slip_peak=... mu_end=... mu_ss_before=...
      mu_ss_after=... D_c=... a=... a_minus_b=... b=...
                           (one line per segment K = 0, 1, ...: the change at
                            its start, see below)
  # pre FN=... Fx=... mu=... a2=...   (stationary state at V0 before t = 0;
                                       under --F0 also d=... a1=...)
  t,segment,FN,Fx,mu,a2               (under --F0: t,segment,FN,Fx,mu,a2,d,a1)
  ... N rows per segment, segment after segment; segment is 0-based, t is
      measured from the first change (t = 0 is the instant just after it) ...
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

} // namespace

std::string simulate_help() {
  return "Usage: mdrmap simulate" + required_usage() +
         R"(
           (--v1 V1 [--t-end T] | --history W1:T1,W2:T2,...) [options]

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

Case parameters:
)" + profile_help() +
         parameter_help(false) +
         "\nRelaxation spectrum and temperature (optional; none: the Kelvin foundation):\n" +
         rheology_help() + "\nVelocity history after t = 0 (--v1 or --history):\n" +
         history_help() + "\nSampling, per segment:\n" + sampling_help() + R"(
Other options:
  --rtol E       target accuracy: bound on the case error (below), a number
                 in (0, 0.1]. Default: 1e-4
  --solver S     auto, exact, mdr, baseline or spectrum. Default: auto
                   exact     continuum (dx -> 0) solution, semi-analytic
                   mdr       discrete MDR element simulation with error control
                   baseline  the paper's brute-force method, for reference
                   spectrum  element row of any rheology (--prony), exact
                             exponential updates, error control
                   auto      the cheapest solver that meets rtol (exact at
                             fixed depth, the load solver under --F0, spectrum
                             with --prony or a cone or power profile)
  --output FILE  write to FILE instead of stdout. A regular file (or the
                 file a symbolic link points to) is replaced at once when
                 the run succeeds and left untouched when it fails; a
                 device or a FIFO is written to, never replaced (a FIFO
                 needs its reader running); "-" means stdout
  --help         print this text and exit

)" + output_help() +
         R"(
Examples:
  mdrmap simulate --d 0.1 --R 10 --tau 1 --v 2 --v1 0.5 --output step.csv
  mdrmap simulate --d 0.1 --R 10 --tau 1 --v 1 --history 1:2,0:1000,1:5 \
      --samples 101 --spacing log       (slide-hold-slide: a hold of 1000 tau)
  mdrmap simulate --F0 0.1 --R 10 --tau 1 --v 1 --history 0.1:20,1:20
                                        (load control: a step down and up)

Exit codes:
  0  success
  1  runtime failure (the solver or writing the output failed)
  2  bad input (one line on stderr names the option and what it allows)
)";
}

int simulate_main(const std::vector<std::string>& args) {
  return command_main(kCommand, args, simulate_help, parse_args, run, "try fewer --samples");
}

} // namespace mdrmap::app
