// The point-update kernels of bodies with different equations of state (mixed_equation_of_state.hpp),
// for every strength, viscosity and failure law.
#include "point_update_kernels.inl"

namespace mpmshock {

template UpdatePointsKernel<2> update_points_kernel<2, MixedEquationOfState>(const Model&);
template UpdatePointsKernel<3> update_points_kernel<3, MixedEquationOfState>(const Model&);

}  // namespace mpmshock
