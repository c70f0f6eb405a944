// The grid rows two MPI ranks share, and how their sums stay those of one process.
//
// A rank owns the points whose first node row lies in its slab of strips (decomposition.hpp); a
// point of its top strip also touches the first S - 1 node rows of the next slab (S: the stencil's
// nodes per axis), so those rows get sums from both ranks. One process adds each node's shares in a
// fixed order: the even strip's points first (colour 0 of StripBins::scatter), then the odd strip's,
// each in id order, starting from 0. Two neighbouring slabs meet at a strip boundary, so of the two
// strips that reach the shared rows one is even and one odd. The rank with the even one scatters its
// colour 0 and sends its sums of the shared rows to the other (between the colours); that rank takes
// them as the rows' values, adds its odd strip in colour 1 (continuing the very additions one process
// makes), and sends the finished sums back (after the colours). Both ranks then hold the same bits in
// the shared rows, the same that one process computes, and every later pass (the grid update, G2P)
// reads them there.
#pragma once

#include <cstring>
#include <vector>

#include "mpmshock/comm.hpp"
#include "mpmshock/grid.hpp"

namespace mpmshock {

template <int D>
class Halo {
 public:
  // One rank, or nothing shared.
  Halo() = default;
  // A rank holding the strips [first_strip, end_strip), with a neighbour below and/or above, and
  // stencils of `support` nodes per axis.
  Halo(const Comm& comm, const GridGeometry<D>& geo, int first_strip, int end_strip, int rows_per_strip,
       int support, bool below, bool above)
      : comm_(&comm), geo_(geo), below_(below ? comm.rank() - 1 : -1), above_(above ? comm.rank() + 1 : -1) {
    const int shared = support - 1;
    lower_ = {first_strip * rows_per_strip, first_strip * rows_per_strip + shared};
    upper_ = {end_strip * rows_per_strip, std::min(geo.ny, end_strip * rows_per_strip + shared)};
    lower_even_ = first_strip % 2 == 0;    // my strip at the lower boundary
    upper_even_ = (end_strip - 1) % 2 == 0;  // my strip at the upper boundary
  }

  bool active() const { return below_ >= 0 || above_ >= 0; }
  // The rows shared with the rank below and above (empty without that neighbour).
  RowRange lower_rows() const { return below_ >= 0 ? lower_ : RowRange{}; }
  RowRange upper_rows() const { return above_ >= 0 ? upper_ : RowRange{}; }

  // Zeroes the shared rows of the fields (before a scatter: a rank may share rows its own points do
  // not touch, and its sums of them are still sent).
  template <class... Fields>
  void zero(Fields&... fields) const {
    for (const RowRange rows : {lower_rows(), upper_rows()})
      (zero_rows(fields, rows), ...);
  }

  // Between the colours: the rank whose boundary strip is even sends its partial sums.
  template <class... Fields>
  void between_colours(Fields&... fields) const {
    if (!active()) return;
    pass(upper_even_, !lower_even_, fields...);   // upwards: my even top strip; from below, if mine is odd
    pass_down(lower_even_, !upper_even_, fields...);
  }
  // After the colours: the rank whose boundary strip is odd sends the finished sums back.
  template <class... Fields>
  void after_colours(Fields&... fields) const {
    if (!active()) return;
    pass(!upper_even_, lower_even_, fields...);
    pass_down(!lower_even_, upper_even_, fields...);
  }

 private:
  const Comm* comm_ = nullptr;
  GridGeometry<D> geo_;
  int below_ = -1, above_ = -1;
  RowRange lower_, upper_;
  bool lower_even_ = true, upper_even_ = true;

  template <class T>
  void zero_rows(std::vector<T>& field, RowRange rows) const {
    if (rows.end <= rows.begin) return;
    std::fill(field.begin() + static_cast<std::ptrdiff_t>(geo_.row_start(rows.begin)),
              field.begin() + static_cast<std::ptrdiff_t>(geo_.row_start(rows.end)), T{});
  }
  template <class T>
  void pack(std::vector<char>& out, const std::vector<T>& field, RowRange rows) const {
    const std::size_t b = geo_.row_start(rows.begin), bytes = (geo_.row_start(rows.end) - b) * sizeof(T);
    const std::size_t at = out.size();
    out.resize(at + bytes);
    std::memcpy(out.data() + at, field.data() + b, bytes);
  }
  template <class T>
  void unpack(const std::vector<char>& in, std::size_t& at, std::vector<T>& field, RowRange rows) const {
    const std::size_t b = geo_.row_start(rows.begin), bytes = (geo_.row_start(rows.end) - b) * sizeof(T);
    std::memcpy(field.data() + b, in.data() + at, bytes);
    at += bytes;
  }

  // One upward exchange: my upper rows to the rank above (if `send`), the rows I share with the
  // rank below from it (if `receive`), which overwrite mine.
  template <class... Fields>
  void pass(bool send, bool receive, Fields&... fields) const {
    std::vector<char> out;
    const int to = send ? above_ : -1, from = receive ? below_ : -1;
    if (to >= 0) (pack(out, fields, upper_), ...);
    const std::vector<char> in = comm_->exchange(to, out, from);
    std::size_t at = 0;
    if (from >= 0) (unpack(in, at, fields, lower_), ...);
  }
  // One downward exchange: my lower rows to the rank below, my upper rows from the rank above.
  template <class... Fields>
  void pass_down(bool send, bool receive, Fields&... fields) const {
    std::vector<char> out;
    const int to = send ? below_ : -1, from = receive ? above_ : -1;
    if (to >= 0) (pack(out, fields, lower_), ...);
    const std::vector<char> in = comm_->exchange(to, out, from);
    std::size_t at = 0;
    if (from >= 0) (unpack(in, at, fields, upper_), ...);
  }
};

}  // namespace mpmshock
