// print_case_set history|load|spectrum SAMPLES: the tests' case sets as JSON lines
// {"name": ..., "kw": {keyword arguments of mdrmap.simulate}} for the Python
// tests, which compare the module with the CLI on them. A test program: the
// case sets are not part of the shipped library or module.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cases/case_set.hpp"
#include "cases/load_case_set.hpp"
#include "cases/spectrum_case_set.hpp"
#include "core/model/params.hpp"

namespace {

using namespace mdrmap;

/// A double as the shortest-round-trip text JSON and Python read back exactly.
std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

/// The table's parameters that are set (of a one_of group the member given;
/// not those at their default), the history as [w, T] pairs, the spectrum as
/// prony [G, tau] pairs where it has terms, and the spacing when logarithmic.
std::string keywords(const Case& c) {
  std::string kw;
  for (const auto& p : case_parameters()) {
    if (!p.applies_to(c.indenter.profile)) continue; // another profile's (0)
    if (p.one_of && p.get(c) == 0.0) continue;
    if (!p.required && !p.one_of && p.get(c) == p.fallback) continue;
    std::string key = p.name;
    for (char& ch : key)
      if (ch == '-') ch = '_';
    const std::string value =
        p.integer() ? std::to_string(static_cast<long long>(p.get(c))) : number(p.get(c));
    kw += "\"" + key + "\": " + value + ", ";
  }
  kw += "\"history\": [";
  for (std::size_t k = 0; k < c.history.size(); ++k)
    kw += (k ? ", [" : "[") + number(c.history.segments[k].w) + ", " +
          number(c.history.segments[k].T) + "]";
  kw += "]";
  if (!c.rheology.branches.empty()) {
    kw += ", \"prony\": [";
    for (std::size_t k = 0; k < c.rheology.branches.size(); ++k)
      kw += (k ? ", [" : "[") + number(c.rheology.branches[k].G) + ", " +
            number(c.rheology.branches[k].tau) + "]";
    kw += "]";
  }
  if (c.sampling.spacing == Spacing::Log) kw += ", \"spacing\": \"log\"";
  return "{" + kw + "}";
}

} // namespace

int main(int argc, char** argv) {
  const std::string which = argc == 3 ? argv[1] : "";
  if (which != "history" && which != "load" && which != "spectrum") {
    std::fprintf(stderr, "usage: print_case_set history|load|spectrum SAMPLES\n");
    return 2;
  }
  const long samples = std::strtol(argv[2], nullptr, 10);
  const auto set = which == "history" ? history_case_set(samples)
                   : which == "load"  ? load_case_set(samples)
                                      : spectrum_case_set(samples);
  for (const auto& nc : set)
    std::printf("{\"name\": \"%s\", \"kw\": %s}\n", nc.name.c_str(), keywords(nc.c).c_str());
  return 0;
}
