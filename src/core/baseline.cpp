#include "core/baseline.hpp"
#include <stdexcept>
namespace mdrmap {
RunResult run_baseline(const Scene&, const Protocol&, const BaselineOptions&) {
  throw std::logic_error("baseline solver: work in progress");
}
} // namespace mdrmap
