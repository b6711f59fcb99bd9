// Study configs: INI parsing, axis specs, case lists, canonical text,
// command-line overrides, and a seeded fuzz test of the parsers.
#include <gtest/gtest.h>

#include <stdlib.h> // mkdtemp

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "core/model/case.hpp"
#include "study/case_columns.hpp"
#include "study/config.hpp"
#include "study/config_keys.hpp"

namespace fs = std::filesystem;
using mdrmap::InvalidInput;
using namespace mdrmap::study;

namespace {

/// A fresh directory from mkdtemp, removed at exit.
class TempDir {
public:
  TempDir() {
    std::string templ = (fs::temp_directory_path() / "mdrmap_test_config_XXXXXX").string();
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (mkdtemp(buf.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = buf.data();
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string write(const std::string& name, const std::string& content) const {
    const std::string p = (fs::path(path_) / name).string();
    fs::create_directories(fs::path(p).parent_path());
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p;
  }

private:
  std::string path_;
};

TempDir& tmp() {
  static TempDir dir;
  return dir;
}

StudyConfig parse(const std::string& text) {
  return parse_config(text, tmp().path(), "t.ini");
}

/// The base config, one line per entry (line numbers 1..9).
const std::vector<std::string> kBaseLines = {
    "[grid]",          // 1
    "d = 1e-3",        // 2
    "R = 1",           // 3
    "tau = 1",         // 4
    "v = 1",           // 5
    "v1_over_v = 0.5", // 6
    "[run]",           // 7
    "samples = 11",    // 8
    "rtol = 1e-4",     // 9
};

/// The base config with some lines replaced (1-based; "" drops the line's
/// content but keeps the numbering) and text appended.
std::string base(const std::map<int, std::string>& replace = {}, const std::string& append = "") {
  std::string out;
  for (std::size_t i = 0; i < kBaseLines.size(); ++i) {
    const auto it = replace.find(static_cast<int>(i + 1));
    out += (it != replace.end() ? it->second : kBaseLines[i]) + "\n";
  }
  return out + append;
}

/// Runs f, expects InvalidInput; returns it (option and message).
template <class F> std::pair<std::string, std::string> error_of(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return {e.option(), e.what()};
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than InvalidInput: " << e.what();
    return {"", ""};
  }
  ADD_FAILURE() << "did not throw";
  return {"", ""};
}

bool one_line(const std::string& s) {
  return s.find('\n') == std::string::npos && s.find('\r') == std::string::npos;
}

double at(const StudyConfig& c, std::size_t axis, std::size_t i) {
  return c.axes.at(axis).values.at(i);
}

/// The names of a study's columns, in column order.
std::vector<std::string> names(const StudyConfig& c) {
  std::vector<std::string> out;
  for (const Axis& a : c.axes)
    out.push_back(a.name);
  return out;
}

/// Index of the column `name` (c.axes.size() and a test failure when there is none).
std::size_t col(const StudyConfig& c, const std::string& name) {
  for (std::size_t i = 0; i < c.axes.size(); ++i)
    if (c.axes[i].name == name) return i;
  ADD_FAILURE() << "no column " << name;
  return c.axes.size();
}

/// The value of column `name` in a row.
double val(const StudyConfig& c, const Row& r, const std::string& name) {
  return r.at(col(c, name));
}

/// The cases of a study as Cases.
std::vector<mdrmap::Case> cases_of(const StudyConfig& c) {
  std::vector<mdrmap::Case> out;
  for (const Row& r : expand_cases(c))
    out.push_back(case_for(c, r));
  return out;
}

// --- Bad configs ----------------------------------------------------------------

struct BadConfig {
  const char* name;
  std::string text;
  std::string option;
  std::vector<std::string> mentions; ///< substrings the message must contain
};

std::vector<BadConfig> bad_configs() {
  const std::string big = "[grid]\nd = logspace:1e-6:1e-2:1000\nR = linspace:1:2:1000\n"
                          "tau = linspace:1:2:1001\nv = 1\nv1 = 0\n";
  return {
      {"unknown section", base({{7, "[runn]"}}), "config", {"t.ini:7:", "[run]"}},
      {"unknown section far", base({{7, "[xyzzy_section]"}}), "config", {"t.ini:7:", "[grid]"}},
      {"unknown run key",
       base({{8, "sample = 11"}}),
       "run.sample",
       {"t.ini:8:", "unknown key 'sample' in [run]; did you mean 'samples'?"}},
      {"unknown grid key", base({{4, "tua = 1"}}), "grid.tua", {"t.ini:4:", "'tau'"}},
      {"key case", base({{3, "r = 1"}}), "grid.r", {"t.ini:3:", "did you mean 'R'?"}},
      {"far key", base({{9, "foobarbaz = 1"}}), "run.foobarbaz", {"t.ini:9:", "keys of [run]"}},
      {"key in wrong section", base({{8, "d = 1"}}), "run.d", {"t.ini:8:", "belongs in [grid]"}},
      {"duplicate key", base({{9, "samples = 12"}}), "run.samples", {"t.ini:9:", "line 8"}},
      {"key outside section", "samples = 3\n" + base(), "config", {"t.ini:1:", "outside"}},
      {"grid and cases", base({}, "[cases]\nfile = x.csv\n"), "config", {"t.ini:10:", "[grid]"}},
      {"neither grid nor cases", "[run]\nsamples = 11\n", "config", {"t.ini:", "[grid]"}},
      {"section twice", base({}, "[run]\nG = 2\n"), "config", {"t.ini:10:", "line 7"}},
      {"missing axis tau",
       base({{4, ""}}),
       "grid.tau",
       {"t.ini:1:", "no tau", "d or F0, R, tau and v"}},
      {"missing v1", base({{6, ""}}), "history.w1", {"t.ini:1:", "w1_over_v", "v1"}},
      {"both v1 and v1_over_v",
       base({{6, "v1_over_v = 0.5\nv1 = 1"}}),
       "grid.v1",
       {"t.ini:7:", "both v1_over_v (grid.v1_over_v) and v1 are given", "give only one"}},
      {"missing cases file key",
       "[cases]\n[run]\nsamples = 5\n",
       "cases.file",
       {"t.ini:1:", "file"}},
      {"cases file does not exist",
       "[cases]\nfile = nope.csv\n",
       "cases.file",
       {"t.ini:2:", "nope.csv", "No such file"}},
      {"malformed section", base({{1, "[grid"}}), "config", {"t.ini:1:"}},
      {"junk after section", base({{7, "[run] x"}}), "config", {"t.ini:7:", "'x'"}},
      {"no equals sign", base({{9, "rtol 1e-4"}}), "config", {"t.ini:9:", "key = value"}},
      {"empty key", base({{9, "= 1e-4"}}), "config", {"t.ini:9:"}},
      {"empty value", base({{9, "rtol ="}}), "run.rtol", {"t.ini:9:", "no value"}},
      {"only a comment", base({{9, "rtol = ; none"}}), "run.rtol", {"t.ini:9:", "no value"}},
      {"number 1e", base({{2, "d = 1e"}}), "grid.d", {"t.ini:2:", "'1e' is not a number"}},
      {"number 1.2.3", base({{4, "tau = 1.2.3"}}), "grid.tau", {"t.ini:4:", "'1.2.3'"}},
      {"trailing junk", base({{3, "R = 1x"}}), "grid.R", {"t.ini:3:", "'1x'"}},
      {"nan", base({{5, "v = nan"}}), "grid.v", {"t.ini:5:", "finite"}},
      {"inf", base({{5, "v = inf"}}), "grid.v", {"t.ini:5:", "finite"}},
      {"overflow", base({{5, "v = 1e999"}}), "grid.v", {"t.ini:5:", "too large"}},
      {"empty list item", base({{5, "v = 1,,2"}}), "grid.v", {"t.ini:5:", "empty"}},
      {"trailing comma", base({{5, "v = 1, 2,"}}), "grid.v", {"t.ini:5:", "value 3 of 3"}},
      {"negative tau",
       base({{4, "tau = -1"}}),
       "grid.tau",
       {"t.ini:4:", "must be a finite number >= 0, got -1"}},
      {"zero depth", base({{2, "d = 0"}}), "grid.d", {"t.ini:2:", "> 0, got 0"}},
      {"list value out of range",
       base({{4, "tau = 1, -2, 3"}}),
       "grid.tau",
       {"t.ini:4:", "got -2", "value 2"}},
      {"linspace n = 0", base({{4, "tau = linspace:0:1:0"}}), "grid.tau", {"t.ini:4:", "n = 0"}},
      {"linspace n = 1 lo != hi",
       base({{4, "tau = linspace:0:1:1"}}),
       "grid.tau",
       {"t.ini:4:", "lo == hi"}},
      {"linspace fractional n",
       base({{4, "tau = linspace:0:1:2.5"}}),
       "grid.tau",
       {"t.ini:4:", "'2.5' is not an integer"}},
      {"linspace missing field",
       base({{4, "tau = linspace:0:1"}}),
       "grid.tau",
       {"t.ini:4:", "linspace:lo:hi:n"}},
      {"linspace bad lo", base({{4, "tau = linspace:a:1:3"}}), "grid.tau", {"t.ini:4:", "'a'"}},
      {"logspace lo = 0", base({{5, "v = logspace:0:1:3"}}), "grid.v", {"t.ini:5:", "lo > 0"}},
      {"logspace negative hi",
       base({{5, "v = logspace:1:-1:3"}}),
       "grid.v",
       {"t.ini:5:", "hi > 0"}},
      {"unknown form", base({{5, "v = lin:1:2:3"}}), "grid.v", {"t.ini:5:", "linspace"}},
      {"negative ratio",
       base({{6, "v1_over_v = -0.5"}}),
       "grid.v1_over_v",
       {"t.ini:6:", "got -0.5"}},
      {"negative v1", base({{6, "v1 = -1"}}), "grid.v1", {"t.ini:6:", "got -1"}},
      {"samples 1", base({{8, "samples = 1"}}), "run.samples", {"t.ini:8:", "from 2 to 1000000"}},
      {"samples too many", base({{8, "samples = 1000001"}}), "run.samples", {"t.ini:8:"}},
      {"samples huge",
       base({{8, "samples = 99999999999999999999999"}}),
       "run.samples",
       {"t.ini:8:", "99999999999999999999999"}},
      {"samples fractional", base({{8, "samples = 2.5"}}), "run.samples", {"t.ini:8:", "'2.5'"}},
      {"rtol too large", base({{9, "rtol = 0.5"}}), "run.rtol", {"t.ini:9:", "(0, 0.1]"}},
      {"rtol zero", base({{9, "rtol = 0"}}), "run.rtol", {"t.ini:9:"}},
      {"unknown solver", base({}, "solver = fast\n"), "run.solver", {"t.ini:10:", "'fast'", "row"}},
      {"retired solver",
       base({}, "solver = mdr\n"),
       "run.solver",
       {"t.ini:10:", "mdr was retired: use row"}},
      {"bad timeseries",
       base({}, "timeseries = maybe\n"),
       "run.timeseries",
       {"t.ini:10:", "true or false"}},
      {"G zero", base({}, "G = 0\n"), "run.G", {"t.ini:10:", "got 0"}},
      {"t_end_over_tau negative",
       base({}, "t_end_over_tau = -6\n"),
       "run.t_end_over_tau",
       {"t.ini:10:", "got -6"}},
      {"grid too large", big, "config", {"t.ini:1:", "1001000000", "1e9"}},
      {"timeseries too large",
       base({{2, "d = linspace:1e-3:1e-2:2000"}, {8, "samples = 1000000"}}, "timeseries = true\n"),
       "run.timeseries",
       {"t.ini:10:", "GiB", "2000 cases"}},
      {"d d G overflows",
       base({{2, "d = 1, 1e300"}, {3, "R = 1e300"}}),
       "grid.d",
       {"t.ini:2:", "(case d = 1"}},
      {"v tau overflows",
       base({{4, "tau = 1e300"}, {5, "v = 1, 1e300"}}),
       "grid.tau",
       {"t.ini:4:", "overflow", "(case d ="}},
      {"t_end overflows",
       base({{4, "tau = 1e300"}, {5, "v = 1e-300"}}, "t_end_over_tau = 1e10\n"),
       "run.t_end_over_tau",
       {"t.ini:10:", "t_end"}},
      {"v1_over_v * v overflows",
       base({{4, "tau = 0"}, {5, "v = 1e300"}, {6, "v1_over_v = 1e10"}}),
       "grid.v1_over_v",
       {"t.ini:6:", "v1_over_v * v"}},
      {"CRLF line numbers",
       "[grid]\r\nd = 1e-3\r\nR = 1\r\ntau = x\r\n",
       "grid.tau",
       {"t.ini:4:", "'x'"}},
  };
}

TEST(StudyConfigBad, EachNamesItsKeyAndLine) {
  const auto table = bad_configs();
  ASSERT_GE(table.size(), 30u);
  for (const auto& b : table) {
    SCOPED_TRACE(b.name);
    const auto [option, message] = error_of([&] { parse(b.text); });
    EXPECT_EQ(option, b.option) << message;
    for (const auto& m : b.mentions)
      EXPECT_NE(message.find(m), std::string::npos) << message;
    EXPECT_TRUE(one_line(message)) << message;
    EXPECT_EQ(message.rfind("t.ini:", 0), 0u) << message;
  }
}

// --- Good configs ---------------------------------------------------------------

TEST(StudyConfigGood, AllAxisFormsAndExactEnds) {
  const StudyConfig c = parse("; a comment\n"
                              "# another\n"
                              "\n"
                              "[grid]\n"
                              "  d   = 1e-3          ; single number\n"
                              "R = 1, 2 ,5\t# list\n"
                              "tau=linspace:0.5:2:4\n"
                              "v = logspace:1e-2:1e2:5\n"
                              "v1_over_v = 0, 1e-4\n");
  EXPECT_EQ(c.kind, StudyConfig::Kind::Grid);
  // the seed's form: G (default 1) and its window t_end_over_tau (default 6) are columns too
  EXPECT_EQ(names(c),
            std::vector<std::string>({"d", "R", "tau", "G", "v", "v1_over_v", "t_end_over_tau"}));
  EXPECT_EQ(c.axes[0].values, std::vector<double>({1e-3}));
  EXPECT_EQ(c.axes[0].section, "grid");
  EXPECT_EQ(c.axes[1].values, std::vector<double>({1, 2, 5}));
  EXPECT_EQ(c.axes[1].spec, "1, 2 ,5");
  EXPECT_EQ(c.axes[2].values, std::vector<double>({0.5, 1.0, 1.5, 2.0}));
  EXPECT_FALSE(c.axes[2].logarithmic);
  ASSERT_EQ(c.axes[4].values.size(), 5u);
  EXPECT_TRUE(c.axes[4].logarithmic);
  EXPECT_EQ(at(c, 4, 0), 1e-2); // exactly the ends
  EXPECT_EQ(at(c, 4, 4), 1e2);
  EXPECT_NEAR(at(c, 4, 1), 0.1, 1e-15);
  EXPECT_NEAR(at(c, 4, 2), 1.0, 1e-15);
  EXPECT_NEAR(at(c, 4, 3), 10.0, 1e-13);
  EXPECT_EQ(c.axes[5].values, std::vector<double>({0, 1e-4}));
  EXPECT_EQ(c.axes[5].column.kind, Column::Kind::VelocityOverV);
  EXPECT_EQ(c.axes[5].column.segment, 1u);
  EXPECT_EQ(case_count(c), 1u * 3 * 4 * 5 * 2);
  EXPECT_EQ(c.segments(), 1u);
  EXPECT_FALSE(c.by_force());
  // defaults
  EXPECT_EQ(c.axes[3].values, std::vector<double>({1.0})); // G
  EXPECT_EQ(c.axes[6].values, std::vector<double>({6.0})); // t_end_over_tau
  EXPECT_EQ(c.axes[6].section, "run");
  EXPECT_EQ(c.axes[6].option(), "run.t_end_over_tau");
  EXPECT_EQ(c.axes[6].column.kind, Column::Kind::DurationOverTau);
  EXPECT_EQ(c.run.samples, 201);
  EXPECT_EQ(c.run.rtol, 1e-4);
  EXPECT_EQ(c.run.solver, "auto");
  EXPECT_FALSE(c.run.timeseries);
  EXPECT_EQ(c.run.spacing, mdrmap::Spacing::Linear);
  EXPECT_EQ(c.run.decades, 4.0);
}

TEST(StudyConfigGood, LinspaceAndLogspaceEndsAreExact) {
  for (const auto& [lo, hi, n] : std::vector<std::tuple<double, double, int>>{
           {0.1, 0.7, 7}, {1e-9, 3.3, 13}, {0.3, 0.1, 3}, {1e-300, 1e300, 11}, {2.5, 2.5, 1}}) {
    for (const char* form : {"linspace", "logspace"}) {
      std::ostringstream spec;
      spec.precision(17);
      spec << form << ":" << lo << ":" << hi << ":" << n;
      SCOPED_TRACE(spec.str());
      const Axis a = parse_axis("grid", "v", spec.str());
      ASSERT_EQ(a.values.size(), static_cast<std::size_t>(n));
      EXPECT_EQ(a.values.front(), lo);
      EXPECT_EQ(a.values.back(), hi);
      for (std::size_t i = 0; i < a.values.size(); ++i)
        EXPECT_TRUE(std::isfinite(a.values[i]));
    }
  }
  const Axis g = parse_axis("grid", "v", "logspace:1e-300:1e300:7");
  EXPECT_NEAR(std::log10(g.values[3]), 0.0, 1e-12); // no overflow of hi/lo
}

TEST(StudyConfigGood, DescendingLinspace) {
  const Axis a = parse_axis("grid", "tau", "linspace:2:0.5:4");
  EXPECT_EQ(a.values, std::vector<double>({2.0, 1.5, 1.0, 0.5}));
  const Axis b = parse_axis("grid", "tau", "linspace:1:0:3");
  EXPECT_EQ(b.values, std::vector<double>({1.0, 0.5, 0.0}));
  const Axis l = parse_axis("grid", "v", "logspace:100:1:3");
  EXPECT_EQ(l.values.front(), 100.0);
  EXPECT_NEAR(l.values[1], 10.0, 1e-13);
  EXPECT_EQ(l.values.back(), 1.0);
}

TEST(StudyConfigGood, CaseOrderLastAxisFastest) {
  const StudyConfig c = parse("[grid]\nd = 1, 2\nR = 3\ntau = 0, 5\nv = 7\nv1 = 0, 11\n");
  const auto cases = expand_cases(c);
  ASSERT_EQ(cases.size(), 8u);
  ASSERT_EQ(case_count(c), 8u);
  std::size_t k = 0;
  for (double d : {1.0, 2.0})
    for (double tau : {0.0, 5.0})
      for (double v1 : {0.0, 11.0}) {
        SCOPED_TRACE(k);
        EXPECT_EQ(val(c, cases[k], "d"), d);
        EXPECT_EQ(val(c, cases[k], "R"), 3.0);
        EXPECT_EQ(val(c, cases[k], "tau"), tau);
        EXPECT_EQ(val(c, cases[k], "v"), 7.0);
        EXPECT_EQ(val(c, cases[k], "v1"), v1);
        EXPECT_EQ(val(c, cases[k], "G"), 1.0);
        EXPECT_EQ(val(c, cases[k], "t_end_over_tau"), 6.0);
        const mdrmap::Case x = case_for(c, cases[k]);
        EXPECT_EQ(x.loading.d, d);
        EXPECT_EQ(x.history.segments.at(0).w, v1);
        ++k;
      }
}

TEST(StudyConfigGood, V1OverVMultipliesV) {
  const StudyConfig c =
      parse("[grid]\nd = 1e-3\nR = 1\ntau = 1\nv = 2, 4\nv1_over_v = 0.5, 3\n[run]\nG = 2.5\n");
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 4u);
  EXPECT_EQ(cases[0].history.segments[0].w, 1.0);
  EXPECT_EQ(cases[1].history.segments[0].w, 6.0);
  EXPECT_EQ(cases[2].history.segments[0].w, 2.0);
  EXPECT_EQ(cases[3].history.segments[0].w, 12.0);
  for (const mdrmap::Case& k : cases)
    EXPECT_EQ(k.rheology.G, 2.5);
  EXPECT_EQ(c.axes[col(c, "G")].section, "run"); // the seed's [run] G
  EXPECT_EQ(c.axes[col(c, "G")].option(), "run.G");
}

TEST(StudyConfigGood, RunSettingsAndNormalization) {
  const StudyConfig c = parse("\xEF\xBB\xBF[run]\r\n"
                              "t_end_over_tau = 3 ; window\r\n"
                              "samples = +401\r\n"
                              "rtol = 1e-6\r\n"
                              "solver = spectrum\r\n"
                              "timeseries = YES\r\n"
                              "G = 0x10\r\n"
                              "spacing = LOG\r\n"
                              "decades = 6\r\n"
                              "[grid]\r\n"
                              "d=1e-3\r\nR=1\r\ntau=2, 0\r\nv=1\r\nv1=1 #comment\r\n");
  EXPECT_EQ(c.axes[col(c, "t_end_over_tau")].values, std::vector<double>({3.0}));
  EXPECT_EQ(c.run.samples, 401);
  EXPECT_EQ(c.run.rtol, 1e-6);
  EXPECT_EQ(c.run.solver, "row"); // spectrum: the row's old name
  EXPECT_TRUE(c.run.timeseries);
  EXPECT_EQ(c.run.spacing, mdrmap::Spacing::Log);
  EXPECT_EQ(c.run.decades, 6.0);
  EXPECT_EQ(c.axes[col(c, "G")].values, std::vector<double>({16.0}));
  for (const auto& [text, want] : std::vector<std::pair<std::string, bool>>{{"true", true},
                                                                            {"false", false},
                                                                            {"yes", true},
                                                                            {"no", false},
                                                                            {"1", true},
                                                                            {"0", false}}) {
    const StudyConfig t = parse(base({}, "timeseries = " + text + "\n"));
    EXPECT_EQ(t.run.timeseries, want) << text;
  }
}

TEST(StudyConfigGood, TrailingCommentNeedsWhitespace) {
  // "v1=1#x": '#' not after whitespace is part of the value, so it is not a number.
  const auto [option, message] = error_of([] { parse(base({{6, "v1 = 1#x"}})); });
  EXPECT_EQ(option, "grid.v1");
  EXPECT_NE(message.find("'1#x'"), std::string::npos) << message;
  const StudyConfig a = parse(base({{6, "v1 = 1 #x"}}));
  EXPECT_EQ(a.axes[col(a, "v1")].values, std::vector<double>({1.0}));
  const StudyConfig b = parse(base({{6, "v1 = 1\t;x"}}));
  EXPECT_EQ(b.axes[col(b, "v1")].values, std::vector<double>({1.0}));
}

TEST(StudyConfigGood, CaseForIsTheSeedStep) {
  const StudyConfig c = parse(base({{4, "tau = 0, 2"}}, "t_end_over_tau = 3\n"));
  const auto rows = expand_cases(c);
  ASSERT_EQ(rows.size(), 2u);
  for (const Row& r : rows) {
    // one segment v -> v1 over the window, [run] samples, linear
    const mdrmap::Case k = case_for(c, r);
    EXPECT_EQ(k.loading.d, val(c, r, "d"));
    EXPECT_EQ(k.loading.F0, 0.0);
    EXPECT_EQ(k.indenter.as<mdrmap::Parabola>().R, val(c, r, "R"));
    EXPECT_EQ(k.rheology.tau, val(c, r, "tau"));
    EXPECT_EQ(k.rheology.G, val(c, r, "G"));
    EXPECT_EQ(k.history.v0, val(c, r, "v"));
    ASSERT_EQ(k.history.size(), 1u);
    EXPECT_EQ(k.history.segments[0].w, val(c, r, "v1_over_v") * val(c, r, "v"));
    EXPECT_EQ(k.sampling.samples, 11);
    EXPECT_EQ(k.sampling.spacing, mdrmap::Spacing::Linear);
  }
  // tau = 0: the seed's default window, six contact half-widths at the slower velocity
  const mdrmap::Case k0 = case_for(c, rows[0]);
  EXPECT_DOUBLE_EQ(k0.history.segments[0].T,
                   mdrmap::default_step_duration(1e-3, 1.0, 0.0, 1.0, 0.5));
  EXPECT_EQ(case_for(c, rows[1]).history.segments[0].T, 6.0); // t_end_over_tau * tau
}

TEST(StudyConfigGood, ParseAxisErrorsNameTheAxis) {
  EXPECT_EQ(error_of([] { parse_axis("grid", "R", "0"); }).first, "grid.R");
  EXPECT_EQ(error_of([] { parse_axis("grid", "v1_over_v", "-1"); }).first, "grid.v1_over_v");
  EXPECT_EQ(error_of([] { parse_axis("grid", "q", "1"); }).first, "grid.q");
  EXPECT_EQ(error_of([] { parse_axis("grid", "v", "linspace:1:2:100000000"); }).first, "grid.v");
  EXPECT_EQ(error_of([] { parse_axis("grid", "v", ""); }).first, "grid.v");
  EXPECT_EQ(error_of([] { parse_axis("history", "T1_over_tau", "0"); }).first,
            "history.T1_over_tau");
  EXPECT_EQ(error_of([] { parse_axis("history", "w0", "1"); }).first, "history.w0");
  EXPECT_EQ(parse_axis("grid", "tau", "-0").values, std::vector<double>({0.0}));
  EXPECT_FALSE(std::signbit(parse_axis("grid", "tau", "-0").values[0])); // -0 normalized
}

TEST(StudyConfigGood, ParseColumnNames) {
  Column k;
  ASSERT_TRUE(parse_column("F0", k));
  EXPECT_EQ(k.kind, Column::Kind::Param);
  EXPECT_EQ(std::string(k.param->name), "F0");
  ASSERT_TRUE(parse_column("w12_over_v", k));
  EXPECT_EQ(k.kind, Column::Kind::VelocityOverV);
  EXPECT_EQ(k.segment, 12u);
  ASSERT_TRUE(parse_column("T3", k));
  EXPECT_EQ(k.kind, Column::Kind::Duration);
  EXPECT_EQ(k.segment, 3u);
  ASSERT_TRUE(parse_column("T2_over_tau", k));
  EXPECT_EQ(k.kind, Column::Kind::DurationOverTau);
  ASSERT_TRUE(parse_column("v1", k));
  EXPECT_EQ(k.kind, Column::Kind::Velocity);
  EXPECT_EQ(k.segment, 1u);
  for (const char* bad : {"w0", "T01", "w", "T", "w1_over_tau", "T1_over_v", "samples",
                          "log-decades", "x", "", "w1x", "v2"})
    EXPECT_FALSE(parse_column(bad, k)) << bad;
}

// --- Case lists ------------------------------------------------------------------

/// A case list `csv` read through a [cases] config with `extra` lines: its rows.
StudyConfig list_config(const std::string& csv, const std::string& extra = "") {
  return parse_config("[cases]\nfile = " + csv + "\n" + extra, "", "l.ini");
}

TEST(StudyCases, GoodCsvAnyColumnOrder) {
  const std::string p = tmp().write("good.csv", "v1, tau ,d,R,v\r\n"
                                                "\r\n"
                                                "0.5,1,1e-3,1,2\r\n"
                                                "  0 , 0 , 2e-3 , 3 , 4  \r\n"
                                                "\n"
                                                "7,2,1e-2,1,7\n");
  const StudyConfig c = list_config(p, "[run]\nG = 2\n");
  EXPECT_EQ(names(c),
            std::vector<std::string>({"d", "R", "tau", "G", "v", "v1", "t_end_over_tau"}));
  for (const char* listed : {"d", "R", "tau", "v", "v1"}) {
    EXPECT_TRUE(c.axes[col(c, listed)].listed) << listed;
    EXPECT_EQ(c.axes[col(c, listed)].option(), std::string("cases.") + listed);
  }
  EXPECT_FALSE(c.axes[col(c, "G")].listed);
  const auto rows = expand_cases(c);
  ASSERT_EQ(rows.size(), 3u);
  const auto cases = cases_of(c);
  EXPECT_EQ(cases[0].loading.d, 1e-3);
  EXPECT_EQ(cases[0].indenter.as<mdrmap::Parabola>().R, 1.0);
  EXPECT_EQ(cases[0].rheology.tau, 1.0);
  EXPECT_EQ(cases[0].history.v0, 2.0);
  EXPECT_EQ(cases[0].history.segments.at(0).w, 0.5);
  EXPECT_EQ(cases[0].history.segments.at(0).T, 6.0); // the seed's window: 6 tau
  EXPECT_EQ(cases[0].rheology.G, 2.0);
  EXPECT_EQ(cases[1].loading.d, 2e-3);
  EXPECT_EQ(cases[1].rheology.tau, 0.0);
  EXPECT_EQ(cases[1].history.segments.at(0).w, 0.0);
  EXPECT_EQ(cases[2].history.segments.at(0).w, 7.0);
  EXPECT_EQ(cases[2].rheology.tau, 2.0);
  EXPECT_EQ(cases[2].history.segments.at(0).T, 12.0);
}

TEST(StudyCases, BadCsvNamesLineAndColumn) {
  struct BadCsv {
    const char* name;
    std::string text;
    std::string option;
    std::vector<std::string> mentions;
  };
  const std::vector<BadCsv> table = {
      {"bad cell",
       "d,tau,R,v,v1\n1e-3,1,1,1,0\n1e-3,abc,1,1,0\n",
       "cases.tau",
       {"bad.csv:3:2:", "tau", "'abc'"}},
      {"negative d",
       "d,R,tau,v,v1\n\n-1,1,1,1,0\n",
       "cases.d",
       {"bad.csv:3:1:", "must be a finite number > 0, got -1"}},
      {"negative v1 last column",
       "R,d,tau,v,v1\n1,1e-3,1,1,-2\n",
       "cases.v1",
       {"bad.csv:2:5:", "got -2"}},
      {"nan cell", "d,R,tau,v,v1\n1e-3,nan,1,1,0\n", "cases.R", {"bad.csv:2:2:", "finite"}},
      {"empty cell", "d,R,tau,v,v1\n1e-3,1,,1,0\n", "cases.tau", {"bad.csv:2:3:", "empty"}},
      {"trailing junk", "d,R,tau,v,v1\n1e-3,1,1,1 m/s,0\n", "cases.v", {"bad.csv:2:4:", "'1 m/s'"}},
      {"missing column",
       "d,R,tau,v\n1e-3,1,1,1\n",
       "history.w1",
       {"bad.csv' and the config: no history", "w1_over_v", "v1"}},
      {"missing column R", "d,tau,v,v1\n1e-3,1,1,1\n", "grid.R", {"bad.csv' and the config: no R"}},
      {"unknown column", "d,R,tau,v,vv\n", "cases.file", {"bad.csv:1:5:", "'vv'"}},
      {"duplicate column", "d,R,tau,v,d,v1\n", "cases.file", {"bad.csv:1:5:", "twice"}},
      {"same column twice over",
       "d,R,tau,v,w1,v1,T1\n",
       "cases.file",
       {"bad.csv:1:6:", "'v1'", "'w1'"}},
      {"wrong field count", "d,R,tau,v,v1\n1e-3,1,1,1\n", "cases.file", {"bad.csv:2:", "4 fields"}},
      {"too many fields",
       "d,R,tau,v,v1\n1e-3,1,1,1,0,9\n",
       "cases.file",
       {"bad.csv:2:", "6 fields"}},
      {"header only", "d,R,tau,v,v1\n\n", "cases.file", {"bad.csv", "no cases"}},
      {"empty file", "", "cases.file", {"bad.csv", "header"}},
      {"combined overflow",
       "d,R,tau,v,v1\n1e-3,1,1e300,1e300,0\n",
       "cases.tau",
       {"bad.csv: case 1:", "overflow", "(case d = 0.001"}},
  };
  for (const auto& b : table) {
    SCOPED_TRACE(b.name);
    const std::string p = tmp().write("bad.csv", b.text);
    const auto [option, message] = error_of([&] { expand_cases(list_config(p)); });
    EXPECT_EQ(option, b.option) << message;
    for (const auto& m : b.mentions)
      EXPECT_NE(message.find(m), std::string::npos) << message;
    EXPECT_TRUE(one_line(message)) << message;
  }
  const auto missing = error_of([] { list_config(tmp().path() + "/nope.csv"); });
  EXPECT_EQ(missing.first, "cases.file");
  EXPECT_NE(missing.second.find("cannot read"), std::string::npos) << missing.second;
  const auto dir = error_of([] { list_config(tmp().path()); });
  EXPECT_EQ(dir.first, "cases.file");
  const std::string good = tmp().write("g.csv", "d,R,tau,v,v1\n1,1,1,1,1\n");
  EXPECT_EQ(error_of([&] { list_config(good, "[run]\nG = 0\n"); }).first, "run.G");
  EXPECT_EQ(cases_of(list_config(good)).at(0).rheology.G, 1.0); // G defaults to 1
}

TEST(StudyCases, CasesSectionResolvesRelativeToTheIni) {
  tmp().write("sub/list.csv", "d,R,tau,v,v1\n1e-3,1,1,1,0\n2e-3,1,0,1,0.5\n1e-3,2,1,3,9\n");
  const std::string ini =
      tmp().write("sub/study.ini", "[cases]\nfile = list.csv ; relative\n[run]\nsamples = 5\n");
  const StudyConfig c = load_config(ini);
  EXPECT_EQ(c.kind, StudyConfig::Kind::Cases);
  EXPECT_EQ(fs::path(c.cases_file), fs::path(tmp().path()) / "sub" / "list.csv");
  EXPECT_EQ(c.source_path, ini);
  EXPECT_NE(c.source_text.find("list.csv"), std::string::npos);
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 3u); // file order
  EXPECT_EQ(cases[0].loading.d, 1e-3);
  EXPECT_EQ(cases[1].loading.d, 2e-3);
  EXPECT_EQ(cases[2].history.segments.at(0).w, 9.0);
  EXPECT_EQ(case_count(c), 3u);
  // Absolute paths stay as they are.
  const std::string abs = (fs::path(tmp().path()) / "sub" / "list.csv").string();
  const StudyConfig a = parse_config("[cases]\nfile = " + abs + "\n", "/nonexistent", "x.ini");
  EXPECT_EQ(a.cases_file, abs);
  // canonical() holds the values, not the path.
  tmp().write("other/renamed.csv", "v1,v,tau,R,d\n0,1,1,1,1e-3\n0.5,1,0,1,2e-3\n9,3,1,2,1e-3\n");
  const StudyConfig b = parse_config("[run]\nsamples=5\n[cases]\nfile=renamed.csv\n",
                                     tmp().path() + "/other", "y.ini");
  EXPECT_EQ(canonical(b), canonical(c));
  tmp().write("other/changed.csv", "d,R,tau,v,v1\n1e-3,1,1,1,0\n2e-3,1,0,1,0.5\n1e-3,2,1,3,9.5\n");
  const StudyConfig d = parse_config("[run]\nsamples=5\n[cases]\nfile=changed.csv\n",
                                     tmp().path() + "/other", "y.ini");
  EXPECT_NE(canonical(d), canonical(c));
}

TEST(StudyCases, TimeseriesMemoryOfACaseList) {
  tmp().write("two.csv", "d,R,tau,v,v1\n1e-3,1,1,1,0\n2e-3,1,0,1,0.5\n");
  StudyConfig c =
      parse_config("[cases]\nfile = two.csv\n[run]\ntimeseries = true\n", tmp().path(), "t.ini");
  EXPECT_EQ(expand_cases(c).size(), 2u);
  c.run.samples = 1'000'000'000'000; // hand-made: far beyond what parse allows
  EXPECT_EQ(error_of([&] { expand_cases(c); }).first, "run.timeseries");
}

// --- canonical() -------------------------------------------------------------------

TEST(StudyCanonical, InvariantUnderFormatting) {
  const std::string a = "[grid]\nd = 1e-3\nR = 1, 2\ntau = linspace:0.5:2:4\nv = 1\n"
                        "v1_over_v = 0, 0.01\n[run]\nsamples = 101\ntimeseries = true\n"
                        "solver = auto\n";
  const std::string b = "# same study, reformatted\r\n"
                        "[run]\r\n"
                        "  solver=auto  ; the default\r\n"
                        "timeseries = yes\r\n"
                        "samples = +101\r\n"
                        "rtol = 0.0001\r\n"
                        "G = 1.0\r\n"
                        "t_end_over_tau = 6e0\r\n"
                        "\r\n"
                        "[grid]\r\n"
                        "v1_over_v =0,1e-2\r\n"
                        "v = 1.000\r\n"
                        "tau = 0.5, 1, 1.5, 2\r\n"
                        "R = 1,2\r\n"
                        "d = 0.001 # depth\r\n";
  const StudyConfig ca = parse(a), cb = parse(b);
  EXPECT_EQ(canonical(ca), canonical(cb));
  EXPECT_EQ(canonical(ca), canonical(ca));
  EXPECT_EQ(canonical(ca).find("t.ini"), std::string::npos);
}

TEST(StudyCanonical, SensitiveToEveryValue) {
  const std::string a = base();
  const std::string ref = canonical(parse(a));
  const double next = std::nextafter(1e-3, 1.0);
  std::ostringstream d1;
  d1.precision(17);
  d1 << "d = " << next;
  ASSERT_EQ(parse(base({{2, d1.str()}})).axes[0].values[0], next);
  const std::vector<std::string> changed = {
      base({{2, d1.str()}}),
      base({{3, "R = 1, 1"}}),
      base({{4, "tau = 2"}}),
      base({{5, "v = 1.5"}}),
      base({{6, "v1_over_v = 0.25"}}),
      base({{6, "v1 = 0.5"}}), // same numbers, different meaning
      base({{8, "samples = 12"}}),
      base({{9, "rtol = 2e-4"}}),
      base({}, "solver = exact\n"),
      base({}, "timeseries = true\n"),
      base({}, "G = 2\n"),
      base({}, "t_end_over_tau = 7\n"),
  };
  for (const auto& t : changed)
    EXPECT_NE(canonical(parse(t)), ref) << t;
}

// --- Overrides -------------------------------------------------------------------

TEST(StudyOverride, RunKeys) {
  StudyConfig c = parse(base());
  apply_override(c, "run.samples", "401");
  apply_override(c, "run.t_end_over_tau", "2.5");
  apply_override(c, "run.rtol", "1e-5");
  apply_override(c, "run.solver", "baseline");
  apply_override(c, "run.timeseries", "true");
  apply_override(c, "run.G", "3");
  apply_override(c, "run.spacing", "log");
  apply_override(c, "run.decades", "3");
  EXPECT_EQ(c.run.samples, 401);
  EXPECT_EQ(c.axes[col(c, "t_end_over_tau")].values, std::vector<double>({2.5}));
  EXPECT_EQ(c.run.rtol, 1e-5);
  EXPECT_EQ(c.run.solver, "baseline");
  EXPECT_TRUE(c.run.timeseries);
  EXPECT_EQ(c.run.spacing, mdrmap::Spacing::Log);
  EXPECT_EQ(c.run.decades, 3.0);
  EXPECT_EQ(c.axes[col(c, "G")].values, std::vector<double>({3.0}));
  const mdrmap::Case k = cases_of(c).front();
  EXPECT_EQ(k.rheology.G, 3.0);
  EXPECT_EQ(k.history.segments.at(0).T, 2.5); // tau = 1
  EXPECT_EQ(k.sampling.spacing, mdrmap::Spacing::Log);
  EXPECT_EQ(k.sampling.decades, 3.0);
  EXPECT_EQ(names(c).size(), 7u); // replaced, not added
}

// The key table (study/config_keys.hpp) behind `mdrmap help config` and
// docs/reference/config.md: every [grid] and [history] key it lists is a
// column the reader takes (a pattern's k, K as 1), every [run] key is
// accepted, and a [run] key's documented default, set explicitly, leaves the
// study as it was (the reader's default is the one the reference states).
TEST(StudyConfigKeys, TheReferenceTableIsWhatTheReaderTakes) {
  const StudyConfig ref =
      parse("[grid]\nd = 1e-3\nR = 1\ntau = 1\nv = 1\n[history]\nw1 = 2\nT1 = 1\n");
  const std::vector<std::string> keys = override_keys();
  std::size_t run_defaults = 0;
  for (const ConfigKey& k : config_keys()) {
    std::string key = k.key;
    for (const char* pattern : {"Gk", "tauk"})
      if (key == pattern) key.back() = '1';
    if (k.section == "history") key.replace(1, 1, "1"); // wK -> w1, TK_over_tau -> T1_over_tau
    if (k.section == "grid" || k.section == "history") {
      Column col;
      EXPECT_TRUE(parse_column(key, col)) << k.section << "." << k.key;
      EXPECT_EQ(col.history(), k.section == "history" || key == "v1" || key == "v1_over_v")
          << k.key;
    } else if (k.section == "run") {
      EXPECT_EQ(std::count(keys.begin(), keys.end(), "run." + key), 1) << key;
      if (k.given.rfind("default ", 0) != 0) continue;
      StudyConfig c = ref;
      apply_override(c, "run." + key, k.given.substr(8));
      EXPECT_EQ(canonical(c), canonical(ref)) << "run." << key << " = " << k.given;
      ++run_defaults;
    }
  }
  EXPECT_EQ(run_defaults, 8u); // samples ... timeseries, allow_large_shift, profile
}

TEST(StudyOverride, GridAxesAndV1Switch) {
  StudyConfig c = parse(base());
  apply_override(c, "grid.tau", "linspace:0:1:3");
  EXPECT_EQ(c.axes[2].values, std::vector<double>({0.0, 0.5, 1.0}));
  apply_override(c, "grid.d", "1e-4, 1e-2");
  EXPECT_EQ(c.axes[0].values, std::vector<double>({1e-4, 1e-2}));
  apply_override(c, "grid.v", "2");
  apply_override(c, "grid.R", "3");
  apply_override(c, "grid.v1", "0.25");
  EXPECT_EQ(names(c),
            std::vector<std::string>({"d", "R", "tau", "G", "v", "v1", "t_end_over_tau"}));
  EXPECT_EQ(cases_of(c).front().history.segments.at(0).w, 0.25);
  apply_override(c, "grid.v1_over_v", "0.25");
  EXPECT_EQ(c.axes[5].name, "v1_over_v");
  EXPECT_EQ(cases_of(c).front().history.segments.at(0).w, 0.5);
  EXPECT_EQ(case_count(c), 6u);
  apply_override(c, "grid.G", "2, 4"); // G as a grid axis replaces the default
  EXPECT_EQ(c.axes[3].option(), "grid.G");
  EXPECT_EQ(case_count(c), 12u);
}

TEST(StudyOverride, ErrorsSayCommandLineAndLeaveConfigUnchanged) {
  StudyConfig c = parse(base());
  const std::string before = canonical(c);
  struct Bad {
    std::string key, value, option, mention;
  };
  const std::vector<Bad> table = {
      {"run.samples", "1", "run.samples", "from 2 to"},
      {"run.sample", "5", "run.sample", "did you mean 'run.samples'?"},
      {"samples", "5", "samples", "did you mean 'run.samples'?"},
      {"grid.tau", "-1", "grid.tau", "must be a finite number >= 0, got -1"},
      {"grid.v", "logspace:0:1:2", "grid.v", "lo > 0"},
      {"run.solver", "fast", "run.solver", "'fast'"},
      {"run.rtol", "", "run.rtol", "no value"},
      {"grid.d", "linspace:1e-3:1:100000", "config", "cases"},
      {"run.timeseries", "true", "run.timeseries", "GiB"},
      {"cases.file", "x.csv", "cases.file", "[grid]"},
      {"grid.v", "1e300", "grid.v1_over_v", "v1_over_v * v"},
  };
  apply_override(c, "run.samples", "1000000");
  apply_override(c, "grid.d", "linspace:1e-3:1e-2:10000");
  const std::string big = canonical(c);
  for (const auto& b : table) {
    SCOPED_TRACE(b.key + "=" + b.value);
    StudyConfig copy = c;
    if (b.key == "grid.d") apply_override(copy, "grid.R", "linspace:1:2:100000");
    if (b.key == "grid.v") apply_override(copy, "grid.v1_over_v", "1e10");
    if (b.key == "grid.v" && b.value == "logspace:0:1:2")
      apply_override(copy, "grid.v1_over_v", "1");
    const std::string copy_before = canonical(copy);
    const auto [option, message] = error_of([&] { apply_override(copy, b.key, b.value); });
    EXPECT_EQ(option, b.option) << message;
    EXPECT_EQ(message.rfind("command line: ", 0), 0u) << message;
    EXPECT_NE(message.find(b.mention), std::string::npos) << message;
    EXPECT_EQ(canonical(copy), copy_before);
  }
  EXPECT_EQ(canonical(c), big);
  EXPECT_NE(before, big);
  // A [cases] study refuses grid axes.
  tmp().write("one.csv", "d,R,tau,v,v1\n1e-3,1,1,1,0\n");
  StudyConfig k = parse("[cases]\nfile = one.csv\n");
  EXPECT_EQ(error_of([&] { apply_override(k, "grid.d", "1"); }).first, "grid.d");
  apply_override(k, "run.samples", "7");
  EXPECT_EQ(k.run.samples, 7);
}

// --- Histories, loading by force, G -------------------------------------------------

/// A [grid] at fixed depth d = 1e-2 (a1 = 0.1), R = 1, and `rest` (tau, v, [history] ...).
StudyConfig depth_study(const std::string& rest) {
  return parse("[grid]\nd = 1e-2\nR = 1\n" + rest);
}

TEST(StudyHistory, HoldTimeSweepIsAnAxis) {
  const StudyConfig c = depth_study("tau = 2\nv = 0.5\n[history]\nw1_over_v = 0\n"
                                    "T1_over_tau = logspace:0.1:100:4\nw2_over_v = 1\n"
                                    "T2_over_tau = 20\n");
  EXPECT_EQ(names(c), std::vector<std::string>({"d", "R", "tau", "G", "v", "w1_over_v",
                                                "T1_over_tau", "w2_over_v", "T2_over_tau"}));
  EXPECT_EQ(c.segments(), 2u);
  const std::size_t T1 = col(c, "T1_over_tau");
  EXPECT_EQ(c.axes[T1].section, "history");
  EXPECT_EQ(c.axes[T1].option(), "history.T1_over_tau");
  EXPECT_TRUE(c.axes[T1].logarithmic);
  EXPECT_EQ(c.axes[T1].column.kind, Column::Kind::DurationOverTau);
  EXPECT_EQ(c.axes[T1].column.segment, 1u);
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 4u);
  const double holds[] = {0.1, 1.0, 10.0, 100.0};
  for (std::size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    ASSERT_EQ(cases[i].history.size(), 2u);
    EXPECT_EQ(cases[i].history.segments[0].w, 0.0);
    EXPECT_NEAR(cases[i].history.segments[0].T, 2.0 * holds[i], 1e-12 * holds[i]);
    EXPECT_EQ(cases[i].history.segments[1].w, 0.5);
    EXPECT_EQ(cases[i].history.segments[1].T, 40.0);
  }
  EXPECT_EQ(cases[0].history.segments[0].T, 0.2); // the ends exactly
  EXPECT_EQ(cases[3].history.segments[0].T, 200.0);
}

TEST(StudyHistory, RelativeColumnsResolveAgainstVAndTau) {
  const StudyConfig c = depth_study("tau = 0.5, 3\nv = 0.25, 2\n[history]\nw1_over_v = 4\n"
                                    "T1_over_tau = 1.5\n");
  const auto rows = expand_cases(c);
  ASSERT_EQ(rows.size(), 4u);
  for (const Row& r : rows) {
    const mdrmap::Case k = case_for(c, r);
    EXPECT_EQ(k.history.segments.at(0).w, 4.0 * val(c, r, "v"));
    EXPECT_EQ(k.history.segments.at(0).T, 1.5 * val(c, r, "tau"));
  }
  // absolute columns are taken as they are
  const StudyConfig a = depth_study("tau = 0.5, 3\nv = 0.25, 2\n[history]\nw1 = 4\nT1 = 1.5\n");
  for (const mdrmap::Case& k : cases_of(a)) {
    EXPECT_EQ(k.history.segments.at(0).w, 4.0);
    EXPECT_EQ(k.history.segments.at(0).T, 1.5);
  }
  EXPECT_NE(canonical(a), canonical(c));
  // a resolved value out of its range names the relative column and how it was resolved
  const auto [option, message] =
      error_of([] { depth_study("tau = 1e300\nv = 1\n[history]\nw1 = 1\nT1_over_tau = 1e10\n"); });
  EXPECT_EQ(option, "history.T1_over_tau");
  EXPECT_NE(message.find("T1 = T1_over_tau * tau"), std::string::npos) << message;
  EXPECT_EQ(message.rfind("t.ini:", 0), 0u) << message;
  EXPECT_TRUE(one_line(message)) << message;
}

TEST(StudyHistory, ThreeSegmentsInAnyKeyOrder) {
  const StudyConfig c = parse("[history]\nT3 = 7\nw2_over_v = 0\nT1_over_tau = 2\n"
                              "w3 = 0.25\nT2 = 5\nw1 = 3\n[grid]\ntau = 1.5\nv = 0.5\nR = 1\n"
                              "d = 1e-2\n");
  EXPECT_EQ(names(c), std::vector<std::string>({"d", "R", "tau", "G", "v", "w1", "T1_over_tau",
                                                "w2_over_v", "T2", "w3", "T3"}));
  EXPECT_EQ(c.segments(), 3u);
  const mdrmap::Case k = cases_of(c).at(0);
  ASSERT_EQ(k.history.size(), 3u);
  EXPECT_EQ(k.history.segments[0].w, 3.0);
  EXPECT_EQ(k.history.segments[0].T, 3.0);
  EXPECT_EQ(k.history.segments[1].w, 0.0);
  EXPECT_EQ(k.history.segments[1].T, 5.0);
  EXPECT_EQ(k.history.segments[2].w, 0.25);
  EXPECT_EQ(k.history.segments[2].T, 7.0);
  EXPECT_EQ(k.history.v0, 0.5);
}

TEST(StudyHistory, CaseOrderIsColumnOrderWhateverTheFileOrder) {
  const StudyConfig c = parse("[history]\nT2 = 1, 2\nw2 = 0, 1\nT1 = 3, 4\nw1 = 5, 6\n"
                              "[grid]\nv = 7, 8\nG = 9, 10\ntau = 11, 12\nR = 13, 14\n"
                              "F0 = 1e-3, 2e-3\n");
  EXPECT_EQ(names(c),
            std::vector<std::string>({"F0", "R", "tau", "G", "v", "w1", "T1", "w2", "T2"}));
  const auto rows = expand_cases(c);
  ASSERT_EQ(rows.size(), 512u);
  // C order over the columns: the last (T2) fastest, the loading slowest
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::size_t rest = i;
    for (std::size_t j = c.axes.size(); j-- > 0;) {
      EXPECT_EQ(rows[i][j], c.axes[j].values[rest % 2]) << i << " " << c.axes[j].name;
      rest /= 2;
    }
  }
  EXPECT_EQ(rows[1][8], 2.0);    // T2
  EXPECT_EQ(rows[2][7], 1.0);    // w2
  EXPECT_EQ(rows[256][0], 2e-3); // F0
}

TEST(StudyHistory, MissingOrDuplicatedSegmentColumns) {
  struct Bad {
    const char* name;
    std::string history;
    std::string option;
    std::vector<std::string> mentions;
  };
  const std::vector<Bad> table = {
      {"no history", "", "history.w1", {"no history", "w1", "T1_over_tau"}},
      {"segment 2 missing",
       "w1 = 1\nT1 = 1\nw3 = 1\nT3 = 1\n",
       "history.w2",
       {"segment 2 of 3 has no velocity", "give w2 or w2_over_v"}},
      {"duration missing",
       "w1 = 1\nT1 = 1\nw2_over_v = 1\n",
       "history.T2",
       {"segment 2 of 2 has no duration", "give T2 or T2_over_tau"}},
      {"velocity missing",
       "T1_over_tau = 1\n",
       "history.w1",
       {"segment 1 of 1 has no velocity", "give w1 or w1_over_v"}},
      {"w1 and w1_over_v",
       "w1 = 1\nT1 = 1\nw1_over_v = 2\n",
       "history.w1_over_v",
       {"both w1 (history.w1) and w1_over_v are given", "give only one"}},
      {"T1 and T1_over_tau",
       "T1_over_tau = 1\nw1 = 1\nT1 = 2\n",
       "history.T1",
       {"both T1_over_tau (history.T1_over_tau) and T1 are given"}},
      {"key twice", "w1 = 1\nT1 = 1\nw1 = 2\n", "history.w1", {"line"}},
      {"segment 0", "w0 = 1\nT1 = 1\n", "history.w0", {"w0"}},
      {"negative duration", "w1 = 1\nT1 = -1\n", "history.T1", {"got -1"}},
      {"zero duration ratio", "w1 = 1\nT1_over_tau = 0\n", "history.T1_over_tau", {"got 0"}},
      {"negative velocity ratio", "w1_over_v = -1\nT1 = 1\n", "history.w1_over_v", {"got -1"}},
  };
  for (const auto& b : table) {
    SCOPED_TRACE(b.name);
    const auto [option, message] =
        error_of([&] { depth_study("tau = 1\nv = 1\n[history]\n" + b.history); });
    EXPECT_EQ(option, b.option) << message;
    for (const auto& m : b.mentions)
      EXPECT_NE(message.find(m), std::string::npos) << message;
    EXPECT_TRUE(one_line(message)) << message;
    EXPECT_EQ(message.rfind("t.ini:", 0), 0u) << message;
  }
  // the seed's form and the new one say the same thing: both are refused
  const auto seed_and_new =
      error_of([] { depth_study("tau = 1\nv = 1\nv1 = 0.5\n[history]\nw1 = 1\nT1 = 1\n"); });
  EXPECT_EQ(seed_and_new.first, "history.w1") << seed_and_new.second;
  EXPECT_NE(seed_and_new.second.find("both v1 (grid.v1) and w1"), std::string::npos)
      << seed_and_new.second;
  const auto in_grid = error_of([] { parse(base({{6, "w1 = 1"}}, "[history]\nT1 = 1\n")); });
  EXPECT_EQ(in_grid.first, "grid.w1") << in_grid.second;
  EXPECT_NE(in_grid.second.find("[history]"), std::string::npos) << in_grid.second;
  EXPECT_EQ(
      error_of([] { parse(base({}, "t_end_over_tau = 3\n[history]\nT1_over_tau = 3\n")); }).first,
      "history.T1_over_tau");
}

TEST(StudyLoading, ByForceAndByDepth) {
  StudyConfig f = parse("[grid]\nF0 = logspace:1e-4:1e-2:3\nR = 1\ntau = 1\nv = 0.1\n"
                        "[history]\nw1_over_v = 10\nT1_over_tau = 10\n");
  EXPECT_TRUE(f.by_force());
  EXPECT_EQ(names(f).front(), "F0");
  EXPECT_EQ(f.axes[0].option(), "grid.F0");
  const auto cases = cases_of(f);
  ASSERT_EQ(cases.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_TRUE(cases[i].loading.by_force());
    EXPECT_EQ(cases[i].loading.d, 0.0);
    EXPECT_EQ(cases[i].loading.F0, f.axes[0].values[i]);
    EXPECT_EQ(cases[i].history.segments.at(0).w, 1.0);
  }
  EXPECT_FALSE(parse(base()).by_force());
  EXPECT_NE(canonical(f).find("F0 ="), std::string::npos);

  const auto both = error_of([] { parse(base({}, "[grid]\nF0 = 1e-3\n")); });
  EXPECT_EQ(both.first, "config") << both.second; // [grid] twice
  const auto d_and_fn = error_of([] { parse(base({{2, "d = 1e-3\nF0 = 1e-3"}})); });
  EXPECT_EQ(d_and_fn.first, "grid.F0") << d_and_fn.second;
  EXPECT_NE(d_and_fn.second.find("both d (grid.d) and F0 are given"), std::string::npos)
      << d_and_fn.second;
  EXPECT_EQ(d_and_fn.second.rfind("t.ini:3:", 0), 0u) << d_and_fn.second;
  const auto neither = error_of([] { parse(base({{2, ""}})); });
  EXPECT_EQ(neither.first, "grid.d") << neither.second;
  EXPECT_NE(neither.second.find("no d or F0"), std::string::npos) << neither.second;
  EXPECT_TRUE(one_line(neither.second));
  const auto zero = error_of([] { parse(base({{2, "F0 = 0"}})); });
  EXPECT_EQ(zero.first, "grid.F0");
  EXPECT_NE(zero.second.find("F0 must be a finite number > 0, got 0"), std::string::npos)
      << zero.second;
  // an override of the loading replaces it, as grid.v1_over_v replaces v1
  StudyConfig c = parse(base());
  apply_override(c, "grid.F0", "1e-3");
  EXPECT_TRUE(c.by_force());
  EXPECT_EQ(names(c).front(), "F0");
  EXPECT_EQ(cases_of(c).at(0).loading.F0, 1e-3);
  apply_override(c, "grid.d", "1e-3");
  EXPECT_FALSE(c.by_force());
  apply_override(f, "grid.F0", "2e-3");
  EXPECT_EQ(f.axes[0].values, std::vector<double>({2e-3}));
}

// FN, the prescribed load's old spelling, is read as F0 wherever a study
// names it (a [grid] key, an override, a case list's column): the same
// cases, the map's /cases/F0 and the same canonical text, so that either
// spelling resumes the other's map; both spellings at once are refused in
// one line naming both (issue 22).
TEST(StudyLoading, FNIsTheOldSpellingOfF0) {
  const auto grid = [](const std::string& key) {
    return "[grid]\n" + key +
           " = 1e-3, 2e-3\nR = 1\ntau = 1\nv = 0.1\n[history]\n"
           "w1_over_v = 10\nT1_over_tau = 10\n";
  };
  const StudyConfig f0 = parse(grid("F0")), fn = parse(grid("FN"));
  Column k;
  ASSERT_TRUE(parse_column("FN", k));
  EXPECT_EQ(std::string(k.param->name), "F0");
  EXPECT_TRUE(fn.by_force());
  EXPECT_EQ(fn.axes[0].option(), "grid.FN"); // located as written
  EXPECT_EQ(canonical(fn), canonical(f0));
  EXPECT_NE(canonical(fn).find("\nF0 = 0.001, 0.002\n"), std::string::npos) << canonical(fn);
  EXPECT_EQ(canonical(fn).find("FN"), std::string::npos) << canonical(fn);
  const auto load_of = [](const StudyConfig& c) {
    std::vector<double> out;
    for (const mdrmap::Case& x : cases_of(c))
      out.push_back(x.loading.F0);
    return out;
  };
  EXPECT_EQ(load_of(fn), load_of(f0));
  EXPECT_EQ(load_of(fn), std::vector<double>({1e-3, 2e-3}));
  // the map's /cases column of the load is F0, whatever the spelling
  const auto cases_paths = [](const StudyConfig& c) {
    std::vector<std::string> out;
    for (const auto& info : case_parameter_info(c))
      out.push_back(info.path);
    return out;
  };
  const std::vector<std::string> want{"cases/F0", "cases/R", "cases/tau", "cases/G", "cases/v"};
  EXPECT_EQ(cases_paths(fn), want);
  EXPECT_EQ(cases_paths(f0), want);
  EXPECT_NE(case_parameter_info(fn)[0].meaning.find("prescribed normal load"), std::string::npos);
  // an override grid.FN, on a depth study and on a load study's F0
  StudyConfig d = parse(base());
  apply_override(d, "grid.FN", "3e-3");
  EXPECT_TRUE(d.by_force());
  EXPECT_EQ(cases_paths(d).front(), "cases/F0");
  EXPECT_EQ(cases_of(d).at(0).loading.F0, 3e-3);
  StudyConfig o = parse(grid("F0"));
  apply_override(o, "grid.FN", "3e-3");
  EXPECT_EQ(load_of(o), std::vector<double>({3e-3}));
  const std::vector<std::string> keys = override_keys();
  EXPECT_NE(std::find(keys.begin(), keys.end(), "grid.F0"), keys.end());
  // a case list's column FN
  const std::string old_list = tmp().write("fn_alias.csv", "FN,R,tau,v,w1,T1\n1e-3,1,1,0.1,1,10\n");
  const std::string new_list = tmp().write("f0_alias.csv", "F0,R,tau,v,w1,T1\n1e-3,1,1,0.1,1,10\n");
  const StudyConfig lo = list_config(old_list), ln = list_config(new_list);
  EXPECT_TRUE(lo.by_force());
  EXPECT_EQ(cases_paths(lo), want);
  EXPECT_EQ(load_of(lo), load_of(ln));
  EXPECT_NE(canonical(lo).find("\nF0 = (listed)\n"), std::string::npos) << canonical(lo);
  EXPECT_EQ(canonical(lo), canonical(ln));
  // both spellings: one line naming both
  const auto two_keys = error_of([] { parse(base({{2, "F0 = 1e-3\nFN = 1e-3"}})); });
  EXPECT_EQ(two_keys.first, "grid.FN") << two_keys.second;
  EXPECT_NE(two_keys.second.find("both F0 (grid.F0) and FN are given"), std::string::npos)
      << two_keys.second;
  EXPECT_TRUE(one_line(two_keys.second)) << two_keys.second;
  StudyConfig c = parse(base());
  const auto overrides = error_of([&] {
    apply_overrides(c, {{"grid.F0", "1e-3"}, {"grid.FN", "2e-3"}});
  });
  EXPECT_EQ(overrides.first, "grid.FN") << overrides.second;
  EXPECT_EQ(overrides.second, "command line: grid.F0 and grid.FN are the same parameter (FN is "
                              "the old spelling of F0); give only one");
  const std::string both = tmp().write("both_alias.csv", "F0,FN,R,tau,v,w1,T1\n1,1,1,1,0.1,1,10\n");
  const auto columns = error_of([&] { list_config(both); });
  EXPECT_NE(columns.second.find("column 'FN' sets what column 'F0' sets"), std::string::npos)
      << columns.second;
  EXPECT_TRUE(one_line(columns.second)) << columns.second;
}

// The solver must solve the study's loading (the core's solver_handles):
// exact solves depth control only and is refused under a load at once, from
// the file or the command line, in a grid or a case list (it used to run and
// fail every case, exit 0).
TEST(StudyLoading, SolverMustSolveTheLoading) {
  const auto force = [](const std::string& solver) {
    return "[grid]\nF0 = 1e-3\nR = 1\ntau = 1\nv = 0.1\n[history]\nw1_over_v = 10\n"
           "T1_over_tau = 10\n[run]\nsolver = " +
           solver + "\n";
  };
  const auto in_file = error_of([&] { parse(force("exact")); });
  EXPECT_EQ(in_file.first, "run.solver") << in_file.second;
  EXPECT_EQ(in_file.second.rfind("t.ini:10: ", 0), 0u) << in_file.second;
  EXPECT_NE(in_file.second.find("exact does not solve load control"), std::string::npos)
      << in_file.second;
  EXPECT_NE(in_file.second.find("give solver = auto, row or baseline"), std::string::npos)
      << in_file.second;
  EXPECT_TRUE(one_line(in_file.second)) << in_file.second;
  for (const char* ok : {"auto", "row", "baseline"})
    EXPECT_TRUE(parse(force(ok)).by_force()) << ok;

  StudyConfig f = parse(force("auto"));
  const std::string before = canonical(f);
  const auto cl = error_of([&] { apply_override(f, "run.solver", "exact"); });
  EXPECT_EQ(cl.first, "run.solver") << cl.second;
  EXPECT_EQ(cl.second.rfind("command line: ", 0), 0u) << cl.second;
  EXPECT_EQ(canonical(f), before);
  // depth control takes every solver; switching it to a load refuses exact
  StudyConfig d = parse(base({}, "solver = exact\n"));
  EXPECT_FALSE(d.by_force());
  EXPECT_EQ(error_of([&] { apply_override(d, "grid.F0", "1e-3"); }).first, "run.solver");
  // a case list whose loading is a column of its CSV
  const std::string csv = tmp().write("fn_list.csv", "F0,R,tau,v,w1,T1\n1e-3,1,1,0.1,1,10\n");
  EXPECT_EQ(error_of([&] { list_config(csv, "[run]\nsolver = exact\n"); }).first, "run.solver");
  EXPECT_TRUE(list_config(csv, "[run]\nsolver = row\n").by_force());
}

// load_config with the command line's overrides applies them all, then checks
// (docs/studies.md): a file without [history] takes its segment from --set, a problem
// is located where its key was set.
TEST(StudyOverride, LoadConfigTakesTheHistoryFromOverrides) {
  const std::string ini = tmp().write("no_history.ini", "[grid]\nd = 1e-3\nR = 1\ntau = 2\n"
                                                        "v = 1\n[run]\nsamples = 5\n");
  const StudyConfig c =
      load_config(ini, {{"history.w1_over_v", "0"}, {"history.T1_over_tau", "10"}});
  EXPECT_EQ(c.segments(), 1u);
  EXPECT_EQ(c.source_path, ini);
  ASSERT_EQ(cases_of(c).size(), 1u);
  EXPECT_EQ(cases_of(c).at(0).history.segments.at(0).w, 0.0);
  EXPECT_EQ(cases_of(c).at(0).history.segments.at(0).T, 20.0);
  // the same as the file with the [history] section, but for the file's text
  const StudyConfig whole = parse_config("[grid]\nd = 1e-3\nR = 1\ntau = 2\nv = 1\n[run]\n"
                                         "samples = 5\n[history]\nw1_over_v = 0\n"
                                         "T1_over_tau = 10\n",
                                         tmp().path(), "w.ini");
  EXPECT_EQ(canonical(c), canonical(whole));
  // half a segment from the command line: its missing duration is located there
  const auto half = error_of([&] { load_config(ini, {{"history.w1_over_v", "0"}}); });
  EXPECT_EQ(half.first, "history.T1") << half.second;
  EXPECT_EQ(half.second.rfind("command line: ", 0), 0u) << half.second;
  // no history at all: the file's problem, located in the file
  const auto none = error_of([&] { load_config(ini, {{"grid.R", "2"}}); });
  EXPECT_EQ(none.first, "history.w1") << none.second;
  EXPECT_EQ(none.second.rfind(ini + ":1: ", 0), 0u) << none.second;
  // a bad override value is the command line's; a key of the file it did not set stays the file's
  EXPECT_EQ(error_of([&] { load_config(ini, {{"grid.R", "-1"}}); }).first, "grid.R");
  const std::string big = tmp().write("big_series.ini", "[grid]\nd = linspace:1e-3:2e-3:100\n"
                                                        "R = linspace:1:2:100\ntau = 1\nv = 1\n"
                                                        "v1_over_v = 0.5\n[run]\n"
                                                        "samples = 1000000\ntimeseries = true\n");
  const auto file = error_of([&] { load_config(big, {{"grid.tau", "2"}}); });
  EXPECT_EQ(file.first, "run.timeseries") << file.second;
  EXPECT_EQ(file.second.rfind(big + ":9: ", 0), 0u) << file.second;
  EXPECT_EQ(load_config(big, {{"run.samples", "5"}}).run.samples, 5);
}

TEST(StudyLoading, GAsAGridColumnAndTheSeedsRunG) {
  const StudyConfig g = parse(base({{3, "R = 1\nG = 0.5, 2"}}));
  EXPECT_EQ(g.axes[3].name, "G");
  EXPECT_EQ(g.axes[3].option(), "grid.G");
  const auto cases = cases_of(g);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].rheology.G, 0.5);
  EXPECT_EQ(cases[1].rheology.G, 2.0);
  const StudyConfig r = parse(base({}, "G = 0.5\n"));
  EXPECT_EQ(r.axes[3].option(), "run.G");
  EXPECT_EQ(cases_of(r).at(0).rheology.G, 0.5);
  // the same G either way: the same study
  EXPECT_EQ(canonical(r), canonical(parse(base({{3, "R = 1\nG = 0.5"}}))));
  const auto both = error_of([] { parse(base({{3, "R = 1\nG = 2"}}, "G = 2\n")); });
  EXPECT_EQ(both.first, "run.G") << both.second;
  EXPECT_NE(both.second.find("both G (grid.G) and G"), std::string::npos) << both.second;
  EXPECT_EQ(error_of([] { parse(base({{3, "R = 1\nG = -1"}})); }).first, "grid.G");
}

TEST(StudyHistory, DurationOverTauWithTauZero) {
  // depth control: a1 = sqrt(R d) = 0.1; six half-widths at the slower moving velocity
  const StudyConfig c = depth_study("tau = 0\nv = 2\n[history]\nw1_over_v = 0.5\n"
                                    "T1_over_tau = 3\nw2_over_v = 0\nT2_over_tau = 3\n"
                                    "w3 = 4\nT3_over_tau = 1\n");
  const mdrmap::Case k = cases_of(c).at(0);
  EXPECT_DOUBLE_EQ(k.history.segments[0].T, 6.0 * 0.1 / 1.0); // min(v, w1) = 1
  EXPECT_DOUBLE_EQ(k.history.segments[1].T, 6.0 * 0.1 / 1.0); // a hold after w1 = 1
  EXPECT_DOUBLE_EQ(k.history.segments[2].T, 6.0 * 0.1 / 4.0); // after a hold: w3
  // under load: the Hertz radius a0 (F0 = 16/3 G a0^3 / R with a0 = 0.1)
  const StudyConfig f = parse("[grid]\nF0 = 5.3333333333333e-3\nR = 1\ntau = 0\nv = 2\n"
                              "[history]\nw1 = 8\nT1_over_tau = 1\n");
  const mdrmap::Case kf = cases_of(f).at(0);
  EXPECT_NEAR(kf.a0(), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(kf.history.segments[0].T, 6.0 * kf.a0() / 2.0);
  // a hold after a hold has no time scale
  const auto [option, message] = error_of(
      [] { depth_study("tau = 0\nv = 2\n[history]\nw1 = 0\nT1 = 1\nw2 = 0\nT2_over_tau = 3\n"); });
  EXPECT_EQ(option, "history.T2_over_tau");
  EXPECT_NE(message.find("a hold after a hold"), std::string::npos) << message;
  EXPECT_NE(message.find("give T2 instead"), std::string::npos) << message;
  EXPECT_EQ(message.rfind("t.ini:", 0), 0u) << message;
  EXPECT_TRUE(one_line(message));
  // with tau > 0 in the same grid, only the tau = 0 cases are refused: the corners find them
  const auto grid = error_of([] {
    depth_study("tau = 0, 1\nv = 2\n[history]\nw1 = 0\nT1 = 1\nw2 = 0\nT2_over_tau = 3\n");
  });
  EXPECT_EQ(grid.first, "history.T2_over_tau") << grid.second;
  EXPECT_NE(grid.second.find("tau = 0"), std::string::npos) << grid.second;
}

// --- Relaxation spectra and the temperature (issue 19) ----------------------------

const char* const kWlf = "8.86:101.6:20";

double wlf_aT(double T) {
  return std::pow(10.0, -8.86 * (T - 20.0) / (101.6 + T - 20.0));
}

TEST(StudySpectrum, GridOverATermAndTheTemperature) {
  const StudyConfig c =
      depth_study("tau = 0\nG = 0.1\ntemperature = 20, 50\ntau1 = 0.5, 2\nG1 = 1\nG2 = 3\n"
                  "tau2 = 40\nv = 1\n[history]\nw1_over_v = 0.1\nT1_over_tau = 3\n[run]\n"
                  "wlf = " +
                  std::string(kWlf) + "\n");
  // the terms follow G, the temperature stands where aT would: the column order
  EXPECT_EQ(names(c), std::vector<std::string>({"d", "R", "tau", "G", "G1", "tau1", "G2", "tau2",
                                                "temperature", "v", "w1_over_v", "T1_over_tau"}));
  EXPECT_EQ(c.axes[col(c, "tau1")].option(), "grid.tau1");
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 4u); // tau1 x temperature, the last fastest
  for (std::size_t i = 0; i < 4; ++i) {
    const mdrmap::Rheology& r = cases[i].rheology;
    ASSERT_EQ(r.branches.size(), 2u);
    EXPECT_EQ(r.G, 0.1);
    EXPECT_EQ(r.tau, 0.0);
    EXPECT_EQ(r.branches[0].G, 1.0);
    EXPECT_EQ(r.branches[0].tau, i < 2 ? 0.5 : 2.0);
    EXPECT_EQ(r.branches[1].G, 3.0);
    EXPECT_EQ(r.branches[1].tau, 40.0);
    const double aT = i % 2 == 0 ? 1.0 : wlf_aT(50.0);
    EXPECT_NEAR(r.aT, aT, 1e-15 * aT);
    // tau = 0: the durations are relative to the time scale aT max(tau, tauk)
    EXPECT_NEAR(cases[i].history.segments[0].T, 3.0 * 40.0 * aT, 1e-13 * aT);
  }
  EXPECT_NE(canonical(c).find("wlf = 8.8599999999999994:101.59999999999999:20\n"),
            std::string::npos)
      << canonical(c);
}

// Issue 33: [run] wlf takes TREF's unit, the temperature column is in it and
// the canonical config records it; allow_large_shift takes a large shift.
TEST(StudySpectrum, WlfTakesTheUnitOfItsReference) {
  const auto grid = [](const std::string& T) {
    return "[grid]\nd = 1e-2\nR = 1\ntau = 1\nv = 1\ntemperature = " + T +
           "\n[history]\nw1_over_v = 0.5\nT1 = 1\n[run]\nwlf = ";
  };
  const StudyConfig c = parse(grid("308.15") + "17.44:51.6:298.15K\n");
  EXPECT_NEAR(std::log10(cases_of(c).at(0).rheology.aT), -17.44 * 10.0 / 61.6, 1e-12);
  EXPECT_NE(canonical(c).find("wlf = 17.440000000000001:51.600000000000001:298.14999999999998K\n"),
            std::string::npos)
      << canonical(c);
  const StudyConfig large = parse(grid("25") + "17.44:51.6:-100C\nallow_large_shift = true\n");
  EXPECT_NE(canonical(large).find("allow_large_shift = true\n"), std::string::npos);
  EXPECT_NEAR(std::log10(cases_of(large).at(0).rheology.aT), -17.44 * 125.0 / 176.6, 1e-12);
}

// Issue 33: the temperature column takes a unit, as --T does: converted to
// TREF's unit where TREF has another (the column, /cases and canonical in it);
// a bare TREF is read in the column's unit; one unit per column.
TEST(StudySpectrum, TemperaturesTakeUnits) {
  const auto grid = [](const std::string& T, const std::string& wlf) {
    return "[grid]\nd = 1e-2\nR = 1\ntau = 1\nv = 1\ntemperature = " + T +
           "\n[history]\nw1_over_v = 0.5\nT1 = 1\n[run]\nwlf = " + wlf + "\n";
  };
  const double at10 = -8.86 * 10.0 / 111.6; // log10 aT 10 degrees above TREF
  const StudyConfig k = parse(grid("25C, 35C", "8.86:101.6:298.15K"));
  ASSERT_EQ(k.axes.at(4).name, "temperature");
  EXPECT_EQ(k.axes[4].values, std::vector<double>({25.0 + 273.15, 35.0 + 273.15}));
  EXPECT_EQ(k.axes[4].unit, mdrmap::TempUnit::Kelvin);
  auto cases = cases_of(k);
  EXPECT_NEAR(std::log10(cases.at(0).rheology.aT), 0.0, 1e-12);
  EXPECT_NEAR(std::log10(cases.at(1).rheology.aT), at10, 1e-12);
  EXPECT_NE(canonical(k).find("temperature = 298.14999999999998K, 308.14999999999998K\n"),
            std::string::npos)
      << canonical(k);
  // the same study in C, spaced, against a Celsius TREF; and against a bare one
  for (const char* wlf : {"8.86:101.6:25C", "8.86:101.6:25"}) {
    const StudyConfig c = parse(grid("linspace:25C:35C:2", wlf));
    EXPECT_EQ(c.axes[4].values, std::vector<double>({25.0, 35.0}));
    EXPECT_NEAR(std::log10(cases_of(c).at(1).rheology.aT), at10, 1e-12);
  }
  // Kelvin values against a Celsius TREF
  const StudyConfig kc = parse(grid("308.15K", "8.86:101.6:25C"));
  EXPECT_NEAR(kc.axes[4].values.at(0), 35.0, 1e-12);
  EXPECT_NEAR(std::log10(cases_of(kc).at(0).rheology.aT), at10, 1e-12);
  // an override takes a unit too
  StudyConfig o = parse(grid("25", "8.86:101.6:25C"));
  apply_override(o, "grid.temperature", "308.15K");
  EXPECT_NEAR(std::log10(cases_of(o).at(0).rheology.aT), at10, 1e-12);
  // bare values keep their meaning: TREF's unit
  EXPECT_NEAR(std::log10(cases_of(parse(grid("35", "8.86:101.6:25C"))).at(0).rheology.aT), at10,
              1e-12);

  struct Bad {
    std::string T, wlf, said;
  };
  const std::vector<Bad> bad = {
      {"25C, 300K", "8.86:101.6:25C", "one unit for all its values, C or K"},
      {"25C, 35", "8.86:101.6:25C", "got 25C and 35"},
      {"25C,, 35C", "8.86:101.6:25C", "empty item"},
      {"-300C", "8.86:101.6:25C", "absolute zero"},
      {"linspace:-1K:20K:3", "8.86:101.6:25C", "absolute zero"},
      {"35C", "8.86:101.6:298.15", "give TREF its unit"},
      {"308.15", "8.86:101.6:25C", "give T its unit"},
      {"-77C", "8.86:101.6:25C", "must be > TREF - C2"},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.T + " " + b.wlf);
    const auto [option, message] = error_of([&] { parse(grid(b.T, b.wlf)); });
    EXPECT_EQ(option, "grid.temperature") << message;
    EXPECT_NE(message.find(b.said), std::string::npos) << message;
    EXPECT_EQ(message.rfind("t.ini:6: ", 0), 0u) << message;
    EXPECT_TRUE(one_line(message)) << message;
  }
}

// A case list's temperature cells take a unit each where TREF has one: each
// converted to TREF's unit as it is read; with a bare TREF a unit is refused.
TEST(StudySpectrum, ListedTemperaturesTakeUnits) {
  TempDir dir;
  dir.write("t.csv", "d,R,tau,temperature,v,w1,T1\n"
                     "1e-2,1,1,25C,1,0.5,1\n"
                     "1e-2,1,1,308.15K,1,0.5,1\n"
                     "1e-2,1,1,35,1,0.5,1\n");
  const auto study = [&](const std::string& wlf) {
    return parse_config("[cases]\nfile = t.csv\n[run]\nwlf = " + wlf + "\n", dir.path(), "l.ini");
  };
  const auto cases = cases_of(study("8.86:101.6:25C"));
  ASSERT_EQ(cases.size(), 3u);
  const double at10 = -8.86 * 10.0 / 111.6;
  EXPECT_NEAR(std::log10(cases[0].rheology.aT), 0.0, 1e-12);
  EXPECT_NEAR(std::log10(cases[1].rheology.aT), at10, 1e-12);
  EXPECT_NEAR(std::log10(cases[2].rheology.aT), at10, 1e-12); // bare: TREF's unit
  // against a Kelvin TREF the bare 35 reads as a Kelvin/Celsius mix-up (case 3)
  const auto [mixed_option, mixed] = error_of([&] { expand_cases(study("8.86:101.6:298.15K")); });
  EXPECT_NE(mixed.find("case 3: temperature T = 35 is a bare number"), std::string::npos) << mixed;
  // the rows as stored: in TREF's unit
  dir.write("t.csv", "d,R,tau,temperature,v,w1,T1\n1e-2,1,1,25C,1,0.5,1\n"
                     "1e-2,1,1,308.15K,1,0.5,1\n");
  const StudyConfig k = study("8.86:101.6:298.15K");
  const auto rows = expand_cases(k);
  const auto order = names(k);
  const auto T = static_cast<std::size_t>(std::find(order.begin(), order.end(), "temperature") -
                                          order.begin());
  EXPECT_EQ(rows.at(0).at(T), 25.0 + 273.15);
  EXPECT_EQ(rows.at(1).at(T), 308.15);
  EXPECT_NEAR(std::log10(case_for(k, rows.at(1)).rheology.aT), at10, 1e-12);
  const auto [option, message] = error_of([&] { expand_cases(study("8.86:101.6:25")); });
  EXPECT_EQ(option, "cases.temperature") << message;
  EXPECT_NE(message.find("t.csv:2:4: temperature 25C has a unit and TREF none"), std::string::npos)
      << message;
  EXPECT_TRUE(one_line(message)) << message;
}

TEST(StudySpectrum, ACaseListWithTermsAndAnAT) {
  TempDir dir;
  dir.write("spec.csv", "tau1,G1,aT,d,R,tau,G,v,w1,T1_over_tau,G2,tau2\n"
                        "0.1,2,1e-3,1e-2,1,0,1,1,0,10,1,5\n"
                        "0.2,3,10,1e-2,1,1,1,1,1,2,1,5\n");
  const StudyConfig c =
      parse_config("[cases]\nfile = spec.csv\n[run]\nsamples = 3\n", dir.path(), "l.ini");
  EXPECT_EQ(names(c), std::vector<std::string>({"d", "R", "tau", "G", "G1", "tau1", "G2", "tau2",
                                                "aT", "v", "w1", "T1_over_tau"}));
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].rheology.branches.at(0).tau, 0.1);
  EXPECT_EQ(cases[0].rheology.branches.at(0).G, 2.0);
  EXPECT_EQ(cases[0].rheology.aT, 1e-3);
  EXPECT_EQ(cases[0].history.segments[0].T, 10.0 * 5.0 * 1e-3); // aT max(tau, tauk)
  EXPECT_EQ(cases[1].rheology.aT, 10.0);
  EXPECT_EQ(cases[1].history.segments[0].T, 2.0 * 5.0 * 10.0);
}

TEST(StudySpectrum, ATIsAColumnOnlyWhereGiven) {
  // a study without the optional columns has those it always had
  EXPECT_EQ(names(parse(base())),
            std::vector<std::string>({"d", "R", "tau", "G", "v", "v1_over_v", "t_end_over_tau"}));
  const StudyConfig c = parse(base({{4, "tau = 2\naT = 1e-2, 1"}}));
  EXPECT_EQ(names(c), std::vector<std::string>(
                          {"d", "R", "tau", "G", "aT", "v", "v1_over_v", "t_end_over_tau"}));
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].rheology.aT, 1e-2);
  // the seed's default window t_end_over_tau = 6: six shifted times
  EXPECT_EQ(cases[0].history.segments[0].T, 6.0 * 2.0 * 1e-2);
  EXPECT_EQ(cases[1].history.segments[0].T, 12.0);
}

// Issue 33: [run] material = FILE takes the spectrum (G, Gk, tauk: columns
// of one value) and the WLF constants from an Abaqus card, relative to the
// config's directory; the canonical study holds the card's text.
const std::string kCard = "** two terms\n*Material, name=R\n*Elastic, moduli=INSTANTANEOUS\n"
                          "15., 0.5\n*Viscoelastic, time=PRONY\n0.2, 0.1, 0.5\n0.6, 0., 20.\n"
                          "*Trs, definition=WLF\n25., 8.86, 101.6\n";

std::string card_study(const std::string& grid = "", const std::string& run = "") {
  return "[grid]\nd = 1e-2\nR = 1\ntau = 0\nv = 1\n" + grid +
         "[history]\nw1_over_v = 0.5\nT1 = 1\n[run]\nmaterial = card.inp\n" + run;
}

TEST(StudyMaterial, CardGivesTheSpectrumAndItsWlf) {
  TempDir dir;
  dir.write("sub/card.inp", kCard);
  const std::string ini = dir.write("sub/s.ini", card_study("temperature = 25, 35\n"));
  const StudyConfig c = load_config(ini); // the card is found beside the config, not in the cwd
  EXPECT_EQ(names(c), std::vector<std::string>({"d", "R", "tau", "G", "G1", "tau1", "G2", "tau2",
                                                "temperature", "v", "w1_over_v", "T1"}));
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 2u);
  // G0 = E / 3 = 5 (INSTANTANEOUS), G_i = g_i G0, G = G0 (1 - sum g_i)
  EXPECT_DOUBLE_EQ(cases[0].rheology.G, 1.0);
  ASSERT_EQ(cases[0].rheology.branches.size(), 2u);
  EXPECT_DOUBLE_EQ(cases[0].rheology.branches[0].G, 1.0);
  EXPECT_EQ(cases[0].rheology.branches[0].tau, 0.5);
  EXPECT_DOUBLE_EQ(cases[0].rheology.branches[1].G, 3.0);
  EXPECT_EQ(cases[0].rheology.branches[1].tau, 20.0);
  EXPECT_EQ(cases[0].rheology.aT, 1.0); // the card's Tref: 25
  EXPECT_NEAR(std::log10(cases[1].rheology.aT), -8.86 * 10.0 / 111.6, 1e-12);
  EXPECT_EQ(c.run.material_text, kCard);
  // the card's text is part of the study: another card is another study
  const std::string canon = canonical(c);
  EXPECT_NE(canon.find("[material card]\n| ** two terms\n| *Material, name=R\n"), std::string::npos)
      << canon;
  dir.write("sub/card.inp", kCard + "** a comment more\n");
  EXPECT_NE(canonical(load_config(ini)), canon);
  // a card without *TRS gives no WLF; the study then has no temperature
  dir.write("sub/card.inp", kCard.substr(0, kCard.find("*Trs")));
  const StudyConfig plain = load_config(dir.write("sub/p.ini", card_study()));
  EXPECT_FALSE(plain.run.wlf);
  EXPECT_DOUBLE_EQ(cases_of(plain).at(0).rheology.G, 1.0);
}

TEST(StudyMaterial, OverrideReplacesTheCard) {
  TempDir dir;
  dir.write("card.inp", kCard);
  StudyConfig c = load_config(dir.write("s.ini", card_study()));
  const std::string other =
      dir.write("other.inp", "*Elastic\n9., 0.5\n*Viscoelastic, time=PRONY\n0.5, 0, 2.\n");
  apply_override(c, "run.material", other);
  EXPECT_EQ(names(c),
            std::vector<std::string>({"d", "R", "tau", "G", "G1", "tau1", "v", "w1_over_v", "T1"}));
  const mdrmap::Case k = cases_of(c).at(0);
  EXPECT_DOUBLE_EQ(k.rheology.G, 3.0); // LONG TERM: E / 3
  EXPECT_DOUBLE_EQ(k.rheology.branches.at(0).G, 3.0);
  EXPECT_FALSE(c.run.wlf); // the first card's WLF went with it
}

TEST(StudyMaterial, OverrideGivesACardToAStudyWithoutOne) {
  TempDir dir;
  const std::string card = dir.write("card.inp", kCard);
  // the default G = 1 of a finished study gives way to the card's
  StudyConfig c = parse("[grid]\nd = 1e-2\nR = 1\ntau = 0\nv = 1\n[history]\nw1_over_v = "
                        "0.5\nT1 = 1\n");
  apply_override(c, "run.material", card);
  EXPECT_EQ(names(c), std::vector<std::string>({"d", "R", "tau", "G", "G1", "tau1", "G2", "tau2",
                                                "v", "w1_over_v", "T1"}));
  EXPECT_DOUBLE_EQ(cases_of(c).at(0).rheology.branches.at(1).G, 3.0);
  // a G of the study's own is not replaced
  StudyConfig own = parse("[grid]\nd = 1e-2\nR = 1\ntau = 0\nG = 2\nv = 1\n[history]\n"
                          "w1_over_v = 0.5\nT1 = 1\n");
  const auto [option, message] = error_of([&] { apply_override(own, "run.material", card); });
  EXPECT_EQ(option, "run.material") << message;
  EXPECT_NE(message.find("and grid.G are given"), std::string::npos) << message;
}

TEST(StudyMaterial, BadCardsAndDoublesAreRefusedInOneLine) {
  TempDir dir;
  struct Bad {
    std::string card, grid, run, option, said;
  };
  const std::string elastic = "*Elastic\n3., 0.5\n*Viscoelastic, time=PRONY\n";
  const std::vector<Bad> bad = {
      // both named; the option is the later in the file: [run] material
      {kCard, "G1 = 2\n", "", "run.material", "both [run] material (" + dir.path() + "/card.inp"},
      {kCard, "G = 2\n", "", "run.material", "and grid.G are given; give the material once"},
      {kCard, "G3 = 1\ntau3 = 1\n", "", "run.material", "and grid.G3 are given"},
      {kCard, "temperature = 30\n", "wlf = 8.86:101.6:25\n", "run.wlf", "*TRS"},
      {elastic + "0., 0.3, 1.\n", "", "", "run.material", "card.inp:4: g1 must be > 0 and < 1"},
      {elastic + "0.5, 0, 1.\n0.5, 0, 10.\n", "", "", "run.material", "the Prony g_i sum to 1"},
      {"*Elastic, moduli=SHORT\n3., 0.5\n", "", "", "run.material",
       "card.inp:1: *ELASTIC: the option MODULI=SHORT is not supported"},
      {kCard, "temperature = -76.6\n", "", "grid.temperature", "must be > TREF - C2"},
      {kCard, "temperature = 308.15\n", "", "grid.temperature", "a Kelvin/Celsius mix-up"},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.card + b.grid + b.run);
    dir.write("card.inp", b.card);
    const std::string ini = dir.write("s.ini", card_study(b.grid, b.run));
    const auto [option, message] = error_of([&] { load_config(ini); });
    EXPECT_EQ(option, b.option) << message;
    EXPECT_NE(message.find(b.said), std::string::npos) << message;
    EXPECT_NE(message.find("s.ini:"), std::string::npos) << message; // located in the config
    EXPECT_TRUE(one_line(message)) << message;
  }
  // a missing card names the option and the path as resolved
  const auto [option, message] =
      error_of([&] { parse_config(card_study(), dir.path() + "/none", "m.ini"); });
  EXPECT_EQ(option, "run.material");
  EXPECT_NE(message.find("none/card.inp"), std::string::npos) << message;
}

TEST(StudySpectrum, OverridesSetTermsTheShiftAndTheTemperature) {
  StudyConfig c = parse(base());
  apply_overrides(
      c,
      {{"grid.G1", "1, 2"}, {"grid.tau1", "0.5"}, {"grid.temperature", "30"}, {"run.wlf", kWlf}});
  EXPECT_EQ(names(c), std::vector<std::string>({"d", "R", "tau", "G", "G1", "tau1", "temperature",
                                                "v", "v1_over_v", "t_end_over_tau"}));
  EXPECT_EQ(cases_of(c).size(), 2u);
  EXPECT_NEAR(cases_of(c).at(1).rheology.aT, wlf_aT(30.0), 1e-15);
  // aT replaces the temperature (they set the same thing), whose WLF constants then apply to none
  const auto dangling = error_of([&] {
    StudyConfig d = c;
    apply_overrides(d, {{"grid.aT", "2"}});
  });
  EXPECT_EQ(dangling.first, "run.wlf") << dangling.second;
  EXPECT_EQ(dangling.second.rfind("command line: wlf applies to a temperature column only", 0), 0u)
      << dangling.second;
  EXPECT_EQ(error_of([&] {
              StudyConfig d = c;
              apply_overrides(d, {{"grid.G33", "1"}});
            }).first,
            "grid.G33");
}

TEST(StudySpectrum, BadSpectraAndTemperaturesNameTheKey) {
  struct Bad {
    std::string grid, run, option, said;
  };
  const std::vector<Bad> bad = {
      {"G1 = 1\n", "", "grid.tau1", "term 1 of the spectrum has G1 but no tau1"},
      {"tau2 = 1\nG1 = 1\ntau1 = 1\n", "", "grid.G2", "has tau2 but no G2"},
      {"G2 = 1\ntau2 = 1\n", "", "grid.G1", "terms up to 2 but no G1 and tau1"},
      {"G1 = 0\ntau1 = 1\n", "", "grid.G1", "G1 must be a finite number > 0, got 0"},
      {"G1 = 1\ntau1 = -1\n", "", "grid.tau1", "tau1 must be a finite number > 0"},
      {"G1 = 1\ntau1 = nan\n", "", "grid.tau1", "not a finite number"},
      {"G1 = 1\ntau1 = 1e999\n", "", "grid.tau1", "too large"},
      {"G1 = 1\ntau1 = 1e10\naT = 1e300\n", "", "grid.aT", "aT times tau1"},
      {"aT = 0\n", "", "grid.aT", "aT must be a finite number > 0"},
      {"temperature = 20\n", "", "grid.temperature", "needs the WLF constants"},
      {"", "wlf = 8.86:101.6:20\n", "run.wlf", "applies to a temperature column only"},
      {"temperature = -81.6\n", "wlf = 8.86:101.6:20\n", "grid.temperature",
       "must be > TREF - C2 = -81.599999999999994"},
      {"temperature = -90, 20\n", "wlf = 8.86:101.6:20\n", "grid.temperature",
       "(WLF 8.8599999999999994:101.59999999999999:20)"},
      {"temperature = 19.9001\n", "wlf = 8.86:0.1:20\n", "grid.temperature",
       "beyond the range of a double"},
      {"temperature = 19.5\nG1 = 1\ntau1 = 1e308\n", "wlf = 1:1:20\n", "grid.temperature",
       "temperature gives aT = "},
      {"temperature = 20\naT = 1\n", "wlf = 8.86:101.6:20\n", "grid.aT",
       "both temperature (grid.temperature) and aT"},
      {"temperature = 20\n", "wlf = 8.86:101.6\n", "run.wlf", "wlf must be C1:C2:TREF"},
      {"temperature = 20\n", "wlf = 0:101.6:20\n", "run.wlf", "wlf C1 must be > 0"},
      {"temperature = 20\n", "wlf = 8.86:-1:20\n", "run.wlf", "wlf C2 must be > 0"},
      // issue 33: TREF's unit; a shift beyond 12 decades is refused unless allowed
      {"temperature = 25\n", "wlf = 17.44:51.6:-100C\n", "grid.temperature",
       "more than 12 decades from 1"},
      {"temperature = 20\n", "wlf = 8.86:101.6:20F\n", "run.wlf", "TREF is not a number"},
      {"temperature = 308.15\n", "wlf = 8.86:101.6:25C\n", "grid.temperature",
       "give T its unit (308.15K or 308.15C)"},
      {"temperature = 20, 308.15\n", "wlf = 8.86:101.6:25\n", "grid.temperature",
       "a Kelvin/Celsius mix-up"},
      {"temperature = 20\n", "wlf = 8.86:101.6:-5K\n", "run.wlf", "absolute zero"},
      {"temperature = 20\n", "wlf = 8.86:101.6:20\nallow_large_shift = maybe\n",
       "run.allow_large_shift", "allow_large_shift must be true or false"},
      {"G1 = 1\ntau1 = 1\n", "solver = exact\n", "run.solver",
       "solver exact does not solve a relaxation spectrum (the study has G1, tau1); give solver "
       "= auto, row or baseline"},
      {"G01 = 1\ntau01 = 1\n", "", "grid.G01", "unknown key"},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.grid + b.run);
    const auto [option, message] = error_of([&] {
      parse("[grid]\nd = 1e-2\nR = 1\ntau = 1\nG = 1\nv = 1\n" + b.grid +
            "[history]\nw1_over_v = 0.5\nT1 = 1\n[run]\n" + b.run);
    });
    EXPECT_EQ(option, b.option) << message;
    EXPECT_NE(message.find(b.said), std::string::npos) << message;
    EXPECT_TRUE(one_line(message)) << message;
  }
  // a spectrum has no default long-term modulus G (issue 33): refused, naming G
  for (const std::string& grid :
       {std::string("G1 = 1\ntau1 = 1\n"), std::string("G1 = 1, 2\ntau1 = 1\n")}) {
    const auto [option, message] = error_of([&] {
      parse("[grid]\nd = 1e-2\nR = 1\ntau = 1\nv = 1\n" + grid +
            "[history]\nw1_over_v = 0.5\nT1 = 1\n");
    });
    EXPECT_EQ(option, "grid.G") << message;
    EXPECT_NE(message.find("needs the long-term (rubbery) modulus G > 0"), std::string::npos)
        << message;
    EXPECT_TRUE(one_line(message)) << message;
  }
  // under load a spectrum takes auto, row (spectrum: its old name) or
  // baseline; at fixed depth exact (the Kelvin foundation only) is refused
  const std::string load_spectrum =
      "[grid]\nF0 = 1e-3\nR = 1\ntau = 0\nG = 1\nG1 = 1\ntau1 = 1\nv = 1\n"
      "[history]\nw1_over_v = 0.5\nT1 = 1\n[run]\nsolver = ";
  for (const char* ok : {"auto", "row", "spectrum", "baseline"})
    EXPECT_TRUE(parse(load_spectrum + ok + "\n").by_force()) << ok;
  const auto [option, message] = error_of([&] {
    parse("[grid]\nd = 1e-3\nR = 1\ntau = 0\nG = 1\nG1 = 1\ntau1 = 1\nv = 1\n"
          "[history]\nw1_over_v = 0.5\nT1 = 1\n[run]\nsolver = exact\n");
  });
  EXPECT_EQ(option, "run.solver") << message;
  EXPECT_NE(message.find("solver exact does not solve a relaxation spectrum (the study has G1, "
                         "tau1); give solver = auto, row or baseline"),
            std::string::npos)
      << message;
  // 32 terms are allowed, a 33rd is no column
  std::string terms;
  for (int k = 1; k <= 32; ++k)
    terms += "G" + std::to_string(k) + " = 1\ntau" + std::to_string(k) + " = " + std::to_string(k) +
             "\n";
  const StudyConfig c = depth_study("tau = 0\nG = 1\n" + terms +
                                    "v = 1\n[history]\nw1 = 1\n"
                                    "T1_over_tau = 1\n");
  EXPECT_EQ(cases_of(c).at(0).rheology.branches.size(), 32u);
  EXPECT_EQ(cases_of(c).at(0).history.segments[0].T, 32.0);
  Column none;
  EXPECT_FALSE(parse_column("G33", none));
  EXPECT_FALSE(parse_column("tau0", none));
  EXPECT_TRUE(parse_column("tau32", none));
  EXPECT_EQ(none.branch, 32u);
  EXPECT_TRUE(none.spectrum());
}

TEST(StudyCases, HistoryColumnsInTheCsv) {
  const std::string p = tmp().write("hist.csv", "T2,w2,F0,R,tau,v,w1,T1,G\n"
                                                "5,0.1,1e-3,1,1,0.1,0,2,1\n"
                                                "6,1,2e-3,1,0,0.2,0.3,4,3\n");
  const StudyConfig c = list_config(p);
  EXPECT_TRUE(c.by_force());
  EXPECT_EQ(c.segments(), 2u);
  EXPECT_EQ(names(c),
            std::vector<std::string>({"F0", "R", "tau", "G", "v", "w1", "T1", "w2", "T2"}));
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].loading.F0, 1e-3);
  EXPECT_EQ(cases[0].history.segments[0].w, 0.0);
  EXPECT_EQ(cases[0].history.segments[0].T, 2.0);
  EXPECT_EQ(cases[0].history.segments[1].w, 0.1);
  EXPECT_EQ(cases[0].history.segments[1].T, 5.0);
  EXPECT_EQ(cases[1].rheology.G, 3.0);
  EXPECT_EQ(cases[1].rheology.tau, 0.0);
  EXPECT_EQ(cases[1].history.segments[1].T, 6.0);
  // a history column missing from the header
  const std::string q = tmp().write("hist_missing.csv", "d,R,tau,v,w1,T1,w2\n1e-3,1,1,1,0,1,1\n");
  const auto e = error_of([&] { list_config(q); });
  EXPECT_EQ(e.first, "history.T2");
  EXPECT_NE(e.second.find("hist_missing.csv' and the config: segment 2 of 2 has no duration"),
            std::string::npos)
      << e.second;
  // a bad history cell names its line and column
  const std::string r = tmp().write("hist_bad.csv", "d,R,tau,v,w1,T1\n1e-3,1,1,1,0,1\n"
                                                    "1e-3,1,1,1,0,-3\n");
  const auto bad = error_of([&] { expand_cases(list_config(r)); });
  EXPECT_EQ(bad.first, "cases.T1");
  EXPECT_NE(bad.second.find("hist_bad.csv:3:6: T1 must be"), std::string::npos) << bad.second;
}

TEST(StudyCases, HistoryFromASingleValuedHistorySection) {
  const std::string p = tmp().write("nohist.csv", "d,R,tau,v\n1e-3,1,2,1\n2e-3,1,0.5,3\n");
  const StudyConfig c = list_config(p, "[history]\nw1_over_v = 0.5\nT1_over_tau = 3\n"
                                       "w2 = 0\nT2 = 1\n");
  EXPECT_EQ(c.segments(), 2u);
  EXPECT_FALSE(c.axes[col(c, "w1_over_v")].listed);
  const auto cases = cases_of(c);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].history.segments[0].w, 0.5);
  EXPECT_EQ(cases[0].history.segments[0].T, 6.0);
  EXPECT_EQ(cases[1].history.segments[0].w, 1.5);
  EXPECT_EQ(cases[1].history.segments[0].T, 1.5);
  EXPECT_EQ(cases[1].history.segments[1].T, 1.0);
  // more than one value is a grid, not a case list
  const auto many = error_of([&] { list_config(p, "[history]\nw1 = 0\nT1_over_tau = 1, 2\n"); });
  EXPECT_EQ(many.first, "history.T1_over_tau") << many.second;
  EXPECT_NE(many.second.find("has 2 values; a case list takes one value per column"),
            std::string::npos)
      << many.second;
  // a column the CSV has is not set again by the config
  const std::string h = tmp().write("withw1.csv", "d,R,tau,v,w1\n1e-3,1,2,1,0\n");
  const auto twice = error_of([&] { list_config(h, "[history]\nw1_over_v = 1\nT1 = 1\n"); });
  EXPECT_EQ(twice.first, "history.w1_over_v") << twice.second;
  EXPECT_NE(twice.second.find("withw1.csv"), std::string::npos) << twice.second;
  EXPECT_TRUE(one_line(twice.second));
  const StudyConfig ok = list_config(h, "[history]\nT1 = 1\n");
  EXPECT_EQ(cases_of(ok).at(0).history.segments.at(0).T, 1.0);
}

TEST(StudyOverride, HistoryKeys) {
  StudyConfig c = depth_study("tau = 2\nv = 0.5\n[history]\nw1_over_v = 0\nT1_over_tau = 1\n"
                              "w2_over_v = 1\nT2_over_tau = 20\n");
  const std::string before = canonical(c);
  apply_override(c, "history.T1_over_tau", "1,10,100");
  EXPECT_EQ(c.axes[col(c, "T1_over_tau")].values, std::vector<double>({1, 10, 100}));
  EXPECT_EQ(case_count(c), 3u);
  EXPECT_NE(canonical(c), before);
  EXPECT_EQ(cases_of(c).at(2).history.segments[0].T, 200.0);
  // an absolute key replaces the relative one of the same segment
  apply_override(c, "history.w2", "3");
  EXPECT_EQ(col(c, "w2"), 7u);
  EXPECT_EQ(cases_of(c).at(0).history.segments[1].w, 3.0);
  // a new segment needs both its columns: one alone is refused, the study unchanged
  const std::string now = canonical(c);
  const auto alone = error_of([&] { apply_override(c, "history.w3", "0"); });
  EXPECT_EQ(alone.first, "history.T3") << alone.second;
  EXPECT_EQ(alone.second.rfind("command line: ", 0), 0u) << alone.second;
  EXPECT_NE(alone.second.find("segment 3 of 3 has no duration; give T3 or T3_over_tau"),
            std::string::npos)
      << alone.second;
  EXPECT_EQ(canonical(c), now);
  EXPECT_EQ(c.segments(), 2u);
  // ... and both together, as the command line passes them, add it
  apply_overrides(c, {{"history.w3", "0"}, {"history.T3_over_tau", "5"}});
  EXPECT_EQ(c.segments(), 3u);
  EXPECT_EQ(cases_of(c).at(0).history.segments[2].w, 0.0);
  EXPECT_EQ(cases_of(c).at(0).history.segments[2].T, 10.0);
  // history keys of any segment are known; others are not
  // (a far segment leaves the ones between without columns: the first is named)
  EXPECT_EQ(error_of([&] { apply_override(c, "history.w12", "0"); }).first, "history.w4");
  EXPECT_EQ(error_of([&] { apply_override(c, "history.x1", "0"); }).first, "history.x1");
  EXPECT_EQ(error_of([&] { apply_override(c, "history.T1_over_tau", "0"); }).first,
            "history.T1_over_tau");
  const auto keys = override_keys();
  for (const char* k : {"history.w1", "history.T1_over_tau", "history.w9_over_v", "grid.F0",
                        "grid.G", "run.G", "run.t_end_over_tau", "run.spacing"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), k), keys.end()) << k;
}

TEST(StudyCanonical, EveryColumnValueCountsAndKeyOrderDoesNot) {
  const std::string text = "[grid]\nF0 = 1e-3, 2e-3\nR = 1\ntau = 1\nG = 1\nv = 0.1\n"
                           "[history]\nw1_over_v = 0\nT1_over_tau = 1, 10\nw2 = 0.1\nT2 = 20\n";
  const std::string ref = canonical(parse(text));
  const std::string reordered = "[history]\nT2 = 20\nw2 = 0.1\nT1_over_tau = 1,10\n"
                                "w1_over_v = 0\n[grid]\nv = 0.1\nG = 1\ntau = 1\nR = 1\n"
                                "F0 = 1e-3,2e-3\n";
  EXPECT_EQ(canonical(parse(reordered)), ref);
  // G = 1 is the default: leaving it out is the same study
  std::string no_g = text;
  no_g.erase(no_g.find("G = 1\n"), 6);
  EXPECT_EQ(canonical(parse(no_g)), ref);
  const std::vector<std::pair<std::string, std::string>> changes = {
      {"F0 = 1e-3, 2e-3", "F0 = 1e-3, 3e-3"},
      {"R = 1", "R = 2"},
      {"tau = 1", "tau = 3"},
      {"G = 1", "G = 2"},
      {"v = 0.1", "v = 0.2"},
      {"w1_over_v = 0", "w1_over_v = 0.5"},
      {"T1_over_tau = 1, 10", "T1_over_tau = 1, 11"},
      {"w2 = 0.1", "w2 = 0.3"},
      {"T2 = 20", "T2 = 21"},
      {"w2 = 0.1", "w2_over_v = 0.1"}};
  for (const auto& [from, to] : changes) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    EXPECT_NE(canonical(parse(t)), ref) << to;
  }
}

// --- Size limits ---------------------------------------------------------------------

TEST(StudyLimits, CaseCountOfAHugeGridWithoutExpanding) {
  const auto t0 = std::chrono::steady_clock::now();
  const StudyConfig c = parse("[grid]\nd = logspace:1e-6:1e-2:1000\nR = linspace:0.5:2:1000\n"
                              "tau = linspace:0:10:1000\nv = 1\nv1_over_v = 0\n");
  EXPECT_EQ(case_count(c), 1'000'000'000u);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 1.0);
  // One more value is over the limit, and the message gives the size.
  const auto [option, message] = error_of([] {
    parse("[grid]\nd = logspace:1e-6:1e-2:1000\nR = linspace:0.5:2:1000\n"
          "tau = linspace:0:10:1000\nv = 1, 2\nv1_over_v = 0\n");
  });
  EXPECT_EQ(option, "config");
  EXPECT_NE(message.find("2000000000"), std::string::npos) << message;
  // A hand-made grid whose size would overflow size_t.
  StudyConfig h = c;
  for (auto& a : h.axes)
    a.values.assign(100000, 1.0);
  EXPECT_EQ(error_of([&] { case_count(h); }).first, "config");
}

TEST(StudyLimits, LoadConfigFileErrors) {
  const auto missing = error_of([] { load_config(tmp().path() + "/missing.ini"); });
  EXPECT_EQ(missing.first, "config");
  EXPECT_NE(missing.second.find("cannot read '"), std::string::npos) << missing.second;
  EXPECT_NE(missing.second.find("No such file"), std::string::npos) << missing.second;
  const auto dir = error_of([] { load_config(tmp().path()); });
  EXPECT_EQ(dir.first, "config");
  EXPECT_NE(dir.second.find("directory"), std::string::npos) << dir.second;
  std::string huge = base();
  huge += std::string(17u * 1024 * 1024, ';');
  const std::string big = tmp().write("huge.ini", huge);
  const auto too_big = error_of([&] { load_config(big); });
  EXPECT_EQ(too_big.first, "config");
  EXPECT_NE(too_big.second.find("16 MiB"), std::string::npos) << too_big.second;
  fs::remove(big);
  // Errors from a file name the file.
  const std::string bad = tmp().write("bad.ini", base({{8, "sample = 3"}}));
  const auto e = error_of([&] { load_config(bad); });
  EXPECT_EQ(e.first, "run.sample");
  EXPECT_EQ(e.second.rfind(bad + ":8: ", 0), 0u) << e.second;
}

TEST(StudyExamples, ShippedConfigsLoad) {
  const fs::path dir = fs::path(__FILE__).parent_path().parent_path() / "jobs" / "examples";
  if (!fs::exists(dir)) GTEST_SKIP() << "no " << dir;
  const std::map<std::string, std::size_t> expected = {
      {"quick.ini", 40},      {"start_stop.ini", 3}, {"friction_map.ini", 561},
      {"v1_sweep.ini", 60},   {"cases.ini", 7},      {"seed_step.ini", 60},
      {"load_sweep.ini", 75}, {"shs_holds.ini", 27}, {"velocity_steps.ini", 9}};
  for (const auto& [name, count] : expected) {
    SCOPED_TRACE(name);
    const StudyConfig c = load_config((dir / name).string());
    EXPECT_EQ(case_count(c), count);
    EXPECT_EQ(expand_cases(c).size(), count);
    EXPECT_FALSE(canonical(c).empty());
  }
  const StudyConfig s = load_config((dir / "start_stop.ini").string());
  EXPECT_TRUE(s.run.timeseries);
  for (const mdrmap::Case& k : cases_of(s)) {
    // a start-stop test: fast before (zeta >> 1, a2 ~ 0) and nearly stopped
    // after (zeta1 << 1, a2 -> a1), v1 = 1e-4 v as in the paper
    const double v = k.history.v0, v1 = k.history.segments.at(0).w;
    EXPECT_EQ(v1, 1e-4 * v);
    EXPECT_GE(mdrmap::zeta(k, v), 100.0);
    EXPECT_LE(mdrmap::zeta(k, v1), 0.1 + 1e-12);
  }
  // the new examples: load control, a hold and a reslide
  const StudyConfig h = load_config((dir / "shs_holds.ini").string());
  EXPECT_TRUE(h.by_force());
  EXPECT_EQ(h.segments(), 2u);
  for (const mdrmap::Case& k : cases_of(h)) {
    EXPECT_GT(k.loading.F0, 0.0);
    EXPECT_EQ(k.history.segments.at(0).w, 0.0);
    EXPECT_EQ(k.history.segments.at(1).w, k.history.v0);
    EXPECT_EQ(k.history.segments.at(1).T, 20.0);
  }
}

// --- Fuzz ------------------------------------------------------------------------------
//
// Seeded and deterministic: the same inputs on every run. The environment can
// run longer or other inputs:
//   MDRMAP_FUZZ_ITERS=N   iterations of every fuzz test (defaults: a few seconds
//                         under ASan in all)
//   MDRMAP_FUZZ_SEED=S    mixed into every test's seed
// e.g. MDRMAP_FUZZ_ITERS=200000 build-asan/tests/test_study --gtest_filter='StudyFuzz.*'
// A failure prints the input as a C string literal (and the seed, iteration).
// tests/fuzz/fuzz_config.cpp is the same check for libFuzzer (MDRMAP_LIBFUZZER).

/// MDRMAP_FUZZ_ITERS, or `fallback`.
int fuzz_iters(int fallback) {
  const char* env = std::getenv("MDRMAP_FUZZ_ITERS");
  if (env == nullptr || *env == '\0') return fallback;
  char* end = nullptr;
  const long n = std::strtol(env, &end, 10);
  if (*end != '\0' || n < 1 || n > 2'000'000'000L) {
    ADD_FAILURE() << "MDRMAP_FUZZ_ITERS=" << env << " is not a count from 1 to 2e9";
    return fallback;
  }
  return static_cast<int>(n);
}

/// A test's seed, varied by MDRMAP_FUZZ_SEED.
std::uint64_t fuzz_seed(std::uint64_t base) {
  const char* env = std::getenv("MDRMAP_FUZZ_SEED");
  if (env == nullptr || *env == '\0') return base;
  return base + 0x9E3779B97F4A7C15ULL * (std::strtoull(env, nullptr, 10) + 1);
}

/// Text as a C string literal (octal escapes), to paste a failing input into a test.
std::string c_literal(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (ch == '\n') {
      out += "\\n";
    } else if (c < 0x20 || c >= 0x7f) {
      const char digits[] = {'\\', static_cast<char>('0' + (c >> 6)),
                             static_cast<char>('0' + ((c >> 3) & 7)),
                             static_cast<char>('0' + (c & 7)), '\0'};
      out += digits;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

/// Writes a file the fast way: in place, then cut to size. (Truncating an
/// existing file to 0 and writing it again makes ext4 flush it on close, about
/// 2 ms each; creating a file each time is also slower.)
void write_fast(const std::string& path, const std::string& content) {
  {
    std::fstream out(path, std::ios::in | std::ios::out | std::ios::binary);
    if (!out.is_open()) out.open(path, std::ios::out | std::ios::binary);
    out << content;
    if (!out) throw std::runtime_error("cannot write " + path);
  }
  fs::resize_file(path, content.size());
}

/// A message a user may see: non-empty, one line, no control bytes but tab.
::testing::AssertionResult good_message(const std::string& m) {
  if (m.empty()) return ::testing::AssertionFailure() << "empty message";
  for (const char ch : m) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\t') || c == 0x7f)
      return ::testing::AssertionFailure()
             << "control byte " << static_cast<int>(c) << " in message " << c_literal(m);
  }
  return ::testing::AssertionSuccess();
}

/// Runs f() on a fuzzed input: true when it returns, false when it throws
/// InvalidInput (whose message must be good); anything else fails the test.
/// `input` describes the input for the failure message.
template <class F> bool returns_or_refuses(const char* step, const std::string& input, F&& f) {
  try {
    f();
    return true;
  } catch (const InvalidInput& e) {
    EXPECT_TRUE(good_message(e.what())) << step << " of " << input;
    EXPECT_FALSE(e.option().empty()) << step << ": " << e.what() << "\n" << input;
    return false;
  } catch (const std::exception& e) {
    ADD_FAILURE() << step << " threw " << typeid(e).name() << " (not InvalidInput): " << e.what()
                  << "\ninput: " << input;
  } catch (...) {
    ADD_FAILURE() << step << " threw a non-std exception\ninput: " << input;
  }
  return false;
}

/// Expanding more cases than this is skipped (case_count() tells first): a
/// fuzzed grid may hold up to 1e9. big.ini has 20000.
constexpr std::size_t kFuzzExpandLimit = 25000;

/// The cases of a config that parsed: they expand (grids: always, their
/// cases were checked at parse time; case lists: or InvalidInput), and each
/// is finite and valid as the runner will run it. Returns the number of cases
/// checked.
std::size_t check_cases(const StudyConfig& c, const std::string& input) {
  std::size_t count = 0;
  if (!returns_or_refuses("case_count", input, [&] { count = case_count(c); })) {
    EXPECT_EQ(c.kind, StudyConfig::Kind::Cases) << "a parsed grid's case_count threw\n" << input;
    return 0;
  }
  if (count > kFuzzExpandLimit) return 0;
  std::vector<Row> cases;
  if (!returns_or_refuses("expand_cases", input, [&] { cases = expand_cases(c); })) {
    EXPECT_EQ(c.kind, StudyConfig::Kind::Cases)
        << "a parsed grid refused to expand (a case the parse-time check missed)\n"
        << input;
    return 0;
  }
  EXPECT_EQ(cases.size(), count) << input;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Row& s = cases[i];
    EXPECT_EQ(s.size(), c.axes.size()) << input;
    bool finite = true;
    for (const double x : s)
      finite = finite && std::isfinite(x);
    EXPECT_TRUE(finite) << "case " << i + 1 << "\n" << input;
    try {
      const mdrmap::Case k = case_for(c, s);
      mdrmap::validate(k);
      EXPECT_EQ(k.history.size(), c.segments()) << input;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "expanded case " << i + 1 << " is invalid: " << e.what() << "\n" << input;
    }
    if (::testing::Test::HasFailure()) return 0;
  }
  std::string text;
  if (returns_or_refuses("canonical", input, [&] { text = canonical(c); })) {
    EXPECT_FALSE(text.empty()) << input;
  }
  return cases.size();
}

/// The repository's study configs and case lists: the fuzz seeds.
struct FuzzCorpus {
  std::vector<std::pair<std::string, std::string>> ini, csv; ///< file name, text
  std::vector<std::pair<std::string, std::string>> cards;    ///< material cards (.inp), unmutated
};

const FuzzCorpus& shipped_corpus() {
  static const FuzzCorpus corpus = [] {
    FuzzCorpus c;
    const fs::path root = fs::path(__FILE__).parent_path().parent_path();
    for (const fs::path& dir : {root / "jobs" / "examples", root / "tests" / "mpi"}) {
      std::vector<fs::path> files;
      for (const auto& entry : fs::directory_iterator(dir))
        files.push_back(entry.path());
      std::sort(files.begin(), files.end()); // directory order is not deterministic
      for (const auto& p : files) {
        const std::string ext = p.extension().string();
        if (ext != ".ini" && ext != ".csv" && ext != ".inp") continue;
        std::ifstream in(p, std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        (ext == ".ini"   ? c.ini
         : ext == ".csv" ? c.csv
                         : c.cards)
            .emplace_back(p.filename().string(), text.str());
      }
    }
    return c;
  }();
  return corpus;
}

/// Tokens that mutations insert or substitute: numbers at and past the limits
/// of double, the axis forms, INI and CSV syntax, keys, control and UTF-8
/// bytes, and very long runs.
const std::vector<std::string>& fuzz_tokens() {
  static const std::vector<std::string> tokens = [] {
    std::vector<std::string> t = {"nan",
                                  "NaN",
                                  "-nan",
                                  "inf",
                                  "-inf",
                                  "infinity",
                                  "-0",
                                  "0",
                                  "-1",
                                  "1",
                                  "+1",
                                  "1e400",
                                  "-1e400",
                                  "1e-400",
                                  "1e308",
                                  "1.7976931348623157e308",
                                  "4.9e-324",
                                  "2.2250738585072014e-308",
                                  "1e-310",
                                  "0x1p3",
                                  "0x1p-1074",
                                  "0x1.fffffffffffffp1023",
                                  "0x",
                                  "1e",
                                  "1.2.3",
                                  ".",
                                  "e5",
                                  "99999999999999999999999",
                                  "9223372036854775807",
                                  "-9223372036854775808",
                                  "linspace:",
                                  "logspace:",
                                  "linspace:1:2:",
                                  "logspace:1e-3:1e3:",
                                  "linspace:0:1:3",
                                  "logspace:1e-300:1e300:4",
                                  "linspace:1e308:-1e308:3",
                                  ":",
                                  "::",
                                  ",",
                                  ",,",
                                  "=",
                                  "==",
                                  "[",
                                  "]",
                                  "[grid]",
                                  "[cases]",
                                  "[run]",
                                  "[]",
                                  ";",
                                  "#",
                                  " ; c",
                                  " # c",
                                  "\r",
                                  "\n",
                                  "\r\n",
                                  std::string(1, '\0'),
                                  "\t",
                                  " ",
                                  "\v",
                                  "\f",
                                  "\x7f",
                                  "\x1b[31m",
                                  "\xEF\xBB\xBF",
                                  "\xC3\xA9",
                                  "\xE2\x80\xA8",
                                  "\xF0\x9F\x98\x80",
                                  "\xC0\x80",
                                  "\xFF\xFE",
                                  "\x80",
                                  "d",
                                  "R",
                                  "tau",
                                  "v",
                                  "v1",
                                  "v1_over_v",
                                  "file",
                                  "t_end_over_tau",
                                  "samples",
                                  "rtol",
                                  "solver",
                                  "timeseries",
                                  "G",
                                  "true",
                                  "false",
                                  "yes",
                                  "auto",
                                  "exact",
                                  "row",
                                  "baseline",
                                  "cases.csv",
                                  "failing.csv",
                                  "/",
                                  "..",
                                  "nope.csv",
                                  "1000000",
                                  "1000001",
                                  "2",
                                  "1e-4",
                                  "0.1",
                                  "1e10",
                                  "1e-10",
                                  "10000001",
                                  "d,R,tau,v,v1",
                                  "[history]",
                                  "F0",
                                  "w1",
                                  "T1",
                                  "w1_over_v",
                                  "T1_over_tau",
                                  "w2",
                                  "T2_over_tau",
                                  "w3_over_v",
                                  "spacing",
                                  "decades",
                                  "log",
                                  "d,R,tau,v,w1,T1,w2,T2"};
    t.push_back(std::string(400, '9')); // very long numbers
    t.push_back("0." + std::string(400, '0') + "1");
    t.push_back("1" + std::string(330, '0')); // past the largest double
    t.push_back(std::string(10000, 'x'));     // 10k-character runs
    t.push_back(std::string(10000, '1'));
    std::string list; // a 2000-value list
    for (int i = 1; i <= 2000; ++i)
      list += (i > 1 ? ", " : "") + std::to_string(i);
    t.push_back(list);
    return t;
  }();
  return tokens;
}

/// Mutates INI and CSV text: byte flips, token insertions and substitutions,
/// values replaced by edge-case numbers and axis forms, lines duplicated,
/// deleted, swapped, spliced in from other seeds and cut, the text truncated,
/// line ends changed.
class Mutator {
public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  std::size_t below(std::size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_);
  }
  bool chance(std::size_t one_in) { return below(one_in) == 0; }
  template <class T> const T& pick(const std::vector<T>& v) { return v[below(v.size())]; }

  std::string number() {
    static const std::vector<std::string> n = {
        "1",     "2",      "0",      "-0",     "1e-3",    "0.5",   "3",      "1e2",    "1e-300",
        "1e300", "1e308",  "5e-324", "1e-310", "-1",      "1e-12", "1e12",   "0x1p-3", "1e-4",
        "100",   "1e-200", "1e200",  "7e-155", "1.5e154", "0.9",   "1e-100", "1e100",  "6",
        "1e-6",  "1e4",    "0.01",   "nan",    "inf",     "1e400", "1e-400", "+2",     "2.5"};
    return chance(8) ? pick(fuzz_tokens()) : pick(n);
  }

  /// A value for "key = value": a number, a list, linspace or logspace.
  std::string value() {
    static const std::vector<std::string> counts = {
        "0", "1", "2", "3", "5", "17", "1000", "100000", "-1", "2.5", "x", "", "10000001", "01"};
    switch (below(6)) {
    case 0:
      return pick(fuzz_tokens());
    case 1: {
      std::string s = number();
      for (std::size_t k = below(4); k > 0; --k)
        s += (chance(2) ? ", " : ",") + number();
      return s;
    }
    case 2:
    case 3:
      return std::string(chance(2) ? "linspace:" : "logspace:") + number() + ":" + number() + ":" +
             pick(counts);
    default:
      return number();
    }
  }

  std::string mutate(std::string s, const std::vector<std::string>& splice_from) {
    for (std::size_t n = 1 + below(2) * below(5); n > 0; --n)
      mutate_once(s, splice_from);
    return s;
  }

private:
  static std::vector<std::string> lines_of(const std::string& s) {
    std::vector<std::string> lines;
    std::size_t pos = 0;
    while (pos < s.size()) {
      std::size_t eol = s.find('\n', pos);
      if (eol == std::string::npos) eol = s.size();
      lines.push_back(s.substr(pos, eol - pos));
      pos = eol + 1;
    }
    return lines;
  }
  static std::string join_lines(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines)
      s += l + "\n";
    return s;
  }

  void mutate_once(std::string& s, const std::vector<std::string>& splice_from) {
    std::vector<std::string> lines = lines_of(s);
    const auto at = [&](std::size_t size) { return static_cast<std::ptrdiff_t>(below(size)); };
    switch (below(14)) {
    case 0: // flip a bit
      if (!s.empty()) s[below(s.size())] ^= static_cast<char>(1u << below(8));
      return;
    case 1: // any byte
      if (!s.empty()) s[below(s.size())] = static_cast<char>(below(256));
      return;
    case 2:
    case 3: // insert a token
      s.insert(below(s.size() + 1), pick(fuzz_tokens()));
      return;
    case 4: { // replace a short span by a token
      const std::size_t p = below(s.size() + 1);
      s.replace(p, below(8), pick(fuzz_tokens()));
      return;
    }
    case 5:
    case 6: { // a new value for a key, or a new CSV cell
      if (lines.empty()) return;
      std::string& l = lines[below(lines.size())];
      const std::size_t eq = l.find('=');
      if (eq != std::string::npos) {
        l = l.substr(0, eq + 1) + " " + value();
      } else {
        auto cells = split_cells(l);
        cells[below(cells.size())] = number();
        l.clear();
        for (std::size_t i = 0; i < cells.size(); ++i)
          l += (i > 0 ? "," : "") + cells[i];
      }
      s = join_lines(lines);
      return;
    }
    case 7: // duplicate a line
      if (lines.empty()) return;
      lines.insert(lines.begin() + at(lines.size() + 1), lines[below(lines.size())]);
      s = join_lines(lines);
      return;
    case 8: // delete a line
      if (lines.empty()) return;
      lines.erase(lines.begin() + at(lines.size()));
      s = join_lines(lines);
      return;
    case 9: // swap two lines
      if (lines.empty()) return;
      std::swap(lines[below(lines.size())], lines[below(lines.size())]);
      s = join_lines(lines);
      return;
    case 10: { // splice in a line from another seed
      if (splice_from.empty()) return;
      const auto other = lines_of(pick(splice_from));
      if (other.empty()) return;
      lines.insert(lines.begin() + at(lines.size() + 1), pick(other));
      s = join_lines(lines);
      return;
    }
    case 11: // cut a line short
      if (lines.empty()) return;
      {
        std::string& l = lines[below(lines.size())];
        l.resize(below(l.size() + 1));
      }
      s = join_lines(lines);
      return;
    case 12: // truncate the text
      s.resize(below(s.size() + 1));
      return;
    default: { // line ends: CRLF, CR only, or none at the end
      const std::size_t how = below(3);
      if (how == 2) {
        while (!s.empty() && s.back() == '\n')
          s.pop_back();
        return;
      }
      std::string out;
      for (const char ch : s)
        out +=
            ch == '\n' ? (how == 0 ? std::string("\r\n") : std::string("\r")) : std::string(1, ch);
      s = out;
      return;
    }
    }
  }

  static std::vector<std::string> split_cells(const std::string& l) {
    std::vector<std::string> cells;
    std::size_t start = 0;
    for (;;) {
      const std::size_t p = l.find(',', start);
      cells.push_back(l.substr(start, p == std::string::npos ? std::string::npos : p - start));
      if (p == std::string::npos) return cells;
      start = p + 1;
    }
  }

  std::mt19937_64 rng_;
};

/// Fuzzes parse_config -> case_count -> expand_cases -> canonical and a
/// command-line override, seeded from every shipped config; [cases] studies
/// read the shipped case lists, mutated half of the time.
TEST(StudyFuzz, ShippedConfigsMutated) {
  const FuzzCorpus& corpus = shipped_corpus();
  ASSERT_GE(corpus.ini.size(), 8u) << "jobs/examples/*.ini and tests/mpi/*.ini";
  ASSERT_GE(corpus.csv.size(), 2u) << "jobs/examples/cases.csv and tests/mpi/failing.csv";
  std::vector<std::string> all;
  for (const auto& f : corpus.ini)
    all.push_back(f.second);
  for (const auto& f : corpus.csv)
    all.push_back(f.second);
  const std::string dir = (fs::path(tmp().path()) / "fuzz_ini").string();
  fs::create_directories(dir);
  for (const auto& [name, text] : corpus.cards) // [run] material = rubber_card.inp
    write_fast((fs::path(dir) / name).string(), text);
  const std::vector<std::string> keys = {"grid.d",
                                         "grid.R",
                                         "grid.tau",
                                         "grid.v",
                                         "grid.v1",
                                         "grid.v1_over_v",
                                         "run.samples",
                                         "run.rtol",
                                         "run.G",
                                         "run.solver",
                                         "run.timeseries",
                                         "run.t_end_over_tau",
                                         "cases.file",
                                         "grid.F0",
                                         "grid.G",
                                         "run.spacing",
                                         "run.decades",
                                         "history.w1",
                                         "history.w1_over_v",
                                         "history.T1",
                                         "history.T1_over_tau",
                                         "history.w2_over_v",
                                         "history.T2_over_tau",
                                         "history.w3",
                                         "history.T3"};

  const std::uint64_t seed = fuzz_seed(20250101);
  const int iters = fuzz_iters(4000);
  Mutator m(seed);
  std::map<std::string, int> parsed;
  int refused = 0, overridden = 0, expanded = 0;
  std::size_t cases_checked = 0;
  for (int iter = 0; iter < iters; ++iter) {
    const auto& [name, seed_text] = corpus.ini[static_cast<std::size_t>(iter) % corpus.ini.size()];
    const std::string text = m.chance(20) ? seed_text : m.mutate(seed_text, all);
    std::string csv_note;
    if (text.find("cases") != std::string::npos) {
      for (const auto& [csv_name, csv_text] : corpus.csv) {
        const std::string csv = m.chance(2) ? csv_text : m.mutate(csv_text, all);
        write_fast((fs::path(dir) / csv_name).string(), csv);
        csv_note += "\n" + csv_name + ": " + c_literal(csv);
      }
    }
    const std::string input = "seed " + std::to_string(seed) + " iteration " +
                              std::to_string(iter) + ", mutated " + name + ": " + c_literal(text) +
                              csv_note;
    StudyConfig c;
    if (!returns_or_refuses("parse_config", input, [&] { c = parse_config(text, dir, name); })) {
      ++refused;
      continue;
    }
    ++parsed[name];
    const std::size_t n = check_cases(c, input);
    expanded += n > 0 ? 1 : 0;
    cases_checked += n;
    // A command-line override on top: applies or refuses, leaving c as it was.
    const std::string key = m.pick(keys), value = m.chance(4) ? m.pick(fuzz_tokens()) : m.value();
    const std::string with = input + "\noverride " + key + " = " + c_literal(value);
    StudyConfig o = c;
    std::string before, after;
    returns_or_refuses("canonical", input, [&] { before = canonical(c); });
    if (returns_or_refuses("apply_override", with, [&] { apply_override(o, key, value); })) {
      ++overridden;
      cases_checked += check_cases(o, with);
    } else {
      returns_or_refuses("canonical", with, [&] { after = canonical(o); });
      EXPECT_EQ(after, before) << "a refused override changed the study\n" << with;
    }
    if (::testing::Test::HasFailure()) return; // the first input that fails is enough
  }
  std::string summary;
  for (const auto& [name, n] : parsed)
    summary += " " + name + ":" + std::to_string(n);
  std::cout << "[ fuzz     ] " << iters << " inputs (seed " << seed << "): " << refused
            << " refused; parsed" << summary << "; " << expanded << " expanded, " << cases_checked
            << " cases checked; " << overridden << " overrides applied\n";
  // Each seed yields configs that parse, and most mutations are refused.
  if (iters >= 1000) {
    for (const auto& f : corpus.ini)
      EXPECT_GE(parsed[f.first], 10) << f.first;
  }
  EXPECT_GT(refused, iters / 3);
}

/// Fuzzes reading the shipped case lists, mutated, with G edge values.
TEST(StudyFuzz, ShippedCsvsMutated) {
  const FuzzCorpus& corpus = shipped_corpus();
  ASSERT_GE(corpus.csv.size(), 2u);
  std::vector<std::string> all;
  for (const auto& f : corpus.csv)
    all.push_back(f.second);
  const std::string path = (fs::path(tmp().path()) / "fuzz_cases.csv").string();
  const std::uint64_t seed = fuzz_seed(4242);
  const int iters = fuzz_iters(4000);
  Mutator m(seed);
  int ok = 0, refused = 0;
  for (int iter = 0; iter < iters; ++iter) {
    const auto& [name, seed_text] = corpus.csv[static_cast<std::size_t>(iter) % corpus.csv.size()];
    const std::string text = m.mutate(seed_text, all);
    const double G = m.chance(8) ? m.pick(std::vector<double>{2.5, 1e-300, 1e300, 0.0}) : 1.0;
    write_fast(path, text);
    const std::string input = "seed " + std::to_string(seed) + " iteration " +
                              std::to_string(iter) + ", G = " + mdrmap::format_number(G) +
                              ", mutated " + name + ": " + c_literal(text);
    std::vector<Row> cases;
    StudyConfig c;
    try {
      c = parse_config("[cases]\nfile = " + path + "\n[run]\nG = " + mdrmap::format_number(G) +
                           "\n",
                       "", "fuzz.ini");
      cases = expand_cases(c);
    } catch (const InvalidInput& e) {
      ++refused;
      ASSERT_TRUE(good_message(e.what())) << input;
      const std::string& o = e.option();
      ASSERT_TRUE(o.rfind("cases.", 0) == 0 || o.rfind("run.", 0) == 0 ||
                  o.rfind("grid.", 0) == 0 || o.rfind("history.", 0) == 0)
          << o << "\n"
          << input;
      continue;
    } catch (const std::exception& e) {
      FAIL() << "threw " << typeid(e).name() << " (not InvalidInput): " << e.what() << "\n"
             << input;
    }
    ++ok;
    ASSERT_FALSE(cases.empty()) << input;
    for (const Row& s : cases) {
      for (const double x : s)
        ASSERT_TRUE(std::isfinite(x)) << input;
      ASSERT_EQ(val(c, s, "G"), G) << input;
      try {
        mdrmap::validate(case_for(c, s));
      } catch (const std::exception& e) {
        FAIL() << "a case read is invalid: " << e.what() << "\n" << input;
      }
    }
  }
  std::cout << "[ fuzz     ] " << iters << " case lists (seed " << seed << "): " << ok << " read, "
            << refused << " refused\n";
  EXPECT_GT(ok, iters / 20);
  EXPECT_GT(refused, iters / 3);
}

// The original fuzz tests: a hand-made config and case list, mutated with
// single characters of a small alphabet.

const char* const kFuzzIni = "; fuzz seed\n"
                             "[grid]\n"
                             "d   = 1e-3, 2e-3      ; depth\n"
                             "R   = 1\n"
                             "tau = linspace:0.5:2:4\n"
                             "v   = logspace:1e-2:1e2:5\n"
                             "v1_over_v = 0, 1e-4\n"
                             "\n"
                             "[run]\n"
                             "t_end_over_tau = 6\n"
                             "samples = 21\n"
                             "rtol = 1e-4\n"
                             "solver = auto\n"
                             "timeseries = false\n"
                             "G = 1\n";

const std::string kFuzzAlphabet =
    "[]=;#,:.-+eE0123456789 \t\r\nabcdgilnoprstuvxyz_RGV\"'\\/\x01\xff";

std::string mutate(std::string s, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> times(1, 4), op(0, 5);
  const int n = times(rng);
  for (int k = 0; k < n; ++k) {
    const auto pick = [&](std::size_t size) {
      return size == 0 ? std::size_t{0}
                       : std::uniform_int_distribution<std::size_t>(0, size - 1)(rng);
    };
    const char ch = kFuzzAlphabet[pick(kFuzzAlphabet.size())];
    switch (op(rng)) {
    case 0: // delete a character
      if (!s.empty()) s.erase(pick(s.size()), 1);
      break;
    case 1: // insert a character
      s.insert(s.begin() + static_cast<std::ptrdiff_t>(pick(s.size() + 1)), ch);
      break;
    case 2: // replace a character
      if (!s.empty()) s[pick(s.size())] = ch;
      break;
    case 3:   // swap two lines
    case 4: { // or duplicate one
      std::vector<std::string> lines;
      std::string line;
      std::istringstream in(s);
      while (std::getline(in, line))
        lines.push_back(line);
      if (lines.empty()) break;
      const std::size_t i = pick(lines.size()), j = pick(lines.size());
      if (op(rng) % 2 == 0)
        std::swap(lines[i], lines[j]);
      else
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(j), lines[i]);
      s.clear();
      for (const auto& l : lines)
        s += l + "\n";
      break;
    }
    default: // delete a line
    {
      const std::size_t p = pick(s.size());
      const std::size_t b = s.rfind('\n', p), e = s.find('\n', p);
      const std::size_t from = b == std::string::npos ? 0 : b + 1;
      s.erase(from, e == std::string::npos ? std::string::npos : e - from + 1);
    }
    }
  }
  return s;
}

TEST(StudyFuzz, ParseConfigReturnsOrThrowsInvalidInput) {
  std::mt19937_64 rng(fuzz_seed(20240611));
  const int iters = fuzz_iters(20000);
  int ok = 0, refused = 0;
  for (int iter = 0; iter < iters; ++iter) {
    const std::string text = mutate(kFuzzIni, rng);
    try {
      const StudyConfig c = parse(text);
      ++ok;
      if (c.kind == StudyConfig::Kind::Grid && case_count(c) <= 20000) {
        // A config that parses expands: every case was validated up front.
        const auto cases = expand_cases(c);
        ASSERT_EQ(cases.size(), case_count(c)) << text;
        for (const Row& s : cases)
          mdrmap::validate(case_for(c, s));
        ASSERT_FALSE(canonical(c).empty());
      }
    } catch (const InvalidInput& e) {
      ++refused;
      ASSERT_FALSE(e.option().empty()) << c_literal(text);
      ASSERT_TRUE(good_message(e.what())) << c_literal(text);
    } catch (const std::exception& e) {
      FAIL() << "unexpected exception " << e.what() << " for:\n" << c_literal(text);
    } catch (...) {
      FAIL() << "unexpected non-std exception for:\n" << c_literal(text);
    }
  }
  EXPECT_GT(ok, iters / 20);
  EXPECT_GT(refused, iters / 20);
}

TEST(StudyFuzz, OverridesReturnOrThrowInvalidInput) {
  std::mt19937_64 rng(fuzz_seed(7));
  const StudyConfig base_config = parse(kFuzzIni);
  const std::vector<std::string> keys = {
      "grid.d",      "grid.R",   "grid.tau", "grid.v",     "grid.v1",        "grid.v1_over_v",
      "run.samples", "run.rtol", "run.G",    "run.solver", "run.timeseries", "run.t_end_over_tau",
      "cases.file",  "run"};
  const std::vector<std::string> values = {
      "1",     "0",   "linspace:0:1:3", "logspace:1:10:4", "1e-3, 2e-3", "true",
      "exact", "401", "0.01",           "1e300",           "-1",         ""};
  const int iters = fuzz_iters(3000);
  for (int iter = 0; iter < iters; ++iter) {
    StudyConfig c = base_config;
    const std::string key = keys[rng() % keys.size()];
    const std::string value = mutate(values[rng() % values.size()], rng);
    try {
      apply_override(c, key, value);
      ASSERT_LE(case_count(c), 1'000'000'000u);
    } catch (const InvalidInput& e) {
      ASSERT_TRUE(good_message(e.what())) << key << " = " << c_literal(value);
      ASSERT_EQ(std::string(e.what()).rfind("command line: ", 0), 0u) << e.what();
    } catch (const std::exception& e) {
      FAIL() << "unexpected exception " << e.what() << " for " << key << " = " << c_literal(value);
    }
  }
}

TEST(StudyFuzz, ReadCasesCsvReturnsOrThrowsInvalidInput) {
  std::mt19937_64 rng(fuzz_seed(99));
  const std::string csv = "d,R,tau,v,v1\n1e-3,1,1,1,0\n2e-3,1,0,1,0.5\n\n1e-3,2,1,3,9\n";
  const std::string path = (fs::path(tmp().path()) / "fuzz.csv").string();
  const int iters = fuzz_iters(5000);
  int ok = 0, refused = 0;
  for (int iter = 0; iter < iters; ++iter) {
    const std::string text = mutate(csv, rng);
    write_fast(path, text);
    try {
      const StudyConfig c = parse_config("[cases]\nfile = " + path + "\n", "", "fuzz.ini");
      const auto cases = expand_cases(c);
      ++ok;
      ASSERT_FALSE(cases.empty());
      for (const Row& s : cases)
        mdrmap::validate(case_for(c, s));
    } catch (const InvalidInput& e) {
      ++refused;
      ASSERT_TRUE(good_message(e.what())) << c_literal(text);
      ASSERT_FALSE(e.option().empty()) << c_literal(text);
    } catch (const std::exception& e) {
      FAIL() << "unexpected exception " << e.what() << " for:\n" << c_literal(text);
    }
  }
  EXPECT_GT(ok, iters / 25);
  EXPECT_GT(refused, iters / 25);
}

} // namespace
