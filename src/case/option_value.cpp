#include "case/option_value.hpp"

#include <charconv>
#include <system_error>

namespace mdrmap::cases {

std::string shortest(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  if (r.ec != std::errc()) return "?";
  return std::string(buf, r.ptr);
}

std::string text_of(const OptionValue& v) {
  std::string s;
  switch (v.kind) {
  case OptionValue::Kind::Text:
    return v.text;
  case OptionValue::Kind::Number:
    return shortest(v.number);
  case OptionValue::Kind::Flag:
    return v.flag ? "true" : "false";
  case OptionValue::Kind::Pairs:
    for (const auto& [a, b] : v.pairs)
      s += (s.empty() ? "" : ",") + shortest(a) + ":" + shortest(b);
    return s;
  case OptionValue::Kind::Numbers:
    for (const double x : v.numbers)
      s += (s.empty() ? "" : ":") + shortest(x);
    return s;
  }
  return s;
}

std::map<std::string, std::string> as_texts(const OptionValues& values) {
  std::map<std::string, std::string> out;
  for (const auto& [name, value] : values)
    out.emplace(name, text_of(value));
  return out;
}

} // namespace mdrmap::cases
