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
#include <sys/stat.h>

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
  if (::stat(dir.c_str(), &dst) != 0 || !S_ISDIR(dst.st_mode))
    throw InvalidInput("output", "directory '" + dir + "' of '" + out + "' does not exist");
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
  const std::vector<Scene>& cases;
  const std::vector<std::size_t>& todo;
  io::MapFile& map;
  SolverKind kind;
  std::size_t done = 0, failed = 0;
  double compute_seconds = 0.0;

  bool stop_requested() const { return req.stop && *req.stop != 0; }

  // Computes todo[pos, pos+count) (stops early on a stop request) and writes
  // the finished rows; returns how many were finished.
  std::size_t run_chunk(std::size_t pos, std::size_t count,
                        const std::function<void()>& between_cases) {
    std::vector<io::CaseRow> rows;
    rows.reserve(count);
    std::size_t finished = 0;
    for (; finished < count; ++finished) {
      if (stop_requested()) break;
      const Scene& s = cases[todo[pos + finished]];
      const auto t0 = Clock::now();
      rows.push_back(compute_case(s, protocol_for(req.config, s), kind, req.config.run.rtol,
                                  map.timeseries()));
      compute_seconds += seconds_since(t0);
      if (rows.back().status == 1)
        ++done;
      else
        ++failed;
      if (between_cases) between_cases();
    }
    // write runs of consecutive case indices
    std::size_t i = 0;
    while (i < rows.size()) {
      std::size_t j = i + 1;
      while (j < rows.size() && todo[pos + j] == todo[pos + j - 1] + 1)
        ++j;
      std::vector<io::CaseRow> run(std::make_move_iterator(rows.begin() + static_cast<long>(i)),
                                   std::make_move_iterator(rows.begin() + static_cast<long>(j)));
      map.write_rows(todo[pos + i], run);
      i = j;
    }
    return finished;
  }
};

} // namespace

io::CaseRow compute_case(const Scene& s, const Protocol& p, SolverKind kind, double rtol,
                         bool timeseries) {
  io::CaseRow row;
  row.values.assign(io::row_fields().size(), 0.0);
  const auto t0 = Clock::now();
  try {
    // The analytic estimates exist for every valid scene.
    const State an_pre = analytic::stationary(s, s.v);
    const State an_jump = analytic::jump(s);
    const State an_post = analytic::stationary(s, s.v1);
    fill_state(row, "analytic", "pre", an_pre);
    fill_state(row, "analytic", "jump", an_jump);
    fill_state(row, "analytic", "post", an_post);
    const double lim[4] = {analytic::FN_inf(s), analytic::Fx_inf(s), analytic::mu_inf(s),
                           analytic::mu_post_drop_limit(s)};
    const char* lim_names[4] = {"FN_inf", "Fx_inf", "mu_inf", "mu_post_drop"};
    for (int i = 0; i < 4; ++i)
      row.values[io::field_index(std::string("analytic/") + lim_names[i])] = lim[i];

    RunResult r = run_case(s, p, kind, rtol);
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
    // distance of the scene from the limits: before the step vs v -> inf
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
  SolverKind kind = SolverKind::Auto;
  std::vector<Scene> cases;
  std::string canon;
  collectively(comm, [&] {
    kind = parse_solver(cfg.run.solver);
    cases = expand_cases(cfg);
    canon = canonical(cfg);
    if (rank == 0) {
      check_output(req);
      if (req.resume) check_resume_matches(req, canon);
    }
  });

  // Create (under a temporary name, renamed when complete) or open the map.
  std::optional<io::MapFile> map;
  if (req.resume) {
    collectively(comm, [&] { map.emplace(io::MapFile::open(comm, req.output)); });
  } else {
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
    io::MapSpec spec;
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
    const std::string tmp =
        bcast_from_root(comm, req.output + ".tmp-" + std::to_string(static_cast<long>(::getpid())));
    try {
      collectively(comm, [&] { map.emplace(io::MapFile::create(comm, tmp, spec, prov, cases)); });
      MPI_Barrier(comm);
      collectively(comm, [&] {
        if (rank == 0 && std::rename(tmp.c_str(), req.output.c_str()) != 0)
          throw std::runtime_error("cannot rename '" + tmp + "' to '" + req.output + "'");
      });
    } catch (...) {
      map.reset();
      if (rank == 0) std::remove(tmp.c_str());
      throw;
    }
  }

  // What is left to do: every rank derives the same list from rank 0's read.
  std::vector<std::int8_t> status;
  collectively(comm, [&] {
    if (rank == 0) status = map->read_status();
  });
  status.resize(cases.size());
  MPI_Bcast(status.data(), static_cast<int>(status.size()), MPI_INT8_T, 0, comm);
  std::vector<std::size_t> todo;
  std::size_t already_done = 0;
  for (std::size_t i = 0; i < status.size(); ++i) {
    if (status[i] == 0)
      todo.push_back(i);
    else
      ++already_done;
  }

  Worker w{comm, req, cases, todo, *map, kind};
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
  collectively(comm, [&] { map->close(); });
  return sum;
}

} // namespace mdrmap::study
