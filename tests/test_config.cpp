// Study configs: INI parsing, axis specs, case lists, canonical text,
// command-line overrides, and a seeded fuzz test of the parsers.
#include <gtest/gtest.h>

#include <stdlib.h> // mkdtemp

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "study/config.hpp"

namespace fs = std::filesystem;
using mdrmap::InvalidInput;
using mdrmap::Scene;
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
      {"missing axis tau", base({{4, ""}}), "grid.tau", {"t.ini:1:", "'tau'"}},
      {"missing v1", base({{6, ""}}), "grid.v1", {"t.ini:1:", "v1_over_v"}},
      {"both v1 and v1_over_v",
       base({{6, "v1_over_v = 0.5\nv1 = 1"}}),
       "grid.v1",
       {"t.ini:7:", "line 6"}},
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
      {"unknown solver", base({}, "solver = fast\n"), "run.solver", {"t.ini:10:", "'fast'", "mdr"}},
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
  ASSERT_EQ(c.axes.size(), 5u);
  EXPECT_EQ(c.axes[0].name, "d");
  EXPECT_EQ(c.axes[0].values, std::vector<double>({1e-3}));
  EXPECT_EQ(c.axes[1].values, std::vector<double>({1, 2, 5}));
  EXPECT_EQ(c.axes[1].spec, "1, 2 ,5");
  EXPECT_EQ(c.axes[2].values, std::vector<double>({0.5, 1.0, 1.5, 2.0}));
  EXPECT_FALSE(c.axes[2].logarithmic);
  ASSERT_EQ(c.axes[3].values.size(), 5u);
  EXPECT_TRUE(c.axes[3].logarithmic);
  EXPECT_EQ(at(c, 3, 0), 1e-2); // exactly the ends
  EXPECT_EQ(at(c, 3, 4), 1e2);
  EXPECT_NEAR(at(c, 3, 1), 0.1, 1e-15);
  EXPECT_NEAR(at(c, 3, 2), 1.0, 1e-15);
  EXPECT_NEAR(at(c, 3, 3), 10.0, 1e-13);
  EXPECT_EQ(c.axes[4].name, "v1_over_v");
  EXPECT_EQ(c.axes[4].values, std::vector<double>({0, 1e-4}));
  EXPECT_EQ(case_count(c), 1u * 3 * 4 * 5 * 2);
  // [run] defaults
  EXPECT_EQ(c.run.samples, 201);
  EXPECT_EQ(c.run.t_end_over_tau, 6.0);
  EXPECT_EQ(c.run.rtol, 1e-4);
  EXPECT_EQ(c.run.solver, "auto");
  EXPECT_FALSE(c.run.timeseries);
  EXPECT_EQ(c.run.G, 1.0);
}

TEST(StudyConfigGood, LinspaceAndLogspaceEndsAreExact) {
  for (const auto& [lo, hi, n] : std::vector<std::tuple<double, double, int>>{
           {0.1, 0.7, 7}, {1e-9, 3.3, 13}, {0.3, 0.1, 3}, {1e-300, 1e300, 11}, {2.5, 2.5, 1}}) {
    for (const char* form : {"linspace", "logspace"}) {
      std::ostringstream spec;
      spec.precision(17);
      spec << form << ":" << lo << ":" << hi << ":" << n;
      SCOPED_TRACE(spec.str());
      const Axis a = parse_axis("v", spec.str());
      ASSERT_EQ(a.values.size(), static_cast<std::size_t>(n));
      EXPECT_EQ(a.values.front(), lo);
      EXPECT_EQ(a.values.back(), hi);
      for (std::size_t i = 0; i < a.values.size(); ++i)
        EXPECT_TRUE(std::isfinite(a.values[i]));
    }
  }
  const Axis g = parse_axis("v", "logspace:1e-300:1e300:7");
  EXPECT_NEAR(std::log10(g.values[3]), 0.0, 1e-12); // no overflow of hi/lo
}

TEST(StudyConfigGood, DescendingLinspace) {
  const Axis a = parse_axis("tau", "linspace:2:0.5:4");
  EXPECT_EQ(a.values, std::vector<double>({2.0, 1.5, 1.0, 0.5}));
  const Axis b = parse_axis("tau", "linspace:1:0:3");
  EXPECT_EQ(b.values, std::vector<double>({1.0, 0.5, 0.0}));
  const Axis l = parse_axis("v", "logspace:100:1:3");
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
        EXPECT_EQ(cases[k].d, d);
        EXPECT_EQ(cases[k].R, 3.0);
        EXPECT_EQ(cases[k].tau, tau);
        EXPECT_EQ(cases[k].v, 7.0);
        EXPECT_EQ(cases[k].v1, v1);
        EXPECT_EQ(cases[k].G, 1.0);
        ++k;
      }
}

TEST(StudyConfigGood, V1OverVMultipliesV) {
  const StudyConfig c =
      parse("[grid]\nd = 1e-3\nR = 1\ntau = 1\nv = 2, 4\nv1_over_v = 0.5, 3\n[run]\nG = 2.5\n");
  const auto cases = expand_cases(c);
  ASSERT_EQ(cases.size(), 4u);
  EXPECT_EQ(cases[0].v1, 1.0);
  EXPECT_EQ(cases[1].v1, 6.0);
  EXPECT_EQ(cases[2].v1, 2.0);
  EXPECT_EQ(cases[3].v1, 12.0);
  for (const Scene& s : cases)
    EXPECT_EQ(s.G, 2.5);
}

TEST(StudyConfigGood, RunSettingsAndNormalization) {
  const StudyConfig c = parse("\xEF\xBB\xBF[run]\r\n"
                              "t_end_over_tau = 3 ; window\r\n"
                              "samples = +401\r\n"
                              "rtol = 1e-6\r\n"
                              "solver = mdr\r\n"
                              "timeseries = YES\r\n"
                              "G = 0x10\r\n"
                              "[grid]\r\n"
                              "d=1e-3\r\nR=1\r\ntau=2, 0\r\nv=1\r\nv1=1 #comment\r\n");
  EXPECT_EQ(c.run.t_end_over_tau, 3.0);
  EXPECT_EQ(c.run.samples, 401);
  EXPECT_EQ(c.run.rtol, 1e-6);
  EXPECT_EQ(c.run.solver, "mdr");
  EXPECT_TRUE(c.run.timeseries);
  EXPECT_EQ(c.run.G, 16.0);
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
  EXPECT_EQ(parse(base({{6, "v1 = 1 #x"}})).axes[4].values, std::vector<double>({1.0}));
  EXPECT_EQ(parse(base({{6, "v1 = 1\t;x"}})).axes[4].values, std::vector<double>({1.0}));
}

TEST(StudyConfigGood, ProtocolFor) {
  const StudyConfig c = parse(base({{4, "tau = 0, 2"}}, "t_end_over_tau = 3\n"));
  const auto cases = expand_cases(c);
  ASSERT_EQ(cases.size(), 2u);
  const mdrmap::Protocol p0 = protocol_for(c, cases[0]);
  EXPECT_EQ(p0.t_end, mdrmap::default_t_end(cases[0]));
  EXPECT_EQ(p0.samples, 11);
  const mdrmap::Protocol p1 = protocol_for(c, cases[1]);
  EXPECT_EQ(p1.t_end, 6.0);
  EXPECT_EQ(p1.samples, 11);
}

TEST(StudyConfigGood, ParseAxisErrorsNameTheAxis) {
  EXPECT_EQ(error_of([] { parse_axis("R", "0"); }).first, "grid.R");
  EXPECT_EQ(error_of([] { parse_axis("v1_over_v", "-1"); }).first, "grid.v1_over_v");
  EXPECT_EQ(error_of([] { parse_axis("q", "1"); }).first, "grid.q");
  EXPECT_EQ(error_of([] { parse_axis("v", "linspace:1:2:100000000"); }).first, "grid.v");
  EXPECT_EQ(error_of([] { parse_axis("v", ""); }).first, "grid.v");
  EXPECT_EQ(parse_axis("tau", "-0").values, std::vector<double>({0.0}));
  EXPECT_FALSE(std::signbit(parse_axis("tau", "-0").values[0])); // -0 normalized
}

// --- Case lists ------------------------------------------------------------------

TEST(StudyCases, GoodCsvAnyColumnOrder) {
  const std::string p = tmp().write("good.csv", "v1, tau ,d,R,v\r\n"
                                                "\r\n"
                                                "0.5,1,1e-3,1,2\r\n"
                                                "  0 , 0 , 2e-3 , 3 , 4  \r\n"
                                                "\n"
                                                "7,2,1e-2,1,7\n");
  const auto cases = read_cases_csv(p, 2.0);
  ASSERT_EQ(cases.size(), 3u);
  EXPECT_EQ(cases[0].d, 1e-3);
  EXPECT_EQ(cases[0].R, 1.0);
  EXPECT_EQ(cases[0].tau, 1.0);
  EXPECT_EQ(cases[0].v, 2.0);
  EXPECT_EQ(cases[0].v1, 0.5);
  EXPECT_EQ(cases[0].G, 2.0);
  EXPECT_EQ(cases[1].d, 2e-3);
  EXPECT_EQ(cases[1].tau, 0.0);
  EXPECT_EQ(cases[1].v1, 0.0);
  EXPECT_EQ(cases[2].v1, 7.0);
  EXPECT_EQ(cases[2].tau, 2.0);
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
      {"missing column", "d,R,tau,v\n1e-3,1,1,1\n", "cases.file", {"bad.csv:1:", "'v1'"}},
      {"unknown column", "d,R,tau,v,vv\n", "cases.file", {"bad.csv:1:5:", "'vv'"}},
      {"duplicate column", "d,R,tau,v,d,v1\n", "cases.file", {"bad.csv:1:5:", "twice"}},
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
       {"bad.csv:2:3:", "overflow"}},
  };
  for (const auto& b : table) {
    SCOPED_TRACE(b.name);
    const std::string p = tmp().write("bad.csv", b.text);
    const auto [option, message] = error_of([&] { read_cases_csv(p, 1.0); });
    EXPECT_EQ(option, b.option) << message;
    for (const auto& m : b.mentions)
      EXPECT_NE(message.find(m), std::string::npos) << message;
    EXPECT_TRUE(one_line(message)) << message;
  }
  const auto missing = error_of([] { read_cases_csv(tmp().path() + "/nope.csv", 1.0); });
  EXPECT_EQ(missing.first, "cases.file");
  EXPECT_NE(missing.second.find("cannot read"), std::string::npos) << missing.second;
  const auto dir = error_of([] { read_cases_csv(tmp().path(), 1.0); });
  EXPECT_EQ(dir.first, "cases.file");
  const std::string good = tmp().write("g.csv", "d,R,tau,v,v1\n1,1,1,1,1\n");
  EXPECT_EQ(error_of([&] { read_cases_csv(good, 0.0); }).first, "run.G");
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
  const auto cases = expand_cases(c);
  ASSERT_EQ(cases.size(), 3u); // file order
  EXPECT_EQ(cases[0].d, 1e-3);
  EXPECT_EQ(cases[1].d, 2e-3);
  EXPECT_EQ(cases[2].v1, 9.0);
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
  EXPECT_EQ(c.run.samples, 401);
  EXPECT_EQ(c.run.t_end_over_tau, 2.5);
  EXPECT_EQ(c.run.rtol, 1e-5);
  EXPECT_EQ(c.run.solver, "baseline");
  EXPECT_TRUE(c.run.timeseries);
  EXPECT_EQ(c.run.G, 3.0);
  EXPECT_EQ(expand_cases(c).front().G, 3.0);
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
  EXPECT_EQ(c.axes.size(), 5u);
  EXPECT_EQ(c.axes[4].name, "v1");
  EXPECT_EQ(expand_cases(c).front().v1, 0.25);
  apply_override(c, "grid.v1_over_v", "0.25");
  EXPECT_EQ(c.axes[4].name, "v1_over_v");
  EXPECT_EQ(expand_cases(c).front().v1, 0.5);
  EXPECT_EQ(case_count(c), 6u);
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
  const std::map<std::string, std::size_t> expected = {{"quick.ini", 40},
                                                       {"start_stop.ini", 3},
                                                       {"friction_map.ini", 561},
                                                       {"v1_sweep.ini", 60},
                                                       {"cases.ini", 7}};
  for (const auto& [name, count] : expected) {
    SCOPED_TRACE(name);
    const StudyConfig c = load_config((dir / name).string());
    EXPECT_EQ(case_count(c), count);
    EXPECT_EQ(expand_cases(c).size(), count);
    EXPECT_FALSE(canonical(c).empty());
  }
  const StudyConfig s = load_config((dir / "start_stop.ini").string());
  EXPECT_TRUE(s.run.timeseries);
  for (const Scene& sc : expand_cases(s)) {
    // a start-stop test: fast before (zeta >> 1, a2 ~ 0) and nearly stopped
    // after (zeta1 << 1, a2 -> a1), v1 = 1e-4 v as in the paper
    EXPECT_EQ(sc.v1, 1e-4 * sc.v);
    EXPECT_GE(mdrmap::zeta(sc), 100.0);
    EXPECT_LE(mdrmap::zeta1(sc), 0.1 + 1e-12);
  }
}

// --- Fuzz ------------------------------------------------------------------------------

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
  std::mt19937_64 rng(20240611);
  int ok = 0, refused = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    const std::string text = mutate(kFuzzIni, rng);
    try {
      const StudyConfig c = parse(text);
      ++ok;
      if (c.kind == StudyConfig::Kind::Grid && case_count(c) <= 20000) {
        // A config that parses expands: every case was validated up front.
        const auto cases = expand_cases(c);
        ASSERT_EQ(cases.size(), case_count(c)) << text;
        for (const Scene& s : cases)
          mdrmap::validate(protocol_for(c, s));
        ASSERT_FALSE(canonical(c).empty());
      }
    } catch (const InvalidInput& e) {
      ++refused;
      ASSERT_FALSE(e.option().empty()) << text;
      ASSERT_TRUE(one_line(e.what())) << e.what();
    } catch (const std::exception& e) {
      FAIL() << "unexpected exception " << e.what() << " for:\n" << text;
    } catch (...) {
      FAIL() << "unexpected non-std exception for:\n" << text;
    }
  }
  EXPECT_GT(ok, 1000);
  EXPECT_GT(refused, 1000);
}

TEST(StudyFuzz, OverridesReturnOrThrowInvalidInput) {
  std::mt19937_64 rng(7);
  const StudyConfig base_config = parse(kFuzzIni);
  const std::vector<std::string> keys = {
      "grid.d",      "grid.R",   "grid.tau", "grid.v",     "grid.v1",        "grid.v1_over_v",
      "run.samples", "run.rtol", "run.G",    "run.solver", "run.timeseries", "run.t_end_over_tau",
      "cases.file",  "run"};
  const std::vector<std::string> values = {
      "1",     "0",   "linspace:0:1:3", "logspace:1:10:4", "1e-3, 2e-3", "true",
      "exact", "401", "0.01",           "1e300",           "-1",         ""};
  for (int iter = 0; iter < 3000; ++iter) {
    StudyConfig c = base_config;
    const std::string key = keys[rng() % keys.size()];
    const std::string value = mutate(values[rng() % values.size()], rng);
    try {
      apply_override(c, key, value);
      ASSERT_LE(case_count(c), 1'000'000'000u);
    } catch (const InvalidInput& e) {
      ASSERT_TRUE(one_line(e.what())) << e.what();
      ASSERT_EQ(std::string(e.what()).rfind("command line: ", 0), 0u) << e.what();
    } catch (const std::exception& e) {
      FAIL() << "unexpected exception " << e.what() << " for " << key << " = " << value;
    }
  }
}

TEST(StudyFuzz, ReadCasesCsvReturnsOrThrowsInvalidInput) {
  std::mt19937_64 rng(99);
  const std::string csv = "d,R,tau,v,v1\n1e-3,1,1,1,0\n2e-3,1,0,1,0.5\n\n1e-3,2,1,3,9\n";
  const std::string path = (fs::path(tmp().path()) / "fuzz.csv").string();
  int ok = 0, refused = 0;
  for (int iter = 0; iter < 5000; ++iter) {
    const std::string text = mutate(csv, rng);
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out << text;
    }
    try {
      const auto cases = read_cases_csv(path, 1.0);
      ++ok;
      ASSERT_FALSE(cases.empty());
      for (const Scene& s : cases)
        mdrmap::validate(s);
    } catch (const InvalidInput& e) {
      ++refused;
      ASSERT_TRUE(one_line(e.what())) << e.what();
      ASSERT_EQ(e.option().rfind("cases.", 0), 0u) << e.option();
    } catch (const std::exception& e) {
      FAIL() << "unexpected exception " << e.what() << " for:\n" << text;
    }
  }
  EXPECT_GT(ok, 200);
  EXPECT_GT(refused, 200);
}

} // namespace
