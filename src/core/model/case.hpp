#pragma once
// The case model: one computation of mdrmap, made of parts that are each
// validated once (docs/design.md, "The case model").
//
//   indenter  the rigid profile and its MDR image g(x): parabola, cone or power
//             law (profile.hpp)
//   rheology  the foundation element: the Kelvin element G, tau of the seed, or a
//             relaxation spectrum (Maxwell branches), shifted by aT (rheology.hpp)
//   loading   what holds the indenter in the foundation: today a fixed depth d
//   history   stationary sliding at v0 > 0 before t = 0, then segments of
//             constant velocity w_k >= 0 (0 is a hold) lasting T_k > 0
//   sampling  output instants per segment, linear or logarithmic in the time
//             since the segment's start
//
// Units are the user's (any consistent set); forces come out in units of
// G * length^2. Time t is measured from the first velocity change.
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/model/profile.hpp"
#include "core/model/rheology.hpp"

namespace mdrmap {

/// Bad input: names the option (as the CLI spells it, without dashes) and
/// says what is allowed. The app layer turns it into a one-line error.
class InvalidInput : public std::invalid_argument {
public:
  InvalidInput(std::string option, const std::string& message)
      : std::invalid_argument(message), option_(std::move(option)) {}
  const std::string& option() const noexcept { return option_; }

private:
  std::string option_;
};

/// A number with 17 significant digits, as error messages quote it.
std::string format_number(double x);

/// How the indenter is held: at a fixed depth d (depth control), or under a
/// prescribed normal force F0 with the depth free (load control). Exactly one
/// of the two is given (> 0); the other is 0.
struct Loading {
  double d = 0.0;  ///< indentation depth, > 0 under depth control
  double F0 = 0.0; ///< normal force, > 0 under load control
  bool by_force() const { return F0 > 0.0; }
};

/// One segment of the velocity history: constant velocity w for a time T.
struct Segment {
  double w = 0.0; ///< sliding velocity, >= 0 (0 is a hold)
  double T = 0.0; ///< duration, > 0
};

/// Stationary sliding at v0 for t < 0, then the segments one after another;
/// segment k starts at start(k) = T_0 + ... + T_(k-1).
struct History {
  double v0 = 0.0; ///< velocity of the stationary sliding before t = 0, > 0
  std::vector<Segment> segments;
  std::size_t size() const { return segments.size(); }
  double start(std::size_t k) const;
  double end() const { return start(segments.size()); }
  /// Velocity before segment k (v0 for k = 0).
  double before(std::size_t k) const { return k == 0 ? v0 : segments[k - 1].w; }
};

enum class Spacing { Linear, Log };

/// Output instants of a segment of duration T: `samples` instants, j = 0 the
/// state just after the change at its start, j = samples - 1 the state at its
/// end. Linear: offset j T / (samples - 1). Log: offset 0, then
/// T 10^(-decades (samples - 1 - j) / (samples - 2)) for j >= 1.
struct Sampling {
  long samples = 201;
  Spacing spacing = Spacing::Linear;
  double decades = 4.0; ///< log spacing: the first offset after 0 is T 10^-decades
  /// Explicit instants (a lab record's times, case/lab_record.hpp): per
  /// segment, the times since its start, from 0 to its duration T strictly
  /// increasing (validate() checks). Empty: `samples` instants per segment,
  /// spaced as above.
  std::vector<std::vector<double>> at;
  /// Number of output instants of segment k.
  long count(std::size_t k) const { return at.empty() ? samples : static_cast<long>(at[k].size()); }
  /// Time since the start of segment k (duration T) of its sample j.
  double offset(std::size_t k, long j, double T) const {
    return at.empty() ? offset(j, T) : at[k][static_cast<std::size_t>(j)];
  }
  /// Time since the segment's start of sample j. (Inline: it is asked at
  /// every sample.)
  double offset(long j, double T) const {
    if (j <= 0) return 0.0;
    if (j >= samples - 1) return T;
    if (spacing == Spacing::Linear) {
      const double t = T * static_cast<double>(j) / static_cast<double>(samples - 1);
      if (std::isfinite(t)) return t;
    }
    return inner_offset(j, T);
  }

private:
  /// offset() of 0 < j < samples - 1: log spacing, or linear where T j overflows.
  double inner_offset(long j, double T) const;
};

inline constexpr long kMaxSamples = 100'000'000;
inline constexpr std::size_t kMaxSegments = 10'000;

struct Case {
  Indenter indenter;
  Rheology rheology;
  Loading loading;
  History history;
  Sampling sampling;

  /// Leading edge a1 = contact radius at depth d (depth control).
  double a1() const { return indenter.contact_radius(loading.d); }
  /// Hertz contact radius of F0 (load control): F0 = 4 G int (g(a0) - g)
  /// over [-a0, a0] (16/3 G a0^3 / R for the parabola).
  double a0() const;
  /// The length the error metric measures edges by: a1 at fixed depth, a0
  /// under load.
  double edge_scale() const { return loading.by_force() ? a0() : a1(); }
  /// Output samples of the whole history: the sum of sampling.count(k).
  std::size_t total_samples() const;
  /// Index of the first sample of segment k in the series.
  std::size_t first_sample(std::size_t k) const;
};

/// Throws InvalidInput naming the first offending parameter (as the CLI
/// spells it). Checks every part and the parameter table: the parameters in
/// their ranges, one of each group, the profile's limits, the rheology, the
/// history and its explicit instants, the element row's limits where the case
/// needs the row. The scales derived from the parts (which need the
/// stationary states of core/metrics) are validate()'s, above the model
/// (core/solvers/checked_case.hpp), which calls this first.
void validate_parts(const Case& c);

/// The history's part of validate_parts: its segments, and the explicit
/// output instants (Sampling::at) where given. Throws InvalidInput
/// ("history", "history-file").
void validate_history(const History& h, const Sampling& s);

/// The seed's experiment: one step v -> v1 at t = 0, observed over t_end
/// (0: default_step_duration), `samples` linear samples.
Case step_case(double d, double R, double tau, double v, double v1, double G = 1.0,
               double t_end = 0.0, long samples = 201);

/// Default observation window of the one-step history: 6 tau; for tau = 0
/// (nothing relaxes) the time the indenter needs to travel six contact
/// half-widths at the slower speed.
double default_step_duration(double d, double R, double tau, double v, double v1);

/// Throws InvalidInput("solver") unless the case is depth-controlled: the fixed-
/// depth solvers' guard (`solver` names the caller in the message).
void require_depth_control(const Case& c, const char* solver);

/// Throws InvalidInput("prony") unless the case's rheology is the Kelvin
/// foundation (no Maxwell branches): the guard of the solvers and closed forms
/// that take the Kelvin foundation only (`solver` names the caller).
void require_kelvin(const Case& c, const char* solver);

/// Throws InvalidInput("profile") unless the indenter is the parabola: the
/// guard of the solvers that take the parabola only (`solver` names the caller).
void require_parabola(const Case& c, const char* solver);

/// Similarity variable zeta = w tau / a1 at velocity w.
double zeta(const Case& c, double w);

} // namespace mdrmap
