// The seed path's shortcuts (issue 22): a case checked once (CheckedCase),
// the exact solver's answers cached where its edge sits at the cap for good,
// and the map row's fields resolved once (RowSlots). Each must give the very
// bits the long way gives.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/model/case.hpp"
#include "core/solvers/dispatch.hpp"
#include "core/solvers/exact.hpp"
#include "io/case_row.hpp"

namespace {

using mdrmap::Case;
using mdrmap::CheckedCase;
using mdrmap::ExactSolution;
using mdrmap::Segment;
using mdrmap::State;

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

void expect_same_state(const State& a, const State& b, const std::string& where) {
  EXPECT_TRUE(same_bits(a.FN, b.FN)) << where << ": FN " << a.FN << " vs " << b.FN;
  EXPECT_TRUE(same_bits(a.Fx, b.Fx)) << where << ": Fx " << a.Fx << " vs " << b.Fx;
  EXPECT_TRUE(same_bits(a.mu, b.mu)) << where << ": mu " << a.mu << " vs " << b.mu;
  EXPECT_TRUE(same_bits(a.a2, b.a2)) << where << ": a2 " << a.a2 << " vs " << b.a2;
}

Case history_case(double v, const std::vector<Segment>& segments, long samples) {
  Case c;
  c.loading.d = 1e-3;
  c.indenter.as<mdrmap::Parabola>().R = 1.0;
  c.rheology.tau = 1.0;
  c.history.v0 = v;
  c.history.segments = segments;
  c.sampling.samples = samples;
  return c;
}

// Steps out of stationary sliding over zeta0 = 3e-4 .. 3e3 (a1 = 0.0316),
// and histories whose later segments start from several pieces.
std::vector<Case> cases() {
  std::vector<Case> out;
  for (double v : {1e-5, 1e-3, 0.03, 1.0, 100.0})
    for (double r : {0.0, 1e-3, 0.1, 0.5, 0.9, 1.0, 2.0, 1e3})
      out.push_back(history_case(v, {{r * v, 6.0}}, 301));
  out.push_back(history_case(0.03, {{0.003, 0.5}, {0.0, 2.0}, {0.03, 3.0}, {0.01, 6.0}}, 201));
  out.push_back(history_case(1.0, {{0.5, 0.2}, {0.1, 0.2}, {0.01, 5.0}, {2.0, 1.0}}, 201));
  return out;
}

// The cache of the walk's answer (at_cap_from) changes no answer: states
// asked in increasing offsets (the cache fills and is used) equal those
// asked in decreasing offsets (every sample walks the pieces), bit for bit.
TEST(ExactCache, AnswersDoNotDependOnTheOrderOfTheQuestions) {
  int cached = 0;
  for (const Case& c : cases()) {
    ExactSolution up(c, 50), down(c, 50);
    for (std::size_t k = 0; k < c.history.size(); ++k) {
      const double T = c.history.segments[k].T;
      const long N = c.sampling.samples;
      std::vector<State> late_first(static_cast<std::size_t>(N));
      for (long j = N; j-- > 0;)
        late_first[static_cast<std::size_t>(j)] = down.at(k, c.sampling.offset(j, T));
      for (long j = 0; j < N; ++j)
        expect_same_state(up.at(k, c.sampling.offset(j, T)),
                          late_first[static_cast<std::size_t>(j)],
                          "v0 " + std::to_string(c.history.v0) + " segment " + std::to_string(k) +
                              " sample " + std::to_string(j));
      cached += up.segment_start(k).at_cap_from < T ? 1 : 0;
    }
  }
  EXPECT_GE(cached, 10) << "the cache was used on too few segments to test it";
}

// A drop out of stationary sliding reaches the cap and stays (the cache
// fills); a rise is at the cap throughout (no walk at all); a stop never
// reaches the cap a1.
TEST(ExactCache, ADropFillsItARiseNeedsNoneAStopNever) {
  const Case drop = history_case(0.03, {{0.015, 6.0}}, 61);
  const Case rise = history_case(0.03, {{0.3, 6.0}}, 61);
  const Case stop = history_case(0.03, {{0.0, 6.0}}, 61);
  for (const Case* c : {&drop, &rise, &stop}) {
    const mdrmap::RunResult r = mdrmap::run_exact(mdrmap::CheckedCase(*c), 1e-10);
    EXPECT_GT(r.series.size(), 0u);
  }
  ExactSolution d(drop, 50), r(rise, 50), s(stop, 50);
  for (long j = 0; j < 61; ++j) {
    d.at(0, drop.sampling.offset(j, 6.0));
    s.at(0, stop.sampling.offset(j, 6.0));
  }
  EXPECT_TRUE(d.segment_start(0).gap_at_cap_grows);
  EXPECT_LT(d.segment_start(0).at_cap_from, 6.0);
  EXPECT_TRUE(r.segment_start(0).at_cap_throughout);
  EXPECT_FALSE(d.segment_start(0).at_cap_throughout);
  EXPECT_EQ(s.segment_start(0).at_cap_from, std::numeric_limits<double>::infinity());
}

TEST(CheckedCase, IsValidatedWhenMade) {
  Case bad = history_case(1.0, {{0.5, 1.0}}, 11);
  bad.indenter.as<mdrmap::Parabola>().R = -1.0;
  try {
    CheckedCase c(bad);
    ADD_FAILURE() << "no InvalidInput";
  } catch (const mdrmap::InvalidInput& e) {
    EXPECT_EQ(e.option(), "R");
  }
}

// with_durations checks what the durations change (the history) and
// nothing else may differ.
TEST(CheckedCase, NewDurationsAreCheckedAsTheHistory) {
  const Case c = history_case(1.0, {{0.5, 1.0}, {2.0, 1.0}}, 11);
  {
    CheckedCase checked(c);
    const CheckedCase longer = std::move(checked).with_durations({{0.5, 3.0}, {2.0, 4.0}});
    EXPECT_EQ(longer.get().history.segments[0].T, 3.0);
    EXPECT_EQ(longer.get().history.segments[1].T, 4.0);
  }
  {
    CheckedCase checked(c);
    try {
      (void)std::move(checked).with_durations({{0.5, 1.0}, {2.0, 1e308}}); // slip 2e308
      ADD_FAILURE() << "no InvalidInput";
    } catch (const mdrmap::InvalidInput& e) {
      EXPECT_EQ(e.option(), "history");
    }
  }
  {
    CheckedCase checked(c);
    EXPECT_THROW((void)std::move(checked).with_durations({{0.7, 1.0}, {2.0, 1.0}}),
                 std::logic_error);
  }
  {
    CheckedCase checked(c);
    EXPECT_THROW((void)std::move(checked).with_durations({{0.5, 1.0}}), std::logic_error);
  }
}

// run_case hands the checked case to its solver as it is (the solvers take
// the CheckedCase and check nothing again): auto's run of these Kelvin cases
// at fixed depth is exact's run of the same checked case, bit for bit.
TEST(CheckedCase, RunCaseHandsItToTheSolverAsIs) {
  for (const Case& c : cases()) {
    const CheckedCase checked(c);
    const mdrmap::RunResult a = mdrmap::run_case(checked, mdrmap::SolverKind::Auto, 1e-6);
    const mdrmap::RunResult b = mdrmap::run_exact(checked, 1e-6);
    ASSERT_EQ(a.series.size(), b.series.size());
    for (std::size_t i = 0; i < a.series.size(); ++i)
      expect_same_state(a.series.at(i), b.series.at(i), "sample " + std::to_string(i));
    EXPECT_TRUE(same_bits(a.info.error_estimate, b.info.error_estimate));
  }
}

// The slots are the fields' indices by name, at depth and under load.
TEST(RowSlots, AreTheFieldsByName) {
  for (const bool load : {false, true})
    for (const std::size_t K : {1u, 3u}) {
      const mdrmap::io::RowLayout L(K, load);
      const mdrmap::io::RowSlots& S = L.slots();
      // the table's results, event metrics and event states the map holds, each once
      std::size_t results = 0, metrics = 0, states = 0;
      for (const mdrmap::OutputSpec& o : mdrmap::output_table()) {
        if ((o.where & mdrmap::kInMap) == 0) continue;
        results += o.group == mdrmap::OutputGroup::Result ? 1 : 0;
        metrics += o.group == mdrmap::OutputGroup::Event ? 1 : 0;
        states += o.group == mdrmap::OutputGroup::EventState ? 1 : 0;
      }
      EXPECT_EQ(S.results.size() + 1, results); // + wall_seconds
      EXPECT_EQ(S.event_metrics.size(), metrics);
      EXPECT_EQ(S.event_states.size(), states);
      EXPECT_EQ(S.wall_seconds, L.at("results/wall_seconds"));
      for (const auto& [o, at] : S.results)
        EXPECT_EQ(at, L.at(std::string("results/") + o->name)) << o->name;
      for (const auto& [o, at] : S.event_metrics)
        EXPECT_EQ(at + K - 1, L.at(std::string("events/") + o->name, K - 1)) << o->name;
      for (const auto& [o, at] : S.event_states)
        for (std::size_t q = 0; q < L.quantities(); ++q)
          EXPECT_EQ(at[q] + K - 1,
                    L.at("events/" + std::string(L.quantity(q)) + "_" + o->name, K - 1));
      for (std::size_t q = 0; q < L.quantities(); ++q) {
        const std::string n = L.quantity(q);
        EXPECT_EQ(S.results_pre[q], L.at("results/" + n + "_pre"));
        EXPECT_EQ(S.analytic_pre[q], L.at("analytic/" + n + "_pre"));
        EXPECT_EQ(S.residuals_pre[q], L.at("residuals/" + n + "_pre"));
        EXPECT_EQ(S.analytic_ss[q], L.at("analytic/" + n + "_ss"));
        EXPECT_EQ(S.residuals_end[q], L.at("residuals/" + n + "_end"));
        if (load) continue;
        EXPECT_EQ(S.analytic_jump[q], L.at("analytic/" + n + "_jump"));
        EXPECT_EQ(S.residuals_jump[q], L.at("residuals/" + n + "_jump"));
      }
    }
}

} // namespace
