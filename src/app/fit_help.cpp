// The help of mdrmap fit (its options and what it writes), apart from the
// command itself: the program mdrmap prints it without loading what the fit
// links (Ceres, MPI; the fit runs in mdrmap-fit).
#include <string>
#include <vector>

#include "app/cli_common.hpp"
#include "app/fit_cmd.hpp"
#include "app/help_layout.hpp"

namespace mdrmap::app {
namespace {

constexpr const char* kCommand = "fit";

std::vector<HelpSection> sections() {
  std::vector<HelpEntry> fitting = {
      {"--data FILE", "a lab record (repeat for several scenes): CSV with columns t, v (as for "
                      "simulate --history-file) and what was measured: mu, Fx, FN at fixed depth; "
                      "mu, Fx, d under --F0; an empty or nan value is not measured; an optional sd "
                      "column (with one measured column) weights the rows by 1/sd"},
      {"--free NAME,...", "the parameters to fit: R (or beta, n, A), d or F0, G, tau, aT or T, "
                          "a --prony spectrum's Gk, tauk, and Gscale (--G and every --prony "
                          "modulus times it); their values as given are the start"},
      {"--bounds NAME=LO:HI", "bounds of a free parameter (repeatable); LO > 0 for a positive "
                              "one. Default: none (the pre-search spans a decade either side "
                              "of the start)"},
      {"--starts N", "Levenberg-Marquardt runs from the N best pre-search points, the best "
                     "result kept; 1 to 25. Default: 1"},
      {"--rtol E", "the model's accuracy per evaluation, in (0, 0.001]; the difference step is "
                   "100 E in ln(parameter). Default: 1e-4"},
      {"--output FILE", "the JSON result. Default: standard output"},
      {"--plot FILE.png", "also draw the records, the fitted model and the residuals (python3 -m "
                          "mdrmap plot_fit on the JSON; needs matplotlib)"}};
  const std::vector<HelpEntry> geometry = geometry_entries(false), material = material_entries();
  return {{"fit", "Fitting", fitting},
          {"geometry", "Case geometry and loading (the start values of free ones)", geometry},
          {"material", "Material", material},
          {"help", "Help", {help_option_entry(kCommand), help_all_option_entry(kCommand)}}};
}

std::string usage() {
  return "Usage: mdrmap fit --data FILE [--data FILE ...] --free NAME[,NAME...]\n"
         "           [--bounds NAME=LO:HI ...] [case options as for simulate]\n"
         "       mpirun -np P mdrmap fit ...   (the ranks share the evaluations)\n";
}

std::string examples() {
  return R"(Example:
  mdrmap fit --data a.csv --data b.csv --free R,aT --d 0.1 --R 8 --tau 1 \
      --aT 2 --output fit.json
)";
}

} // namespace

std::string fit_help() {
  return usage() + R"(
Fits case parameters to lab records by least squares (Ceres Solver); writes
the values, standard errors, 95% intervals and correlations as JSON.

)" + options_summary(sections()) +
         "\n" + examples() + "\n" + full_list_pointer(kCommand);
}

std::string fit_help_all() {
  return usage() + R"(
Fits the free parameters of a case to one or more lab records (each record
is one scene: its rows give the velocity history, as simulate --history-file,
and the measured values). Each evaluation simulates every record. The fit
works in ln(parameter) for positive parameters; it starts from the best point
of a coarse pre-search (5 points a parameter, up to three parameters; 3 for
four; over the bounds, or a decade either side of the start) and runs
Levenberg-Marquardt (--starts: from several) with a forward-difference
Jacobian whose columns are evaluated together (over the ranks under mpirun).
Residuals are (model - data)/sd with an sd column, else (model -
data)/max|data| per column with one common noise level estimated from them.
At the optimum: the covariance from the Jacobian, 95% intervals from the
Student t quantile (asymmetric for a log parameter); where the cost at a
bound, the others re-fitted, misses its expected rise by over 10%, the
profile-likelihood bound instead. A parameter the records do not determine
(its interval would span more than a factor 10) is reported as such, exit 2,
nothing written.

)" + full_options(sections()) +
         R"(
Output (JSON): parameters.NAME.{value, stderr, ci95, ci95_method,
ci95_covariance, start, log, at_bound};
correlation.{names, matrix}; rms (of the weighted residuals), sigma, residuals,
evaluations, batches, iterations, converged, termination, rtol, step,
wall_seconds, ranks, command, best_fit (mdrmap simulate of each record at the
fitted values); records (per record its file, t, v and per fitted column the
data and the model: python3 -m mdrmap plot_fit FIT.json -o FIT.png draws them).

)" + examples() +
         R"(
Exit codes:
  0  success
  1  runtime failure (the model or writing the output failed)
  2  bad input (one line on stderr names the option, or the file and line)
)";
}

} // namespace mdrmap::app
