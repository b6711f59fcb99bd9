#pragma once
// The transient of one segment as the event metrics take it from a solver's
// solution, not from its output instants (docs/design.md, "Event metrics"):
// the largest and the smallest mu and when they occur, and the decay of
// |mu - mu_ss| from a reference point (the change itself, or the peak after
// it: see TransientTracker) to 1/e of its value there, with the overshoot
// beyond mu_ss after it. A solver that can evaluate any instant computes it
// by root finding (the exact solver); a stepping solver feeds its solution at
// instants that do not depend on the output samples to a TransientTracker,
// which keeps O(1) state however long the segment.
#include <limits>
#include <vector>

namespace mdrmap {

/// A segment's solution mu(t) (t since the change) at instants fixed by the
/// segment, not by its output samples: what a stepping solver shows the
/// event metrics, which feed it to a TransientTracker once mu_ss is known.
struct Probes {
  std::vector<double> t, mu;
};

struct Transient {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double mu_max = kNaN; ///< largest mu within the segment (mu(0+) included)
  double t_max = 0.0;   ///< its time since the change
  double mu_min = kNaN; ///< smallest mu within the segment (mu(0+) included)
  double t_min = 0.0;   ///< its time since the change
  /// The reference point of the decay: the change (t_ref = 0) or the peak on
  /// the side of the change (TransientTracker::Reference::Peak); dev_ref =
  /// |mu(t_ref) - mu_ss|.
  double t_ref = 0.0;
  double dev_ref = 0.0;
  bool ref_at_end = false; ///< the reference is the segment's last point (still rising)
  /// Time since the change at which |mu - mu_ss| first falls, after t_ref, to
  /// 1/e of dev_ref; NaN if it does not within the segment or dev_ref = 0.
  double t_decay = kNaN;
  /// Largest excursion of mu beyond mu_ss after t_ref on the side opposite
  /// to mu(t_ref), relative to dev_ref; 0 for a one-sided transient.
  double overshoot = 0.0;
};

/// Keeps what a Transient needs from a segment's solution fed point by point
/// in time order. Between points the solution is taken as the parabola
/// through three consecutive points (the crossing, and the vertex of an
/// interior extremum).
class TransientTracker {
public:
  /// Where the decay is measured from: the change (a material whose friction
  /// jumps there: a parallel dashpot), or the peak on the side of the change
  /// (the largest mu after a rise, the smallest after a drop: a material
  /// without one, whose friction is continuous across the change).
  enum class Reference { Change, Peak };
  /// mu_ss: the stationary mu at the segment's velocity; mu0: mu(0+);
  /// direction: +1 for a rise, -1 for a drop (the side of Reference::Peak).
  TransientTracker(double mu_ss, double mu0, Reference ref = Reference::Change,
                   double direction = 1.0);
  /// The solution at time t since the change (t > the previous point's).
  void add(double t, double mu);
  Transient result() const;

private:
  struct P {
    double t = 0.0, mu = 0.0;
  };
  /// An extremum of s * f(mu) among the points so far, with its neighbours.
  struct Extremum {
    P at[3]{};
    int n = 0; ///< 1: first point so far; 2: no right neighbour yet; 3: complete
    double value = -std::numeric_limits<double>::infinity();
  };
  /// Offers the newest point to x (value s * (mu - offset)); true if it is
  /// the new extremum.
  bool offer(Extremum& x, double s, double offset) const;
  void new_reference();
  void find_crossing();
  static double vertex(const Extremum& x, double s, double offset, double* t);

  double mu_ss_;
  Reference ref_;
  double direction_;
  P last_[3]{}; ///< the three latest points (last_[2] the newest)
  int count_ = 0;
  Extremum max_, min_; ///< of mu and of -mu
  // the reference point and what follows it
  P ref_point_{};
  double side_ = 1.0, dev_ = 0.0;
  Extremum beyond_; ///< of -side (mu - mu_ss) after the reference
  double t_decay_ = Transient::kNaN;
};

} // namespace mdrmap
