#include "study/config_detail.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace mdrmap::study::detail {

Num to_number(const std::string& s) {
  if (s.empty()) return {0.0, NumError::Empty};
  if (is_space(s.front())) return {0.0, NumError::NotNumber};
  const char* begin = s.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  const int err = errno;
  if (end == begin || end != begin + s.size()) return {0.0, NumError::NotNumber};
  if (std::isnan(x)) return {0.0, NumError::NotFinite};
  if (std::isinf(x)) return {0.0, err == ERANGE ? NumError::TooLarge : NumError::NotFinite};
  return {x == 0.0 ? 0.0 : x, NumError::None}; // -0 is 0
}

std::string number_problem(const std::string& text, NumError e) {
  switch (e) {
  case NumError::Empty:
    return "the value is empty";
  case NumError::NotNumber:
    return shown(text) + " is not a number";
  case NumError::NotFinite:
    return shown(text) + " is not a finite number";
  case NumError::TooLarge:
    return shown(text) + " is too large for a double";
  case NumError::None:
    break;
  }
  return "";
}

bool to_integer(const std::string& s, long long& out) {
  std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  if (i >= s.size()) return false;
  const bool negative = s[0] == '-';
  long long v = 0;
  for (; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    if (v < 100'000'000'000'000'000LL) v = v * 10 + (s[i] - '0');
  }
  out = negative ? -v : v;
  return true;
}

} // namespace mdrmap::study::detail
