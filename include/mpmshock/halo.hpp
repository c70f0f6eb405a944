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
    if (active()) pass(upper_even_, lower_even_, fields...);
  }
  // After the colours: the rank whose boundary strip is odd sends the finished sums back.
  template <class... Fields>
  void after_colours(Fields&... fields) const {
    if (active()) pass(!upper_even_, !lower_even_, fields...);
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

  template <class T>
  std::size_t bytes_of(const std::vector<T>&, RowRange rows) const {
    return (geo_.row_start(rows.end) - geo_.row_start(rows.begin)) * sizeof(T);
  }

  // One round with both neighbours: this rank sends its upper rows up if `send_up` and its lower
  // rows down if `send_down`; a neighbour sends to it exactly when it does not send to that
  // neighbour (one of each pair of strips is even), and what arrives overwrites the shared rows.
  template <class... Fields>
  void pass(bool send_up, bool send_down, Fields&... fields) const {
    std::vector<char> to_up, to_down, from_up, from_down;
    const int up = above_, down = below_;
    if (up >= 0) {
      if (send_up) (pack(to_up, fields, upper_), ...);
      else from_up.resize((bytes_of(fields, upper_) + ...));
    }
    if (down >= 0) {
      if (send_down) (pack(to_down, fields, lower_), ...);
      else from_down.resize((bytes_of(fields, lower_) + ...));
    }
    comm_->swap(up, to_up, from_up, down, to_down, from_down);
    std::size_t at = 0;
    if (!from_up.empty()) (unpack(from_up, at, fields, upper_), ...);
    at = 0;
    if (!from_down.empty()) (unpack(from_down, at, fields, lower_), ...);
  }
};

}  // namespace mpmshock
