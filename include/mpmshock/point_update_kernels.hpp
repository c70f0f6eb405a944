// The point update's kernel for a run's laws. Its instantiations are compiled per equation of
// state, each in its law's file (src/laws/<law>.cpp; bodies of mixed laws in
// src/point_update_mixed.cpp), so the kernels of each compile apart, in parallel with the
// transfers (simulation.cpp).
#pragma once

#include "mpmshock/constitutive.hpp"

namespace mpmshock {

template <int D>
using UpdatePointsKernel = StressUpdateResult (*)(Particles<D>&, PointRange, const Model&, double dt,
                                                  const double* volume_rate);

// The kernel for equation of state Eos and the model's strength, viscosity and failure laws.
template <int D, class Eos>
UpdatePointsKernel<D> update_points_kernel(const Model& m);

}  // namespace mpmshock
