#pragma once
// The MPI parameter study: cases are handed out by rank 0 in chunks on
// request (pull-based), computed by every rank (rank 0 too, between
// requests), and written by the rank that computed them straight into the
// map file. The communicator is a parameter; nothing here prints. One case's
// row is computed by compute_case (study/compute.hpp, no MPI calls).
#include <mpi.h>

#include <csignal>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/solvers/dispatch.hpp"
#include "io/map_file.hpp"
#include "study/compute.hpp"
#include "study/config.hpp"

namespace mdrmap::study {

/// A runtime failure that every rank of the communicator raised together, so
/// all can shut down cleanly (any other exception from run_study is local to
/// one rank, and the caller should abort the job).
class CollectiveFailure : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct StudyRequest {
  StudyConfig config;
  std::string output;
  bool resume = false;
  bool overwrite = false;
  std::string command_line;
  /// Set asynchronously (SIGTERM/SIGINT handler): stop taking work, flush, return.
  const volatile std::sig_atomic_t* stop = nullptr;
  /// Target wall time of one chunk; bounds the work lost to a kill and the tail.
  double chunk_seconds = 0.2;
};

struct Progress {
  std::size_t done = 0, failed = 0; ///< in this run
  std::size_t todo = 0;             ///< cases this run set out to do
  std::size_t total = 0;            ///< cases in the study
  std::size_t already_done = 0;     ///< done before this run (resume)
  double elapsed = 0.0;             ///< seconds since the dispatch began
  bool final = false;
};

/// Receives progress on rank 0 (at most every `interval` seconds, and a final call).
class ProgressSink {
public:
  virtual ~ProgressSink() = default;
  virtual void report(const Progress& p) = 0;
  double interval = 1.0;
};

struct StudySummary {
  bool interrupted = false;
  std::size_t total = 0, already_done = 0, done = 0, failed = 0, pending = 0;
  std::size_t already_failed = 0; ///< of already_done: failed before, with a recorded message
  std::size_t recorded = 0;       ///< rank 0: failed cases whose message /failures holds at the end
  std::size_t chunks = 0;         ///< chunks handed out (to workers and to rank 0 itself)
  std::size_t messages = 0;       ///< request/assignment pairs rank 0 served
  double wall_seconds = 0.0;
  /// Non-empty when writing the map failed on some rank (full disk, I/O
  /// error): the study stopped, every row written before is intact, and the
  /// pending cases can be run with --resume once the cause is fixed.
  std::string write_failure;
};

/// Collective over comm. Bad input (existing output, mismatched resume, a
/// study too large for memory or disk, ...) throws InvalidInput on every rank
/// alike; a failure to create, open or close the map throws CollectiveFailure
/// on every rank; a failed row write ends the study early with
/// StudySummary::write_failure set. Anything else is local to one rank.
StudySummary run_study(MPI_Comm comm, const StudyRequest& req, ProgressSink* sink);

} // namespace mdrmap::study
