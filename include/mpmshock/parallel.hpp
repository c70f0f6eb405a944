// How mpmshock shares work between threads, in one place.
//
// On a shared machine (a laptop with a browser, a cluster node with a neighbour) a thread can lose
// its core for a whole scheduler time slice (milliseconds) at any moment. Loops over points and
// nodes therefore hand out chunks dynamically, so that the threads that have a core take over the
// work of one that has not. The results do not depend on which thread computes a point: every sum
// runs in a fixed order (strip_bins.hpp, diagnostics.cpp). How many threads a run uses is chosen
// as it goes (thread_tuner.hpp).
#pragma once

#include <cstddef>

namespace mpmshock {

// Points (or grid nodes) per chunk of a dynamically scheduled loop: large enough that handing out
// chunks costs nothing measurable, small enough to balance the load between threads.
constexpr std::size_t kChunk = 1024;

}  // namespace mpmshock
