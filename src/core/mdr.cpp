#include "core/mdr.hpp"
#include <stdexcept>
namespace mdrmap {
RunResult run_mdr(const Scene&, const Protocol&, const MdrOptions&) {
  throw std::logic_error("mdr solver: work in progress");
}
} // namespace mdrmap
