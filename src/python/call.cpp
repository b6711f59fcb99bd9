#include "python/call.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

namespace py = pybind11;

namespace mdrmap::python {
namespace {

using Clock = std::chrono::steady_clock;

/// The work on its own thread; the destructor stops it (where it still runs)
/// and joins it, so that no thread outlives the call, whatever is thrown.
class Worker {
public:
  Worker(const std::function<void(const RunControl&)>& work, std::atomic<double>* progress) {
    control_.stop = &stop_;
    control_.progress = progress;
    thread_ = std::thread([this, &work] {
      try {
        work(control_);
      } catch (...) {
        error_ = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
      done_cv_.notify_all();
    });
  }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;
  ~Worker() {
    stop_ = 1;
    py::gil_scoped_release release;
    thread_.join();
  }

  /// Waits up to `seconds` (without the GIL); whether the work has ended.
  bool wait(double seconds) {
    py::gil_scoped_release release;
    std::unique_lock<std::mutex> lock(mutex_);
    return done_cv_.wait_for(lock, std::chrono::duration<double>(seconds),
                             [this] { return done_; });
  }
  void stop() { stop_ = 1; }
  bool stopping() const { return stop_ != 0; }
  /// What the work threw, once it has ended.
  std::exception_ptr error() const { return error_; }

private:
  volatile std::sig_atomic_t stop_ = 0;
  RunControl control_;
  std::mutex mutex_;
  std::condition_variable done_cv_;
  bool done_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

} // namespace

void run_call(const std::function<void(const RunControl&)>& work, const py::object& progress) {
  std::atomic<double> fraction{0.0};
  std::optional<py::error_already_set> raised; // KeyboardInterrupt or the callback's
  const bool report = !progress.is_none();
  {
    Worker worker(work, report ? &fraction : nullptr);
    auto last = Clock::now();
    double shown = -1.0;
    while (!worker.wait(kPollSeconds)) {
      if (worker.stopping()) continue; // (stopping: wait for the work to end)
      try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        const double f = fraction.load(std::memory_order_relaxed);
        if (report && f != shown &&
            std::chrono::duration<double>(Clock::now() - last).count() >= kProgressSeconds) {
          progress(f);
          shown = f;
          last = Clock::now();
        }
      } catch (py::error_already_set& e) {
        raised.emplace(std::move(e));
        worker.stop();
      }
    }
    if (!raised && worker.error()) std::rethrow_exception(worker.error());
  }
  if (raised) throw std::move(*raised);
  if (report) progress(1.0);
}

} // namespace mdrmap::python
