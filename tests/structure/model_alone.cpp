// The model, the core's lowest floor, alone: this program links the objects
// of core/model and no other library of mdrmap (tests/CMakeLists.txt), so a
// model file that calls into the floors above it (metrics, solvers, outputs)
// fails to link it. Run, it checks the seed's case with the model's own
// checks (validate_parts) and that they refuse a depth out of range naming d.
#include <cstdio>

#include "core/model/case.hpp"

int main() {
  const mdrmap::Case seed = mdrmap::step_case(0.1, 10.0, 1.0, 1.0, 0.1);
  try {
    mdrmap::validate_parts(seed);
  } catch (const mdrmap::InvalidInput& e) {
    std::printf("model_alone: the seed's case refused: --%s: %s\n", e.option().c_str(), e.what());
    return 1;
  }
  mdrmap::Case bad = seed;
  bad.loading.d = -1.0;
  try {
    mdrmap::validate_parts(bad);
  } catch (const mdrmap::InvalidInput& e) {
    if (e.option() == "d") return 0;
    std::printf("model_alone: d = -1 refused naming --%s\n", e.option().c_str());
    return 1;
  }
  std::printf("model_alone: d = -1 accepted\n");
  return 1;
}
