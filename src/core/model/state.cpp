#include "core/model/state.hpp"

namespace mdrmap {

void Series::resize(std::size_t n) {
  t.assign(n, 0.0);
  segment.assign(n, 0);
  FN.assign(n, 0.0);
  Fx.assign(n, 0.0);
  mu.assign(n, 0.0);
  a2.assign(n, 0.0);
  d.assign(n, 0.0);
  a1.assign(n, 0.0);
}

void Series::set(std::size_t k, double time, int seg, const State& st) {
  t[k] = time;
  segment[k] = seg;
  FN[k] = st.FN;
  Fx[k] = st.Fx;
  mu[k] = st.mu;
  a2[k] = st.a2;
  d[k] = st.d;
  a1[k] = st.a1;
}

} // namespace mdrmap
