#pragma once
// What the two runs of the spectrum solver share (internal): the fixed-depth
// run (spectrum.cpp) and the load-controlled run (spectrum_load_run.cpp),
// whose entry run_spectrum dispatches to.
#include <deque>
#include <utility>

#include "core/model/case.hpp"
#include "core/model/state.hpp"
#include "core/numerics/run_control.hpp"
#include "core/solvers/refine.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/spectrum_law.hpp"

namespace mdrmap::spectrum::detail {

/// The trailing edge is located to kEdgeTol rtol a1. Where the pressure jumps
/// there (a re-touch front) the forces err by about that times the jump
/// relative to the mean pressure, up to kEdgeFloor / kEdgeTol = 4 times it
/// (the cone's Kelvin drops: 3): both runs of the estimate share it, so it is
/// added to the estimate.
inline constexpr double kEdgeTol = 1e-3, kEdgeFloor = 4e-3;

inline constexpr const char* kName = "row";
inline constexpr double kMaxCells = 2e5; // window memory: 4e5 elements of up to 33 doubles

/// The stationary states the watches compare with (stationary_watch.hpp),
/// each formed once per velocity for every run of a case, and only when a
/// check first needs it: a cone's or a power law's with a spectrum is a
/// quadrature (75 ms with 11 terms), which per segment and run made a cone's
/// velocity steps twice as dear.
class StationaryStates {
public:
  explicit StationaryStates(const Case& c) : c_(c) {}
  const State& at(double w);

private:
  const Case& c_;
  std::deque<std::pair<double, State>> known_; // (references stay valid)
};

/// The load-controlled run at resolution `cells` (spectrum_load_run.cpp,
/// "load control"); the fixed-depth run's counterpart (spectrum.cpp, run_once).
ResolutionRun run_once_load(const Case& c, const spectrum::Law& law, double cells, double phase,
                            double fine, const SpectrumOptions& o, const RunControl& control,
                            StationaryStates& states);

} // namespace mdrmap::spectrum::detail
