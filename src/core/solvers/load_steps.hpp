#pragma once
// The time steps of kelvin_load within a segment (docs/design/load.md,
// "Steps"). The step grid is the step control's steps (adaptive by step
// doubling, or fixed) cut at the segment's lattice (load_lattice.hpp) and at
// nothing else: it depends on the case, the resolution and the lattice, never
// on the output samples, and so do the event metrics read off its steps. A
// sample strictly inside a grid step is a side step: the row is checkpointed
// at the grid's last step end, stepped to the instant (two balanced half
// steps, as a grid step keeps) and measured there; the next reach() rolls it
// back, and the grid carries on as if it never happened. The step control
// and the transient tracker see grid steps only.
#include "core/metrics/transient.hpp"
#include "core/solvers/load_lattice.hpp"
#include "core/solvers/load_row.hpp"

namespace mdrmap {

/// How one run of kelvin_load steps.
struct LoadStepSettings {
  double time_tol = 0.0;               ///< local error per step, relative to d
  double dt_over_tau = 0.0;            ///< fixed steps h = dt_over_tau tau (0: adaptive)
  long lattice_n = LoadLattice::kFine; ///< lattice points per segment
};

class LoadStepper {
public:
  LoadStepper(LoadRow& row, const LoadStepSettings& s, double tau) : row_(row), s_(s), tau_(tau) {}
  /// A new segment of duration T (the row's clock restarted at its change):
  /// the first step size again, and the tracker that is fed the state after
  /// every grid step (and its midpoint) from now on (nullptr: none).
  void begin(double T, TransientTracker* tracker);
  /// The row at offset s of the segment (on the row's clock; not before the
  /// grid's last step end): the grid's steps up to s and, where s falls
  /// strictly inside one, a side step to it, which the next reach() undoes.
  void reach(double s);
  long steps() const { return steps_; } ///< grid steps taken (side steps not counted)

private:
  void grid_step(double h, bool to_point, double point);
  void adaptive_step(double h, bool to_point, double point);
  void reject_outside(const LoadRow::Trial& a, const LoadRow::Trial& b) const;
  void side_step(double s);
  void undo_side();
  void track();

  LoadRow& row_;
  LoadStepSettings s_;
  double tau_;
  LoadLattice lattice_;
  long j_ = 0;     ///< the next lattice point after the grid's last step end
  double h_ = 0.0; ///< the step control's next step
  long steps_ = 0;
  bool side_ = false; ///< the row is at a side step's end (checkpointed at the grid)
  TransientTracker* tracker_ = nullptr;
};

} // namespace mdrmap
