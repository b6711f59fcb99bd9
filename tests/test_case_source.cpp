// The cases of a study by index (study/case_source): a grid's computed from
// the index, a case list's read by range through its sparse index, each equal
// to expand_cases; the streamed checks fail as expand_cases fails; a case
// list's canonical text by digest.
#include <gtest/gtest.h>

#include <stdlib.h> // mkdtemp

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "study/case_list.hpp"
#include "study/case_source.hpp"
#include "study/config.hpp"

namespace fs = std::filesystem;
using mdrmap::Case;
using mdrmap::InvalidInput;
using namespace mdrmap::study;

namespace {

/// Writes `text` to `name` in a fresh directory, removed at exit.
std::string file_with(const std::string& name, const std::string& text) {
  static const struct Dir {
    std::string path;
    ~Dir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  } dir{[] {
    std::string t = (fs::temp_directory_path() / "mdrmap_case_source_XXXXXX").string();
    if (mkdtemp(t.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    return t;
  }()};
  const std::string path = dir.path + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::pair<std::string, std::string> failure(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return {e.option(), e.what()};
  }
  return {"", "(no error)"};
}

void expect_same(const Row& a, const Row& b, std::size_t i) {
  EXPECT_EQ(a, b) << "case " << i;
}

/// Sets the one value of column `name` (a hand-made config).
void set_column(StudyConfig& c, const std::string& name, double x) {
  for (Axis& a : c.axes)
    if (a.name == name) {
      a.values = {x};
      return;
    }
  ADD_FAILURE() << "no column " << name;
}

/// Every case by row(i), and random ranges by rows(), against expand_cases.
void expect_matches_expansion(const StudyConfig& c, const CaseSource& s) {
  const std::vector<Row> all = expand_cases(c);
  ASSERT_EQ(s.size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i)
    expect_same(s.row(i), all[i], i);
  std::mt19937_64 rng(7);
  std::vector<Row> got;
  for (int k = 0; k < 50; ++k) {
    std::size_t i0 = rng() % all.size(), i1 = rng() % (all.size() + 1);
    if (i1 < i0) std::swap(i0, i1);
    s.rows(i0, i1, got);
    ASSERT_EQ(got.size(), i1 - i0);
    for (std::size_t i = i0; i < i1; ++i)
      expect_same(got[i - i0], all[i], i);
  }
  s.rows(0, all.size(), got); // all at once, in order
  ASSERT_EQ(got.size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i)
    expect_same(got[i], all[i], i);
}

std::string csv_of(std::size_t n) {
  std::string text = "\xEF\xBB\xBF# a comment before the header\r\n\nv1, v, tau, R, d\r\n";
  for (std::size_t i = 0; i < n; ++i) {
    if (i % 1000 == 7) text += "\n# a comment\n   \n";
    const double x = static_cast<double>(i + 1);
    text += std::to_string(x * 1e-6) + "," + std::to_string(1.0 + x) + "," +
            std::to_string(0.5 + 1e-5 * x) + ", 1e0 ," + std::to_string(1e-3 + 1e-9 * x) +
            (i % 3 == 0 ? "\r\n" : "\n");
  }
  return text;
}

} // namespace

TEST(CaseSource, GridCasesFromTheirIndexInExpansionOrder) {
  for (const char* fifth : {"v1 = 0, 0.5, 2", "v1_over_v = linspace:0:0.9:4"}) {
    const StudyConfig c = parse_config(
        std::string("[grid]\nd = 1e-3, 2e-3\nR = logspace:1:10:3\ntau = 0, 1, 2\nv = 1, 3\n") +
            fifth + "\n[run]\nG = 2.5\n",
        "", "g.ini");
    const CaseSource s(c);
    expect_matches_expansion(c, s);
    EXPECT_EQ(s.canonical(), canonical(c));
  }
}

TEST(CaseSource, CaseListRowsByRangeAcrossIndexBlocks) {
  const std::size_t n = 3 * CaseListIndex::kStride + 17;
  file_with("many.csv", csv_of(n));
  const StudyConfig c = parse_config("[cases]\nfile = many.csv\n[run]\nG = 3\n",
                                     fs::path(file_with("x", "")).parent_path().string(), "l.ini");
  const CaseListIndex index = scan_case_list(c, true);
  EXPECT_EQ(index.count, n);
  EXPECT_EQ(index.offsets.size(), 4u); // one per 4096 cases
  EXPECT_EQ(index.sha256.size(), 64u);
  const CaseListIndex copy = CaseListIndex::unpack(index.pack());
  EXPECT_EQ(copy.count, index.count);
  EXPECT_EQ(copy.file_bytes, index.file_bytes);
  EXPECT_EQ(copy.offsets, index.offsets);
  EXPECT_EQ(copy.lines, index.lines);
  EXPECT_EQ(copy.sha256, index.sha256);
  const CaseSource s(c, copy);
  expect_matches_expansion(c, s);
  // the canonical text: by digest, as canonical() makes it, and as a
  // scanning CaseSource makes it
  EXPECT_EQ(s.canonical(), canonical(c));
  EXPECT_EQ(CaseSource(c).canonical(), canonical(c));
  EXPECT_NE(canonical(c).find("count = " + std::to_string(n)), std::string::npos);
}

TEST(CaseSource, CaseListCanonicalHoldsTheValues) {
  const std::string dir =
      fs::path(file_with("a.csv", "d,R,tau,v,v1\n1e-3,1,1,1,0\n2e-3,1,0,1,0.5\n"))
          .parent_path()
          .string();
  file_with("b.csv", "# same values, other form\nv1,v,tau,R,d\n0,1,1,1,0.001\n0.5,1.0,0,1,2e-3\n");
  file_with("c.csv", "d,R,tau,v,v1\n1e-3,1,1,1,0\n2e-3,1,0,1,0.25\n");
  const auto cfg = [&](const char* f) {
    return parse_config(std::string("[cases]\nfile = ") + f + "\n", dir, "x.ini");
  };
  EXPECT_EQ(canonical(cfg("a.csv")), canonical(cfg("b.csv")));
  EXPECT_NE(canonical(cfg("a.csv")), canonical(cfg("c.csv")));
  StudyConfig other = cfg("a.csv");
  other.run.samples = 7;
  EXPECT_NE(canonical(other), canonical(cfg("a.csv")));
}

TEST(CaseSource, ACaseListChangedAfterTheScanIsRefused) {
  const std::string p = file_with("changing.csv", csv_of(100));
  const StudyConfig c =
      parse_config("[cases]\nfile = changing.csv\n", fs::path(p).parent_path().string(), "x.ini");
  const CaseSource s(c);
  file_with("changing.csv", csv_of(50));
  std::vector<Row> rows;
  EXPECT_EQ(failure([&] { s.rows(0, 10, rows); }).first, "cases.file");
}

TEST(CaseSource, StreamedChecksFailAsExpandCases) {
  // a grid: a window that overflows for the larger tau only (hand-made:
  // parse_config would refuse it from the grid's corners)
  StudyConfig g =
      parse_config("[grid]\nd = 1e-3\nR = 1\ntau = 1, 1e300\nv = 1, 2\nv1 = 0, 1\n", "", "g.ini");
  set_column(g, "t_end_over_tau", 1e10);
  const auto expanded = failure([&] { expand_cases(g); });
  ASSERT_NE(expanded.first, "");
  EXPECT_NE(expanded.second.find("case 5:"), std::string::npos) << expanded.second;
  EXPECT_EQ(failure([&] { check_grid_cases(g, 0, 8); }), expanded);
  EXPECT_EQ(failure([&] { check_grid_cases(g, 3, 6); }), expanded);
  EXPECT_EQ(failure([&] { check_grid_cases(g, 0, 4); }).first, ""); // the cases before pass

  // a case list: a bad window in case 2, an unreadable value on a later line
  // (read first, as expand_cases reads the whole list first), then the window
  const std::string dir =
      fs::path(file_with("window.csv", "d,R,tau,v,v1\n1e-3,1,1,1,0\n1e-3,1,1e300,1,0\n"))
          .parent_path()
          .string();
  file_with("both.csv", "d,R,tau,v,v1\n1e-3,1,1,1,0\n1e-3,1,1e300,1,0\n1e-3,1,x,1,0\n");
  for (const char* f : {"window.csv", "both.csv"}) {
    StudyConfig c = parse_config(std::string("[cases]\nfile = ") + f + "\n", dir, "l.ini");
    set_column(c, "t_end_over_tau", 1e10);
    const auto want = failure([&] { expand_cases(c); });
    ASSERT_NE(want.first, "") << f;
    EXPECT_EQ(failure([&] { scan_case_list(c, true); }), want) << f;
  }
  // the time series' memory, after reading every case
  StudyConfig t = parse_config("[cases]\nfile = window.csv\n[run]\ntimeseries = true\n", dir, "t");
  t.run.samples = 1'000'000'000'000;
  EXPECT_EQ(failure([&] { scan_case_list(t, true); }), failure([&] { expand_cases(t); }));
  EXPECT_EQ(failure([&] { scan_case_list(t, true); }).first, "run.timeseries");
  // an empty list, as expand_cases says it
  file_with("empty.csv", "d,R,tau,v,v1\n# nothing\n");
  const StudyConfig e = parse_config("[cases]\nfile = empty.csv\n", dir, "e.ini");
  EXPECT_EQ(failure([&] { scan_case_list(e, true); }), failure([&] { expand_cases(e); }));
  EXPECT_NE(failure([&] { expand_cases(e); }).second.find("no cases"), std::string::npos);
}

TEST(CaseSource, Sha256KnownAnswers) {
  const auto sha = [](const std::string& s) {
    mdrmap::study::detail::Sha256 h;
    h.add(s);
    return h.hex();
  };
  EXPECT_EQ(sha(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  mdrmap::study::detail::Sha256 million; // in pieces of odd sizes
  const std::string a(997, 'a');
  std::size_t left = 1'000'000;
  while (left > 0) {
    const std::size_t k = std::min(left, a.size());
    million.add(a.data(), k);
    left -= k;
  }
  EXPECT_EQ(million.hex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(CaseSource, HistoryGridRowsAsExpansion) {
  const StudyConfig c =
      parse_config("[grid]\nFN = 1e-3, 2e-3\nR = 1\ntau = 0.5, 2\nv = 0.1, 1\n"
                   "[history]\nw1_over_v = 0, 0.5\nT1_over_tau = logspace:1:100:3\nw2_over_v = 1\n"
                   "T2_over_tau = 5, 20\n",
                   "", "h.ini");
  const CaseSource s(c);
  ASSERT_EQ(s.size(), 2u * 2 * 2 * 2 * 3 * 2);
  const std::vector<Row> all = expand_cases(c);
  for (std::size_t i = 0; i < all.size(); ++i)
    ASSERT_EQ(s.row(i), all[i]) << i;
  expect_matches_expansion(c, s);
  EXPECT_EQ(s.canonical(), canonical(c));
  // the last column fastest: T2_over_tau, then T1_over_tau
  EXPECT_EQ(s.row(0).back(), 5.0);
  EXPECT_EQ(s.row(1).back(), 20.0);
  EXPECT_EQ(s.row(2)[c.axes.size() - 3], 10.0); // T1_over_tau's second value
}

TEST(CaseSource, CaseListWithHistoryColumnsByRange) {
  std::string text = "w1,T1,w2,T2,F0,R,tau,v\n";
  const std::size_t n = CaseListIndex::kStride + 5;
  for (std::size_t i = 0; i < n; ++i)
    text += "0," + std::to_string(1 + i) + ",0.5,3,1e-3,1,1,0.5\n";
  const std::string p = file_with("hist.csv", text);
  const StudyConfig c =
      parse_config("[cases]\nfile = hist.csv\n", fs::path(p).parent_path().string(), "h.ini");
  EXPECT_EQ(c.segments(), 2u);
  const CaseSource s(c);
  expect_matches_expansion(c, s);
  const Case k = case_for(c, s.row(n - 1));
  EXPECT_EQ(k.history.segments.at(0).T, static_cast<double>(n));
  EXPECT_EQ(k.history.segments.at(1).w, 0.5);
}

// A grid over a spectrum's terms and the temperature, and a case list with
// terms and aT, by index as expanded (issue 19).
TEST(CaseSource, SpectrumAndTemperatureColumnsAsExpansion) {
  const StudyConfig g =
      parse_config("[grid]\nd = 1e-3\nR = 1\ntau = 0\nG = 1\nG1 = 1, 2\ntau1 = logspace:0.01:1:3\n"
                   "temperature = 20, 30\nv = 1\n[history]\nw1_over_v = 0\nT1_over_tau = 10\n"
                   "[run]\nwlf = 8.86:101.6:20\n",
                   "", "s.ini");
  const CaseSource s(g);
  ASSERT_EQ(s.size(), 2u * 3 * 2);
  expect_matches_expansion(g, s);
  EXPECT_EQ(s.canonical(), canonical(g));
  EXPECT_EQ(case_for(g, s.row(0)).rheology.branches.at(0).tau, 0.01);
  EXPECT_LT(case_for(g, s.row(1)).rheology.aT, 1.0); // temperature fastest: 30 > TREF
  std::string text = "G1,tau1,aT,d,R,tau,G,v,w1,T1\n";
  const std::size_t n = CaseListIndex::kStride + 3;
  for (std::size_t i = 0; i < n; ++i)
    text += "2," + std::to_string(1 + i) + ",0.5,1e-3,1,0,1,1,0,3\n";
  const std::string p = file_with("spec.csv", text);
  const StudyConfig c =
      parse_config("[cases]\nfile = spec.csv\n", fs::path(p).parent_path().string(), "l.ini");
  const CaseSource l(c);
  expect_matches_expansion(c, l);
  const Case k = case_for(c, l.row(n - 1));
  EXPECT_EQ(k.rheology.branches.at(0).tau, static_cast<double>(n));
  EXPECT_EQ(k.rheology.aT, 0.5);
}
