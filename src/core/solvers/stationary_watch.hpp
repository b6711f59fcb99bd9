#pragma once
// A segment's approach to its stationary state (docs/design.md, "Stationary
// segments"). After each traverse (the travel that renews the material the
// indenter reaches) a stepping solver compares two of its quantities with the
// continuum's stationary state at the segment's velocity (relative
// deviations: F_N at fixed depth or the depth under load, and mu). Once within
// kNear rtol at three checks in a row, and the last three within kSpread rtol
// of each other (not the streak's first: a streak that starts while the
// solution still approaches would keep that check's extreme), the
// segment is frozen: its later samples are that state of the solver, without
// further steps. Against the continuum alone the solver's own error, which
// cycles with the grid's phase, would decide; against itself alone a slow
// creep could pass. The fine run and its companion decide alone, so their
// difference still sees the solver's own error at the stationary state.
#include <algorithm>
#include <cmath>

namespace mdrmap {

class StationaryWatch {
public:
  static constexpr double kNear = 0.5, kSpread = 0.25;
  static constexpr int kChecks = 3;

  /// traverse: the travel that renews the window; off: never freezes.
  StationaryWatch(double rtol, double traverse, bool on)
      : rtol_(rtol), traverse_(traverse), on_(on) {}

  /// A new segment at w (> 0 and a stationary state known: watched).
  void start(double w, bool known) {
    *this = StationaryWatch(rtol_, traverse_, on_);
    watching_ = on_ && known && w > 0.0;
  }
  /// The travel between checks from now on.
  void set_traverse(double traverse) { traverse_ = traverse; }
  /// The solver travelled `travel` since the last call.
  void moved(double travel) {
    if (watching_) travel_ += travel;
  }
  /// Whether a check is due (a traverse since the last one).
  bool due() const { return watching_ && !frozen_ && travel_ >= traverse_; }
  /// The check: x0, x1 the relative deviations from the stationary state.
  void check(double x0, double x1) {
    travel_ = 0.0;
    if (!(std::abs(x0) <= kNear * rtol_ && std::abs(x1) <= kNear * rtol_)) {
      within_ = 0;
      return;
    }
    last_[within_ % kChecks][0] = x0;
    last_[within_ % kChecks][1] = x1;
    ++within_;
    if (within_ < kChecks) return;
    double spread = 0.0; // (of the last kChecks: an early one of a streak does not stay in it)
    for (int q = 0; q < 2; ++q) {
      double lo = last_[0][q], hi = lo;
      for (int i = 1; i < kChecks; ++i) {
        lo = std::min(lo, last_[i][q]);
        hi = std::max(hi, last_[i][q]);
      }
      spread = std::max(spread, hi - lo);
    }
    frozen_ = spread <= kSpread * rtol_;
  }
  /// No stationary state to compare with: not watched any longer.
  void stop() { watching_ = false; }
  bool frozen() const { return frozen_; }

private:
  double rtol_, traverse_;
  bool on_;
  bool watching_ = false, frozen_ = false;
  double travel_ = 0.0;
  int within_ = 0;
  double last_[kChecks][2] = {}; // the streak's last kChecks checks
};

} // namespace mdrmap
