#include "core/solvers/checked_case.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/metrics/analytic.hpp"
#include "core/metrics/load_stationary.hpp"
#include "core/metrics/profile_stationary.hpp"

namespace mdrmap {
namespace {

// The range of the contact radius (any length the contact forces are formed
// from): its powers up to a^4 stay normal doubles.
constexpr double kMinRadius = 1e-75, kMaxRadius = 1e75;
// The largest w tau and w tau a^3 the stationary formulas form (sums of a few
// of them must not overflow).
constexpr double kMaxProduct = 1e306;
// Forces below this have lost digits to underflow.
constexpr double kMinForce = 1e-290;

/// What makes the contact of radius a1 = sqrt(R d) at depth d sliding at w
/// unrepresentable ("" if nothing): its radius, the products w tau, w tau a1^3,
/// or the forces of its stationary state.
std::string contact_problem(const Case& at_depth, double w) {
  const double a = at_depth.a1(), L = w * at_depth.rheology.tau;
  if (!(a >= kMinRadius) || !(a <= kMaxRadius))
    return "a contact radius a1 = " + format_number(a) + ", outside [1e-75, 1e75]";
  if (!(L <= kMaxProduct) || !(L * a * a * a <= kMaxProduct))
    return "w tau = " + format_number(L) + " at a1 = " + format_number(a) +
           ": w tau or w tau a1^3 above 1e306 (an overflow)";
  const State st = at_depth.indenter.parabolic() ? analytic::stationary(at_depth, w)
                                                 : profile_stationary(at_depth, w);
  if (!std::isfinite(st.FN) || !std::isfinite(st.Fx) || !std::isfinite(st.mu) ||
      !(st.FN >= kMinForce))
    return "contact forces F_N = " + format_number(st.FN) + ", F_x = " + format_number(st.Fx) +
           " that are not representable";
  return "";
}

/// contact_problem of the stationary contact at w: of the case itself at
/// fixed depth (no copy), under load of the case at its stationary depth.
std::string stationary_contact_problem(const Case& c, double w) {
  if (!c.loading.by_force()) return contact_problem(c, w);
  const double d = c.indenter.parabolic() ? stationary_depth(c, w) : profile_stationary_depth(c, w);
  return contact_problem(at_depth(c, d), w);
}

/// The option a velocity of the history stands for: a segment's W is the
/// history's; v0 is blamed on tau (v0 tau / a is the same for any v0 and tau).
InvalidInput velocity_problem(const History& h, std::size_t k, const std::string& what) {
  if (k == 0) return InvalidInput("tau", "with v = " + format_number(h.v0) + " " + what);
  return InvalidInput("history", "segment " + std::to_string(k) +
                                     ": W = " + format_number(h.segments[k - 1].w) + " " + what);
}

// The velocities of the history (k = 0: v0, k >= 1: segment k): w tau / a
// representable for each, and the stationary contact at the fastest one
// (the largest forces, under load the smallest contact) too.
void check_velocities(const Case& c, double a) {
  const History& h = c.history;
  std::size_t fastest = 0;
  for (std::size_t k = 0; k <= h.size(); ++k) {
    const double w = k == 0 ? h.v0 : h.segments[k - 1].w;
    if (!std::isfinite(w * c.rheology.tau / a))
      throw velocity_problem(
          h, k, "makes w tau / a (a = " + format_number(a) + ") overflow; rescale the units");
    if (w > (fastest == 0 ? h.v0 : h.segments[fastest - 1].w)) fastest = k;
  }
  const double w = fastest == 0 ? h.v0 : h.segments[fastest - 1].w;
  if (const std::string p = stationary_contact_problem(c, w); !p.empty())
    throw velocity_problem(h, fastest, "gives " + p + "; rescale the units");
}

/// "with R gives a contact radius sqrt(R d) = " and the like: the words
/// before the contact radius of the case's loading and profile.
std::string contact_radius_words(const Case& c) {
  const bool load = c.loading.by_force();
  return c.indenter.visit([load](const auto& s) -> std::string {
    return load ? s.load_radius_words : s.depth_radius_words;
  });
}

// Derived scales must be representable: the contact radius a (a1 = sqrt(R d),
// or a0 under load) within [1e-75, 1e75], the force scale 16 G d^2 (d0 =
// a0^2 / R under load), w tau / a for every velocity of the history, and the
// stationary contact at rest and at the fastest velocity (radius, products,
// forces; see contact_problem).
void check_scales(const Case& c) {
  const bool load = c.loading.by_force();
  const char* opt = load ? "F0" : "d";
  const double a = c.edge_scale();
  const std::string radius = contact_radius_words(c);
  if (!(a > 0.0) || !std::isfinite(a))
    throw InvalidInput(opt,
                       radius + format_number(a) + " that is not representable; rescale the units");
  if (const double most = c.indenter.max_radius(); !(a < most))
    throw InvalidInput(opt, radius + format_number(a) + ", not below the profile's largest " +
                                format_number(most) + " (the sphere's radius); lower it");
  const double d = load ? c.indenter.g(a) : c.loading.d;
  const double force_scale = d * d * c.rheology.G * 16.0;
  if (!std::isfinite(force_scale))
    throw InvalidInput(opt, "with G gives a force scale 16 G d^2 = " + format_number(force_scale) +
                                " that is not representable; rescale the units");
  // forces far below it (mu F_N at small d/R) must not underflow to zero
  if (force_scale < 1e-280)
    throw InvalidInput(opt, "with G gives a force scale 16 G d^2 = " + format_number(force_scale) +
                                " that underflows (below 1e-280); rescale the units");
  if (!(a >= kMinRadius) || !(a <= kMaxRadius))
    throw InvalidInput(opt, radius + format_number(a) +
                                " outside [1e-75, 1e75], where its powers overflow or underflow; "
                                "rescale the units");
  if (const std::string p = stationary_contact_problem(c, 0.0); !p.empty())
    throw InvalidInput(opt, "gives at rest " + p + "; rescale the units");
  check_velocities(c, a);
}

/// The Kelvin case whose scales bound those of `c`: the glassy modulus G0
/// and the longest (shifted) time, so that its stationary forces are at least
/// the spectrum's. `c` itself (no copy) where it is Kelvin and unshifted.
const Case& kelvin_bound(const Case& c, Case& storage) {
  if (c.rheology.kelvin() && c.rheology.aT == 1.0) return c;
  storage = c;
  storage.rheology = Rheology{c.rheology.G0(), c.rheology.longest_time(), {}, 1.0};
  return storage;
}

} // namespace

void validate(const Case& c) {
  validate_parts(c);
  Case storage;
  check_scales(kelvin_bound(c, storage));
}

CheckedCase CheckedCase::with_durations(const std::vector<Segment>& segments) && {
  std::vector<Segment>& own = c_.history.segments;
  if (segments.size() != own.size())
    throw std::logic_error("CheckedCase::with_durations: " + std::to_string(segments.size()) +
                           " segments for a history of " + std::to_string(own.size()));
  for (std::size_t k = 0; k < own.size(); ++k) {
    if (segments[k].w != own[k].w)
      throw std::logic_error("CheckedCase::with_durations: the velocities differ");
    own[k].T = segments[k].T;
  }
  validate_history(c_.history, c_.sampling);
  return CheckedCase(std::move(c_), Trusted{});
}

CheckedCase CheckedCase::shifted() const {
  Case c = c_;
  c.rheology = c_.rheology.shifted();
  return CheckedCase(std::move(c), Trusted{});
}

} // namespace mdrmap
