#include "mpmshock/diagnostics.hpp"

#include <cmath>

namespace mpmshock {

template <int D>
Totals compute_totals(const Particles<D>& p, const Comm& comm) {
  enum { kMass, kMomentum, kMagnitude = kMomentum + 3, kKinetic, kInternal, kSums };
  ExactSum sums[kSums];
  const auto n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel
  {
    ExactSum mine[kSums];
#pragma omp for schedule(static) nowait
    for (std::ptrdiff_t q = 0; q < n; ++q) {
      const double m = p.m[q];
      const Vec<D>& v = p.v[q];
      mine[kMass].add(m);
      for (int d = 0; d < D; ++d) mine[kMomentum + d].add(m * v[d]);
      mine[kMagnitude].add(m * speed(v));
      mine[kKinetic].add(0.5 * m * dot(v, v));
      mine[kInternal].add(m * p.E[q]);
    }
#pragma omp critical(mpmshock_totals)
    for (int k = 0; k < kSums; ++k) sums[k] += mine[k];
  }
  comm.sum(sums, kSums);
  Totals t;
  t.mass = sums[kMass].value();
  for (int d = 0; d < 3; ++d) t.momentum[d] = sums[kMomentum + d].value();
  t.momentum_magnitude = sums[kMagnitude].value();
  t.kinetic = sums[kKinetic].value();
  t.internal = sums[kInternal].value();
  return t;
}

template Totals compute_totals<2>(const Particles<2>&, const Comm&);
template Totals compute_totals<3>(const Particles<3>&, const Comm&);

}  // namespace mpmshock
