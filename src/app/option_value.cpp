#include "app/option_value.hpp"

#include <charconv>
#include <system_error>

namespace mdrmap::app {

std::string shortest(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  if (r.ec != std::errc()) return "?";
  return std::string(buf, r.ptr);
}

} // namespace mdrmap::app
