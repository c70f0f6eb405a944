// The artificial heat flux's scatter, carried by P2G's own sweep over each point's stencil (the
// physics is in artificial_heat_flux.hpp), so that the flux takes no scatter sweep of its own: a
// sweep loads the point's stencil, weighs by its columns and works out each row's nodes and how it
// wraps; the flux's own scatter cost 100 instructions per point-step in 2D, riding on P2G 34
// (issue 32).
//
//   P2G:  C_i r_i += N_ip C_p r_p,  C_i T_i += N_ip C_p T_p  (several materials: C_i += N_ip C_p)
//
// The flux fills the point values before P2G (before_to_grid) and normalises and gathers after it
// (after_to_grid); P2G only adds, in the same order and with the same products as the flux's own
// sweep did (where that skipped a point, a point of rate 0 or in a bad state, P2G adds +0, which
// changes no sum that starts at +0), so the sums are the same numbers (the same bits built with
// -ffp-contract=off; with contraction, as the compiler fuses the new loop). The gather rides on
// nothing: in G2P's sweep or the velocity gradient's it saved little or nothing (the extra
// fields' row offsets spill from the registers: 2D, 1,212 instructions per point-step with its own
// sweep, 1,216 riding on G2P, 1,198 on the gradient pass, which would also move its heat after the
// FLIP/PIC blend's; measured 2026-12-07 before G2P began to sum v^{n+1} for the move and the
// gradient pass stopped, which changes both sweeps: not measured since).
#pragma once

#include <cstddef>
#include <vector>

#include "mpmshock/lanes.hpp"

namespace mpmshock {

struct HeatFluxRider {
  // By point, what P2G scatters; zero for a point in a bad state, which gives its nodes nothing so
  // that the step reports it and not its neighbours.
  const double* rate = nullptr;      // C_p r_p
  const double* heat = nullptr;      // C_p T_p
  const double* capacity = nullptr;  // C_p (several materials only)
  // The nodal sums C_i r_i, C_i T_i and C_i, as vectors for the MPI halo's sums of shared rows.
  std::vector<double>* node_rate = nullptr;
  std::vector<double>* node_temperature = nullptr;
  std::vector<double>* node_capacity = nullptr;
};

// What P2G is compiled to carry: no flux, its two nodal sums (one material: C_i = m_i), or three
// (several materials: C_i summed too).
enum class FluxSums { none = 0, two = 2, three = 3 };

// A point's scatter values weighed by its stencil's columns (node_rows.hpp), once per point.
template <FluxSums Sums>
struct FluxColumns {
  Lanes rate{}, heat{}, capacity{};
  FluxColumns() = default;
  [[gnu::always_inline]] FluxColumns(const HeatFluxRider& f, std::size_t p, const Lanes& column_weight) {
    rate = column_weight * f.rate[p];
    heat = column_weight * f.heat[p];
    if constexpr (Sums == FluxSums::three) capacity = column_weight * f.capacity[p];
  }
  // Adds them to one row of the nodal sums with the row's weight.
  template <class Nodes, class Factor>
  [[gnu::always_inline]] void add_to_row(const HeatFluxRider& f, std::size_t row, const Factor& weight,
                                         const Nodes& nodes) const {
    add(*f.node_rate, rate, row, weight, nodes);
    add(*f.node_temperature, heat, row, weight, nodes);
    if constexpr (Sums == FluxSums::three) add(*f.node_capacity, capacity, row, weight, nodes);
  }

 private:
  template <class Nodes, class Factor>
  [[gnu::always_inline]] static void add(std::vector<double>& field, const Lanes& columns, std::size_t row,
                                         const Factor& weight, const Nodes& nodes) {
    Lanes sum;
    nodes.load(sum, &field[row]);
    sum += weight * columns;
    nodes.store(&field[row], sum);
  }
};

}  // namespace mpmshock
