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
//
// A segment that has reached its stationary state under load keeps it
// (stationary_watch.hpp): after each traverse of the window the depth and mu
// after a grid step are compared with the stationary state; once the watch
// freezes the segment, no further steps are taken, the row stays as it is,
// its later samples are that state and the tracker is fed it at the
// segment's remaining lattice points. The watch sees grid steps only, so the
// freeze does not depend on the samples either.
#include "core/metrics/transient.hpp"
#include "core/model/state.hpp"
#include "core/solvers/load_lattice.hpp"
#include "core/solvers/load_row.hpp"
#include "core/solvers/stationary_watch.hpp"

namespace mdrmap {

/// How one run of kelvin_load steps.
struct LoadStepSettings {
  double time_tol = 0.0;               ///< local error per step, relative to d
  double dt_over_tau = 0.0;            ///< fixed steps h = dt_over_tau tau (0: adaptive)
  long lattice_n = LoadLattice::kFine; ///< lattice points per segment
};

class LoadStepper {
public:
  /// `watch`: when a segment counts as stationary (off: never frozen).
  LoadStepper(LoadRow& row, const LoadStepSettings& s, double tau, const StationaryWatch& watch)
      : row_(row), s_(s), tau_(tau), watch_(watch) {}
  /// A new segment of duration T at velocity w (the row's clock restarted at
  /// its change): the first step size again, the tracker that is fed the
  /// state after every grid step (and its midpoint) from now on (nullptr:
  /// none), and the segment's stationary state under load, which the watch
  /// compares with (F_N = 0: none, not watched).
  void begin(double T, TransientTracker* tracker, double w, const State& stationary);
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
  void watch(double h);
  void keep(double s);

  LoadRow& row_;
  LoadStepSettings s_;
  double tau_;
  LoadLattice lattice_;
  long j_ = 0;     ///< the next lattice point after the grid's last step end
  double h_ = 0.0; ///< the step control's next step
  long steps_ = 0;
  bool side_ = false; ///< the row is at a side step's end (checkpointed at the grid)
  TransientTracker* tracker_ = nullptr;
  StationaryWatch watch_;
  double w_ = 0.0;       ///< the segment's velocity
  State stationary_;     ///< its stationary state under load
  double kept_ = 0.0;    ///< a frozen segment: the last instant fed to the tracker
  double kept_mu_ = 0.0; ///< and the mu it keeps
};

} // namespace mdrmap
