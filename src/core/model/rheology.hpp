#pragma once
// The foundation element's rheology (docs/design.md, "Rheology"): the linear
// network of the material's own shear relaxation, each modulus times 4 dx,
//
//   p = 4 [ G u + G tau u' + sum_k G_k (u - q_k) ],   tau_k q_k' = u - q_k,
//
// a long-term spring G, a parallel dashpot of time tau >= 0 and N <= 32
// Maxwell branches (G_k, tau_k). N = 0 is the Kelvin foundation of the seed;
// tau = 0, N = 1 the standard linear solid; tau = 0, N > 1 a Prony series.
// A shift factor aT multiplies every relaxation time (time-temperature
// superposition). The solvers see the shifted times only (shifted()).
#include <cstddef>
#include <vector>

namespace mdrmap {

/// One Maxwell branch: a spring G_k in series with a dashpot of time tau_k.
struct Branch {
  double G = 0.0;   ///< modulus, > 0
  double tau = 0.0; ///< relaxation time, > 0
};

inline constexpr std::size_t kMaxBranches = 32;

struct Rheology {
  double G = 1.0;               ///< long-term (rubbery) shear modulus, > 0
  double tau = 0.0;             ///< time of the parallel dashpot eta/G, >= 0 (0: none)
  std::vector<Branch> branches; ///< Maxwell branches (the Prony terms), at most kMaxBranches
  double aT = 1.0;              ///< time-temperature shift factor: multiplies tau and every tau_k

  /// No branches: the Kelvin foundation, the model of the closed-form solvers.
  bool kelvin() const { return branches.empty(); }
  /// Glassy (instantaneous) modulus G + sum G_k; G for the Kelvin foundation.
  double G0() const;
  /// The longest relaxation time of the element, shifted: aT max(tau, tau_k).
  /// 0 for the purely elastic foundation.
  double longest_time() const;
  /// The same element with aT folded into its times (aT = 1).
  Rheology shifted() const;
  /// Relaxation modulus G(t) = G + sum G_k exp(-t / (aT tau_k)) for t > 0
  /// (the dashpot's delta at t = 0 left out).
  double relaxation_modulus(double t) const;
};

/// Throws InvalidInput naming the key ("G", "tau", "aT", "prony" for the
/// count, "G<k>"/"tau<k>" for a term) unless every value is in range and the
/// shifted times are finite.
void validate(const Rheology& r);

} // namespace mdrmap
