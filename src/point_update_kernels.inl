// The definition of update_points_kernel (point_update_kernels.hpp), included only by the
// translation units that instantiate it: each equation of state's file (src/laws/<law>.cpp) and
// src/point_update_mixed.cpp.
#include <type_traits>
#include <variant>

#include "mpmshock/point_update_kernels.hpp"

namespace mpmshock {

template <int D, class Eos>
UpdatePointsKernel<D> update_points_kernel(const Model& m) {
  return std::visit(
      [](const auto& strength, const auto& viscosity, const auto& failure) -> UpdatePointsKernel<D> {
        return update_all_points<D, Eos, std::decay_t<decltype(strength)>, std::decay_t<decltype(viscosity)>,
                                 std::decay_t<decltype(failure)>>;
      },
      m.strength[1], m.viscosity, m.failure);  // every body's laws are of the same types
}

}  // namespace mpmshock
