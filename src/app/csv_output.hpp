#pragma once
// Text output of `mdrmap simulate`: provenance comment lines, then CSV.
//
//   # mdrmap <version> (<commit>) simulate solver=... rtol=... error_estimate=...
//     cells_per_a1=... elements=... steps=... element_updates=... root_solves=...
//     wall_seconds=...                                        (one line)
//   # scene d=... R=... tau=... v=... v1=... G=... t_end=... samples=... zeta=... zeta1=...
//   # error_vs_exact=...                  (only when the solver is not the exact one)
//   # pre FN=... Fx=... mu=... a2=...     (always the last comment line)
//   t,FN,Fx,mu,a2
//   <samples rows>
//
// Every floating-point number is printed with 17 significant digits, which
// reads back to the same double.
#include <cstdio>
#include <optional>
#include <string>

#include "core/scene.hpp"
#include "core/solver.hpp"

namespace mdrmap::app {

/// `%.17g`: round-trips every finite double.
std::string format_double(double x);

/// Everything the comment lines report besides the series itself.
struct SimulateRecord {
  std::string version;                  ///< program version (kVersion)
  std::string commit;                   ///< git commit (kGitCommit)
  std::string solver;                   ///< name of the solver that ran
  double rtol = 0.0;                    ///< requested tolerance
  RunInfo info;                         ///< cost and error estimate of the run
  double wall_seconds = 0.0;            ///< wall time of the run
  Scene scene;                          ///< the scene as run
  Protocol protocol;                    ///< the sampling as run (t_end resolved)
  std::optional<double> error_vs_exact; ///< case error against the continuum solver
};

/// The CSV column header line (without newline).
inline constexpr const char* kCsvHeader = "t,FN,Fx,mu,a2";

/// Writes the comment lines, the header and one row per sample to `out`.
/// Does not flush or check for I/O errors; the caller does (ferror / fclose).
void write_simulate_csv(std::FILE* out, const SimulateRecord& rec, const Series& series);

} // namespace mdrmap::app
