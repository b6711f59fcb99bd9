#include "core/solvers/load_row.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "core/metrics/load_stationary.hpp"
#include "core/numerics/phi.hpp"
#include "core/numerics/root.hpp"

namespace mdrmap {
namespace {

constexpr double kNoMemory = -std::numeric_limits<double>::infinity(); // ln 0: fresh material
constexpr long long kNoElement = std::numeric_limits<long long>::min();
constexpr double kRootWork = 16.0; // work units of one evaluation of the edge

/// phi(x) = 1 - (1 - exp(-x)) / x = x phi_2(x) (numerics/phi.hpp), the weight
/// of D's change over a step of x = h / tau.
double phi(double x) {
  return x * numerics::phi(2, x);
}

// Root of f on [lo, hi] with f(lo) and f(hi) of opposite signs.
template <class F> double bracketed_root(F f, double lo, double hi, double flo, double fhi) {
  if (flo == 0.0) return lo;
  if (fhi == 0.0) return hi;
  // (charged by the caller, with the walk: kRootWork)
  return numerics::toms748(f, lo, hi, flo, fhi, numerics::bits_tolerance(50),
                           {"kelvin_load: front"})
      .mid();
}

} // namespace

LoadRow::LoadRow(const Case& c, double dx, double A, double phase, const RunControl& control)
    : c_(c), control_(control), R_(c.indenter.as<Parabola>().R), G_(c.rheology.G),
      tau_(c.rheology.tau), F0_(c.loading.F0), a0_(c.a0()), dx_(dx), A_(A), phase_(phase) {
  if (!(tau_ > 0.0)) throw std::invalid_argument("LoadRow: tau must be > 0 (tau = 0 is Hertz)");
  cap_ = static_cast<std::size_t>(std::ceil(2.0 * A / dx)) + 8;
  lnU_.assign(cap_, kNoMemory);
  tag_.assign(cap_, kNoElement);
}

double LoadRow::a1() const {
  return std::sqrt(R_ * d_);
}

LoadRow::Frame LoadRow::frame_at(double h) const {
  const long double P = P_ + static_cast<long double>(w_ * h / dx_);
  const long double fl = std::floor(P);
  return Frame{static_cast<long long>(fl), static_cast<double>(P - fl)};
}

double LoadRow::xi(const Frame& f, long long j) const {
  return (static_cast<double>(j + f.m) + f.th + phase_) * dx_;
}

long long LoadRow::first_beyond(const Frame& f, double x) const {
  long long j = static_cast<long long>(std::floor(x / dx_ - f.th - phase_)) - f.m;
  while (xi(f, j) > x)
    --j;
  while (xi(f, j) <= x)
    ++j;
  return j;
}

long long LoadRow::jlo(const Frame& f) const {
  return static_cast<long long>(std::ceil(-A_ / dx_ - f.th - phase_)) - f.m;
}
long long LoadRow::jhi(const Frame& f) const {
  return static_cast<long long>(std::floor(A_ / dx_ - f.th - phase_)) - f.m;
}

std::size_t LoadRow::slot(long long j) const {
  const auto c = static_cast<long long>(cap_);
  return static_cast<std::size_t>(((j % c) + c) % c);
}

double LoadRow::ln_u_at(long long j, double t) const {
  const std::size_t s = slot(j);
  if (tag_[s] != j || lnU_[s] == kNoMemory) return kNoMemory;
  return lnU_[s] - (t - t_base_) / tau_;
}

double LoadRow::u_at(long long j, double t) const {
  const double v = ln_u_at(j, t);
  return v == kNoMemory ? 0.0 : std::exp(v);
}

void LoadRow::set_lnU(long long j, double v) {
  const std::size_t s = slot(j);
  if (logging_) log_.push_back(Undo{s, lnU_[s], tag_[s]});
  lnU_[s] = v;
  tag_[s] = j;
  ++updates_;
}

// The cap when the edge sits at it: (a + c)^2 (2c - a + 3L) = 4 a0^3, by
// Newton from above (the cubic is increasing and convex there).
double LoadRow::cap_joint(double a, double L) const {
  const double k = 4.0 * a0_ * a0_ * a0_;
  const double q = 3.0 * (L - a);
  double y = q >= 0.0 ? std::min(std::cbrt(2.0) * a0_, std::sqrt(k / std::max(q, 1e-300)))
                      : -0.5 * q + std::cbrt(2.0) * a0_;
  double c = y - a;
  for (int i = 0; i < 100; ++i) {
    const double s = c + a;
    const double f = s * s * (2.0 * c - a + 3.0 * L) - k;
    const double step = f / (6.0 * s * (c + L));
    c -= step;
    if (!(std::abs(step) > 4e-16 * std::max(std::abs(c), 1e-8 * a))) break;
  }
  return c;
}

double LoadRow::D_front(double a, double e, double L) const {
  return F0_ / (4.0 * G_ * (a + e)) + ((e * e - e * a + a * a) / 3.0 + L * (e - a)) / R_;
}

// Front between the last contact element and free element jf at t1, on
// [xb, min(xf, a1)]: the root of psi = d1 - g - u. ln u of the free material
// is interpolated linearly between the material of the previous edge (it had
// psi = 0 there at t0, so u = h0(e0) decayed by E: exact data, carried with
// the material to xe) and element jf: exact for material that left at the cap
// (ln u linear), second order elsewhere. Without that point (an edge at a1),
// quadratically through jf, jf+1, jf+2. xb if the gap does not open.
double LoadRow::front_root(const Frame& f1, long long jf, double d1, double t1, double xb,
                           double xe, double lue) const {
  const double a = std::sqrt(R_ * d1);
  const double xf = xi(f1, jf);
  double x[3], l[3];
  int n = 0;
  if (lue != kNoMemory && xe < xf) {
    x[n] = xe;
    l[n++] = lue;
  }
  for (int i = 0; n < (lue != kNoMemory ? 2 : 3) && jf + i <= jhi(f1); ++i) {
    // (ln u from the stored logarithm: a steep tail stays exact where u underflows)
    const double lu = ln_u_at(jf + i, t1);
    if (lu == kNoMemory) break;
    x[n] = xi(f1, jf + i);
    l[n++] = lu;
  }
  auto lnu = [&](double y) {
    if (n == 0) return kNoMemory;
    if (n == 1) return l[0];
    const double s01 = (l[1] - l[0]) / (x[1] - x[0]);
    double v = l[0] + s01 * (y - x[0]);
    if (n == 3) {
      const double s12 = (l[2] - l[1]) / (x[2] - x[1]);
      v += (s12 - s01) / (x[2] - x[0]) * (y - x[0]) * (y - x[1]);
    }
    return v;
  };
  auto psi = [&](double y) { return (a - y) * (a + y) / R_ - std::exp(lnu(y)); };
  const double xr = std::min(xf, a); // psi(a) = -u <= 0
  const double plo = psi(xb), phi_ = psi(xr);
  if (!(plo > 0.0)) return xb;
  if (!(phi_ < 0.0)) return xr;
  return bracketed_root(psi, xb, xr, plo, phi_);
}

// The edge and D at the end of a step h if the depth there is d1.
LoadRow::Edge LoadRow::edge_at(double d1, double h, const Frame& f1) const {
  const double a = std::sqrt(R_ * d1), t1 = t_ + h, L = w_ * tau_;
  // walk outward over the free elements of t0 that touched by t1
  const long long j0 = first_beyond(f_, e_);
  long long j = j0;
  const long long top = jhi(f1);
  double front = a;
  const double a0e = a1(), he = (a0e - e_) * (a0e + e_) / R_; // u of the edge material at t0
  const double lue = he > 0.0 ? std::log(he) - h / tau_ : kNoMemory;
  while (j <= top) {
    const double x = xi(f1, j);
    const double psi = (a - x) * (a + x) / R_ - u_at(j, t1);
    if (x >= a || !(psi >= 0.0)) { // (beyond a1 psi < 0: the front lies before a1)
      // free material begins at the previous front carried with the material
      // (in material coordinates the front never moves back), or at the last
      // element that touched
      const double xb = std::min(std::max(xi(f1, j - 1), e_ + w_ * h), std::min(x, a));
      front = front_root(f1, j, d1, t1, xb, e_ + w_ * h, lue);
      break;
    }
    ++j;
  }
  // (a root evaluation: the walk, the front's bracketed root and the cap's
  // Newton iteration, about 16 element updates' worth)
  control_.charge(static_cast<double>(j - j0) + kRootWork, "kelvin_load");
  front = std::min(front, a);
  const double cap = cap_joint(a, L);
  if (front < cap) return Edge{front, D_front(a, front, L)};
  return Edge{cap, cap * (cap + 2.0 * L) / R_};
}

// -dD/dd at the row's state (>= 0). At the cap D = c (c + 2L) / R with
// (a + c)^2 (2c - a + 3L) = 4 a0^3, so dD/dd = -(c - a + 2L) / (2a); at a
// front (held) dD/da = -F0 / (4G (a + e)^2) + ((2a - e)/3 - L) / R, and
// da/dd = R / (2a).
// Only the order of magnitude matters (any k >= 0 keeps the scheme second
// order; a k near the true slope makes the coupling weak).
double LoadRow::stiffness() const {
  const double a = a1(), L = w_ * tau_, e = e_;
  if (!(a > 0.0)) return 0.0;
  double k = 0.0;
  if (e >= cap_joint(a, L) * (1.0 - 1e-12))
    k = (e - a + 2.0 * L) / (2.0 * a);
  else
    k = (F0_ / (4.0 * G_ * (a + e) * (a + e)) - ((2.0 * a - e) / 3.0 - L) / R_) * R_ / (2.0 * a);
  return std::isfinite(k) ? std::max(k, 0.0) : 0.0;
}

LoadRow::Trial LoadRow::trial(double h, double h_gate) const {
  // (where the plain coupling still damps the mode, k h / tau <= 10, it is
  // used, k = 0: its error constant is the smaller one)
  const double ks = stiffness(), k = ks * (h_gate / tau_) > 10.0 ? ks : 0.0, l = 1.0 + k;
  const double x = l * (h / tau_);
  const double E = std::exp(-x), omE = -std::expm1(-x), ph = phi(x);
  const Frame f1 = frame_at(h);
  const double Dk0 = D_ + k * d_;
  const double base = d_ * E + Dk0 / l * omE;
  auto r = [&](double d1) { return d1 - (base + (edge_at(d1, h, f1).D + k * d1 - Dk0) / l * ph); };
  // r is strictly increasing in d1: bracket around the explicit guess
  // (D, hence base, may be negative while the depth falls fast: start from d)
  double lo = base > 0.0 ? base : 0.5 * d_, hi = lo;
  double rlo = r(lo), rhi = rlo;
  for (double s = 1e-6; rlo > 0.0 && s < 1e300; s *= 4.0) {
    hi = lo, rhi = rlo;
    lo = hi / (1.0 + s);
    rlo = r(lo);
  }
  for (double s = 1e-6; rhi < 0.0 && s < 1e300; s *= 4.0) {
    lo = hi, rlo = rhi;
    hi = lo * (1.0 + s);
    rhi = r(hi);
  }
  Trial tr;
  tr.h = h;
  tr.k = k;
  tr.t_end = t_ + h;
  if (!(rlo <= 0.0 && rhi >= 0.0 && lo > 0.0)) {
    // no positive depth balances the load over this step (the depth would
    // fall through 0: the step is far too long): a trial that does not fit
    tr.d = tr.D = tr.e = std::numeric_limits<double>::quiet_NaN();
    return tr;
  }
  tr.d = bracketed_root(r, lo, hi, rlo, rhi);
  const Edge ed = edge_at(tr.d, h, f1);
  tr.D = ed.D;
  tr.e = ed.e;
  return tr;
}

// Depth a fraction theta into a trial step (the same exponential formula).
double LoadRow::depth_within(double theta, const Trial& tr) const {
  const double l = 1.0 + tr.k, x = l * (theta * tr.h / tau_);
  const double Dk0 = D_ + tr.k * d_, Dk1 = tr.D + tr.k * tr.d;
  return d_ * std::exp(-x) - Dk0 / l * std::expm1(-x) + (Dk1 - Dk0) / l * theta * phi(x);
}

// Elements in contact at t0 that lie beyond the new edge at t1 left it where
// they crossed the edge (edge linear in time over the step) with u = d - g
// there (p = 0 at the cap), and relaxed freely since.
void LoadRow::detach(const Trial& tr, const Frame& f1) {
  const double move = w_ * tr.h, de = tr.e - e_;
  // (material ahead of the contact at t0 that is beyond the edge at t1 went
  // through the whole contact during the step: it left at the edge too)
  const long long top = std::min(first_beyond(f_, e_) - 1, jhi(f1));
  long long j = top;
  for (; j >= jlo(f1); --j) {
    const double x1 = xi(f1, j);
    const double x0 = xi(f_, j);
    if (x1 <= tr.e) break;
    const double rel = move - de; // closing speed of element and edge over the step
    const double theta = rel > 0.0 ? std::clamp((e_ - x0) / rel, 0.0, 1.0) : 0.0;
    const double xc = x0 + theta * move;
    const double dc = depth_within(theta, tr);
    const double ac = std::sqrt(R_ * dc);
    const double u = (ac - xc) * (ac + xc) / R_;
    const double tc = t_ + theta * tr.h;
    set_lnU(j, u > 0.0 ? std::log(u) + (tc - t_base_) / tau_ : kNoMemory);
  }
  control_.charge(static_cast<double>(top - j + 1), "kelvin_load");
}

bool LoadRow::fits(const Trial& tr) const {
  return std::isfinite(tr.d) && std::sqrt(R_ * tr.d) <= A_ - 3.0 * dx_;
}

bool LoadRow::at_window_edge() const {
  return a1() > A_ - 3.5 * dx_;
}

void LoadRow::commit(const Trial& tr) {
  if (!std::isfinite(tr.d))
    throw std::runtime_error("kelvin_load: no depth balances the load over a step of " +
                             format_number(tr.h) + " (fixed steps too long)");
  const Frame f1 = frame_at(tr.h);
  detach(tr, f1);
  P_ += static_cast<long double>(w_ * tr.h / dx_);
  f_ = f1;
  t_ = tr.t_end;
  d_ = tr.d;
  D_ = tr.D;
  e_ = tr.e;
  const double a = a1(), L = w_ * tau_;
  checks_.max_a1_over_a0 = std::max(checks_.max_a1_over_a0, a / a0_);
  if (!(a <= A_ - 3.0 * dx_))
    throw WindowExceeded("kelvin_load: the leading edge a1 = " + format_number(a) +
                         " left the element window (" + format_number(A_) + ")");
  // p(-a1) / 4G = D - d + 2 L a1 / R: the leading edge stays attached while >= 0
  if ((D_ - d_) + 2.0 * L * a / R_ < -1e-12 * d_) ++checks_.leading_edge_detached;
}

void LoadRow::checkpoint() {
  saved_ = Saved{f_, P_, t_, d_, D_, e_, updates_};
  log_.clear();
  logging_ = true;
}

void LoadRow::rollback() {
  for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
    lnU_[it->slot] = it->lnU;
    tag_[it->slot] = it->tag;
  }
  f_ = saved_.f;
  P_ = saved_.P;
  t_ = saved_.t;
  d_ = saved_.d;
  D_ = saved_.D;
  e_ = saved_.e;
  log_.clear();
  logging_ = false;
}

void LoadRow::release() {
  log_.clear();
  logging_ = false;
}

void LoadRow::rebase_time() {
  if (logging_) return;
  // the travel counter: whole ring lengths renumber the elements, keep the slots
  const auto ring = static_cast<long long>(cap_);
  if (std::llabs(f_.m) > (1LL << 24)) {
    const long long K = (f_.m / ring) * ring;
    P_ -= static_cast<long double>(K);
    f_.m -= K;
    for (long long& g : tag_) // ids j = k - m grow by K (same slots)
      if (g != kNoElement) g += K;
  }
  const double s = (t_ - t_base_) / tau_;
  if (s < 512.0) return;
  control_.charge(static_cast<double>(cap_), "kelvin_load");
  for (double& v : lnU_)
    if (v != kNoMemory) v -= s;
  t_base_ = t_;
}

// The clock then reads 0. Within 512 tau of the base the base moves along
// (t - t_base is kept, nothing is rewritten: a short segment costs O(1));
// beyond, the stored logarithms are rebased to the current instant.
void LoadRow::restart_clock() {
  const double s = (t_ - t_base_) / tau_;
  if (s < 512.0) {
    t_base_ -= t_;
    t_ = 0.0;
    return;
  }
  control_.charge(static_cast<double>(cap_), "kelvin_load");
  for (double& v : lnU_)
    if (v != kNoMemory) v -= s; // (-inf after a hold of ~1e308 tau: u = 0, as it is)
  t_ = t_base_ = 0.0;
}

void LoadRow::start_stationary(double w) {
  control_.charge(static_cast<double>(cap_), "kelvin_load");
  w_ = w;
  d_ = stationary_depth(c_, w);
  D_ = d_;
  const double a = a1(), L = w * tau_;
  e_ = a * (a / (std::hypot(L, a) + L)); // a2(w), eq. (7) without cancellation
  // the free tail: left at the cap with u = h(a2), relaxed while carried at w
  const double h2 = (a - e_) * (a + e_) / R_;
  for (long long j = jlo(f_); j <= jhi(f_); ++j) {
    const double x = xi(f_, j);
    lnU_[slot(j)] = (x > e_ && h2 > 0.0) ? std::log(h2) - (x - e_) / L : kNoMemory;
    tag_[slot(j)] = j;
  }
  checks_.max_a1_over_a0 = a / a0_;
}

void LoadRow::start_rest() {
  w_ = 0.0;
  d_ = a0_ * (a0_ / R_);
  D_ = d_;
  e_ = a0_;
  std::fill(lnU_.begin(), lnU_.end(), kNoMemory);
  std::fill(tag_.begin(), tag_.end(), kNoElement);
  checks_.max_a1_over_a0 = 1.0;
}

void LoadRow::start_undeformed(double d_rel) {
  w_ = 0.0;
  d_ = d_rel * a0_ * (a0_ / R_);
  e_ = a1();
  D_ = D_front(e_, e_, 0.0);
  std::fill(lnU_.begin(), lnU_.end(), kNoMemory);
  std::fill(tag_.begin(), tag_.end(), kNoElement);
  checks_.max_a1_over_a0 = e_ / a0_;
}

void LoadRow::note_piece(double width) {
  if (!(width > 0.0)) return;
  if (width >= piece_floor_) min_piece_ = std::min(min_piece_, width);
  if (width < piece_resolved_) max_unresolved_ = std::max(max_unresolved_, width);
}

void LoadRow::change_velocity(double w) {
  if (w_ > 0.0 && t_ > 0.0) note_piece(w_ * t_); // what left the contact in the segment
  restart_clock();
  w_ = w;
  const double a = a1(), L = w * tau_;
  const double cap = cap_joint(a, L);
  if (e_ <= cap) { // the contact stays; its elements now move at w
    D_ = D_front(a, e_, L);
    return;
  }
  // the contact beyond the new cap lets go at once: u = d - g there
  for (long long j = first_beyond(f_, cap); j <= jhi(f_); ++j) {
    const double x = xi(f_, j);
    if (x > e_) break;
    const double u = (a - x) * (a + x) / R_;
    set_lnU(j, u > 0.0 ? std::log(u) + (t_ - t_base_) / tau_ : kNoMemory);
  }
  note_piece(e_ - cap);
  e_ = cap;
  D_ = cap * (cap + 2.0 * L) / R_;
}

// Forces of the contact [-a1, e] with p = 4G (D - g - L g'), D = d + delta:
//   F_N = 4G/R [ (a + e)^2 (2a - e)/3 + L (a^2 - e^2) + R delta (a + e) ],
//   F_x = 4G/R [ (a^2 - e^2) ((a^2 - e^2)/(2R) + delta) + 4 L (a^3 + e^3)/(3R) ].
State LoadRow::measure() const {
  const double a = a1(), e = e_, L = w_ * tau_, delta = D_ - d_;
  const double y = a + e, diff2 = (a - e) * y;
  State st;
  st.FN = 4.0 * G_ / R_ * (y * y * (2.0 * a - e) / 3.0 + L * diff2 + R_ * delta * y);
  st.Fx = 4.0 * G_ / R_ *
          (diff2 * (diff2 / (2.0 * R_) + delta) + 4.0 * L * (a * a * a + e * e * e) / (3.0 * R_));
  st.mu = st.Fx / st.FN;
  st.a2 = e;
  st.d = d_;
  st.a1 = a;
  return st;
}

void LoadRow::check_one_interval() {
  const double a = a1();
  long long j = first_beyond(f_, e_);
  bool gap_seen = false;
  for (; j <= jhi(f_); ++j) {
    const double x = xi(f_, j);
    if (x >= a) break;
    const double psi = (a - x) * (a + x) / R_ - u_at(j, t_);
    if (psi < 0.0) gap_seen = true;
    if (gap_seen && psi > 1e-9 * d_) {
      ++checks_.second_contact;
      break;
    }
  }
  control_.charge(static_cast<double>(j - first_beyond(f_, e_) + 1), "kelvin_load");
}

} // namespace mdrmap
