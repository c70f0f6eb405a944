#include "mpmshock/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>


namespace mpmshock {

template <int D>
Totals compute_totals(const Particles<D>& p) {
  // Fixed blocks summed in parallel, then the block sums in order: the same bits on any thread count.
  constexpr std::size_t kBlock = 4096;
  const std::size_t n = p.size();
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<Totals> partial(blocks);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t b = 0; b < blocks; ++b) {
    Totals t;
    const std::size_t end = std::min(n, (b + 1) * kBlock);
    for (std::size_t q = b * kBlock; q < end; ++q) {
      const double m = p.m[q];
      const Vec<D>& v = p.v[q];
      t.mass += m;
      for (int d = 0; d < D; ++d) t.momentum[d] += m * v[d];
      t.momentum_magnitude += m * speed(v);
      t.kinetic += 0.5 * m * dot(v, v);
      t.internal += m * p.E[q];
    }
    partial[b] = t;
  }
  Totals sum;
  for (const Totals& t : partial) {
    sum.mass += t.mass;
    for (int d = 0; d < 3; ++d) sum.momentum[d] += t.momentum[d];
    sum.momentum_magnitude += t.momentum_magnitude;
    sum.kinetic += t.kinetic;
    sum.internal += t.internal;
  }
  return sum;
}

template Totals compute_totals<2>(const Particles<2>&);
template Totals compute_totals<3>(const Particles<3>&);

}  // namespace mpmshock
