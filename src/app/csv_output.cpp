#include "app/csv_output.hpp"

#include <cmath>
#include <cstdio>

#include "core/params.hpp"

namespace mdrmap::app {
namespace {

const char* spacing_name(Spacing s) {
  return s == Spacing::Log ? "log" : "linear";
}

/// " name=value" for every table parameter of the sampling part (`sampling`)
/// or of the other parts.
std::string parameters(const Case& c, bool sampling) {
  std::string s;
  for (const auto& p : case_parameters())
    if ((p.part == Part::Sampling) == sampling)
      s += std::string(" ") + p.name + "=" + format_double(p.get(c));
  return s;
}

void write_event(std::FILE* out, std::size_t k, const EventMetrics& e) {
  const std::pair<const char*, double> f[] = {
      {"t", e.t},
      {"w_before", e.w_before},
      {"w_after", e.w_after},
      {"mu_before", e.mu_before},
      {"mu_after", e.mu_after},
      {"mu_peak", e.mu_peak},
      {"t_peak", e.t_peak},
      {"slip_peak", e.slip_peak},
      {"mu_end", e.end.mu},
      {"mu_ss_before", e.ss_before.mu},
      {"mu_ss_after", e.ss_after.mu},
      {"D_c", e.d_c},
      {"a", e.a},
      {"a_minus_b", e.a_minus_b},
      {"b", e.b},
  };
  std::string line = "# event k=" + std::to_string(k);
  for (const auto& [name, value] : f)
    line += std::string(" ") + name + "=" + format_double(value);
  std::fprintf(out, "%s\n", line.c_str());
}

} // namespace

std::string format_double(double x) {
  if (std::isnan(x)) return "nan";
  char buf[64];
  const int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  return std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0U);
}

std::string format_history(const History& h) {
  std::string s;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (k > 0) s += ',';
    s += format_double(h.segments[k].w) + ":" + format_double(h.segments[k].T);
  }
  return s;
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

  const Case& c = rec.c;
  const std::string case_line =
      "# case" + parameters(c, false) + " history=" + format_history(c.history) +
      " spacing=" + spacing_name(c.sampling.spacing) + parameters(c, true) +
      " zeta0=" + format_double(zeta(c, c.history.v0));
  std::fprintf(out, "%s\n", case_line.c_str());

  if (rec.error_vs_exact) std::fprintf(out, "# error_vs_exact=%.17g\n", *rec.error_vs_exact);

  for (std::size_t k = 0; k < rec.events.size(); ++k)
    write_event(out, k, rec.events[k]);

  const State& pre = series.pre;
  std::fprintf(out, "# pre FN=%.17g Fx=%.17g mu=%.17g a2=%.17g\n", pre.FN, pre.Fx, pre.mu, pre.a2);

  std::fprintf(out, "%s\n", kCsvHeader);
  for (std::size_t k = 0; k < series.size(); ++k)
    std::fprintf(out, "%.17g,%d,%.17g,%.17g,%.17g,%.17g\n", series.t[k], series.segment[k],
                 series.FN[k], series.Fx[k], series.mu[k], series.a2[k]);
}

} // namespace mdrmap::app
