#include "core/model/scales.hpp"

namespace mdrmap {

Scales scales(const Case& c) {
  Scales s;
  s.length = c.edge_scale();
  s.depth = c.loading.by_force() ? c.indenter.g(s.length) : c.loading.d;
  s.force = c.loading.by_force() ? c.loading.F0 : c.indenter.elastic_force(s.length, c.rheology.G);
  s.friction = 0.5 * c.indenter.slope(s.length);
  s.time = c.rheology.longest_time();
  return s;
}

} // namespace mdrmap
