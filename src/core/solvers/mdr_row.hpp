#pragma once
// The element row of the Kelvin MDR solver (core/solvers/mdr.cpp runs it):
// springs 4 G dx and dashpots 4 eta dx under the sliding indenter. Element j
// sits at lab position x_j = (j + phase) dx; the moving coordinate is
// xi_j = x_j + s(t), so the indenter occupies [-a1, a1] in xi and elements
// enter at -a1 and leave at +a1 (h < 0 beyond: they can never touch again
// while v >= 0). Only that window is stored (ring buffer): memory is
// independent of the travel distance.
//
// Time integration is exact for piecewise-constant velocity w, so the only
// error left is the spatial one (dx):
//  - an element in contact follows the indenter: u = h(xi), u' = -w g'(xi);
//    its force 4 G dx (h - tau w g') turns negative exactly where xi passes
//    a2(w), the stationary trailing edge, where it detaches with u = h(a2(w));
//  - a free element relaxes as u = u0 exp(-t/tau) (stable for any dt and for
//    tau = 0);
//  - a free element touches again when u <= h(xi). Once touched (with
//    xi < a2(w)) it stays in contact until a2(w), because there its contact
//    force is positive; so "has it touched during the step" is answered by
//    one comparison at the end of the step (or where it reaches a2(w)).
// Untouched material ahead of the indenter is simply free with u = 0.
//
// Forces at a sample are quadratures of the element forces (force per unit
// length p = 4 G (h - tau w g')) over the contact nodes, with the partial
// cells at both ends integrated on the cubic through the nearest nodes: the
// integrands are cubics in xi, so the only error left is the sub-grid location
// of the trailing edge (docs/design.md, "The discrete solvers"), which
// core/solvers/mdr_edge.cpp reads off the row (pieces, tracers, ghosts).
// Stepping and the forces are in core/solvers/mdr_row.cpp.
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "core/model/case.hpp"
#include "core/model/state.hpp"
#include "core/solvers/mdr.hpp"
#include "core/solvers/run_control.hpp"

namespace mdrmap::mdr {

constexpr int kNoPiece = -1; // material without a free profile

/// A piece of free material: how it was freed fixes the form of its profile.
struct Piece {
  /// Left contact at the cap (u log-linear), else let go at a change (a
  /// parabola).
  bool at_cap = true;
  double lam = 0.0; ///< at_cap: decay length w tau of the profile
};

/// An element (node or tracer): its free depression u (the free continuation
/// while in contact), the gap psi = h - u, carried along without cancellation
/// (the edge is a root of psi, and psi is a small difference of large terms
/// where new contact grows from a tangency), the piece whose profile u
/// belongs to, and its position (nodes: filled in when read).
struct Site {
  double x = 0.0;
  double u = 0.0;
  double psi = 0.0;
  int piece = kNoPiece;
  bool contact = false;
};

/// The trailing edge as read off the row.
struct Edge {
  double x = 0.0;
  int piece = kNoPiece; ///< piece of the free material just beyond the edge
  bool at_cap = false;  ///< the edge is the cap a2(w)
  bool marked = false;  ///< a pair of tracers already marks it
};

/// Free depression of one piece near an anchor site a, in the piece's form:
/// u = a.u + du(x) with du log-linear (cap pieces) or from a parabola
/// P(x) = c1 (x - x0) + c2 (x - x0)(x - x1) (material let go at a change).
struct Profile {
  Site a;
  bool log_linear = false;
  double k = 0.0; ///< d ln u / dx (log-linear)
  double c1 = 0.0, c2 = 0.0, x0 = 0.0, x1 = 0.0;
  double du(double x) const {
    const double y = x - a.x;
    if (log_linear) return a.u * std::expm1(k * y);
    return y * (c1 + c2 * (x + a.x - x0 - x1)); // P(x) - P(a.x)
  }
  double u(double x) const { return log_linear ? a.u * std::exp(k * (x - a.x)) : a.u + du(x); }
  double log_u(double x) const { // (-inf where u <= 0)
    if (log_linear) return std::log(a.u) + k * (x - a.x);
    const double v = u(x);
    return v > 0.0 ? std::log(v) : -std::numeric_limits<double>::infinity();
  }
};

/// Three free continuations of a piece let go at a change, spread around it.
/// Its depression u = C h(x - D) (the depth where it let go, decayed by C,
/// carried a distance D) is one parabola for all x, and these never touch, so
/// they keep its shape known wherever its material went (sites of the piece
/// leave it as they touch again and reach the cap).
struct Ghosts {
  int piece = kNoPiece;
  double near_end = 0.0; ///< material at the piece's near end: pruned once past the window
  Site g[3];
};

/// One exact time step at constant velocity: decay exp(-dt/tau), 1 - decay,
/// the cap a2(w) and the indenter depth there.
struct Step {
  double dt, dec, omd, a2w, h_a2w;
};

class Row {
public:
  Row(const Case& s, double cells_per_a1, double phase, MdrSubgrid subgrid,
      const RunControl& control);

  std::size_t capacity() const { return cap_; }
  long updates() const { return updates_; }
  long steps() const { return steps_; }

  /// Stationary state at velocity w at position P = s/dx (cells).
  void init_stationary(double w, long double P);
  /// Indenter pressed into an undeformed foundation at position P, at rest.
  void init_undeformed(long double P);
  /// Instantaneous velocity change to w: contact elements whose force turns
  /// negative (xi > a2(w)) let go at once with u = h(xi). Tracers mark the
  /// trailing edge (and the new cap after a rise); see
  /// core/solvers/mdr_edge.cpp.
  void change_velocity(double w);
  /// Advance by dt at the current velocity; exact.
  void advance(double dt);
  /// Forces and trailing edge of the current state.
  State measure() const;

private:
  // stepping (core/solvers/mdr_row.cpp)
  void carry_markers(double ds, const Step& st);
  template <class F> double integrate(long long ja, long long jb, double xr, F f) const;
  static double partial_cell(const double g[4], double len);
  void step_element(Site& el, double xs, double xe, const Step& st) const;
  void relax(Site& el, double xs, double xe, double dec, double omd) const;
  void leave_at_cap(Site& el, double xe, double dt_c, const Step& st) const;
  void set_position(long double P);
  void rebase();

  // the trailing edge, pieces and tracers (core/solvers/mdr_edge.cpp)
  std::vector<Site> sites_in(double x0, double x1) const;
  Edge read_edge(long long jb) const;
  Profile profile(int q, const Site& a, const Site* b) const;
  double root_on(const Profile& p, double lo, double hi) const;
  double cell_root(const Site& c, const Site& f) const;
  void mark_cap_boundary();
  void let_go(double cap, const Edge& e);
  void add_tracer(const Site& t);
  void add_boundary(const Site& left, const Site& right);
  void prune_tracers();

  double decay(double dt) const {
    if (s_.rheology.tau > 0.0) return std::exp(-dt / s_.rheology.tau);
    return dt > 0.0 ? 0.0 : 1.0;
  }
  double one_minus_decay(double dt) const {
    if (s_.rheology.tau > 0.0) return -std::expm1(-dt / s_.rheology.tau);
    return dt > 0.0 ? 1.0 : 0.0;
  }

  double h(double x) const { return (a1_ - x) * (a1_ + x) / s_.indenter.as<Parabola>().R; }
  double dh(double xa, double xb) const {
    return (xa - xb) * (xa + xb) / s_.indenter.as<Parabola>().R;
  }
  double pressure(double x) const { // contact force per unit length
    return 4.0 * s_.rheology.G *
           (h(x) - s_.rheology.tau * w_ * 2.0 * x / s_.indenter.as<Parabola>().R);
  }

  double xi(long long j) const { return (static_cast<double>(j + m_) + theta_ + phase_) * dx_; }
  std::size_t slot(long long j) const {
    const auto c = static_cast<long long>(cap_);
    return static_cast<std::size_t>(((j % c) + c) % c);
  }
  Site node(long long j) const {
    Site n = nodes_[slot(j)];
    n.x = xi(j);
    return n;
  }
  long long last_contact_node() const {
    for (long long j = jhi_; j >= jlo_; --j)
      if (nodes_[slot(j)].contact) return j;
    return jlo_ - 1;
  }
  int new_piece(bool at_cap, double lam) {
    pieces_.push_back(Piece{at_cap, lam});
    return static_cast<int>(pieces_.size()) - 1;
  }
  // u(b) - u(a) of two sites, from their gaps: no cancellation.
  double udiff(const Site& a, const Site& b) const { return dh(a.x, b.x) - (b.psi - a.psi); }

  Case s_;
  double a1_, dx_, phase_;
  MdrSubgrid subgrid_;
  const RunControl& control_;
  std::size_t cap_;
  std::vector<Site> nodes_;      // ring buffer over the window (x filled in by node())
  std::vector<Piece> pieces_;    // every piece made so far
  int cap_piece_ = kNoPiece;     // piece of material leaving at the cap in this segment
  std::vector<Site> tracers_;    // sorted by x; a boundary is a pair at one x
  std::vector<Ghosts> ghosts_;   // of the pieces let go at a change, while in the window
  long double P_ = 0.0L;         // travel s/dx in cells
  long long m_ = 0;              // floor(P)
  double theta_ = 0.0;           // P - m
  long long jlo_ = 0, jhi_ = -1; // element ids in the window
  double w_ = 0.0;
  double seg_time_ = 0.0; // time since the last velocity change
  long updates_ = 0, steps_ = 0;
};

} // namespace mdrmap::mdr
