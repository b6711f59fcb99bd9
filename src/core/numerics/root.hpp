#pragma once
// The core's one bracketed scalar root finder (docs/design.md, "Numerics
// floor"): TOMS 748 (Boost's toms748_solve) on a bracket whose end values are
// known, with a stopping rule and an evaluation cap of the caller's; a bracket
// that is not one (values of one sign, or not finite) throws NoBracket naming
// the search, never Boost's own message; the evaluations are charged to the
// case's RunControl when one is given. Two ways to the bracket of an
// increasing function: scaled_bracket (halving and doubling from a start),
// increasing_root (secant steps, widened, then the root).
#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "core/numerics/run_control.hpp"

namespace mdrmap::numerics {

/// The ends of a root search do not bracket a root (their values have one
/// sign or are not finite): the case cannot be computed (CaseAbandoned).
class NoBracket : public CaseAbandoned {
public:
  using CaseAbandoned::CaseAbandoned;
};

/// Stop once the bracket's ends agree to `bits` binary digits.
inline boost::math::tools::eps_tolerance<double> bits_tolerance(int bits) {
  return boost::math::tools::eps_tolerance<double>(static_cast<unsigned>(bits));
}

/// Stop once the bracket is at most `width` wide.
struct WidthTolerance {
  double width;
  bool operator()(double lo, double hi) const { return hi - lo <= width; }
};

/// What a search is called (in NoBracket's message and the work charge), how
/// many evaluations it may make, and who pays for them: `units` work units per
/// evaluation to `control` (nullptr: nobody, e.g. a metric without a case run,
/// or a caller that charges the whole search itself).
struct RootSearch {
  const char* what;
  std::uintmax_t max_evaluations = 200;
  const RunControl* control = nullptr;
  double units = 1.0;
};

/// The final bracket [lo, hi] and the evaluations spent (Boost's count).
struct Bracket {
  double lo, hi;
  std::uintmax_t evaluations;
  double mid() const { return 0.5 * (lo + hi); }
  double width() const { return hi - lo; }
};

namespace detail {
inline std::string number(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", x);
  return s;
}
} // namespace detail

/// Root of f on [a, b] (a < b) with f(a) = fa and f(b) = fb of opposite signs
/// or zero (a zero end is the root), to tolerance `tol` (bits_tolerance,
/// WidthTolerance or any Boost-style tol(lo, hi)). The cap ends a search early
/// with the bracket it has (Boost's rule).
template <class F, class Tol>
Bracket toms748(F&& f, double a, double b, double fa, double fb, Tol tol, const RootSearch& s) {
  if (!std::isfinite(fa) || !std::isfinite(fb) || (fa > 0.0 && fb > 0.0) || (fa < 0.0 && fb < 0.0))
    throw NoBracket(std::string(s.what) + ": the root search's ends do not bracket a root (f(" +
                    detail::number(a) + ") = " + detail::number(fa) + ", f(" + detail::number(b) +
                    ") = " + detail::number(fb) + ")");
  std::uintmax_t n = s.max_evaluations;
  const auto r = boost::math::tools::toms748_solve(f, a, b, fa, fb, tol, n);
  if (s.control != nullptr) s.control->charge(s.units * static_cast<double>(n), s.what);
  return {r.first, r.second, n};
}

/// The same with the end values evaluated here (two of the evaluations: as
/// Boost's toms748_solve without them).
template <class F, class Tol>
Bracket toms748(F&& f, double a, double b, Tol tol, const RootSearch& s) {
  if (s.max_evaluations <= 2) return {a, b, s.max_evaluations};
  RootSearch inner = s;
  inner.max_evaluations -= 2;
  const double fa = f(a), fb = f(b);
  Bracket r = toms748(f, a, b, fa, fb, tol, inner);
  r.evaluations += 2;
  if (s.control != nullptr) s.control->charge(2.0 * s.units, s.what);
  return r;
}

/// A bracket of an increasing f from x0 > 0 by scaling: lo halved while
/// f(lo) > 0, hi doubled while f(hi) < 0, or moved halfway to `most` where
/// that is nearer (at most max_steps times each, from lo = hi = x0), with the
/// values there. It brackets unless a bound stopped a loop or f is NaN: the
/// caller checks flo <= 0 <= fhi.
struct ScaledBracket {
  double lo, hi, flo, fhi;
};
template <class F>
ScaledBracket scaled_bracket(F&& f, double x0, int max_steps,
                             double most = std::numeric_limits<double>::infinity()) {
  ScaledBracket e{x0, x0, f(x0), 0.0};
  e.fhi = e.flo;
  for (int i = 0; i < max_steps && e.flo > 0.0; ++i)
    e.flo = f(e.lo *= 0.5);
  for (int i = 0; i < max_steps && e.fhi < 0.0; ++i)
    e.fhi = f(e.hi = std::fmin(2.0 * e.hi, 0.5 * (e.hi + most)));
  return e;
}

/// The root of an increasing f: scaled_bracket from x0 (max_steps), then
/// toms748 (x0 itself where f(x0) = 0 or is NaN).
template <class F, class Tol>
double scaled_root(F&& f, double x0, int max_steps, Tol tol, const RootSearch& s,
                   double most = std::numeric_limits<double>::infinity()) {
  const ScaledBracket e = scaled_bracket(f, x0, max_steps, most);
  if (e.lo == e.hi) return e.lo;
  return toms748(f, e.lo, e.hi, e.flo, e.fhi, tol, s).mid();
}

/// Root of an increasing f from x0: a secant step with the expected slope k
/// (> 0) past the root, widened (times 4) until it brackets (at most 60
/// widenings, else NoBracket), then TOMS 748 to width `width`; lo_limit bounds
/// the search below (each step goes at most halfway to it). k receives the
/// slope of the final bracket (the next call's guess).
template <class F>
double increasing_root(F&& f, double x0, double& k, double width, double lo_limit,
                       const RootSearch& s) {
  double a = x0, fa = f(x0);
  if (fa == 0.0) return x0;
  double step = -1.2 * fa / k, b = a, fb = fa;
  for (int n = 0; fa * fb > 0.0; ++n) {
    if (n > 60 || !std::isfinite(step))
      throw NoBracket(std::string(s.what) + ": no root near " + detail::number(x0));
    a = b;
    fa = fb;
    b = std::max(a + step, 0.5 * (a + lo_limit));
    fb = f(b);
    step *= 4.0;
  }
  if (fb == 0.0) return b;
  if (a > b) {
    std::swap(a, b);
    std::swap(fa, fb);
  }
  const Bracket r = toms748(f, a, b, fa, fb, WidthTolerance{width}, s);
  if (fb > fa) k = (fb - fa) / (b - a);
  return r.mid();
}

/// What newton_in_bracket returns: the last point it evaluated f at (a
/// caller whose f forms state at t finds it formed there), or its next
/// Newton point (one more step: the root to the last ulps).
enum class NewtonEnd { Evaluated, Next };

/// Root in (0, h) of f with f(0) = f0 > 0 > f(h) (else 0 where f0 <= 0, h
/// where f(h) >= 0): Newton from start(f(h), f'(h)) (the secant's point where
/// that is not inside), kept inside the bracket (bisection where a step would
/// leave it or the slope is not negative), until f is within `noise` below
/// zero (0: at zero exactly) or a step is within 4 ulps of h. f(t, v, dv)
/// gives the value and its slope.
template <class F, class Start>
double newton_in_bracket(F&& f, double f0, double h, Start&& start, double noise, NewtonEnd end) {
  if (!(f0 > 0.0)) return 0.0;
  double v = 0.0, dv = 0.0;
  f(h, v, dv);
  if (!(v < 0.0)) return h;
  double lo = 0.0, hi = h, t = start(v, dv);
  if (!(t > 0.0 && t < h)) t = h * f0 / (f0 - v);
  const double tiny = 4.0 * std::numeric_limits<double>::epsilon() * h;
  const bool next = end == NewtonEnd::Next;
  for (int it = 0; it < 100; ++it) {
    f(t, v, dv);
    if (v <= 0.0 && v >= -noise) return t;
    (v > 0.0 ? lo : hi) = t;
    double tn = dv < 0.0 ? t - v / dv : 0.5 * (lo + hi);
    // (a converged step first: at the root it may round onto the bracket's end)
    if (!next && std::abs(tn - t) <= tiny) return t;
    if (!(tn > lo && tn < hi)) tn = 0.5 * (lo + hi);
    if (std::abs(tn - t) <= tiny || hi - lo <= tiny) return next ? tn : t;
    t = tn;
  }
  return next ? 0.5 * (lo + hi) : t;
}

/// The same from the secant's point, to f = 0, its next Newton point.
template <class F> double newton_in_bracket(F&& f, double f0, double h) {
  return newton_in_bracket(
      f, f0, h, [](double, double) { return -1.0; }, 0.0, NewtonEnd::Next);
}

} // namespace mdrmap::numerics
