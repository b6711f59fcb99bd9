#include "python/call.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <exception>
#include <optional>
#include <utility>

namespace py = pybind11;

namespace mdrmap::python {
namespace {

using Clock = std::chrono::steady_clock;

/// Python's ident of the main thread (threading.main_thread().ident).
unsigned long main_thread_ident = 0;

/// What the polls of one call share.
struct Watch {
  explicit Watch(const py::object& p) : progress(p) {}
  const py::object& progress;
  bool signals = false; ///< in the main thread: run the signal handlers
  volatile std::sig_atomic_t stop = 0;
  std::atomic<double> fraction{0.0};
  double shown = -1.0;
  Clock::time_point last = Clock::now();
  std::optional<py::error_already_set> raised; ///< KeyboardInterrupt or the callback's
};

/// RunControl::poll: runs the signal handlers and the progress callback; an
/// exception stops the case and is kept for the caller.
void poll(void* data) {
  Watch& w = *static_cast<Watch*>(data);
  if (w.stop != 0) return;
  py::gil_scoped_acquire gil;
  try {
    if (w.signals && PyErr_CheckSignals() != 0) throw py::error_already_set();
    const double f = w.fraction.load(std::memory_order_relaxed);
    if (!w.progress.is_none() && f != w.shown &&
        std::chrono::duration<double>(Clock::now() - w.last).count() >= kProgressSeconds) {
      w.progress(f);
      w.shown = f;
      w.last = Clock::now();
    }
  } catch (py::error_already_set& e) {
    w.raised.emplace(std::move(e));
    w.stop = 1;
  }
}

} // namespace

void init_call() {
  main_thread_ident =
      py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
}

void run_call(const std::function<void(const RunControl&)>& work, const py::object& progress) {
  Watch w(progress);
  w.signals = PyThread_get_thread_ident() == main_thread_ident;
  RunControl control;
  control.stop = &w.stop;
  if (!progress.is_none()) control.progress = &w.fraction;
  if (w.signals || !progress.is_none()) {
    control.poll = &poll;
    control.poll_data = &w;
    control.poll_seconds = kPollSeconds;
  }
  std::exception_ptr error;
  {
    py::gil_scoped_release release;
    try {
      work(control);
    } catch (...) {
      error = std::current_exception();
    }
  }
  if (w.raised) throw std::move(*w.raised); // (the work ended by Interrupted, or just before)
  if (error) std::rethrow_exception(error);
  if (!progress.is_none()) progress(1.0);
}

} // namespace mdrmap::python
