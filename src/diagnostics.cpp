#include "mpmshock/diagnostics.hpp"

#include <cmath>
#include <vector>

namespace mpmshock {

Totals compute_totals(const Particles& p) {
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
      const double m = p.mass[q], vx = p.vx[q], vy = p.vy[q];
      t.mass += m;
      t.momentum_x += m * vx;
      t.momentum_y += m * vy;
      t.momentum_magnitude += m * std::hypot(vx, vy);
      t.kinetic += 0.5 * m * (vx * vx + vy * vy);
      t.internal += m * p.energy[q];
    }
    partial[b] = t;
  }
  Totals sum;
  for (const Totals& t : partial) {
    sum.mass += t.mass;
    sum.momentum_x += t.momentum_x;
    sum.momentum_y += t.momentum_y;
    sum.momentum_magnitude += t.momentum_magnitude;
    sum.kinetic += t.kinetic;
    sum.internal += t.internal;
  }
  return sum;
}

}  // namespace mpmshock
