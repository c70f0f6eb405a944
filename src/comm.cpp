#include "mpmshock/comm.hpp"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#ifdef MPMSHOCK_HAVE_MPI
// The C API only: Open MPI and MPICH would otherwise pull in their deprecated C++ bindings.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace mpmshock {

namespace {

bool mpi_running = false;

// Adds the wall time of a scope to the rank's traffic (MPI_Wtime is only there with MPI).
struct Timed {
  explicit Timed(Comm::Traffic& t) : traffic(t), start(std::chrono::steady_clock::now()) {}
  ~Timed() { traffic.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }
  Comm::Traffic& traffic;
  std::chrono::steady_clock::time_point start;
};

#ifdef MPMSHOCK_HAVE_MPI
// Launchers announce themselves in the environment: Open MPI's mpirun, PMIx, Slurm's PMI, MPICH's
// Hydra. A process started alone runs without MPI, so that no daemon is spawned for it.
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}
#endif

}  // namespace

Comm& Comm::world() {
  static Comm comm;
  return comm;
}

bool Comm::built_with_mpi() {
#ifdef MPMSHOCK_HAVE_MPI
  return true;
#else
  return false;
#endif
}

bool Comm::init(int* argc, char*** argv) {
#ifdef MPMSHOCK_HAVE_MPI
  if (!launched_by_mpi()) return false;
  int provided = 0;
  // OpenMP threads compute between the calls; only the main thread talks to MPI.
  check(MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  mpi_running = true;
  Comm& w = world();
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size_);
  MPI_Comm node;  // the ranks that share this machine's memory
  check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node), "MPI_Comm_split_type");
  MPI_Comm_size(node, &w.node_size_);
  MPI_Comm_free(&node);
  return true;
#else
  (void)argc;
  (void)argv;
  return false;
#endif
}

void Comm::finalize() {
#ifdef MPMSHOCK_HAVE_MPI
  if (mpi_running) MPI_Finalize();
  mpi_running = false;
#endif
}

void Comm::sum(ExactSum* sums, int count) const {
  if (size_ == 1 || count == 0) return;
#ifdef MPMSHOCK_HAVE_MPI
  std::vector<std::int64_t> words(static_cast<std::size_t>(count) * ExactSum::kWords);
  const Timed timed(traffic_);
  traffic_.bytes += sizeof(std::int64_t) * ExactSum::kWords * static_cast<std::uint64_t>(count);
  ++traffic_.messages;
  for (int k = 0; k < count; ++k) {
    sums[k].carry();  // canonical digits below 2^32: thousands of ranks add without overflow
    std::memcpy(&words[static_cast<std::size_t>(k) * ExactSum::kWords], sums[k].words().data(),
                sizeof(std::int64_t) * ExactSum::kWords);
  }
  check(MPI_Allreduce(MPI_IN_PLACE, words.data(), static_cast<int>(words.size()), MPI_INT64_T, MPI_SUM,
                      MPI_COMM_WORLD),
        "MPI_Allreduce");
  for (int k = 0; k < count; ++k) sums[k] = ExactSum::from_words(&words[static_cast<std::size_t>(k) * ExactSum::kWords]);
#endif
}

void Comm::sum(std::int64_t* values, int count) const {
  if (size_ == 1 || count == 0) return;
#ifdef MPMSHOCK_HAVE_MPI
  const Timed timed(traffic_);
  traffic_.bytes += sizeof(std::int64_t) * static_cast<std::uint64_t>(count);
  ++traffic_.messages;
  check(MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
#endif
}

void Comm::max(double* values, int count) const {
  if (size_ == 1 || count == 0) return;
#ifdef MPMSHOCK_HAVE_MPI
  const Timed timed(traffic_);
  traffic_.bytes += sizeof(double) * static_cast<std::uint64_t>(count);
  ++traffic_.messages;
  check(MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
#endif
}

std::vector<char> Comm::exchange(int to, const std::vector<char>& out, int from) const {
  std::vector<char> in;
  if (size_ == 1) return in;
#ifdef MPMSHOCK_HAVE_MPI
  constexpr int kSizeTag = 11, kDataTag = 12;
  const Timed timed(traffic_);
  if (to >= 0) traffic_.bytes += out.size() + sizeof(std::uint64_t), traffic_.messages += 2;
  const int dest = to >= 0 ? to : MPI_PROC_NULL, source = from >= 0 ? from : MPI_PROC_NULL;
  std::uint64_t out_size = out.size(), in_size = 0;
  check(MPI_Sendrecv(&out_size, 1, MPI_UINT64_T, dest, kSizeTag, &in_size, 1, MPI_UINT64_T, source, kSizeTag,
                     MPI_COMM_WORLD, MPI_STATUS_IGNORE),
        "MPI_Sendrecv");
  if (source == MPI_PROC_NULL) in_size = 0;
  in.resize(in_size);
  if (out_size > static_cast<std::uint64_t>(INT32_MAX) || in_size > static_cast<std::uint64_t>(INT32_MAX))
    throw std::runtime_error("MPI: a message of more than 2 GB between two ranks");
  check(MPI_Sendrecv(out.data(), static_cast<int>(out_size), MPI_BYTE, dest, kDataTag, in.data(),
                     static_cast<int>(in_size), MPI_BYTE, source, kDataTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
        "MPI_Sendrecv");
#else
  (void)to, (void)out, (void)from;
#endif
  return in;
}

void Comm::swap(int up, const std::vector<char>& to_up, std::vector<char>& from_up, int down,
                const std::vector<char>& to_down, std::vector<char>& from_down) const {
  if (size_ == 1) return;
#ifdef MPMSHOCK_HAVE_MPI
  constexpr int kUpTag = 41, kDownTag = 42;  // by direction of travel
  const Timed timed(traffic_);
  MPI_Request requests[4];
  int n = 0;
  auto too_big = [](std::size_t bytes) {
    if (bytes > static_cast<std::size_t>(INT32_MAX)) throw std::runtime_error("MPI: a message of more than 2 GB");
    return static_cast<int>(bytes);
  };
  if (up >= 0 && !from_up.empty())
    check(MPI_Irecv(from_up.data(), too_big(from_up.size()), MPI_BYTE, up, kDownTag, MPI_COMM_WORLD, &requests[n++]),
          "MPI_Irecv");
  if (down >= 0 && !from_down.empty())
    check(MPI_Irecv(from_down.data(), too_big(from_down.size()), MPI_BYTE, down, kUpTag, MPI_COMM_WORLD,
                    &requests[n++]),
          "MPI_Irecv");
  if (up >= 0 && !to_up.empty()) {
    check(MPI_Isend(to_up.data(), too_big(to_up.size()), MPI_BYTE, up, kUpTag, MPI_COMM_WORLD, &requests[n++]),
          "MPI_Isend");
    traffic_.bytes += to_up.size(), ++traffic_.messages;
  }
  if (down >= 0 && !to_down.empty()) {
    check(MPI_Isend(to_down.data(), too_big(to_down.size()), MPI_BYTE, down, kDownTag, MPI_COMM_WORLD,
                    &requests[n++]),
          "MPI_Isend");
    traffic_.bytes += to_down.size(), ++traffic_.messages;
  }
  check(MPI_Waitall(n, requests, MPI_STATUSES_IGNORE), "MPI_Waitall");
#else
  (void)up, (void)to_up, (void)from_up, (void)down, (void)to_down, (void)from_down;
#endif
}

std::vector<std::vector<char>> Comm::gather(const std::vector<char>& mine) const {
  std::vector<std::vector<char>> all;
  if (size_ == 1) {
    all.push_back(mine);
    return all;
  }
#ifdef MPMSHOCK_HAVE_MPI
  // Point to point, one rank at a time: no counts array of 2 GB limits, and rank 0 holds one
  // message more at a time than it keeps.
  constexpr int kSizeTag = 21, kDataTag = 22;
  if (rank_ == 0) {
    all.resize(static_cast<std::size_t>(size_));
    all[0] = mine;
    for (int r = 1; r < size_; ++r) {
      std::uint64_t n = 0;
      check(MPI_Recv(&n, 1, MPI_UINT64_T, r, kSizeTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
      all[r].resize(n);
      for (std::uint64_t done = 0; done < n;) {
        const int part = static_cast<int>(std::min<std::uint64_t>(n - done, 1u << 30));
        check(MPI_Recv(all[r].data() + done, part, MPI_BYTE, r, kDataTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
        done += static_cast<std::uint64_t>(part);
      }
    }
  } else {
    const std::uint64_t n = mine.size();
    check(MPI_Send(&n, 1, MPI_UINT64_T, 0, kSizeTag, MPI_COMM_WORLD), "MPI_Send");
    for (std::uint64_t done = 0; done < n;) {
      const int part = static_cast<int>(std::min<std::uint64_t>(n - done, 1u << 30));
      check(MPI_Send(mine.data() + done, part, MPI_BYTE, 0, kDataTag, MPI_COMM_WORLD), "MPI_Send");
      done += static_cast<std::uint64_t>(part);
    }
  }
#endif
  return all;
}

std::vector<char> Comm::scatter(const std::vector<std::vector<char>>& pieces) const {
  if (size_ == 1) return pieces.empty() ? std::vector<char>{} : pieces[0];
  std::vector<char> mine;
#ifdef MPMSHOCK_HAVE_MPI
  constexpr int kSizeTag = 31, kDataTag = 32;
  if (rank_ == 0) {
    for (int r = 1; r < size_; ++r) {
      const std::vector<char>& piece = pieces[static_cast<std::size_t>(r)];
      const std::uint64_t n = piece.size();
      check(MPI_Send(&n, 1, MPI_UINT64_T, r, kSizeTag, MPI_COMM_WORLD), "MPI_Send");
      for (std::uint64_t done = 0; done < n;) {
        const int part = static_cast<int>(std::min<std::uint64_t>(n - done, 1u << 30));
        check(MPI_Send(piece.data() + done, part, MPI_BYTE, r, kDataTag, MPI_COMM_WORLD), "MPI_Send");
        done += static_cast<std::uint64_t>(part);
      }
    }
    mine = pieces[0];
  } else {
    std::uint64_t n = 0;
    check(MPI_Recv(&n, 1, MPI_UINT64_T, 0, kSizeTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
    mine.resize(n);
    for (std::uint64_t done = 0; done < n;) {
      const int part = static_cast<int>(std::min<std::uint64_t>(n - done, 1u << 30));
      check(MPI_Recv(mine.data() + done, part, MPI_BYTE, 0, kDataTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
            "MPI_Recv");
      done += static_cast<std::uint64_t>(part);
    }
  }
#endif
  return mine;
}

void Comm::broadcast(std::vector<char>& bytes) const {
  if (size_ == 1) return;
#ifdef MPMSHOCK_HAVE_MPI
  std::uint64_t n = bytes.size();
  check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
  bytes.resize(n);
  for (std::uint64_t done = 0; done < n;) {
    const int part = static_cast<int>(std::min<std::uint64_t>(n - done, 1u << 30));
    check(MPI_Bcast(bytes.data() + done, part, MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
    done += static_cast<std::uint64_t>(part);
  }
#endif
}

void Comm::broadcast(std::string& text) const {
  if (size_ == 1) return;
  std::vector<char> bytes(text.begin(), text.end());
  broadcast(bytes);
  text.assign(bytes.begin(), bytes.end());
}

void Comm::barrier() const {
#ifdef MPMSHOCK_HAVE_MPI
  if (size_ > 1) check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
#endif
}

void Comm::abort(int code) const {
#ifdef MPMSHOCK_HAVE_MPI
  if (mpi_running) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace mpmshock
