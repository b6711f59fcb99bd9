#pragma once
// What a solver may spend on one case, and a flag that stops it
// (docs/design.md, "Work budget and stopping"). Every solver loop charges its
// work here: a case that would run past its budget fails with a message
// (CaseAbandoned: status -1 in a study, exit 1 from simulate) instead of
// running unbounded; a stop request (SIGTERM/SIGINT in the app layer) ends
// the case within one check (Interrupted: a study leaves it pending).
// The flag is the caller's; the core holds no global state.
#include <csignal>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace mdrmap {

/// The case cannot be computed within its budget or its tolerance: the case
/// fails with this message (not bad input; the inputs were valid).
class CaseAbandoned : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// A stop was requested while the case ran: the case has no result and is
/// not failed either (a study leaves it pending for --resume).
class Interrupted : public std::runtime_error {
public:
  Interrupted() : std::runtime_error("stopped by a signal") {}
};

/// Work units: one element update, one scalar root solve or one time step each.
struct RunControl {
  /// Default budget: about 1e9 element updates, tens of seconds on one core.
  static constexpr double kDefaultMaxWork = 1e9;

  double max_work = kDefaultMaxWork;                ///< > 0
  const volatile std::sig_atomic_t* stop = nullptr; ///< nonzero: stop now

  /// Counts `units` of work; throws Interrupted if a stop was requested and
  /// CaseAbandoned once the case's work passes max_work. `what` names the
  /// solver in the message.
  void charge(double units, const char* what) const {
    spent_ += units;
    if (stop != nullptr && *stop != 0) throw Interrupted();
    if (spent_ > max_work) {
      char budget[32]; // (max_work may exceed what a long long holds)
      std::snprintf(budget, sizeof budget, "%.3g", max_work);
      throw CaseAbandoned(
          std::string(what) + " needs more than its work budget of " + budget +
          " work units (an element's sub-step, 1 + N/4 for N spectrum branches; a root "
          "solve; a time step): the case is too stiff or too long for this "
          "solver at this rtol; a looser --rtol needs less work");
    }
  }
  double spent() const { return spent_; }

private:
  mutable double spent_ = 0.0;
};

} // namespace mdrmap
