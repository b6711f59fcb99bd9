#include "app/stationary_cmd.hpp"
#include "app/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "app/case_input.hpp"
#include "app/cli_common.hpp"
#include "app/csv_output.hpp"
#include "app/exit_codes.hpp"
#include "app/output_file.hpp"
#include "app/prony_input.hpp"
#include "core/metrics/stationary.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "mdrmap/version.hpp"

namespace po = boost::program_options;

namespace mdrmap::app {
namespace {

constexpr const char* kCommand = "stationary";
constexpr const char* kColumns = "v,d,a1,a2,FN,Fx,mu";
/// Rows of one run at most: every state is computed before any is written.
constexpr long kMaxVelocities = 1'000'000;

// --- Options -------------------------------------------------------------------

/// Whether an option of simulate's case (case_option_spellings) describes the
/// stationary case: the table's parameters but the sampling (with --v, the
/// velocity), the profile, the spectrum and the temperature. The history,
/// the spacing and how to run (rtol, solver) are simulate's only.
bool stationary_case_option(const std::string& name) {
  if (const ParamSpec* p = find_parameter(name)) return p->part != Part::Sampling;
  return name == "profile" || name == "prony" || name == "prony-file" || name == "T" ||
         name == "wlf";
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

// --- Velocities ----------------------------------------------------------------

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> items;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = text.find(sep, start);
    items.push_back(text.substr(start, at == std::string::npos ? at : at - start));
    if (at == std::string::npos) return items;
    start = at + 1;
  }
}

/// A velocity of --v-list or --v-range (`what` names it): the whole text a
/// number in the range of the table's v.
double velocity(const std::string& option, const std::string& what, const std::string& text) {
  const ParamSpec& v = *find_parameter("v");
  const std::string t = trimmed(text);
  char* end = nullptr;
  const double x = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !v.contains(x))
    throw InvalidInput(option, what + " must be a velocity (" + dim_name(v.dim) + "), " +
                                   v.allowed() + ", got " + shown(text));
  return x;
}

std::string list_count_text() {
  return "at most " + std::to_string(kMaxVelocities) + " velocities";
}

/// --v-list V1,V2,...: the velocities in the order given.
std::vector<double> velocity_list(const std::string& text) {
  const std::vector<std::string> items = split(text, ',');
  if (items.size() > static_cast<std::size_t>(kMaxVelocities))
    throw InvalidInput("v-list", "has " + std::to_string(items.size()) + " items; " +
                                     list_count_text() + " are allowed");
  std::vector<double> out;
  for (std::size_t k = 0; k < items.size(); ++k)
    out.push_back(velocity("v-list", "item " + std::to_string(k + 1), items[k]));
  return out;
}

/// N of --v-range: an integer from 2 to kMaxVelocities.
long range_count(const std::string& text) {
  const std::string t = trimmed(text);
  const bool digits = !t.empty() && t.size() <= 9 &&
                      std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
  const long n = digits ? std::strtol(t.c_str(), nullptr, 10) : 0;
  if (n < 2 || n > kMaxVelocities)
    throw InvalidInput("v-range", "N (LO:HI:N) must be an integer from 2 to " +
                                      std::to_string(kMaxVelocities) + ", got " + shown(text));
  return n;
}

/// --v-range LO:HI:N: N velocities from LO to HI, equally spaced in log v,
/// the ends exactly LO and HI.
std::vector<double> velocity_range(const std::string& text) {
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() != 3)
    throw InvalidInput("v-range", "must be LO:HI:N, N velocities log-spaced from LO to HI "
                                  "(0 < LO < HI, N >= 2), got " +
                                      shown(text));
  const double lo = velocity("v-range", "LO", parts[0]);
  const double hi = velocity("v-range", "HI", parts[1]);
  if (!(lo < hi))
    throw InvalidInput("v-range", "LO must be below HI (LO:HI:N), got LO = " + format_number(lo) +
                                      ", HI = " + format_number(hi));
  const long n = range_count(parts[2]);
  std::vector<double> v(static_cast<std::size_t>(n));
  // in decades: whole decades (1e-3:1e3:7) come out as the powers of ten
  const double l0 = std::log10(lo), span = std::log10(hi) - l0;
  for (long j = 0; j < n; ++j)
    v[static_cast<std::size_t>(j)] =
        std::pow(10.0, l0 + span * static_cast<double>(j) / static_cast<double>(n - 1));
  v.front() = lo;
  v.back() = hi;
  return v;
}

// --- Command line --------------------------------------------------------------

struct StationaryArgs {
  CaseInput in;
  std::string velocity_option;    ///< v, v-list or v-range: named for a velocity's problem
  std::vector<double> velocities; ///< the rows, in order
  std::string output;             ///< empty or "-": stdout
};

/// Which of --v, --v-list, --v-range gives the velocities: exactly one.
std::string velocity_option(const po::variables_map& vm) {
  std::string given, first;
  for (const char* o : {"v", "v-list", "v-range"}) {
    if (!vm.count(o)) continue;
    given += (given.empty() ? "--" : " and --") + std::string(o);
    if (first.empty()) first = o;
  }
  if (!given.empty() && given.find(" and ") == std::string::npos) return first;
  throw InvalidInput("", "give exactly one of --v V, --v-list V1,V2,... or --v-range LO:HI:N (the "
                         "velocities of the stationary states, length/time); got " +
                             (given.empty() ? std::string("none") : given));
}

/// The case from its option texts, as simulate reads it, with a history of
/// one segment at the case's velocity (its first checks of a velocity blame
/// `vopt`).
CaseInput read_stationary_case(OptionTexts texts, const std::string& vopt) {
  texts["history"] = texts["v"] + ":1";
  try {
    return read_case_input(texts);
  } catch (const InvalidInput& e) {
    if (e.option() == "history" || (e.option() == "v" && vopt != "v"))
      throw InvalidInput(vopt, e.what());
    throw;
  }
}

/// The case's checks of a velocity (validate: w tau / a and the stationary
/// contact representable) at w; a problem blames `vopt`.
void check_velocity(const Case& base, double w, const std::string& vopt) {
  Case c = base;
  c.history.v0 = w;
  c.history.segments = {Segment{w, 1.0}};
  try {
    validate(c);
  } catch (const InvalidInput& e) {
    const std::string who = e.option().empty() ? "" : "--" + e.option() + " ";
    throw InvalidInput(vopt, "at v = " + format_number(w) + ": " + who + e.what());
  }
}

/// Parses and validates the command line. Throws InvalidInput, or lets
/// boost::program_options errors through.
StationaryArgs parse_args(const std::vector<std::string>& args) {
  const po::variables_map vm = option_texts(args, kCommand, option_names(), "--v 0.1");
  OptionTexts texts = given_texts(vm, case_options());
  StationaryArgs a;
  a.velocity_option = velocity_option(vm);
  if (a.velocity_option == "v-list") a.velocities = velocity_list(vm["v-list"].as<std::string>());
  if (a.velocity_option == "v-range")
    a.velocities = velocity_range(vm["v-range"].as<std::string>());
  if (!a.velocities.empty()) // the slowest: the case's own checks at v the mildest
    texts["v"] = format_double(*std::min_element(a.velocities.begin(), a.velocities.end()));
  a.in = read_stationary_case(texts, a.velocity_option);
  if (a.velocities.empty()) a.velocities = {a.in.c.history.v0};
  for (const double w : a.velocities)
    check_velocity(a.in.c, w, a.velocity_option);
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
  if (t) s += " T=" + format_double(t->T) + " wlf=" + format_wlf(t->wlf);
  if (c.loading.by_force()) s += " a0=" + format_double(c.a0());
  return s;
}

void write_csv(std::FILE* out, const StationaryArgs& a, const std::vector<State>& states) {
  std::fprintf(out, "# mdrmap %s (%s) stationary\n", kVersion, kGitCommit);
  std::fprintf(out, "%s\n%s\n", stationary_case_line(a.in.c, a.in.temperature).c_str(), kColumns);
  for (std::size_t k = 0; k < states.size(); ++k) {
    const State& s = states[k];
    std::string row = format_double(a.velocities[k]);
    for (const double x : {s.d, s.a1, s.a2, s.FN, s.Fx, s.mu})
      row += "," + format_double(x);
    std::fprintf(out, "%s\n", row.c_str());
  }
}

int run(const StationaryArgs& a) {
  OutputFile out(a.output); // opened first: a bad path fails before any work
  std::vector<State> states;
  states.reserve(a.velocities.size());
  for (const double w : a.velocities)
    states.push_back(stationary_state(a.in.c, w));
  write_csv(out.get(), a, states);
  out.commit();
  return kExitOk;
}

// --- Help ----------------------------------------------------------------------

/// The profile and the table's case parameters (not v, not the sampling),
/// as simulate's help gives them.
std::string case_help() {
  std::string s =
      help_entry("--profile P", "the indenter: parabola (f = r^2/2R, --R), cone (--beta, the angle "
                                "of its surface to the plane) or power (f = A r^n, --n --A); MDR "
                                "image g(x) = kappa_n A |x|^n. Default: parabola");
  for (const auto& p : case_parameters())
    if (p.part != Part::Sampling && p.part != Part::History) s += parameter_entry(p);
  return s;
}

std::string velocity_help() {
  const ParamSpec& v = *find_parameter("v");
  const std::string unit = std::string("(") + dim_name(v.dim) + ") ", range = v.allowed();
  return help_entry("--v V", unit + "one velocity, " + range) +
         help_entry("--v-list V1,V2,...", unit + "velocities in the order given, each " + range +
                                              "; " + list_count_text()) +
         help_entry("--v-range LO:HI:N",
                    unit +
                        "N velocities equally spaced in log v from LO to HI, the ends "
                        "exactly LO and HI: LO and HI each " +
                        range + ", LO < HI; N an integer from 2 to " +
                        std::to_string(kMaxVelocities)) +
         "Each velocity must pass the checks of --v in mdrmap simulate: v tau / a1 (a0\n"
         "under --F0) and the stationary contact at v representable in doubles.\n";
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

std::string examples_help() {
  return R"(
Examples:
  mdrmap stationary --d 0.1 --R 10 --tau 1 --v-range 1e-3:1e3:61
  mdrmap stationary --profile cone --beta 10 --d 0.01 --tau 1 --v-list 0.01,1
  mdrmap stationary --profile power --n 1.5 --A 1 --F0 0.01 --tau 0 \
      --prony 1:0.1,2:10 --v 1 --output power.csv

Exit codes:
  0  success
  1  runtime failure (computing a state or writing the output failed)
  2  bad input (one line on stderr names the option and what it allows;
     nothing is written)
)";
}

} // namespace

std::string stationary_help() {
  return R"(Usage: mdrmap stationary (--d D | --F0 F0) --tau TAU
           (--R R | --profile cone --beta DEG | --profile power --n N --A A)
           (--v V | --v-list V1,V2,... | --v-range LO:HI:N) [options]

Prints the stationary sliding states of one case at one or more velocities,
in the method of dimensionality reduction (MDR): the state that the contact
reaches after sliding steadily at the velocity v for long enough, from the
closed forms (or by quadrature) of the core, with no time stepping. Any
indenter profile (parabola, cone, power law), the Kelvin foundation or a
relaxation spectrum (--prony), at fixed depth (--d) or under the normal load
F0 (--F0: the depth follows). The case is given as to mdrmap simulate,
without its velocity history and sampling.

Any consistent units work (e.g. mm, s, MPa): d, R, a1, a2 are lengths, tau a
time, velocities length/time; forces come out in units of G * length^2.

Case parameters:
)" + case_help() +
         "\nRelaxation spectrum and temperature (optional; none: the Kelvin foundation):\n" +
         rheology_help() + "\nVelocities (exactly one of --v, --v-list, --v-range):\n" +
         velocity_help() + R"(
Other options:
  --output FILE  write to FILE instead of stdout, as mdrmap simulate does: a
                 regular file (or the file a symbolic link points to) is
                 replaced at once when the run succeeds and left untouched
                 when it fails; a device or a FIFO is written to, never
                 replaced; "-" means stdout
  --help         print this text and exit

)" + output_help() +
         examples_help();
}

int stationary_main(const std::vector<std::string>& args) {
  return command_main(kCommand, args, stationary_help, parse_args, run, "try fewer velocities");
}

} // namespace mdrmap::app
