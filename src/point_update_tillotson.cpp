// The point-update kernels of Tillotson (tillotson.hpp), for every strength, viscosity and failure law.
#include "point_update_kernels.inl"

namespace mpmshock {

template UpdatePointsKernel<2> update_points_kernel<2, Tillotson>(const Model&);
template UpdatePointsKernel<3> update_points_kernel<3, Tillotson>(const Model&);

}  // namespace mpmshock
