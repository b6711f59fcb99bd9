// Typed option values (case/option_value.hpp), what the Python module hands
// the case reader: a number given as a number is that double, pairs are the
// history's segments or the spectrum's terms, three numbers the WLF
// constants; the case, the refusals and their messages are those of the
// same values given as the command line's texts. And one part of a case
// read alone (read_case_part) with the whole case's messages.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <map>
#include <string>

#include "case/case_input.hpp"
#include "case/option_value.hpp"

namespace {

using mdrmap::InvalidInput;
using mdrmap::Part;
using mdrmap::cases::OptionTexts;
using mdrmap::cases::OptionValue;
using mdrmap::cases::OptionValues;
using mdrmap::cases::read_case_input;
using mdrmap::cases::read_case_part;

/// The option and message read_case_input throws for `v` ("" / "" if none).
template <class In> std::pair<std::string, std::string> refusal(const In& v) {
  try {
    read_case_input(v);
  } catch (const InvalidInput& e) {
    return {e.option(), e.what()};
  }
  return {"", ""};
}

OptionValues base_values() {
  return {{"d", OptionValue::of_number(0.1)},
          {"R", OptionValue::of_number(10)},
          {"tau", OptionValue::of_number(1)},
          {"v", OptionValue::of_number(2)}};
}

OptionTexts base_texts() {
  return {{"d", "0.1"}, {"R", "10"}, {"tau", "1"}, {"v", "2"}};
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(OptionValues, NumbersAreTheirDoublesAndMakeTheCaseOfTheirTexts) {
  // 0.1 + 0.2 has no short text: 17 digits read back to it
  const double d = 0.1 + 0.2, w = 1.0 / 3.0;
  OptionValues v = base_values();
  v["d"] = OptionValue::of_number(d);
  v["history"] = OptionValue::of_pairs({{w, 2.5}, {0.0, 1.0}});
  v["samples"] = OptionValue::of_number(7);
  v["G"] = OptionValue::of_number(1);
  v["prony"] = OptionValue::of_pairs({{1.0, 0.1}, {2.0, w}});
  v["T"] = OptionValue::of_number(310);
  v["wlf"] = OptionValue::of_numbers({8.86, 101.6, 298});
  OptionTexts t = base_texts();
  t["d"] = "0.30000000000000004";
  t["history"] = "0.33333333333333331:2.5,0:1";
  t["samples"] = "7";
  t["G"] = "1";
  t["prony"] = "1:0.1,2:0.33333333333333331";
  t["T"] = "310";
  t["wlf"] = "8.86:101.6:298";
  const mdrmap::Case a = read_case_input(v).c, b = read_case_input(t).c;
  EXPECT_TRUE(same_bits(a.loading.d, d) && same_bits(b.loading.d, d));
  EXPECT_TRUE(same_bits(a.history.segments[0].w, w) && same_bits(b.history.segments[0].w, w));
  EXPECT_TRUE(same_bits(a.rheology.branches[1].tau, b.rheology.branches[1].tau));
  EXPECT_TRUE(same_bits(a.rheology.aT, b.rheology.aT));
  EXPECT_LT(a.rheology.aT, 1.0);
  EXPECT_EQ(a.sampling.samples, 7);
  EXPECT_EQ(a.history.segments.size(), 2U);
}

TEST(OptionValues, RefusalsAreTheTexts) {
  // {option, value as a number/pairs/numbers, the same as text}
  struct Row {
    const char* option;
    OptionValue value;
    const char* text;
  };
  const Row rows[] = {
      {"d", OptionValue::of_number(-1), "-1"},
      {"tau", OptionValue::of_number(std::numeric_limits<double>::quiet_NaN()), "nan"},
      {"samples", OptionValue::of_number(2.5), "2.5"},
      {"samples", OptionValue::of_number(1), "1"},
      {"history", OptionValue::of_pairs({{1, 2}, {-1, 2}}), "1:2,-1:2"},
      {"history", OptionValue::of_pairs({{1, std::numeric_limits<double>::infinity()}}), "1:inf"},
      {"prony", OptionValue::of_pairs({{0, 1}}), "0:1"},
      {"prony", OptionValue::of_pairs({{1, 1}, {2, -3}}), "1:1,2:-3"},
      {"rtol", OptionValue::of_number(0.2), "0.2"},
      {"wlf", OptionValue::of_numbers({0, 51.6, 0}), "0:51.6:0"},
      {"wlf", OptionValue::of_numbers({17.44, -51.6, 0}), "17.44:-51.6:0"},
      {"T", OptionValue::of_number(-60), "-60"},
  };
  for (const Row& r : rows) {
    OptionValues v = base_values();
    OptionTexts t = base_texts();
    const bool history = std::string(r.option) == "history";
    if (!history) {
      v["v1"] = OptionValue::of_number(0.5);
      t["v1"] = "0.5";
    }
    if (std::string(r.option) == "prony") {
      v["G"] = OptionValue::of_number(1);
      t["G"] = "1";
    }
    if (std::string(r.option) == "T" || std::string(r.option) == "wlf") {
      v.emplace("T", OptionValue::of_number(20));
      v.emplace("wlf", OptionValue::of_numbers({17.44, 51.6, 0}));
      t.emplace("T", "20");
      t.emplace("wlf", "17.44:51.6:0");
    }
    v[r.option] = r.value;
    t[r.option] = r.text;
    const auto typed = refusal(v), texts = refusal(t);
    EXPECT_EQ(typed.first, r.option) << r.text;
    EXPECT_EQ(typed, texts) << r.option << " " << r.text;
  }
}

TEST(OptionValues, AValueOfAnotherKindIsRefusedNamingTheOption) {
  OptionValues v = base_values();
  v["v1"] = OptionValue::of_number(0.5);
  v["profile"] = OptionValue::of_number(3);
  EXPECT_EQ(refusal(v), (std::pair<std::string, std::string>{"profile", "must be a text, got 3"}));
  v.erase("profile");
  v["d"] = OptionValue::of_pairs({{1, 2}});
  EXPECT_EQ(refusal(v).first, "d");
  EXPECT_EQ(refusal(v).second, "must be a number, got 1:2");
}

TEST(OptionValues, APartAloneIsReadWithTheWholeCasesMessages) {
  const auto part_refusal = [](const OptionValues& v, Part p) {
    try {
      read_case_part(v, p);
    } catch (const InvalidInput& e) {
      return std::pair<std::string, std::string>{e.option(), e.what()};
    }
    return std::pair<std::string, std::string>{"", ""};
  };
  const auto cone = read_case_part(
      {{"profile", OptionValue::of_text("cone")}, {"beta", OptionValue::of_number(10)}},
      Part::Indenter);
  EXPECT_EQ(cone.c.indenter.profile, mdrmap::Profile::of<mdrmap::Cone>());
  EXPECT_EQ(cone.c.indenter.as<mdrmap::Cone>().beta, 10.0);
  const auto m = read_case_part({{"G", OptionValue::of_number(1)},
                                 {"tau", OptionValue::of_number(0)},
                                 {"prony", OptionValue::of_pairs({{1, 0.1}})}},
                                Part::Material);
  EXPECT_EQ(m.c.rheology.branches.size(), 1U);
  const auto h =
      read_case_part({{"history", OptionValue::of_pairs({{1, 2}, {0, 3}})}}, Part::History);
  EXPECT_EQ(h.c.history.segments.size(), 2U);
  // the refusals of the whole case, option and message
  OptionValues whole = base_values();
  whole["v1"] = OptionValue::of_number(0.5);
  whole["beta"] = OptionValue::of_number(3);
  EXPECT_EQ(part_refusal({{"R", OptionValue::of_number(10)}, {"beta", OptionValue::of_number(3)}},
                         Part::Indenter),
            refusal(whole));
  whole.erase("beta");
  whole["G"] = OptionValue::of_number(-1);
  EXPECT_EQ(part_refusal({{"G", OptionValue::of_number(-1)}, {"tau", OptionValue::of_number(1)}},
                         Part::Material),
            refusal(whole));
  EXPECT_EQ(part_refusal({{"G", OptionValue::of_number(1)}}, Part::Material).first, "tau");
  EXPECT_EQ(part_refusal({{"d", OptionValue::of_number(1)}}, Part::Indenter).first, "d");
  EXPECT_EQ(part_refusal({}, Part::History).first, "history");
}

} // namespace
