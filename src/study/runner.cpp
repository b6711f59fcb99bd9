#include "study/runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <optional>
#include <stdexcept>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include <fstream>

#include "core/analytic.hpp"
#include "mdrmap/version.hpp"

namespace mdrmap::study {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr int kTagRequest = 11;
constexpr int kTagAssign = 12;

// ---- collective error handling ---------------------------------------------
// Runs fn on every rank; if it throws anywhere, every rank throws the error
// of the lowest failing rank (InvalidInput stays InvalidInput), so no rank is
// left waiting in a collective call.
template <class F> void collectively(MPI_Comm comm, F fn) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  int kind = 0; // 0 ok, 1 InvalidInput, 2 other
  std::string option, message;
  try {
    fn();
  } catch (const InvalidInput& e) {
    kind = 1, option = e.option(), message = e.what();
  } catch (const std::exception& e) {
    kind = 2, message = e.what();
  }
  int mine = kind ? rank : 1 << 30, first = 0;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == 1 << 30) return;
  auto bcast_string = [&](std::string& s) {
    int n = static_cast<int>(s.size());
    MPI_Bcast(&n, 1, MPI_INT, first, comm);
    s.resize(static_cast<std::size_t>(n));
    MPI_Bcast(s.data(), n, MPI_CHAR, first, comm);
  };
  MPI_Bcast(&kind, 1, MPI_INT, first, comm);
  bcast_string(option);
  bcast_string(message);
  if (kind == 1) throw InvalidInput(option, message);
  throw CollectiveFailure(message);
}

std::string bcast_from_root(MPI_Comm comm, std::string s) {
  int n = static_cast<int>(s.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  s.resize(static_cast<std::size_t>(n));
  MPI_Bcast(s.data(), n, MPI_CHAR, 0, comm);
  return s;
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string parent_dir(const std::string& path) {
  const auto pos = path.find_last_of('/');
  if (pos == std::string::npos) return ".";
  if (pos == 0) return "/";
  return path.substr(0, pos);
}

// First line where two texts differ, for the resume refusal message.
std::string first_difference(const std::string& a, const std::string& b) {
  std::size_t i = 0, line = 1, start = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) {
    if (a[i] == '\n') ++line, start = i + 1;
    ++i;
  }
  auto line_of = [&](const std::string& s) {
    const std::size_t end = s.find('\n', start);
    return s.substr(start, end == std::string::npos ? std::string::npos : end - start);
  };
  return "stored '" + line_of(a) + "', now '" + line_of(b) + "'";
}

// Rank 0's checks of the output path before anything is written.
void check_output(const StudyRequest& req) {
  const std::string& out = req.output;
  if (out.empty()) throw InvalidInput("output", "must name the map file to write");
  struct stat st {};
  const bool exists = ::stat(out.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode))
    throw InvalidInput("output", "'" + out + "' is a directory; give a file name");
  const std::string dir = parent_dir(out);
  struct stat dst {};
  if (::stat(dir.c_str(), &dst) != 0)
    throw InvalidInput("output", "directory '" + dir + "' of '" + out + "' does not exist");
  if (!S_ISDIR(dst.st_mode))
    throw InvalidInput("output", "'" + dir + "' in '" + out + "' is not a directory");
  if (::access(dir.c_str(), W_OK) != 0)
    throw InvalidInput("output", "no permission to write in directory '" + dir + "'");
  if (req.resume && req.overwrite)
    throw InvalidInput("resume", "--resume and --overwrite exclude each other");
  std::string why;
  if (req.resume) {
    if (!exists) throw InvalidInput("resume", "there is no map '" + out + "' to resume");
    if (!io::MapFile::is_map(out, &why))
      throw InvalidInput("resume", "'" + out + "' is " + why + "; refusing to touch it");
    return;
  }
  if (!exists) return;
  if (!req.overwrite)
    throw InvalidInput("output", "'" + out +
                                     "' exists; pass --resume to continue it or --overwrite to "
                                     "replace it");
  if (!io::MapFile::is_map(out, &why))
    throw InvalidInput("overwrite", "'" + out + "' is " + why + "; refusing to replace it");
}

std::string format_bytes(double b) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int u = 0;
  while (b >= 1024.0 && u < 5)
    b /= 1024.0, ++u;
  char buf[48];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", b, units[u]);
  return buf;
}

// Memory this machine can give without swapping (MemAvailable), 0 if unknown.
double available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  const long pages = ::sysconf(_SC_AVPHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

// Cases of the study and the memory one rank needs for them, without
// building them: per case the row (6 doubles), its place in the to-do list,
// its status and rank 0's column buffer at creation; a case list's canonical
// text besides. Counting a case list streams its file.
std::pair<std::size_t, double> study_memory(const StudyConfig& cfg) {
  if (cfg.kind == StudyConfig::Kind::Grid) {
    const std::size_t n = case_count(cfg);
    return {n, 72.0 * static_cast<double>(n)};
  }
  std::ifstream in(cfg.cases_file, std::ios::binary);
  std::size_t lines = 0;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    lines += static_cast<std::size_t>(
        std::count(buf.begin(), buf.begin() + static_cast<long>(in.gcount()), '\n'));
  }
  return {lines, 200.0 * static_cast<double>(lines)}; // unreadable: 0, expand_cases says why
}

// Refuses, before anything is built or written, a study whose cases would
// not fit in the memory of this node (ranks_here ranks each hold them all).
void check_memory(const StudyConfig& cfg, int ranks_here) {
  const auto [n_cases, per_rank] = study_memory(cfg);
  const double need = per_rank * ranks_here;
  const double have = available_memory_bytes();
  if (have > 0.0 && need > 0.5 * have)
    throw InvalidInput("config", "the study has " + std::to_string(n_cases) + " cases; its " +
                                     std::to_string(ranks_here) +
                                     " rank(s) on this node would need about " +
                                     format_bytes(need) + " of memory, more than half of the " +
                                     format_bytes(have) +
                                     " available; split the study or run fewer ranks per node");
}

// Refuses a new map that would not fit on its file system or under the
// file-size limit, before anything is written.
void check_space(const std::string& out, std::uint64_t bytes) {
  const std::string dir = parent_dir(out);
  const std::string need = format_bytes(static_cast<double>(bytes));
  struct rlimit lim {};
  if (::getrlimit(RLIMIT_FSIZE, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY &&
      bytes > static_cast<std::uint64_t>(lim.rlim_cur))
    throw InvalidInput("output", "the map '" + out + "' needs " + need +
                                     " but the file-size limit (ulimit -f) is " +
                                     format_bytes(static_cast<double>(lim.rlim_cur)));
  struct statvfs fs {};
  if (::statvfs(dir.c_str(), &fs) == 0) {
    const double avail = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
    if (static_cast<double>(bytes) > avail)
      throw InvalidInput("output", "the map '" + out + "' needs " + need +
                                       " but the file system of '" + dir + "' has " +
                                       format_bytes(avail) +
                                       " free; free space, or write the map elsewhere");
  }
}

// The message for a failed write: what HDF5 said, and whether the disk is full.
std::string describe_write_failure(const std::string& out, const std::string& what) {
  std::string msg = "writing '" + out + "' failed (" + what + ")";
  struct statvfs fs {};
  if (::statvfs(parent_dir(out).c_str(), &fs) == 0 && fs.f_bavail == 0)
    msg += "; the file system of '" + parent_dir(out) + "' is full";
  return msg;
}

// Compares the study in an existing map with the requested one (rank 0,
// read-only, before the file is opened for writing).
void check_resume_matches(const StudyRequest& req, const std::string& canon) {
  io::silence_hdf5_errors();
  const hid_t f = H5Fopen(req.output.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw InvalidInput("resume", "cannot open '" + req.output + "' to resume it");
  io::Handle file(f, H5Fclose);
  std::string stored;
  try {
    stored = io::read_text_dataset(f, "provenance/config_canonical");
  } catch (const io::H5Error&) {
    throw InvalidInput("resume", "'" + req.output + "' has no readable study definition");
  }
  if (stored != canon)
    throw InvalidInput("config", "differs from the study stored in '" + req.output + "' (" +
                                     first_difference(stored, canon) +
                                     "); resume with the same config and options, or write a new "
                                     "map");
}

void fill_state(io::CaseRow& row, const char* group, const char* when, const State& st) {
  const std::string g = group, w = when;
  row.values[io::field_index(g + "/FN_" + w)] = st.FN;
  row.values[io::field_index(g + "/Fx_" + w)] = st.Fx;
  row.values[io::field_index(g + "/mu_" + w)] = st.mu;
  row.values[io::field_index(g + "/a2_" + w)] = st.a2;
}

// (sim - analytic) / |analytic|; 0 when both vanish (tau = 0: F_x = mu = 0).
double residual(double sim, double an) {
  if (an == 0.0) return sim == 0.0 ? 0.0 : (sim > 0.0 ? 1.0 : -1.0);
  return (sim - an) / std::abs(an);
}

// ---- scheduling ---------------------------------------------------------------

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

} // namespace

io::CaseRow compute_case(const StudyConfig& cfg, const StepRow& s, SolverKind kind,
                         bool timeseries) {
  io::CaseRow row;
  row.values.assign(io::row_fields().size(), 0.0);
  const auto t0 = Clock::now();
  try {
    const Case c = case_for(cfg, s);
    // The analytic estimates exist for every valid case.
    const State an_pre = analytic::stationary(c, s.v);
    const State an_jump = analytic::jump(c, s.v, s.v1);
    const State an_post = analytic::stationary(c, s.v1);
    fill_state(row, "analytic", "pre", an_pre);
    fill_state(row, "analytic", "jump", an_jump);
    fill_state(row, "analytic", "post", an_post);
    const double lim[4] = {analytic::FN_inf(c, s.v), analytic::Fx_inf(c, s.v), analytic::mu_inf(c),
                           analytic::mu_post_drop_limit(c)};
    const char* lim_names[4] = {"FN_inf", "Fx_inf", "mu_inf", "mu_post_drop"};
    for (int i = 0; i < 4; ++i)
      row.values[io::field_index(std::string("analytic/") + lim_names[i])] = lim[i];

    RunResult r = run_case(c, kind, cfg.run.rtol);
    const Series& x = r.series;
    const State jump = x.at(0), post = x.at(x.size() - 1);
    fill_state(row, "results", "pre", x.pre);
    fill_state(row, "results", "jump", jump);
    fill_state(row, "results", "post", post);
    row.values[io::field_index("results/error_estimate")] = r.info.error_estimate;
    const State sims[3] = {x.pre, jump, post}, ans[3] = {an_pre, an_jump, an_post};
    const char* when[3] = {"pre", "jump", "post"};
    for (int i = 0; i < 3; ++i) {
      const State res{residual(sims[i].FN, ans[i].FN), residual(sims[i].Fx, ans[i].Fx),
                      residual(sims[i].mu, ans[i].mu), residual(sims[i].a2, ans[i].a2)};
      fill_state(row, "residuals", when[i], res);
    }
    // distance of the case from the limits: before the step vs v -> inf
    // (eqs. 12-14), just after it vs the start-stop value 3/4 sqrt(d/R)
    const double lim_sim[4] = {x.pre.FN, x.pre.Fx, x.pre.mu, jump.mu};
    for (int i = 0; i < 4; ++i)
      row.values[io::field_index(std::string("residuals/") + lim_names[i])] =
          residual(lim_sim[i], lim[i]);
    for (double v : row.values)
      if (!std::isfinite(v)) throw std::runtime_error("the solver returned a non-finite value");
    if (timeseries) {
      row.t = x.t, row.FN = x.FN, row.Fx = x.Fx, row.mu = x.mu, row.a2 = x.a2;
      for (const auto* vec : {&row.FN, &row.Fx, &row.mu, &row.a2})
        for (double v : *vec)
          if (!std::isfinite(v)) throw std::runtime_error("the solver returned a non-finite value");
    }
    row.status = 1;
  } catch (const std::exception& e) {
    std::fill(row.values.begin(), row.values.end(), 0.0);
    row.t.clear(), row.FN.clear(), row.Fx.clear(), row.mu.clear(), row.a2.clear();
    row.status = -1;
    row.message = e.what();
  }
  row.values[io::field_index("results/wall_seconds")] = seconds_since(t0);
  return row;
}

StudySummary run_study(MPI_Comm comm, const StudyRequest& req, ProgressSink* sink) {
  io::silence_hdf5_errors();
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const StudyConfig& cfg = req.config;
  // ranks sharing this node's memory
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks_here = 1;
  MPI_Comm_size(node, &ranks_here);
  MPI_Comm_free(&node);

  SolverKind kind = SolverKind::Auto;
  std::vector<StepRow> cases;
  std::string canon;
  io::MapSpec spec;
  collectively(comm, [&] {
    kind = parse_solver(cfg.run.solver);
    check_memory(cfg, ranks_here);
    cases = expand_cases(cfg);
    canon = canonical(cfg);
    spec.n_cases = cases.size();
    spec.samples = cfg.run.samples;
    spec.timeseries = cfg.run.timeseries;
    if (cfg.kind == StudyConfig::Kind::Grid) {
      for (const auto& ax : cfg.axes) {
        spec.grid.names.push_back(ax.name);
        spec.grid.values.push_back(ax.values);
        spec.grid.logarithmic.push_back(ax.logarithmic ? 1 : 0);
      }
    }
    if (rank == 0) {
      check_output(req);
      if (req.resume)
        check_resume_matches(req, canon);
      else
        check_space(req.output, io::map_file_bytes(spec, cfg.source_text.size() + canon.size() +
                                                             req.command_line.size()));
    }
  });

  // Create the map (under a temporary name, renamed when complete).
  if (!req.resume) {
    io::Provenance prov;
    prov.program_version = kVersion;
    prov.git_commit = kGitCommit;
    prov.created_utc = bcast_from_root(comm, utc_now());
    prov.command_line = bcast_from_root(comm, req.command_line);
    prov.units = "consistent user units: d, R, a2 lengths; tau, t times; v, v1 length/time; G "
                 "force/length^2; FN, Fx force = G * length^2; mu dimensionless";
    prov.config_text = cfg.source_text;
    prov.config_canonical = canon;
    prov.mpi_size = size;
    const std::string tmp =
        bcast_from_root(comm, req.output + ".tmp-" + std::to_string(static_cast<long>(::getpid())));
    try {
      collectively(comm, [&] { io::MapFile::create(comm, tmp, spec, prov, cases); });
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

  // Where the rows go, and what is left to do: every rank gets rank 0's read.
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
    if (status.size() != cases.size())
      throw InvalidInput("resume", "'" + req.output + "' holds " + std::to_string(status.size()) +
                                       " cases, the study " + std::to_string(cases.size()) +
                                       "; refusing to touch it");
  });
  unsigned long long n_packed = packed.size();
  MPI_Bcast(&n_packed, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  packed.resize(static_cast<std::size_t>(n_packed));
  MPI_Bcast(packed.data(), static_cast<int>(n_packed), MPI_UINT64_T, 0, comm);
  status.resize(cases.size());
  MPI_Bcast(status.data(), static_cast<int>(status.size()), MPI_INT8_T, 0, comm);
  std::optional<io::RowWriter> map;
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
  std::vector<std::size_t> todo;
  std::size_t already_done = 0;
  for (std::size_t i = 0; i < status.size(); ++i) {
    if (status[i] == 0)
      todo.push_back(i);
    else
      ++already_done;
  }

  Worker w{comm, req, cases, todo, *map, kind, 0, 0, 0.0, {}};
  const auto t_start = Clock::now();
  StudySummary sum;
  sum.total = cases.size();
  sum.already_done = already_done;

  if (rank == 0) {
    // Master: answers requests, computes its own small chunks in between.
    std::size_t pos = 0, others_done = 0, others_failed = 0;
    int active = size - 1;
    bool stopping = false;
    double case_seconds = 0.0; // running mean cost of a case, from all reports
    std::size_t cost_samples = 0;
    auto last_report = Clock::now();
    auto chunk_size = [&](int share) {
      const std::size_t remaining = todo.size() - pos;
      // guided self-scheduling: a quarter of the fair share of what is left,
      // capped so that one chunk takes about chunk_seconds
      std::size_t k = (remaining + 4 * static_cast<std::size_t>(share) - 1) /
                      (4 * static_cast<std::size_t>(share));
      if (cost_samples > 0 && case_seconds > 0.0)
        k = std::min<std::size_t>(
            k, static_cast<std::size_t>(std::max(1.0, req.chunk_seconds / case_seconds)));
      else
        k = std::min<std::size_t>(k, 4); // cost unknown yet: start small
      return std::max<std::size_t>(1, std::min(k, remaining));
    };
    auto report = [&](bool final) {
      if (!sink) return;
      if (!final && seconds_since(last_report) < sink->interval) return;
      last_report = Clock::now();
      Progress p;
      p.done = w.done + others_done;
      p.failed = w.failed + others_failed;
      p.todo = todo.size();
      p.total = cases.size();
      p.already_done = already_done;
      p.elapsed = seconds_since(t_start);
      p.final = final;
      sink->report(p);
    };
    auto serve = [&](bool block) {
      int flag = 0;
      MPI_Status st;
      if (block) {
        MPI_Probe(MPI_ANY_SOURCE, kTagRequest, comm, &st);
        flag = 1;
      } else {
        MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, comm, &flag, &st);
      }
      while (flag) {
        long long msg[4];
        MPI_Recv(msg, 4, MPI_LONG_LONG, st.MPI_SOURCE, kTagRequest, comm, MPI_STATUS_IGNORE);
        others_done += static_cast<std::size_t>(msg[0]);
        others_failed += static_cast<std::size_t>(msg[1]);
        if (msg[0] + msg[1] > 0 && msg[2] > 0) {
          const double per =
              static_cast<double>(msg[2]) * 1e-9 / static_cast<double>(msg[0] + msg[1]);
          case_seconds = (case_seconds * static_cast<double>(cost_samples) + per) /
                         static_cast<double>(cost_samples + 1);
          ++cost_samples;
        }
        if (msg[3] != 0) stopping = true; // that worker was asked to stop
        if (w.stop_requested()) stopping = true;
        long long assign[2] = {0, 0};
        ++sum.messages;
        if (!stopping && pos < todo.size()) {
          const std::size_t k = chunk_size(size);
          assign[0] = static_cast<long long>(pos), assign[1] = static_cast<long long>(k);
          pos += k;
          ++sum.chunks;
        } else {
          --active;
        }
        MPI_Send(assign, 2, MPI_LONG_LONG, st.MPI_SOURCE, kTagAssign, comm);
        MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, comm, &flag, &st);
      }
      report(false);
    };
    while (true) {
      if (w.stop_requested()) stopping = true;
      serve(false);
      if (!stopping && pos < todo.size()) {
        const std::size_t k =
            (size == 1) ? chunk_size(1) : std::min<std::size_t>(chunk_size(size), 64);
        const std::size_t p0 = pos;
        pos += k;
        ++sum.chunks;
        const double before = w.compute_seconds;
        const std::size_t n_before = w.done + w.failed;
        const std::size_t finished = w.run_chunk(p0, k, [&] { serve(false); });
        if (finished < k) stopping = true; // stop request mid-chunk: the rest stays pending
        const std::size_t n = w.done + w.failed - n_before;
        if (n > 0) {
          const double per = (w.compute_seconds - before) / static_cast<double>(n);
          case_seconds = (case_seconds * static_cast<double>(cost_samples) + per) /
                         static_cast<double>(cost_samples + 1);
          ++cost_samples;
        }
        continue;
      }
      if (active == 0) break;
      serve(true);
    }
    sum.done = w.done + others_done;
    sum.failed = w.failed + others_failed;
    sum.wall_seconds = seconds_since(t_start);
    sum.pending = todo.size() - sum.done - sum.failed;
    sum.interrupted = sum.pending > 0;
    report(true);
  } else {
    long long report_msg[4] = {0, 0, 0, 0};
    while (true) {
      report_msg[3] = w.stop_requested() ? 1 : 0;
      MPI_Send(report_msg, 4, MPI_LONG_LONG, 0, kTagRequest, comm);
      long long assign[2];
      MPI_Recv(assign, 2, MPI_LONG_LONG, 0, kTagAssign, comm, MPI_STATUS_IGNORE);
      if (assign[1] == 0) break;
      const std::size_t d0 = w.done, f0 = w.failed;
      const double c0 = w.compute_seconds;
      w.run_chunk(static_cast<std::size_t>(assign[0]), static_cast<std::size_t>(assign[1]), {});
      report_msg[0] = static_cast<long long>(w.done - d0);
      report_msg[1] = static_cast<long long>(w.failed - f0);
      report_msg[2] = static_cast<long long>((w.compute_seconds - c0) * 1e9);
    }
  }
  // Everyone agrees on the outcome.
  long long counts[4] = {static_cast<long long>(sum.done), static_cast<long long>(sum.failed),
                         static_cast<long long>(sum.pending), sum.interrupted ? 1 : 0};
  MPI_Bcast(counts, 4, MPI_LONG_LONG, 0, comm);
  sum.done = static_cast<std::size_t>(counts[0]);
  sum.failed = static_cast<std::size_t>(counts[1]);
  sum.pending = static_cast<std::size_t>(counts[2]);
  sum.interrupted = counts[3] != 0;
  MPI_Bcast(&sum.wall_seconds, 1, MPI_DOUBLE, 0, comm);
  // A failed write anywhere fails the study (the lowest failing rank's
  // message); the map is closed all the same, its written rows intact.
  try {
    collectively(comm, [&] {
      if (!w.write_error.empty())
        throw std::runtime_error("rank " + std::to_string(rank) + ": " + w.write_error);
    });
  } catch (const CollectiveFailure& e) {
    sum.write_failure = e.what();
  }
  try {
    collectively(comm, [&] {
      try {
        map->close();
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
  return sum;
}

} // namespace mdrmap::study
