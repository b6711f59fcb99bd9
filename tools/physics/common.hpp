#pragma once
// What every study of mdrmap_spectrum_physics shares: its options, the
// spectra it measures, the cases it builds from them and its CSV files.
//
// Units: R = 1, G = 1 (PIB: G = 1e5 Pa), d = 1 at fixed depth (a1 = 1) and
// F0 = 16/3 under load (a0 = 1): mu is in units of a/R, velocities in a per
// unit time.
#include <fstream>
#include <string>
#include <vector>

#include "core/model/case.hpp"
#include "core/model/rheology.hpp"

namespace mdrmap::physics {

struct Options {
  std::string out;
  std::string pib = "jobs/examples/pib_prony.csv";
  int part = 0; // 0: all
  double rtol = 1e-3;
  int healing_run = 0;   // part 3: only this run (1..9), 0: all
  int load_material = 0; // part 6: only this material (1..3), 0: all
};

/// tau = 0 and N terms a decade apart, the longest at tau_max = 1, moduli
/// G_k proportional to tau_k^p with sum G_k = G0/G - 1 (G = 1).
Rheology decade_spectrum(int n, double glassy_ratio, double p = 0.0);

/// tau = 0 and N terms a decade apart (longest tau = 1) whose relaxation modulus
/// falls so that sqrt(G(t)/G0) drops by the same step at each term: G(tau_k^+) =
/// G0 (1 - k s)^2, s = (1 - sqrt(G/G0)) / N, the fastest term the heaviest.
Rheology sqrt_linear_spectrum(int n, double glassy_ratio);

/// The Prony series of a CSV file "G,tau" with the long-term modulus G added.
Rheology read_pib(const std::string& path, double G);

/// Fixed depth d = 1 (a1 = 1) or load F0 = 16/3 G (a0 = 1); R = 1.
Case make_case(const Rheology& r, bool load);

/// Stationary mu at v (closed form), at the case's depth or under its load.
double mu_stationary(const Case& c, double v);

/// lo .. hi, `per_decade` points per decade, both ends included.
std::vector<double> logspace(double lo, double hi, int per_decade);

/// Opens DIR/name for writing (10 digits) with its header line; throws if it cannot.
std::ofstream open_csv(const Options& o, const std::string& name, const std::string& header);

} // namespace mdrmap::physics
