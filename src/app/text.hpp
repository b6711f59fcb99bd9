#pragma once
// Small text helpers of the command-line readers.
#include <string>

namespace mdrmap::app {

/// `s` without leading and trailing blanks and tabs.
inline std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

} // namespace mdrmap::app
