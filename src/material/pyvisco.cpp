#include "material/pyvisco.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "core/model/case.hpp"
#include "core/model/params.hpp"
#include "material/text.hpp"

namespace mdrmap::material {
namespace {

const std::string kOption = "material";

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string item;
  while (std::getline(in, item, ','))
    out.push_back(trimmed(item));
  return out;
}

/// The columns pyvisco's CSV is read by.
struct Columns {
  std::size_t tau = 0, alpha = 0, modulus = 0; ///< indices; modulus: E_0 or G_0
  bool young = false;                          ///< E_0
};

Columns columns(const std::string& path, const std::vector<std::string>& header) {
  Columns c;
  bool tau = false, alpha = false, modulus = false;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "tau_i") c.tau = i, tau = true;
    if (header[i] == "alpha_i") c.alpha = i, alpha = true;
    if (header[i] == "E_0" || header[i] == "G_0")
      c.modulus = i, modulus = true, c.young = header[i] == "E_0";
  }
  if (!tau || !alpha || !modulus)
    throw InvalidInput(kOption, path + ":1: a pyvisco Prony CSV names the columns tau_i, alpha_i "
                                       "and E_0 (or G_0), the instantaneous modulus");
  return c;
}

double number(const std::string& at, const std::string& name, const std::string& text) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(x))
    throw InvalidInput(kOption,
                       at + "column " + name + " must be a finite number, got " + shown(text));
  return x;
}

} // namespace

bool is_pyvisco_csv(const std::string& text) {
  const std::string first = text.substr(0, text.find('\n'));
  return first.find("tau_i") != std::string::npos && first.find("alpha_i") != std::string::npos;
}

MaterialCard read_pyvisco(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  const Columns c = columns(path, cells(line));
  MaterialCard m;
  double G0 = 0.0, sum = 0.0;
  for (std::size_t n = 2; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string> v = cells(line);
    if (trimmed(line).empty() ||
        (n == 2 && v.size() > c.tau && std::strtod(v[c.tau].c_str(), nullptr) == 0.0))
      continue; // a blank line, or the row of units
    const std::string at = path + ":" + std::to_string(n) + ": ";
    if (v.size() <= std::max(c.tau, std::max(c.alpha, c.modulus)))
      throw InvalidInput(kOption, at + "the row has " + std::to_string(v.size()) +
                                      " values, fewer than the header's columns");
    const double tau = number(at, "tau_i", v[c.tau]), alpha = number(at, "alpha_i", v[c.alpha]);
    const double E0 = number(at, c.young ? "E_0" : "G_0", v[c.modulus]);
    if (!(E0 > 0.0)) throw InvalidInput(kOption, at + "the instantaneous modulus must be > 0");
    G0 = c.young ? E0 / 3.0 : E0; // nu = 0.5: G = E / (4 (1 - nu^2)) = E / 3
    if (alpha < 0.0 || alpha >= 1.0)
      throw InvalidInput(kOption, at + "alpha_i must be >= 0 and < 1, got " + format_number(alpha));
    if (!branch_time_spec().contains(tau))
      throw InvalidInput(kOption, at + "tau_i must be " + branch_time_spec().allowed());
    if (alpha == 0.0) continue; // a term the fit dropped
    if (m.branches.size() == kMaxBranches)
      throw InvalidInput(kOption,
                         at + "more than " + std::to_string(kMaxBranches) + " nonzero terms");
    m.branches.push_back(Branch{alpha, tau});
    sum += alpha;
  }
  if (m.branches.empty()) throw InvalidInput(kOption, path + ": no Prony terms with alpha_i > 0");
  if (!(sum < 1.0))
    throw InvalidInput(kOption, path + ": the alpha_i sum to " + format_number(sum) +
                                    "; the sum must be < 1 (G = G0 (1 - sum alpha_i) > 0)");
  for (Branch& b : m.branches)
    b.G *= G0;
  m.G = G0 * (1.0 - sum);
  return m;
}

} // namespace mdrmap::material
