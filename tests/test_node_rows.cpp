// A stencil row's four nodes in vector lanes (node_rows.hpp): for every way four columns lie in a
// periodic row (one run, or wrapped round the seam after 1, 2 or 3 nodes), every first column and
// every grid width from the narrowest allowed (4 cells) to 9, in 2D and 3D, for_each_row's loads
// give each lane its node's value and its stores write exactly the stencil's nodes, each with its
// own lane, and nothing else; and each row's factors are its y (and z) weights and derivatives,
// in 3D their products in every lane, row by row in for_each_node's order.
#include <cstring>
#include <random>
#include <vector>

#include "check.hpp"
#include "mpmshock/node_rows.hpp"

using namespace mpmshock;

namespace {

template <int D>
GridGeometry<D> grid(int nx, int ny, int nz) {
  GridGeometry<D> g;
  g.nx = nx;
  g.ny = ny;
  g.nz = D == 3 ? nz : 1;
  g.h = 1.0;
  g.inv_h = 1.0;
  return g;
}

// The stencil whose first column is c0 (-1 .. nx - 2, as a point's base column is), rows from 1.
template <int D>
Stencil<4, D> stencil_at(int c0, int nx, int nz, int z0) {
  Stencil<4, D> st{};
  for (int a = 0; a < 4; ++a) {
    st.column[a] = ((c0 + a) % nx + nx) % nx;
    if constexpr (D == 3) st.layer[a] = ((z0 + a) % nz + nz) % nz;
  }
  st.row0 = 1;
  for (int k = 0; k < D; ++k)
    for (int a = 0; a < 4; ++a) st.w[k][a] = st.g[k][a] = 0.25;
  return st;
}

template <int D>
void every_split(int nx) {
  const int ny = 6, nz = 5;
  const GridGeometry<D> g = grid<D>(nx, ny, nz);
  std::mt19937_64 rng(static_cast<unsigned>(nx * 10 + D));
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int c0 = -1; c0 <= nx - 2; ++c0) {
    const Stencil<4, D> st = stencil_at<D>(c0, nx, nz, nz - 2);
    std::vector<Vec<D>> field(g.nodes());
    std::vector<double> scalar(g.nodes());
    for (auto& n : field)
      for (int d = 0; d < D; ++d) n[d] = value(rng);
    for (double& m : scalar) m = value(rng);
    const std::vector<Vec<D>> field0 = field;
    const std::vector<double> scalar0 = scalar;
    int rows = 0;
    for_each_row(st, g, [&](std::size_t row, const RowFactors<D>&, const auto& nodes) {
      ++rows;
      RowLanes<D> v;
      Lanes m;
      nodes.load(v, &field[row]);
      nodes.load(m, &scalar[row]);
      for (int a = 0; a < 4; ++a) {
        const std::size_t node = row + static_cast<std::size_t>(st.column[a]);
        CHECK(m[a] == scalar0[node]);
        for (int d = 0; d < D; ++d) CHECK(v.v[(D * a + d) / 4][(D * a + d) % 4] == field0[node][d]);
      }
      // Store lane l's value plus l + 1 (the component's lane in the pattern), then compare.
      for (int k = 0; k < D; ++k)
        for (int l = 0; l < 4; ++l) v.v[k][l] += 4 * k + l + 1;
      for (int l = 0; l < 4; ++l) m[l] += 100 + l;
      nodes.store(&field[row], v);
      nodes.store(&scalar[row], m);
    });
    CHECK(rows == (D == 2 ? 4 : 16));
    // Every node of the stencil changed by its lanes' increments, every other node not at all.
    std::vector<Vec<D>> expected = field0;
    std::vector<double> expected_scalar = scalar0;
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < (D == 3 ? 4 : 1); ++c) {
        std::size_t row = g.row_start(st.row0 + b);
        if constexpr (D == 3) row += static_cast<std::size_t>(st.layer[c]) * static_cast<std::size_t>(nx);
        for (int a = 0; a < 4; ++a) {
          const std::size_t node = row + static_cast<std::size_t>(st.column[a]);
          expected_scalar[node] += 100 + a;
          for (int d = 0; d < D; ++d) expected[node][d] += D * a + d + 1;
        }
      }
    CHECK(std::memcmp(field.data(), expected.data(), field.size() * sizeof(Vec<D>)) == 0);
    CHECK(std::memcmp(scalar.data(), expected_scalar.data(), scalar.size() * sizeof(double)) == 0);
  }
}

// Each row's factors, on a stencil with distinct weights and derivatives on every axis: the row
// weight w_y(b) (w_z(c)) and the gradient factors g_y(b) (w_z(c)) and w_y(b) g_z(c), the same
// products as computed one by one, in every lane in 3D; rows y outermost, then z.
template <int D>
void row_factors() {
  const GridGeometry<D> g = grid<D>(7, 6, 5);
  std::mt19937_64 rng(42 + D);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Stencil<4, D> st = stencil_at<D>(2, 7, 5, 1);
  for (int k = 0; k < D; ++k)
    for (int a = 0; a < 4; ++a) {
      st.w[k][a] = value(rng);
      st.g[k][a] = value(rng);
    }
  int visited = 0;
  for_each_row(st, g, [&](std::size_t, const RowFactors<D>& r, const auto&) {
    const int b = D == 2 ? visited : visited / 4, c = D == 2 ? 0 : visited % 4;
    ++visited;
    const double wy = st.w[1][b], gy = st.g[1][b];
    if constexpr (D == 2) {
      CHECK(r.weight == wy);
      CHECK(r.gradient[1] == gy);
    } else {
      const double wz = st.w[2][c], gz = st.g[2][c];
      for (int l = 0; l < 4; ++l) {
        CHECK(r.weight[l] == wy * wz);
        CHECK(r.gradient[1][l] == gy * wz);
        CHECK(r.gradient[2][l] == wy * gz);
      }
    }
  });
  CHECK(visited == (D == 2 ? 4 : 16));
}

}  // namespace

int main() {
  for (int nx = 4; nx <= 9; ++nx) {
    every_split<2>(nx);
    every_split<3>(nx);
  }
  row_factors<2>();
  row_factors<3>();
  return check::result();
}
