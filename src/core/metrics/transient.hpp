#pragma once
// The transient of one segment as the event metrics take it from a solver's
// solution, not from its output instants (docs/design.md, "Event metrics"):
// the extremum of mu, the first fall of |mu - mu_ss| to 1/e of its value just
// after the change, and the overshoot beyond mu_ss. A solver that can
// evaluate any instant computes it by root finding (the exact solver); a
// stepping solver feeds its accepted steps to a TransientTracker, which
// keeps O(1) state however long the segment.
#include <limits>

namespace mdrmap {

struct Transient {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double mu_peak = kNaN; ///< mu farthest from mu_ss within the segment (mu(0+) if none is farther)
  double t_peak = 0.0;   ///< its time since the change
  /// Time since the change at which |mu - mu_ss| first falls to 1/e of
  /// |mu(0+) - mu_ss|; NaN if it does not within the segment or mu(0+) = mu_ss
  /// (to 1e-12 of mu_ss: a solver's rounding).
  double t_decay = kNaN;
  /// Largest excursion of mu beyond mu_ss on the side opposite to mu(0+),
  /// relative to |mu(0+) - mu_ss|; 0 for a one-sided transient and where
  /// mu(0+) = mu_ss (to 1e-12 of mu_ss).
  double overshoot = 0.0;
};

/// Keeps what a Transient needs from a segment's solution fed point by point
/// in time order (a solver's accepted steps and its samples). Between points
/// the solution is taken as the parabola through three consecutive points
/// (the crossing, and the vertex of an interior extremum).
class TransientTracker {
public:
  /// mu_ss: the stationary mu at the segment's velocity; mu0: mu(0+).
  TransientTracker(double mu_ss, double mu0);
  /// The solution at time t since the change (t > the previous point's).
  void add(double t, double mu);
  Transient result() const;

private:
  struct P {
    double t = 0.0, y = 0.0; ///< y = (mu - mu_ss) * side: > 0 on the side of mu(0+)
  };
  /// An extremum of s * y among the points so far, with its neighbours.
  struct Extremum {
    P at[3]{};
    int n = 0; ///< 1: first point so far; 2: no right neighbour yet; 3: complete
    double value = -std::numeric_limits<double>::infinity();
  };
  void offer(Extremum& x, double s, int last_n);
  static double vertex(const Extremum& x, double s, double* t);

  double mu_ss_, side_, dev0_;
  P last_[3]{}; ///< the three latest points (last_[2] the newest)
  int count_ = 0;
  Extremum peak_near_, peak_far_; ///< of y and of -y
  double t_decay_ = Transient::kNaN;
};

} // namespace mdrmap
