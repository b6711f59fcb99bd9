#pragma once
// What a solver may spend on one case, and a flag that stops it
// (docs/design.md, "Work budget and stopping"). Every solver loop charges its
// work here: a case that would run past its budget fails with a message
// (CaseAbandoned: status -1 in a study, exit 1 from simulate) instead of
// running unbounded; a stop request (SIGTERM/SIGINT in the app layer) ends
// the case within one check (Interrupted: a study leaves it pending).
// The solvers also report how far the case got (report: the fraction of the
// history's samples computed), for a caller that shows progress; and a caller
// may have its `poll` called now and then from the solver's thread (e.g. the
// Python module, to run the interpreter's signal handlers: Ctrl-C).
// The flag and the progress are the caller's; the core holds no global state.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstddef>
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
  /// Where report() writes the fraction of the samples done (any thread may
  /// read it while the solver runs); nullptr: not reported.
  std::atomic<double>* progress = nullptr;
  /// Called from the solver's thread within charge(), at most about every
  /// poll_seconds while the case runs (nullptr: never); it may set *stop to
  /// end the case. `poll_data` is its argument.
  void (*poll)(void* poll_data) = nullptr;
  void* poll_data = nullptr;
  double poll_seconds = 0.02;

  /// Counts `units` of work; throws Interrupted if a stop was requested and
  /// CaseAbandoned once the case's work passes max_work. `what` names the
  /// solver in the message.
  void charge(double units, const char* what) const {
    spent_ += units;
    if (poll != nullptr && --poll_countdown_ <= 0) poll_now();
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

  /// The same budget, stop flag and progress, with nothing spent (for a
  /// further run of the case with a budget of its own, e.g. a reference).
  RunControl fresh() const {
    RunControl out;
    out.max_work = max_work;
    out.stop = stop;
    out.progress = progress;
    out.poll = poll;
    out.poll_data = poll_data;
    out.poll_seconds = poll_seconds;
    return out;
  }

  /// The solver has computed `done` of the `total` samples of its current run
  /// over the history (a solver that refines runs the history again: the
  /// fraction starts again from 0).
  void report(std::size_t done, std::size_t total) const {
    if (progress != nullptr && total > 0)
      progress->store(static_cast<double>(done) / static_cast<double>(total),
                      std::memory_order_relaxed);
  }

private:
  /// Charges between two looks at the clock.
  static constexpr int kPollEvery = 64;

  void poll_now() const {
    poll_countdown_ = kPollEvery;
    const auto now = std::chrono::steady_clock::now();
    const bool first = next_poll_ == std::chrono::steady_clock::time_point{};
    if (!first && now < next_poll_) return;
    next_poll_ = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(poll_seconds));
    if (!first) poll(poll_data); // (the first poll_seconds after the start)
  }

  mutable double spent_ = 0.0;
  mutable int poll_countdown_ = 0;
  mutable std::chrono::steady_clock::time_point next_poll_{};
};

} // namespace mdrmap
