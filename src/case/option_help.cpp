#include "case/option_help.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "core/model/rheology.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap::cases {
namespace {

/// "(UNIT), RANGE" of a spec, as the texts give a value's unit and range.
std::string unit_range(const ParamSpec& p) {
  return "(" + std::string(dim_name(p.dim)) + "), " + p.allowed();
}

std::vector<OptionHelp> geometry_and_material() {
  const std::string n = std::to_string(kMaxBranches);
  return {
      {"profile", "P",
       "the indenter: parabola (f = r^2/2R, --R), cone (--beta, the angle of its surface to the "
       "plane) or power (f = A r^n, --n --A); MDR image g(x) = kappa_n A |x|^n",
       "parabola", ""},
      {"material", "FILE",
       "the material from an Abaqus card: *ELASTIC E, nu (MODULI=LONG TERM, the default, or "
       "INSTANTANEOUS; G = E / (4 (1 - nu^2))), *VISCOELASTIC, TIME=PRONY rows g_i, k_i, tau_i "
       "normalised by the instantaneous modulus G0 (G_i = g_i G0, G = G0 (1 - sum g_i); nonzero "
       "bulk terms k_i are noted and ignored) and *TRS, DEFINITION=WLF Tref, C1, C2 (the WLF "
       "constants of --T). Or pyvisco's Prony CSV (tau_i, alpha_i normalised by E_0 = 3 G0 or "
       "G_0). Instead of --G, --prony, --prony-file and --wlf",
       "", ""},
      {"prony", "G1:TAU1,G2:TAU2,...",
       "the Maxwell branches of a relaxation spectrum (Prony series): branch k is a spring of "
       "modulus Gk " +
           unit_range(branch_modulus_spec()) +
           ", in series with a dashpot of relaxation time tauk " + unit_range(branch_time_spec()) +
           "; at most " + n +
           " terms, absolute values in the units of --G and --tau. With a spectrum --G "
           "(required) is the long-term (rubbery) modulus and --tau the parallel dashpot's time "
           "(0: none); G(t) = G + sum Gk exp(-t / (aT tauk))",
       "", ""},
      {"prony-file", "FILE",
       "the same terms from a CSV file whose header names its columns, in any order: tau and "
       "one of G (shear moduli), E (Young's moduli, G = E / (4 (1 - nu^2))) or g (moduli "
       "normalised by the instantaneous modulus, given by a line '# G0 = VALUE' or '# E0 = "
       "VALUE'; then G = G0 (1 - sum g) and --G is not given). At most " +
           n +
           " terms; blank lines and other lines starting with # are skipped, a UTF-8 BOM is "
           "read. A regular file of at most 1 MiB, lines of at most 4096 characters (a FIFO or a "
           "device is refused). Give --prony or --prony-file, not both",
       "", ""},
      {"nu", "NU",
       "Poisson's ratio of a spectrum file's Young's moduli (column E or E0), -1 < NU <= 0.5",
       "0.5 (G = E / 3)", ""},
      {"T", "TEMP",
       "temperature: with --wlf, gives the shift factor aT by the WLF equation (instead of "
       "--aT), a finite number > TREF - C2 with an optional unit, 25C or 298.15K (converted to "
       "TREF's unit; a bare number is in the other's unit)",
       "", ""},
      {"wlf", "C1:C2:TREF",
       "WLF constants of --T: log10 aT = -C1 (T - TREF) / (C2 + T - TREF), C1 > 0, C2 > 0 (a "
       "temperature difference), TREF the reference temperature (aT = 1) with an optional unit, "
       "e.g. 8.86:101.6:25C",
       "", ""},
      {"allow-large-shift", "",
       "take a shift of --T more than 12 decades from 1 (|log10 aT| > 12), which is refused "
       "otherwise: most often a C/K mix-up",
       "", ""}};
}

std::vector<OptionHelp> history_sampling_solver() {
  const ParamSpec &w = segment_velocity_spec(), &T = segment_duration_spec();
  return {
      {"v1", "V1",
       "one step: the sliding velocity from t = 0 on " + unit_range(w) +
           "; 0 stops the indenter, V1 > V0 is a speed-up",
       "", ""},
      {"t-end", "T", "with --v1: how long the step is followed " + unit_range(T),
       "6 tau (with a spectrum: 6 times the longest shifted time aT max(tau, tauk)); for a "
       "purely elastic foundation, 6 a1/min(V0,V1) (6 a1/V0 if V1 = 0), a0 in place of a1 "
       "under --F0",
       ""},
      {"history", "W1:T1,W2:T2,...",
       "segments one after another from t = 0: sliding velocity Wk " + unit_range(w) +
           ", 0 is a hold; duration Tk " + unit_range(T) + "; at most " +
           std::to_string(kMaxSegments) +
           " segments. --v1 V1 --t-end T is --history V1:T; give one of the two forms, not both",
       "", ""},
      {"history-file", "FILE",
       "a lab record as the history: CSV with a header naming the columns t (time) and v "
       "(load-point velocity), in any order, other columns ignored; '#' comments and blank lines "
       "allowed; t strictly increasing, v >= 0. V0 is the first row's v, t = 0 the first row's "
       "time; a row's v holds until the next row's time, the last row ends the record. The "
       "output rows are the record's rows, with columns v and slip. Not with --v, --v1, "
       "--t-end, --history or the sampling options",
       "", ""},
      {"spacing", "S",
       "linear or log: where the N instants of a segment k (start t_k, duration T_k) lie", "linear",
       "                   linear  t_k + j T_k/(N-1), j = 0..N-1\n"
       "                   log     t_k, then t_k + T_k 10^(-D (N-1-j)/(N-2)),\n"
       "                           j = 1..N-1 (D = --log-decades): a long hold and\n"
       "                           the transient at its start both resolved\n"},
      {"rtol", "E",
       std::string("target accuracy: bound on the case error (see the output), ") + kRtolAllowed,
       "1e-4", ""},
      {"solver", "S", "auto, exact, row or baseline", "auto",
       "                   auto      the cheapest solver that meets rtol: exact\n"
       "                             for the Kelvin parabola at fixed depth, its\n"
       "                             load solver (kelvin_load) under --F0, row\n"
       "                             otherwise (--prony, a cone or power profile)\n"
       "                   exact     continuum (dx -> 0) solution, semi-analytic:\n"
       "                             the Kelvin parabola at fixed depth\n"
       "                   row       element row of every case (any rheology,\n"
       "                             profile, depth or load), exact exponential\n"
       "                             updates, error control (spectrum: old name)\n"
       "                   baseline  fixed-step brute-force row of every case, the\n"
       "                             independent check; a1/dx = 5/rtol (<= 4000)\n"}};
}

} // namespace

std::string OptionHelp::full(const std::string& extra) const {
  std::string s = text;
  if (!extra.empty()) s += ". " + extra;
  if (!fallback.empty()) s += (extra.empty() ? ". " : " ") + std::string("Default: ") + fallback;
  return s;
}

const std::vector<OptionHelp>& case_option_help() {
  static const std::vector<OptionHelp> all = [] {
    std::vector<OptionHelp> v = geometry_and_material();
    for (auto& h : history_sampling_solver())
      v.push_back(std::move(h));
    return v;
  }();
  return all;
}

const OptionHelp& option_help(const std::string& name) {
  for (const OptionHelp& h : case_option_help())
    if (h.name == name) return h;
  throw std::out_of_range("option_help: no option " + name);
}

} // namespace mdrmap::cases
