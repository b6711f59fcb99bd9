#include "study/runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <sys/statvfs.h>
#include <vector>

#include "mdrmap/version.hpp"
#include "study/compute.hpp"
#include "study/preflight.hpp"

namespace mdrmap::study {
namespace {

using detail::bcast_from_root;
using detail::collectively;
using detail::parent_dir;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr int kTagRequest = 11;
constexpr int kTagAssign = 12;

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// The message for a failed write: what HDF5 said, and whether the disk is full.
std::string describe_write_failure(const std::string& out, const std::string& what) {
  std::string msg = "writing '" + out + "' failed (" + what + ")";
  struct statvfs fs {};
  if (::statvfs(parent_dir(out).c_str(), &fs) == 0 && fs.f_bavail == 0)
    msg += "; the file system of '" + parent_dir(out) + "' is full";
  return msg;
}

// ---- the map ------------------------------------------------------------------

// Collective. Creates the map under a temporary name and renames it when
// complete; on failure the temporary file is removed.
void create_map(MPI_Comm comm, const StudyRequest& req, const detail::StudyPlan& plan) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  io::Provenance prov;
  prov.program_version = kVersion;
  prov.git_commit = kGitCommit;
  prov.created_utc = bcast_from_root(comm, utc_now());
  prov.command_line = bcast_from_root(comm, req.command_line);
  prov.units = "consistent user units: d, R, a2 lengths; tau, t times; v, v1 length/time; G "
               "force/length^2; FN, Fx force = G * length^2; mu dimensionless";
  prov.config_text = req.config.source_text;
  prov.config_canonical = plan.canon;
  prov.mpi_size = size;
  const std::string tmp =
      bcast_from_root(comm, req.output + ".tmp-" + std::to_string(static_cast<long>(::getpid())));
  try {
    collectively(comm, [&] { io::MapFile::create(comm, tmp, plan.spec, prov, plan.cases); });
    collectively(comm, [&] {
      if (rank == 0 && std::rename(tmp.c_str(), req.output.c_str()) != 0)
        throw std::runtime_error("cannot rename '" + tmp + "' to '" + req.output +
                                 "': " + std::strerror(errno));
    });
  } catch (...) {
    if (rank == 0) std::remove(tmp.c_str());
    throw;
  }
}

// What is left to do: indices of the pending cases, and how many are not.
struct Pending {
  std::vector<std::size_t> todo;
  std::size_t already_done = 0;
};

// Collective. Where the rows go, and what is left to do: every rank gets rank
// 0's read of the map's layout and status column and opens the map for its
// rows; rank 0 locks it (one job at a time).
Pending open_map(MPI_Comm comm, const StudyRequest& req, std::size_t n_cases,
                 std::optional<io::RowWriter>& map) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<std::int8_t> status;
  std::vector<std::uint64_t> packed;
  collectively(comm, [&] {
    if (rank != 0) return;
    try {
      packed = io::MapFile::read_layout(req.output, &status).pack();
    } catch (const io::H5Error& e) {
      if (!req.resume) throw;
      throw InvalidInput("resume", "'" + req.output + "' is damaged (" + e.what() +
                                       "); refusing to touch it");
    }
    if (status.size() != n_cases)
      throw InvalidInput("resume", "'" + req.output + "' holds " + std::to_string(status.size()) +
                                       " cases, the study " + std::to_string(n_cases) +
                                       "; refusing to touch it");
  });
  unsigned long long n_packed = packed.size();
  MPI_Bcast(&n_packed, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  packed.resize(static_cast<std::size_t>(n_packed));
  MPI_Bcast(packed.data(), static_cast<int>(n_packed), MPI_UINT64_T, 0, comm);
  status.resize(n_cases);
  MPI_Bcast(status.data(), static_cast<int>(status.size()), MPI_INT8_T, 0, comm);
  collectively(comm, [&] {
    map.emplace(req.output, io::MapLayout::unpack(packed));
    // one job at a time: a second --resume of a map in use is refused
    long holder = 0;
    if (rank == 0 && !map->lock(&holder))
      throw InvalidInput(req.resume ? "resume" : "output",
                         "'" + req.output + "' is being written by another mdrmap job" +
                             (holder > 0 ? " (process " + std::to_string(holder) + ")" : "") +
                             "; refusing to touch it");
  });
  Pending p;
  for (std::size_t i = 0; i < status.size(); ++i) {
    if (status[i] == 0)
      p.todo.push_back(i);
    else
      ++p.already_done;
  }
  return p;
}

// ---- scheduling ---------------------------------------------------------------

// What every rank computes with: its share of the cases, computed
// (compute_case) and written into the map in chunks of the to-do list.
struct Worker {
  MPI_Comm comm;
  const StudyRequest& req;
  const std::vector<StepRow>& cases;
  const std::vector<std::size_t>& todo;
  io::RowWriter& map;
  SolverKind kind;
  std::size_t done = 0, failed = 0; ///< rows written by this rank
  double compute_seconds = 0.0;
  std::string write_error; ///< why writing the map failed here ("" if it did not)

  // A stop signal, or a failed write: either way this rank takes no more work.
  bool stop_requested() const { return (req.stop && *req.stop != 0) || !write_error.empty(); }

  // Computes todo[pos, pos+count) (stops early on a stop request) and writes
  // the finished rows; returns how many were finished.
  std::size_t run_chunk(std::size_t pos, std::size_t count,
                        const std::function<void()>& between_cases) {
    std::vector<io::CaseRow> rows;
    rows.reserve(count);
    std::size_t finished = 0;
    for (; finished < count; ++finished) {
      if (stop_requested()) break;
      const auto t0 = Clock::now();
      rows.push_back(compute_case(req.config, cases[todo[pos + finished]], kind, map.timeseries()));
      compute_seconds += seconds_since(t0);
      if (between_cases) between_cases();
    }
    // write runs of consecutive case indices; a row counts once it is written
    std::size_t i = 0;
    while (i < rows.size()) {
      std::size_t j = i + 1;
      while (j < rows.size() && todo[pos + j] == todo[pos + j - 1] + 1)
        ++j;
      std::vector<io::CaseRow> run(std::make_move_iterator(rows.begin() + static_cast<long>(i)),
                                   std::make_move_iterator(rows.begin() + static_cast<long>(j)));
      try {
        map.write_rows(todo[pos + i], run);
      } catch (const std::exception& e) {
        // The rows of this run stay pending (their status is written last);
        // this rank stops, the others finish their chunks, the study ends.
        write_error = describe_write_failure(req.output, e.what());
        return finished;
      }
      for (const auto& r : run)
        ++(r.status == 1 ? done : failed);
      i = j;
    }
    return finished;
  }
};

// Rank 0's side of the dispatch: answers the workers' requests for chunks
// (pull-based, guided self-scheduling), and computes its own small chunks in
// between, serving requests after every case.
class Master {
public:
  Master(Worker& w, ProgressSink* sink, StudySummary& sum)
      : w_(w), sink_(sink), sum_(sum), size_(comm_size(w.comm)), active_(size_ - 1) {}

  // Runs until every case is handed out (or a stop) and every worker is
  // dismissed; fills sum's counts, and reports a last time.
  void run() {
    while (true) {
      if (w_.stop_requested()) stopping_ = true;
      serve(false);
      if (!stopping_ && pos_ < w_.todo.size()) {
        run_own_chunk();
        continue;
      }
      if (active_ == 0) break;
      serve(true);
    }
    sum_.done = w_.done + others_done_;
    sum_.failed = w_.failed + others_failed_;
    sum_.wall_seconds = seconds_since(t_start_);
    sum_.pending = w_.todo.size() - sum_.done - sum_.failed;
    sum_.interrupted = sum_.pending > 0;
    report(true);
  }

private:
  static int comm_size(MPI_Comm comm) {
    int size = 1;
    MPI_Comm_size(comm, &size);
    return size;
  }

  std::size_t chunk_size(int share) const {
    const std::size_t remaining = w_.todo.size() - pos_;
    // guided self-scheduling: a quarter of the fair share of what is left,
    // capped so that one chunk takes about chunk_seconds
    std::size_t k = (remaining + 4 * static_cast<std::size_t>(share) - 1) /
                    (4 * static_cast<std::size_t>(share));
    if (cost_samples_ > 0 && case_seconds_ > 0.0)
      k = std::min<std::size_t>(
          k, static_cast<std::size_t>(std::max(1.0, w_.req.chunk_seconds / case_seconds_)));
    else
      k = std::min<std::size_t>(k, 4); // cost unknown yet: start small
    return std::max<std::size_t>(1, std::min(k, remaining));
  }

  // One more sample of the cost of a case, into the running mean.
  void add_cost(double per_case) {
    case_seconds_ = (case_seconds_ * static_cast<double>(cost_samples_) + per_case) /
                    static_cast<double>(cost_samples_ + 1);
    ++cost_samples_;
  }

  void report(bool final) {
    if (!sink_) return;
    if (!final && seconds_since(last_report_) < sink_->interval) return;
    last_report_ = Clock::now();
    Progress p;
    p.done = w_.done + others_done_;
    p.failed = w_.failed + others_failed_;
    p.todo = w_.todo.size();
    p.total = w_.cases.size();
    p.already_done = sum_.already_done;
    p.elapsed = seconds_since(t_start_);
    p.final = final;
    sink_->report(p);
  }

  // Answers the pending requests (block: waits for one first).
  void serve(bool block) {
    int flag = 0;
    MPI_Status st;
    if (block) {
      MPI_Probe(MPI_ANY_SOURCE, kTagRequest, w_.comm, &st);
      flag = 1;
    } else {
      MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, w_.comm, &flag, &st);
    }
    while (flag) {
      answer(st.MPI_SOURCE);
      MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, w_.comm, &flag, &st);
    }
    report(false);
  }

  // One request: the worker's report of its last chunk (done, failed, compute
  // nanoseconds, stop asked), answered with the next chunk (start, count), or
  // count 0 to dismiss it.
  void answer(int source) {
    long long msg[4];
    MPI_Recv(msg, 4, MPI_LONG_LONG, source, kTagRequest, w_.comm, MPI_STATUS_IGNORE);
    others_done_ += static_cast<std::size_t>(msg[0]);
    others_failed_ += static_cast<std::size_t>(msg[1]);
    if (msg[0] + msg[1] > 0 && msg[2] > 0)
      add_cost(static_cast<double>(msg[2]) * 1e-9 / static_cast<double>(msg[0] + msg[1]));
    if (msg[3] != 0) stopping_ = true; // that worker was asked to stop
    if (w_.stop_requested()) stopping_ = true;
    long long assign[2] = {0, 0};
    ++sum_.messages;
    if (!stopping_ && pos_ < w_.todo.size()) {
      const std::size_t k = chunk_size(size_);
      assign[0] = static_cast<long long>(pos_), assign[1] = static_cast<long long>(k);
      pos_ += k;
      ++sum_.chunks;
    } else {
      --active_;
    }
    MPI_Send(assign, 2, MPI_LONG_LONG, source, kTagAssign, w_.comm);
  }

  // A chunk of rank 0's own (at most 64 cases when there are workers to serve).
  void run_own_chunk() {
    const std::size_t k =
        (size_ == 1) ? chunk_size(1) : std::min<std::size_t>(chunk_size(size_), 64);
    const std::size_t p0 = pos_;
    pos_ += k;
    ++sum_.chunks;
    const double before = w_.compute_seconds;
    const std::size_t n_before = w_.done + w_.failed;
    const std::size_t finished = w_.run_chunk(p0, k, [&] { serve(false); });
    if (finished < k) stopping_ = true; // stop request mid-chunk: the rest stays pending
    const std::size_t n = w_.done + w_.failed - n_before;
    if (n > 0) add_cost((w_.compute_seconds - before) / static_cast<double>(n));
  }

  Worker& w_;
  ProgressSink* sink_;
  StudySummary& sum_;
  int size_;
  int active_; ///< workers not yet dismissed
  std::size_t pos_ = 0, others_done_ = 0, others_failed_ = 0;
  bool stopping_ = false;
  double case_seconds_ = 0.0; ///< running mean cost of a case, from all reports
  std::size_t cost_samples_ = 0;
  const Clock::time_point t_start_ = Clock::now();
  Clock::time_point last_report_ = Clock::now();
};

// A worker rank's side: asks rank 0 for a chunk, reporting what its last one
// did, and computes it, until rank 0 dismisses it.
void pull_work(Worker& w) {
  long long report_msg[4] = {0, 0, 0, 0};
  while (true) {
    report_msg[3] = w.stop_requested() ? 1 : 0;
    MPI_Send(report_msg, 4, MPI_LONG_LONG, 0, kTagRequest, w.comm);
    long long assign[2];
    MPI_Recv(assign, 2, MPI_LONG_LONG, 0, kTagAssign, w.comm, MPI_STATUS_IGNORE);
    if (assign[1] == 0) break;
    const std::size_t d0 = w.done, f0 = w.failed;
    const double c0 = w.compute_seconds;
    w.run_chunk(static_cast<std::size_t>(assign[0]), static_cast<std::size_t>(assign[1]), {});
    report_msg[0] = static_cast<long long>(w.done - d0);
    report_msg[1] = static_cast<long long>(w.failed - f0);
    report_msg[2] = static_cast<long long>((w.compute_seconds - c0) * 1e9);
  }
}

// ---- the outcome --------------------------------------------------------------

// Everyone agrees on rank 0's counts.
void share_outcome(MPI_Comm comm, StudySummary& sum) {
  long long counts[4] = {static_cast<long long>(sum.done), static_cast<long long>(sum.failed),
                         static_cast<long long>(sum.pending), sum.interrupted ? 1 : 0};
  MPI_Bcast(counts, 4, MPI_LONG_LONG, 0, comm);
  sum.done = static_cast<std::size_t>(counts[0]);
  sum.failed = static_cast<std::size_t>(counts[1]);
  sum.pending = static_cast<std::size_t>(counts[2]);
  sum.interrupted = counts[3] != 0;
  MPI_Bcast(&sum.wall_seconds, 1, MPI_DOUBLE, 0, comm);
}

// A failed write anywhere fails the study (the lowest failing rank's
// message); the map is closed all the same, its written rows intact.
void close_map(Worker& w, StudySummary& sum) {
  int rank = 0;
  MPI_Comm_rank(w.comm, &rank);
  try {
    collectively(w.comm, [&] {
      if (!w.write_error.empty())
        throw std::runtime_error("rank " + std::to_string(rank) + ": " + w.write_error);
    });
  } catch (const CollectiveFailure& e) {
    sum.write_failure = e.what();
  }
  try {
    collectively(w.comm, [&] {
      try {
        w.map.close();
      } catch (const std::exception& e) {
        throw std::runtime_error("rank " + std::to_string(rank) + ": " + e.what());
      }
    });
  } catch (const CollectiveFailure& e) {
    if (sum.write_failure.empty())
      sum.write_failure = std::string(e.what()) +
                          "; rows of this run may not have reached the disk: check the map "
                          "(tools/maps/check_map.py)";
  }
}

} // namespace

StudySummary run_study(MPI_Comm comm, const StudyRequest& req, ProgressSink* sink) {
  io::silence_hdf5_errors();
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const detail::StudyPlan plan = detail::preflight(comm, req);
  if (!req.resume) create_map(comm, req, plan);
  std::optional<io::RowWriter> map;
  const Pending pending = open_map(comm, req, plan.cases.size(), map);

  Worker w{comm, req, plan.cases, pending.todo, *map, plan.kind, 0, 0, 0.0, {}};
  StudySummary sum;
  sum.total = plan.cases.size();
  sum.already_done = pending.already_done;
  if (rank == 0)
    Master(w, sink, sum).run();
  else
    pull_work(w);
  share_outcome(comm, sum);
  close_map(w, sum);
  return sum;
}

} // namespace mdrmap::study
