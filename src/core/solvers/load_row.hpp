#pragma once
// The element row under load control (docs/design.md, "Load control"): the
// moving window of Kelvin elements plus the free depth d(t). Internal to
// the load solver (core/load.cpp); the tests reach it through run_load.
//
// What is stored. Element j sits at lab position (j + phase) dx, at
// xi_j = (j + P + phase) dx in the frame of the indenter (P = travel / dx). In
// contact an element follows the indenter, u = d - g(xi), and carries no
// memory; the contact is the interval [-a1, e], a1 = sqrt(R d), so the only
// memory is the free depression of the material behind e. Each element keeps
// ln u of its free continuation (what u would be had it stayed free) as
// lnU = ln u + (t - t_base) / tau: free relaxation exp(-dt/tau) is exact and
// costs nothing per step; only elements that detach (at the trailing edge)
// are written (a slot also holds the id of its element: one that entered the
// window since is fresh material, u = 0), so a step costs O(elements that
// change).
//
// Forces given the contact. p = 4G (D - g(xi) - tau w g'(xi)), D = d + tau d',
// so F0 = integral of p over [-a1, e] gives D in closed form:
//   e at the re-touch front:  D = F0 / (4G (a1 + e)) + ((e^2 - e a1 + a1^2)/3 + L (e - a1)) / R;
//   e at the force-zero point (p(e) = 0, R D = e^2 + 2 L e): (a1 + e)^2 (2e - a1 + 3L) = 4 a0^3,
// L = w tau. The edge is the smaller of the front and that cap (material
// beyond the cap would pull). Forces are then exact polynomial integrals over
// [-a1, e]; the row only locates the front.
//
// The depth. tau d' = D - d, where D depends on d itself (through a1 and the
// edge) with a slope -k that reaches ~L / a1 at zeta0 >> 1: a mode as fast as
// the contact time a1 / v. Where k h / tau > 10, with k frozen over the step
// (from the state at its start, core/load_row.cpp: stiffness), it is written
// tau d' = Dk - (1 + k) d, Dk = D + k d, and integrated exponentially at the
// rate (1 + k) / tau with Dk linear over the step: d1 = d0 E + Dk0 (1 - E) / l
// + (Dk1 - Dk0) phi(x) / l, l = 1 + k, x = l h / tau, E = exp(-x),
// phi(x) = 1 - (1 - exp(-x))/x. What is left of the coupling, Dk's slope
// k - k_true, is weak, and the weight of Dk0 vanishes as x grows: the
// coupling is L-stable (the fast mode is damped, not flipped from step to
// step as by a trapezoid), second order for any k, and exact for tau -> 0
// (d = D, Hertz); elsewhere k = 0, the plain exponential step with D linear.
// Dk1 depends on d1 through a1 and the contact set at the step's end: one
// scalar equation, solved by a bracketed root.
//
// Time. The row's clock runs from the start of the current segment
// (restart_clock at each velocity change): a step after a hold of 1e18 tau
// is as fine as after one of 1 tau (no digits are lost to the hold).
//
// Work. Every loop over elements and every root evaluation is charged to the
// case's RunControl (a case past its budget throws CaseAbandoned, a stop
// request Interrupted).
//
// The front. A free element touches when its gap psi = d - g(xi) - u >= 0
// (below the cap a touched element stays in contact: psi' = p / (4 G tau) at
// psi = 0, so checking at the step's end is exact). Between the last element
// in contact and the first free one the front is the root of psi, with ln u of
// the free material interpolated linearly between the material of the previous
// edge (psi = 0 there when it was the edge: exact data) and the first free
// element (exact for material that left at the cap). In material coordinates
// the front never moves back.
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/model/case.hpp"
#include "core/model/state.hpp"
#include "core/numerics/run_control.hpp"

namespace mdrmap {

/// Conditions the load solver detects and reports: the model's structure
/// (leading edge attached, one contact interval) checked at every step/sample.
struct LoadChecks {
  long leading_edge_detached = 0; ///< steps where p(-a1) < 0 (the leading edge would lift)
  long second_contact = 0;        ///< samples with free material touching beyond the front
  double max_a1_over_a0 = 0.0;    ///< deepest state reached (the window is sized for it)
};

/// The leading edge would leave the element window (the run needs a wider one).
class WindowExceeded : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class LoadRow {
public:
  /// dx the element spacing, A the half-width of the window (>= the largest
  /// a1); `control` is charged with the row's work (it must outlive the row).
  LoadRow(const Case& c, double dx, double A, double phase, const RunControl& control);

  void start_stationary(double w); ///< stationary sliding at w under F0
  void start_rest();               ///< fully relaxed at rest under F0: Hertz
  /// At rest on undeformed material at depth d = d_rel d0, all in contact
  /// ([-a1, a1]): the creep start (d ~ d0 (t/tau)^(2/3) from d = 0).
  void start_undeformed(double d_rel);
  /// Velocity change to w at the current instant: contact beyond the new cap
  /// lets go at once (u = d - g), d is continuous, D jumps. The clock
  /// restarts: t() is the time since this change.
  void change_velocity(double w);

  /// The state after a step h, computed without changing the row.
  struct Trial {
    double h = 0.0, d = 0.0, D = 0.0, e = 0.0;
    double k = 0.0;     ///< the stiffness frozen over the step (see the header)
    double t_end = 0.0; ///< t + h (the stepper may snap it to a sample instant)
  };
  /// `h_gate`: the stiff form (k > 0) is used where k h_gate / tau > 10 (the
  /// plain coupling still damps the mode below); the stepper passes the same
  /// h_gate for a step and its two halves.
  Trial trial(double h, double h_gate) const;
  /// Whether a trial has a depth and its leading edge stays inside the window.
  bool fits(const Trial& tr) const;
  /// Whether the leading edge is within half a cell of the window's limit.
  bool at_window_edge() const;
  /// Apply a trial step (recorded for rollback while a checkpoint is open).
  void commit(const Trial& tr);
  void checkpoint();
  void rollback();
  void release();
  /// Keeps t - t_base small in the stored logarithms (outside checkpoints).
  void rebase_time();

  State measure() const;
  double t() const { return t_; }
  double d() const { return d_; }
  double D() const { return D_; }
  double e() const { return e_; }
  double a1() const;
  double R() const { return R_; }
  long updates() const { return updates_; }
  std::size_t capacity() const { return cap_; }
  const LoadChecks& checks() const { return checks_; }
  /// Counts free material touching beyond the front (the contact would not
  /// be one interval); called at samples.
  void check_one_interval();
  /// Pieces of free material at least `floor` wide are recorded in
  /// min_piece (narrower ones cannot move the edge by more than their
  /// width); pieces narrower than `resolved` in max_unresolved.
  void set_pieces(double floor, double resolved) {
    piece_floor_ = floor;
    piece_resolved_ = resolved;
  }
  /// The narrowest piece of free material recorded (infinity if none): a band
  /// let go at a velocity change ([cap, e]) and the travel of a segment that
  /// slid (what left the contact during it). A piece much narrower than dx is
  /// not represented by any element: a later re-touch front crosses it at the
  /// wrong time, in this run and in its half-resolution companion alike.
  double min_piece() const { return min_piece_; }
  /// The widest piece narrower than `resolved` (0 if none): the edge may be
  /// off by up to its width where a front crosses it.
  double max_unresolved() const { return max_unresolved_; }

private:
  struct Frame { // position of the row: P = m + th cells of travel
    long long m = 0;
    double th = 0.0;
  };
  Frame frame_at(double h) const;
  double xi(const Frame& f, long long j) const;
  long long first_beyond(const Frame& f, double x) const; ///< smallest j with xi > x
  long long jlo(const Frame& f) const;
  long long jhi(const Frame& f) const;
  std::size_t slot(long long j) const;
  double u_at(long long j, double t) const;
  double ln_u_at(long long j, double t) const; ///< -inf for fresh material
  void set_lnU(long long j, double v);

  struct Edge {
    double e = 0.0, D = 0.0;
  };
  Edge edge_at(double d1, double h, const Frame& f1) const;
  double front_root(const Frame& f1, long long jf, double d1, double t1, double xb, double xe,
                    double lue) const;
  double cap_joint(double a, double L) const;
  double D_front(double a, double e, double L) const;
  double stiffness() const;
  double depth_within(double theta, const Trial& tr) const;
  void restart_clock();
  void detach(const Trial& tr, const Frame& f1);

  Case c_;
  const RunControl& control_;
  double R_, G_, tau_, F0_, a0_;
  double dx_, A_, phase_;
  std::size_t cap_;
  std::vector<double> lnU_;
  std::vector<long long> tag_; // element id whose lnU a slot holds (else: fresh material)
  Frame f_;
  long double P_ = 0.0L;
  double t_ = 0.0, t_base_ = 0.0;
  double w_ = 0.0, d_ = 0.0, D_ = 0.0, e_ = 0.0;
  double piece_floor_ = 0.0, min_piece_ = std::numeric_limits<double>::infinity();
  double piece_resolved_ = 0.0, max_unresolved_ = 0.0;
  void note_piece(double width);
  long updates_ = 0;
  LoadChecks checks_;

  struct Saved {
    Frame f;
    long double P;
    double t, d, D, e;
    long updates;
  };
  bool logging_ = false;
  Saved saved_{};
  struct Undo {
    std::size_t slot;
    double lnU;
    long long tag;
  };
  std::vector<Undo> log_;
};

} // namespace mdrmap
