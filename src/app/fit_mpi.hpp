#pragma once
// The Evaluator of `mpirun -np P mdrmap fit`: rank 0 drives the fit and
// hands each batch of parameter vectors (the pre-search, a Jacobian's
// columns) to every rank, point k to rank k mod P; the others serve batches
// until rank 0 says stop. The communicator is a parameter.
#include <mpi.h>

#include "case/fit_problem.hpp"

namespace mdrmap::app {

class MpiEvaluator : public fit::Evaluator {
public:
  MpiEvaluator(const cases::FitProblem& p, MPI_Comm comm) : p_(p), comm_(comm) {}
  /// Rank 0: the residuals of each point, computed across the ranks.
  std::vector<std::vector<double>>
  evaluate(const std::vector<std::vector<double>>& points) override;
  /// Rank 0: releases the other ranks from serve().
  void stop();
  /// Ranks other than 0: evaluates batches until stop().
  void serve();

private:
  /// Every rank: the batch (rank 0's points; count 0 sets `stopped`).
  std::vector<std::vector<double>> spread(const std::vector<std::vector<double>>& points,
                                          bool& stopped);

  const cases::FitProblem& p_;
  MPI_Comm comm_;
};

} // namespace mdrmap::app
