// Profile-likelihood bounds of the 95% intervals. The profile of parameter
// i is S_i(z) = the least cost with z_i = z held and the others re-fitted;
// its 95% bound is where S_i rises by t^2 sigma^2 above the optimum's cost
// (with an estimated sigma the F-test's S0 (1 + t^2 / (m - n)), the same).
// The covariance's bound is kept where the profile's rise there is within
// Options::profile_tolerance of that: the problem is linear enough. Else
// secant steps on g(z) = sqrt(S_i(z) - S0), nearly linear in z, find it.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "fit/batch_cost.hpp"

namespace mdrmap::fit {
namespace {

constexpr int kSecantSteps = 8;
constexpr double kRootTolerance = 0.02; ///< of sqrt(rise) at the bound

/// S_i(z_i = zi) - S0, from `from` (the others' start; updated to their optimum); NaN
/// where the model refuses.
double rise(const Transform& tr, const BatchCost& cost, std::size_t i, double zi,
            std::vector<double>& from, const Options& opt, double s0, Result& out) {
  from[i] = zi;
  double s = NAN;
  if (tr.size() == 1) {
    const auto r = cost.evaluate({from}).front();
    if (!r.empty()) s = std::inner_product(r.begin(), r.end(), r.begin(), 0.0);
  } else {
    const Run run = levenberg_marquardt(tr, cost, from, opt, i);
    out.iterations += run.iterations;
    if (std::isfinite(run.cost)) {
      from = run.z;
      s = run.cost;
    }
  }
  return s - s0;
}

/// The bound on side `side` (-1, +1) of parameter i in z, from the
/// covariance's bound zc; NaN where the profile cannot be followed.
double bound(const Transform& tr, const BatchCost& cost, const std::vector<double>& z,
             std::size_t i, int side, double zc, const Options& opt, Result& out) {
  const double s0 = out.ssr, target = out.t_quantile * out.sigma;
  const double limit = side < 0 ? tr.z_lo(i) : tr.z_hi(i);
  std::vector<double> from = z;
  double za = z[i], ga = 0.0, zb = zc;
  double gb = std::sqrt(std::max(0.0, rise(tr, cost, i, zb, from, opt, s0, out)));
  if (!std::isfinite(gb)) return zc;
  if (std::fabs(gb * gb - target * target) <= opt.profile_tolerance * target * target) return zc;
  for (int k = 0; k < kSecantSteps; ++k) {
    if (std::fabs(gb - target) <= kRootTolerance * target) return zb;
    double zn = gb > ga ? zb + (target - gb) * (zb - za) / (gb - ga) : zb + 2.0 * (zb - za);
    // at most twice as far from the optimum per step, never past the bound
    const double far = z[i] + 2.0 * (zb - z[i]);
    zn = side > 0 ? std::min({zn, far, limit}) : std::max({zn, far, limit});
    if (zn == zb) return zb; // at the bound, the rise still short: the interval ends there
    const double gn = std::sqrt(std::max(0.0, rise(tr, cost, i, zn, from, opt, s0, out)));
    if (!std::isfinite(gn)) return NAN;
    za = zb;
    ga = gb;
    zb = zn;
    gb = gn;
  }
  return std::fabs(gb - target) <= 4.0 * kRootTolerance * target ? zb : NAN;
}

} // namespace

void profile_intervals(const Transform& tr, const BatchCost& cost, const std::vector<double>& z,
                       const Options& opt, Result& out) {
  if (!opt.profile) return;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    ParameterResult& p = out.parameters[i];
    if (!std::isfinite(p.cov_lo) || !std::isfinite(p.cov_hi)) continue;
    double zb[2];
    for (const int side : {-1, 1}) {
      const double zc = tr.to_z(i, side < 0 ? p.cov_lo : p.cov_hi);
      zb[side > 0] = bound(tr, cost, z, i, side, zc, opt, out);
    }
    for (const int side : {-1, 1}) {
      double& ci = side < 0 ? p.ci95_lo : p.ci95_hi;
      // where the profile cannot be followed (the model refuses a point)
      // the covariance's bound stays
      const double b = zb[side > 0];
      if (!std::isfinite(b) || tr.to_x(i, b) == ci) continue;
      p.ci95_method = "profile";
      ci = tr.to_x(i, b);
    }
  }
}

} // namespace mdrmap::fit
