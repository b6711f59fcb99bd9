// End-to-end tests of the mdrmap command line: run the built binary
// (MDRMAP_EXE) and check exit codes, stderr and the exact output format.
#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <spawn.h>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <utility>
#include <vector>

#include "app/csv_output.hpp"
#include "case/case_input.hpp"
#include "case/prony_input.hpp"
#include "core/metrics/analytic.hpp"
#include "core/metrics/events.hpp"
#include "core/metrics/stationary.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "core/solvers/dispatch.hpp"
#include "core/solvers/exact.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;

#ifndef MDRMAP_EXE
#error "MDRMAP_EXE must name the mdrmap binary"
#endif

struct Outcome {
  int code = -1; ///< exit status; -1 if the process did not exit normally (crash)
  std::string out, err;
};

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

/// A fresh directory, removed with everything in it at the end of the test.
class TempDir {
public:
  TempDir() {
    const char* base = std::getenv("TMPDIR");
    std::string templ = std::string(base && *base ? base : "/tmp") + "/mdrmap_cli_XXXXXX";
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (!::mkdtemp(buf.data())) throw std::runtime_error("mkdtemp failed");
    path_ = buf.data();
  }
  ~TempDir() {
    std::error_code ec;
    // A read-only subdirectory must be made writable again to be removed.
    for (auto it = fs::recursive_directory_iterator(path_, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
      if (it->is_directory(ec)) fs::permissions(it->path(), fs::perms::owner_all, ec);
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

/// Runs MDRMAP_EXE with `args`, capturing stdout and stderr through files.
/// With limit_seconds > 0, a run still going after that long is killed and
/// reported as code -1 with "timed out" in err (a hang fails the test
/// instead of blocking it).
Outcome run_mdrmap(const std::vector<std::string>& args, int limit_seconds = 0) {
  TempDir io;
  const std::string out_path = (io.path() / "stdout").string();
  const std::string err_path = (io.path() / "stderr").string();

  std::vector<std::string> argv_store{MDRMAP_EXE};
  argv_store.insert(argv_store.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_store)
    argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, out_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, MDRMAP_EXE, &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  Outcome r;
  if (rc != 0) {
    r.err = "posix_spawn failed";
    return r;
  }
  int status = 0;
  bool timed_out = false;
  if (limit_seconds > 0) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(limit_seconds);
    while (::waitpid(pid, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        ::kill(pid, SIGKILL);
        timed_out = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10)); // poll for the exit
    }
  }
  if (limit_seconds <= 0 || timed_out)
    while (::waitpid(pid, &status, 0) < 0) {
    }
  r.code = WIFEXITED(status) && !timed_out ? WEXITSTATUS(status) : -1;
  r.out = read_file(out_path);
  r.err = read_file(err_path);
  if (timed_out) r.err += "timed out after " + std::to_string(limit_seconds) + " s";
  return r;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) {
      lines.push_back(text.substr(pos));
      break;
    }
    lines.push_back(text.substr(pos, nl - pos));
    pos = nl + 1;
  }
  return lines;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep))
    parts.push_back(cur);
  return parts;
}

/// Strict number parse for the test's reading of the CSV.
double to_double(const std::string& s) {
  std::size_t used = 0;
  const double x = std::stod(s, &used);
  if (used != s.size()) throw std::runtime_error("not a number: " + s);
  return x;
}

/// "key=value" fields of a comment line after its prefix.
std::map<std::string, std::string> fields(const std::string& line) {
  std::map<std::string, std::string> kv;
  for (const auto& tok : split(line, ' ')) {
    const auto eq = tok.find('=');
    if (eq != std::string::npos) kv[tok.substr(0, eq)] = tok.substr(eq + 1);
  }
  return kv;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

/// The parsed output of `mdrmap simulate`.
struct Parsed {
  std::vector<std::string> comments;
  std::string header;
  std::map<std::string, std::string> run, case_line, scales, pre;
  std::vector<std::map<std::string, std::string>> events; ///< one per segment
  std::optional<double> error_vs_exact;                   ///< or error_vs_reference under load
  std::map<std::string, std::string> reference;           ///< the error_vs_reference line's fields
  bool load = false;                                      ///< the load-control header
  std::vector<std::vector<double>> rows;                  ///< t, segment, FN, Fx, mu, a2 [, d, a1]
};

/// Column of each quantity in a parsed row (kD, kA1: under load control only).
enum Col { kT = 0, kSegment = 1, kFN = 2, kFx = 3, kMu = 4, kA2 = 5, kD = 6, kA1 = 7 };

/// The `# case` line as the parameter table makes it: every case parameter
/// by name (of the loading group only the one given: F0 under load, d at
/// fixed depth), the history, the spacing, the sampling parameters, a0 under
/// load, zeta0.
std::regex case_line_regex(bool load) {
  // the parabola's parameters (the other profiles' are not shown), the loading given
  auto given = [&](const mdrmap::ParamSpec& p) {
    return p.applies_to(mdrmap::Profile::of<mdrmap::Parabola>()) &&
           (!p.one_of || (std::string(p.name) == "F0") == load);
  };
  std::string re = "^# case";
  for (const auto& p : mdrmap::case_parameters())
    if (p.part != mdrmap::Part::Sampling && given(p))
      re += std::string(p.name) == "aT" ? std::string(R"(( aT=\S+)?)") // only where it shifts
                                        : std::string(" ") + p.name + R"(=\S+)";
  // a spectrum where there are terms, the temperature where --T gave aT
  re += R"(( prony=[^,\s:]+:[^,\s:]+(,[^,\s:]+:[^,\s:]+)*)?( T=\S+ wlf=[^:\s]+:[^:\s]+:[^:\s]+)?)";
  re += R"( history=\S+ spacing=(linear|log))";
  for (const auto& p : mdrmap::case_parameters())
    if (p.part == mdrmap::Part::Sampling) re += std::string(" ") + p.name + R"(=\S+)";
  return std::regex(re + (load ? R"( a0=\S+)" : "") + R"( zeta0=\S+$)");
}

const char* const kEventKeys[] = {
    "k",         "t",        "w_before",     "w_after",     "mu_before", "mu_after",  "mu_max",
    "t_max",     "slip_max", "mu_min",       "t_min",       "slip_min",  "mu_peak",   "t_peak",
    "slip_peak", "mu_end",   "mu_ss_before", "mu_ss_after", "D_c",       "overshoot", "a",
    "a_minus_b", "b",        "healing"};

std::regex event_regex() {
  std::string re = "^# event";
  for (const char* key : kEventKeys)
    re += std::string(" ") + key + (std::string(key) == "k" ? R"(=\d+)" : R"(=\S+)");
  // (where D_c is undefined, why)
  return std::regex(
      re + R"(( D_c_undefined=(no_change|hold|no_transient|peak_at_end|overshoot|no_decay))?$)");
}

/// Checks the exact structure of the simulate contract (docs/design.md,
/// "Contracts"; src/app/csv_output.hpp) and returns the parsed content.
/// Fails the test (non-fatally) on deviations.
Parsed parse_output(const std::string& text) {
  Parsed p;
  EXPECT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "output must end with a newline";
  const auto lines = split_lines(text);
  std::size_t i = 0;
  while (i < lines.size() && starts_with(lines[i], "#"))
    p.comments.push_back(lines[i++]);
  if (i < lines.size()) p.header = lines[i++];
  p.load = p.header == "t,segment,FN,Fx,mu,a2,d,a1";
  if (!p.load) {
    EXPECT_EQ(p.header, "t,segment,FN,Fx,mu,a2");
  }

  EXPECT_GE(p.comments.size(), 5U); // version, case, scales, at least one event, pre
  if (p.comments.size() < 5) return p;
  const std::regex first(R"(^# mdrmap \S+ \(\S+\) simulate solver=\S+ rtol=\S+ error_estimate=\S+ )"
                         R"(cells_per_a1=\S+ elements=-?\d+ steps=-?\d+ element_updates=-?\d+ )"
                         R"(root_solves=-?\d+ wall_seconds=\S+$)");
  EXPECT_TRUE(std::regex_match(p.comments[0], first)) << p.comments[0];
  p.run = fields(p.comments[0]);
  EXPECT_TRUE(std::regex_match(p.comments[1], case_line_regex(p.load))) << p.comments[1];
  p.case_line = fields(p.comments[1]);
  const std::regex scales(R"(^# scales length=\S+ depth=\S+ force=\S+ friction=\S+ time=\S+$)");
  EXPECT_TRUE(std::regex_match(p.comments[2], scales)) << p.comments[2];
  p.scales = fields(p.comments[2]);
  std::size_t c = 3;
  if (starts_with(p.comments[c], "# error_vs_exact=")) {
    EXPECT_TRUE(std::regex_match(p.comments[c], std::regex(R"(^# error_vs_exact=\S+$)")))
        << p.comments[c];
    p.error_vs_exact = to_double(fields(p.comments[c]).at("error_vs_exact"));
    ++c;
  } else if (starts_with(p.comments[c], "# error_vs_reference=")) {
    const std::regex ref(R"(^# error_vs_reference=\S+ reference=\S+ reference_rtol=\S+$)");
    EXPECT_TRUE(p.load || p.case_line.count("prony"))
        << "a reference other than exact under load control or with a spectrum only";
    EXPECT_TRUE(std::regex_match(p.comments[c], ref)) << p.comments[c];
    p.reference = fields(p.comments[c]);
    p.error_vs_exact = to_double(p.reference.at("error_vs_reference"));
    ++c;
  }
  for (; c + 1 < p.comments.size(); ++c) {
    EXPECT_TRUE(std::regex_match(p.comments[c], event_regex())) << p.comments[c];
    p.events.push_back(fields(p.comments[c]));
    EXPECT_EQ(p.events.back()["k"], std::to_string(p.events.size() - 1)) << p.comments[c];
  }
  const std::regex pre(p.load ? R"(^# pre FN=\S+ Fx=\S+ mu=\S+ a2=\S+ d=\S+ a1=\S+$)"
                              : R"(^# pre FN=\S+ Fx=\S+ mu=\S+ a2=\S+$)");
  EXPECT_TRUE(std::regex_match(p.comments.back(), pre))
      << "the last comment line must be '# pre ...': " << p.comments.back();
  p.pre = fields(p.comments.back());

  for (; i < lines.size(); ++i) {
    const auto cells = split(lines[i], ',');
    EXPECT_EQ(cells.size(), p.load ? 8U : 6U) << "row " << lines[i];
    std::vector<double> row;
    for (const auto& cell : cells) {
      const double x = to_double(cell);
      EXPECT_TRUE(std::isfinite(x)) << "row " << lines[i];
      row.push_back(x);
    }
    p.rows.push_back(row);
  }
  return p;
}

/// The history of the `# case` line: (w, T) per segment.
std::vector<std::pair<double, double>> history_of(const Parsed& p) {
  std::vector<std::pair<double, double>> h;
  for (const auto& seg : split(p.case_line.at("history"), ',')) {
    const auto wt = split(seg, ':');
    EXPECT_EQ(wt.size(), 2U) << seg;
    if (wt.size() == 2) h.emplace_back(to_double(wt[0]), to_double(wt[1]));
  }
  return h;
}

/// Checks the number of rows, segment 0 everywhere and t_k = k T / (N-1).
void expect_time_grid(const Parsed& p, long n, double t_end) {
  ASSERT_EQ(p.rows.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(p.rows.front()[kT], 0.0);
  EXPECT_EQ(p.rows.back()[kT], t_end);
  for (std::size_t k = 0; k < p.rows.size(); ++k) {
    const double tk = t_end * static_cast<double>(k) / static_cast<double>(n - 1);
    EXPECT_LE(std::abs(p.rows[k][kT] - tk), 1e-15 * t_end) << "k = " << k;
    EXPECT_EQ(p.rows[k][kSegment], 0.0) << "k = " << k;
  }
}

/// Compares the CSV rows and the pre line with a library series, per column
/// relative to the column's largest magnitude; the segment column exactly.
void expect_matches_series(const Parsed& p, const mdrmap::Series& ref, double tol) {
  ASSERT_EQ(p.rows.size(), ref.size());
  const std::vector<std::pair<Col, const std::vector<double>*>> cols{
      {kT, &ref.t}, {kFN, &ref.FN}, {kFx, &ref.Fx}, {kMu, &ref.mu}, {kA2, &ref.a2}};
  for (const auto& [c, col] : cols) {
    double scale = 0.0;
    for (const double x : *col)
      scale = std::max(scale, std::abs(x));
    for (std::size_t k = 0; k < ref.size(); ++k)
      EXPECT_LE(std::abs(p.rows[k][c] - (*col)[k]), tol * scale)
          << "column " << c << " row " << k << ": " << p.rows[k][c] << " vs " << (*col)[k];
  }
  for (std::size_t k = 0; k < ref.size(); ++k)
    EXPECT_EQ(p.rows[k][kSegment], static_cast<double>(ref.segment[k])) << "row " << k;
  const mdrmap::State& pre = ref.pre;
  EXPECT_LE(std::abs(to_double(p.pre.at("FN")) - pre.FN), tol * std::abs(pre.FN));
  EXPECT_LE(std::abs(to_double(p.pre.at("Fx")) - pre.Fx), tol * std::abs(pre.Fx));
  EXPECT_LE(std::abs(to_double(p.pre.at("mu")) - pre.mu), tol * std::abs(pre.mu));
  EXPECT_LE(std::abs(to_double(p.pre.at("a2")) - pre.a2), tol * std::abs(pre.a2));
}

const std::vector<std::string> kOptionNames{
    "--d",       "--F0",          "--R",       "--tau",  "--v",      "--v1",     "--G",   "--t-end",
    "--history", "--log-decades", "--spacing", "--rtol", "--solver", "--output", "--help"};

/// The seed's one-step case as the command line gives it (--v1 shorthand).
struct Step {
  double d, R, tau, v, v1, G = 1.0;
};

std::string num(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

std::vector<std::string> simulate_args(const Step& s) {
  return {"simulate", "--d",    num(s.d), "--R",     num(s.R), "--tau", num(s.tau),
          "--v",      num(s.v), "--v1",   num(s.v1), "--G",    num(s.G)};
}

/// The case the shorthand stands for (t_end 0: the default window).
mdrmap::Case step_case(const Step& s, long samples, double t_end = 0.0) {
  return mdrmap::step_case(s.d, s.R, s.tau, s.v, s.v1, s.G, t_end, samples);
}

double default_window(const Step& s) {
  return mdrmap::default_step_duration(s.d, s.R, s.tau, s.v, s.v1);
}

// A scene whose transient (drop v = 10 -> v1 = 0.1) lasts about a third of the
// default window, so the samples cover both the root-solving part and the end.
Step transient_scene() {
  return Step{0.1, 10.0, 1.0, 10.0, 0.1};
}

// ---------------------------------------------------------------------------

TEST(cli, TopHelpListsSubcommands) {
  const Outcome r = run_mdrmap({"--help"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("simulate"), std::string::npos);
  EXPECT_NE(r.out.find("study"), std::string::npos);
  EXPECT_NE(r.out.find("--version"), std::string::npos);
}

TEST(cli, TopVersion) {
  const Outcome r = run_mdrmap({"--version"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(std::regex_match(r.out, std::regex(R"(mdrmap \d+\.\d+\.\d+\S* \(\S+\)\n)"))) << r.out;
  // The same version string heads the simulate output.
  const Outcome sim = run_mdrmap({"simulate", "--d", "0.1", "--R", "10", "--tau", "1", "--v", "2",
                                  "--v1", "0.5", "--samples", "2"});
  ASSERT_EQ(sim.code, 0) << sim.err;
  const std::string version_line = r.out.substr(0, r.out.size() - 1);
  EXPECT_TRUE(starts_with(sim.out, "# " + version_line + " simulate ")) << sim.out;
}

TEST(cli, TopBadSubcommandsExit2WithOneLine) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {}, {"simulat"}, {"--frobnicate"}, {"study", "--config", "x.ini"}}) {
    const Outcome r = run_mdrmap(args);
    EXPECT_EQ(r.code, 2) << (args.empty() ? "(no args)" : args[0]);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.back(), '\n');
  }
  const Outcome study = run_mdrmap({"study"});
  EXPECT_EQ(study.code, 2);
  EXPECT_NE(study.err.find("--config"), std::string::npos) << study.err;
}

TEST(cli, SimulateHelpMentionsEveryOption) {
  const Outcome r = run_mdrmap({"simulate", "--help-all"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "");
  for (const auto& opt : kOptionNames)
    EXPECT_NE(r.out.find(opt + " "), std::string::npos) << opt;
  for (const char* word : {"t,segment,FN,Fx,mu,a2", "# case", "# event", "# pre", "nan", "Example",
                           "Exit codes", "Default: 201", "Default: 1e-4", "Default: auto",
                           "Default: linear", "6 tau", "Kelvin", "mu = Fx/FN", "W1:T1,W2:T2"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
  // --help wins over missing or bad options, and `mdrmap help simulate` is the same text.
  EXPECT_EQ(run_mdrmap({"simulate", "--d", "abc", "--help-all"}).out, r.out);
  EXPECT_EQ(run_mdrmap({"help", "simulate"}).out, r.out);
}

TEST(cli, SimulateDefaultRunHasExactStructure) {
  const Outcome r =
      run_mdrmap({"simulate", "--d", "0.1", "--R", "10", "--tau", "1", "--v", "2", "--v1", "0.5"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const Parsed p = parse_output(r.out);
  ASSERT_EQ(p.comments.size(), 5U) << "auto runs the exact solver: no error_vs_exact line";
  EXPECT_FALSE(p.error_vs_exact.has_value());
  EXPECT_EQ(p.run.at("solver"), "exact");
  EXPECT_EQ(to_double(p.run.at("rtol")), 1e-4);
  EXPECT_GE(to_double(p.run.at("wall_seconds")), 0.0);
  EXPECT_LE(to_double(p.run.at("error_estimate")), 1e-4);
  EXPECT_EQ(to_double(p.case_line.at("d")), 0.1);
  EXPECT_EQ(to_double(p.case_line.at("R")), 10.0);
  EXPECT_EQ(to_double(p.case_line.at("tau")), 1.0);
  EXPECT_EQ(to_double(p.case_line.at("v")), 2.0);
  EXPECT_EQ(to_double(p.case_line.at("G")), 1.0);
  // one segment: v1 = 0.5 over the default window 6 tau
  EXPECT_EQ(history_of(p), (std::vector<std::pair<double, double>>{{0.5, 6.0}}));
  EXPECT_EQ(p.case_line.at("spacing"), "linear");
  EXPECT_EQ(p.case_line.at("samples"), "201");
  EXPECT_NEAR(to_double(p.case_line.at("zeta0")), 2.0, 1e-15); // v tau / sqrt(R d) = 2 / 1
  // the scales: a1 = sqrt(R d) = 1, d, 16/3 G a1^3 / R, a1 / R, tau
  EXPECT_NEAR(to_double(p.scales.at("length")), 1.0, 1e-15);
  EXPECT_EQ(to_double(p.scales.at("depth")), 0.1);
  EXPECT_NEAR(to_double(p.scales.at("force")), 16.0 / 30.0, 1e-15);
  EXPECT_NEAR(to_double(p.scales.at("friction")), 0.1, 1e-16);
  EXPECT_EQ(to_double(p.scales.at("time")), 1.0);
  ASSERT_EQ(p.events.size(), 1U);
  EXPECT_EQ(to_double(p.events[0].at("t")), 0.0);
  EXPECT_EQ(to_double(p.events[0].at("w_before")), 2.0);
  EXPECT_EQ(to_double(p.events[0].at("w_after")), 0.5);
  expect_time_grid(p, 201, 6.0);
}

TEST(cli, SimulateValuesEqualTheLibrary) {
  const Step s = transient_scene();
  const Outcome r = run_mdrmap(simulate_args(s));
  ASSERT_EQ(r.code, 0) << r.err;
  const Parsed p = parse_output(r.out);
  const mdrmap::Case c = step_case(s, 201);
  expect_time_grid(p, 201, default_window(s));
  EXPECT_GT(std::stol(p.run.at("root_solves")), 0L) << "scene should have a transient";
  // Same call as the command (auto at the default rtol): identical to the last digit printed.
  expect_matches_series(p, mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-4).series, 1e-15);
  // And within rtol of the tightly solved continuum solution.
  expect_matches_series(p, mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-12).series, 1e-4);
}

TEST(cli, SimulateExplicitOptionsAreHonoured) {
  const Outcome r =
      run_mdrmap({"simulate",  "--d=0.2", "--R",    "5",    "--tau",    "0.5",     "--v",
                  "3",         "--v1",    "1",      "--G",  "2.5",      "--t-end", "2",
                  "--samples", "11",      "--rtol", "1e-6", "--solver", "exact"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Parsed p = parse_output(r.out);
  EXPECT_EQ(p.run.at("solver"), "exact");
  EXPECT_EQ(to_double(p.run.at("rtol")), 1e-6);
  EXPECT_EQ(to_double(p.case_line.at("G")), 2.5);
  expect_time_grid(p, 11, 2.0);
  const Step s{0.2, 5, 0.5, 3, 1, 2.5};
  expect_matches_series(
      p, mdrmap::run_exact(mdrmap::CheckedCase(step_case(s, 11, 2.0)), 1e-6).series, 1e-15);
}

// wall_seconds is the only field that may differ between two runs.
std::string without_wall_time(const std::string& text) {
  return std::regex_replace(text, std::regex(R"(wall_seconds=\S+)"), "wall_seconds=X");
}

TEST(cli, SimulateOutputFileEqualsStdout) {
  TempDir dir;
  const fs::path out = dir.path() / "step.csv";
  auto args = simulate_args(transient_scene());
  const Outcome to_stdout = run_mdrmap(args);
  ASSERT_EQ(to_stdout.code, 0) << to_stdout.err;

  args.insert(args.end(), {"--output", out.string()});
  const Outcome to_file = run_mdrmap(args);
  ASSERT_EQ(to_file.code, 0) << to_file.err;
  EXPECT_EQ(to_file.out, "");
  EXPECT_EQ(to_file.err, "");
  EXPECT_EQ(without_wall_time(read_file(out)), without_wall_time(to_stdout.out));

  // A second run replaces the file, and no temporary is left behind.
  write_file(out, "old content\n");
  const Outcome again = run_mdrmap(args);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(without_wall_time(read_file(out)), without_wall_time(to_stdout.out));
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir.path()))
    names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"step.csv"});

  // "-" is stdout.
  args.back() = "-";
  const Outcome dash = run_mdrmap(args);
  ASSERT_EQ(dash.code, 0) << dash.err;
  EXPECT_EQ(without_wall_time(dash.out), without_wall_time(to_stdout.out));
}

// --- --output onto links and special files ------------------------------------

/// Runs that must not wait for anything: a generous bound for a loaded
/// machine (each takes well under a second).
constexpr int kNoHangSeconds = 120;

bool is_link_to(const fs::path& p, const fs::path& target) {
  std::error_code ec;
  return fs::is_symlink(fs::symlink_status(p, ec)) && fs::read_symlink(p, ec) == target;
}

std::vector<std::string> small_run(const std::vector<std::string>& extra = {}) {
  auto args = simulate_args(transient_scene());
  args.insert(args.end(), {"--samples", "5"});
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Exit 2 with one line naming --output.
void expect_output_refused(const Outcome& r, const std::string& words) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(starts_with(r.err, "mdrmap simulate: error: --output: ")) << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

// A symbolic link to a regular file: the file it names is replaced (a
// temporary beside it, renamed over it); the link stays a link.
TEST(cli, SimulateOutputLinkToAFileReplacesTheFile) {
  TempDir dir;
  fs::create_directories(dir.path() / "data");
  const fs::path target = dir.path() / "data" / "step.csv";
  write_file(target, "old content\n");
  const fs::path link = dir.path() / "link.csv";
  fs::create_symlink("data/step.csv", link);
  const Outcome ref = run_mdrmap(small_run());
  ASSERT_EQ(ref.code, 0) << ref.err;
  const Outcome r = run_mdrmap(small_run({"--output", link.string()}), kNoHangSeconds);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(is_link_to(link, "data/step.csv"));
  EXPECT_EQ(without_wall_time(read_file(target)), without_wall_time(ref.out));
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"data", "link.csv"}));
  EXPECT_EQ(names_in(dir.path() / "data"), std::vector<std::string>{"step.csv"});
}

// Special files are written, never replaced: a FIFO with its reader, a link
// to a device (/dev/null) or to standard output (/proc/self/fd/1, what
// /dev/stdout is). A FIFO without a reader and a link to nothing are refused
// at once (exit 2, one line) instead of waiting forever or replacing them.
TEST(cli, SimulateOutputWritesThroughSpecialFiles) {
  TempDir dir;
  const Outcome ref = run_mdrmap(small_run());
  ASSERT_EQ(ref.code, 0) << ref.err;
  const std::string expected = without_wall_time(ref.out);

  const fs::path fifo = dir.path() / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  {
    SCOPED_TRACE("a FIFO with a reader");
    const int rd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(rd, 0) << std::strerror(errno);
    const Outcome r = run_mdrmap(small_run({"--output", fifo.string()}), kNoHangSeconds);
    std::string got; // (the output is far below a pipe's capacity)
    char buf[4096];
    for (ssize_t n = 0; (n = ::read(rd, buf, sizeof buf)) > 0;)
      got.append(buf, static_cast<std::size_t>(n));
    ::close(rd);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(without_wall_time(got), expected);
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
  }
  {
    SCOPED_TRACE("a FIFO without a reader");
    expect_output_refused(run_mdrmap(small_run({"--output", fifo.string()}), kNoHangSeconds),
                          "without a reader");
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
  }
  const fs::path null_link = dir.path() / "null";
  fs::create_symlink("/dev/null", null_link);
  {
    SCOPED_TRACE("a link to /dev/null");
    const Outcome r = run_mdrmap(small_run({"--output", null_link.string()}), kNoHangSeconds);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_TRUE(is_link_to(null_link, "/dev/null"));
  }
  const fs::path out_link = dir.path() / "stdout";
  fs::create_symlink("/proc/self/fd/1", out_link);
  {
    SCOPED_TRACE("a link to /proc/self/fd/1 (standard output: here a file)");
    const Outcome r = run_mdrmap(small_run({"--output", out_link.string()}), kNoHangSeconds);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(without_wall_time(r.out), expected);
    EXPECT_TRUE(is_link_to(out_link, "/proc/self/fd/1"));
  }
  const fs::path dangling = dir.path() / "dangling";
  fs::create_symlink("missing.csv", dangling);
  {
    SCOPED_TRACE("a link to nothing");
    expect_output_refused(run_mdrmap(small_run({"--output", dangling.string()}), kNoHangSeconds),
                          "symbolic link to nothing");
    EXPECT_TRUE(is_link_to(dangling, "missing.csv"));
  }
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"dangling", "fifo", "null", "stdout"}));
}

// A device node (as root: mknod n c 1 3, /dev/null's numbers) is written to,
// not replaced by a regular file.
TEST(cli, SimulateOutputDeviceNodeIsWrittenNotReplaced) {
  if (::geteuid() != 0) GTEST_SKIP() << "mknod of a character device needs root";
  TempDir dir;
  const fs::path node = dir.path() / "n";
  if (::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
    GTEST_SKIP() << "mknod failed (" << std::strerror(errno) << "): no CAP_MKNOD here";
  const Outcome r = run_mdrmap(small_run({"--output", node.string()}), kNoHangSeconds);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  struct stat st {};
  ASSERT_EQ(::lstat(node.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
  EXPECT_EQ(st.st_rdev, makedev(1, 3));
  EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"n"});
}

struct EdgeScene {
  const char* label;
  Step scene;
};

TEST(cli, SimulateEdgeScenesAreValid) {
  const std::vector<EdgeScene> cases{
      {"tau = 0 (elastic)", {0.1, 10.0, 0.0, 2.0, 0.5, 1.0}},
      {"tau = 0, v1 = 0", {0.1, 10.0, 0.0, 2.0, 0.0, 1.0}},
      {"v1 = 0 (stop)", {0.1, 10.0, 1.0, 2.0, 0.0, 1.0}},
      {"v1 > v (speed-up)", {0.1, 10.0, 1.0, 2.0, 5.0, 1.0}},
      {"v1 = v (no step)", {0.1, 10.0, 1.0, 2.0, 2.0, 1.0}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.label);
    auto args = simulate_args(c.scene);
    args.insert(args.end(), {"--samples", "41"});
    const Outcome r = run_mdrmap(args);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const Parsed p = parse_output(r.out);
    const double t_end = default_window(c.scene);
    EXPECT_EQ(history_of(p), (std::vector<std::pair<double, double>>{{c.scene.v1, t_end}}));
    expect_time_grid(p, 41, t_end);
    expect_matches_series(
        p, mdrmap::run_exact(mdrmap::CheckedCase(step_case(c.scene, 41)), 1e-4).series, 1e-15);
    if (c.scene.v1 == c.scene.v) { // nothing changes: every row is the state before the step
      for (const auto& row : p.rows) {
        EXPECT_NEAR(row[kFN], to_double(p.pre.at("FN")), 1e-14 * std::abs(row[kFN]));
        EXPECT_NEAR(row[kA2], to_double(p.pre.at("a2")), 1e-14 * std::abs(row[kA2]));
      }
    }
  }
}

// The discrete solvers may still be in development: the option must be
// accepted, and the run must either succeed with the full structure (plus the
// error_vs_exact line) or fail cleanly with exit 1, never crash.
TEST(cli, SimulateOtherSolversAreAcceptedAndNeverCrash) {
  TempDir dir;
  const fs::path out = dir.path() / "out.csv";
  for (const char* solver : {"row", "baseline"}) {
    SCOPED_TRACE(solver);
    write_file(out, "keep me\n");
    const Outcome r = run_mdrmap({"simulate", "--d", "0.1", "--R", "10", "--tau", "1", "--v", "2",
                                  "--v1", "0.5", "--samples", "5", "--rtol", "1e-2", "--solver",
                                  solver, "--output", out.string()});
    ASSERT_TRUE(r.code == 0 || r.code == 1) << "exit " << r.code << ": " << r.err;
    if (r.code == 0) {
      const Parsed p = parse_output(read_file(out));
      EXPECT_EQ(p.comments.size(), 6U);
      EXPECT_TRUE(p.error_vs_exact.has_value());
      expect_time_grid(p, 5, 6.0);
    } else {
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(starts_with(r.err, "mdrmap simulate: error: ")) << r.err;
      EXPECT_EQ(read_file(out), "keep me\n") << "a failed run must not touch --output";
    }
  }
}

// Valid but absurd scales (found by the sanitizer build: an out-of-range
// float-to-integer conversion that hung the old Kelvin row, a NaN element
// count in the old baseline): each solver either answers without NaN or
// refuses with one line (the rows: outside their number range, exit 2).
TEST(cli, SimulateAbsurdScalesNeverHangOrProduceNaN) {
  struct Row {
    std::vector<std::string> scene;
    const char* solver;
    bool must_fail;
  };
  const std::vector<Row> rows = {
      {{"--d", "1e-3", "--R", "1", "--tau", "1", "--v", "1e-300", "--v1", "1e300"}, "row", true},
      {{"--d", "1e-3", "--R", "1", "--tau", "0", "--v", "1", "--v1", "1e300"}, "row", true},
      {{"--d", "1e-3", "--R", "1", "--tau", "1e-300", "--v", "1e-300", "--v1", "1e300"},
       "baseline",
       true},
      {{"--d", "1e-3", "--R", "1", "--tau", "1", "--v", "1e-300", "--v1", "1e300"}, "auto", false},
      {{"--d", "1e-3", "--R", "1", "--tau", "1", "--v", "1e-300", "--v1", "1e300"}, "exact", false},
  };
  for (const Row& row : rows) {
    std::vector<std::string> args = {"simulate"};
    args.insert(args.end(), row.scene.begin(), row.scene.end());
    args.insert(args.end(), {"--samples", "5", "--solver", row.solver});
    SCOPED_TRACE(row.solver + std::string(" ") + row.scene[7] + " -> " + row.scene[9]);
    const Outcome r = run_mdrmap(args);
    if (row.must_fail) {
      ASSERT_EQ(r.code, 2) << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(starts_with(r.err, "mdrmap simulate: error: --")) << r.err;
      EXPECT_NE(r.err.find("the element row"), std::string::npos) << r.err;
    } else {
      ASSERT_EQ(r.code, 0) << r.err;
      const Parsed p = parse_output(r.out);
      EXPECT_EQ(p.rows.size(), 5U);
      for (const auto& v : p.rows)
        for (double x : v)
          EXPECT_TRUE(std::isfinite(x));
    }
  }
}

// Holds near the largest double (issue 23, class 7): the sample time j T
// overflowed, and 200 rows of inf and nan came out with exit 0.
TEST(cli, SimulateHoldsNearTheLargestDoubleGiveFiniteRows) {
  const Outcome r = run_mdrmap({"simulate", "--d", "1e-3", "--R", "1", "--tau", "1", "--v", "1",
                                "--history", "0:1e306,1:1"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Parsed p = parse_output(r.out);
  ASSERT_EQ(p.rows.size(), 402U);
  for (const auto& v : p.rows)
    for (double x : v)
      EXPECT_TRUE(std::isfinite(x));
  EXPECT_EQ(p.rows[200][kT], 1e306);
}

// A case past its work budget, or one the solver cannot resolve to rtol,
// fails with one line and exit 1 (issue 23, class 3): the fixed-step baseline
// at a1/dx = 4000 over 160 contact widths needs ~4e11 element updates (it ran
// for many minutes); the row's estimate cannot go below its rounding floor
// (the case was reported done with an estimate above rtol).
TEST(cli, SimulateCasesPastTheirBudgetOrRtolFailWithOneLine) {
  const std::vector<std::string> scene = {"simulate", "--d", "1e-3", "--R",       "1", "--tau",
                                          "1",        "--v", "1",    "--samples", "5", "--history"};
  struct Row {
    std::vector<std::string> extra;
    const char* says;
  };
  const std::vector<Row> rows = {
      {{"1:5", "--solver", "baseline", "--rtol", "1e-4"},
       "baseline needs more than its work budget of 1e+09 work units (an element's sub-step"},
      {{"0.1:0.1,0:0.1,1:0.1", "--solver", "row", "--rtol", "1e-15"}, "stays above rtol"},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(row.says);
    std::vector<std::string> args = scene;
    args.insert(args.end(), row.extra.begin(), row.extra.end());
    const Outcome r = run_mdrmap(args, 240); // (a hang fails instead of blocking)
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(row.says), std::string::npos) << r.err;
    if (row.extra[2] == "baseline") { // the budget names the option to change
      EXPECT_NE(r.err.find("--rtol"), std::string::npos) << r.err;
    }
  }
}

// --- Bad input: exit 2, one line naming the option, no output touched ------

constexpr const char* kDrop = "\x01drop";

struct BadCase {
  const char* label;
  std::vector<std::pair<std::string, std::string>> set; ///< option -> value (kDrop removes it)
  std::vector<std::string> extra;                       ///< raw tokens appended
  const char* option;                                   ///< must appear as "--option:"
  bool touches_output = false;                          ///< the row sets --output itself
  bool needs_non_root = false;                          ///< permission checks do not fail for root
};

TEST(cli, SimulateBadInputsExit2WithOneLineNamingTheOption) {
  TempDir dir;
  const fs::path existing = dir.path() / "existing.csv";
  const std::string sentinel = "# previous result\nt,segment,FN,Fx,mu,a2\n0,0,1,2,3,4\n";
  const fs::path readonly_dir = dir.path() / "readonly";
  fs::create_directory(readonly_dir);
  fs::permissions(readonly_dir, fs::perms::owner_read | fs::perms::owner_exec);
  const fs::path plain_file = dir.path() / "plain";
  write_file(plain_file, "x");
  const fs::path missing_dir = dir.path() / "no_such_dir";
  // relaxation spectra from files (issue 19): each fault on its line
  const auto prony_file = [&](const char* name, const std::string& text) {
    write_file(dir.path() / name, text);
    return (dir.path() / name).string();
  };
  const std::string no_header = prony_file("no_header.csv", "1,2\n");
  const std::string only_header = prony_file("only_header.csv", "# spectrum\nG,tau\n\n");
  const std::string bad_tau = prony_file("bad_tau.csv", "G,tau\n1,2\n# comment\n3,-4\n");
  const std::string half_term = prony_file("half_term.csv", "G,tau\n1,\n");
  const std::string three_values = prony_file("three_values.csv", "G,tau\n1,2,3\n");
  std::string many = "G,tau\n", many_terms;
  for (int k = 0; k < 33; ++k) {
    many += "1,2\n";
    many_terms += std::string(k ? "," : "") + "1:2";
  }
  const std::string too_many = prony_file("too_many.csv", many);

  const std::vector<BadCase> cases{
      {"d = 0", {{"d", "0"}}, {}, "d"},
      {"d < 0", {{"d", "-1"}}, {}, "d"},
      {"R = 0", {{"R", "0"}}, {}, "R"},
      {"R < 0", {{"R", "-10"}}, {}, "R"},
      {"G = 0", {{"G", "0"}}, {}, "G"},
      {"G < 0", {{"G", "-1"}}, {}, "G"},
      {"v = 0", {{"v", "0"}}, {}, "v"},
      {"v < 0", {{"v", "-2"}}, {}, "v"},
      {"tau < 0", {{"tau", "-1"}}, {}, "tau"},
      {"v1 < 0", {{"v1", "-0.5"}}, {}, "v1"},
      {"d = nan", {{"d", "nan"}}, {}, "d"},
      {"tau = nan", {{"tau", "NaN"}}, {}, "tau"},
      {"R = inf", {{"R", "inf"}}, {}, "R"},
      {"v1 = inf", {{"v1", "infinity"}}, {}, "v1"},
      {"v = -inf", {{"v", "-inf"}}, {}, "v"},
      {"d = 1e999 (overflow)", {{"d", "1e999"}}, {}, "d"},
      {"d not a number", {{"d", "abc"}}, {}, "d"},
      {"d trailing junk", {{"d", "0.1mm"}}, {}, "d"},
      {"d empty", {{"d", ""}}, {}, "d"},
      {"samples = 1", {{"samples", "1"}}, {}, "samples"},
      {"samples = 0", {{"samples", "0"}}, {}, "samples"},
      {"samples = -3", {{"samples", "-3"}}, {}, "samples"},
      {"samples = 2.5", {{"samples", "2.5"}}, {}, "samples"},
      {"samples = 1e99", {{"samples", "1e99"}}, {}, "samples"},
      {"samples = abc", {{"samples", "abc"}}, {}, "samples"},
      {"samples too many", {{"samples", "100000001"}}, {}, "samples"},
      {"samples beyond long", {{"samples", "99999999999999999999999"}}, {}, "samples"},
      {"t-end = 0", {{"t-end", "0"}}, {}, "t-end"},
      {"t-end < 0", {{"t-end", "-1"}}, {}, "t-end"},
      {"t-end = nan", {{"t-end", "nan"}}, {}, "t-end"},
      {"rtol = 0", {{"rtol", "0"}}, {}, "rtol"},
      {"rtol = 0.2", {{"rtol", "0.2"}}, {}, "rtol"},
      {"rtol < 0", {{"rtol", "-1"}}, {}, "rtol"},
      {"rtol = nan", {{"rtol", "nan"}}, {}, "rtol"},
      {"unknown solver", {{"solver", "fast"}}, {}, "solver"},
      {"unknown option", {}, {"--speed", "3"}, "speed"},
      {"wrong case option", {}, {"--g", "3"}, "g"},
      {"F0 = 0", {{"d", kDrop}, {"F0", "0"}}, {}, "F0"},
      {"F0 < 0", {{"d", kDrop}, {"F0", "-1"}}, {}, "F0"},
      {"F0 = nan", {{"d", kDrop}, {"F0", "nan"}}, {}, "F0"},
      {"F0 = inf", {{"d", kDrop}, {"F0", "inf"}}, {}, "F0"},
      {"F0 not a number", {{"d", kDrop}, {"F0", "1N"}}, {}, "F0"},
      {"d = 0 beside F0", {{"d", "0"}, {"F0", "1"}}, {}, "d"},
      {"F0 = -1 beside d", {{"F0", "-1"}}, {}, "F0"},
      {"F0 twice", {{"d", kDrop}, {"F0", "1"}}, {"--F0", "2"}, "F0"},
      // the old spelling FN of F0: its errors name it as given
      {"FN = 0", {{"d", kDrop}, {"FN", "0"}}, {}, "FN"},
      {"FN not a number", {{"d", kDrop}, {"FN", "1N"}}, {}, "FN"},
      {"FN twice", {{"d", kDrop}, {"FN", "1"}}, {"--FN", "2"}, "FN"},
      {"fn (case)", {}, {"--fn", "1"}, "fn"},
      {"missing --v1", {{"v1", kDrop}}, {}, "v1"},
      {"--d twice", {}, {"--d", "0.2"}, "d"},
      {"--v1 and --history", {}, {"--history", "0.5:6"}, "history"},
      {"--t-end with --history", {{"v1", kDrop}}, {"--history", "0.5:6", "--t-end", "6"}, "t-end"},
      {"--history twice", {{"v1", kDrop}}, {"--history", "1:1", "--history", "2:2"}, "history"},
      {"spacing unknown", {{"spacing", "lin"}}, {}, "spacing"},
      {"log-decades without log spacing", {{"log-decades", "3"}}, {}, "log-decades"},
      {"log-decades = 0", {{"spacing", "log"}, {"log-decades", "0"}}, {}, "log-decades"},
      {"log-decades > 300", {{"spacing", "log"}, {"log-decades", "301"}}, {}, "log-decades"},
      {"samples x segments too many",
       {{"v1", kDrop}, {"samples", "60000000"}},
       {"--history", "1:1,2:2"},
       "samples"},
      {"--d without value", {{"d", kDrop}}, {"--d"}, "d"},
      // derived scales out of range (issue 23, class 7): the option that sets them
      {"contact radius below 1e-75", {{"R", "1e-300"}}, {}, "d"},
      {"contact radius above 1e75", {{"R", "1e300"}, {"d", "1e10"}}, {}, "d"},
      {"w tau / a overflows by a segment's W",
       {{"v1", kDrop}, {"d", "1e-60"}, {"R", "1e-60"}},
       {"--history", "1e300:1"},
       "history"},
      {"w tau overflows by a segment's W",
       {{"v1", kDrop}, {"d", "1"}, {"R", "1"}},
       {"--history", "1e308:1"},
       "history"},
      {"slip W T overflows", {{"v1", kDrop}}, {"--history", "1e300:1e300"}, "history"},
      {"under load a segment's W shrinks the contact below 1e-75",
       {{"v1", kDrop}, {"d", kDrop}, {"F0", "5.333333333333333"}, {"R", "1"}},
       {"--history", "5e307:1"},
       "history"},
      {"output into a missing directory",
       {{"output", (missing_dir / "out.csv").string()}},
       {},
       "output",
       true},
      {"output into a read-only directory",
       {{"output", (readonly_dir / "out.csv").string()}},
       {},
       "output",
       true,
       true},
      {"output below a regular file",
       {{"output", (plain_file / "out.csv").string()}},
       {},
       "output",
       true},
      {"output is a directory", {{"output", dir.path().string()}}, {}, "output", true},
      // indenter profiles (issue 21): each profile's parameters, in range, with it only
      {"profile unknown", {{"profile", "ellipsoid"}}, {}, "profile"},
      {"--beta with the parabola", {{"beta", "10"}}, {}, "beta"},
      {"--n with the parabola", {{"n", "2"}}, {}, "n"},
      {"--R with a cone", {{"profile", "cone"}, {"beta", "10"}}, {}, "R"},
      {"--A with a cone", {{"profile", "cone"}, {"beta", "10"}, {"R", kDrop}, {"A", "1"}}, {}, "A"},
      {"cone without --beta", {{"profile", "cone"}, {"R", kDrop}}, {}, "beta"},
      {"beta = 0", {{"profile", "cone"}, {"R", kDrop}, {"beta", "0"}}, {}, "beta"},
      {"beta = 90", {{"profile", "cone"}, {"R", kDrop}, {"beta", "90"}}, {}, "beta"},
      {"beta < 0", {{"profile", "cone"}, {"R", kDrop}, {"beta", "-10"}}, {}, "beta"},
      {"n < 1", {{"profile", "power"}, {"R", kDrop}, {"n", "0.5"}, {"A", "1"}}, {}, "n"},
      {"A = 0", {{"profile", "power"}, {"R", kDrop}, {"n", "2"}, {"A", "0"}}, {}, "A"},
      {"A < 0", {{"profile", "power"}, {"R", kDrop}, {"n", "2"}, {"A", "-1"}}, {}, "A"},
      {"power without --A", {{"profile", "power"}, {"R", kDrop}, {"n", "2"}}, {}, "A"},
      {"--R with power", {{"profile", "power"}, {"n", "2"}, {"A", "1"}}, {}, "R"},
      {"a cone on the continuum solver",
       {{"profile", "cone"}, {"R", kDrop}, {"beta", "10"}, {"solver", "exact"}},
       {},
       "profile"},
      {"the retired mdr solver", {{"solver", "mdr"}}, {}, "solver"},
      {"an unknown solver", {{"solver", "spectrum_baseline"}}, {}, "solver"},
      // relaxation spectra and the temperature shift (issue 19)
      {"prony without --G", {{"G", kDrop}, {"prony", "1:1"}}, {}, "G"},
      {"prony-file without --G",
       {{"G", kDrop}, {"prony-file", prony_file("good.csv", "G,tau\n1,2\n3,40\n")}},
       {},
       "G"},
      {"prony G = 0", {{"prony", "0:1"}}, {}, "prony"},
      {"prony G < 0", {{"prony", "1:1,-2:10"}}, {}, "prony"},
      {"prony tau = 0", {{"prony", "1:0"}}, {}, "prony"},
      {"prony tau < 0", {{"prony", "1:-1"}}, {}, "prony"},
      {"prony G = nan", {{"prony", "nan:1"}}, {}, "prony"},
      {"prony tau = inf", {{"prony", "1:inf"}}, {}, "prony"},
      {"prony tau overflows", {{"prony", "1:1e999"}}, {}, "prony"},
      {"prony term without its time", {{"prony", "5:"}}, {}, "prony"},
      {"prony term without its modulus", {{"prony", ":2"}}, {}, "prony"},
      {"prony term without ':'", {{"prony", "1:1,5"}}, {}, "prony"},
      {"prony term with two ':'", {{"prony", "1:1:1"}}, {}, "prony"},
      {"prony empty term", {{"prony", "1:1,,2:2"}}, {}, "prony"},
      {"prony empty", {{"prony", ""}}, {}, "prony"},
      {"prony not a number", {{"prony", "1:2s"}}, {}, "prony"},
      {"prony 33 terms", {{"prony", many_terms}}, {}, "prony"},
      {"prony and prony-file", {{"prony", "1:1"}, {"prony-file", bad_tau}}, {}, "prony-file"},
      {"prony-file missing", {{"prony-file", (missing_dir / "p.csv").string()}}, {}, "prony-file"},
      {"prony-file is a directory", {{"prony-file", dir.path().string()}}, {}, "prony-file"},
      {"prony-file without header", {{"prony-file", no_header}}, {}, "prony-file"},
      {"prony-file without terms", {{"prony-file", only_header}}, {}, "prony-file"},
      {"prony-file tau < 0", {{"prony-file", bad_tau}}, {}, "prony-file"},
      {"prony-file half a term", {{"prony-file", half_term}}, {}, "prony-file"},
      {"prony-file three values", {{"prony-file", three_values}}, {}, "prony-file"},
      {"prony-file 33 terms", {{"prony-file", too_many}}, {}, "prony-file"},
      {"aT = 0", {{"aT", "0"}}, {}, "aT"},
      {"aT = inf", {{"aT", "inf"}}, {}, "aT"},
      {"aT shifts a time beyond a double", {{"aT", "1e300"}, {"prony", "1:1e10"}}, {}, "aT"},
      {"aT shifts tau beyond a double", {{"aT", "1e300"}, {"tau", "1e10"}}, {}, "aT"},
      {"T without wlf", {{"T", "20"}}, {}, "T"},
      {"wlf without T", {{"wlf", "17.44:51.6:0"}}, {}, "wlf"},
      {"T with aT", {{"T", "20"}, {"wlf", "17.44:51.6:0"}, {"aT", "2"}}, {}, "T"},
      {"T = TREF - C2", {{"T", "-50"}, {"wlf", "10:50:0"}}, {}, "T"},
      {"T below TREF - C2", {{"T", "-60"}, {"wlf", "17.44:51.6:0"}}, {}, "T"},
      {"T = nan", {{"T", "nan"}, {"wlf", "17.44:51.6:0"}}, {}, "T"},
      {"T shifts a time beyond a double",
       {{"T", "-0.99"}, {"wlf", "1:1:0"}, {"prony", "1:1e250"}},
       {},
       "T"},
      {"T gives an aT beyond a double", {{"T", "-49.99"}, {"wlf", "17.44:50:0"}}, {}, "T"},
      {"wlf with two constants", {{"T", "20"}, {"wlf", "17.44:51.6"}}, {}, "wlf"},
      {"wlf C1 = 0", {{"T", "20"}, {"wlf", "0:51.6:0"}}, {}, "wlf"},
      {"wlf C2 < 0", {{"T", "20"}, {"wlf", "17.44:-51.6:0"}}, {}, "wlf"},
      {"wlf TREF not a number", {{"T", "20"}, {"wlf", "17.44:51.6:room"}}, {}, "wlf"},
      {"wlf TREF = inf", {{"T", "20"}, {"wlf", "17.44:51.6:inf"}}, {}, "wlf"},
      {"T in F", {{"T", "20F"}, {"wlf", "17.44:51.6:0"}}, {}, "T"},
      {"T below absolute zero", {{"T", "-300C"}, {"wlf", "17.44:51.6:0C"}}, {}, "T"},
      {"T below 0K", {{"T", "-1K"}, {"wlf", "17.44:51.6:0C"}}, {}, "T"},
      {"wlf TREF below 0K", {{"T", "20C"}, {"wlf", "17.44:51.6:-5K"}}, {}, "wlf"},
      {"T more than 12 decades from TREF", {{"T", "25C"}, {"wlf", "17.44:51.6:-100C"}}, {}, "T"},
      {"T 25 against TREF 298.15K", {{"T", "25"}, {"wlf", "8.86:101.6:298.15K"}}, {}, "T"},
      // a bare number whose pair reads as the other scale: a shift the 12 decades miss
      {"T 308.15 against TREF 25C", {{"T", "308.15"}, {"wlf", "8.86:101.6:25C"}}, {}, "T"},
      {"T 35C against TREF 298.15", {{"T", "35C"}, {"wlf", "8.86:101.6:298.15"}}, {}, "T"},
      {"T 308.15 against TREF 25, both bare", {{"T", "308.15"}, {"wlf", "8.86:101.6:25"}}, {}, "T"},
      {"allow-large-shift without T",
       {{"aT", "2"}, {"allow-large-shift", "true"}},
       {},
       "allow-large-shift"},
      {"allow-large-shift not a flag",
       {{"T", "20"}, {"wlf", "17.44:51.6:0"}, {"allow-large-shift", "maybe"}},
       {},
       "allow-large-shift"},
      // a spectrum the parser takes, on a solver that cannot: one line naming prony
      {"prony on the exact solver", {{"prony", "1:1,2:10"}, {"solver", "exact"}}, {}, "prony"},
      {"prony-file on the Kelvin solvers",
       {{"prony-file", prony_file("good.csv", "G,tau\n1,2\n3,40\n")}, {"solver", "exact"}},
       {},
       "prony"},
      {"output empty", {{"output", ""}}, {}, "output", true},
  };
  ASSERT_GE(cases.size(), 20U);

  const std::vector<std::pair<std::string, std::string>> base{
      {"d", "0.1"}, {"R", "10"}, {"tau", "1"}, {"G", "1"}, {"v", "2"}, {"v1", "0.5"}};

  auto listing = [&] {
    std::set<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir.path()))
      names.insert(e.path().string());
    return names;
  };

  for (const auto& c : cases) {
    SCOPED_TRACE(c.label);
    if (c.needs_non_root && ::geteuid() == 0) continue; // root ignores directory permissions

    // Each row twice: printing to stdout, and with --output onto an existing file.
    for (const bool with_output : {false, true}) {
      if (with_output && c.touches_output) continue;
      std::vector<std::pair<std::string, std::string>> opts = base;
      for (const auto& [key, value] : c.set) {
        bool found = false;
        for (auto& kv : opts)
          if (kv.first == key) {
            kv.second = value;
            found = true;
          }
        if (!found) opts.emplace_back(key, value);
      }
      if (with_output) opts.emplace_back("output", existing.string());
      std::vector<std::string> args{"simulate"};
      for (const auto& [key, value] : opts)
        if (value != kDrop) args.insert(args.end(), {"--" + key, value});
      args.insert(args.end(), c.extra.begin(), c.extra.end());

      write_file(existing, sentinel);
      const auto before = listing();
      const Outcome r = run_mdrmap(args);

      EXPECT_EQ(r.code, 2) << r.err;
      EXPECT_EQ(r.out, "");
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << r.err;
      EXPECT_TRUE(starts_with(r.err, "mdrmap simulate: error: --" + std::string(c.option) + ": "))
          << r.err;
      EXPECT_EQ(read_file(existing), sentinel) << "an existing output file must stay unchanged";
      EXPECT_EQ(listing(), before) << "a failed run must not create files";
      EXPECT_FALSE(fs::exists(missing_dir));
    }
  }
}

// --- Relaxation spectra and the temperature shift (issue 19) -------------------

using mdrmap::cases::OptionTexts;

OptionTexts spectrum_texts(OptionTexts extra) {
  OptionTexts t{{"d", "0.1"}, {"R", "10"}, {"tau", "0"}, {"G", "1"}, {"v", "1"}, {"v1", "2"}};
  for (auto& [k, v] : extra)
    if (v == kDrop)
      t.erase(k);
    else
      t[k] = v;
  return t;
}

TEST(cli, SpectrumInputIsReadIntoTheRheology) {
  const auto in = mdrmap::cases::read_case_input(
      spectrum_texts({{"prony", "1:0.01, 2.5:1,0.5:1e4"}, {"G", "0.1"}}));
  const mdrmap::Rheology& r = in.c.rheology;
  ASSERT_EQ(r.branches.size(), 3U);
  EXPECT_EQ(r.branches[0].G, 1.0);
  EXPECT_EQ(r.branches[0].tau, 0.01);
  EXPECT_EQ(r.branches[1].G, 2.5);
  EXPECT_EQ(r.branches[2].tau, 1e4);
  EXPECT_EQ(r.G, 0.1);
  EXPECT_EQ(r.tau, 0.0);
  EXPECT_EQ(r.aT, 1.0);
  EXPECT_FALSE(in.temperature);
  // the default window: six times the longest relaxation time (tau = 0 here)
  EXPECT_EQ(in.c.history.segments.at(0).T, 6e4);
  // 32 terms are allowed, and the printed spectrum reads back to the same doubles
  std::string text;
  for (int k = 1; k <= 32; ++k)
    text += (k > 1 ? "," : "") + std::to_string(k) + ":" + std::to_string(0.1 / k);
  const auto b = mdrmap::cases::parse_prony(text);
  ASSERT_EQ(b.size(), 32U);
  const auto again = mdrmap::cases::parse_prony(mdrmap::cases::format_prony(b));
  for (std::size_t k = 0; k < b.size(); ++k) {
    EXPECT_EQ(again[k].G, b[k].G);
    EXPECT_EQ(again[k].tau, b[k].tau);
  }
}

// A spectrum runs end to end, at fixed depth and under load: auto picks the
// row, whose stationary start is the closed form's (mu_ss_before) within
// rtol, and exact (Kelvin only) refuses it in one line naming prony.
TEST(cli, SpectrumCasesRunAtDepthAndUnderLoad) {
  for (const char* loading : {"--d", "--F0"}) {
    SCOPED_TRACE(loading);
    const std::vector<std::string> base = {
        "simulate",      loading,     "0.1",     "--R",    "10",  "--tau", "0",
        "--G",           "1",         "--prony", "9:1",    "--v", "0.1",   "--history",
        "1:2,0:5,0.1:2", "--samples", "5",       "--rtol", "1e-3"};
    const Outcome r = run_mdrmap(base);
    ASSERT_EQ(r.code, 0) << r.err;
    const Parsed p = parse_output(r.out);
    EXPECT_EQ(p.run.at("solver"), "row");
    ASSERT_EQ(p.events.size(), 3U);
    const double mu = to_double(p.pre.at("mu")), ss = to_double(p.events[0].at("mu_ss_before"));
    EXPECT_NEAR(mu, ss, 1e-3 * ss);
    if (std::string(loading) == "--F0") continue; // (exact refuses the loading first)
    auto args = base;
    args.insert(args.end(), {"--solver", "exact"});
    const Outcome refused = run_mdrmap(args);
    EXPECT_EQ(refused.code, 2) << refused.err;
    EXPECT_TRUE(starts_with(refused.err, "mdrmap simulate: error: --prony: solver exact "))
        << refused.err;
    EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  }
}

TEST(cli, SpectrumFileEqualsTheOption) {
  TempDir dir;
  const fs::path f = dir.path() / "spectrum.csv";
  write_file(f, "# a spectrum\r\n G , tau \r\n\r\n1,0.01\r\n  # between terms\n2.5 , 1\n0.5,1e4");
  const auto a = mdrmap::cases::read_case_input(spectrum_texts({{"prony-file", f.string()}}));
  const auto b =
      mdrmap::cases::read_case_input(spectrum_texts({{"prony", "1:0.01,2.5:1,0.5:1e4"}}));
  ASSERT_EQ(a.c.rheology.branches.size(), 3U);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(a.c.rheology.branches[k].G, b.c.rheology.branches[k].G);
    EXPECT_EQ(a.c.rheology.branches[k].tau, b.c.rheology.branches[k].tau);
  }
  // a fault names the file and its line
  write_file(f, "G,tau\n1,2\n\n# comment\n3,0\n");
  try {
    mdrmap::cases::read_case_input(spectrum_texts({{"prony-file", f.string()}}));
    FAIL() << "a zero time was taken";
  } catch (const mdrmap::InvalidInput& e) {
    EXPECT_EQ(e.option(), "prony-file");
    EXPECT_TRUE(starts_with(e.what(), f.string() + ":5: column 2 (tau): tau2 must be")) << e.what();
  }
}

// Issue 33: a spectrum file's columns by name, in any order: G, E (G = E /
// (4 (1 - nu^2)), --nu 0.5 by default) or g normalised by '# G0 = ...' (then
// G = G0 (1 - sum g), and --G is not given).
TEST(cli, SpectrumFileColumnsByName) {
  TempDir dir;
  const auto file = [&](const char* name, const std::string& text) {
    const fs::path p = dir.path() / name;
    write_file(p, text);
    return p.string();
  };
  const auto read = [](OptionTexts t) {
    return mdrmap::cases::read_case_input(spectrum_texts(t)).c;
  };
  const auto same_terms = [](const mdrmap::Case& a, const std::vector<mdrmap::Branch>& b) {
    ASSERT_EQ(a.rheology.branches.size(), b.size());
    for (std::size_t k = 0; k < b.size(); ++k) {
      EXPECT_DOUBLE_EQ(a.rheology.branches[k].G, b[k].G) << k;
      EXPECT_EQ(a.rheology.branches[k].tau, b[k].tau) << k;
    }
  };
  same_terms(read({{"prony-file", file("tauG.csv", "tau,G\n0.5,1\n20,3\n")}}), {{1, 0.5}, {3, 20}});
  same_terms(read({{"prony-file", file("E.csv", "# DMA\nE , tau\n3,0.5\n9,20\n")}}),
             {{1, 0.5}, {3, 20}});
  same_terms(read({{"prony-file", file("E.csv", "E,tau\n3,0.5\n")}, {"nu", "0"}}), {{0.75, 0.5}});
  const mdrmap::Case g =
      read({{"G", kDrop}, {"prony-file", file("g.csv", "# G0 = 5\ntau,g\n0.5,0.2\n20,0.6\n")}});
  same_terms(g, {{1, 0.5}, {3, 20}});
  EXPECT_DOUBLE_EQ(g.rheology.G, 1.0);
  const mdrmap::Case g_E =
      read({{"G", kDrop}, {"prony-file", file("gE.csv", "# E0 = 15\ng,tau\n0.2,0.5\n")}});
  same_terms(g_E, {{1, 0.5}});
  EXPECT_DOUBLE_EQ(g_E.rheology.G, 4.0);
  struct Bad {
    OptionTexts texts;
    std::string option, said;
  };
  const std::vector<Bad> bad = {
      {{{"prony-file", file("x.csv", "G,tau,x\n1,2\n")}}, "prony-file", "x.csv:1: header column 3"},
      {{{"prony-file", file("GE.csv", "G,E\n1,2\n")}}, "prony-file", "a second modulus column"},
      {{{"prony-file", file("notau.csv", "E\n1\n")}}, "prony-file", "has no tau column"},
      {{{"prony-file", file("badE.csv", "tau,E\n1,2\n1,-3\n")}},
       "prony-file",
       "badE.csv:3: column 2 (E): E2 must be a finite number > 0, got -3"},
      {{{"prony-file", file("row.csv", "G,tau\n1,2,3\n")}}, "prony-file", "row.csv:2: term 1"},
      {{{"G", kDrop}, {"prony-file", file("noG0.csv", "g,tau\n0.5,1\n")}},
       "prony-file",
       "needs a line '# G0 = VALUE'"},
      {{{"G", kDrop}, {"prony-file", file("sum.csv", "# G0 = 1\ng,tau\n0.5,1\n0.5,2\n")}},
       "prony-file",
       "sum to 1"},
      {{{"G", kDrop}, {"prony-file", file("g1.csv", "# G0 = 1\ng,tau\n1.5,1\n")}},
       "prony-file",
       "g1.csv:3: column 1 (g): g1 must be a finite number > 0 and < 1"},
      {{{"prony-file", file("g2.csv", "# G0 = 1\ng,tau\n0.5,1\n")}}, "G", "drop --G"},
      {{{"prony-file", file("G0.csv", "# G0 = 1\nG,tau\n0.5,1\n")}},
       "prony-file",
       "G0.csv:1: G0 applies to normalised moduli"},
      {{{"prony-file", file("G0bad.csv", "# G0 = -1\ng,tau\n0.5,1\n")}},
       "prony-file",
       "G0bad.csv:1: G0 must be a finite number > 0"},
      {{{"prony-file", file("E3.csv", "E,tau\n3,1\n")}, {"nu", "0.6"}}, "nu", "<= 0.5"},
      {{{"prony-file", file("G3.csv", "G,tau\n3,1\n")}, {"nu", "0.3"}}, "nu", "Young's moduli"},
      {{{"prony", "1:1"}, {"nu", "0.3"}}, "nu", "applies to a spectrum file"},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.said);
    try {
      read(b.texts);
      ADD_FAILURE() << "taken";
    } catch (const mdrmap::InvalidInput& e) {
      EXPECT_EQ(e.option(), b.option) << e.what();
      EXPECT_NE(std::string(e.what()).find(b.said), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

// Issue 32: a spectrum file is a small regular file. A FIFO (no writer: its
// read would wait forever) and a device (/dev/zero: endless) are refused at
// once, like --output's; so are a file past 1 MiB and a line past 4096
// characters; a UTF-8 BOM (a spreadsheet's "CSV UTF-8") is read; a bad field
// is echoed cut to 60 characters.
TEST(cli, PronyFileIsASmallRegularFile) {
  TempDir dir;
  const fs::path fifo = dir.path() / "spectrum.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  const auto refused = [](const std::string& file, const std::string& what) {
    SCOPED_TRACE(file);
    const Outcome r = run_mdrmap(
        {"stationary", "--d", "0.1", "--R", "10", "--tau", "0", "--v", "1", "--prony-file", file},
        20);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(starts_with(r.err, "mdrmap stationary: error: --prony-file: ")) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_LT(r.err.size(), 300U) << r.err;
  };
  refused(fifo.string(), "a FIFO");
  refused("/dev/zero", "a character device");
  const fs::path big = dir.path() / "big.csv";
  write_file(big, "G,tau\n" + std::string(2U << 20, '#') + "\n1,2\n");
  refused(big.string(), "larger than 1 MiB");
  const fs::path long_line = dir.path() / "long_line.csv";
  write_file(long_line, "G,tau\n1," + std::string(5000, '9') + "\n");
  refused(long_line.string(), "longer than 4096 characters");
  const fs::path long_field = dir.path() / "long_field.csv";
  write_file(long_field, "G,tau\n1," + std::string(1000, 'x') + "\n");
  refused(long_field.string(), "'" + std::string(60, 'x') + "...' (1000 characters)");

  const fs::path bom = dir.path() / "bom.csv";
  write_file(bom, "\xEF\xBB\xBFG,tau\r\n1,0.01\r\n2.5,1\r\n");
  const auto a = mdrmap::cases::read_case_input(spectrum_texts({{"prony-file", bom.string()}}));
  const auto b = mdrmap::cases::read_case_input(spectrum_texts({{"prony", "1:0.01,2.5:1"}}));
  ASSERT_EQ(a.c.rheology.branches.size(), 2U);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(a.c.rheology.branches[k].G, b.c.rheology.branches[k].G);
    EXPECT_EQ(a.c.rheology.branches[k].tau, b.c.rheology.branches[k].tau);
  }
}

TEST(cli, TemperatureGivesTheWlfShift) {
  const auto in = mdrmap::cases::read_case_input(
      spectrum_texts({{"tau", "1"}, {"T", "40"}, {"wlf", "17.44:51.6:-10"}}));
  ASSERT_TRUE(in.temperature);
  EXPECT_EQ(in.temperature->T, 40.0);
  EXPECT_EQ(in.temperature->wlf.C1, 17.44);
  EXPECT_EQ(in.temperature->wlf.C2, 51.6);
  EXPECT_EQ(in.temperature->wlf.Tref, -10.0);
  const double aT = std::pow(10.0, -17.44 * 50.0 / (51.6 + 50.0));
  EXPECT_NEAR(in.c.rheology.aT, aT, 1e-15 * aT);
  // at TREF no shift
  const auto ref = mdrmap::cases::read_case_input(
      spectrum_texts({{"tau", "1"}, {"T", "-10"}, {"wlf", "17.44:51.6:-10"}}));
  EXPECT_EQ(ref.c.rheology.aT, 1.0);
  // the default window is six shifted times
  EXPECT_NEAR(in.c.history.segments.at(0).T, 6.0 * aT, 1e-15 * aT);
}

// Issue 33: a bare temperature whose pair reads as the other scale is a
// Kelvin/Celsius mix-up (--T 308.15 against TREF 25C: 35C taken as 308.15C,
// log10 aT = -6.5, within the 12 decades): refused naming --T, saying to give
// the unit; with the unit the same temperature gives the shift at 35C.
TEST(cli, BareTemperatureOfTheOtherScaleIsRefused) {
  const auto message = [](const std::string& T, const std::string& wlf) {
    try {
      mdrmap::cases::read_case_input(spectrum_texts({{"tau", "1"}, {"T", T}, {"wlf", wlf}}));
    } catch (const mdrmap::InvalidInput& e) {
      EXPECT_EQ(e.option(), "T") << e.what();
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("308.15", "8.86:101.6:25C").find("give T its unit (308.15K or 308.15C)"),
            std::string::npos);
  EXPECT_NE(message("35C", "8.86:101.6:298.15").find("give TREF its unit"), std::string::npos);
  EXPECT_NE(message("308.15", "8.86:101.6:25").find("give T and TREF their units"),
            std::string::npos);
  const std::string hot = message("308.15", "8.86:101.6:25C");
  EXPECT_EQ(hot.find('\n'), std::string::npos) << hot;
  // within 150 degrees of TREF a bare number is read as before (no refusal)
  EXPECT_EQ(message("140", "8.86:101.6:25C"), "");
  EXPECT_EQ(message("0", "8.86:101.6:25"), "");
  // with its unit the temperature is converted: 308.15K is 35C
  for (const char* T : {"308.15K", "35C", "35"}) {
    SCOPED_TRACE(T);
    const auto in = mdrmap::cases::read_case_input(
        spectrum_texts({{"tau", "1"}, {"T", T}, {"wlf", "8.86:101.6:25C"}}));
    EXPECT_NEAR(std::log10(in.c.rheology.aT), -8.86 * 10.0 / 111.6, 1e-12);
  }
  // a temperature at or below TREF - C2 is refused in one line naming --T
  const std::string cold = message("-76.6C", "8.86:101.6:25C");
  EXPECT_NE(cold.find("must be > TREF - C2"), std::string::npos) << cold;
  EXPECT_EQ(cold.find('\n'), std::string::npos) << cold;
}

// Issue 33: --material reads an Abaqus card: *ELASTIC E, nu (LONG TERM by
// default or INSTANTANEOUS), *VISCOELASTIC, TIME=PRONY g_i, k_i, tau_i
// normalised by G0, *TRS, DEFINITION=WLF Tref, C1, C2; anything else is refused.
TEST(cli, MaterialCardGivesTheSpectrum) {
  TempDir dir;
  const auto file = [&](const char* name, const std::string& text) {
    const fs::path p = dir.path() / name;
    write_file(p, text);
    return p.string();
  };
  const std::string body = ", 0.5\n*VISCOELASTIC, TIME=PRONY\n0.2, 0.1, 0.5\n0.6, 0., 20.\n"
                           "*TRS, DEFINITION=WLF\n25., 8.86, 101.6\n";
  const auto read = [](OptionTexts t) {
    t["G"] = kDrop;
    return mdrmap::cases::read_case_input(spectrum_texts(t));
  };
  const auto inst = read({{"material", file("i.inp", "** card\n*Material, name=R\n*Elastic, "
                                                     "moduli=INSTANTANEOUS\n15." +
                                                         body)},
                          {"T", "35"}});
  ASSERT_EQ(inst.c.rheology.branches.size(), 2U);
  EXPECT_DOUBLE_EQ(inst.c.rheology.G, 1.0); // G0 = 15 / 3, G = G0 (1 - 0.8)
  EXPECT_DOUBLE_EQ(inst.c.rheology.branches[0].G, 1.0);
  EXPECT_DOUBLE_EQ(inst.c.rheology.branches[1].G, 3.0);
  EXPECT_EQ(inst.c.rheology.branches[1].tau, 20.0);
  ASSERT_TRUE(inst.temperature);
  EXPECT_EQ(inst.temperature->wlf.Tref, 25.0); // Tref, C1, C2: not mdrmap's order
  EXPECT_EQ(inst.temperature->wlf.C1, 8.86);
  EXPECT_NEAR(inst.c.rheology.aT, std::pow(10.0, -8.86 * 10.0 / 111.6), 1e-15);
  ASSERT_EQ(inst.notes.size(), 1U); // k_1 = 0.1
  EXPECT_NE(inst.notes[0].find("bulk Prony terms k_i are ignored"), std::string::npos);
  const auto lt = read({{"material", file("l.inp", "*ELASTIC\n15." + body)}});
  EXPECT_DOUBLE_EQ(lt.c.rheology.G, 5.0); // the long-term modulus is E's
  EXPECT_DOUBLE_EQ(lt.c.rheology.branches[1].G, 15.0);
  struct Bad {
    OptionTexts texts;
    std::string option, said;
  };
  const std::string card = file("c.inp", "*ELASTIC\n15." + body);
  const std::vector<Bad> bad = {
      {{{"material", file("h.inp", "*ELASTIC\n3, 0.5\n*HYPERELASTIC\n1, 2\n")}},
       "material",
       "h.inp:3: *HYPERELASTIC: not a keyword"},
      {{{"material", file("f.inp", "*ELASTIC\n3, 0.5\n*VISCOELASTIC, FREQUENCY=TABULAR\n")}},
       "material",
       "f.inp:3: *VISCOELASTIC: the option FREQUENCY=TABULAR is not supported"},
      {{{"material", file("t.inp", "*ELASTIC\n3, 0.5\n*VISCOELASTIC, TIME=PRONY\n0.5,0,-2\n")}},
       "material",
       "t.inp:4: tau1 must be"},
      {{{"material", file("s.inp", "*ELASTIC\n3, 0.5\n*VISCOELASTIC, TIME=PRONY\n0.5,0,1\n"
                                   "0.5,0,2\n")}},
       "material",
       "sum to 1"},
      {{{"material", file("n.inp", "*ELASTIC\n3\n")}}, "material", "n.inp:2: *ELASTIC E, nu"},
      {{{"material", file("e.inp", "*VISCOELASTIC, TIME=PRONY\n0.5,0,1\n")}},
       "material",
       "no *ELASTIC"},
      {{{"material", card}, {"G", "2"}}, "G", "cannot be combined with --material"},
      {{{"material", card}, {"prony", "1:1"}}, "prony", "cannot be combined with --material"},
      {{{"material", card}, {"T", "30"}, {"wlf", "1:1:1"}}, "wlf", "*TRS"},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.said);
    try {
      OptionTexts t = spectrum_texts(b.texts);
      if (!b.texts.count("G")) t.erase("G");
      mdrmap::cases::read_case_input(t);
      ADD_FAILURE() << "taken";
    } catch (const mdrmap::InvalidInput& e) {
      EXPECT_EQ(e.option(), b.option) << e.what();
      EXPECT_NE(std::string(e.what()).find(b.said), std::string::npos) << e.what();
    }
  }
  // the CLI: the note on stderr, G in the case line
  const Outcome r = run_mdrmap(
      {"stationary", "--d", "0.1", "--R", "10", "--tau", "0", "--v", "1", "--material", card});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("mdrmap stationary: note: "), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("# case d=0.10000000000000001 R=10 tau=0 G=5 prony="), std::string::npos)
      << r.out;
}

// Issue 33: --material reads pyvisco's Prony CSV too (header, a row of units,
// alpha_i normalised by E_0, E_0 = 3 G0): the spectrum of the same material.
TEST(cli, MaterialReadsPyviscoCsv) {
  TempDir dir;
  const fs::path f = dir.path() / "prony.csv";
  write_file(f, "Prony terms,tau_i,alpha_i,E_0,E_i\r\n-,s,-,MPa,MPa\r\n1,0.1,0.25,12,3\r\n"
                "2,10,0.5,12,6\r\n3,1000,0,12,0\r\n");
  OptionTexts t = spectrum_texts({{"material", f.string()}});
  t.erase("G");
  const mdrmap::Case c = mdrmap::cases::read_case_input(t).c;
  ASSERT_EQ(c.rheology.branches.size(), 2U); // the term alpha = 0 dropped
  EXPECT_DOUBLE_EQ(c.rheology.G, 1.0);       // G0 = 12 / 3 = 4, G = 4 (1 - 0.75)
  EXPECT_DOUBLE_EQ(c.rheology.branches[0].G, 1.0);
  EXPECT_DOUBLE_EQ(c.rheology.branches[1].G, 2.0);
  EXPECT_EQ(c.rheology.branches[1].tau, 10.0);
  write_file(f, "tau_i,alpha_i,G_0\ns,-,Pa\n0.1,0.6,10\n1,x,10\n");
  try {
    mdrmap::cases::read_case_input(t);
    ADD_FAILURE() << "taken";
  } catch (const mdrmap::InvalidInput& e) {
    EXPECT_EQ(e.option(), "material");
    EXPECT_NE(std::string(e.what()).find(f.string() + ":4: column alpha_i must be a finite number"),
              std::string::npos)
        << e.what();
  }
}

// Issue 33, "Done when" 1: one material as an Abaqus card (g_i normalised by
// the instantaneous E = 15, nu = 0.5), as pyvisco's CSV (alpha_i, E_0), as a
// Prony file of normalised g with its G0, and as --G and --prony with the
// G the card gives (5 (1 - 0.8) = 0.99999999999999978): the same case line
// and the same rows, bit for bit.
TEST(cli, CardPyviscoPronyFileAndOptionsGiveIdenticalOutput) {
  TempDir dir;
  const auto file = [&](const char* name, const std::string& text) {
    write_file(dir.path() / name, text);
    return (dir.path() / name).string();
  };
  const std::vector<std::string> base = {"simulate", "--d",       "0.1", "--R",    "10",
                                         "--tau",    "0",         "--v", "1",      "--v1",
                                         "0.1",      "--samples", "5",   "--rtol", "1e-4"};
  const std::vector<std::vector<std::string>> forms = {
      {"--material", file("c.inp", "*Material, name=R\n*Elastic, moduli=INSTANTANEOUS\n15., "
                                   "0.5\n*Viscoelastic, time=PRONY\n0.2, 0., 0.5\n0.6, 0., 20.\n")},
      {"--material", file("p.csv", "tau_i,alpha_i,E_0\ns,-,MPa\n0.5,0.2,15\n20,0.6,15\n")},
      {"--prony-file", file("g.csv", "# G0 = 5\ng,tau\n0.2,0.5\n0.6,20\n")},
      {"--G", "0.99999999999999978", "--prony", "1:0.5,3:20"}};
  // the output less its first line (the solver's wall time)
  const auto rows = [](const std::string& out) { return out.substr(out.find('\n') + 1); };
  std::string first;
  for (const auto& form : forms) {
    std::vector<std::string> args = base;
    args.insert(args.end(), form.begin(), form.end());
    const Outcome r = run_mdrmap(args);
    ASSERT_EQ(r.code, 0) << form[0] << ": " << r.err;
    EXPECT_NE(r.out.find("G=0.99999999999999978 v=1 prony=1:0.5,3:20 "), std::string::npos)
        << form[0] << ": " << r.out;
    if (first.empty()) first = rows(r.out);
    EXPECT_EQ(rows(r.out), first) << form[0];
  }
}

// Issue 33: temperatures with units. C and K are converted into TREF's unit
// (C2 is a difference); a bare number is in the other's unit (today's
// meaning); a shift of more than 12 decades is refused naming --T unless
// --allow-large-shift; the case line prints T and TREF with their unit.
TEST(cli, TemperaturesHaveUnits) {
  const auto aT_of = [](const std::string& T, const std::string& wlf) {
    return mdrmap::cases::read_case_input(spectrum_texts({{"tau", "1"}, {"T", T}, {"wlf", wlf}}))
        .c.rheology.aT;
  };
  const double expected = std::pow(10.0, -8.86 * 10.0 / (101.6 + 10.0));
  for (const auto& [T, wlf] :
       std::vector<std::pair<std::string, std::string>>{{"35", "8.86:101.6:25"},
                                                        {"35C", "8.86:101.6:25C"},
                                                        {"35", "8.86:101.6:25C"},
                                                        {"35C", "8.86:101.6:25"},
                                                        {"308.15K", "8.86:101.6:25C"},
                                                        {"35C", "8.86:101.6:298.15K"},
                                                        {"308.15K", "8.86:101.6:298.15K"}}) {
    SCOPED_TRACE(T + " " + wlf);
    EXPECT_NEAR(aT_of(T, wlf), expected, 1e-12 * expected);
  }
  const auto in = mdrmap::cases::read_case_input(
      spectrum_texts({{"tau", "1"}, {"T", "35C"}, {"wlf", "8.86:101.6:298.15K"}}));
  const std::string line = mdrmap::app::case_line(in.c, in.temperature);
  EXPECT_TRUE(std::regex_match(line, case_line_regex(false))) << line;
  EXPECT_NE(line.find(" G=1 aT="), std::string::npos) << line;
  EXPECT_NE(line.find(" T=308.14999999999998K wlf=8.8599999999999994:101.59999999999999:"
                      "298.14999999999998K "),
            std::string::npos)
      << line;
  // 25C against TREF -100 (C2 = 51.6, C1 = 17.44): log10 aT = -12.3, refused unless allowed
  const OptionTexts large{{"tau", "1"}, {"T", "25C"}, {"wlf", "17.44:51.6:-100"}};
  try {
    mdrmap::cases::read_case_input(spectrum_texts(large));
    ADD_FAILURE() << "a shift of 12.3 decades was taken";
  } catch (const mdrmap::InvalidInput& e) {
    EXPECT_EQ(e.option(), "T");
    EXPECT_NE(std::string(e.what()).find("more than 12 decades from 1"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("--allow-large-shift"), std::string::npos) << e.what();
  }
  OptionTexts allowed = large;
  allowed["allow-large-shift"] = "true";
  EXPECT_NEAR(std::log10(mdrmap::cases::read_case_input(spectrum_texts(allowed)).c.rheology.aT),
              -17.44 * 125.0 / (51.6 + 125.0), 1e-12);
  // the flag on the command line
  const Outcome r = run_mdrmap({"simulate", "--d", "0.1", "--R", "10", "--tau", "1", "--v", "1",
                                "--v1", "2", "--samples", "3", "--T", "25C", "--wlf",
                                "17.44:51.6:-100C", "--allow-large-shift"});
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST(cli, CaseLinePrintsTheSpectrumAndTheShiftOnlyWhereGiven) {
  const auto kelvin = mdrmap::cases::read_case_input(spectrum_texts({{"tau", "1"}}));
  const std::string plain = mdrmap::app::case_line(kelvin.c, kelvin.temperature);
  EXPECT_TRUE(std::regex_match(plain, case_line_regex(false))) << plain;
  for (const char* word : {"prony=", "aT=", " T=", "wlf="})
    EXPECT_EQ(plain.find(word), std::string::npos) << plain;

  const auto spec = mdrmap::cases::read_case_input(
      spectrum_texts({{"prony", "1:0.5,3:20"}, {"T", "30"}, {"wlf", "8.86:101.6:20"}}));
  const std::string line = mdrmap::app::case_line(spec.c, spec.temperature);
  EXPECT_TRUE(std::regex_match(line, case_line_regex(false))) << line;
  EXPECT_NE(line.find(" G=1 aT=" + mdrmap::app::format_double(spec.c.rheology.aT) +
                      " v=1 prony=1:0.5,3:20 T=30 wlf=8.8599999999999994:101.59999999999999:20 "
                      "history="),
            std::string::npos)
      << line;
  // aT = 1 is not printed; an explicit aT is, without T and wlf
  const auto shifted =
      mdrmap::cases::read_case_input(spectrum_texts({{"tau", "1"}, {"aT", "1e-3"}}));
  const std::string s = mdrmap::app::case_line(shifted.c, shifted.temperature);
  EXPECT_NE(s.find(" G=1 aT=0.001 v=1 history="), std::string::npos) << s;
}

// --- Velocity histories --------------------------------------------------------

/// The help text with every run of whitespace made one space (wrapped lines
/// joined), to look for a sentence whatever the line breaks.
std::string flattened(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const bool space = c == ' ' || c == '\n';
    if (!(space && !out.empty() && out.back() == ' ')) out += space ? ' ' : c;
  }
  return out;
}

TEST(cli, SimulateHelpIsGeneratedFromTheParameterTable) {
  const Outcome r = run_mdrmap({"simulate", "--help-all"});
  ASSERT_EQ(r.code, 0);
  const std::string help = flattened(r.out);
  for (const auto& p : mdrmap::case_parameters()) {
    SCOPED_TRACE(p.name);
    EXPECT_NE(help.find(std::string("--") + p.name + " " + p.symbol + " "), std::string::npos);
    EXPECT_NE(help.find(flattened(p.meaning)), std::string::npos);
    EXPECT_NE(help.find(std::string("(") + mdrmap::dim_name(p.dim) + ") " + p.meaning),
              std::string::npos);
    std::string allowed = p.allowed().substr(1); // sentence case in the help
    EXPECT_NE(help.find(allowed), std::string::npos) << allowed;
    if (!p.required && !p.one_of) {
      EXPECT_NE(help.find("Default: " + mdrmap::format_number(p.fallback)), std::string::npos);
    }
  }
  // the history's values are checked against the segment specs: the help says so
  EXPECT_NE(help.find(mdrmap::segment_velocity_spec().allowed() + ", 0 is a hold"),
            std::string::npos);
  EXPECT_NE(help.find(mdrmap::segment_duration_spec().allowed()), std::string::npos);
}

const std::vector<std::string> kHistoryBase{"simulate", "--d", "0.1", "--R", "10",
                                            "--tau",    "1",   "--v", "1"};

std::vector<std::string> history_args(const std::string& history,
                                      std::vector<std::string> extra = {}) {
  std::vector<std::string> args = kHistoryBase;
  args.insert(args.end(), {"--history", history});
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

/// A 3-segment history out of stationary sliding at v0 = 1 (tau = 1, a1 = 1):
/// a drop to v0/10 for 0.5 tau, a rise to v0/5 inside the transient, and a
/// rise back to v0 after 3 tau, when the contact is stationary at v0/5.
TEST(cli, SimulateThreeSegmentHistory) {
  const long N = 21;
  const Outcome r = run_mdrmap(history_args("0.1:0.5,0.2:3,1:2", {"--samples", "21"}));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const Parsed p = parse_output(r.out);
  const std::vector<std::pair<double, double>> h{{0.1, 0.5}, {0.2, 3.0}, {1.0, 2.0}};
  EXPECT_EQ(history_of(p), h);
  EXPECT_EQ(to_double(p.case_line.at("v")), 1.0);
  ASSERT_EQ(p.rows.size(), 3U * N);
  // rows: segment after segment, t_k + j T_k/(N-1), t_k = 0, 0.5, 3.5
  const double t_start[3] = {0.0, 0.5, 3.5};
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const std::size_t k = i / N, j = i % N;
    const double t = t_start[k] + h[k].second * static_cast<double>(j) / (N - 1.0);
    EXPECT_EQ(p.rows[i][kSegment], static_cast<double>(k)) << "row " << i;
    EXPECT_LE(std::abs(p.rows[i][kT] - t), 1e-15 * 5.5) << "row " << i;
  }
  for (std::size_t k = 1; k < 3; ++k) // a change: the same instant on both sides
    EXPECT_EQ(p.rows[k * N][kT], p.rows[k * N - 1][kT]) << "segment " << k;

  // The same case in the library, the same call: identical to the last digit.
  mdrmap::Case c = mdrmap::step_case(0.1, 10, 1, 1, 0.1, 1.0, 0.5, N);
  c.history.segments = {{0.1, 0.5}, {0.2, 3.0}, {1.0, 2.0}};
  const mdrmap::RunResult run = mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-4);
  const mdrmap::Series& ref = run.series;
  expect_matches_series(p, ref, 1e-15);

  // Physics: before t = 0 the stationary state at v0; just after the drop the
  // contact set of v0 with its elements at v0/10 (corrected eqs. 15, 16); the
  // rise out of the stationary state at v0/5 cuts the contact to a2(v0) at
  // once: from then on every row is the stationary state at v0 again.
  const mdrmap::State pre = mdrmap::analytic::stationary(c, 1.0);
  const mdrmap::State jump = mdrmap::analytic::jump(c, 1.0, 0.1);
  EXPECT_NEAR(to_double(p.pre.at("mu")), pre.mu, 1e-15 * pre.mu);
  EXPECT_NEAR(p.rows[0][kMu], jump.mu, 1e-12 * jump.mu);
  EXPECT_NEAR(p.rows[0][kA2], jump.a2, 1e-12);
  for (std::size_t i = 2 * N; i < 3 * N; ++i) {
    EXPECT_NEAR(p.rows[i][kFN], pre.FN, 1e-12 * pre.FN) << "row " << i;
    EXPECT_NEAR(p.rows[i][kMu], pre.mu, 1e-12 * pre.mu) << "row " << i;
    EXPECT_NEAR(p.rows[i][kA2], pre.a2, 1e-12) << "row " << i;
  }

  // Events: one per segment, the library's metrics of the printed series.
  const auto ev =
      mdrmap::event_metrics(c, ref, run.transients, run.info.error_estimate, run.probes);
  ASSERT_EQ(p.events.size(), 3U);
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE("event " + std::to_string(k));
    const auto& e = p.events[k];
    EXPECT_EQ(to_double(e.at("t")), t_start[k]);
    EXPECT_EQ(to_double(e.at("w_before")), k == 0 ? 1.0 : h[k - 1].first);
    EXPECT_EQ(to_double(e.at("w_after")), h[k].first);
    // mu just before the change: the previous segment's last row (pre for k = 0)
    EXPECT_EQ(to_double(e.at("mu_before")),
              k == 0 ? to_double(p.pre.at("mu")) : p.rows[k * N - 1][kMu]);
    EXPECT_EQ(to_double(e.at("mu_after")), p.rows[k * N][kMu]);
    EXPECT_EQ(to_double(e.at("mu_end")), p.rows[k * N + N - 1][kMu]);
    const std::pair<const char*, double> lib[] = {{"mu_max", ev[k].mu_max},
                                                  {"t_max", ev[k].t_max},
                                                  {"mu_min", ev[k].mu_min},
                                                  {"t_min", ev[k].t_min},
                                                  {"healing", ev[k].healing},
                                                  {"mu_peak", ev[k].mu_peak},
                                                  {"t_peak", ev[k].t_peak},
                                                  {"slip_peak", ev[k].slip_peak},
                                                  {"mu_ss_before", ev[k].ss_before.mu},
                                                  {"mu_ss_after", ev[k].ss_after.mu},
                                                  {"D_c", ev[k].d_c},
                                                  {"overshoot", ev[k].overshoot},
                                                  {"a", ev[k].a},
                                                  {"a_minus_b", ev[k].a_minus_b},
                                                  {"b", ev[k].b}};
    for (const auto& [key, value] : lib) {
      if (std::isnan(value))
        EXPECT_EQ(e.at(key), "nan") << key;
      else
        EXPECT_EQ(to_double(e.at(key)), value) << key;
    }
  }
  // the last change ends in the stationary state at once: no 1/e decay to measure
  EXPECT_EQ(p.events[2].at("D_c"), "nan");
}

/// Logarithmic sampling: j = 0 at the change, then t_k + T_k 10^(-D (N-1-j)/(N-2)).
TEST(cli, SimulateLogSpacingGivesTheDocumentedInstants) {
  const std::vector<std::pair<double, double>> h{{1.0, 2.0}, {0.0, 1000.0}, {1.0, 5.0}};
  for (const double D : {3.0, 4.0}) {
    SCOPED_TRACE("log-decades " + num(D));
    const long N = 6;
    std::vector<std::string> extra{"--samples", "6", "--spacing", "log"};
    if (D != 4.0) extra.insert(extra.end(), {"--log-decades", num(D)}); // 4: the default
    const Outcome r = run_mdrmap(history_args("1:2,0:1000,1:5", extra));
    ASSERT_EQ(r.code, 0) << r.err;
    const Parsed p = parse_output(r.out);
    EXPECT_EQ(p.case_line.at("spacing"), "log");
    EXPECT_EQ(to_double(p.case_line.at("log-decades")), D);
    ASSERT_EQ(p.rows.size(), 3U * N);
    double start = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double T = h[k].second;
      for (long j = 0; j < N; ++j) {
        const double expo = -D * static_cast<double>(N - 1 - j) / static_cast<double>(N - 2);
        const double t = start + (j == 0 ? 0.0 : T * std::pow(10.0, expo));
        const auto& row = p.rows[k * N + static_cast<std::size_t>(j)];
        EXPECT_NEAR(row[kT], t, 1e-15 * t) << "segment " << k << " j " << j;
        EXPECT_EQ(row[kSegment], static_cast<double>(k));
      }
      EXPECT_EQ(p.rows[k * N + N - 1][kT], start + T) << "the last instant is the segment's end";
      start += T;
    }
    // Physics: a hold of 1000 tau relaxes the contact to the elastic one,
    // symmetric (a2 = a1 = 1) and without friction.
    mdrmap::Case c = mdrmap::step_case(0.1, 10, 1, 1, 1, 1.0, 2.0, N);
    const mdrmap::State hold = mdrmap::analytic::stationary(c, 0.0);
    const auto& end_of_hold = p.rows[2 * N - 1];
    EXPECT_NEAR(end_of_hold[kFN], hold.FN, 1e-12 * hold.FN);
    EXPECT_NEAR(end_of_hold[kA2], 1.0, 1e-12);
    EXPECT_LE(std::abs(end_of_hold[kMu]), 1e-12);
    // and the library's run of the same case, to the last digit
    c.history.segments = {{1.0, 2.0}, {0.0, 1000.0}, {1.0, 5.0}};
    c.sampling.spacing = mdrmap::Spacing::Log;
    c.sampling.decades = D;
    expect_matches_series(p, mdrmap::run_exact(mdrmap::CheckedCase(c), 1e-4).series, 1e-15);
  }
}

/// Each bad token of --history: exit 2, one line naming --history, the
/// segment or token at fault and what is allowed; nothing written.
TEST(cli, SimulateBadHistoryTokensExit2WithOneLineNamingHistory) {
  std::string too_many;
  for (std::size_t k = 0; k <= mdrmap::kMaxSegments; ++k)
    too_many += (k ? "," : "") + std::string("1:1");
  const std::string w_allowed = mdrmap::segment_velocity_spec().allowed();
  const std::string t_allowed = mdrmap::segment_duration_spec().allowed();
  struct Bad {
    const char* label;
    std::string history;
    std::vector<std::string> said; ///< fragments the message must contain
  };
  const std::vector<Bad> cases{
      {"empty history", "", {"an empty string", "W:T"}},
      {"blank history", "  ", {"W:T"}},
      {"missing colon", "1:2,5", {"segment 2 '5'", "no ':'", "W:T"}},
      {"extra colon", "1:2:3", {"segment 1 '1:2:3'", "more than one ':'", "W:T"}},
      {"W not a number", "1:2,abc:1", {"segment 2 'abc:1'", "W must be a number, got abc"}},
      {"T not a number", "1:2x", {"segment 1 '1:2x'", "T must be a number, got 2x"}},
      {"W empty", ":5", {"segment 1 ':5'", "W must be a number"}},
      {"T empty", "1:", {"segment 1 '1:'", "T must be a number"}},
      {"W < 0", "1:1,-1:2", {"segment 2 '-1:2'", "W must be " + w_allowed, "got -1"}},
      {"T = 0", "1:0", {"segment 1 '1:0'", "T must be " + t_allowed, "got 0"}},
      {"T < 0", "1:-3", {"segment 1 '1:-3'", "T must be " + t_allowed, "got -3"}},
      {"W = nan", "nan:1", {"segment 1 'nan:1'", "W must be " + w_allowed, "got nan"}},
      {"T = inf", "1:inf", {"segment 1 '1:inf'", "T must be " + t_allowed, "got inf"}},
      {"W = -inf", "-inf:1", {"segment 1 '-inf:1'", "W must be " + w_allowed}},
      {"T overflows", "1:1e999", {"segment 1 '1:1e999'", "too large for a double"}},
      {"empty item", "1:2,,3:4", {"segment 2 is empty", "W:T"}},
      {"leading comma", ",1:2", {"segment 1 is empty"}},
      {"trailing comma", "1:2,", {"segment 2 is empty"}},
      {"too many segments",
       too_many,
       {std::to_string(mdrmap::kMaxSegments + 1) + " segments",
        "at most " + std::to_string(mdrmap::kMaxSegments)}},
      {"durations overflow", "1:1e308,1:1e308", {"durations add up"}},
  };
  TempDir dir;
  const fs::path existing = dir.path() / "existing.csv";
  for (const auto& c : cases) {
    SCOPED_TRACE(c.label);
    write_file(existing, "keep me\n");
    const Outcome r = run_mdrmap(history_args(c.history, {"--output", existing.string()}));
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(starts_with(r.err, "mdrmap simulate: error: --history: ")) << r.err;
    for (const auto& s : c.said)
      EXPECT_NE(r.err.find(s), std::string::npos) << "'" << s << "' in " << r.err;
    EXPECT_EQ(read_file(existing), "keep me\n");
  }
  // a history that parses is not refused for its spelling: spaces around items
  EXPECT_EQ(run_mdrmap(history_args(" 0.1:0.5, 1:2 ", {"--samples", "3"})).code, 0);
}

TEST(cli, SimulateV1WithHistoryIsRefused) {
  const Outcome r = run_mdrmap(history_args("0.5:6", {"--v1", "0.5"}));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(starts_with(r.err, "mdrmap simulate: error: --history: ")) << r.err;
  EXPECT_NE(r.err.find("--v1"), std::string::npos) << r.err;
  // and neither form: --v1 is missing, and --history is named as the alternative
  const Outcome none = run_mdrmap(kHistoryBase);
  EXPECT_EQ(none.code, 2);
  EXPECT_TRUE(starts_with(none.err, "mdrmap simulate: error: --v1: is required")) << none.err;
  EXPECT_NE(none.err.find("--history"), std::string::npos) << none.err;
}

/// The one-step command line is the one-segment history --history V1:T: the
/// same case, so the same output, digit for digit (wall time aside), for the
/// default window and an explicit --t-end, and for every solver.
TEST(cli, SimulateShorthandEqualsOneSegmentHistory) {
  struct Row {
    std::vector<std::string> extra;
    double t_end; ///< 0: the default window
  };
  const Step s = transient_scene();
  const std::vector<Row> rows{{{}, 0.0},
                              {{"--t-end", "2.5", "--samples", "17"}, 2.5},
                              {{"--solver", "row", "--rtol", "1e-3", "--samples", "21"}, 0.0}};
  for (const auto& row : rows) {
    const double T = row.t_end > 0.0 ? row.t_end : default_window(s);
    std::vector<std::string> shorthand = simulate_args(s);
    shorthand.insert(shorthand.end(), row.extra.begin(), row.extra.end());
    std::vector<std::string> history = {"simulate",
                                        "--d",
                                        num(s.d),
                                        "--R",
                                        num(s.R),
                                        "--tau",
                                        num(s.tau),
                                        "--v",
                                        num(s.v),
                                        "--history",
                                        num(s.v1) + ":" + num(T),
                                        "--G",
                                        num(s.G)};
    for (std::size_t i = 0; i < row.extra.size(); ++i) {
      if (row.extra[i] == "--t-end") {
        ++i;
        continue;
      }
      history.push_back(row.extra[i]);
    }
    const Outcome a = run_mdrmap(shorthand), b = run_mdrmap(history);
    ASSERT_EQ(a.code, 0) << a.err;
    ASSERT_EQ(b.code, 0) << b.err;
    SCOPED_TRACE(b.out.substr(0, 400));
    EXPECT_EQ(without_wall_time(a.out), without_wall_time(b.out));
    const Parsed p = parse_output(a.out);
    EXPECT_EQ(history_of(p), (std::vector<std::pair<double, double>>{{s.v1, T}}));
  }
}

// --- Load control (--F0) ----------------------------------------------------------

/// The members of the table's loading group, as the help and messages spell them.
std::vector<const mdrmap::ParamSpec*> loading_group() {
  std::vector<const mdrmap::ParamSpec*> g;
  for (const auto& p : mdrmap::case_parameters())
    if (p.one_of && std::string(p.one_of) == "loading") g.push_back(&p);
  return g;
}

/// Neither or both of --d and --F0: exit 2, one line naming both (and saying
/// which were given), no output touched or created.
TEST(cli, SimulateLoadingNeedsExactlyOneOfDepthAndForce) {
  const auto group = loading_group();
  ASSERT_EQ(group.size(), 2U);
  TempDir dir;
  const fs::path existing = dir.path() / "existing.csv";
  const std::vector<std::string> scene{"--R", "10", "--tau", "1", "--v", "1", "--v1", "0.1"};
  struct Row {
    const char* label;
    std::vector<std::string> loading;
    const char* got;
  };
  for (const Row& row :
       {Row{"neither", {}, "got none"},
        Row{"both", {"--d", "0.1", "--F0", "0.2"}, "got --d and --F0"},
        Row{"both, F0 first", {"--F0", "0.2", "--d", "0.1"}, "got --d and --F0"},
        Row{"both, the old spelling FN", {"--FN", "0.2", "--d", "0.1"}, "got --d and --FN"}}) {
    SCOPED_TRACE(row.label);
    for (const bool with_output : {false, true}) {
      std::vector<std::string> args{"simulate"};
      args.insert(args.end(), row.loading.begin(), row.loading.end());
      args.insert(args.end(), scene.begin(), scene.end());
      if (with_output) args.insert(args.end(), {"--output", existing.string()});
      write_file(existing, "keep me\n");
      const Outcome r = run_mdrmap(args);
      EXPECT_EQ(r.code, 2) << r.err;
      EXPECT_EQ(r.out, "");
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(starts_with(r.err, "mdrmap simulate: error: give exactly one of ")) << r.err;
      for (const auto* p : group) {
        EXPECT_NE(r.err.find(std::string("--") + p->name + " " + p->symbol), std::string::npos)
            << r.err;
        EXPECT_NE(r.err.find(p->meaning), std::string::npos) << r.err;
      }
      EXPECT_NE(r.err.find(row.got), std::string::npos) << r.err;
      EXPECT_EQ(read_file(existing), "keep me\n");
      std::size_t files = 0;
      for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path()))
        ++files;
      EXPECT_EQ(files, 1U) << "no temporary left behind";
    }
  }
  // An explicit value out of range is reported by its own range, even beside
  // the other member: the range first, then the group.
  for (const auto& [opt, value] :
       std::vector<std::pair<std::string, std::string>>{{"d", "0"}, {"F0", "-1"}, {"F0", "0"}}) {
    std::vector<std::string> args{"simulate", "--" + opt, value};
    args.insert(args.end(), scene.begin(), scene.end());
    const Outcome r = run_mdrmap(args);
    EXPECT_EQ(r.code, 2);
    const auto* spec = mdrmap::find_parameter(opt);
    ASSERT_NE(spec, nullptr);
    EXPECT_EQ(r.err, "mdrmap simulate: error: --" + opt + ": must be " + spec->allowed() +
                         ", got " + value + "\n");
  }
}

/// The help shows the loading group from the table's one_of field: both
/// members in the usage line as one alternative, and no "Default: 0".
TEST(cli, SimulateHelpShowsTheLoadingGroup) {
  const Outcome r = run_mdrmap({"simulate", "--help-all"});
  ASSERT_EQ(r.code, 0);
  const std::string help = flattened(r.out);
  std::string alternative, listed;
  for (const auto* p : loading_group()) {
    const std::string opt = std::string("--") + p->name + " " + p->symbol;
    alternative += (alternative.empty() ? "(" : " | ") + opt;
    listed += (listed.empty() ? "" : " or ") + opt;
  }
  EXPECT_TRUE(starts_with(r.out, "Usage: mdrmap simulate " + alternative + ") ")) << r.out;
  for (const auto* p : loading_group()) {
    SCOPED_TRACE(p->name);
    // the entry in the option list: from its line to the next option's line
    const std::string entry = std::string("\n  --") + p->name + " " + p->symbol + " ";
    const std::size_t at = r.out.find(entry);
    ASSERT_NE(at, std::string::npos);
    const std::string text = flattened(r.out.substr(at, r.out.find("\n  --", at + 1) - at));
    EXPECT_NE(text.find("The " + std::string(p->one_of) + ": give exactly one of " + listed),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("Default"), std::string::npos) << text;
  }
  for (const char* word : {"t,segment,FN,Fx,mu,a2,d,a1", "a0=", "d=... a1=...",
                           "zeta0 = V0 tau / a0", "error_vs_reference"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
}

/// The case at fixed depth d with everything else of `c`: what the
/// fixed-depth formulas take (independent of the load solver).
mdrmap::Case held_at(mdrmap::Case c, double d) {
  c.loading.F0 = 0.0;
  c.loading.d = d;
  return c;
}

// Load control end to end: F0 = 16/3 G a0^3 / R with a0 = 1, R = 100, tau = 1:
// v0 = 1 (zeta0 = 1), a drop to 0.1 for 40 tau (long enough to settle), then
// a rise back to 1 for 40 tau.
constexpr double kF0 = 16.0 / 3.0 / 100.0;
const std::vector<std::string> kLoadBase{"simulate", "--F0", num(kF0), "--R",    "100", "--tau",
                                         "1",        "--v",  "1",      "--rtol", "1e-3"};

TEST(cli, SimulateUnderLoadHasTheLoadColumnsAndPhysics) {
  const long N = 41;
  std::vector<std::string> args = kLoadBase;
  args.insert(args.end(), {"--history", "0.1:40,1:40", "--samples", num(N), "--spacing", "log"});
  const Outcome r = run_mdrmap(args);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const Parsed p = parse_output(r.out);
  ASSERT_TRUE(p.load) << p.header;
  EXPECT_FALSE(p.error_vs_exact.has_value()) << "the default solver: no reference line";
  EXPECT_EQ(p.case_line.count("d"), 0U) << "only the loading given";
  EXPECT_EQ(to_double(p.case_line.at("F0")), kF0);
  const double a0 = to_double(p.case_line.at("a0"));
  EXPECT_NEAR(a0, 1.0, 1e-15);                                 // 16/3 G a0^3 / R = F0
  EXPECT_NEAR(to_double(p.case_line.at("zeta0")), 1.0, 1e-15); // v tau / a0
  // the scales under load: a0, d0 = a0^2 / R, F0, a0 / R, tau
  EXPECT_EQ(to_double(p.scales.at("length")), a0);
  EXPECT_NEAR(to_double(p.scales.at("depth")), 0.01, 1e-17);
  EXPECT_EQ(to_double(p.scales.at("force")), kF0);
  EXPECT_NEAR(to_double(p.scales.at("friction")), 0.01, 1e-17);
  EXPECT_EQ(to_double(p.scales.at("time")), 1.0);
  ASSERT_EQ(p.rows.size(), 2U * N);

  // Before t = 0: the fixed-depth stationary state at the depth printed, whose
  // normal force is F0 (stationary sliding under load).
  mdrmap::Case c = mdrmap::step_case(1.0, 100.0, 1.0, 1.0, 0.1, 1.0, 40.0, N);
  const double d_pre = to_double(p.pre.at("d"));
  const mdrmap::State pre = mdrmap::analytic::stationary(held_at(c, d_pre), 1.0);
  EXPECT_NEAR(to_double(p.pre.at("FN")), kF0, 1e-12 * kF0);
  EXPECT_NEAR(pre.FN, kF0, 1e-12 * kF0);
  EXPECT_NEAR(to_double(p.pre.at("mu")), pre.mu, 1e-12 * pre.mu);
  EXPECT_NEAR(to_double(p.pre.at("a2")), pre.a2, 1e-12);
  EXPECT_NEAR(to_double(p.pre.at("a1")), std::sqrt(100.0 * d_pre), 1e-14);

  // Every sample: F_N = F0 within rtol, the leading edge a1 = sqrt(R d).
  for (const auto& row : p.rows) {
    EXPECT_LE(std::abs(row[kFN] - kF0), 1e-3 * kF0) << "t = " << row[kT];
    EXPECT_NEAR(row[kA1], std::sqrt(100.0 * row[kD]), 1e-12) << "t = " << row[kT];
    EXPECT_LE(row[kA2], row[kA1] * (1 + 1e-12));
  }
  // The end of each segment is the stationary state under load at its velocity,
  // and the events' stationary states are those under load: mu_ss_before of
  // the first change is the state before t = 0, mu_ss_after the settled end.
  ASSERT_EQ(p.events.size(), 2U);
  EXPECT_NEAR(to_double(p.events[0].at("mu_ss_before")), to_double(p.pre.at("mu")), 1e-12 * pre.mu);
  for (std::size_t k = 0; k < 2; ++k) {
    SCOPED_TRACE("segment " + std::to_string(k));
    const auto& end = p.rows[k * N + N - 1];
    const double w = k == 0 ? 0.1 : 1.0;
    const mdrmap::State ss = mdrmap::analytic::stationary(held_at(c, end[kD]), w);
    EXPECT_LE(std::abs(ss.FN - kF0), 2e-3 * kF0);
    EXPECT_LE(std::abs(end[kMu] - ss.mu), 2e-3 * pre.mu);
    EXPECT_LE(std::abs(to_double(p.events[k].at("mu_ss_after")) - end[kMu]), 2e-3 * pre.mu);
    EXPECT_EQ(p.events[k].at("a_minus_b") == "nan", false);
  }
  // The same case in the library, the same call: identical to the last digit.
  c.loading = {0.0, kF0};
  c.history.segments = {{0.1, 40.0}, {1.0, 40.0}};
  c.sampling.spacing = mdrmap::Spacing::Log;
  const mdrmap::Series lib =
      mdrmap::run_case(mdrmap::CheckedCase(c), mdrmap::SolverKind::Auto, 1e-3).series;
  ASSERT_EQ(lib.size(), p.rows.size());
  for (std::size_t i = 0; i < lib.size(); ++i) {
    EXPECT_EQ(p.rows[i][kFN], lib.FN[i]);
    EXPECT_EQ(p.rows[i][kMu], lib.mu[i]);
    EXPECT_EQ(p.rows[i][kD], lib.d[i]);
    EXPECT_EQ(p.rows[i][kA1], lib.a1[i]);
  }
}

/// Under load a solver other than the default is compared with the load
/// solver at a 1000x tighter rtol; exact refuses the case (exit 2, --solver).
TEST(cli, SimulateUnderLoadOtherSolvers) {
  std::vector<std::string> args = kLoadBase;
  args.insert(args.end(), {"--v1", "0.1", "--samples", "11", "--solver", "row"});
  const Outcome r = run_mdrmap(args);
  ASSERT_EQ(r.code, 0) << r.err;
  const Parsed p = parse_output(r.out);
  ASSERT_TRUE(p.load);
  ASSERT_TRUE(p.error_vs_exact.has_value());
  EXPECT_EQ(to_double(p.reference.at("reference_rtol")), 1e-6);
  EXPECT_LE(*p.error_vs_exact, 1e-3);
  EXPECT_GE(*p.error_vs_exact, 0.0);

  TempDir dir;
  const fs::path out = dir.path() / "out.csv";
  write_file(out, "keep me\n");
  args = kLoadBase;
  args.insert(args.end(), {"--v1", "0.1", "--solver", "exact", "--output", out.string()});
  const Outcome ex = run_mdrmap(args);
  EXPECT_EQ(ex.code, 2) << ex.err;
  EXPECT_EQ(std::count(ex.err.begin(), ex.err.end(), '\n'), 1) << ex.err;
  EXPECT_TRUE(starts_with(ex.err, "mdrmap simulate: error: --solver: ")) << ex.err;
  EXPECT_EQ(read_file(out), "keep me\n");
}

/// The solvers' old names: spectrum is the row's (the same output, digit for
/// digit but the wall time, reported as solver=row); mdr was retired and is
/// refused in one line naming --solver and what to use, nothing written.
TEST(cli, SimulateOldSolverNames) {
  std::vector<std::string> args = kLoadBase;
  args.insert(args.end(), {"--v1", "0.1", "--samples", "5", "--solver"});
  auto with = [&](const char* solver) {
    std::vector<std::string> a = args;
    a.emplace_back(solver);
    return run_mdrmap(a);
  };
  const Outcome row = with("row"), spectrum = with("spectrum");
  ASSERT_EQ(row.code, 0) << row.err;
  ASSERT_EQ(spectrum.code, 0) << spectrum.err;
  const Parsed a = parse_output(row.out), b = parse_output(spectrum.out);
  EXPECT_EQ(a.run.at("solver"), "row");
  EXPECT_EQ(b.run.at("solver"), "row");
  EXPECT_EQ(a.rows, b.rows);
  TempDir dir;
  const fs::path out = dir.path() / "out.csv";
  write_file(out, "keep me\n");
  std::vector<std::string> mdr = args;
  mdr.insert(mdr.end(), {"mdr", "--output", out.string()});
  const Outcome refused = run_mdrmap(mdr);
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  EXPECT_TRUE(
      starts_with(refused.err, "mdrmap simulate: error: --solver: mdr was retired: use row"))
      << refused.err;
  EXPECT_EQ(read_file(out), "keep me\n");
}

/// tau = 0 under load: Hertz at once (d = d0 = a0^2/R, a1 = a2 = a0, mu = 0),
/// and the default window of --v1 is 6 a0 / min(v, v1).
TEST(cli, SimulateUnderLoadElasticIsHertz) {
  const Outcome r = run_mdrmap({"simulate", "--F0", num(kF0), "--R", "100", "--tau", "0", "--v",
                                "2", "--v1", "0.5", "--samples", "5"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Parsed p = parse_output(r.out);
  ASSERT_TRUE(p.load);
  EXPECT_EQ(history_of(p), (std::vector<std::pair<double, double>>{{0.5, 6.0 / 0.5}}));
  for (const auto& row : p.rows) {
    EXPECT_NEAR(row[kD], 0.01, 1e-14);
    EXPECT_NEAR(row[kA1], 1.0, 1e-12);
    EXPECT_NEAR(row[kA2], 1.0, 1e-12);
    EXPECT_NEAR(row[kFN], kF0, 1e-12 * kF0);
    EXPECT_LE(std::abs(row[kMu]), 1e-12);
  }
}

// --- study -------------------------------------------------------------------

// `study --set` adds a history segment to a config without [history] (docs/studies.md:
// every override is applied, then the study is checked); half a segment is
// refused at the command line. Run as an MPI singleton.
TEST(cli, StudySetAddsTheSegmentOfAConfigWithoutHistory) {
  TempDir dir;
  const fs::path ini = dir.path() / "no_history.ini";
  write_file(ini, "[grid]\nd = 1e-3\nR = 1\ntau = 1\nv = 1\n[run]\nsamples = 5\n");
  const fs::path map = dir.path() / "map.h5";
  const std::vector<std::string> base = {"study",      "--quiet",  "--config",
                                         ini.string(), "--output", map.string()};
  auto half = base;
  half.insert(half.end(), {"--set", "history.w1_over_v=0"});
  const Outcome refused = run_mdrmap(half, kNoHangSeconds);
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  EXPECT_TRUE(starts_with(refused.err, "mdrmap study: error: history.T1: command line: "))
      << refused.err;
  EXPECT_FALSE(fs::exists(map));

  auto whole = half;
  whole.insert(whole.end(), {"--set", "history.T1_over_tau=10"});
  const Outcome r = run_mdrmap(whole, kNoHangSeconds);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("1 cases in " + map.string() + ": 1 done, 0 failed"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::is_regular_file(map));
}

// Every case parameter of the table is an override of mdrmap study, as of
// simulate: --F0 gives a config without a loading its load (issue 22).
TEST(cli, StudyTakesEveryCaseParameterOfTheTable) {
  TempDir dir;
  const fs::path ini = dir.path() / "no_loading.ini";
  write_file(ini, "[grid]\nR = 1\ntau = 1\nv = 1\nv1_over_v = 0.1\n[run]\nsamples = 5\n");
  const fs::path map = dir.path() / "map.h5";
  const Outcome r = run_mdrmap({"study", "--quiet", "--config", ini.string(), "--output",
                                map.string(), "--F0", "5.333333333333333,1"},
                               kNoHangSeconds);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("2 cases in " + map.string() + ": 2 done, 0 failed"), std::string::npos)
      << r.err;
  const fs::path other = dir.path() / "other.h5";
  const Outcome both = run_mdrmap({"study", "--quiet", "--config", ini.string(), "--output",
                                   other.string(), "--F0", "1", "--d", "1e-3"},
                                  kNoHangSeconds);
  EXPECT_EQ(both.code, 2) << both.err;
  EXPECT_EQ(std::count(both.err.begin(), both.err.end(), '\n'), 1) << both.err;
  EXPECT_FALSE(fs::exists(other));
}

// The prescribed load is F0 (--F0, `# case F0=`), the measured normal force
// FN (the CSV's column FN, `# pre FN=`); --FN, the load's old spelling, gives
// the same case, and both spellings at once are refused in one line, nothing
// written (issue 22).
TEST(cli, SimulateTakesFNAsTheOldSpellingOfF0) {
  std::vector<std::string> args = kLoadBase;
  args.insert(args.end(), {"--history", "0.1:5", "--samples", "5"});
  ASSERT_EQ(args[1], "--F0");
  const Outcome f0 = run_mdrmap(args);
  ASSERT_EQ(f0.code, 0) << f0.err;
  std::vector<std::string> old = args;
  old[1] = "--FN";
  const Outcome fn = run_mdrmap(old);
  ASSERT_EQ(fn.code, 0) << fn.err;
  const Parsed p = parse_output(f0.out), q = parse_output(fn.out);
  EXPECT_EQ(p.case_line, q.case_line);
  EXPECT_EQ(p.pre, q.pre);
  EXPECT_EQ(p.events, q.events);
  EXPECT_EQ(p.rows, q.rows);
  // the case line names the load F0, never FN
  EXPECT_NE(f0.out.find("\n# case F0=" + num(kF0) + " "), std::string::npos) << f0.out;
  EXPECT_EQ(p.case_line.count("FN"), 0U);
  EXPECT_EQ(to_double(p.case_line.at("F0")), kF0);
  // FN is the measured force: the column FN of the rows and `# pre FN=`,
  // which load control holds at F0 (within the run's rtol 1e-3)
  EXPECT_EQ(p.header, "t,segment,FN,Fx,mu,a2,d,a1");
  EXPECT_NEAR(to_double(p.pre.at("FN")), kF0, 1e-12 * kF0);
  ASSERT_EQ(p.rows.size(), 5U);
  for (const auto& row : p.rows) {
    EXPECT_NEAR(row[kFN], kF0, 1e-3 * kF0);
    EXPECT_NE(row[kD], 0.0) << "the depth follows the load";
  }
  // both spellings: refused in one line naming both
  TempDir dir;
  const fs::path out = dir.path() / "out.csv";
  for (const auto& extra :
       std::vector<std::vector<std::string>>{{"--FN", num(kF0)},
                                             {"--FN", num(2 * kF0)},
                                             {"--FN", num(kF0), "--output", out.string()}}) {
    std::vector<std::string> both = args;
    both.insert(both.end(), extra.begin(), extra.end());
    const Outcome r = run_mdrmap(both);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "mdrmap simulate: error: --F0 and --FN are the same parameter (FN is the "
                     "old spelling of F0); give only one\n");
    EXPECT_FALSE(fs::exists(out));
  }
  // the help documents --F0 and names --FN as its old spelling
  const Outcome help = run_mdrmap({"simulate", "--help-all"});
  const std::size_t at = help.out.find("\n  --F0 F0 ");
  ASSERT_NE(at, std::string::npos) << help.out;
  const std::string entry = flattened(help.out.substr(at, help.out.find("\n  --", at + 1) - at));
  EXPECT_NE(entry.find("prescribed normal load"), std::string::npos) << entry;
  EXPECT_NE(entry.find("--FN is accepted as its old spelling"), std::string::npos) << entry;
}

// mdrmap study takes the prescribed load as --F0 and as its old spelling
// --FN; both spellings at once (as options, as --set keys or as keys of the
// config) are refused in one line, nothing written (issue 22). The maps'
// /cases/F0 is checked by tests/python/test_old_names.py.
TEST(cli, StudyTakesFNAsTheOldSpellingOfF0) {
  TempDir dir;
  const fs::path ini = dir.path() / "no_loading.ini";
  write_file(ini, "[grid]\nR = 1\ntau = 1\nv = 1\nv1_over_v = 0.1\n[run]\nsamples = 5\n");
  for (const char* spelling : {"--F0", "--FN"}) {
    SCOPED_TRACE(spelling);
    const fs::path map = dir.path() / (std::string(spelling + 2) + ".h5");
    const Outcome r = run_mdrmap({"study", "--quiet", "--config", ini.string(), "--output",
                                  map.string(), spelling, "5.333333333333333,1"},
                                 kNoHangSeconds);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("2 cases in " + map.string() + ": 2 done, 0 failed"), std::string::npos)
        << r.err;
  }
  const fs::path both_keys = dir.path() / "both_keys.ini";
  write_file(both_keys, "[grid]\nF0 = 1\nFN = 1\nR = 1\ntau = 1\nv = 1\nv1_over_v = 0.1\n");
  struct Row {
    const char* label;
    std::vector<std::string> args;
    const char* says;
  };
  for (const Row& row :
       {Row{"--F0 and --FN",
            {"--config", ini.string(), "--F0", "1", "--FN", "1"},
            "mdrmap study: error: --FN: --F0 and --FN are the same parameter (FN is the old "
            "spelling of F0); give only one\n"},
        Row{"--set grid.F0 and grid.FN",
            {"--config", ini.string(), "--set", "grid.F0=1", "--set", "grid.FN=1"},
            "mdrmap study: error: grid.FN: command line: grid.F0 and grid.FN are the same "
            "parameter (FN is the old spelling of F0); give only one\n"},
        Row{"--FN and --d",
            {"--config", ini.string(), "--FN", "1", "--d", "1e-3"},
            "mdrmap study: error: --d: --d and --FN set the same thing (the loading); give "
            "only one\n"},
        Row{"keys F0 and FN", {"--config", both_keys.string()}, "both F0 (grid.F0) and FN"}}) {
    SCOPED_TRACE(row.label);
    const fs::path map = dir.path() / "refused.h5";
    std::vector<std::string> args{"study", "--quiet", "--output", map.string()};
    args.insert(args.end(), row.args.begin(), row.args.end());
    const Outcome r = run_mdrmap(args, kNoHangSeconds);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(row.says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(map));
  }
}

// A spectrum's terms, the shift and the temperature are overrides of mdrmap
// study (issue 19): a term given by halves, a temperature without its WLF
// constants and a named Kelvin solver are refused with one line naming the key.
TEST(cli, StudyTakesSpectrumTermsAndTheTemperature) {
  TempDir dir;
  const fs::path ini = dir.path() / "kelvin.ini";
  write_file(ini, "[grid]\nd = 1e-3\nR = 1\ntau = 1\nG = 1\nv = 1\nv1_over_v = 0.1\n"
                  "[run]\nsamples = 5\n");
  const fs::path map = dir.path() / "map.h5";
  const std::vector<std::string> base = {"study",      "--quiet",  "--config",
                                         ini.string(), "--output", map.string()};
  struct Refused {
    std::vector<std::string> extra;
    std::string key;
  };
  const std::vector<Refused> refused = {
      {{"--G1", "1"}, "grid.tau1"},
      {{"--G2", "1", "--tau2", "1"}, "grid.G1"},
      {{"--temperature", "20"}, "grid.temperature"},
      {{"--wlf", "8.86:101.6:20"}, "run.wlf"},
      {{"--temperature", "-90", "--wlf", "8.86:101.6:20"}, "grid.temperature"},
      {{"--aT", "1e300", "--tau", "1e10"}, "grid.aT"},
      {{"--G1", "1", "--tau1", "2", "--solver", "exact"}, "run.solver"},
  };
  for (const Refused& r : refused) {
    SCOPED_TRACE(r.key);
    auto args = base;
    args.insert(args.end(), r.extra.begin(), r.extra.end());
    const Outcome o = run_mdrmap(args, kNoHangSeconds);
    EXPECT_EQ(o.code, 2) << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_TRUE(starts_with(o.err, "mdrmap study: error: " + r.key + ": ")) << o.err;
    EXPECT_FALSE(fs::exists(map));
  }
  auto args = base;
  args.insert(args.end(), {"--tau", "0", "--G1", "1,2", "--tau1", "0.5", "--temperature", "20,40",
                           "--wlf", "8.86:101.6:20"});
  const Outcome o = run_mdrmap(args, kNoHangSeconds);
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("4 cases in " + map.string()), std::string::npos) << o.err;
  EXPECT_TRUE(fs::is_regular_file(map));
  // the Kelvin study with the shift as a column
  const fs::path shifted = dir.path() / "shifted.h5";
  const Outcome k = run_mdrmap({"study", "--quiet", "--config", ini.string(), "--output",
                                shifted.string(), "--aT", "0.01,1"},
                               kNoHangSeconds);
  EXPECT_EQ(k.code, 0) << k.err;
  EXPECT_NE(k.err.find("2 cases in " + shifted.string() + ": 2 done, 0 failed"), std::string::npos)
      << k.err;
}

// --- mdrmap stationary -----------------------------------------------------------

/// The output of `mdrmap stationary`: comment lines, the header, then the
/// rows as the texts of their fields.
struct StationaryTable {
  std::vector<std::string> comments;
  std::string header;
  std::vector<std::vector<std::string>> rows;
};

StationaryTable parse_stationary(const std::string& text) {
  StationaryTable t;
  for (const auto& line : split_lines(text)) {
    if (starts_with(line, "#") && t.header.empty())
      t.comments.push_back(line);
    else if (t.header.empty())
      t.header = line;
    else
      t.rows.push_back(split(line, ','));
  }
  return t;
}

/// Runs `mdrmap stationary ARGS`: exit 0, nothing on stderr, the two comment
/// lines, the header and rows of seven fields.
StationaryTable run_stationary(const std::vector<std::string>& args) {
  std::vector<std::string> all{"stationary"};
  all.insert(all.end(), args.begin(), args.end());
  const Outcome r = run_mdrmap(all, kNoHangSeconds);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const StationaryTable t = parse_stationary(r.out);
  EXPECT_EQ(t.comments.size(), 2U) << r.out;
  EXPECT_TRUE(!t.comments.empty() && starts_with(t.comments[0], "# mdrmap ") &&
              t.comments[0].size() > 11 &&
              t.comments[0].compare(t.comments[0].size() - 11, 11, " stationary") == 0)
      << r.out;
  EXPECT_TRUE(t.comments.size() > 1 && starts_with(t.comments[1], "# case ")) << r.out;
  EXPECT_EQ(t.header, "v,d,a1,a2,FN,Fx,mu");
  for (const auto& row : t.rows)
    EXPECT_EQ(row.size(), 7U);
  return t;
}

/// Every row is the core's stationary_state of `c` at the row's v, printed
/// with 17 significant digits: each field's text equals format_double of the
/// core's double (which reads back to that double), so the command adds
/// nothing to the numbers.
void expect_core_states(const StationaryTable& t, const mdrmap::Case& c) {
  for (const auto& row : t.rows) {
    ASSERT_EQ(row.size(), 7U);
    const double v = to_double(row[0]);
    const mdrmap::State s = mdrmap::stationary_state(c, v);
    const double want[] = {v, s.d, s.a1, s.a2, s.FN, s.Fx, s.mu};
    for (std::size_t k = 0; k < 7; ++k)
      EXPECT_EQ(row[k], mdrmap::app::format_double(want[k]))
          << "column " << k << ", v = " << row[0];
  }
}

double rel_diff(double x, double ref) {
  return std::abs(x - ref) / std::abs(ref);
}

/// The cone's c = (pi/2) tan(beta) in long double, independent of the core.
double cone_c(double beta_deg) {
  const long double pi = 3.141592653589793238462643383279502884L;
  return static_cast<double>(pi / 2 * std::tan(static_cast<long double>(beta_deg) * pi / 180));
}

mdrmap::Case stationary_case(mdrmap::Profile profile, double G, double tau) {
  mdrmap::Case c;
  c.indenter.profile = profile;
  c.rheology.G = G;
  c.rheology.tau = tau;
  return c;
}

// The printed states are the core's (core/metrics/stationary.hpp), digit for
// digit; the cone's also equal the closed forms of docs/design.md ("Indenter
// profiles") to 1e-14.
TEST(cli, StationaryConeAtFixedDepthIsTheClosedForm) {
  const double beta = 20, d = 0.02, G = 3, tau = 2;
  const StationaryTable t =
      run_stationary({"--profile", "cone", "--beta", "20", "--d", "0.02", "--G", "3", "--tau", "2",
                      "--v-list", "0.001,0.01,0.0174,0.05,1"});
  ASSERT_EQ(t.rows.size(), 5U);
  EXPECT_EQ(t.comments[1], "# case profile=cone d=0.02 tau=2 G=3 beta=20");
  mdrmap::Case c = stationary_case(mdrmap::Profile::of<mdrmap::Cone>(), G, tau);
  c.indenter.as<mdrmap::Cone>().beta = beta;
  c.loading.d = d;
  expect_core_states(t, c);
  const double cc = cone_c(beta), a1 = d / cc;
  int rear_let_go = 0;
  for (const auto& row : t.rows) {
    const double v = to_double(row[0]), L = v * tau;
    SCOPED_TRACE("v = " + row[0]);
    const bool contact = L < a1;
    const double a2 = contact ? a1 - L : 0.0;
    const double FN =
        contact ? 4 * G * cc * (a1 * a1 + L * L / 2) : 4 * G * cc * (a1 * a1 / 2 + L * a1);
    const double Fx = contact ? 4 * G * cc * cc * L * (2 * a1 - L / 2) : cc * FN;
    rear_let_go += contact ? 0 : 1;
    EXPECT_EQ(to_double(row[1]), d);
    EXPECT_LE(rel_diff(to_double(row[2]), a1), 1e-14);
    EXPECT_LE(std::abs(to_double(row[3]) - a2), 1e-14 * a1);
    EXPECT_LE(rel_diff(to_double(row[4]), FN), 1e-14);
    EXPECT_LE(rel_diff(to_double(row[5]), Fx), 1e-14);
    EXPECT_LE(rel_diff(to_double(row[6]), Fx / FN), 1e-14);
  }
  EXPECT_EQ(rear_let_go, 2) << "the velocities straddle v tau = a1";
}

// A power law n = 1.5 under load on a two-term spectrum (quadrature and the
// root in a1): the core's states digit for digit, and F_N = F0.
TEST(cli, StationaryPowerLawUnderLoadWithASpectrumIsTheCores) {
  const StationaryTable t =
      run_stationary({"--profile", "power", "--n", "1.5", "--A", "2", "--F0", "0.05", "--tau",
                      "0.5", "--G", "1", "--prony", "2:0.1,5:10", "--v-list", "0.01,1,100"});
  ASSERT_EQ(t.rows.size(), 3U);
  EXPECT_TRUE(starts_with(t.comments[1], "# case profile=power F0=0.05000000000000000"))
      << t.comments[1];
  EXPECT_NE(t.comments[1].find(" prony=2:0.10000000000000001,5:10 a0="), std::string::npos)
      << t.comments[1];
  mdrmap::Case c = stationary_case(mdrmap::Profile::of<mdrmap::Power>(), 1.0, 0.5);
  c.indenter.as<mdrmap::Power>().n = 1.5;
  c.indenter.as<mdrmap::Power>().A = 2;
  c.loading.F0 = 0.05;
  c.rheology.branches = {{2.0, 0.1}, {5.0, 10.0}};
  expect_core_states(t, c);
  for (const auto& row : t.rows) {
    EXPECT_LE(rel_diff(to_double(row[4]), 0.05), 1e-12) << row[0];
    EXPECT_GT(to_double(row[3]), 0.0);
    EXPECT_LT(to_double(row[3]), to_double(row[2]));
  }
}

// The parabola, at fixed depth (with a modulus and a shift) and under load.
TEST(cli, StationaryParabolaIsTheCores) {
  const StationaryTable depth = run_stationary({"--d", "0.1", "--R", "10", "--tau", "1", "--G", "2",
                                                "--aT", "0.5", "--v-range", "0.01:100:5"});
  ASSERT_EQ(depth.rows.size(), 5U);
  EXPECT_EQ(depth.comments[1], "# case d=0.10000000000000001 R=10 tau=1 G=2 aT=0.5");
  mdrmap::Case c = stationary_case(mdrmap::Profile::of<mdrmap::Parabola>(), 2.0, 1.0);
  c.indenter.as<mdrmap::Parabola>().R = 10;
  c.loading.d = 0.1;
  c.rheology.aT = 0.5;
  expect_core_states(depth, c);

  const StationaryTable load =
      run_stationary({"--F0", "0.2", "--R", "10", "--tau", "1", "--v-list", "0.1,1,10"});
  ASSERT_EQ(load.rows.size(), 3U);
  mdrmap::Case l = stationary_case(mdrmap::Profile::of<mdrmap::Parabola>(), 1.0, 1.0);
  l.indenter.as<mdrmap::Parabola>().R = 10;
  l.loading.F0 = 0.2;
  expect_core_states(load, l);
  for (const auto& row : load.rows)
    EXPECT_LE(rel_diff(to_double(row[4]), 0.2), 1e-12) << row[0];
}

// The cone on the Kelvin foundation: for v tau >= a1 (the boundary
// included) the rear face has let go, a2 = 0, and mu = (pi/2) tan(beta),
// compared with the long-double value to 1e-15 (its double to a few ulps);
// just below, a2 > 0 and mu < (pi/2) tan(beta). Under load as well.
TEST(cli, StationaryConeOnKelvinHasMuPiOver2TanBetaForVTauFromA1) {
  for (const double beta : {10.0, 45.0, 80.0}) {
    SCOPED_TRACE("beta = " + num(beta));
    const mdrmap::Indenter cone = mdrmap::Cone{beta};
    const double a1 = cone.contact_radius(0.01); // the core's a1: v = a1 is v tau = a1 exactly
    std::string list = mdrmap::app::format_double(0.5 * a1);
    for (const double k : {1.0, 1.5, 10.0, 1e6})
      list += "," + mdrmap::app::format_double(k * a1);
    const StationaryTable t = run_stationary(
        {"--profile", "cone", "--beta", num(beta), "--d", "0.01", "--tau", "1", "--v-list", list});
    ASSERT_EQ(t.rows.size(), 5U);
    EXPECT_EQ(to_double(t.rows[1][0]), a1);
    EXPECT_GT(to_double(t.rows[0][3]), 0.0);
    EXPECT_LT(to_double(t.rows[0][6]), cone_c(beta) * (1 - 1e-3));
    for (std::size_t k = 1; k < t.rows.size(); ++k) {
      SCOPED_TRACE("v = " + t.rows[k][0]);
      EXPECT_EQ(t.rows[k][3], "0");
      EXPECT_LE(rel_diff(to_double(t.rows[k][6]), cone_c(beta)), 1e-15);
    }
    // under load: a0 of the load F0 = 4 G c a0^2, v tau from 2 a0 on (a1 < a0)
    const StationaryTable load = run_stationary({"--profile", "cone", "--beta", num(beta), "--F0",
                                                 "0.01", "--tau", "1", "--v-list", "1,100"});
    const double a0 = std::sqrt(0.01 / (4 * cone_c(beta)));
    ASSERT_EQ(load.rows.size(), 2U);
    for (const auto& row : load.rows) {
      SCOPED_TRACE("under load, v = " + row[0]);
      ASSERT_GE(to_double(row[0]), 2 * a0);
      EXPECT_EQ(row[3], "0");
      EXPECT_LE(rel_diff(to_double(row[6]), cone_c(beta)), 1e-15);
      EXPECT_LE(rel_diff(to_double(row[4]), 0.01), 1e-14);
    }
  }
}

// The exact sphere from the command line: at rest its force is Hertz's for the
// sphere (at a/R = 0.64, 16% above the paraboloid's), under load F_N is the
// load, simulate runs it, and a depth whose contact radius would reach R is
// refused in one line naming --d.
TEST(cli, SphereIsHertzsSphereAndRefusesAContactReachingR) {
  const double R = 0.02, d = 0.01;
  const double a = mdrmap::Indenter(mdrmap::Sphere{R}).contact_radius(d);
  const double hertz = 2.0 * ((a * a + R * R) * std::log((R + a) / (R - a)) - 2.0 * a * R);
  const std::vector<std::string> sphere{"--profile", "sphere", "--radius", num(R), "--tau", "1"};
  auto with = [&](std::vector<std::string> more) {
    more.insert(more.begin(), sphere.begin(), sphere.end());
    return more;
  };
  const StationaryTable t = run_stationary(with({"--d", num(d), "--v-list", "1e-14,1"}));
  ASSERT_EQ(t.rows.size(), 2U);
  EXPECT_LE(rel_diff(to_double(t.rows[0][4]), hertz), 1e-11); // (v tau / a = 1e-12)
  EXPECT_GT(rel_diff(hertz, 16.0 / 3.0 * a * a * a / R), 0.1);
  const StationaryTable load = run_stationary(with({"--F0", "0.001", "--v-list", "0.01,1"}));
  ASSERT_EQ(load.rows.size(), 2U);
  for (const auto& row : load.rows)
    EXPECT_LE(rel_diff(to_double(row[4]), 0.001), 1e-12) << row[0];
  std::vector<std::string> simulate = with({"--d", num(d), "--v", "0.01", "--v1", "0.001"});
  simulate.insert(simulate.begin(), "simulate");
  const Outcome sim = run_mdrmap(simulate, kNoHangSeconds);
  EXPECT_EQ(sim.code, 0) << sim.err;
  const Outcome far = run_mdrmap({"simulate", "--profile", "sphere", "--radius", "1", "--d", "100",
                                  "--tau", "1", "--v", "1", "--v1", "0.1"});
  EXPECT_EQ(far.code, 2);
  EXPECT_EQ(std::count(far.err.begin(), far.err.end(), '\n'), 1) << far.err;
  EXPECT_NE(far.err.find("--d: "), std::string::npos) << far.err;
  EXPECT_NE(far.err.find("not below"), std::string::npos) << far.err;
}

// --v-range LO:HI:N: N rows, log-spaced, the ends exactly the doubles of LO
// and HI as typed; --v-list keeps its order.
TEST(cli, StationaryVRangeIsLogSpacedWithExactEnds) {
  const std::vector<std::string> scene{"--d", "0.1", "--R", "10", "--tau", "1"};
  struct Range {
    std::string lo, hi;
    std::size_t n;
  };
  for (const Range& r : {Range{"0.003", "70", 9}, Range{"1e-3", "1e3", 2}, Range{"0.7", "0.71", 13},
                         Range{"1.5e-12", "3e+11", 101}}) {
    const std::string text = r.lo + ":" + r.hi + ":" + std::to_string(r.n);
    SCOPED_TRACE(text);
    auto args = scene;
    args.insert(args.end(), {"--v-range", text});
    const StationaryTable t = run_stationary(args);
    ASSERT_EQ(t.rows.size(), r.n);
    const double lo = to_double(r.lo), hi = to_double(r.hi);
    EXPECT_EQ(to_double(t.rows.front()[0]), lo);
    EXPECT_EQ(to_double(t.rows.back()[0]), hi);
    const double step = (std::log10(hi) - std::log10(lo)) / static_cast<double>(r.n - 1);
    for (std::size_t k = 1; k < r.n; ++k) {
      const double prev = to_double(t.rows[k - 1][0]), v = to_double(t.rows[k][0]);
      EXPECT_LT(prev, v) << k;
      EXPECT_LE(std::abs(std::log10(v) - std::log10(prev) - step), 1e-12 * std::max(1.0, step))
          << k;
    }
  }
  auto args = scene;
  args.insert(args.end(), {"--v-list", "10, 0.1,1"});
  const StationaryTable t = run_stationary(args);
  ASSERT_EQ(t.rows.size(), 3U);
  EXPECT_EQ(t.rows[0][0], "10");
  EXPECT_EQ(t.rows[1][0], "0.10000000000000001");
  EXPECT_EQ(t.rows[2][0], "1");
  // one velocity with --v
  args = scene;
  args.insert(args.end(), {"--v", "2"});
  const StationaryTable one = run_stationary(args);
  ASSERT_EQ(one.rows.size(), 1U);
  EXPECT_EQ(one.rows[0][0], "2");
}

// --output gets exactly what stdout gets.
TEST(cli, StationaryOutputFileEqualsStdout) {
  TempDir dir;
  const fs::path file = dir.path() / "states.csv";
  write_file(file, "old\n");
  const std::vector<std::string> args{"stationary", "--profile", "cone",     "--beta",
                                      "10",         "--d",       "0.01",     "--tau",
                                      "1",          "--v-range", "0.001:1:4"};
  const Outcome to_stdout = run_mdrmap(args);
  auto with_file = args;
  with_file.insert(with_file.end(), {"--output", file.string()});
  const Outcome to_file = run_mdrmap(with_file);
  EXPECT_EQ(to_stdout.code, 0) << to_stdout.err;
  EXPECT_EQ(to_file.code, 0) << to_file.err;
  EXPECT_EQ(to_file.out, "");
  EXPECT_EQ(to_file.err, "");
  EXPECT_EQ(read_file(file), to_stdout.out);
  EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"states.csv"});
}

// Bad input: exit 2, one line on stderr naming the option (or, where no one
// option is at fault, the choice to make), nothing on stdout, an existing
// --output file unchanged and no file left behind.
TEST(cli, StationaryBadInputsExit2WithOneLineNamingTheOption) {
  struct Bad {
    const char* label;
    std::vector<std::string> args; ///< after the scene
    std::string says;              ///< the message after "mdrmap stationary: error: "
  };
  const std::string choose = "give exactly one of --v V, --v-list V1,V2,... or --v-range LO:HI:N";
  const std::vector<Bad> rows{
      {"v-range N = 1", {"--v-range", "0.1:1:1"}, "--v-range: N (LO:HI:N) must be an integer"},
      {"v-range N = 0", {"--v-range", "0.1:1:0"}, "--v-range: N (LO:HI:N) must be an integer"},
      {"v-range N = 2.5", {"--v-range", "0.1:1:2.5"}, "--v-range: N (LO:HI:N) must be an integer"},
      {"v-range N too many", {"--v-range", "0.1:1:1000001"}, "--v-range: N (LO:HI:N)"},
      {"v-range LO = HI", {"--v-range", "1:1:3"}, "--v-range: LO must be below HI"},
      {"v-range LO > HI", {"--v-range", "2:1:3"}, "--v-range: LO must be below HI"},
      {"v-range two parts", {"--v-range", "0.1:1"}, "--v-range: must be LO:HI:N"},
      {"v-range LO = 0", {"--v-range", "0:1:3"}, "--v-range: LO must be a velocity"},
      {"v-range LO < 0", {"--v-range", "-1:1:3"}, "--v-range: LO must be a velocity"},
      {"v-range HI nan", {"--v-range", "0.1:nan:3"}, "--v-range: HI must be a velocity"},
      {"v-list not a number", {"--v-list", "0.1,abc,1"}, "--v-list: item 2 must be a velocity"},
      {"v-list empty item", {"--v-list", "0.1,,1"}, "--v-list: item 2 must be a velocity"},
      {"v-list trailing junk", {"--v-list", "0.1,1mm"}, "--v-list: item 2 must be a velocity"},
      {"v-list 0", {"--v-list", "1,0"}, "--v-list: item 2 must be a velocity"},
      {"v-list < 0", {"--v-list", "-2"}, "--v-list: item 1 must be a velocity"},
      {"v-list inf", {"--v-list", "1,inf"}, "--v-list: item 2 must be a velocity"},
      {"v-list overflows w tau / a", {"--v-list", "1,1e308"}, "--v-list: at v = 1e+308: "},
      {"v = 0", {"--v", "0"}, "--v: must be a finite number > 0, got 0"},
      {"v < 0", {"--v", "-1"}, "--v: must be a finite number > 0, got -1"},
      {"v not a number", {"--v", "fast"}, "--v: "},
      {"v twice", {"--v", "1", "--v", "2"}, "--v: may be given only once"},
      {"v without value", {"--v"}, "--v: needs a value"},
      {"--v and --v-list", {"--v", "1", "--v-list", "1,2"}, choose},
      {"--v-list and --v-range", {"--v-list", "1,2", "--v-range", "1:2:3"}, choose},
      {"none of them", {}, choose},
      {"--R with a cone", {"--R", "10", "--v", "1"}, "--R: applies to --profile parabola only"},
      {"--beta 90", {"--beta", "90", "--v", "1"}, "--beta: "},
      {"--n with a cone", {"--n", "2", "--v", "1"}, "--n: "},
      {"unknown option",
       {"--v", "1", "--speed", "3"},
       "--speed: not an option of mdrmap stationary"},
      {"simulate's option", {"--v", "1", "--samples", "5"}, "--samples: not an option"},
      {"history", {"--v", "1", "--history", "1:1"}, "--history: not an option"},
      {"stray argument", {"--v", "1", "7"}, "unexpected argument 7"},
      {"bad prony", {"--v", "1", "--prony", "1:-1"}, "--prony: "},
  };
  const std::vector<std::string> cone{"--profile", "cone", "--d", "0.01", "--tau", "1"};
  TempDir dir;
  const fs::path existing = dir.path() / "existing.csv";
  const std::string sentinel = "v,d,a1,a2,FN,Fx,mu\n1,2,3,4,5,6,7\n";
  for (const Bad& row : rows) {
    SCOPED_TRACE(row.label);
    std::vector<std::string> args{"stationary"};
    args.insert(args.end(), cone.begin(), cone.end());
    const bool sets_beta = std::find(row.args.begin(), row.args.end(), "--beta") != row.args.end();
    if (!sets_beta) args.insert(args.end(), {"--beta", "10"});
    args.insert(args.end(), row.args.begin(), row.args.end());
    if (row.args.empty() || row.args.back() != "--v")
      args.insert(args.end(), {"--output", existing.string()});
    write_file(existing, sentinel);
    const Outcome r = run_mdrmap(args, kNoHangSeconds);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(starts_with(r.err, "mdrmap stationary: error: " + row.says)) << r.err;
    EXPECT_EQ(read_file(existing), sentinel);
    EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"existing.csv"});
  }
  // neither or both: the message names what was given
  const Outcome both = run_mdrmap(
      {"stationary", "--d", "0.1", "--R", "1", "--tau", "1", "--v", "1", "--v-range", "1:2:3"});
  EXPECT_NE(both.err.find("got --v and --v-range"), std::string::npos) << both.err;
  const Outcome none = run_mdrmap({"stationary", "--d", "0.1", "--R", "1", "--tau", "1"});
  EXPECT_NE(none.err.find("got none"), std::string::npos) << none.err;
}

// The help lists every option with what it allows, in lines of at most 79
// columns; --help wins over bad options, and `mdrmap help stationary` is
// the same text. The options an unknown option's message lists are those.
TEST(cli, StationaryHelpListsEveryOptionWithItsRange) {
  const Outcome r = run_mdrmap({"stationary", "--help-all"});
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(run_mdrmap({"help", "stationary"}).out, r.out);
  EXPECT_EQ(run_mdrmap({"stationary", "--v", "abc", "--help-all"}).out, r.out);
  for (const auto& line : split_lines(r.out))
    EXPECT_LE(line.size(), 79U) << line;
  const std::string help = flattened(r.out);
  const std::vector<std::string> options{"--profile", "--d",          "--F0",     "--R",   "--tau",
                                         "--G",       "--aT",         "--beta",   "--n",   "--A",
                                         "--prony",   "--prony-file", "--T",      "--wlf", "--v",
                                         "--v-list",  "--v-range",    "--output", "--help"};
  for (const auto& o : options)
    EXPECT_NE(r.out.find("\n  " + o + " "), std::string::npos) << o;
  for (const auto& p : mdrmap::case_parameters()) {
    if (p.part == mdrmap::Part::Sampling || p.part == mdrmap::Part::History) continue;
    SCOPED_TRACE(p.name);
    EXPECT_NE(help.find(std::string("--") + p.name + " " + p.symbol + " (" +
                        mdrmap::dim_name(p.dim) + ") " + flattened(p.meaning)),
              std::string::npos);
    EXPECT_NE(help.find(p.allowed().substr(1)), std::string::npos) << p.allowed();
  }
  const mdrmap::ParamSpec& v = *mdrmap::find_parameter("v");
  for (const std::string& word :
       {"--v V (length/time) one velocity, " + v.allowed(), "each " + v.allowed(),
        "LO and HI each " + v.allowed() + ", LO < HI; N an integer from 2 to 1000000",
        std::string("at most 1000000 velocities"), mdrmap::branch_modulus_spec().allowed(),
        mdrmap::branch_time_spec().allowed(), std::string("at most 32 terms"),
        std::string("v,d,a1,a2,FN,Fx,mu"), std::string("--FN is accepted"),
        std::string("Default: parabola"), std::string("Exit codes")})
    EXPECT_NE(help.find(flattened(word)), std::string::npos) << word;

  const Outcome bad = run_mdrmap({"stationary", "--nope", "1"});
  std::string listed;
  for (const auto& o : options)
    if (o != "--help") listed += o + ", ";
  EXPECT_EQ(bad.code, 2);
  const std::string list = bad.err.substr(bad.err.find("case-sensitive: ") + 16);
  for (const auto& o : options)
    EXPECT_NE(list.find(o + ","), std::string::npos) << o;
  EXPECT_NE(list.find("--help-all)"), std::string::npos) << list;
  EXPECT_NE(list.find("--FN, "), std::string::npos);
}

} // namespace

namespace {

// Issue 32: a velocity step on a spectrum without a parallel dashpot printed
// a = -0 (mu is continuous across the change: 0 over a negative log) and
// D_c = nan at every step. Now the direct effect is read from the peak after
// the change (docs/design.md, "Event metrics"), and no number is printed as
// -0.
TEST(cli, SpectrumStepHasADirectEffectAndNoMinusZero) {
  for (const char* v1 : {"0.1", "10"}) {
    SCOPED_TRACE(v1);
    const Outcome r =
        run_mdrmap({"simulate", "--d", "0.1", "--R", "10", "--tau", "0", "--G", "1", "--prony",
                    "9:1,3:10", "--v", "1", "--v1", v1, "--samples", "5", "--rtol", "1e-3"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.find("=-0 "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("=-0\n"), std::string::npos) << r.out;
    const Parsed p = parse_output(r.out);
    ASSERT_EQ(p.events.size(), 1U);
    EXPECT_NE(to_double(p.events[0].at("a")), 0.0);
  }
}

} // namespace

// A 33rd spectrum term as an option (--G33, --tau33) is refused in one line
// naming the 32-term limit, not as an unknown option (issue 32).
TEST(cli, SpectrumTermPastTheLastNamesThe32TermLimit) {
  const std::vector<std::string> base{"--d", "0.1", "--R", "10",      "--tau",
                                      "0",   "--G", "1",   "--prony", "1:1"};
  for (const std::string cmd : {"simulate", "stationary"})
    for (const std::string opt : {"--G33", "--tau33", "--G100"}) {
      SCOPED_TRACE(cmd + " " + opt);
      std::vector<std::string> args{cmd};
      args.insert(args.end(), base.begin(), base.end());
      args.insert(args.end(), {"--v", "1", opt, "1"});
      const Outcome r = run_mdrmap(args, kNoHangSeconds);
      EXPECT_EQ(r.code, 2) << r.err;
      EXPECT_EQ(r.out, "");
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(starts_with(r.err, "mdrmap " + cmd + ": error: " + opt +
                                         ": a spectrum has at most 32 terms"))
          << r.err;
    }
}

// --- Help that fits a screen (issue 34) -----------------------------------------

namespace {

const std::vector<std::string> kHelpTopics{"simulate", "spectrum", "stationary", "study",
                                           "profiles", "history",  "config",     "exit-codes"};

/// Every line of `text` at most `columns` wide; at most `max_lines` lines.
void expect_fits(const std::string& text, std::size_t max_lines, std::size_t columns) {
  const auto lines = split_lines(text);
  EXPECT_LE(lines.size(), max_lines) << text;
  for (const auto& line : lines)
    EXPECT_LE(line.size(), columns) << line;
}

} // namespace

// mdrmap --help and every subcommand's --help: at most 40 lines of at most 80
// columns, pointing to --help-all; --help wins over bad options.
TEST(cli, HelpOfEverySubcommandFitsAScreen) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"--help"},
                                             {"simulate", "--help"},
                                             {"stationary", "--help"},
                                             {"study", "--help"},
                                             {"fit", "--help"}}) {
    SCOPED_TRACE(args.front());
    const Outcome r = run_mdrmap(args);
    EXPECT_EQ(r.code, 0);
    EXPECT_EQ(r.err, "");
    expect_fits(r.out, 40, 80);
    EXPECT_NE(r.out.find(args.size() == 1 ? "help [TOPIC]" : "--help-all"), std::string::npos);
  }
  EXPECT_EQ(run_mdrmap({"simulate", "--d", "abc", "--help"}).out,
            run_mdrmap({"simulate", "--help"}).out);
  EXPECT_EQ(run_mdrmap({"-h"}).out, run_mdrmap({"--help"}).out);
}

// --help-all names every option of the parameter table (stationary: those of
// a stationary case; study: every case parameter's override), and is the
// text of `mdrmap help COMMAND`.
TEST(cli, HelpAllListsEveryOptionOfTheParameterTable) {
  for (const std::string cmd : {"simulate", "stationary", "study"}) {
    SCOPED_TRACE(cmd);
    const Outcome r = run_mdrmap({cmd, "--help-all"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, run_mdrmap({"help", cmd}).out);
    expect_fits(r.out, 1000, 80);
    for (const auto& p : mdrmap::case_parameters()) {
      const bool sampling = p.part == mdrmap::Part::Sampling;
      if ((cmd == "stationary" && (sampling || p.part == mdrmap::Part::History)) ||
          (cmd == "study" && sampling))
        continue;
      const std::string label = cmd == "study" ? std::string("\n  --") + p.name + " "
                                               : std::string("\n  --") + p.name + " " + p.symbol;
      EXPECT_NE(r.out.find(label), std::string::npos) << p.name;
    }
    for (const auto& a : mdrmap::parameter_aliases())
      EXPECT_NE(r.out.find(std::string("--") + a.alias), std::string::npos) << a.alias;
  }
}

// `mdrmap help` lists the topics; `mdrmap help TOPIC` prints each in lines
// of at most 80 columns; an unknown topic is one line naming the topics,
// exit 2.
TEST(cli, HelpTopicsAndUnknownTopic) {
  const Outcome list = run_mdrmap({"help"});
  ASSERT_EQ(list.code, 0);
  expect_fits(list.out, 40, 80);
  for (const auto& t : kHelpTopics) {
    SCOPED_TRACE(t);
    EXPECT_NE(list.out.find("\n  " + t + " "), std::string::npos);
    const Outcome r = run_mdrmap({"help", t});
    EXPECT_EQ(r.code, 0);
    EXPECT_EQ(r.err, "");
    EXPECT_GT(split_lines(r.out).size(), 3U);
    expect_fits(r.out, 1000, 80);
  }
  EXPECT_NE(run_mdrmap({"help", "spectrum"}).out.find("--prony-file FILE"), std::string::npos);
  EXPECT_NE(run_mdrmap({"help", "config"}).out.find("grid.F0"), std::string::npos);
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"help", "bogus"}, {"help", "Simulate"}, {"help", "simulate", "extra"}}) {
    SCOPED_TRACE(args[1]);
    const Outcome r = run_mdrmap(args);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const auto& t : kHelpTopics)
      EXPECT_NE(r.err.find(t), std::string::npos) << t;
  }
}

// `mdrmap help --markdown [PAGE]` (either order) prints the generated
// reference pages of docs/reference/: the config page has a row for every
// case parameter of the core's table a study sets, the map page for every
// root attribute written; an unknown page is one line naming the pages, exit 2.
TEST(cli, HelpMarkdownPages) {
  const Outcome config = run_mdrmap({"help", "--markdown", "config"});
  ASSERT_EQ(config.code, 0) << config.err;
  EXPECT_EQ(run_mdrmap({"help", "config", "--markdown"}).out, config.out);
  for (const mdrmap::ParamSpec& p : mdrmap::case_parameters()) {
    if (p.part == mdrmap::Part::Sampling) continue; // [run] samples, decades
    const std::string row = "| `" + std::string(p.name) + "` | `SPEC` | " +
                            mdrmap::dim_name(p.dim) + " | " + p.allowed();
    EXPECT_NE(config.out.find(row), std::string::npos) << p.name;
  }
  const Outcome map = run_mdrmap({"help", "--markdown", "map-schema"});
  ASSERT_EQ(map.code, 0) << map.err;
  for (const char* a : {"mdrmap_schema", "n_cases", "segments", "samples", "loading"})
    EXPECT_NE(map.out.find(std::string("| `") + a + "` |"), std::string::npos) << a;
  EXPECT_EQ(run_mdrmap({"help", "--markdown"}).out.rfind("# Command-line reference", 0), 0u);
  const Outcome bad = run_mdrmap({"help", "--markdown", "bogus"});
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(bad.out, "");
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("map-schema"), std::string::npos) << bad.err;
}

// The study's help no longer says that a cone's or a power law's case fails
// (the spectrum solver takes them; the cone example study completes).
TEST(cli, StudyHelpHasNoStaleProfileStatement) {
  const Outcome r = run_mdrmap({"study", "--help-all"});
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(r.out.find("case fails"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("parabola only"), std::string::npos) << r.out;
}

// --- The tables' number format (app/csv_output.hpp) ---------------------------

namespace {

/// What write_csv_line writes for these values, read back from a temporary file.
std::string csv_line_text(const std::vector<double>& values) {
  std::FILE* f = std::tmpfile();
  if (f == nullptr) return "(no tmpfile)";
  mdrmap::app::write_csv_line(f, values.data(), values.size());
  std::rewind(f);
  std::string text;
  for (int ch = std::fgetc(f); ch != EOF; ch = std::fgetc(f))
    text += static_cast<char>(ch);
  std::fclose(f);
  return text;
}

/// format_double's rule: printf's "%.17g", but "nan" for every NaN and "0" for -0.
std::string printf_g17(double x) {
  if (std::isnan(x)) return "nan";
  if (x == 0.0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

} // namespace

TEST(CsvFormat, FormatDoubleIsPercent17gWithoutMinusZeroOrMinusNan) {
  using mdrmap::app::format_double;
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::pair<double, const char*> cases[] = {
      {0.1, "0.10000000000000001"},
      {1e-300, "1e-300"},
      {1e-5, "1.0000000000000001e-05"},
      {-0.0, "0"},
      {0.0, "0"},
      {1.0, "1"},
      {100.0, "100"},
      {1e16, "10000000000000000"},
      {1e21, "1e+21"},
      {123456789012345678.0, "1.2345678901234568e+17"},
      {5e-324, "4.9406564584124654e-324"},
      {-2.2250738585072014e-308, "-2.2250738585072014e-308"},
      {1.7976931348623157e308, "1.7976931348623157e+308"},
      {inf, "inf"},
      {-inf, "-inf"},
      {nan, "nan"},
      {-nan, "nan"}};
  for (const auto& [x, text] : cases) {
    EXPECT_EQ(format_double(x), text);
    char buf[mdrmap::app::kDoubleChars];
    EXPECT_EQ(std::string(buf, mdrmap::app::format_double_to(buf, x)), text);
  }
}

TEST(CsvFormat, FormatDoubleToMatchesPrintfOnRandomBits) {
  std::mt19937_64 bits(20261129);
  for (int n = 0; n < 20000; ++n) {
    const std::uint64_t b = bits();
    double x;
    std::memcpy(&x, &b, sizeof x);
    char buf[mdrmap::app::kDoubleChars];
    char* end = mdrmap::app::format_double_to(buf, x);
    ASSERT_LE(end - buf, static_cast<std::ptrdiff_t>(mdrmap::app::kDoubleChars));
    ASSERT_EQ(std::string(buf, end), printf_g17(x)) << "bits " << b;
    ASSERT_EQ(mdrmap::app::format_double(x), printf_g17(x)) << "bits " << b;
  }
}

TEST(CsvFormat, CsvLineIsFormatDoubleCommaSeparatedWithNewline) {
  using mdrmap::app::format_double;
  const std::vector<double> row = {
      0.1, 1e-300, -0.0, 123456789012345678.0, 5e-324, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_EQ(csv_line_text(row),
            "0.10000000000000001,1e-300,0,1.2345678901234568e+17,4.9406564584124654e-324,nan\n");
  EXPECT_EQ(csv_line_text({}), "\n");
  EXPECT_EQ(csv_line_text({-1.5}), "-1.5\n");
  // a line longer than the writer's stack buffer: the same text
  std::vector<double> wide;
  std::string want;
  for (int k = 0; k < 40; ++k) {
    wide.push_back(-2.2250738585072014e-308 * static_cast<double>(k + 1));
    want += (k == 0 ? "" : ",") + format_double(wide.back());
  }
  EXPECT_EQ(csv_line_text(wide), want + "\n");
}
