#pragma once
// Common result types and the solver dispatch.
#include <string>
#include <vector>

#include "core/analytic.hpp"
#include "core/scene.hpp"

namespace mdrmap {

/// Time series at the protocol's sample instants, and the stationary state
/// before the step.
struct Series {
  State pre;
  std::vector<double> t, FN, Fx, mu, a2;
  void resize(std::size_t n);
  void set(std::size_t k, double time, const State& st);
  State at(std::size_t k) const { return State{FN[k], Fx[k], mu[k], a2[k]}; }
  std::size_t size() const { return t.size(); }
};

/// What a run cost and how accurate it believes it is.
struct RunInfo {
  std::string solver;          ///< "exact", "mdr" or "baseline"
  double rtol = 0.0;           ///< requested tolerance
  double error_estimate = 0.0; ///< estimated case error (DESIGN.md section 2 metric)
  double cells_per_a1 = 0.0;   ///< resolution a1/dx of the final run (0 for exact)
  long elements = 0;           ///< elements held in memory at once (peak, final run)
  long steps = 0;              ///< time steps taken, all runs included
  long element_updates = 0;    ///< element state updates, all runs included
  long root_solves = 0;        ///< scalar root solves (exact solver)
  int refinements = 0;         ///< resolutions tried by the error control
};

struct RunResult {
  Series series;
  RunInfo info;
};

enum class SolverKind { Auto, Exact, Mdr, Baseline };

/// Parses "auto", "exact", "mdr", "baseline"; throws InvalidInput("solver").
SolverKind parse_solver(const std::string& name);
const char* solver_name(SolverKind k);

/// Throws InvalidInput("rtol") unless 0 < rtol <= 0.1.
void validate_rtol(double rtol);

/// Runs one case. `Auto` picks the cheapest solver that meets rtol: for the
/// step protocol that is always the continuum solver.
RunResult run_case(const Scene& s, const Protocol& p, SolverKind kind, double rtol);

} // namespace mdrmap
