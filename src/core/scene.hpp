#pragma once
// Scene parameters of one case and the sampling protocol, validated once.
//
// Units are the user's (any consistent set); forces come out in units of
// G * length^2. A scene is a rigid parabolic indenter (MDR image g(x) = x^2/R)
// held at depth d on a Kelvin foundation (shear modulus G, relaxation time
// tau = eta/G), sliding stationarily at v until t = 0 and at v1 afterwards.
#include <stdexcept>
#include <string>

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

struct Scene {
  double d = 0.0;   ///< indentation depth, > 0
  double R = 0.0;   ///< radius of curvature of the parabola, > 0
  double tau = 0.0; ///< relaxation time eta/G, >= 0 (0 is the elastic limit)
  double v = 0.0;   ///< sliding velocity before the step, > 0
  double v1 = 0.0;  ///< sliding velocity after the step, >= 0
  double G = 1.0;   ///< shear modulus, > 0
};

/// A number with 17 significant digits, as error messages quote it.
std::string format_number(double x);

/// Throws InvalidInput naming the first offending field.
void validate(const Scene& s);

/// Output sampling: `samples` instants t_k = k * t_end / (samples - 1),
/// measured from the step (t = 0 is the instant just after it).
struct Protocol {
  double t_end = 0.0;
  long samples = 201;
  double time(long k) const {
    return t_end * static_cast<double>(k) / static_cast<double>(samples - 1);
  }
};

inline constexpr long kMaxSamples = 100'000'000;

/// Throws InvalidInput("t-end" / "samples").
void validate(const Protocol& p);

/// Default observation window: 6 tau; for tau = 0 (nothing relaxes) the time
/// the indenter needs to travel three contact half-widths at the slower speed.
double default_t_end(const Scene& s);

/// Similarity variables (DESIGN.md): a1 = sqrt(R d), zeta = v tau / a1.
double contact_radius(const Scene& s);
double zeta(const Scene& s);
double zeta1(const Scene& s);

} // namespace mdrmap
