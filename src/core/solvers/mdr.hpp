#pragma once
// Discrete MDR simulator: the paper's row of Kelvin elements (spring 4 G dx,
// dashpot 4 eta dx) under the sliding indenter.
#include "core/model/case.hpp"
#include "core/solvers/result.hpp"
#include "core/solvers/run_control.hpp"

namespace mdrmap {

/// How the continuum forces and the trailing edge are read off the element row.
enum class MdrSubgrid {
  None,   ///< the paper: raw element sums, a2 = last element in contact (first order)
  Linear, ///< high-order quadrature, gap h - u interpolated linearly (second order)
  /// High-order quadrature; the free depression interpolated in the exact form
  /// of the piece of material it belongs to (log-linear where it left contact
  /// at the cap, a parabola where it let go at a velocity change), with tracers
  /// at the boundaries between pieces: exact to rounding for any history (default).
  Piecewise
};

struct MdrOptions {
  double rtol = 1e-3;         ///< target case error; sets dx when cells_per_a1 == 0
  double cells_per_a1 = 0;    ///< fixed resolution a1/dx (0: chosen from rtol)
  bool spinup = false;        ///< start from an undeformed foundation, not the stationary state
  double phase = 0.5;         ///< element offset at t = 0, in cells (x_i = (i + phase) dx)
  bool estimate_error = true; ///< run a half-resolution companion (other phase) for error_estimate
  MdrSubgrid subgrid = MdrSubgrid::Piecewise;
  /// Work budget and stop flag (nullptr: the default budget, no stop flag).
  const RunControl* control = nullptr;
};

/// Runs the discrete model. With cells_per_a1 == 0 it picks dx from rtol and
/// refines until its error estimate is below rtol; a case whose estimate stays
/// above rtol throws CaseAbandoned (so does one past its work budget).
RunResult run_mdr(const Case& c, const MdrOptions& opt);

} // namespace mdrmap
