#include "case/prony_input.hpp"
#include "case/text.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "case/case_input.hpp"
#include "core/model/case.hpp"
#include "core/model/params.hpp"

namespace mdrmap::cases {
namespace {

/// One value of term k (1-based): `spec` is the branch's modulus or time;
/// the key in a message is its name with k (G3, tau3). Throws
/// InvalidInput(option) with `where` before the message.
double term_value(const std::string& option, const std::string& where, const ParamSpec& spec,
                  std::size_t k, const std::string& text) {
  const std::string key = spec.name + std::to_string(k);
  const std::string t = trimmed(text);
  if (t.empty())
    throw InvalidInput(option, where + "no " + key +
                                   "; a term has its modulus and its relaxation "
                                   "time, both given");
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(t.c_str(), &end);
  if (*end != '\0') throw InvalidInput(option, where + key + " must be a number, got " + shown(t));
  if (!spec.contains(x))
    throw InvalidInput(option, where + key + " must be " + spec.allowed() + ", got " +
                                   (std::isfinite(x) ? format_number(x) : t));
  return x;
}

/// Term k from its two texts.
Branch term(const std::string& option, const std::string& where, std::size_t k,
            const std::string& G, const std::string& tau) {
  return Branch{term_value(option, where, branch_modulus_spec(), k, G),
                term_value(option, where, branch_time_spec(), k, tau)};
}

[[noreturn]] void too_many(const std::string& option, const std::string& where) {
  throw InvalidInput(option, where + "more than " + std::to_string(kMaxBranches) +
                                 " terms; a spectrum has at most " + std::to_string(kMaxBranches));
}

} // namespace

std::vector<Branch> parse_prony(const std::string& text) {
  const std::string form = "terms G:TAU separated by commas, e.g. 1:0.01,1:1,1:100";
  if (trimmed(text).empty())
    throw InvalidInput("prony", "must be " + form + "; got " + shown(text));
  std::vector<Branch> out;
  std::size_t start = 0;
  for (std::size_t k = 1;; ++k) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? comma : comma - start);
    const std::string quoted = item.size() > 60 ? shown(item) : "'" + item + "'"; // (cut)
    const std::string where = "term " + std::to_string(k) + " " + quoted + ": ";
    if (k > kMaxBranches) too_many("prony", "has ");
    const std::string tok = trimmed(item);
    if (tok.empty())
      throw InvalidInput("prony", "term " + std::to_string(k) + " is empty; give " + form);
    const std::size_t colon = tok.find(':');
    if (colon == std::string::npos || tok.find(':', colon + 1) != std::string::npos)
      throw InvalidInput("prony", where + "not G:TAU (one ':' between the modulus G" +
                                      std::to_string(k) + " and the time tau" + std::to_string(k) +
                                      ")");
    out.push_back(term("prony", where, k, tok.substr(0, colon), tok.substr(colon + 1)));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

std::vector<Branch> prony_of_pairs(const std::vector<std::pair<double, double>>& pairs) {
  if (pairs.empty())
    throw InvalidInput("prony", "must be one or more terms (G, TAU), a modulus then a relaxation "
                                "time; got none");
  if (pairs.size() > kMaxBranches) too_many("prony", "has ");
  std::vector<Branch> out;
  for (std::size_t k = 1; k <= pairs.size(); ++k) {
    const auto [G, tau] = pairs[k - 1];
    const std::string where =
        "term " + std::to_string(k) + " '" + shortest(G) + ":" + shortest(tau) + "': ";
    for (const auto& [spec, x] :
         {std::pair{&branch_modulus_spec(), G}, std::pair{&branch_time_spec(), tau}})
      if (!spec->contains(x))
        throw InvalidInput("prony", where + spec->name + std::to_string(k) + " must be " +
                                        spec->allowed() + ", got " + format_number(x));
    out.push_back(Branch{G, tau});
  }
  return out;
}

std::string format_prony(const std::vector<Branch>& branches) {
  std::string s;
  for (const Branch& b : branches)
    s += (s.empty() ? "" : ",") + format_number(b.G) + ":" + format_number(b.tau);
  return s;
}

} // namespace mdrmap::cases
