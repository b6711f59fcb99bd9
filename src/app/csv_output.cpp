#include "app/csv_output.hpp"

#include <cstdio>

namespace mdrmap::app {

std::string format_double(double x) {
  char buf[64];
  const int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  return std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0U);
}

void write_simulate_csv(std::FILE* out, const SimulateRecord& rec, const Series& series) {
  const RunInfo& in = rec.info;
  std::fprintf(out,
               "# mdrmap %s (%s) simulate solver=%s rtol=%.17g error_estimate=%.17g "
               "cells_per_a1=%.17g elements=%ld steps=%ld element_updates=%ld root_solves=%ld "
               "wall_seconds=%.17g\n",
               rec.version.c_str(), rec.commit.c_str(), rec.solver.c_str(), rec.rtol,
               in.error_estimate, in.cells_per_a1, in.elements, in.steps, in.element_updates,
               in.root_solves, rec.wall_seconds);

  const Scene& s = rec.scene;
  std::fprintf(out,
               "# scene d=%.17g R=%.17g tau=%.17g v=%.17g v1=%.17g G=%.17g t_end=%.17g "
               "samples=%ld zeta=%.17g zeta1=%.17g\n",
               s.d, s.R, s.tau, s.v, s.v1, s.G, rec.protocol.t_end, rec.protocol.samples, zeta(s),
               zeta1(s));

  if (rec.error_vs_exact) std::fprintf(out, "# error_vs_exact=%.17g\n", *rec.error_vs_exact);

  const State& pre = series.pre;
  std::fprintf(out, "# pre FN=%.17g Fx=%.17g mu=%.17g a2=%.17g\n", pre.FN, pre.Fx, pre.mu, pre.a2);

  std::fprintf(out, "%s\n", kCsvHeader);
  for (std::size_t k = 0; k < series.size(); ++k)
    std::fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g\n", series.t[k], series.FN[k], series.Fx[k],
                 series.mu[k], series.a2[k]);
}

} // namespace mdrmap::app
