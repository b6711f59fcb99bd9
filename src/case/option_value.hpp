#pragma once
// The value of one option of a case as its caller gives it: the text the
// command line takes, or (from the Python module, src/python) the value
// itself: a number, a list of pairs (history W:T, prony G:TAU), a list of
// numbers (wlf C1, C2, TREF; stationary's v-list), a flag. A number given as
// a number reaches the case as that double, never through a text; the
// checks and messages are those of the text's number (case/case_input.hpp).
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mdrmap::cases {

struct OptionValue {
  enum class Kind { Text, Number, Pairs, Numbers, Flag };
  Kind kind = Kind::Text;
  std::string text;                             ///< Kind::Text
  double number = 0.0;                          ///< Kind::Number
  std::vector<std::pair<double, double>> pairs; ///< Kind::Pairs
  std::vector<double> numbers;                  ///< Kind::Numbers
  bool flag = false;                            ///< Kind::Flag

  static OptionValue of_text(std::string t) {
    OptionValue v;
    v.text = std::move(t);
    return v;
  }
  static OptionValue of_number(double x) {
    OptionValue v;
    v.kind = Kind::Number;
    v.number = x;
    return v;
  }
  static OptionValue of_pairs(std::vector<std::pair<double, double>> p) {
    OptionValue v;
    v.kind = Kind::Pairs;
    v.pairs = std::move(p);
    return v;
  }
  static OptionValue of_numbers(std::vector<double> x) {
    OptionValue v;
    v.kind = Kind::Numbers;
    v.numbers = std::move(x);
    return v;
  }
  static OptionValue of_flag(bool f) {
    OptionValue v;
    v.kind = Kind::Flag;
    v.flag = f;
    return v;
  }
  bool is_text() const { return kind == Kind::Text; }
};

/// Option name (as the CLI spells it, without dashes) -> its value.
using OptionValues = std::map<std::string, OptionValue>;

/// Every value a text (what the command line gives).
inline OptionValues as_values(const std::map<std::string, std::string>& texts) {
  OptionValues out;
  for (const auto& [name, text] : texts)
    out.emplace(name, OptionValue::of_text(text));
  return out;
}

/// The text the command line would give for v: a number as the shortest
/// text that reads back to it, pairs as A:B,C:D, numbers as A:B:C, a flag
/// as true or false (mdrmap fit's problem takes a case as texts).
std::string text_of(const OptionValue& v);
std::map<std::string, std::string> as_texts(const OptionValues& values);

/// The shortest text that reads back to x (a number given as a number, as a
/// message quotes it: 0.1, not 0.10000000000000001).
std::string shortest(double x);

} // namespace mdrmap::cases
