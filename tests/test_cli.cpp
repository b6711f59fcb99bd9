// End-to-end tests of the mdrmap command line: run the built binary
// (MDRMAP_EXE) and check exit codes, stderr and the exact output format.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <spawn.h>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

#include "core/exact.hpp"
#include "core/scene.hpp"
#include "core/solver.hpp"

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
Outcome run_mdrmap(const std::vector<std::string>& args) {
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
  while (::waitpid(pid, &status, 0) < 0) {
  }
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out_path);
  r.err = read_file(err_path);
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
  std::map<std::string, std::string> run, scene, pre;
  std::optional<double> error_vs_exact;
  std::vector<std::vector<double>> rows; ///< t, FN, Fx, mu, a2
};

/// Checks the exact structure of DESIGN.md section 2 / the simulate contract
/// and returns the parsed content. Fails the test (non-fatally) on deviations.
Parsed parse_output(const std::string& text) {
  Parsed p;
  EXPECT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "output must end with a newline";
  const auto lines = split_lines(text);
  std::size_t i = 0;
  while (i < lines.size() && starts_with(lines[i], "#"))
    p.comments.push_back(lines[i++]);
  if (i < lines.size()) p.header = lines[i++];
  EXPECT_EQ(p.header, "t,FN,Fx,mu,a2");

  EXPECT_GE(p.comments.size(), 3U);
  EXPECT_LE(p.comments.size(), 4U);
  if (p.comments.size() < 3) return p;
  const std::regex first(R"(^# mdrmap \S+ \(\S+\) simulate solver=\S+ rtol=\S+ error_estimate=\S+ )"
                         R"(cells_per_a1=\S+ elements=-?\d+ steps=-?\d+ element_updates=-?\d+ )"
                         R"(root_solves=-?\d+ wall_seconds=\S+$)");
  EXPECT_TRUE(std::regex_match(p.comments[0], first)) << p.comments[0];
  p.run = fields(p.comments[0]);
  const std::regex scene(R"(^# scene d=\S+ R=\S+ tau=\S+ v=\S+ v1=\S+ G=\S+ t_end=\S+ )"
                         R"(samples=\d+ zeta=\S+ zeta1=\S+$)");
  EXPECT_TRUE(std::regex_match(p.comments[1], scene)) << p.comments[1];
  p.scene = fields(p.comments[1]);
  if (p.comments.size() == 4) {
    const std::regex err(R"(^# error_vs_exact=\S+$)");
    EXPECT_TRUE(std::regex_match(p.comments[2], err)) << p.comments[2];
    p.error_vs_exact = to_double(fields(p.comments[2]).at("error_vs_exact"));
  }
  const std::regex pre(R"(^# pre FN=\S+ Fx=\S+ mu=\S+ a2=\S+$)");
  EXPECT_TRUE(std::regex_match(p.comments.back(), pre))
      << "the last comment line must be '# pre ...': " << p.comments.back();
  p.pre = fields(p.comments.back());

  for (; i < lines.size(); ++i) {
    const auto cells = split(lines[i], ',');
    EXPECT_EQ(cells.size(), 5U) << "row " << lines[i];
    std::vector<double> row;
    for (const auto& c : cells) {
      const double x = to_double(c);
      EXPECT_TRUE(std::isfinite(x)) << "row " << lines[i];
      row.push_back(x);
    }
    p.rows.push_back(row);
  }
  return p;
}

/// Checks the number of rows and t_k = k T / (N-1).
void expect_time_grid(const Parsed& p, long n, double t_end) {
  ASSERT_EQ(p.rows.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(p.rows.front()[0], 0.0);
  EXPECT_EQ(p.rows.back()[0], t_end);
  for (std::size_t k = 0; k < p.rows.size(); ++k) {
    const double tk = t_end * static_cast<double>(k) / static_cast<double>(n - 1);
    EXPECT_LE(std::abs(p.rows[k][0] - tk), 1e-15 * t_end) << "k = " << k;
  }
}

/// Compares the CSV rows and the pre line with a library series, per column
/// relative to the column's largest magnitude.
void expect_matches_series(const Parsed& p, const mdrmap::Series& ref, double tol) {
  ASSERT_EQ(p.rows.size(), ref.size());
  const std::vector<const std::vector<double>*> cols{&ref.t, &ref.FN, &ref.Fx, &ref.mu, &ref.a2};
  for (std::size_t c = 0; c < cols.size(); ++c) {
    double scale = 0.0;
    for (const double x : *cols[c])
      scale = std::max(scale, std::abs(x));
    for (std::size_t k = 0; k < ref.size(); ++k)
      EXPECT_LE(std::abs(p.rows[k][c] - (*cols[c])[k]), tol * scale)
          << "column " << c << " row " << k << ": " << p.rows[k][c] << " vs " << (*cols[c])[k];
  }
  const mdrmap::State& pre = ref.pre;
  EXPECT_LE(std::abs(to_double(p.pre.at("FN")) - pre.FN), tol * std::abs(pre.FN));
  EXPECT_LE(std::abs(to_double(p.pre.at("Fx")) - pre.Fx), tol * std::abs(pre.Fx));
  EXPECT_LE(std::abs(to_double(p.pre.at("mu")) - pre.mu), tol * std::abs(pre.mu));
  EXPECT_LE(std::abs(to_double(p.pre.at("a2")) - pre.a2), tol * std::abs(pre.a2));
}

const std::vector<std::string> kOptionNames{"--d",    "--R",      "--tau",    "--v",
                                            "--v1",   "--G",      "--t-end",  "--samples",
                                            "--rtol", "--solver", "--output", "--help"};

std::vector<std::string> simulate_args(const mdrmap::Scene& s) {
  auto num = [](double x) {
    std::ostringstream os;
    os.precision(17);
    os << x;
    return os.str();
  };
  return {"simulate", "--d",    num(s.d), "--R",     num(s.R), "--tau", num(s.tau),
          "--v",      num(s.v), "--v1",   num(s.v1), "--G",    num(s.G)};
}

// A scene whose transient (drop v = 10 -> v1 = 0.1) lasts about a third of the
// default window, so the samples cover both the root-solving part and the end.
mdrmap::Scene transient_scene() {
  mdrmap::Scene s;
  s.d = 0.1;
  s.R = 10.0;
  s.tau = 1.0;
  s.v = 10.0;
  s.v1 = 0.1;
  return s;
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
  const Outcome r = run_mdrmap({"simulate", "--help"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "");
  for (const auto& opt : kOptionNames)
    EXPECT_NE(r.out.find(opt + " "), std::string::npos) << opt;
  for (const char* word : {"t,FN,Fx,mu,a2", "# pre", "Example", "Exit codes", "Default: 201",
                           "Default: 1e-4", "Default: auto", "6 tau", "Kelvin", "mu = Fx/FN"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
  // --help wins over missing or bad options, and `mdrmap help simulate` is the same text.
  EXPECT_EQ(run_mdrmap({"simulate", "--d", "abc", "--help"}).out, r.out);
  EXPECT_EQ(run_mdrmap({"help", "simulate"}).out, r.out);
}

TEST(cli, SimulateDefaultRunHasExactStructure) {
  const Outcome r =
      run_mdrmap({"simulate", "--d", "0.1", "--R", "10", "--tau", "1", "--v", "2", "--v1", "0.5"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const Parsed p = parse_output(r.out);
  ASSERT_EQ(p.comments.size(), 3U) << "auto runs the exact solver: no error_vs_exact line";
  EXPECT_EQ(p.run.at("solver"), "exact");
  EXPECT_EQ(to_double(p.run.at("rtol")), 1e-4);
  EXPECT_GE(to_double(p.run.at("wall_seconds")), 0.0);
  EXPECT_LE(to_double(p.run.at("error_estimate")), 1e-4);
  EXPECT_EQ(to_double(p.scene.at("d")), 0.1);
  EXPECT_EQ(to_double(p.scene.at("R")), 10.0);
  EXPECT_EQ(to_double(p.scene.at("tau")), 1.0);
  EXPECT_EQ(to_double(p.scene.at("v")), 2.0);
  EXPECT_EQ(to_double(p.scene.at("v1")), 0.5);
  EXPECT_EQ(to_double(p.scene.at("G")), 1.0);
  EXPECT_EQ(to_double(p.scene.at("t_end")), 6.0);
  EXPECT_EQ(p.scene.at("samples"), "201");
  EXPECT_NEAR(to_double(p.scene.at("zeta")), 2.0, 1e-15);  // v tau / sqrt(R d) = 2 / 1
  EXPECT_NEAR(to_double(p.scene.at("zeta1")), 0.5, 1e-15); // v1 tau / sqrt(R d)
  expect_time_grid(p, 201, 6.0);
}

TEST(cli, SimulateValuesEqualTheLibrary) {
  const mdrmap::Scene s = transient_scene();
  const Outcome r = run_mdrmap(simulate_args(s));
  ASSERT_EQ(r.code, 0) << r.err;
  const Parsed p = parse_output(r.out);
  mdrmap::Protocol proto;
  proto.t_end = mdrmap::default_t_end(s);
  proto.samples = 201;
  expect_time_grid(p, 201, proto.t_end);
  EXPECT_GT(std::stol(p.run.at("root_solves")), 0L) << "scene should have a transient";
  // Same call as the command (auto at the default rtol): identical to the last digit printed.
  expect_matches_series(p, mdrmap::run_exact(s, proto, 1e-4).series, 1e-15);
  // And within rtol of the tightly solved continuum solution.
  expect_matches_series(p, mdrmap::run_exact(s, proto, 1e-12).series, 1e-4);
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
  EXPECT_EQ(to_double(p.scene.at("G")), 2.5);
  expect_time_grid(p, 11, 2.0);
  mdrmap::Scene s;
  s.d = 0.2;
  s.R = 5;
  s.tau = 0.5;
  s.v = 3;
  s.v1 = 1;
  s.G = 2.5;
  mdrmap::Protocol proto;
  proto.t_end = 2;
  proto.samples = 11;
  expect_matches_series(p, mdrmap::run_exact(s, proto, 1e-6).series, 1e-15);
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

struct EdgeScene {
  const char* label;
  mdrmap::Scene scene;
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
    mdrmap::Protocol proto;
    proto.t_end = mdrmap::default_t_end(c.scene);
    proto.samples = 41;
    EXPECT_EQ(to_double(p.scene.at("t_end")), proto.t_end);
    expect_time_grid(p, 41, proto.t_end);
    expect_matches_series(p, mdrmap::run_exact(c.scene, proto, 1e-4).series, 1e-15);
    if (c.scene.v1 == c.scene.v) { // nothing changes: every row is the state before the step
      for (const auto& row : p.rows) {
        EXPECT_NEAR(row[1], to_double(p.pre.at("FN")), 1e-14 * std::abs(row[1]));
        EXPECT_NEAR(row[4], to_double(p.pre.at("a2")), 1e-14 * std::abs(row[4]));
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
  for (const char* solver : {"mdr", "baseline"}) {
    SCOPED_TRACE(solver);
    write_file(out, "keep me\n");
    const Outcome r = run_mdrmap({"simulate", "--d", "0.1", "--R", "10", "--tau", "1", "--v", "2",
                                  "--v1", "0.5", "--samples", "5", "--rtol", "1e-2", "--solver",
                                  solver, "--output", out.string()});
    ASSERT_TRUE(r.code == 0 || r.code == 1) << "exit " << r.code << ": " << r.err;
    if (r.code == 0) {
      const Parsed p = parse_output(read_file(out));
      EXPECT_EQ(p.comments.size(), 4U);
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
// float-to-integer conversion that hung mdr, a NaN element count in the
// baseline): each solver either answers without NaN or fails with one line.
TEST(cli, SimulateAbsurdScalesNeverHangOrProduceNaN) {
  struct Row {
    std::vector<std::string> scene;
    const char* solver;
    bool must_fail;
  };
  const std::vector<Row> rows = {
      {{"--d", "1e-3", "--R", "1", "--tau", "1", "--v", "1e-300", "--v1", "1e300"}, "mdr", true},
      {{"--d", "1e-3", "--R", "1e-300", "--tau", "0", "--v", "1", "--v1", "1e300"}, "mdr", true},
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
      ASSERT_EQ(r.code, 1) << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(starts_with(r.err, std::string("mdrmap simulate: error: ") + row.solver + ":"))
          << r.err;
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
  const std::string sentinel = "# previous result\nt,FN,Fx,mu,a2\n0,1,2,3,4\n";
  const fs::path readonly_dir = dir.path() / "readonly";
  fs::create_directory(readonly_dir);
  fs::permissions(readonly_dir, fs::perms::owner_read | fs::perms::owner_exec);
  const fs::path plain_file = dir.path() / "plain";
  write_file(plain_file, "x");
  const fs::path missing_dir = dir.path() / "no_such_dir";

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
      {"missing --d", {{"d", kDrop}}, {}, "d"},
      {"missing --v1", {{"v1", kDrop}}, {}, "v1"},
      {"--d twice", {}, {"--d", "0.2"}, "d"},
      {"--d without value", {{"d", kDrop}}, {"--d"}, "d"},
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
      {"output empty", {{"output", ""}}, {}, "output", true},
  };
  ASSERT_GE(cases.size(), 20U);

  const std::vector<std::pair<std::string, std::string>> base{
      {"d", "0.1"}, {"R", "10"}, {"tau", "1"}, {"v", "2"}, {"v1", "0.5"}};

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

} // namespace
