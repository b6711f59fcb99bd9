#pragma once
// The element row of the spectrum solver inside a moving window (ring buffer:
// memory independent of travel). Element j sits at lab position
// x_j = (j + phase) dx; in the indenter's frame at xi_j = x_j + s(t), so the
// indenter occupies [-a1, a1], fresh material enters at -a1 (the leading edge)
// and leaves at +a1. Material beyond a1 can never touch again while w >= 0:
// there h(xi) < 0 and xi only grows, while a free depression u stays >= 0
// (q_k are positive-kernel averages of past u, u = h > 0 in contact, free u
// a positive combination of the q_k, or with a dashpot G tau u' >= 0 at
// u = 0), so its gap h - u stays negative: it is dropped.
//
// Every element moves exactly (spectrum_law.hpp) and independently of the
// others; its contact switches are located in time within a step as roots
// (detachment where p turns negative, re-touch where h - u turns
// non-negative, the entry at -a1 where xi crosses it). Steps are needed only
// at samples and velocity changes; an element's step is cut into sub-steps of
// at most `sub_travel` a1 of travel so that a switch and its reversal cannot
// hide inside one.
//
// Profiles. The indenter's image g(x) (core/model/profile.hpp) gives the
// depth h = d - g of a material point. In contact u = h along the material
// path is quadratic in t for the parabola (and on either side of the tip for
// the cone and the power law with n = 1, 2): the branch updates are exact.
// A sub-step never crosses the tip x = 0 of a profile other than the
// parabola (it is cut there: g' jumps at a cone's tip, g'' is singular there
// for n < 2); for other n the forcing of a sub-step is the quadratic through
// u at its start, middle and end, and a sub-step travels at most
// kSubCells dx, so the interpolation error falls with dx as the rest and the
// half-resolution companion sees it. Forces are integrated on either side of
// the tip separately (the force density jumps there with a dashpot or a
// cone's slope), each side's end value extrapolated from its own nodes.
//
// Load control. The depth d(t) may vary: within a step it is quadratic in time
// (from the depth at the step's start to a given end depth, with a given rate
// there where a parallel dashpot sees it, else linear), so in contact u
// stays quadratic in t and the branch updates stay exact for that path; the
// leading edge -a1(t) (g(a1) = d(t)) moves, fresh material enters where it
// crosses it (also at rest, when the indenter sinks). The window is a fixed
// [-a_win, a_win] (the deepest contact the history can reach) and material is
// kept until it leaves it. A caller finds the end depth that balances the
// load by trial steps from a snapshot.
//
// Seams. The point at the leading edge when the velocity changes divides
// material pressed before the change from material that enters after it:
// p(x) has a kink there, and the forces are integrated on either side of it
// (spectrum_forces.cpp; only where fresh material's layers w tau_k are
// resolved by the grid).
//
// Trailing edge. Because elements are independent, the state of any material
// point is its history replayed from the log of steps (a few entries per
// sample: memory independent of travel). The edge lies between the last
// contact node and the next node; it is found by a root search over the
// material points between them, each replayed: exact wherever the contact is one
// interval near its end, whatever the free material's profile (thin tails,
// tangencies after a drop, material let go at a rise). Cubics through the
// forces of the last four contact nodes, or the gaps of the next four free
// ones, predict it, two replayed points confirm a prediction (else the search
// runs); the points lie on a lattice of the tolerance and their replays are
// cached at the last saved log entry, so a point that recurs, over the trials
// of a step under load and over the steps of a hold, continues from there
// instead of from its entry (and its state at the log's end is kept until the
// log changes: a trial's confirmed measure replays nothing again). A free
// point at rest crosses the steps of a hold in spans where its gap is
// bounded below zero (free_until): under load each step is its own depth
// path, which uniform_until cannot merge.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "core/model/case.hpp"
#include "core/model/state.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/spectrum_law.hpp"

namespace mdrmap::spectrum {

enum class Mode : unsigned char { Fresh, Contact, Free };

/// How measure() finds a trailing edge: confirmed by replayed material points
/// (to the edge tolerance), or where the nodes alone predict it (the trials of
/// a load step; the confirmed search where there is no prediction).
enum class Edge : unsigned char { Confirmed, Predicted };

class Row {
public:
  /// Depth control: depth c.loading.d, dx = a1 / cells_per_a1, window [-a1, a1].
  /// edge_tol: the trailing edge is located to edge_tol a1 (at least 1e-3 dx).
  Row(const Case& c, const Law& law, double cells_per_a1, double phase, double sub_travel,
      double edge_tol, const RunControl& control, const char* name);
  /// Any depth: starting depth d, spacing dx, window half-width a_win (>= every a1).
  Row(const Case& c, const Law& law, double d, double dx, double a_win, double phase,
      double sub_travel, double edge_tol, const RunControl& control, const char* name);

  /// What a trial step changes (restore() returns to it).
  /// A leading-edge layer of one branch (spectrum_forces.cpp, leading_layer).
  struct BranchLayer {
    double amp = 0.0, width = 0.0;
  };
  struct Snapshot {
    std::vector<double> y;
    std::vector<Mode> mode;
    long double P = 0.0L;
    long long jlo = 0, jhi = -1;
    std::size_t log = 0;
    double d = 0.0, dd = 0.0, w = 0.0;
    double since = 0.0;
    long double lead = 0.0L;
    std::vector<BranchLayer> layers;
  };
  /// Saves the state (the log up to here is kept by every restore: replayed
  /// points are cached there).
  void save(Snapshot& s) const;
  void restore(const Snapshot& s);

  /// Stationary sliding at v0 with the indenter at s = 0: one step at v0 from
  /// an empty window long enough that every element in the window entered
  /// fresh at the leading edge during it (the stationary state, exactly).
  void start_stationary(double v0);
  /// The same at depth d (under load: the depth that balances the discrete F_N).
  void start_stationary(double v0, double d) {
    d_ = d;
    start_stationary(v0);
  }
  /// The width below which a branch's leading-edge layer is taken out of the
  /// grid's values (spectrum_forces.cpp, entry_layers): the cell by default.
  /// The runs of one error estimate share the finest run's cell, so that a
  /// layer one to two fine cells wide is taken out in all of them or in none.
  void set_layer_width(double width) { layer_dx_ = width; }
  /// Whether advance() takes the composed update (spectrum_composed.cpp)
  /// where it applies (the default) or steps every element sub-step by
  /// sub-step.
  void set_composed(bool on) { composed_on_ = on; }
  /// Velocity change to w: contact elements whose force turns negative let go
  /// (dd: the depth rate just after the change, for the parallel dashpot).
  void change_velocity(double w, double dd = 0.0);
  /// Advance by dt at the current velocity, the depth linear from now to d1
  /// (d1 < 0: unchanged); dd1 the depth rate at the end (the dashpot's u').
  void advance(double dt, double d1 = -1.0, double dd1 = 0.0);
  /// Keeps the travel counter small (between steps, not inside a trial).
  void renumber();
  double depth_now() const { return d_; }
  double rate_now() const { return dd_; }
  double a1_now() const { return radius(d_); }
  /// Forces and trailing edge now.
  State measure(Edge edge = Edge::Confirmed) const;

  std::size_t capacity() const { return cap_; }
  long updates() const { return updates_; }
  /// The element steps advance() took composed (spectrum_composed.cpp).
  long composed_steps() const { return composed_steps_; }
  long steps() const { return steps_; }

private:
  /// Sub-steps of one step: a whole number of full sub-steps D ending at dt,
  /// after a first (partial) one from 0.
  struct Grid {
    double dt = 0.0, D = 0.0;
    long long K = 1; // sub-steps of an element that starts at 0
    StepCoef first, full;
    /// The sub-step from t of a step ending at `end`: its end tn (before a
    /// cut at a tip) and the full sub-steps i after it.
    struct Sub {
      double tn;
      long long i;
    };
    Sub from(double end, double t) const;
    /// The set for the sub-step of h from t (i full ones after it): first,
    /// full, or nullptr (a set of its own length).
    const StepCoef* set(double t, long long i, double h) const;
  };
  /// One entry of the log: a step of dt at w ending at travel P (cells), or
  /// (dt < 0) a velocity change to w.
  struct Entry {
    double dt, w;
    long double P;
    std::shared_ptr<const Grid> g; // (consecutive steps with the same grid share it)
    double d0 = 0.0, s = 0.0;      // depth at the start, its rate over the step (a change: d, dd)
    double k = 0.0;                // the depth's curvature: d0 + s t + k t (t - dt)
    double top = 0.0;              // the deepest over the step (deepest(), set by logged())
  };
  /// The depth along a (sub-)step from its start: d + r t + k t^2.
  struct Path {
    double d, r, k;
    double at(double t) const { return d + (r + k * t) * t; }
    double rate(double t) const { return r + 2.0 * k * t; }
    Path from(double t) const { return {at(t), rate(t), k}; }
  };
  struct Material { // one material point's state
    Mode mode = Mode::Fresh;
    double y[kMaxBranches + 1] = {};
  };
  /// Material point J replayed through the first n log entries (gone: past
  /// the window and free, never to touch again); used: the last measure;
  /// tail: its state at the log's end where the log is still at generation
  /// tail_gen (the measures of a trial and of its confirmation replay the
  /// same trial step).
  struct Tracer {
    long double J = 0.0L;
    std::size_t n = 0;
    bool gone = false;
    long used = 0;
    Material m;
    std::uint64_t tail_gen = 0;
    Material tail;
    std::size_t next = SIZE_MAX; // the tracer found after it, the last time
  };
  void set_position(long double P);
  /// The sub-steps of a step of dt at w where the contact is a (none longer
  /// than `longest`).
  void grid(Grid& g, double dt, double w, double a,
            double longest = std::numeric_limits<double>::infinity()) const;
  double full_substep(double dt, double w, double a) const;
  std::shared_ptr<const Grid> step_grid(double dt, double w, double a) const;
  void step_material(Mode& md, double* y, double xe, double dt, double w, const Grid& g,
                     const Path& p) const;
  /// step_material and substep for the shape's image type Img (the loops of
  /// advance() and carry() call the image's functions directly, not through
  /// the variant at each call).
  /// (From t, the element's state y there; composed: its later sub-steps
  /// may take the step's composition, comp_, which is of this step.)
  template <class Img>
  void step_material(const Img& img, Mode& md, double* y, double xe, double dt, double w,
                     const Grid& g, const Path& p, double t = 0.0, bool composed = false) const;
  template <class Img>
  double substep(const Img& img, Mode& md, double* y, double x, double h, double w,
                 const StepCoef& c, bool may_switch, const Path& q) const;
  void change_material(Mode& md, double* y, double x, double w, double d, double dd) const;
  static double deepest(const Entry& e);
  std::vector<Entry>::const_iterator uniform_until(std::vector<Entry>::const_iterator it,
                                                   std::vector<Entry>::const_iterator end) const;
  std::vector<Entry>::const_iterator free_until(std::vector<Entry>::const_iterator it,
                                                std::vector<Entry>::const_iterator end,
                                                Material& mt, double x) const;
  static double total_time(std::vector<Entry>::const_iterator first,
                           std::vector<Entry>::const_iterator last);
  long carry(Material& mt, bool& gone, long double J, std::size_t from, std::size_t to) const;
  Material replay(long double J) const;
  Tracer& tracer(long double J) const;
  double locate(bool contact, const double* y, double x, double h, double w, const Path& q,
                const StepCoef& ch) const;
  double pressure_at(const double* q, double x) const;
  double node_p(long long j) const;
  double edge_sign(Mode md, const double* y, double x) const;
  double predicted_edge(long long jb, bool contact) const;
  double trailing_edge(long long jb, double& pe, Edge edge) const;
  bool predicted_only(long long jb, double& e, double& pe) const;
  void run_forces(long long ja, long long jb, double& FN, double& Fx, double& e, Edge edge) const;
  /// A seam: the material point that was at the leading edge when the
  /// velocity changed at log entry `entry`. On either side of it the material
  /// has had different histories (in contact through the change, or entered
  /// after it), so p(x) is continuous there but its slope jumps: the forces
  /// are integrated on either side of it, its own pressure from its replay
  /// (docs/design.md, "Seams").
  struct Seam {
    std::size_t entry;
    long double J;
  };
  static constexpr std::size_t kMaxSeams = 16; // the newest kept (older ones lie further back)
  void add_seam(std::size_t entry, double w);
  double position(long double J) const {
    return static_cast<double>((J + P_ + static_cast<long double>(phase_)) *
                               static_cast<long double>(dx_));
  }
  /// The material point at x now (position's inverse).
  long double label(double x) const {
    return static_cast<long double>(x) / static_cast<long double>(dx_) - P_ -
           static_cast<long double>(phase_);
  }
  /// The layers of fresh material's fast branches behind the leading edge,
  /// thinner than a cell: L(s) = sum_k amp_k exp(-s / width_k) at s behind
  /// the edge, which the rule cannot integrate from nodes dx apart
  /// (spectrum_forces.cpp, leading_layer).
  /// Branch k's layer: amplitude and width, for the material that entered
  /// since the last change (s < s_c = c since), and for the material before
  /// it (its layer from before the change, decayed by exp(-since / tau_k)).
  struct Layer {
    std::size_t n = 0;
    BranchLayer now[kMaxBranches], before[kMaxBranches];
    double s_c = 0.0;   ///< where the material at the edge at the change is now (< 0: gone)
    double shift = 0.0; ///< added to today's layers (s < s_c): L continuous at s_c
    double reach = 0.0; ///< beyond it L is below rounding
    double at(double s) const;
    double integral() const;
    double moment() const; ///< int s L(s) ds
  };
  Layer leading_layer() const;
  /// The layers fresh material forms at the leading edge at w and rate dd
  /// (zero amplitude at rest and where w tau_k is not below a cell).
  void entry_layers(double w, double dd, BranchLayer* out) const;
  template <class Piece>
  void across_seams(long long ja, long long jb, double xl, double vl, double xr, double vr,
                    bool rest, bool leading, const Layer& layer, Piece piece) const;
  bool resting() const;
  template <class Value, class NodeValue, class Piece>
  void ends_at_rest(long long ja, long long jb, double xl, double vl, double xr, double vr,
                    bool leading, Value value, NodeValue node_value, Piece piece) const;
  double part_value(const double* y, double x, bool rest) const;

  /// A step's contact update composed over its sub-steps, for the parabola
  /// (spectrum_composed.cpp): an element in contact at the step's start, at
  /// x then, is after sub-step l at q_k = E_lk q0_k + P_lk(x), P_lk(x) =
  /// A_lk + B_lk x + C_lk x^2, and its force at the end of sub-step l is
  /// pi_l(x) - sum_k W_lk q0_k (W_lk = G_k E_lk).
  /// A free element's: after sub-step l z = M_l z0, its depression there
  /// sum_m V_lm z0_m (V_lm = w_m M_lm), the indenter's depth hi_l(x).
  /// Sub-steps 1.. share the grid's full set (suffix): from the end of
  /// sub-step l an element goes on r more of them as e^r (Ep: e_k^r, Wp:
  /// G_k e_k^r; Mp, Vp for the free modes), so an element that enters or
  /// switches within the step takes its own sub-steps only up to the end of
  /// the one it does so in (rest_contact, rest_free).
  struct Composed {
    bool suffix = false;
    std::size_t K = 0, n = 0, m = 0;           // sub-steps, branches, free modes
    std::vector<double> E, A, B, C, W, Ep, Wp; // n per sub-step (Ep, Wp: per power)
    std::vector<double> pi, hi;                // 3 per sub-step
    std::vector<double> M, V, Mp, Vp;          // m per sub-step (Mp, Vp: per power)
    std::vector<double> ends;                  // the sub-steps' ends
    std::vector<StepCoef> own;                 // sub-steps' sets that are not the grid's
    /// P_l(x) into q.
    void prefix(std::size_t l, double x, double* q) const;
  };
  bool compose(const Grid& g, double dt, double w, const Path& p);
  void compose_substep(const StepCoef& c, double t, double tn, double w, const Path& p);
  void compose_powers(const StepCoef& full);
  bool composed_step(std::size_t sl, double x, const Path& p, double& t);
  std::size_t composed_contact(double* y, double x, double& p) const;
  std::size_t composed_free(double* y, double x, double w, const Path& p) const;
  bool touches(std::size_t i, const double* V, const double* z, double x, double w,
               const Path& p) const;
  std::size_t rest_contact(double* y, double x, std::size_t l) const;
  std::size_t rest_free(double* y, double x, double w, const Path& p, std::size_t l) const;

  /// The forcing u = h0 + h1 t + h2 t^2 of a contact sub-step of h from x
  /// along the depth path q.
  struct Forcing {
    double h0, h1, h2;
  };
  Forcing forcing(double x, double w, double h, const Path& q) const;
  double next_cut(double x0, double t, double tn, double w) const;
  // Forces (spectrum_forces.cpp).
  /// The points of a part of a contact run: positions and values (nodes at
  /// spacing dx, or a few points of a short part).
  struct Points {
    const double* x;
    const double* v;
    long long n;
  };
  void piece_forces(const Points& pts, double xl, double pl, double xr, double pr, double& FN,
                    double& Fx) const;
  void profile_piece_forces(const Points& pts, double xl, double bl, double xr, double br,
                            double& FN, double& Fx) const;
  void sliver_forces(double e, double b0, double be, double& FN, double& Fx) const;
  long long last_before_tip() const;
  double side_slope(double x, int side) const;
  double known_p(double x, int side) const;
  struct KnownForces {
    double N, X; ///< int A, int A (-g')
  };
  KnownForces known_forces(double l, double r) const;
  double node_rest(long long j) const;
  double tip_rest(long long jt, int side) const;
  double tip_pressure(long long jt, int side) const;
  double past_tip(double p_ahead) const;

  // The profile: the shape's image (core/model/shapes/), visited here, out of
  // the loops of the callers (the parabola's arithmetic as the seed's, bit
  // for bit).
  template <class F> decltype(auto) shape(F&& f) const {
    return std::visit(std::forward<F>(f), img_);
  }
  double depth(double x) const { return depth(x, d_); }
  double depth(double x, double d) const {
    return shape([&](const auto& i) { return i.depth(x, d); });
  }
  /// g'(x) w: how fast the indenter rises under a point at x moving at w.
  double lift(double x, double w) const {
    return shape([&](const auto& i) { return i.lift(x, w); });
  }
  double radius(double d) const {
    return shape([&](const auto& i) { return i.leading_edge(d); });
  }
  bool inside(double x, double d) const {
    return shape([&](const auto& i) { return i.inside(x, d); });
  }
  double g(double x) const {
    return shape([&](const auto& i) { return i.g(x); });
  }
  /// c of g = c x^2 where the image is the parabola (compose()).
  double g_coefficient() const { return g(1.0); }
  /// g''(x) (x != 0).
  double curvature(double x) const {
    return shape([&](const auto& i) { return i.curvature(x); });
  }
  /// Whether the image is smooth through the tip x = 0 (the parabola): no
  /// sub-step or run is cut there.
  bool smooth() const {
    return shape([](const auto& i) { return i.smooth_apex(); });
  }
  /// The largest travel of a sub-step where the contact is a: sub_travel a,
  /// and at most kSubCells dx where the forcing is interpolated.
  double sub_length(double a) const;
  double xi(long long j) const { return (static_cast<double>(j + m_) + theta_ + phase_) * dx_; }
  std::size_t slot(long long j) const {
    const auto c = static_cast<long long>(cap_);
    return static_cast<std::size_t>(((j % c) + c) % c);
  }

  const Law& law_;
  const RunControl& control_;
  const char* name_;
  ShapeImage img_;   // the indenter's g (Indenter::image)
  bool smooth_;      // img_'s smooth(): the parabola's Taylor forcing, no tip
  bool exact_force_; // u quadratic in t on either side of the tip (no interpolation error)
  double d_, dx_, aw_, phase_, sub_travel_;
  double layer_dx_ = dx_; // set_layer_width
  double dd_ = 0.0;       // depth rate now (load control)
  std::size_t cap_, stride_;
  std::vector<double> y_; // per slot: q (contact) or z (free), stride_ each
  std::vector<Mode> mode_;
  std::vector<Entry> log_;
  long double P_ = 0.0L; // travel s/dx in cells
  long long m_ = 0;      // floor(P)
  double theta_ = 0.0;   // P - m
  long long jlo_ = 0, jhi_ = -1;
  double w_ = 0.0;
  // time since the last change of w or dd (a jump), and the leading edge's
  // layers just before it (leading_layer)
  double since_ = 0.0;
  long double lead_ = 0.0L; // the material point at the leading edge then
  std::vector<BranchLayer> layers_before_;
  mutable long updates_ = 0;
  long steps_ = 0;
  double edge_tol_ = 1e-9; // the trailing edge's tolerance, in a1
  // coefficient sets of a partial sub-step and of a switch's search, whose
  // last is the switch's (kept: their vectors are allocated once)
  mutable StepCoef coef_scratch_[2];
  Composed comp_;           // the last step's (compose)
  bool composed_on_ = true; // set_composed
  // the force each slot's element ended its last step with, where the
  // composed step formed it (node_p), valid while p_gen_[slot] == state_gen_
  // (the state and the depth unchanged since)
  std::vector<double> p_end_;
  std::vector<std::uint64_t> p_gen_;
  std::uint64_t state_gen_ = 1;
  long composed_steps_ = 0;
  // the last span of log entries at one velocity and depth a replay crossed
  // in one step (uniform_until): entries [from, last] found from `from`
  // within [from, to), and the grid of the step over them (its coefficient
  // sets formed once per span)
  struct Span {
    std::size_t from = 0, to = 0, last = 0; // (to = 0: none)
    Grid g;
  };
  mutable Span span_;
  mutable std::vector<Tracer> tracers_;   // replayed points, carried on from here
  std::uint64_t log_gen_ = 1;             // changes with every entry logged or dropped
  mutable std::size_t last_ = SIZE_MAX;   // the tracer found last (tracer())
  std::vector<Seam> seams_;               // kinks of p(x) that may lie in the contact
  mutable std::size_t stable_ = SIZE_MAX; // log entries no restore drops (set by save)
  mutable long measures_ = 0;
  mutable std::vector<double> scratch_x_, scratch_v_; // a part's points while its forces are summed
  double psi_tiny_ = 0.0, p_tiny_ = 0.0;              // gap and force below rounding
  double unit_ = 1.0;                                 // work units per element sub-step
  double window_bytes_ = 0.0, log_bytes_ = 0.0;       // memory held (bounded)
  double entry_bytes(std::size_t i) const;            // log entry i with the grid it owns
  void logged(); // counts the last entry; throws past the bound
  [[noreturn]] void too_much_memory() const;
};

} // namespace mdrmap::spectrum
