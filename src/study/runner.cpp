#include "study/runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <utility>
#include <vector>

#include "io/map_lock.hpp"
#include "mdrmap/version.hpp"
#include "study/case_columns.hpp"
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
constexpr int kTagFailures = 13;

// At most this many failures are recorded in /failures (the rest are failed
// in the status column, their messages not kept: rank 0's memory stays bounded).
constexpr std::size_t kMaxRecordedFailures = 100000;

// Failures as bytes, to send: index (8 bytes), length (4), message, ...
std::vector<char> pack_failures(const std::vector<io::Failure>& v) {
  std::vector<char> out;
  for (const io::Failure& f : v) {
    const auto n = static_cast<std::uint32_t>(std::min<std::size_t>(f.message.size(), 4096));
    const char* idx = reinterpret_cast<const char*>(&f.index);
    const char* len = reinterpret_cast<const char*>(&n);
    out.insert(out.end(), idx, idx + 8);
    out.insert(out.end(), len, len + 4);
    out.insert(out.end(), f.message.data(), f.message.data() + n);
  }
  return out;
}

void unpack_failures(const std::vector<char>& in, std::vector<io::Failure>& out) {
  for (std::size_t at = 0; at + 12 <= in.size();) {
    io::Failure f;
    std::uint32_t n = 0;
    std::memcpy(&f.index, &in[at], 8);
    std::memcpy(&n, &in[at + 8], 4);
    f.message.assign(&in[at + 12], std::min<std::size_t>(n, in.size() - at - 12));
    at += 12 + n;
    out.push_back(std::move(f));
  }
}

// A chunk of work: ranges [begin, end) of case indices, in order, at most
// kMaxRanges of them (pending cases are contiguous but for a resume's gaps).
constexpr std::size_t kMaxRanges = 64;
struct Chunk {
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& [begin, end] : ranges)
      n += end - begin;
    return n;
  }
};

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

// " (process N)" when the holder of a map's lock is known.
std::string holder_text(long holder) {
  return holder > 0 ? " (process " + std::to_string(holder) + ")" : "";
}

// Rank 0: locks the existing map `out` for `option` (--overwrite: "replace",
// --resume: "touch"), refused while another job holds it; retried while other
// jobs replace the file under it. With `may_vanish` (--overwrite) a file that
// is gone needs no lock: the new map is then created as without --overwrite.
void lock_existing(const std::string& out, io::MapLock& lock, const char* option, const char* verb,
                   bool may_vanish) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    struct stat st {};
    if (may_vanish && ::stat(out.c_str(), &st) != 0 && errno == ENOENT) return;
    long holder = 0;
    if (!lock.acquire(out, &holder))
      throw InvalidInput(option, "'" + out + "' is being written by another mdrmap job" +
                                     holder_text(holder) + "; refusing to " + verb + " it");
    if (lock.names(out)) return; // not replaced while we locked it
  }
  throw InvalidInput(option, "'" + out + "' keeps being replaced by other jobs; refusing to " +
                                 verb + " it");
}

// Rank 0: puts the complete map `tmp` (locked by `lock`) in its place: over
// the locked map it replaces, or where there is no file (never over a map
// another job created meanwhile).
void install_map(const std::string& tmp, const std::string& out, const io::MapLock& replaced,
                 io::MapLock& lock) {
  long holder = 0;
  if (!lock.acquire(tmp, &holder))
    throw std::runtime_error("'" + tmp + "' is locked by another process" + holder_text(holder));
  lock.announce();
  if (replaced.held()) {
    if (!replaced.names(out))
      throw InvalidInput("output", "'" + out +
                                       "' was replaced by another job meanwhile; "
                                       "refusing to replace it");
    if (std::rename(tmp.c_str(), out.c_str()) != 0)
      throw std::runtime_error("cannot rename '" + tmp + "' to '" + out +
                               "': " + std::strerror(errno));
    return;
  }
  const int err = io::rename_no_replace(tmp, out);
  if (err == EEXIST) {
    io::MapLock probe;
    holder = 0;
    const bool busy = !probe.acquire(out, &holder);
    throw InvalidInput("output", "'" + out + "' was created meanwhile by another " +
                                     (busy ? "mdrmap job" + holder_text(holder) +
                                                 ", which is writing it; refusing to replace it"
                                           : "job; pass --resume to continue it or --overwrite "
                                             "to replace it"));
  }
  if (err != 0)
    throw std::runtime_error("cannot rename '" + tmp + "' to '" + out + "': " + std::strerror(err));
}

// Collective. Creates the map under a temporary name and renames it when
// complete (never over a map another job holds or created meanwhile); on
// failure the temporary file is removed. Rank 0 holds `lock` on the map on
// return.
void create_map(MPI_Comm comm, const StudyRequest& req, const detail::StudyPlan& plan,
                io::MapLock& lock) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  io::Provenance prov;
  prov.program_version = kVersion;
  prov.git_commit = kGitCommit;
  prov.created_utc = bcast_from_root(comm, utc_now());
  prov.command_line = bcast_from_root(comm, req.command_line);
  prov.units = "consistent user units: d, R, a1, a2 lengths; tau, T, t times; v, w "
               "length/time; G force/length^2; F0, FN, Fx force = G * length^2; mu dimensionless";
  prov.config_text = req.config.source_text;
  prov.config_canonical = plan.canon;
  prov.material_card = req.config.run.material_text;
  prov.mpi_size = size;
  const std::string tmp =
      bcast_from_root(comm, req.output + ".tmp-" + std::to_string(static_cast<long>(::getpid())));
  io::MapLock replaced;
  collectively(comm, [&] {
    if (rank == 0 && req.overwrite) lock_existing(req.output, replaced, "output", "replace", true);
  });
  try {
    collectively(comm, [&] {
      // every rank writes its share of /cases, taking the cases by range
      std::vector<Row> rows;
      io::MapFile::create(
          comm, tmp, plan.spec, prov,
          [&](std::size_t i0, std::size_t i1, std::vector<Case>& out, std::vector<double>& params) {
            plan.cases->rows(i0, i1, rows);
            out.clear();
            params.clear();
            for (const Row& r : rows) {
              out.push_back(case_for(req.config, r));
              append_case_parameters(req.config, r, out.back(), params);
            }
          });
    });
    collectively(comm, [&] {
      if (rank == 0) install_map(tmp, req.output, replaced, lock);
    });
  } catch (...) {
    if (rank == 0) std::remove(tmp.c_str());
    lock.release();
    throw;
  }
}

// Rank 0's view of what is left to do: the status of every case (0 pending,
// 1 byte per case; the other ranks hold nothing per case), handed out from
// the front in chunks of ranges.
class PendingCases {
public:
  PendingCases() = default;
  /// From the map's status and its recorded failures: a failed case whose
  /// failure is not recorded (a killed run's) is pending again.
  PendingCases(std::vector<std::int8_t> status, const std::vector<io::Failure>& recorded)
      : status_(std::move(status)) {
    std::vector<std::uint64_t> kept; // at most kMaxRecordedFailures: no memory per case
    for (const io::Failure& f : recorded)
      kept.push_back(f.index);
    std::sort(kept.begin(), kept.end());
    for (std::size_t i = 0; i < status_.size(); ++i)
      if (status_[i] == -1 && !std::binary_search(kept.begin(), kept.end(), i)) status_[i] = 0;
    left_ = static_cast<std::size_t>(std::count(status_.begin(), status_.end(), 0));
    total_ = left_;
    failed_ = static_cast<std::size_t>(std::count(status_.begin(), status_.end(), -1));
  }
  std::size_t total() const { return total_; }   ///< pending at the start
  std::size_t failed() const { return failed_; } ///< failed before, recorded: not run again
  std::size_t left() const { return left_; }     ///< pending and not handed out yet

  // The next pending cases, at most k of them in at most kMaxRanges ranges.
  Chunk take(std::size_t k) {
    Chunk c;
    std::size_t taken = 0;
    const std::size_t n = status_.size();
    while (taken < k && cursor_ < n) {
      if (status_[cursor_] != 0) {
        ++cursor_;
        continue;
      }
      if (c.ranges.size() == kMaxRanges) break;
      const std::size_t begin = cursor_;
      while (cursor_ < n && status_[cursor_] == 0 && taken < k)
        ++cursor_, ++taken;
      c.ranges.push_back({begin, cursor_});
    }
    left_ -= taken;
    return c;
  }

private:
  std::vector<std::int8_t> status_;
  std::size_t cursor_ = 0, left_ = 0, total_ = 0, failed_ = 0;
};

// Collective. Where the rows go, and what is left to do: every rank gets rank
// 0's read of the map's layout and opens the map for its rows; rank 0 keeps
// the status column and the recorded failures, and holds the map's lock (one job
// at a time: taken here on --resume).
PendingCases open_map(MPI_Comm comm, const StudyRequest& req, std::size_t n_cases,
                      io::MapLock& lock, std::optional<io::RowWriter>& map,
                      std::vector<io::Failure>& recorded) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<std::int8_t> status;
  std::vector<std::uint64_t> packed;
  collectively(comm, [&] {
    if (rank != 0) return;
    // one job at a time: a created map is locked since its creation
    if (!lock.held()) lock_existing(req.output, lock, "resume", "touch", false);
    try {
      packed = io::MapFile::read_layout(req.output, &status).pack();
    } catch (const io::OldOutputNames& e) {
      throw InvalidInput("resume", std::string(e.what()) + "; refusing to touch it");
    } catch (const io::H5Error& e) {
      if (!req.resume) throw;
      throw InvalidInput("resume", "'" + req.output + "' is damaged (" + e.what() +
                                       "); refusing to touch it");
    }
    lock.announce(); // (each HDF5 close drops the PID's lock: announced again at once)
    if (status.size() != n_cases)
      throw InvalidInput("resume", "'" + req.output + "' holds " + std::to_string(status.size()) +
                                       " cases, the study " + std::to_string(n_cases) +
                                       "; refusing to touch it");
    recorded = io::MapFile::read_failures(req.output);
    lock.announce(); // closing HDF5's descriptors of the file dropped the PID's lock
  });
  bcast_from_root(comm, packed);
  collectively(comm, [&] { map.emplace(req.output, io::MapLayout::unpack(packed)); });
  return PendingCases(std::move(status), recorded);
}

// ---- scheduling ---------------------------------------------------------------

// What every rank computes with: its share of the cases, read by range from
// the study's cases (CaseSource), computed (compute_case) and written into
// the map in batches of at most kBatch rows, so that its memory does not
// grow with the size of a chunk.
class Worker {
public:
  static constexpr std::size_t kBatch = 1024;

  Worker(MPI_Comm communicator, const StudyRequest& request, const CaseSource& source,
         io::RowWriter& map, SolverKind kind)
      : comm(communicator), req(request), cases(source), map_(map), kind_(kind),
        layout_(row_layout(request.config)) {}

  MPI_Comm comm;
  const StudyRequest& req;
  const CaseSource& cases;
  std::size_t done = 0, failed = 0; ///< rows written by this rank
  double compute_seconds = 0.0;
  std::string write_error;           ///< why writing the map failed here ("" if it did not)
  std::vector<io::Failure> failures; ///< failed rows written since the last report

  // A stop signal, or a failed write: either way this rank takes no more work.
  bool stop_requested() const { return (req.stop && *req.stop != 0) || !write_error.empty(); }

  // Computes the chunk's cases in order (stops early on a stop request) and
  // writes the finished rows; returns how many were finished.
  std::size_t run_chunk(const Chunk& chunk, const std::function<void()>& between_cases) {
    std::size_t finished = 0;
    for (const auto& [begin, end] : chunk.ranges) {
      for (std::size_t first = begin; first < end; first += kBatch) {
        cases.rows(first, std::min(end, first + kBatch), in_);
        out_.clear();
        for (const Row& r : in_) {
          if (stop_requested()) break;
          const auto t0 = Clock::now();
          try {
            out_.push_back(
                compute_case(req.config, layout_, r, kind_, map_.timeseries(), req.stop));
          } catch (const Interrupted&) {
            break; // stopped during the case: it stays pending (status 0)
          }
          compute_seconds += seconds_since(t0);
          if (between_cases) between_cases();
        }
        finished += out_.size();
        if (!write(first) || out_.size() < in_.size()) return finished;
      }
    }
    return finished;
  }

  void close_map() { map_.close(); }

private:
  // Writes out_ as the rows from case `first` on; a row counts once written.
  bool write(std::size_t first) {
    if (out_.empty()) return true;
    try {
      map_.write_rows(first, out_);
    } catch (const std::exception& e) {
      // The rows of this batch stay pending (their status is written last);
      // this rank stops, the others finish their chunks, the study ends.
      write_error = describe_write_failure(req.output, e.what());
      return false;
    }
    for (std::size_t i = 0; i < out_.size(); ++i) {
      ++(out_[i].status == 1 ? done : failed);
      if (out_[i].status != 1) failures.push_back({first + i, out_[i].message});
    }
    return true;
  }

  io::RowWriter& map_;
  SolverKind kind_;
  io::RowLayout layout_;
  std::vector<Row> in_;          ///< the batch's cases
  std::vector<io::CaseRow> out_; ///< and their rows
};

// An assignment message: the number of ranges, then each range's begin and
// end (0 ranges dismisses the worker).
using Assignment = std::array<long long, 1 + 2 * kMaxRanges>;

// Rank 0's side of the dispatch: answers the workers' requests for chunks
// (pull-based, guided self-scheduling), and computes its own small chunks in
// between, serving requests after every case.
class Master {
public:
  Master(Worker& w, PendingCases pending, ProgressSink* sink, StudySummary& sum,
         std::vector<io::Failure>& failures)
      : w_(w), pending_(std::move(pending)), sink_(sink), sum_(sum), failures_(failures),
        size_(comm_size(w.comm)), active_(size_ - 1) {}

  // Runs until every case is handed out (or a stop) and every worker is
  // dismissed; fills sum's counts, and reports a last time.
  void run() {
    sum_.already_done = sum_.total - pending_.total();
    sum_.already_failed = pending_.failed();
    while (true) {
      if (w_.stop_requested()) stopping_ = true;
      serve(false);
      if (!stopping_ && pending_.left() > 0) {
        run_own_chunk();
        continue;
      }
      if (active_ == 0) break;
      serve(true);
    }
    sum_.done = w_.done + others_done_;
    sum_.failed = w_.failed + others_failed_;
    sum_.wall_seconds = seconds_since(t_start_);
    sum_.pending = pending_.total() - sum_.done - sum_.failed;
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
    const std::size_t remaining = pending_.left();
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
    p.todo = pending_.total();
    p.total = sum_.total;
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
  // nanoseconds, stop asked), answered with the next chunk (its ranges), or
  // none to dismiss it.
  void answer(int source) {
    long long msg[4];
    MPI_Recv(msg, 4, MPI_LONG_LONG, source, kTagRequest, w_.comm, MPI_STATUS_IGNORE);
    others_done_ += static_cast<std::size_t>(msg[0]);
    others_failed_ += static_cast<std::size_t>(msg[1]);
    if (msg[0] + msg[1] > 0 && msg[2] > 0)
      add_cost(static_cast<double>(msg[2]) * 1e-9 / static_cast<double>(msg[0] + msg[1]));
    if (msg[3] != 0) stopping_ = true; // that worker was asked to stop
    if (w_.stop_requested()) stopping_ = true;
    if (msg[1] > 0) receive_failures(source);
    Assignment assign{};
    ++sum_.messages;
    if (!stopping_ && pending_.left() > 0) {
      const Chunk c = pending_.take(chunk_size(size_));
      assign[0] = static_cast<long long>(c.ranges.size());
      for (std::size_t i = 0; i < c.ranges.size(); ++i) {
        assign[1 + 2 * i] = static_cast<long long>(c.ranges[i].first);
        assign[2 + 2 * i] = static_cast<long long>(c.ranges[i].second);
      }
      ++sum_.chunks;
    } else {
      --active_;
    }
    MPI_Send(assign.data(), static_cast<int>(1 + 2 * assign[0]), MPI_LONG_LONG, source, kTagAssign,
             w_.comm);
  }

  // The messages of a worker's failed cases, sent after its report.
  void receive_failures(int source) {
    MPI_Status st;
    MPI_Probe(source, kTagFailures, w_.comm, &st);
    int n = 0;
    MPI_Get_count(&st, MPI_CHAR, &n);
    std::vector<char> buf(static_cast<std::size_t>(n));
    MPI_Recv(buf.data(), n, MPI_CHAR, source, kTagFailures, w_.comm, MPI_STATUS_IGNORE);
    std::vector<io::Failure> got;
    unpack_failures(buf, got);
    record(got);
  }

  void record(std::vector<io::Failure>& got) {
    for (io::Failure& f : got)
      if (failures_.size() < kMaxRecordedFailures) failures_.push_back(std::move(f));
    got.clear();
  }

  // A chunk of rank 0's own (at most 64 cases when there are workers to serve).
  void run_own_chunk() {
    const std::size_t k =
        (size_ == 1) ? chunk_size(1) : std::min<std::size_t>(chunk_size(size_), 64);
    const Chunk c = pending_.take(k);
    ++sum_.chunks;
    const double before = w_.compute_seconds;
    const std::size_t n_before = w_.done + w_.failed;
    const std::size_t finished = w_.run_chunk(c, [&] { serve(false); });
    record(w_.failures);
    if (finished < c.size()) stopping_ = true; // stop request mid-chunk: the rest stays pending
    const std::size_t n = w_.done + w_.failed - n_before;
    if (n > 0) add_cost((w_.compute_seconds - before) / static_cast<double>(n));
  }

  Worker& w_;
  PendingCases pending_;
  ProgressSink* sink_;
  StudySummary& sum_;
  std::vector<io::Failure>& failures_;
  int size_;
  int active_; ///< workers not yet dismissed
  std::size_t others_done_ = 0, others_failed_ = 0;
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
  std::vector<char> pending_failures; // the failed cases of the last chunk
  Chunk chunk;
  while (true) {
    report_msg[3] = w.stop_requested() ? 1 : 0;
    MPI_Send(report_msg, 4, MPI_LONG_LONG, 0, kTagRequest, w.comm);
    if (report_msg[1] > 0)
      MPI_Send(pending_failures.data(), static_cast<int>(pending_failures.size()), MPI_CHAR, 0,
               kTagFailures, w.comm);
    Assignment assign{};
    MPI_Recv(assign.data(), static_cast<int>(assign.size()), MPI_LONG_LONG, 0, kTagAssign, w.comm,
             MPI_STATUS_IGNORE);
    if (assign[0] == 0) break;
    chunk.ranges.clear();
    for (long long i = 0; i < assign[0]; ++i)
      chunk.ranges.emplace_back(
          static_cast<std::size_t>(assign[static_cast<std::size_t>(1 + 2 * i)]),
          static_cast<std::size_t>(assign[static_cast<std::size_t>(2 + 2 * i)]));
    const std::size_t d0 = w.done, f0 = w.failed;
    const double c0 = w.compute_seconds;
    w.run_chunk(chunk, {});
    report_msg[0] = static_cast<long long>(w.done - d0);
    report_msg[1] = static_cast<long long>(w.failed - f0);
    report_msg[2] = static_cast<long long>((w.compute_seconds - c0) * 1e9);
    pending_failures = pack_failures(w.failures);
    w.failures.clear();
  }
}

// ---- the outcome --------------------------------------------------------------

// Everyone agrees on rank 0's counts.
void share_outcome(MPI_Comm comm, StudySummary& sum) {
  long long counts[6] = {
      static_cast<long long>(sum.done),         static_cast<long long>(sum.failed),
      static_cast<long long>(sum.pending),      sum.interrupted ? 1 : 0,
      static_cast<long long>(sum.already_done), static_cast<long long>(sum.already_failed)};
  MPI_Bcast(counts, 6, MPI_LONG_LONG, 0, comm);
  sum.done = static_cast<std::size_t>(counts[0]);
  sum.failed = static_cast<std::size_t>(counts[1]);
  sum.pending = static_cast<std::size_t>(counts[2]);
  sum.interrupted = counts[3] != 0;
  sum.already_done = static_cast<std::size_t>(counts[4]);
  sum.already_failed = static_cast<std::size_t>(counts[5]);
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
        w.close_map();
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

// Rank 0 writes the failures (in case order) into /failures, in place: its
// slots were reserved when the map was created, so a full disk cannot fail
// it; a failed write (a failing device) fails the study with one line, and
// the failed cases it did not record are run again by --resume.
void record_failures(MPI_Comm comm, io::RowWriter& map, std::vector<io::Failure>& failures,
                     StudySummary& sum) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  sum.recorded = sum.already_failed; // (kept where the write fails)
  try {
    collectively(comm, [&] {
      if (rank != 0) return;
      std::sort(failures.begin(), failures.end(),
                [](const io::Failure& a, const io::Failure& b) { return a.index < b.index; });
      try {
        sum.recorded = std::max(sum.recorded, map.write_failures(failures));
      } catch (const std::exception& e) {
        throw std::runtime_error("rank 0: " + std::string(e.what()));
      }
    });
  } catch (const CollectiveFailure& e) {
    if (sum.write_failure.empty())
      sum.write_failure = std::string("recording the failed cases' messages: ") + e.what();
  }
}

} // namespace

StudySummary run_study(MPI_Comm comm, const StudyRequest& req, ProgressSink* sink) {
  io::silence_hdf5_errors();
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const detail::StudyPlan plan = detail::preflight(comm, req);
  io::MapLock lock; // rank 0: one job at a time on the map, until the end
  if (!req.resume) create_map(comm, req, plan, lock);
  std::optional<io::RowWriter> map;
  std::vector<io::Failure> failures; // rank 0: the recorded ones, then this run's
  PendingCases pending = open_map(comm, req, plan.cases->size(), lock, map, failures);

  Worker w(comm, req, *plan.cases, *map, plan.kind);
  StudySummary sum;
  sum.total = plan.cases->size();
  if (rank == 0)
    Master(w, std::move(pending), sink, sum, failures).run();
  else
    pull_work(w);
  share_outcome(comm, sum);
  record_failures(comm, *map, failures, sum);
  close_map(w, sum);
  return sum;
}

} // namespace mdrmap::study
