// mdrmap_spectrum_physics: what a relaxation spectrum does to MDR friction,
// measured (issue 19 item 7; docs/design.md, "Materials with a relaxation
// spectrum"). Prints one table per study and writes its CSV files into --out
// DIR; tools/plot_spectrum_physics.py makes the figures of docs/physics.md.
//
//   mdrmap_spectrum_physics --out DIR [--pib FILE] [--part 1..7] [--rtol R]
//                           [--healing-run 1..9] [--load-material 1..3]
//
// One file per study (studies.hpp): 1 sls.cpp, 2 width.cpp, 3 healing.cpp,
// 4 direct.cpp, 5 creep.cpp, 6 healing_load.cpp, 7 profiles.cpp; shared: common.* (options,
// spectra, cases, CSV), peak.* (curve maxima), shs.* (slide-hold-slide runs).
// Units (common.hpp): R = 1, G = 1, d = 1 at fixed depth, F0 = 16/3 under load.
// Not a test and not a benchmark: no pass/fail.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <string>

#include "studies.hpp"

using namespace mdrmap::physics;

namespace {

[[noreturn]] void bad(const std::string& option, const std::string& what) {
  std::fprintf(stderr, "mdrmap_spectrum_physics: --%s %s\n", option.c_str(), what.c_str());
  std::exit(2);
}

/// An integer option's value in lo..hi, else one line naming it and exit 2.
int int_in(const std::string& name, const std::string& v, int lo, int hi) {
  const int k = std::atoi(v.c_str());
  if (k < lo || k > hi) bad(name, "must be " + std::to_string(lo) + " to " + std::to_string(hi));
  return k;
}

void set_option(Options& o, const std::string& a, const std::string& v) {
  if (a == "--out")
    o.out = v;
  else if (a == "--pib")
    o.pib = v;
  else if (a == "--part")
    o.part = int_in("part", v, 1, 7);
  else if (a == "--rtol") {
    o.rtol = std::atof(v.c_str());
    if (!(o.rtol > 0.0 && o.rtol <= 0.1)) bad("rtol", "must be in (0, 0.1]");
  } else if (a == "--healing-run")
    o.healing_run = int_in("healing-run", v, 1, 9);
  else if (a == "--load-material")
    o.load_material = int_in("load-material", v, 1, 3);
  else
    bad(a.size() > 2 ? a.substr(2) : a,
        "is not an option (--out, --pib, --part, --rtol, --healing-run, --load-material)");
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::printf("usage: mdrmap_spectrum_physics --out DIR [--pib FILE] [--part 1..7] "
                  "[--rtol R] [--healing-run 1..9] [--load-material 1..3]\n");
      std::exit(0);
    }
    if (i + 1 >= argc) bad(a.size() > 2 ? a.substr(2) : a, "needs a value");
    set_option(o, a, argv[++i]);
  }
  if (o.out.empty()) bad("out", "is required: the directory the CSV files go into");
  return o;
}

} // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  try {
    const std::function<void(const Options&)> studies[] = {
        study_sls,   study_width,        study_healing, study_direct,
        study_creep, study_healing_load, study_profiles};
    for (int k = 1; k <= 7; ++k)
      if (o.part == 0 || o.part == k) {
        studies[k - 1](o);
        std::fflush(stdout);
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mdrmap_spectrum_physics: %s\n", e.what());
    return 1;
  }
  return 0;
}
