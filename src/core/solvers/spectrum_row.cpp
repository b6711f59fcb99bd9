#include "core/solvers/spectrum_row.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <tuple>
#include <utility>

#include "core/numerics/root.hpp"

namespace mdrmap::spectrum {
namespace {

constexpr int kMaxEvents = 8;           // contact switches of one element within one step
constexpr std::size_t kMaxTracers = 64; // replayed points kept (a few per contact run's edge; at
                                        // rest the edge cells' points too: Row::ends_at_rest)
constexpr double kSubCells = 1.0;       // largest travel of an interpolated sub-step, in dx
/// A switch's force (gap) within kNoise of G0 u (u) is zero to rounding.
constexpr double kNoise = 4.0 * std::numeric_limits<double>::epsilon();
/// A switch is located where its force (gap) has just crossed zero, by at
/// most kSwitchTol of G0 u (u): the time then errs by that over the force's
/// rate, and the state after the switch by its square (the two sides' paths
/// leave the switch with one value), far below any rtol. On the far side the
/// element does not switch back at once (a contact let go in tension moves
/// off the indenter; a free point caught inside it presses). Rounding-level
/// searches (kNoise) took 3.3 coefficient sets a switch under load, 4.4 on a
/// hold; this takes about 2.
constexpr double kSwitchTol = 1e-9;
constexpr long long kPast = 5; // nodes kept past the window: four free ones predict an edge there
// The row's memory (window, its snapshot, the log of steps and their
// coefficient sets) is bounded: a case that would need more fails at once
// instead of growing to gigabytes (32 terms under load: 1.5 GB).
constexpr double kMaxBytes = 128e6;

/// Bytes a step's coefficient sets hold.
double coef_bytes(const StepCoef& c) {
  return 8.0 * static_cast<double>(c.e.size() + c.a.size() + c.b.size() + c.modal.size());
}

// Root of f on [0, hi] with f(0) > 0 > f(hi); the end itself when the sign
// condition fails there (rounding at a tangency).
template <class F> double solve(F f, double hi) {
  const double flo = f(0.0), fhi = f(hi);
  if (!(flo > 0.0)) return 0.0;
  if (!(fhi < 0.0)) return hi;
  return numerics::toms748(f, 0.0, hi, flo, fhi, numerics::bits_tolerance(50),
                           {"row: release", 100})
      .mid();
}

// The zero in (0, 1) of the cubic through f0 and f1 at 0 and 1 with slopes m0
// and m1 there (f0 > 0 > f1; Hermite): a switch's first point, within
// O(h^4) of it where the force (gap) is smooth over the sub-step.
double hermite_zero(double f0, double m0, double f1, double m1) {
  const double c2 = 3.0 * (f1 - f0) - 2.0 * m0 - m1, c3 = 2.0 * (f0 - f1) + m0 + m1;
  return numerics::newton_in_bracket(
      [&](double s, double& v, double& dv) {
        v = ((c3 * s + c2) * s + m0) * s + f0;
        dv = (3.0 * c3 * s + 2.0 * c2) * s + m0;
      },
      f0, 1.0);
}

// A switch's time in (0, h): the root of f with f(0) = f0 > 0 > f(h) (else 0
// or h, as solve) and f'(0) = df0, by numerics::newton_in_bracket from the
// zero of the Hermite cubic of f and f' at both ends, until f is within
// `noise` below zero (at the switch or just past it: see kSwitchTol; near a
// tangency, where f is rounding, the steps it leaves are far longer than 4
// ulps, and bisection took some twenty more points). It returns the point it
// evaluated last, whose coefficient set the caller's f formed last: from the
// secant's start the search took about five sets a switch, and the switch's
// update one more; from this one about three in all.
template <class F> double switch_time(F f, double f0, double df0, double h, double noise) {
  return numerics::newton_in_bracket(
      f, f0, h, [&](double v, double dv) { return hermite_zero(f0, df0 * h, v, dv * h) * h; },
      noise, numerics::NewtonEnd::Evaluated);
}

// static_cast<long long>(std::ceil(r)) for 0 <= r < 2^63, without the
// libm call that std::ceil is on x86-64 without SSE4.1 (once per sub-step)
long long ceil_count(double r) {
  const auto n = static_cast<long long>(r);
  return static_cast<double>(n) < r ? n + 1 : n;
}

} // namespace

Row::Grid::Sub Row::Grid::from(double end, double t) const {
  const long long i = std::max(0LL, ceil_count((end - t) / D) - 1);
  double tn = end - static_cast<double>(i) * D;
  if (!(tn > t)) tn = i > 0 ? end - static_cast<double>(i - 1) * D : end;
  return {tn, i};
}

const StepCoef* Row::Grid::set(double t, long long i, double h) const {
  if (t == 0.0 && i == K - 1 && h == first.dt) return &first;
  if (std::abs(h - D) <= 1e-13 * D) return &full;
  return nullptr;
}

Row::Row(const Case& c, const Law& law, double cells_per_a1, double phase, double sub_travel,
         double edge_tol, const RunControl& control, const char* name)
    : Row(c, law, c.loading.d, c.a1() / cells_per_a1, c.a1(), phase, sub_travel, edge_tol, control,
          name) {}

Row::Row(const Case& c, const Law& law, double d, double dx, double a_win, double phase,
         double sub_travel, double edge_tol, const RunControl& control, const char* name)
    : law_(law), control_(control), name_(name), img_(c.indenter.image()), smooth_(smooth()),
      exact_force_(shape([](const auto& i) { return i.exact_forcing(); })), d_(d), dx_(dx),
      aw_(a_win), phase_(phase), sub_travel_(sub_travel) {
  const double cells = aw_ / dx_;
  cap_ = static_cast<std::size_t>(std::floor(2.0 * cells)) + 8 + static_cast<std::size_t>(kPast);
  stride_ = std::max<std::size_t>(law.free_dim(), 1);
  // work units per element sub-step: its cost grows with the branches (one
  // unit ~ 15-20 ns, as an element update of the Kelvin solvers)
  unit_ = 1.0 + 0.25 * static_cast<double>(law.free_dim());
  // the window and the snapshot the load balance keeps of it
  window_bytes_ = 2.0 * (2.0 * cells + 8.0 + static_cast<double>(kPast)) *
                  (8.0 * static_cast<double>(stride_) + static_cast<double>(sizeof(Mode)));
  if (!(window_bytes_ <= kMaxBytes)) too_much_memory();
  y_.assign(cap_ * stride_, 0.0);
  mode_.assign(cap_, Mode::Fresh);
  p_end_.assign(cap_, 0.0);
  p_gen_.assign(cap_, 0);
  // switches need a force or gap beyond rounding: a point that let go at a
  // tangency (p = 0 and h - u = 0 together) must not flip back and forth
  psi_tiny_ = 1e-13 * d_;
  p_tiny_ = law.G0() * psi_tiny_;
  edge_tol_ = std::clamp(edge_tol, 1e-15, 1e-3 * dx_ / a1_now()); // at least 1e-3 dx
}

void Row::save(Snapshot& s) const {
  s.y = y_;
  s.mode = mode_;
  s.P = P_;
  s.jlo = jlo_;
  s.jhi = jhi_;
  s.log = log_.size();
  s.d = d_;
  s.dd = dd_;
  s.w = w_;
  s.since = since_;
  s.lead = lead_;
  s.layers = layers_before_;
  stable_ = log_.size();
}

void Row::restore(const Snapshot& s) {
  ++state_gen_;
  y_ = s.y;
  mode_ = s.mode;
  set_position(s.P);
  jlo_ = s.jlo;
  jhi_ = s.jhi;
  for (std::size_t i = s.log; i < log_.size(); ++i)
    log_bytes_ -= entry_bytes(i);
  log_.resize(s.log);
  ++log_gen_;
  seams_.erase(
      std::remove_if(seams_.begin(), seams_.end(), [&](const Seam& m) { return m.entry >= s.log; }),
      seams_.end());
  span_.to = 0; // (the entries from s.log on are replaced: no span kept)
  tracers_.erase(std::remove_if(tracers_.begin(), tracers_.end(),
                                [&](const Tracer& t) { return t.n > s.log; }),
                 tracers_.end());
  d_ = s.d;
  dd_ = s.dd;
  w_ = s.w;
  since_ = s.since;
  lead_ = s.lead;
  layers_before_ = s.layers;
}

void Row::set_position(long double P) {
  P_ = P;
  const long double fl = std::floor(P);
  m_ = static_cast<long long>(fl);
  theta_ = static_cast<double>(P - fl);
  const double c = aw_ / dx_;
  jlo_ = static_cast<long long>(std::ceil(-c - theta_ - phase_)) - m_;
  // nodes past the window: the gaps of the free material there predict an edge
  jhi_ = static_cast<long long>(std::floor(c - theta_ - phase_)) - m_ + kPast;
}

void Row::start_stationary(double v0) {
  w_ = v0;
  dd_ = 0.0;
  since_ = 0.0; // (the step below sets every element's history)
  layers_before_.assign(law_.branches(), BranchLayer{});
  log_.clear();
  log_bytes_ = 0.0;
  tracers_.clear();
  seams_.clear();
  span_.to = 0;
  const double dt = (a1_now() + aw_ + 6.0 * dx_) / v0;
  set_position(-static_cast<long double>(v0 * dt / dx_));
  lead_ = label(-a1_now()); // (past the window after the step: all entered at v0)
  jhi_ = jlo_ - 1;          // empty: every element enters fresh during the step
  advance(dt);
}

void Row::change_velocity(double w, double dd) {
  ++state_gen_;
  control_.charge(unit_ * static_cast<double>(jhi_ - jlo_ + 1), name_);
  add_seam(log_.size(), w);
  if (w != w_ || dd != dd_) {
    layers_before_.resize(law_.branches());
    entry_layers(w_, dd_, layers_before_.data());
    since_ = 0.0;
    lead_ = label(-a1_now());
  }
  w_ = w;
  dd_ = dd;
  log_.push_back(Entry{-1.0, w, P_, nullptr, d_, dd});
  logged();
  for (long long j = jlo_; j <= jhi_; ++j)
    change_material(mode_[slot(j)], &y_[slot(j) * stride_], xi(j), w, d_, dd);
}

// The seam of a change to w at log entry `entry`, before it acts: the
// material point at the leading edge, where fresh material starts to enter at
// w. Fresh material's branches form layers w tau_k wide behind the edge; the
// kink is a seam only where those are resolved (w tau_k at least the layer
// width of set_layer_width for every branch): across an unresolved layer the
// parts on either side are no smoother than the whole. Seams past the window
// are dropped (that material never touches again), and the oldest beyond
// kMaxSeams.
void Row::add_seam(std::size_t entry, double w) {
  seams_.erase(std::remove_if(seams_.begin(), seams_.end(),
                              [&](const Seam& m) { return position(m.J) > aw_ + 2.0 * dx_; }),
               seams_.end());
  if (!(w * law_.shortest_time() >= layer_dx_)) return;
  seams_.push_back({entry, label(-a1_now())});
  if (seams_.size() > kMaxSeams)
    seams_.erase(seams_.begin(), seams_.end() - static_cast<std::ptrdiff_t>(kMaxSeams));
}

// A contact element whose force at the new velocity is negative lets go.
void Row::change_material(Mode& md, double* y, double x, double w, double d, double dd) const {
  if (md != Mode::Contact || !(law_.pressure(depth(x, d), dd - lift(x, w), y) < 0.0)) return;
  double q[kMaxBranches + 1];
  std::copy(y, y + law_.branches(), q);
  law_.to_modal(depth(x, d), q, y);
  md = Mode::Free;
}

// (In place: a grid that already holds a coefficient set keeps it, Law::coef.)
void Row::grid(Grid& g, double dt, double w, double a, double longest) const {
  g.dt = dt;
  g.D = std::min(full_substep(dt, w, a), longest);
  g.K = std::max(1LL, static_cast<long long>(std::ceil(dt / g.D)));
  // (dt / D a hair above a whole number, as 0.075 / 0.025: no empty first
  // sub-step; step_material would take its coefficients for a full one)
  if (g.K > 1 && !(dt - static_cast<double>(g.K - 1) * g.D > 0.0)) --g.K;
  law_.coef(dt - static_cast<double>(g.K - 1) * g.D, g.first);
  if (g.K == 1 && g.first.dt == g.D)
    g.full = g.first; // (one sub-step: the same set, formed once)
  else
    law_.coef(g.D, g.full);
}

double Row::full_substep(double dt, double w, double a) const {
  return w > 0.0 ? std::min(dt, sub_length(a) / w) : dt;
}

// The grid of a step of dt at w where the contact is a: the last log
// entry's where that has the same sub-steps (the steps of a hold, or at one
// velocity and depth, share one: its coefficient sets are formed and their
// vectors allocated once, not at every step).
std::shared_ptr<const Row::Grid> Row::step_grid(double dt, double w, double a) const {
  const Grid* last = log_.empty() ? nullptr : log_.back().g.get();
  if (last && last->dt == dt && last->D == full_substep(dt, w, a)) return log_.back().g;
  auto g = std::make_shared<Grid>();
  grid(*g, dt, w, a);
  return g;
}

void Row::renumber() {
  // keep the travel counter small (renumbering by whole rings keeps every slot)
  const long long ring = static_cast<long long>(cap_);
  if (m_ > (1LL << 24) || m_ < -(1LL << 24)) {
    const long long K = (m_ / ring) * ring;
    P_ -= static_cast<long double>(K);
    m_ -= K;
    jlo_ += K;
    jhi_ += K;
    for (Entry& e : log_)
      e.P -= static_cast<long double>(K);
    for (Tracer& t : tracers_)
      t.J += static_cast<long double>(K);
    ++log_gen_; // (the positions are the same, their arithmetic not)
    ++state_gen_;
    for (Seam& m : seams_)
      m.J += static_cast<long double>(K);
    lead_ += static_cast<long double>(K);
  }
}

void Row::advance(double dt, double d1, double dd1) {
  if (!(dt > 0.0)) return;
  ++steps_;
  ++state_gen_;
  const double d0 = d_, s = d1 > 0.0 ? (d1 - d0) / dt : 0.0;
  // the path ends at the rate dd1 (a dashpot's force sees it): the parabola
  // through the step's ends with that slope at dd1's end
  const double k = d1 > 0.0 ? (dd1 - s) / dt : 0.0;
  const long long lo0 = jlo_, hi0 = jhi_;
  set_position(P_ + static_cast<long double>(w_ * dt / dx_));
  // sub-steps: the contact's travel at the smaller a1 of the step
  log_.push_back(
      Entry{dt, w_, P_, step_grid(dt, w_, radius(d1 > 0.0 ? std::min(d0, d1) : d0)), d0, s, k});
  logged();
  const Grid& g = *log_.back().g;
  const Path path{d0, s - k * dt, k};
  const bool composed = compose(g, dt, w_, path);
  shape([&](const auto& img) {
    for (long long j = jlo_; j <= jhi_; ++j) {
      const std::size_t sl = slot(j);
      if (j < lo0 || j > hi0) mode_[sl] = Mode::Fresh; // entered during the step
      const long before = updates_;
      double t = 0.0; // (where composed_step leaves off)
      if (!(composed && composed_step(sl, xi(j) - w_ * dt, path, t)))
        step_material(img, mode_[sl], &y_[sl * stride_], xi(j), dt, w_, g, path, t, composed);
      // (charged per element: one element of a stiff branch can take 1e9 sub-steps)
      control_.charge(unit_ * static_cast<double>(updates_ - before), name_);
    }
  });
  if (d1 > 0.0) {
    d_ = d1;
    dd_ = dd1;
  }
  since_ += dt;
}

double Row::entry_bytes(std::size_t i) const {
  const Entry& e = log_[i];
  const bool own = e.g && (i == 0 || log_[i - 1].g != e.g); // (consecutive entries share)
  return static_cast<double>(sizeof(Entry)) +
         (own ? static_cast<double>(sizeof(Grid)) + 32.0 + coef_bytes(e.g->first) +
                    coef_bytes(e.g->full)
              : 0.0);
}

void Row::logged() {
  ++log_gen_;
  Entry& e = log_.back();
  e.top = e.dt > 0.0 ? deepest(e) : e.d0;
  log_bytes_ += entry_bytes(log_.size() - 1);
  if (!(window_bytes_ + log_bytes_ <= kMaxBytes)) too_much_memory();
}

void Row::too_much_memory() const {
  throw CaseAbandoned(std::string(name_) + ": the element row would hold more than " +
                      format_number(kMaxBytes / 1e6) + " MB (" +
                      std::to_string(static_cast<long>(2.0 * aw_ / dx_)) + " elements of " +
                      std::to_string(stride_) + " values and " + std::to_string(log_.size()) +
                      " steps of its history); the case is too long or too stiff for this "
                      "solver at this rtol");
}

// One material point over a step of dt at w, from its state at 0 (or fresh)
// to dt, at the end position xe; positions at time t are xe - w (dt - t), the
// depth p.at(t).
void Row::step_material(Mode& md, double* y, double xe, double dt, double w, const Grid& g,
                        const Path& p) const {
  shape([&](const auto& img) { step_material(img, md, y, xe, dt, w, g, p); });
}

template <class Img>
void Row::step_material(const Img& img, Mode& md, double* y, double xe, double dt, double w,
                        const Grid& g, const Path& p, double t, bool composed) const {
  if (md == Mode::Fresh) { // enters where the leading edge -a1(t) passes it
    const double xs = xe - w * dt;
    auto behind = [&](double tt) { // > 0 while ahead of the edge
      return -(xs + w * tt) - img.leading_edge(std::max(0.0, p.at(tt)));
    };
    if (!(behind(dt) < 0.0)) return;
    t = solve(behind, dt);
    md = Mode::Contact;
    std::fill(y, y + stride_, 0.0);
  }
  StepCoef& local = coef_scratch_[0];
  int events = 0;
  while (t < dt) {
    const Grid::Sub sub = g.from(dt, t);
    const double tn = smooth_ ? sub.tn : next_cut(xe - w * dt, t, sub.tn, w);
    const double h = tn - t;
    const StepCoef* c = tn == sub.tn ? g.set(t, sub.i, h) : nullptr;
    if (c == nullptr) {
      law_.coef(h, local, md == Mode::Contact ? Part::Contact : Part::Free);
      c = &local;
    }
    ++updates_;
    const double done =
        substep(img, md, y, xe - w * (dt - t), h, w, *c, events < kMaxEvents, p.from(t));
    if (done < h) {
      t += done;
      ++events;
    } else {
      t = tn;
      // the rest of the step's sub-steps, the full ones after sub-step l, composed
      const auto ahead = static_cast<std::size_t>(sub.i); // (full sub-steps after this one)
      if (composed && comp_.suffix && ahead > 0 && ahead < comp_.K && tn == sub.tn &&
          events < kMaxEvents && comp_.ends[comp_.K - 1 - ahead] == tn && md != Mode::Fresh) {
        const std::size_t l = comp_.K - 1 - ahead, // (this sub-step's index)
            i = md == Mode::Contact ? rest_contact(y, xe - w * dt, l)
                                    : rest_free(y, xe - w * dt, w, p, l);
        t = comp_.ends[i - 1];
        updates_ += static_cast<long>(i - 1 - l);
      }
    }
  }
}

// One sub-step of h from position x along the depth path q (coefficients c):
// the exact update, or, where the element switches during it (if it still
// may), the update up to the switch, located, and the switch. Returns the time
// advanced.
template <class Img>
double Row::substep(const Img& img, Mode& md, double* y, double x, double h, double w,
                    const StepCoef& c, bool may_switch, const Path& q) const {
  // (stepped in place, its start kept in y0: a switch's search starts there)
  double y0[kMaxBranches + 1], tmp[kMaxBranches + 1];
  StepCoef& at = coef_scratch_[1];
  const double xn = x + w * h, dn = q.at(h);
  if (md == Mode::Contact) {
    const auto u = img.template forcing<Forcing>(x, w, h, q);
    const double p = law_.contact_step_pressure(y, y0, img.depth(xn, dn),
                                                q.rate(h) - img.lift(xn, w), u.h0, u.h1, u.h2, c);
    if (!(may_switch && p < -p_tiny_)) return h;
    const double tc = locate(true, y0, x, h, w, q, c); // lets go
    law_.coef(tc, at, Part::Contact);
    law_.contact_step(y0, tmp, u.h0, u.h1, u.h2, at);
    law_.to_modal(img.depth(x + w * tc, q.at(tc)), tmp, y);
    md = Mode::Free;
    return tc;
  }
  const double gap = img.depth(xn, dn) - law_.free_step_u(y, y0, c);
  if (!(may_switch && gap > psi_tiny_ && img.inside(xn, dn))) return h;
  const double tc = locate(false, y0, x, h, w, q, c); // touches
  law_.coef(tc, at, Part::Free);
  law_.free_step(y0, tmp, at);
  law_.from_modal(tmp, y);
  md = Mode::Contact;
  return tc;
}

// The deepest the indenter goes over a step (its ends, or the parabola's vertex).
double Row::deepest(const Entry& e) {
  const Path p{e.d0, e.s - e.k * e.dt, e.k};
  double d = std::max(e.d0, p.at(e.dt));
  const double top = p.k < 0.0 ? -p.r / (2.0 * p.k) : -1.0;
  if (top > 0.0 && top < e.dt) d = std::max(d, p.at(top));
  return d;
}

// Carries material point J, in state mt after the first `from` log entries,
// through entries [from, to) (node numbering: node j is J = j): fresh until it
// enters at -a1; gone once past the window and free (it never touches again).
// Returns the element updates.
long Row::carry(Material& mt, bool& gone, long double J, std::size_t from, std::size_t to) const {
  auto it = log_.begin() + static_cast<std::ptrdiff_t>(from);
  const auto end = log_.begin() + static_cast<std::ptrdiff_t>(to);
  if (mt.mode == Mode::Fresh) // entries that end with the point ahead of the window (P grows)
    it = std::partition_point(it, end, [&](const Entry& e) {
      return (J + e.P + static_cast<long double>(phase_)) * static_cast<long double>(dx_) <=
             -static_cast<long double>(aw_);
    });
  long done = 0;
  for (; it != end && !gone; ++it) {
    const Entry& e = *it;
    const double x = static_cast<double>((J + e.P + static_cast<long double>(phase_)) *
                                         static_cast<long double>(dx_));
    if (e.dt < 0.0) {
      change_material(mt.mode, mt.y, x, e.w, e.d0, e.s);
    } else if (mt.mode != Mode::Fresh || x > -radius(e.top)) {
      gone = x > aw_ + 2.0 * dx_ && mt.mode != Mode::Contact;
      if (gone) break;
      auto last = mt.mode == Mode::Fresh ? it : uniform_until(it, end);
      if (last != it) { // entries at one velocity and depth: one exact step (its grid in span_)
        const double xl = static_cast<double>((J + last->P + static_cast<long double>(phase_)) *
                                              static_cast<long double>(dx_));
        step_material(mt.mode, mt.y, xl, span_.g.dt, e.w, span_.g, Path{e.d0, 0.0, 0.0});
      } else if (mt.mode != Mode::Free || e.w != 0.0 || (last = free_until(it, end, mt, x)) == it) {
        step_material(mt.mode, mt.y, x, e.dt, e.w, *e.g, Path{e.d0, e.s - e.k * e.dt, e.k});
      } // (else free at rest through `last`: stepped by free_until)
      it = last;
      ++done;
    }
  }
  return done;
}

// The last of the entries from `it` on that move the indenter at one velocity
// (at rest included) and one depth, with no change between them (it itself
// where the next is not such an entry): over them a material point moves as
// over one step of their total time, exactly (the forcing of the profile's
// sub-steps is exact for the parabola, the cone and n = 2; where it is
// interpolated only holds are merged, so that the sub-steps stay where the
// live row takes them). Its switches are located within the sub-steps of that
// step (at most sub_travel a1 of travel, as the live row's; the live row also
// checks at each entry's end, a replay at the span's: a point that would let
// go and touch again within one sub-step is the one case they could tell
// apart). A hold sampled 60 times is replayed in one step; so is a segment's
// stretch at fixed depth, whatever its samples and probes (a point at the
// trailing edge crossed about 100 entries: 61% of a velocity-step test's
// CPU at fixed depth went to such replays).
// The span past `it` is kept in span_ with the grid of that step (grid()
// forms both coefficient sets: a point that switches within rounding of the
// span's start goes on with the full one): the new points replayed in one
// measure at rest all cross the same span, the whole hold so far.
std::vector<Row::Entry>::const_iterator
Row::uniform_until(std::vector<Entry>::const_iterator it,
                   std::vector<Entry>::const_iterator end) const {
  const Entry& e0 = *it;
  auto same = [&](const Entry& e) {
    return e.dt > 0.0 && e.w == e0.w && e.s == 0.0 && e.k == 0.0 && e.d0 == e0.d0;
  };
  if (!same(e0) || (e0.w > 0.0 && !exact_force_)) return it;
  const auto from = static_cast<std::size_t>(it - log_.begin()),
             to = static_cast<std::size_t>(end - log_.begin());
  if (span_.from == from && span_.to == to)
    return log_.begin() + static_cast<std::ptrdiff_t>(span_.last);
  auto last = it;
  double longest = e0.dt;
  while (last + 1 != end && same(*(last + 1)))
    longest = std::max(longest, (++last)->dt);
  if (last != it) {
    span_.from = from;
    span_.to = to;
    span_.last = static_cast<std::size_t>(last - log_.begin());
    // moving, a sub-step is no longer than the longest of the entries: the
    // live row tests for switches at each entry's end, and at a slow
    // velocity a sub-step's travel alone would let one span a whole segment
    // (a drop to 0.1 a1 over a segment: an element that let go and touched
    // again inside it was missed, 6e-3 in mu at the next hold's samples)
    grid(span_.g, total_time(it, last), e0.w, radius(e0.d0),
         e0.w > 0.0 ? longest : std::numeric_limits<double>::infinity());
  }
  return last;
}

// A free material point at rest at x (state mt at entry `it`) over the
// steps at rest from `it` on (under load each its own depth path, so
// uniform_until merges none): its free update is exact over any time, and
// it stays free wherever its gap h - u stays negative. Over entries [it,
// last] of total time T the gap is below depth(x, the deepest of them) less
// the floor of u over [0, T] (Law::free_span); where that bound is negative
// the live row, which tests the gap at each entry's end, lets it pass free
// too, and the point crosses them in one step. The whole run of steps at
// rest is tried first (a point behind the edge mostly stays free through it:
// one floor instead of a dozen), then spans of 2, 4, 8, ... entries until
// the bound fails or the steps at rest end; mt is left after the longest
// that held, which is returned (it itself where none did: mt unchanged). A
// point that lies behind the trailing edge through a hold under load is
// replayed in a few steps instead of one per step (89% of the
// slide-hold-slide's replayed updates were such). (Without the bound,
// SpectrumLoadCaseSet.MeetsRtolWithAnHonestEstimate fails.)
std::vector<Row::Entry>::const_iterator Row::free_until(std::vector<Entry>::const_iterator it,
                                                        std::vector<Entry>::const_iterator end,
                                                        Material& mt, double x) const {
  auto rest = [&](std::vector<Entry>::const_iterator e) {
    return e != end && e->dt > 0.0 && e->w == 0.0;
  };
  double z[kMaxBranches + 1], best[kMaxBranches + 1];
  double T = it->dt, top = it->top;
  const double u0 = law_.free_u(mt.y); // (the floor is below it: no span holds where it fails)
  // the gap's bound over a span of total time Ts reaching the depth `deepest`
  // is negative (z: the state after it)
  auto stays_free = [&](double Ts, double deepest) {
    return depth(x, deepest) - u0 < 0.0 && depth(x, deepest) - law_.free_span(mt.y, z, Ts) < 0.0;
  };
  auto last = it;
  { // the whole run at rest first (a point behind the edge mostly stays free through it)
    double Ta = T, ta = top;
    auto cur = it;
    while (rest(cur + 1)) {
      ++cur;
      Ta += cur->dt;
      ta = std::max(ta, cur->top);
    }
    if (cur != it && stays_free(Ta, ta)) {
      std::copy(z, z + law_.free_dim(), mt.y);
      return cur;
    }
  }
  std::size_t n = 1, next = 2;
  for (auto cur = it; rest(cur + 1);) {
    ++cur;
    T += cur->dt;
    top = std::max(top, cur->top);
    if (++n < next && rest(cur + 1)) continue;
    if (!stays_free(T, top)) break;
    std::copy(z, z + law_.free_dim(), best);
    last = cur;
    next *= 2;
  }
  if (last != it) std::copy(best, best + law_.free_dim(), mt.y);
  return last;
}

double Row::total_time(std::vector<Entry>::const_iterator first,
                       std::vector<Entry>::const_iterator last) {
  double T = 0.0;
  for (auto e = first;; ++e) {
    T += e->dt;
    if (e == last) return T;
  }
}

// The cached tracer at J (a new one, fresh before the log, in the place of the
// least recently used where the cache is full: the first of the least
// used, found in the same pass as the search, since most points are new).
// The one found after the last one found the last time is tried first: a
// measure at rest replays the edge cells' points in the same order from step
// to step.
Row::Tracer& Row::tracer(long double J) const {
  auto found = [&](std::size_t i) -> Tracer& {
    if (last_ < tracers_.size()) tracers_[last_].next = i;
    last_ = i;
    return tracers_[i];
  };
  auto is = [&](std::size_t i) { // (a point is cached once at most)
    return i < tracers_.size() && tracers_[i].J == J && tracers_[i].n <= log_.size();
  };
  if (last_ < tracers_.size() && is(tracers_[last_].next)) return found(tracers_[last_].next);
  std::size_t lru = 0;
  for (std::size_t i = 0; i < tracers_.size(); ++i) {
    if (is(i)) return found(i);
    if (tracers_[i].used < tracers_[lru].used) lru = i;
  }
  if (tracers_.size() < kMaxTracers) {
    lru = tracers_.size();
    tracers_.emplace_back();
  }
  Tracer& t = found(lru);
  t.J = J;
  t.n = 0;
  t.gone = false;
  t.used = 0;
  t.tail_gen = 0;
  t.m.mode = Mode::Fresh;
  std::fill(t.m.y, t.m.y + stride_, 0.0); // (the rest of y is never read)
  return t;
}

// The state now of the material point at J: its tracer carried to the part of
// the log no restore drops (and kept), then through the rest (kept as its
// tail until the log changes: a step's trial and confirmed measures at one
// depth replay the same points through the same trial step).
Row::Material Row::replay(long double J) const {
  Tracer& t = tracer(J);
  t.used = measures_;
  const std::size_t keep = std::min(stable_, log_.size());
  long done = 0;
  if (t.n < keep) {
    done += carry(t.m, t.gone, J, t.n, keep);
    t.n = keep;
    t.tail_gen = 0;
  }
  if (t.tail_gen == log_gen_) return t.tail;
  t.tail = t.m;
  bool gone = t.gone;
  done += carry(t.tail, gone, J, t.n, log_.size());
  t.tail_gen = log_gen_;
  control_.charge(unit_ * static_cast<double>(done), name_);
  return t.tail;
}

// Time within a sub-step of length h (from position x, state y) where a
// contact element's force turns negative, or a free element touches: Newton
// on the exact update's force (gap), with its time derivative from the
// element's law (switch_time). ch: the sub-step's coefficient set, taken for
// the search's first point where it is of that time (h, mostly). The others
// are formed in coef_scratch_[1], where the switch's own update finds the
// last of them (switch_time returns that point).
double Row::locate(bool contact, const double* y, double x, double h, double w, const Path& q,
                   const StepCoef& ch) const {
  StepCoef& scratch = coef_scratch_[1];
  auto coef = [&](double tau, Part part) -> const StepCoef& {
    if (tau == ch.dt && (ch.part == Part::Both || ch.part == part)) return ch;
    law_.coef(tau, scratch, part);
    return scratch;
  };
  double tmp[kMaxBranches + 1];
  const double u0 = depth(x, q.d), rate0 = q.r - lift(x, w); // at the sub-step's start
  // the force's (gap's) rounding: of G0 u (u) over the sub-step
  const double scale = std::max(std::abs(u0), std::abs(depth(x + w * h, q.at(h))));
  if (contact) {
    const Forcing u = forcing(x, w, h, q);
    auto f = [&](double tau, double& v, double& dv) {
      law_.contact_step(y, tmp, u.h0, u.h1, u.h2, coef(tau, Part::Contact));
      const double xn = x + w * tau, un = depth(xn, q.at(tau)), du = q.rate(tau) - lift(xn, w);
      v = law_.pressure(un, du, tmp);
      dv = law_.pressure_rate(un, du, 2.0 * u.h2, tmp);
    };
    const double noise = kSwitchTol * (law_.G0() * scale + law_.G() * law_.tau() * std::abs(rate0));
    return switch_time(f, law_.pressure(u0, rate0, y), law_.pressure_rate(u0, rate0, 2.0 * u.h2, y),
                       h, noise);
  }
  auto f = [&](double tau, double& v, double& dv) {
    law_.free_step(y, tmp, coef(tau, Part::Free));
    const double xn = x + w * tau;
    v = law_.free_u(tmp) - depth(xn, q.at(tau));
    dv = law_.free_rate(tmp) - (q.rate(tau) - lift(xn, w));
  };
  return switch_time(f, law_.free_u(y) - u0, law_.free_rate(y) - rate0, h, kSwitchTol * scale);
}

double Row::pressure_at(const double* q, double x) const {
  return law_.pressure(depth(x), dd_ - lift(x, w_), q);
}

double Row::node_p(long long j) const {
  const std::size_t sl = slot(j);
  if (p_gen_[sl] == state_gen_) return p_end_[sl];
  return pressure_at(&y_[sl * stride_], xi(j));
}

// What the edge search sees of material in mode md, state y, at x: s = p/G0
// in contact (> 0), the gap h - u free (< 0; fresh: h).
double Row::edge_sign(Mode md, const double* y, double x) const {
  if (md == Mode::Contact) return std::max(pressure_at(y, x), 0.0) / law_.G0() + 1e-300;
  return std::min(md == Mode::Fresh ? depth(x) : depth(x) - law_.free_u(y), -1e-300);
}

// The edge after node jb predicted from one side: the zero in (0, 1) of the
// cubic through four nodes, jb-3..jb in contact (their forces) or jb+1..jb+4
// free (their gaps), else NaN. The force of material in contact is smooth up
// to an edge where it lets go, the gap of free material up to an edge where it
// touches again once its fast branches have relaxed (layers as thin as
// v tau_k trail a point that has just let go): each predicts its own kind to
// O(dx^4).
double Row::predicted_edge(long long jb, bool contact) const {
  const long long j0 = contact ? jb - 3 : jb + 1;
  if (j0 < jlo_ || j0 + 3 > jhi_) return std::nan("");
  double f[4];
  for (int i = 0; i < 4; ++i) {
    const std::size_t sl = slot(j0 + i);
    if (mode_[sl] != (contact ? Mode::Contact : Mode::Free)) return std::nan("");
    const double x = xi(j0 + i);
    f[i] = contact ? node_p(j0 + i) : depth(x) - law_.free_u(&y_[sl * stride_]);
  }
  // the cubic through (t0 + i, f[i]) in powers of u = t - t0 (Horner)
  const double c0 = f[0], c1 = (-11.0 * f[0] + 18.0 * f[1] - 9.0 * f[2] + 2.0 * f[3]) / 6.0,
               c2 = (2.0 * f[0] - 5.0 * f[1] + 4.0 * f[2] - f[3]) / 2.0,
               c3 = (-f[0] + 3.0 * f[1] - 3.0 * f[2] + f[3]) / 6.0;
  const double t0 = static_cast<double>(j0 - jb);
  auto cubic = [&](double t) {
    const double u = t - t0;
    return ((c3 * u + c2) * u + c1) * u + c0;
  };
  if (!(cubic(0.0) >= 0.0 && cubic(1.0) < 0.0)) return std::nan("");
  return numerics::newton_in_bracket(
      [&](double t, double& v, double& dv) {
        const double u = t - t0;
        v = cubic(t);
        dv = (3.0 * c3 * u + 2.0 * c2) * u + c1;
      },
      cubic(0.0), 1.0);
}

// The trailing edge of a contact run ending at node jb: the end of the
// contact among the material points between node jb and the next one, each
// replayed: the root of s (edge_sign) to edge_tol. Each side's prediction is
// tried by two replayed points tol apart around it (on a lattice of spacing tol: the
// points recur from trial to trial and step to step while the edge stays
// near, and their replays continue from the cache); else TOMS 748 on the
// bracket left (bisection where s jumps, superlinear where it is smooth). pe:
// the force of the outermost point found in contact.
double Row::trailing_edge(long long jb, double& pe, Edge edge) const {
  const double xb = xi(jb), a1 = a1_now();
  pe = node_p(jb);
  if (jb + 1 > jhi_) return std::min(xb + 0.5 * dx_, a1); // (contact past a1: never)
  const std::size_t next = slot(jb + 1);
  const double s1 = edge_sign(mode_[next], &y_[next * stride_], xb + dx_);
  if (!(s1 < 0.0)) return std::min(xb + dx_, a1); // (the next node is in contact: never)
  double e = 0.0;
  if (edge == Edge::Predicted && predicted_only(jb, e, pe)) return std::min(e, a1);
  double best = 0.0;
  auto s = [&](double frac) {
    const Material mt = replay(static_cast<long double>(jb) + static_cast<long double>(frac));
    const double x = xb + frac * dx_, v = edge_sign(mt.mode, mt.y, x);
    if (v > 0.0 && frac >= best) {
      best = frac;
      pe = pressure_at(mt.y, x);
    }
    return v;
  };
  const double tol = edge_tol_ * a1 / dx_;
  double lo = 0.0, hi = 1.0, slo = std::max(node_p(jb), 0.0) / law_.G0() + 1e-300, shi = s1;
  if (!smooth_ && xb < 0.0 && xb + dx_ > 0.0) { // the tip inside the edge cell
    const double p_left = tip_pressure(jb, -1), p_right = past_tip(p_left);
    if (!(p_right > 0.0)) { // the pressure turns negative across the tip: the rear face is free
      pe = std::max(p_left, 0.0);
      return 0.0;
    }
    lo = -xb / dx_; // in contact past the tip: the edge lies behind it
    slo = p_right / law_.G0() + 1e-300;
  }
  // Where the free gaps' prediction lies cells of tol before the contact
  // forces' (at a re-touch front at rest the force rises from 0 over a layer
  // behind it, and its cubic overshoots), the free one is tried first: it
  // was the edge at 1017 of the slide-hold-slide's 1021 such edges, and the
  // contact's cell beyond cost two new replayed points each time. Where the
  // contact is one interval near its end, either order replays the same
  // points up to a confirmation and leaves the same bracket without one (the
  // cells apart: neither's bounds fall inside the other's). (Not NaN.)
  const double tc_contact = predicted_edge(jb, true), tc_free = predicted_edge(jb, false);
  const bool free_first = std::floor(tc_free / tol) + 1.0 < std::floor(tc_contact / tol);
  for (const bool contact : {!free_first, free_first}) {
    const double tc = contact ? tc_contact : tc_free;
    const double a = std::floor(tc / tol) * tol, b = a + tol;
    if (!(a >= lo && b <= hi)) continue; // (also NaN)
    const double sa = a > lo ? s(a) : slo, sb = b < hi ? s(b) : shi;
    if (sa > 0.0 && sb < 0.0) { // (a <= tc < b)
      if (contact) pe = 0.0;    // where the cubic of the forces vanishes (else at a)
      return std::min(xb + tc * dx_, a1);
    }
    if (sa < 0.0)
      std::tie(hi, shi) = std::make_pair(a, sa);
    else
      std::tie(lo, slo) = std::make_pair(b, sb);
  }
  const numerics::Bracket r =
      numerics::toms748(s, lo, hi, slo, shi, numerics::WidthTolerance{tol}, {"row: edge"});
  pe = std::max(0.0, pe);
  return std::min(xb + r.lo * dx_, a1);
}

// The edge after node jb where the contact forces alone predict it, without
// a replay: the zero of their cubic, pe = 0 (where that is the edge, the
// confirmed search returns the same); false where they predict none or the
// tip lies in the cell. (The free gaps' prediction is not taken: the force
// at a re-touch front comes from a replayed point.)
bool Row::predicted_only(long long jb, double& e, double& pe) const {
  const double xb = xi(jb);
  if (!smooth_ && xb < 0.0 && xb + dx_ > 0.0) return false;
  const double tc = predicted_edge(jb, true);
  if (!(tc >= 0.0 && tc <= 1.0)) return false;
  e = xb + tc * dx_;
  pe = 0.0;
  return true;
}

// The contact forcing of a sub-step of h from x: the parabola's Taylor form
// (exact), a cone's or n = 2's on the sub-step's side of the tip (exact),
// else the quadratic through u at 0, h/2 and h.
Row::Forcing Row::forcing(double x, double w, double h, const Path& q) const {
  return shape([&](const auto& i) { return i.template forcing<Forcing>(x, w, h, q); });
}

// The end of a sub-step from t to tn of a point at x0 + w t: tn, or the time
// it passes the tip where that lies inside (not within rounding of an end).
double Row::next_cut(double x0, double t, double tn, double w) const {
  if (!(w > 0.0)) return tn;
  const double tip = -x0 / w, margin = 1e-9 * (tn - t);
  return tip > t + margin && tip < tn - margin ? tip : tn;
}

double Row::sub_length(double a) const {
  const double s = sub_travel_ * a;
  return exact_force_ ? s : std::min(s, kSubCells * dx_);
}

} // namespace mdrmap::spectrum
