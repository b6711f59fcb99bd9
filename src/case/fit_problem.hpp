#pragma once
// The problem of `mdrmap fit` (and of mdrmap.fit in Python): lab records
// (case/lab_record.hpp) with measured columns, the case options as for
// simulate without its history (each record is one scene's history), the
// free parameters and their bounds. Checks it all once, up front, with one
// InvalidInput naming the option (or the file and line) at fault; then
// gives the weighted residuals at any values of the free parameters, each
// evaluation one simulation per record. Pure C++ (no MPI, no printing);
// fit/least_squares.hpp does the fitting.
//
// Residuals: per record and measured column q (mu, Fx, FN at fixed depth;
// mu, Fx, d under load), per row with a value, (model - data) / w with w the
// row's sd where the record has an sd column (one measured column then),
// else the largest |data| of the column in that record (a common relative
// noise is then estimated from the residuals).
//
// The model's rtol: each evaluation is a simulation with its own error; a
// forward difference with step h in ln(parameter) must see the parameter's
// effect, not that error, so h = kStepPerRtol * rtol (rtol 1e-4: h = 1e-2).
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "case/case_input.hpp"
#include "case/lab_record.hpp"
#include "fit/least_squares.hpp"

namespace mdrmap::cases {

inline constexpr double kStepPerRtol = 100.0;

/// What a fit is asked, as given.
struct FitSpec {
  OptionTexts texts;               ///< case options (as for simulate, no history)
  std::vector<std::string> data;   ///< record files (--data)
  std::vector<std::string> free;   ///< free parameter names (--free)
  std::vector<std::string> bounds; ///< NAME=LO:HI texts (--bounds)
  std::string starts;              ///< --starts N (empty: 1)
};

/// One record and what of it is fitted.
struct FitScene {
  LabRecord record;
  std::vector<std::string> columns;    ///< the measured columns fitted
  std::map<std::string, double> scale; ///< per column without sd: its largest |data|
  bool has_sd = false;
};

class FitProblem {
public:
  /// Checks everything; throws InvalidInput ("data", "free", "bounds" or
  /// a case option).
  explicit FitProblem(const FitSpec& spec);

  const std::vector<fit::FreeParameter>& parameters() const { return params_; }
  const std::vector<FitScene>& scenes() const { return scenes_; }
  /// The difference step, the pre-search and known_sd for fit::fit.
  fit::Options options() const;
  double rtol() const { return rtol_; }
  /// Number of residuals.
  std::size_t size() const { return m_; }

  /// The weighted residuals at x (the free parameters' values), records
  /// in order; empty where the model refuses x (out of range, a failed
  /// run).
  std::vector<double> residuals(const std::vector<double>& x) const;

  /// Per record, the model's values of its columns at its rows (NaN where
  /// the model refuses x), as the plot shows them.
  std::vector<std::map<std::string, std::vector<double>>>
  model_values(const std::vector<double>& x) const;

  /// The option texts of a case at x for record k (simulate's options).
  OptionTexts texts_at(const std::vector<double>& x, std::size_t k) const;

private:
  void read_free(const FitSpec& spec, const CaseInput& start);
  void read_bounds(const FitSpec& spec);
  std::vector<std::map<std::string, std::vector<double>>> run(const std::vector<double>& x) const;

  OptionTexts texts_;
  std::vector<fit::FreeParameter> params_;
  std::vector<FitScene> scenes_;
  bool load_ = false;
  double rtol_ = kDefaultRtol;
  int starts_ = 1;
  std::size_t m_ = 0;
};

/// Calls the problem for each point in turn.
class SerialEvaluator : public fit::Evaluator {
public:
  explicit SerialEvaluator(const FitProblem& p) : p_(p) {}
  std::vector<std::vector<double>>
  evaluate(const std::vector<std::vector<double>>& points) override;

private:
  const FitProblem& p_;
};

/// Spreads each batch over `threads` threads (point k to thread k mod
/// threads); the Python module's evaluator (it runs without the GIL).
class ThreadEvaluator : public fit::Evaluator {
public:
  ThreadEvaluator(const FitProblem& p, unsigned threads) : p_(p), threads_(threads ? threads : 1) {}
  std::vector<std::vector<double>>
  evaluate(const std::vector<std::vector<double>>& points) override;

private:
  const FitProblem& p_;
  unsigned threads_;
};

} // namespace mdrmap::cases
