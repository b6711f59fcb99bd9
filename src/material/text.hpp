#pragma once
// Small text helpers of the input readers (the material files here, the
// command line's in src/app): what a message quotes, a field trimmed.
#include <string>

namespace mdrmap::material {

/// `s` without leading and trailing blanks and tabs.
inline std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

/// The value as typed, quoted only when it would otherwise be unreadable;
/// more than 60 characters are cut, with the length said.
std::string shown(const std::string& text);

} // namespace mdrmap::material
