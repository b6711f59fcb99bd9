// Lab records as histories (issue 33): case/lab_record reads a record into a
// case (history and explicit output instants, Sampling::at); every solver
// samples at those instants what it samples at the same instants of uniform
// sampling; `mdrmap simulate --history-file` writes the record's rows and
// refuses bad files with one line.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "case/case_input.hpp"
#include "case/lab_record.hpp"
#include "core/model/case.hpp"
#include "core/solvers/dispatch.hpp"

#ifndef MDRMAP_EXE
#error "MDRMAP_EXE must name the mdrmap binary"
#endif

namespace {

namespace fs = std::filesystem;
using mdrmap::Case;
using mdrmap::InvalidInput;
using mdrmap::SolverKind;

/// A file of the test's own directory (removed with it).
class Files {
public:
  Files() {
    dir_ = fs::temp_directory_path() /
           ("mdrmap_lab_record_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  ~Files() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  Files(const Files&) = delete;
  Files& operator=(const Files&) = delete;
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path path(const std::string& name) const { return dir_ / name; }

private:
  fs::path dir_;
};

/// A step down and a hold: rows every 0.5 at v = 1, every 0.75 at 0.5, every
/// 0.5 at 0, from t = 10; measured mu and a comment in the record. The same
/// history is --history 1:2,0.5:3,0:2 --samples 5, whose instants are these.
const char* const kStepHold = "# a step and a hold\n"
                              "mu,v,t\n"
                              "0.5,1,10\n0.5,1,10.5\n0.5,1,11\n0.5,1,11.5\n"
                              "0.5,0.5,12\n0.5,0.5,12.75\n0.5,0.5,13.5\n0.5,0.5,14.25\n"
                              "\n"
                              "0.5,0,15\n0.5,0,15.5\n0.5,0,16\n0.5,0,16.5\n0.5,0,17\n";

Case depth_case() {
  Case c;
  c.loading.d = 0.1;
  c.indenter.as<mdrmap::Parabola>().R = 10.0;
  c.rheology.tau = 1.0;
  c.rheology.G = 1.0;
  return c;
}

TEST(LabRecord, ColumnsInAnyOrderCommentsAndEqualVelocitiesMerged) {
  Files f;
  const mdrmap::cases::LabRecord r = mdrmap::cases::read_lab_record(f.write("r.csv", kStepHold));
  ASSERT_EQ(r.t.size(), 13U);
  EXPECT_EQ(r.t.front(), 10.0);
  EXPECT_EQ(r.v[4], 0.5);
  Case c = depth_case();
  mdrmap::cases::apply_lab_record(r, c);
  EXPECT_EQ(c.history.v0, 1.0);
  ASSERT_EQ(c.history.size(), 3U);
  const double w[] = {1.0, 0.5, 0.0}, T[] = {2.0, 3.0, 2.0};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(c.history.segments[k].w, w[k]);
    EXPECT_EQ(c.history.segments[k].T, T[k]);
    EXPECT_EQ(c.sampling.count(k), 5);
    for (long j = 0; j < 5; ++j) // the record's instants are those of 5 linear samples
      EXPECT_DOUBLE_EQ(c.sampling.offset(k, j, T[k]), T[k] * static_cast<double>(j) / 4.0);
  }
  EXPECT_EQ(c.total_samples(), 15U);
  EXPECT_EQ(c.first_sample(2), 10U);
  const std::vector<std::size_t> rows = mdrmap::cases::record_rows(c);
  EXPECT_EQ(rows, (std::vector<std::size_t>{0, 1, 2, 3, 5, 6, 7, 8, 10, 11, 12, 13, 14}));
  const std::vector<double> slip = mdrmap::cases::record_slip(r);
  EXPECT_EQ(slip[4], 2.0);
  EXPECT_EQ(slip.back(), 3.5);
  mdrmap::validate(c);
}

/// The case with a history and its uniform sampling, and the same with the
/// instants given explicitly: each solver gives the same samples.
TEST(LabRecord, ExplicitInstantsGiveTheUniformSamplesWithEverySolver) {
  struct Run {
    SolverKind kind;
    bool load;
    double rtol;
  };
  for (const Run& run : {Run{SolverKind::Exact, false, 1e-6}, Run{SolverKind::Row, true, 1e-3},
                         Run{SolverKind::Row, false, 1e-3}, Run{SolverKind::Baseline, false, 1e-2},
                         Run{SolverKind::Auto, true, 1e-3}}) {
    Case c = depth_case();
    if (run.load) {
      c.loading.d = 0.0;
      c.loading.F0 = 0.5;
    }
    c.history.v0 = 1.0;
    c.history.segments = {{1.0, 2.0}, {0.5, 3.0}, {0.0, 2.0}};
    c.sampling.samples = 5;
    Case explicit_case = c;
    for (const auto& seg : c.history.segments) {
      std::vector<double> at;
      for (long j = 0; j < 5; ++j)
        at.push_back(c.sampling.offset(j, seg.T));
      explicit_case.sampling.at.push_back(at);
    }
    explicit_case.sampling.samples = 201; // (ignored where the instants are given)
    const mdrmap::Series a = mdrmap::run_case(mdrmap::CheckedCase(c), run.kind, run.rtol).series;
    const mdrmap::Series b =
        mdrmap::run_case(mdrmap::CheckedCase(explicit_case), run.kind, run.rtol).series;
    ASSERT_EQ(a.size(), 15U);
    ASSERT_EQ(b.size(), a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      SCOPED_TRACE("solver " + std::to_string(static_cast<int>(run.kind)) + " sample " +
                   std::to_string(i));
      EXPECT_EQ(b.t[i], a.t[i]);
      EXPECT_EQ(b.segment[i], a.segment[i]);
      EXPECT_EQ(b.FN[i], a.FN[i]);
      EXPECT_EQ(b.mu[i], a.mu[i]);
      EXPECT_EQ(b.a2[i], a.a2[i]);
    }
  }
}

TEST(LabRecord, ValidateRefusesInstantsThatDoNotSpanTheSegment) {
  Case c = depth_case();
  c.history.v0 = 1.0;
  c.history.segments = {{0.5, 2.0}};
  c.sampling.at = {{0.0, 1.0}}; // ends before T
  EXPECT_THROW(mdrmap::validate(c), InvalidInput);
  c.sampling.at = {{0.0, 1.5, 1.0, 2.0}}; // not increasing
  EXPECT_THROW(mdrmap::validate(c), InvalidInput);
  c.sampling.at = {{0.0, 1.0, 2.0}, {0.0, 1.0}}; // one list too many
  EXPECT_THROW(mdrmap::validate(c), InvalidInput);
  c.sampling.at = {{0.0, 1.0, 2.0}};
  EXPECT_NO_THROW(mdrmap::validate(c));
}

struct Outcome {
  int code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs mdrmap with `args` (no quoting needed: the test's own paths).
Outcome run_mdrmap(const Files& f, const std::string& args) {
  const fs::path out = f.path("stdout"), err = f.path("stderr");
  const std::string cmd =
      std::string(MDRMAP_EXE) + " " + args + " </dev/null >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  Outcome o;
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  o.out = slurp(out);
  o.err = slurp(err);
  return o;
}

/// The CSV lines after the comment lines (the header first).
std::vector<std::string> table(const std::string& text) {
  std::vector<std::string> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') rows.push_back(line);
  return rows;
}

const char* const kCase = "simulate --d 0.1 --R 10 --tau 1";

TEST(LabRecordCli, RecordRowsAreTheHistoryAtTheRecordsTimes) {
  Files f;
  const std::string rec = f.write("r.csv", kStepHold);
  const Outcome a = run_mdrmap(f, std::string(kCase) + " --history-file " + rec);
  ASSERT_EQ(a.code, 0) << a.err;
  const Outcome b =
      run_mdrmap(f, std::string(kCase) + " --v 1 --history 1:2,0.5:3,0:2 --samples 5");
  ASSERT_EQ(b.code, 0) << b.err;
  const std::vector<std::string> ra = table(a.out), rb = table(b.out);
  ASSERT_EQ(ra.size(), 14U);
  ASSERT_EQ(rb.size(), 16U);
  EXPECT_EQ(ra[0], "t,segment,FN,Fx,mu,a2,v,slip");
  // the record's rows: every sample of the history but the ends of segments
  // 0 and 1 (rows 5 and 10 of the history), which are the next starts' instants
  const std::size_t from[] = {1, 2, 3, 4, 6, 7, 8, 9, 11, 12, 13, 14, 15};
  const char* const v_slip[] = {",1,0",       ",1,0.5",    ",1,1",       ",1,1.5", ",0.5,2",
                                ",0.5,2.375", ",0.5,2.75", ",0.5,3.125", ",0,3.5", ",0,3.5",
                                ",0,3.5",     ",0,3.5",    ",0,3.5"};
  for (std::size_t n = 0; n < 13; ++n)
    EXPECT_EQ(ra[n + 1], rb[from[n]] + v_slip[n]) << "row " << n;
  EXPECT_NE(a.out.find(" sampling=record "), std::string::npos);
}

TEST(LabRecordCli, UnderLoadTheRowsHaveTheLoadColumnsThenVAndSlip) {
  Files f;
  // CR LF line ends and an extra column between t and v
  const std::string rec = f.write("r.csv", "t,FN,v\r\n0,1,1\r\n1,1,1\r\n2,1,0.1\r\n4,1,0.1\r\n");
  const Outcome o = run_mdrmap(f, "simulate --F0 0.5 --R 10 --tau 1 --history-file " + rec);
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<std::string> rows = table(o.out);
  ASSERT_EQ(rows.size(), 5U);
  EXPECT_EQ(rows[0], "t,segment,FN,Fx,mu,a2,d,a1,v,slip");
  EXPECT_EQ(rows[3].substr(0, 4), "2,1,");
  EXPECT_EQ(rows[4].substr(0, 4), "4,1,");
  std::vector<double> last;
  std::istringstream in(rows[4]);
  for (std::string x; std::getline(in, x, ',');)
    last.push_back(std::stod(x));
  ASSERT_EQ(last.size(), 10U);
  EXPECT_EQ(last[8], 0.1);
  EXPECT_DOUBLE_EQ(last[9], 2.2);  // 1 x 2 + 0.1 x 2
  EXPECT_NEAR(last[2], 0.5, 1e-3); // the load holds
}

TEST(LabRecordCli, SlidingAtTheEndOfALongSegmentIsStationary) {
  Files f;
  const std::string rec = f.write("r.csv", "v,t,Fx\n2,0,1\n1,0.5,1\n1,60,1\n");
  const Outcome o = run_mdrmap(f, std::string(kCase) + " --history-file " + rec);
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<std::string> rows = table(o.out);
  ASSERT_EQ(rows.size(), 4U);
  Case c = depth_case();
  c.history.v0 = 1.0;
  c.history.segments = {{1.0, 1.0}};
  const double mu_ss =
      mdrmap::run_case(mdrmap::CheckedCase(c), SolverKind::Exact, 1e-9).series.pre.mu;
  std::vector<double> last;
  std::istringstream in(rows.back());
  for (std::string x; std::getline(in, x, ',');)
    last.push_back(std::stod(x));
  ASSERT_EQ(last.size(), 8U);
  EXPECT_NEAR(last[0], 60.0, 1e-12);
  EXPECT_NEAR(last[4], mu_ss, 1e-9 * mu_ss);
  EXPECT_EQ(last[6], 1.0);
  EXPECT_NEAR(last[7], 1.0 + 59.5, 1e-12);
}

TEST(LabRecordCli, BadFilesAreRefusedWithOneLine) {
  Files f;
  struct Bad {
    const char* name;
    const char* text;
    const char* words;
  };
  for (const Bad& b :
       {Bad{"decreasing.csv", "t,v\n0,1\n1,1\n1,2\n", "decreasing.csv:4: t = 1"},
        Bad{"negative.csv", "t,v\n0,1\n1,-1\n2,1\n", "negative.csv:3: v = -1"},
        Bad{"no_v.csv", "t,mu\n0,1\n1,1\n", "no_v.csv:1: the header has no column v"},
        Bad{"one_row.csv", "t,v\n0,1\n", "needs at least two"},
        Bad{"text.csv", "t,v\n0,1\n1,fast\n", "text.csv:3: v must be a finite"},
        Bad{"short.csv", "t,v\n0,1\n1\n", "short.csv:3: the row has 1 value"},
        Bad{"rest.csv", "t,v\n0,0\n1,1\n", "the first row's v is 0"}}) {
    const Outcome o =
        run_mdrmap(f, std::string(kCase) + " --history-file " + f.write(b.name, b.text));
    EXPECT_EQ(o.code, 2) << b.name;
    EXPECT_TRUE(o.out.empty()) << b.name;
    EXPECT_EQ(o.err.find("--history-file: "), o.err.find("error: ") + 7) << o.err;
    EXPECT_NE(o.err.find(b.words), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find('\n'), o.err.size() - 1) << o.err;
  }
  const Outcome missing =
      run_mdrmap(f, std::string(kCase) + " --history-file " + f.path("none.csv").string());
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("--history-file: cannot read"), std::string::npos) << missing.err;
}

TEST(LabRecordCli, HistoryFileExcludesTheOtherHistoryOptions) {
  Files f;
  const std::string rec = f.write("r.csv", kStepHold);
  for (const char* other :
       {"--v 1", "--v1 0.5", "--history 1:1", "--t-end 3", "--samples 3", "--spacing log"}) {
    const Outcome o = run_mdrmap(f, std::string(kCase) + " --history-file " + rec + " " + other);
    EXPECT_EQ(o.code, 2) << other;
    EXPECT_NE(o.err.find("--history-file: cannot be combined with " +
                         std::string(other).substr(0, std::string(other).find(' '))),
              std::string::npos)
        << o.err;
    EXPECT_EQ(o.err.find('\n'), o.err.size() - 1) << o.err;
  }
}

} // namespace
