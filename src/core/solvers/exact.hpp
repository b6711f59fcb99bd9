#pragma once
// Continuum (dx -> 0) solution of the MDR model at fixed depth, for any
// piecewise-constant velocity history (docs/design.md, "The exact solution").
//
// Every element in contact follows the indenter, so its force per unit length
// p = 4G/R (a1^2 - x^2 - 2 w tau x) depends on its position x in the frame of
// the indenter and on the current velocity w only. The contact set is one
// interval [-a1, e(t)], so the forces are the closed-form integrals
// analytic::contact_forces(e, w) and the whole problem is the trailing edge
// e(t) = min(cap(w), front), cap(w) = a2(w) (a1 during a hold). The front is
// where the free material behind the contact touches the indenter again. The
// free material is held as a list of pieces, each in closed form:
//  - Exp:  material that left contact at the cap while sliding at w_c: a free
//          depression A exp(-(x - xa)/lambda), lambda = w_c tau;
//  - Quad: material that let go at once at a velocity rise (or a restart after
//          a hold): u = C h(x - D), the indenter depth where it let go, decayed
//          by C and carried a distance D.
// On each piece the gap function psi = h - u is concave, so the front is
// found by walking the pieces and solving one scalar root (closed form on a
// Quad piece). Segment boundaries are processed once; samples are then
// independent evaluations.
#include <limits>
#include <utility>
#include <vector>

#include "core/metrics/analytic.hpp"
#include "core/metrics/transient.hpp"
#include "core/model/case.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/checked_case.hpp"
#include "core/solvers/result.hpp"

namespace mdrmap {

/// One piece of free material behind the trailing edge, at a segment start.
struct TailPiece {
  enum class Kind { Exp, Quad } kind = Kind::Exp;
  double lo = 0.0, hi = 0.0; ///< extent in the frame of the indenter (hi may be +inf)
  // Exp: u(x) = A exp(-(x - xa)/lam); psi(xa + y) = c0 - c1 y - y^2 (1/R + A phi2(y/lam)/lam^2)
  // with c0 = h(xa) - A and c1 = g'(xa) - A/lam carried along without cancellation.
  double xa = 0.0, A = 0.0, lam = 0.0, c0 = 0.0, c1 = 0.0;
  double a1_minus_xa = 0.0; ///< a1 - xa without cancellation (edges near a1 at small zeta)
  // Quad: u(x) = C h(x - D); one_minus_C = 1 - C without cancellation.
  double C = 1.0, one_minus_C = 0.0, D = 0.0;
};

/// The state at the start of a segment: its velocity, its cap, the free
/// material behind the edge (sorted outward, contiguous, starting at the edge).
struct SegmentStart {
  double w = 0.0;
  double cap = 0.0;          ///< a2(w), the force-zero point; a1 for a hold
  double a1_minus_cap = 0.0; ///< a1 - cap without cancellation
  State at_cap;              ///< the stationary state at w: the state while the edge is at the cap
  std::vector<TailPiece> tail;
  /// No free material before the cap (a rise or no change out of stationary
  /// sliding, a restart): the edge sits at the cap throughout the segment,
  /// as the walk of the pieces finds (material only moves outward at w >= 0).
  bool at_cap_throughout = false;
  /// One Exp piece reaching to infinity, carried no faster than it left the
  /// cap (w tau <= lam: a drop or a hold out of stationary sliding): its
  /// depression at the cap only shrinks, so the gap there only grows, and
  /// once the edge is at the cap with a clear margin it stays there.
  bool gap_at_cap_grows = false;
  /// With gap_at_cap_grows: 1e-9 of a bound on every term of that gap at any
  /// offset (the terms at the start, where the piece's anchor is farthest
  /// from the cap); rounding stays far below it.
  double cap_margin = 0.0;
  /// The earliest offset at which the walk found the edge at the cap for
  /// good (infinity: not yet): the first piece's material past the cap (its
  /// start only moves outward), or with gap_at_cap_grows its gap at the cap
  /// above cap_margin. Later offsets are at the cap without the walk: a
  /// cache of the walk's own answer, filled as it is asked.
  mutable double at_cap_from = std::numeric_limits<double>::infinity();
  /// The edge just after the change (offset 0), once the walk found it: a
  /// cache for the transient, which starts there (NaN: not yet).
  mutable double start_edge = std::numeric_limits<double>::quiet_NaN();
  mutable double start_a1_minus_edge = 0.0;
  mutable bool start_at_cap = false;
};

class ExactSolution {
public:
  /// `bits`: binary digits the trailing-edge roots are solved to (<= 52).
  /// `control` (if given, it must outlive the solution) is charged for every
  /// piece walked and every root iteration.
  explicit ExactSolution(const Case& c, int bits = 50, const RunControl* control = nullptr);

  /// Stationary state at v0 before t = 0.
  State pre() const { return pre_; }
  /// State in segment k at time `offset` after its start (0: just after the
  /// change). The last segment continues past its end.
  State at(std::size_t k, double offset) const;
  /// State at time t >= 0 since the first change; at a change, just after it.
  State at(double t) const;
  /// Bound on |e error| (length) of the last call to at(): root bracket width.
  double last_bracket() const { return last_bracket_; }
  long root_solves() const { return root_solves_; }
  /// Pieces of free material at the start of segment k (for tests).
  const SegmentStart& segment_start(std::size_t k) const { return starts_[k]; }
  /// Trailing edge (front) in segment k at `offset`, the cap included.
  double edge(std::size_t k, double offset) const;
  /// The transient of segment k over its first T (core/metrics/transient.hpp),
  /// independent of any output instants: within a segment mu is a closed-form
  /// function of the edge and the edge only moves outward, so the extremum
  /// and the 1/e decay are found on mu(e) and timed by when the front
  /// reaches them (docs/design.md, "Event metrics").
  Transient transient(std::size_t k, double T) const;
  /// Largest gap h - u of the free material beyond the edge, over `points`
  /// instants per piece up to min(a1, its end), relative to h(0) = d. Negative
  /// means the contact is one interval: nothing behind the edge touches.
  double max_gap_beyond_edge(std::size_t k, double offset, int points) const;

private:
  struct Edge {
    double e, a1_minus_e;
    bool at_cap;
  };
  Edge front(const SegmentStart& seg, double offset) const;
  double cap_time(const SegmentStart& seg, double T) const {
    return arrival(seg, seg.cap, T, bits_);
  }
  /// When the front reaches x in [0, T], to `bits` binary digits.
  double arrival(const SegmentStart& seg, double x, double T, int bits) const;
  /// The same, in closed form where the free material is one Exp piece to
  /// infinity (a drop or a hold out of stationary sliding; the transients).
  double arrival_time(const SegmentStart& seg, double x, double T, int bits) const;
  /// Extremum of s (mu(e) - mu_ss) on [lo, hi] (lo < hi): its edge and value.
  std::pair<double, double> refine_extremum(const SegmentStart& seg, double s, double lo, double hi,
                                            double a1_minus_lo) const;
  SegmentStart next_start(const SegmentStart& seg, double T, double w_next) const;
  SegmentStart make_start(double w, std::vector<TailPiece> tail, double edge) const;
  void charge(double units) const {
    if (control_ != nullptr) control_->charge(units, "exact");
  }

  Case c_;
  int bits_;
  double a1_ = 0.0;
  State pre_;
  std::vector<SegmentStart> starts_;
  std::vector<double> t_start_;
  const RunControl* control_ = nullptr;
  mutable double last_bracket_ = 0.0;
  mutable long root_solves_ = 0;
};

/// Samples the continuum solution at the case's instants. rtol sets the root
/// tolerance; info.error_estimate bounds the case error. The work is charged
/// to `control` (CaseAbandoned past its budget, Interrupted on a stop). The
/// case was checked where it was made (CheckedCase); refused here is only what
/// this solver does not take (a load, Maxwell branches, another profile).
RunResult run_exact(const CheckedCase& c, double rtol = 1e-12,
                    const RunControl& control = RunControl{});

} // namespace mdrmap
