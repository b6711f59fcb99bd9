// mdrmap_bench_kelvin_load: the Kelvin load solver (run_load, kelvin_load)
// against the element row (run_spectrum, row) at N = 0 under load, side by
// side, on the Kelvin-under-load histories of load_case_set(): whether the
// load solver still earns its place (it stays while the row takes more than
// 1.5 times its CPU time; docs/design/load.md).
//
//   mdrmap_bench_kelvin_load [--reps N] [--rtol E]
//
// For each case, N rounds (default 5) of one call of each solver, alternating
// (the order swapped every round); the per-case median CPU time (std::clock)
// of each, their ratio row/kelvin_load, and over the cases the median ratio
// and the ratio of the summed medians. A case either solver abandons is
// listed and left out of the ratios.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "cases/load_case_set.hpp"
#include "core/solvers/load.hpp"
#include "core/solvers/spectrum.hpp"
#include "stats.hpp"

namespace {

/// CPU seconds of one call, or a negative value when it throws.
double cpu_seconds(const std::function<void()>& call) {
  const std::clock_t t0 = std::clock();
  try {
    call();
  } catch (const std::exception&) {
    return -1.0;
  }
  return static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
}

struct Times {
  std::vector<double> load, row;
};

Times time_case(const mdrmap::Case& c, double rtol, int reps) {
  mdrmap::LoadOptions lo;
  lo.rtol = rtol;
  mdrmap::SpectrumOptions so;
  so.rtol = rtol;
  const auto load = [&] { mdrmap::run_load(mdrmap::CheckedCase(c), lo); };
  const auto row = [&] { mdrmap::run_spectrum(mdrmap::CheckedCase(c), so); };
  Times t;
  for (int r = 0; r < reps; ++r) {
    if (r % 2 == 0) {
      t.load.push_back(cpu_seconds(load));
      t.row.push_back(cpu_seconds(row));
    } else {
      t.row.push_back(cpu_seconds(row));
      t.load.push_back(cpu_seconds(load));
    }
  }
  return t;
}

bool failed(const std::vector<double>& x) {
  for (const double v : x)
    if (v < 0.0) return true;
  return false;
}

} // namespace

int main(int argc, char** argv) {
  int reps = 5;
  double rtol = 1e-4;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--reps") == 0)
      reps = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--rtol") == 0)
      rtol = std::atof(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: mdrmap_bench_kelvin_load [--reps N] [--rtol E]\n");
      return 2;
    }
  }
  if (reps < 1 || !(rtol > 0.0)) {
    std::fprintf(stderr, "--reps must be >= 1 and --rtol > 0\n");
    return 2;
  }
  std::vector<double> ratios;
  double sum_load = 0.0, sum_row = 0.0;
  std::printf("rtol %g, %d alternating rounds, CPU ms (medians)\n", rtol, reps);
  std::printf("%-44s %12s %12s %8s\n", "case", "kelvin_load", "row", "ratio");
  for (const auto& nc : mdrmap::load_case_set()) {
    if (!nc.c.rheology.kelvin()) continue;
    const Times t = time_case(nc.c, rtol, reps);
    if (failed(t.load) || failed(t.row)) {
      std::printf("%-44s %12s %12s %8s\n", nc.name.c_str(), failed(t.load) ? "abandoned" : "ok",
                  failed(t.row) ? "abandoned" : "ok", "-");
      continue;
    }
    const double l = mdrmap::bench::median(t.load), r = mdrmap::bench::median(t.row);
    sum_load += l;
    sum_row += r;
    ratios.push_back(r / l);
    std::printf("%-44s %12.3f %12.3f %8.2f\n", nc.name.c_str(), 1e3 * l, 1e3 * r, r / l);
  }
  std::printf(
      "cases %zu: median ratio row/kelvin_load %.2f, ratio of the sums %.2f (%.1f / %.1f ms)\n",
      ratios.size(), mdrmap::bench::median(ratios), sum_row / sum_load, 1e3 * sum_row,
      1e3 * sum_load);
  return 0;
}
