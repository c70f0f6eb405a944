#include "mpmshock/diagnostics.hpp"

#include <algorithm>
#include <cmath>

#include "mpmshock/lanes.hpp"

namespace mpmshock {

template <int D>
Totals compute_totals(const Particles<D>& p, const Comm& comm) {
  enum { kMass, kMomentum, kMagnitude = kMomentum + 3, kKinetic, kInternal, kSums };
  ExactSum sums[kSums];
  const auto n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel
  {
    ExactSum mine[kSums];
    // Four points' terms at a time (ExactSum::add_lanes: the words of four add() calls).
    const std::ptrdiff_t groups = (n + 3) / 4;
#pragma omp for schedule(static) nowait
    for (std::ptrdiff_t g = 0; g < groups; ++g) {
      const int count = static_cast<int>(std::min<std::ptrdiff_t>(4, n - 4 * g));
      Lanes terms[kSums] = {};
      for (int l = 0; l < count; ++l) {
        const std::ptrdiff_t q = 4 * g + l;
        const double m = p.m[q];
        const Vec<D>& v = p.v[q];
        terms[kMass][l] = m;
        for (int d = 0; d < D; ++d) terms[kMomentum + d][l] = m * v[d];
        terms[kMagnitude][l] = m * speed(v);
        terms[kKinetic][l] = 0.5 * m * dot(v, v);
        terms[kInternal][l] = m * p.E[q];
      }
      for (int k = 0; k < kSums; ++k) mine[k].add_lanes(terms[k], count);  // zeros add nothing
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
