// The processes of a run: MPI ranks under mpirun, else one process. Every MPI call of mpmshock is
// behind this class (comm.cpp), so the rest of the code reads the same with or without MPI and a
// build without MPI has the same interface, with one rank.
//
// Results must not depend on the number of ranks, so nothing here rounds: maxima and minima are
// exact whatever the order, integers add exactly, and sums of doubles travel as ExactSum's integer
// words (exact_sum.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mpmshock/exact_sum.hpp"

namespace mpmshock {

class Comm {
 public:
  // The world of the run: all the ranks mpirun started (after init), else this process alone.
  static Comm& world();
  // Starts MPI when the process was started by mpirun (or another MPI launcher); a process started
  // alone stays a single rank without touching MPI. Returns true when MPI runs.
  static bool init(int* argc, char*** argv);
  static void finalize();
  // True when this build can run on several ranks.
  static bool built_with_mpi();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool parallel() const { return size_ > 1; }
  // The ranks on this machine (sharing its memory), this one included.
  int node_ranks() const { return node_size_; }

  // Element-wise across ranks, the result on every rank.
  void sum(ExactSum* sums, int count) const;
  void sum(std::int64_t* values, int count) const;
  void max(double* values, int count) const;
  double max(double value) const {
    max(&value, 1);
    return value;
  }
  double min(double value) const {
    value = -value;
    max(&value, 1);
    return -value;
  }
  std::int64_t sum(std::int64_t value) const {
    sum(&value, 1);
    return value;
  }

  // Sends `out` to rank `to` and receives what rank `from` sends to us (either may be -1: none).
  std::vector<char> exchange(int to, const std::vector<char>& out, int from) const;
  // One round with both neighbours at once: `to_up` to rank up, `to_down` to rank down, and from
  // them into `from_up` and `from_down`, which are already sized to what they send (-1: no such
  // neighbour, or nothing to send or receive that way; an empty buffer: nothing either).
  void swap(int up, const std::vector<char>& to_up, std::vector<char>& from_up, int down,
            const std::vector<char>& to_down, std::vector<char>& from_down) const;
  // Every rank's bytes, in rank order, at rank 0 (empty elsewhere).
  std::vector<std::vector<char>> gather(const std::vector<char>& mine) const;
  // Rank 0's bytes at every rank.
  void broadcast(std::vector<char>& bytes) const;
  void broadcast(std::string& text) const;
  // Piece k of rank 0's `pieces` to rank k (pieces has size() entries at rank 0).
  std::vector<char> scatter(const std::vector<std::vector<char>>& pieces) const;
  void barrier() const;
  // Stops every rank with this exit code (after an error one rank alone met).
  [[noreturn]] void abort(int code) const;

  // What this rank has sent and how long it spent in MPI calls (waiting included), since start.
  struct Traffic {
    std::uint64_t bytes = 0, messages = 0;
    double seconds = 0.0;
  };
  const Traffic& traffic() const { return traffic_; }

 private:
  int rank_ = 0, size_ = 1, node_size_ = 1;
  mutable Traffic traffic_;
};

}  // namespace mpmshock
