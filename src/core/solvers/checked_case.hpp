#pragma once
// The case the solvers take: validated once, where it is built (the command
// line's and the Python module's case, a study's row), then handed to
// run_case and every solver as is (docs/design.md, "The case model").
//
// Above the model: besides the parts (validate_parts, core/model/case.hpp)
// validate() checks that the scales derived from them are representable,
// which takes the stationary states of core/metrics.
#include <vector>

#include "core/model/case.hpp"

namespace mdrmap {

/// Throws InvalidInput naming the first offending parameter (as the CLI
/// spells it). Checks every part (validate_parts) and that the derived scales
/// are representable: the contact radius, the force scale, w tau / a at every
/// velocity of the history, the stationary contact at rest and at the fastest
/// velocity.
void validate(const Case& c);

/// A case that passed validate(): made once where a case is built (a study's
/// row: study::checked_case_for; a simulation: cases::simulate), then taken by
/// run_case and the solvers (run_exact, run_load, run_spectrum,
/// run_spectrum_baseline), which need not check it again.
class CheckedCase {
public:
  /// Validates `c`; throws InvalidInput as validate() does.
  explicit CheckedCase(Case c) : c_(std::move(c)) { validate(c_); }
  const Case& get() const { return c_; }
  /// The case itself, no longer marked as checked.
  Case take() && { return std::move(c_); }
  /// This case with the durations T of `segments` (one per segment; their
  /// velocities must be this case's): only the history is checked again, as
  /// nothing else validate() checks depends on the durations. Throws
  /// InvalidInput("history") as validate() does.
  CheckedCase with_durations(const std::vector<Segment>& segments) &&;
  /// This case with aT folded into its relaxation times (Rheology::shifted;
  /// validate() checked the shifted times): what the solvers solve.
  CheckedCase shifted() const;

private:
  struct Trusted {};
  CheckedCase(Case c, Trusted) : c_(std::move(c)) {}
  Case c_;
};

} // namespace mdrmap
