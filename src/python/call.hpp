#pragma once
// One call of the package into the core, as a Python function should behave:
// the work runs on a thread of its own without the GIL, while the calling
// thread waits for it in short slices; between two slices it takes the GIL,
// runs the interpreter's pending signal handlers (PyErr_CheckSignals: Ctrl-C
// raises KeyboardInterrupt there, in the main thread) and calls the progress
// callback. An exception there (KeyboardInterrupt, or one the callback
// raises) sets the work's stop flag (RunControl::stop: the solver ends within
// one check), waits for the work to end and is raised; the interpreter's
// signal handlers are never replaced.
#include <functional>

#include <pybind11/pybind11.h>

#include "core/solvers/run_control.hpp"

namespace mdrmap::python {

/// Runs `work` (which must not touch Python objects) with a RunControl whose
/// stop flag and progress the calling thread watches; `progress` is None or
/// a callable called with the fraction of the samples done (RunControl::report),
/// at most about every kProgressSeconds, and with 1.0 once the work succeeded.
/// Rethrows what `work` throws.
void run_call(const std::function<void(const RunControl&)>& work, const pybind11::object& progress);

/// How often the calling thread looks at signals, and the least time between
/// two progress calls.
inline constexpr double kPollSeconds = 0.02, kProgressSeconds = 0.2;

} // namespace mdrmap::python
