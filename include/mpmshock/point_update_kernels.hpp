// The point update's kernel for a run's laws. Its instantiations are compiled per equation of
// state, each in a translation unit of its own (src/point_update_<law>.cpp): a new equation of
// state adds one such file and one alternative of EquationOfState (model.hpp), and the kernels of
// each compile apart, in parallel with the transfers (simulation.cpp).
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
