#pragma once
// One call of the package into the core, as a Python function should behave:
// the work runs in the calling thread without the GIL; from the main thread
// (the only one that runs the interpreter's signal handlers) or with a
// progress callback, the case's RunControl polls about every kPollSeconds:
// it takes the GIL, runs the pending signal handlers (PyErr_CheckSignals:
// Ctrl-C raises KeyboardInterrupt there) and calls the progress callback.
// An exception there (KeyboardInterrupt, or one the callback raises) sets
// the case's stop flag (the solver ends within one check) and is raised once
// the work has ended. The interpreter's signal handlers are never replaced.
#include <functional>

#include <pybind11/pybind11.h>

#include "core/numerics/run_control.hpp"

namespace mdrmap::python {

/// How often the work looks at signals, and the least time between two
/// progress calls.
inline constexpr double kPollSeconds = 0.02, kProgressSeconds = 0.2;

/// Remembers the main thread (call it at import, from any thread).
void init_call();

/// Runs `work` (which must not touch Python objects) without the GIL, with a
/// RunControl that polls as above; `progress` is None or a callable called
/// with the fraction of the samples done (RunControl::report), at most about
/// every kProgressSeconds, and with 1.0 once the work succeeded. Rethrows
/// what `work` throws.
void run_call(const std::function<void(const RunControl&)>& work, const pybind11::object& progress);

} // namespace mdrmap::python
