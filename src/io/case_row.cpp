#include "io/case_row.hpp"

#include <algorithm>
#include <stdexcept>

namespace mdrmap::io {
namespace {

std::vector<std::string> make_fields() {
  std::vector<std::string> f;
  const char* q[] = {"FN", "Fx", "mu", "a2"};
  const char* when[] = {"pre", "jump", "post"};
  for (const char* group : {"results", "analytic", "residuals"}) {
    for (const char* w : when)
      for (const char* x : q)
        f.push_back(std::string(group) + "/" + x + "_" + w);
  }
  f.push_back("results/error_estimate");
  f.push_back("results/wall_seconds");
  for (const char* lim : {"FN_inf", "Fx_inf", "mu_inf", "mu_post_drop"}) {
    f.push_back(std::string("analytic/") + lim);
    f.push_back(std::string("residuals/") + lim);
  }
  return f;
}

} // namespace

const std::vector<std::string>& row_fields() {
  static const std::vector<std::string> f = make_fields();
  return f;
}

std::size_t field_index(const std::string& name) {
  const auto& f = row_fields();
  const auto it = std::find(f.begin(), f.end(), name);
  if (it == f.end()) throw std::out_of_range("no map field " + name);
  return static_cast<std::size_t>(it - f.begin());
}

} // namespace mdrmap::io
