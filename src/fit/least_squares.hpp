#pragma once
// Nonlinear least squares for fitting a model whose every evaluation is a
// full simulation (docs/fitting.md): the free parameters in transformed
// coordinates (the logarithm of a positive parameter, the parameter over
// its scale otherwise), bounds, a coarse pre-search for the start, Ceres
// Solver's Levenberg-Marquardt driving the iterations, and a Jacobian by
// forward differences whose columns are evaluated as one batch through an
// Evaluator (so that a caller can spread them over ranks or threads). At the
// optimum: the covariance from the Jacobian, the directions that the data do
// not determine, 95% intervals from the Student t quantile. No printing, no
// MPI: the caller's Evaluator decides where the model runs.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace mdrmap::fit {

/// The model: the weighted residuals (model - data) / weight at a batch of
/// parameter vectors (in the free parameters' own units and order). Every
/// call returns one vector per point, all of the same length, or an empty
/// vector for a point the model does not take (out of its range, a failed
/// run); it throws for what ends the fit (bad input, interruption).
class Evaluator {
public:
  virtual ~Evaluator() = default;
  virtual std::vector<std::vector<double>>
  evaluate(const std::vector<std::vector<double>>& points) = 0;
};

/// One free parameter: its name, start and bounds (inclusive).
struct FreeParameter {
  std::string name;
  double start = 1.0;
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool log = true; ///< positive: fitted in its logarithm
};

struct Options {
  /// Forward-difference step in the transformed coordinate (a relative step
  /// of a positive parameter). The model's error must be well below it
  /// (the caller picks the model's rtol from it: docs/fitting.md).
  double step = 1e-2;
  int grid_points = 5; ///< pre-search points per parameter (1: none)
  double search_decades =
      1.0; ///< pre-search span either side of the start, unbounded log parameters
  std::size_t max_grid = 125; ///< largest pre-search (fewer points per parameter beyond it)
  int starts = 1;             ///< Levenberg-Marquardt runs from the best pre-search points
  int max_iterations = 50;    ///< per run
  bool known_sd = false;      ///< residuals weighted by their standard deviations: sigma = 1
  /// A direction whose 95% half-width in the transformed coordinates exceeds
  /// this is not determined by the data (a decade for a log parameter).
  double flat_halfwidth = 2.302585092994046;
  /// Profile-likelihood bounds where the problem is clearly nonlinear: where
  /// the cost at a covariance bound (the others re-fitted) misses its
  /// expected rise t^2 sigma^2 by more than this fraction of it.
  bool profile = true;
  double profile_tolerance = 0.1;
};

struct ParameterResult {
  std::string name;
  double value = 0.0;
  double stderr_ = 0.0; ///< standard error (delta method for a log parameter)
  double ci95_lo = 0.0, ci95_hi = 0.0;
  double cov_lo = 0.0, cov_hi = 0.0;      ///< the covariance's 95% interval
  std::string ci95_method = "covariance"; ///< or "profile" where either bound is the profile's
  bool at_bound = false;
};

struct Result {
  std::vector<ParameterResult> parameters;
  std::vector<std::vector<double>> correlation; ///< n x n
  std::vector<double> singular_values;   ///< of the weighted Jacobian, transformed coordinates
  std::vector<std::string> undetermined; ///< parameters in a direction the data do not fix
  std::vector<double> residuals;         ///< weighted, at the optimum
  double ssr = 0.0;                      ///< sum of squared weighted residuals
  double sigma = 0.0;                    ///< residual standard deviation used (1 with known_sd)
  double rms = 0.0;                      ///< sqrt(ssr / m)
  std::size_t m = 0;                     ///< residuals
  std::size_t evaluations = 0;           ///< parameter vectors evaluated (all batches)
  std::size_t batches = 0;               ///< calls of the Evaluator
  int iterations = 0;                    ///< Levenberg-Marquardt iterations, all starts
  bool converged = false;
  std::string termination; ///< Ceres's summary of the best run
  double t_quantile = 0.0; ///< Student t 0.975 quantile at m - n degrees of freedom
};

/// Fits. Throws std::invalid_argument for no parameters, a start outside its
/// bounds or fewer residuals than parameters + 1, std::runtime_error where
/// no pre-search point could be evaluated; what the Evaluator throws.
Result fit(const std::vector<FreeParameter>& params, Evaluator& model, const Options& opt);

} // namespace mdrmap::fit
