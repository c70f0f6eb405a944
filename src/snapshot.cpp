#include "mpmshock/snapshot.hpp"

#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <vector>

#include "mpmshock/decomposition.hpp"
#include "mpmshock/hdf5_io.hpp"
#include "mpmshock/provenance.hpp"
#include "mpmshock/run_directory.hpp"
#include "mpmshock/signals.hpp"
#include "mpmshock/version.hpp"

namespace mpmshock {
namespace {

using h5::Compression;
using h5::Handle;

// A per-point field of small vectors or matrices as the flat doubles HDF5 writes (N x D, N x D x D).
template <class T>
const double* flat(const std::vector<T>& v) {
  static_assert(sizeof(T) % sizeof(double) == 0, "a field of doubles");
  return reinterpret_cast<const double*>(v.data());
}
template <class T>
void unflatten(const std::vector<double>& flat_values, std::vector<T>& v) {
  v.resize(flat_values.size() * sizeof(double) / sizeof(T));
  std::memcpy(static_cast<void*>(v.data()), flat_values.data(), flat_values.size() * sizeof(double));
}

// The stored components of a deviator: xx, yy, xy (and yz, zx in 3D); zz = -(xx + yy).
template <int D>
constexpr hsize_t kDeviatorComponents = D == 2 ? 3 : 5;

// A snapshot is written in chunks of kChunkRows rows (the 64 Ki-row HDF5 chunks of a
// compressed dataset): each chunk is the whole impact's points of those rows, the mirrored flyer's
// made from the target's, gathered from the ranks that hold them (snapshot_rows), and every dataset
// gets its rows of it. No rank, rank 0 included, holds more than a chunk beyond its own points.
constexpr std::size_t kChunkRows = 65536;

// One dataset of the snapshot: what a row of it holds, and how a chunk's points fill its rows.
template <int D>
struct Column {
  hid_t group;
  std::string name;
  hid_t type;
  std::vector<hsize_t> row_shape;  // the dimensions after the first
  std::string units, description;
  Compression compression;
  std::size_t row_bytes;
  std::function<void(const Particles<D>& rows, char* out)> fill;
};

template <int D>
using Columns = std::vector<Column<D>>;

// A column of doubles, `per_row` of them from each point by `value(q, out)`.
template <int D, class F>
Column<D> doubles(hid_t g, const char* name, std::vector<hsize_t> shape, const char* units, const std::string& what,
                  Compression c, F value) {
  std::size_t per_row = 1;
  for (hsize_t d : shape) per_row *= d;
  return {g, name, H5T_NATIVE_DOUBLE, std::move(shape), units, what, c, per_row * sizeof(double),
          [value, per_row](const Particles<D>& rows, char* out) {
            auto* o = reinterpret_cast<double*>(out);
            for (std::size_t q = 0; q < rows.size(); ++q) value(rows, q, o + q * per_row);
          }};
}

// A per-point field of small vectors or matrices, copied as its doubles.
template <int D, class T>
Column<D> field(hid_t g, const char* name, std::vector<hsize_t> shape, const char* units, const std::string& what,
                Compression c, std::vector<T> Particles<D>::*member) {
  static_assert(sizeof(T) % sizeof(double) == 0, "a field of doubles");
  return doubles<D>(g, name, std::move(shape), units, what, c, [member](const Particles<D>& p, std::size_t q, double* o) {
    std::memcpy(o, &(p.*member)[q], sizeof(T));
  });
}

template <int D>
Columns<D> particle_columns(hid_t g, const Particles<D>& layout, const BodyTemperatures* thermal, int level,
                            const std::array<MeltCurve, kBodies>& melt, const std::array<double, kBodies>& melt_temperature) {
  const Compression always{level > 0 ? level : 1};  // fields that compress >100x: worth it at any setting
  const Compression chosen{level};
  const hsize_t d = D;
  const std::string per_depth = D == 2 ? " per metre of depth (plane strain)" : "";
  Columns<D> c;
  c.push_back({g, "id", H5T_NATIVE_UINT32, {}, "", "stable material-point number", always, sizeof(std::uint32_t),
               [](const Particles<D>& p, char* out) { std::memcpy(out, p.id.data(), p.size() * sizeof(std::uint32_t)); }});
  c.push_back({g, "body", H5T_NATIVE_UINT8, {}, "", "0 flyer, 1 target", always, sizeof(std::uint8_t),
               [](const Particles<D>& p, char* out) { std::memcpy(out, p.body.data(), p.size()); }});
  c.push_back(field<D>(g, "position", {d}, "m", D == 2 ? "x, y" : "x, y, z", chosen, &Particles<D>::x));
  c.push_back(field<D>(g, "velocity", {d}, "m/s", D == 2 ? "v_x, v_y" : "v_x, v_y, v_z", chosen, &Particles<D>::v));
  c.push_back(field<D>(g, "mass", {}, D == 2 ? "kg/m" : "kg", "mass" + per_depth, always, &Particles<D>::m));
  c.push_back(doubles<D>(g, "volume", {}, D == 2 ? "m2" : "m3", "volume" + per_depth, chosen,
                         [](const Particles<D>& p, std::size_t q, double* o) { *o = p.volume(q); }));
  c.push_back(doubles<D>(g, "density", {}, "kg/m3", "density of the material point", chosen,
                         [](const Particles<D>& p, std::size_t q, double* o) { *o = p.density(q); }));
  c.push_back(field<D>(g, "pressure", {}, "Pa", "Mie-Grueneisen pressure (without artificial viscosity)", chosen,
                       &Particles<D>::P));
  c.push_back(field<D>(g, "viscous_pressure", {}, "Pa", "artificial viscous pressure q", chosen, &Particles<D>::q));
  c.push_back(doubles<D>(g, "temperature", {}, "K", "T = T_H(V) + (E - E_H(V)) / c_v; NaN when thermal = off", chosen,
                         [thermal](const Particles<D>& p, std::size_t q, double* o) {
                           *o = thermal ? thermal->of_point(p, q) : std::nan("");
                         }));
  if (thermal && thermal->reports_paper_temperature())
    c.push_back(doubles<D>(g, "paper_temperature", {}, "K",
                           "the paper model's T = T_H(V) + W_p / c_v, W_p the plastic work turned to heat "
                           "(paper_temperature = on)",
                           chosen, [thermal](const Particles<D>& p, std::size_t q, double* o) {
                             *o = thermal->paper_of_point(p, q);
                           }));
  c.push_back(field<D>(g, "internal_energy", {}, "J/kg", "specific internal energy, 0 at the reference state", chosen,
                       &Particles<D>::E));
  c.push_back(doubles<D>(g, "stress", {3, 3}, "Pa",
                         D == 2 ? "Cauchy stress s - (P + q) I, plane strain (zz non-zero)" : "Cauchy stress s - (P + q) I",
                         chosen, [](const Particles<D>& p, std::size_t q, double* t) {
                           const double pq = p.P[q] + p.q[q];
                           const Deviator<D> s = p.has_strength() ? p.s[q] : Deviator<D>{};
                           for (int k = 0; k < 9; ++k) t[k] = 0.0;
                           t[0] = s.xx - pq;
                           t[1] = t[3] = s.xy;
                           t[4] = s.yy - pq;
                           t[8] = s.zz() - pq;
                           if constexpr (D == 3) {
                             t[5] = t[7] = s.yz();
                             t[2] = t[6] = s.zx();
                           }
                         }));
  c.push_back(doubles<D>(g, "plastic_strain", {}, "", "effective plastic strain", chosen,
                         [](const Particles<D>& p, std::size_t q, double* o) { *o = p.has_strength() ? p.eps_p[q] : 0.0; }));
  c.push_back(doubles<D>(g, "melted", {}, "",
                         "1 where T is at or above the melt temperature: the Lindemann T_m(J) of the body's material, or "
                         "with strength_model = johnson_cook the body's jc_melt_temperature; else 0 (0 with thermal = "
                         "off, and for a material without a melt curve)",
                         chosen, [thermal, melt, melt_temperature](const Particles<D>& p, std::size_t q, double* o) {
                           const double fixed = melt_temperature[index_of(p.body[q])];
                           const MeltCurve& curve = melt[index_of(p.body[q])];
                           if (!(fixed > 0.0) && !(curve.T_m0 > 0.0)) {
                             *o = 0.0;
                             return;
                           }
                           const double T_m = fixed > 0.0 ? fixed : curve.at(p.material_J(q));
                           *o = thermal && thermal->of_point(p, q) >= T_m ? 1.0 : 0.0;
                         }));
  c.push_back(doubles<D>(g, "damage", {}, "", "0 intact, rising from 0 while it opens in tension, 1 separated (spall = on; 0 without)",
                         chosen, [](const Particles<D>& p, std::size_t q, double* o) { *o = p.has_failure() ? p.damage[q] : 0.0; }));
  c.push_back(field<D>(g, "deformation_gradient", {d, d}, "",
                       D == 2 ? "F, in-plane (F_zz = 1), F[i][j] = dx_i/dX_j" : "F[i][j] = dx_i/dX_j", chosen,
                       &Particles<D>::F));
  c.push_back(field<D>(g, "velocity_gradient", {d, d}, "1/s", "L = grad v of the last step, L[i][j] = dv_i/dx_j", chosen,
                       &Particles<D>::L));
  (void)layout;
  return c;
}

void write_bodies(hid_t g, const RunState& run, int dimension) {
  for (const BodySummary* b : {&run.target, &run.flyer}) {
    const std::string prefix = b->name + "_";
    h5::write_int_attribute(g, (prefix + "lattice_points").c_str(), static_cast<std::int64_t>(b->lattice_points));
    h5::write_int_attribute(g, (prefix + "material_points").c_str(), static_cast<std::int64_t>(b->material_points));
    h5::write_doubles_attribute(g, (prefix + "extent").c_str(), {b->y_bottom, b->y_top});
    std::vector<double> voids;
    for (const Void& v : b->voids) {
      voids.insert(voids.end(), {v.x, v.y});
      if (dimension == 3) voids.push_back(v.z);
      voids.push_back(v.r);
    }
    const hsize_t M = b->voids.size(), columns = dimension == 3 ? 4 : 3;
    h5::write_dataset(g, (prefix + "voids").c_str(), H5T_NATIVE_DOUBLE, voids.data(), {M, columns}, "m",
                      dimension == 3 ? "sphere centres x, y, z and radii" : "void centres x, y and radii", {1});
  }
}

// /restart's attributes, and the columns of the state /particles does not hold.
template <int D>
Columns<D> restart_columns(hid_t g, const Particles<D>& layout, const RunState& run) {
  const hsize_t C = kDeviatorComponents<D>;
  h5::write_double_attribute(g, "max_signal", run.clock.max_signal);
  h5::write_double_attribute(g, "work_mismatch", run.clock.work_mismatch);
  h5::write_double_attribute(g, "work_mismatch_before", run.clock.work_mismatch_before);
  if (run.clock.unreached_tail != Clock::kNoneSaved) {  // ids of the simulated points (unreached.hpp)
    h5::write_int_attribute(g, "unreached_head", static_cast<std::int64_t>(run.clock.unreached_head));
    h5::write_int_attribute(g, "unreached_tail", static_cast<std::int64_t>(run.clock.unreached_tail));
  }
  h5::write_int_attribute(g, "snapshot_index", run.schedule.snapshot_index);
  h5::write_double_attribute(g, "last_dt", run.schedule.last_dt);
  const Totals& t = run.initial;
  std::vector<double> totals = {t.mass};
  for (int d = 0; d < D; ++d) totals.push_back(t.momentum[d]);
  totals.insert(totals.end(), {t.momentum_magnitude, t.kinetic, t.internal});
  h5::write_doubles_attribute(g, "initial_totals", totals);
  h5::write_string_attribute(g, "random_state",
                             "none: random numbers are drawn only at set-up (the void layout, stored here)");
  write_bodies(g, run, D);
  const std::string components = D == 2 ? "xx, yy, xy (zz = -(xx + yy))" : "xx, yy, xy, yz, zx (zz = -(xx + yy))";
  Columns<D> c;
  c.push_back(field<D>(g, "volume0", {}, D == 2 ? "m2" : "m3", "reference volume V0", {1}, &Particles<D>::V0));
  c.push_back(field<D>(g, "work_mismatch", {}, D == 2 ? "J/m" : "J",
                       "the point's own running sum of m (work - own trapezoid work); work_mismatch is their "
                       "exact sum plus work_mismatch_before",
                       {}, &Particles<D>::work_mismatch));
  if (layout.has_strength())
    c.push_back(field<D>(g, "deviatoric_stress", {C}, "Pa", "deviatoric stress s: " + components, {},
                         &Particles<D>::s));
  if (layout.stores_cold_work())
    c.push_back(field<D>(g, "stored_energy", {}, "J/kg", "plastic work stored as cold work, not heat (taylor_quinney < 1)",
                         {}, &Particles<D>::E_stored));
  if (layout.tracks_plastic_heat())
    c.push_back(field<D>(g, "plastic_heat", {}, "J/kg", "plastic work turned to heat so far (temperature_model = paper)",
                         {}, &Particles<D>::plastic_heat));
  if (layout.has_failure())
    c.push_back(field<D>(g, "failure_J", {}, "", "0 while intact; the volume ratio J at which the point began to open in tension",
                         {}, &Particles<D>::failure_J));
  if (layout.has_back_stress())
    c.push_back(field<D>(g, "back_stress", {C}, "Pa", "back stress alpha (kinematic hardening): " + components, {},
                         &Particles<D>::alpha));
  return c;
}

template <int D>
void write_grid(hid_t file, const SnapshotOptions<D>& o) {
  const Grid<D>& grid = *o.grid;
  const GridGeometry<D>& geo = grid.geo;
  Handle group(H5Gcreate2(file, "grid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /grid");
  const hid_t g = group.get();
  h5::write_doubles_attribute(g, "origin", D == 2 ? std::vector<double>{0.0, geo.y_min}
                                                  : std::vector<double>{0.0, geo.y_min, 0.0});
  h5::write_double_attribute(g, "spacing", geo.h);
  std::vector<double> counts = {static_cast<double>(geo.nx), static_cast<double>(geo.ny)};
  if (D == 3) counts.push_back(static_cast<double>(geo.nz));
  h5::write_doubles_attribute(g, "nodes", counts);
  const std::size_t nodes = geo.nodes();
  std::vector<double> mass(nodes, 0.0);
  std::vector<std::vector<double>> velocity(D, std::vector<double>(nodes, 0.0));
  // In the file, layer k (z) is slowest, then row j (y), then column i (x): the order of a
  // co-rectilinear mesh in XDMF. In memory rows are slowest (grid.hpp).
  const auto nx = static_cast<std::size_t>(geo.nx), ny = static_cast<std::size_t>(geo.ny);
  const std::size_t b = geo.row_start(o.grid_rows.begin), e = geo.row_start(o.grid_rows.end);
  for (std::size_t i = b; i < e; ++i) {
    if (!(grid.m[i] > 0.0)) continue;
    const std::size_t row = i / geo.nodes_per_row(), layer = (i % geo.nodes_per_row()) / nx, column = i % nx;
    const std::size_t at = (layer * ny + row) * nx + column;
    mass[at] = grid.m[i];
    for (int d = 0; d < D; ++d) velocity[d][at] = grid.v[i][d];
  }
  // Node (i, j, k) at (i h, y_min + j h, k h) is element [k][j][i] (3D) or [j][i] (2D).
  std::vector<hsize_t> dims;
  if (D == 3) dims.push_back(static_cast<hsize_t>(geo.nz));
  dims.push_back(static_cast<hsize_t>(geo.ny));
  dims.push_back(static_cast<hsize_t>(geo.nx));
  h5::write_dataset(g, "mass", H5T_NATIVE_DOUBLE, mass.data(), dims, D == 2 ? "kg/m" : "kg", "nodal mass m_i", {1});
  const char* names[3] = {"velocity_x", "velocity_y", "velocity_z"};
  const char* what[3] = {"nodal v_x after the last step's momentum update", "nodal v_y after the last step's momentum update",
                         "nodal v_z after the last step's momentum update"};
  for (int d = 0; d < D; ++d)
    h5::write_dataset(g, names[d], H5T_NATIVE_DOUBLE, velocity[d].data(), dims, "m/s", what[d], {1});
}

// FNV-1a, 64 bits: a checksum, not a cryptographic hash; it catches the flipped bits and cut
// files of a damaged disk or copy, not a forger. Snapshots of format 2 hash byte by byte; those
// written now hash 8-byte words in four interleaved lanes (FNV-1a's step on each word), which
// runs at memory speed: sealing a 253 MB snapshot took 0.09 s instead of 0.35 s, which matters
// for the snapshot written when a run is told to stop (mpirun kills the ranks a second later).
class Fnv1a {
 public:
  static constexpr std::uint64_t kOffset = 14695981039346656037ull, kPrime = 1099511628211ull;
  void add(const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) h_ = (h_ ^ b[k]) * kPrime;
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = kOffset;
};

class Fnv1aWords {
 public:
  // Whole words go to the lanes in turn; a call's bytes past its last whole word are hashed as
  // bytes, so only the last call may end off a word (file_checksum_line reads in whole MiB).
  void add(const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    const std::size_t words = n / 8;
    std::size_t k = 0;
    for (; k + 4 <= words; k += 4)
      for (int lane = 0; lane < 4; ++lane) lanes_[lane] = (lanes_[lane] ^ word(b + 8 * (k + lane))) * Fnv1a::kPrime;
    for (; k < words; ++k) lanes_[0] = (lanes_[0] ^ word(b + 8 * k)) * Fnv1a::kPrime;
    tail_.add(b + 8 * words, n - 8 * words);
  }
  std::uint64_t value() const {
    Fnv1a all;
    all.add(lanes_, sizeof lanes_);
    const std::uint64_t tail = tail_.value();
    all.add(&tail, sizeof tail);
    return all.value();
  }

 private:
  static std::uint64_t word(const unsigned char* p) {
    std::uint64_t w = 0;  // little-endian, whatever the machine
    for (int i = 7; i >= 0; --i) w = (w << 8) | p[i];
    return w;
  }
  std::uint64_t lanes_[4] = {Fnv1a::kOffset, Fnv1a::kOffset ^ 1, Fnv1a::kOffset ^ 2, Fnv1a::kOffset ^ 3};
  Fnv1a tail_;
};

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// The first kUserBlock bytes of a snapshot are HDF5's user block: the library skips them, and
// mpmshock keeps there a checksum of every byte after them (format 2). A restart checks it before
// the HDF5 library reads anything, because that library is not safe against damaged files (it can
// crash on them: found by tests/fuzz/fuzz_snapshot.cpp).
constexpr std::size_t kUserBlock = 512;
constexpr const char* kChecksumMagic = "mpmshock snapshot checksum fnv1a64 ";               // bytes
constexpr const char* kWordChecksumMagic = "mpmshock snapshot checksum fnv1a64-words ";     // what is written now

// The seal line of the file's bytes after the user block, by the byte hash or the word hash.
std::string file_checksum_line(std::FILE* f, std::uint64_t& length, bool words) {
  Fnv1a bytes;
  Fnv1aWords lanes;
  std::vector<unsigned char> buffer(1 << 20);
  length = 0;
  if (std::fseek(f, static_cast<long>(kUserBlock), SEEK_SET) != 0) return "";
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), f)) > 0;) {
    if (words) lanes.add(buffer.data(), n);
    else bytes.add(buffer.data(), n);
    length += n;
  }
  return std::string(words ? kWordChecksumMagic : kChecksumMagic) + hex(words ? lanes.value() : bytes.value()) +
         " bytes " + std::to_string(length) + "\n";
}

// Writes the checksum of a finished file into its user block.
void seal(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "r+b");
  if (!f) throw std::runtime_error("cannot reopen " + path + " to seal it");
  std::uint64_t length = 0;
  const std::string line = file_checksum_line(f, length, true);
  const bool ok = !line.empty() && std::fseek(f, 0, SEEK_SET) == 0 &&
                  std::fwrite(line.data(), 1, line.size(), f) == line.size() && std::fflush(f) == 0;
  std::fclose(f);
  if (!ok) throw std::runtime_error("cannot write the checksum of " + path);
}

enum class Seal { valid, absent };

// Checks a file's seal before HDF5 opens it: valid, absent (format 1, or a user block whose first
// line was damaged), or a mismatch, which throws.
Seal check_seal(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open it");
  char head[kUserBlock + 1] = {0};
  const std::size_t got = std::fread(head, 1, kUserBlock, f);
  const std::string first(head, got);
  const bool words = first.rfind(kWordChecksumMagic, 0) == 0;
  if (!words && first.rfind(kChecksumMagic, 0) != 0) {
    std::fclose(f);
    return Seal::absent;
  }
  std::uint64_t length = 0;
  const std::string line = file_checksum_line(f, length, words);
  std::fclose(f);
  if (first.compare(0, line.size(), line) != 0)
    throw std::runtime_error("damaged: its bytes do not match their checksum (a flipped bit, a cut or edited file)");
  return Seal::valid;
}

// Runs `read` in a child process first where the file has no valid seal: a crash of the HDF5
// library on a damaged file then ends the child, not this run, and is reported as damage. Some
// damaged files send the library into an endless loop, so the child has a time limit far above
// what reading a sound file of that size takes (30 s + 1 s per 10 MB), dies with this process, and
// a SIGINT/SIGTERM while it reads ends it at once. MPMSHOCK_SNAPSHOT_READ_LIMIT (seconds) replaces
// the limit.
template <class F>
void probe_in_child(const std::string& path, F&& read) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  unsigned limit_s = 30 + static_cast<unsigned>(ec ? 0 : bytes / 10'000'000);
  if (const char* v = std::getenv("MPMSHOCK_SNAPSHOT_READ_LIMIT"); v && std::atoi(v) > 0)
    limit_s = static_cast<unsigned>(std::atoi(v));  // for tests of the limit itself
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot make a pipe to check it");
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  // Heard from before the fork: a stop signal that comes while the child starts (a loaded machine
  // makes that window wide) is then acted on by the loop below, not raised again as a plain kill.
  const StopRequestsHeard heard;
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot fork to check it");
  if (pid == 0) {
    ::close(fds[0]);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(3);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    ::alarm(limit_s);
    int code = 0;
    try {
      read();
    } catch (const std::exception& e) {
      const std::string what = e.what();
      [[maybe_unused]] const ssize_t n = ::write(fds[1], what.data(), what.size());
      code = 2;
    }
    ::_exit(code);
  }
  ::close(fds[1]);
  std::string message;
  char buf[512];
  for (;;) {
    if (stop_signal() != 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
      ::close(fds[0]);
      throw std::runtime_error(std::string("not checked: stopped by ") +
                               (stop_signal() == SIGINT ? "SIGINT" : "SIGTERM") + " while reading it");
    }
    pollfd readable{fds[0], POLLIN, 0};
    if (::poll(&readable, 1, 200) <= 0) continue;  // timeout, or a signal: look at stop_signal again
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n <= 0) break;
    message.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 2) throw std::runtime_error(message);
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
    throw std::runtime_error("damaged: the HDF5 library was still reading it after " + std::to_string(limit_s) +
                             " s (a loop in a damaged file)");
  throw std::runtime_error("damaged: the HDF5 library failed reading it (" +
                           (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                                : "exit " + std::to_string(WEXITSTATUS(status))) +
                           ")");
}

}  // namespace

namespace {

// Rows [first, end) of the whole impact as points in row order (ids the rows', the mirrored flyer's
// reflected from the target points they mirror), at rank 0; every rank gives the points it holds.
template <int D>
Particles<D> snapshot_rows(const Particles<D>& p, const MirrorImage<D>& mirror, std::size_t first, std::size_t end,
                           const Comm& comm) {
  std::vector<std::uint32_t> needed;  // the simulated points these rows show, by id
  needed.reserve(end - first);
  for (std::size_t k = first; k < end; ++k) needed.push_back(mirror.source_of(static_cast<std::uint32_t>(k)).point);
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  Particles<D> have;  // those points, in id order
  if (comm.parallel()) {
    std::vector<std::size_t> mine;
    for (std::uint32_t id : needed)
      if (const std::size_t q = index_of_id(p, id); q < p.size()) mine.push_back(q);
    have.enable_fields_of(p);
    for (const std::vector<char>& part : comm.gather(pack_points(p, mine))) unpack_points(have, part);
    sort_by_id(have);
    if (!comm.root()) return {};
  }
  const Particles<D>& from = comm.parallel() ? have : p;  // one rank: a point's id is its index
  Particles<D> rows;
  rows.enable_fields_of(p);
  rows.reserve(end - first);
  for (std::size_t k = first; k < end; ++k) {
    const auto [id, mirrored] = mirror.source_of(static_cast<std::uint32_t>(k));
    rows.append_copy(from, comm.parallel() ? index_of_id(from, id) : id);
    rows.id.back() = static_cast<std::uint32_t>(k);
    if (!mirrored) continue;
    reflect_point(rows, rows.size() - 1);
    rows.body.back() = Body::flyer;
  }
  return rows;
}

// /provenance: the build (commit, compiler, flags) and the invocation (command line, start, host,
// directory, ranks) of the process that wrote the snapshot; nothing a restart reads.
void write_provenance(hid_t f) {
  Handle g(H5Gcreate2(f, "provenance", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /provenance");
  const BuildInfo& b = build_info();
  const Invocation& inv = invocation();
  h5::write_string_attribute(g.get(), "version", b.version);
  h5::write_string_attribute(g.get(), "commit", b.commit);
  h5::write_string_attribute(g.get(), "compiler", b.compiler);
  h5::write_string_attribute(g.get(), "flags", b.flags);
  h5::write_string_attribute(g.get(), "build_type", b.build_type);
  h5::write_string_attribute(g.get(), "command_line", inv.command_line);
  h5::write_string_attribute(g.get(), "working_directory", inv.working_directory);
  h5::write_string_attribute(g.get(), "host", inv.host);
  h5::write_string_attribute(g.get(), "started", inv.started);
  h5::write_int_attribute(g.get(), "ranks", inv.ranks);
}

template <int D>
void write_header(hid_t f, const RunState& run, std::size_t rows) {
  h5::write_double_attribute(f, "time", run.clock.time);
  h5::write_int_attribute(f, "step", run.clock.steps);
  h5::write_int_attribute(f, "snapshot", run.schedule.snapshot_index);
  h5::write_int_attribute(f, "particle_count", static_cast<std::int64_t>(rows));
  h5::write_string_attribute(f, "units", D == 2 ? "SI: m, s, kg, Pa, K, J/kg; 2D plane strain, extensive "
                                                  "quantities per metre of depth"
                                                : "SI: m, s, kg, Pa, K, J/kg; 3D");
  h5::write_int_attribute(f, "dimension", D);
  h5::write_string_attribute(f, "scene", run.scene_text);
  h5::write_string_attribute(f, "mpmshock_version", kVersion);
  h5::write_int_attribute(f, "format_version", 2);
  write_provenance(f);
}

}  // namespace

template <int D>
void write_snapshot(const std::string& path, const Particles<D>& p, const BodyTemperatures* thermal,
                    const RunState& run, const SnapshotOptions<D>& options) {
  h5::prepare_library();
  const Comm& comm = options.comm ? *options.comm : Comm::world();
  const MirrorImage<D> none;
  const MirrorImage<D>& mirror = options.mirror ? *options.mirror : none;
  std::int64_t simulated = static_cast<std::int64_t>(p.size());
  comm.sum(&simulated, 1);
  const std::size_t rows = (mirror.on() ? mirror.flyer_points() : 0) + static_cast<std::size_t>(simulated);
  const std::string tmp = path + ".tmp";
  // Rank 0 writes; an error there stops its writing, not the chunks every rank serves, and is then
  // every rank's (AgreedIoError in run_directory.hpp: each rank ends with exit 4).
  std::string failure;
  std::optional<Handle> file, particles, restart;
  std::vector<h5::RowWriter> writers;
  Columns<D> columns;
  auto attempt = [&](auto&& what) {
    if (!comm.root() || !failure.empty()) return;
    try {
      what();
    } catch (const std::runtime_error& e) {
      failure = e.what();
    }
  };
  attempt([&] {
    Handle create(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "make file properties");
    h5::check(H5Pset_userblock(create.get(), kUserBlock), "reserve the user block");
    file.emplace(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, create.get(), H5P_DEFAULT), H5Fclose, "create " + tmp);
    write_header<D>(file->get(), run, rows);
    particles.emplace(H5Gcreate2(file->get(), "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                      "create /particles");
    restart.emplace(H5Gcreate2(file->get(), "restart", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                    "create /restart");
    columns = particle_columns(particles->get(), p, thermal, options.compression, options.melt, options.melt_temperature);
    for (Column<D>& c : restart_columns(restart->get(), p, run)) columns.push_back(std::move(c));
    for (const Column<D>& c : columns) {
      std::vector<hsize_t> dims{rows};
      dims.insert(dims.end(), c.row_shape.begin(), c.row_shape.end());
      writers.emplace_back(c.group, c.name.c_str(), c.type, dims, c.units.c_str(), c.description.c_str(),
                           c.compression);
    }
  });
  std::vector<char> buffer;
  for (std::size_t first = 0; first < rows; first += kChunkRows) {
    const std::size_t end = std::min(rows, first + kChunkRows);
    const Particles<D> chunk = snapshot_rows(p, mirror, first, end, comm);
    attempt([&] {
      for (std::size_t k = 0; k < columns.size(); ++k) {
        buffer.resize(chunk.size() * columns[k].row_bytes);
        columns[k].fill(chunk, buffer.data());
        writers[k].write(first, chunk.size(), buffer.data());
      }
    });
  }
  attempt([&] {
    writers.clear();
    if (options.grid) write_grid(file->get(), options);
    h5::check(H5Fflush(file->get(), H5F_SCOPE_GLOBAL), "flush " + tmp);
    restart.reset();
    particles.reset();
    file.reset();
    seal(tmp);
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + ec.message());
  });
  if (comm.root() && !failure.empty()) {
    writers.clear();
    restart.reset();
    particles.reset();
    file.reset();
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    failure = "writing snapshot " + path + ": " + failure +
              " (is the disk full or the directory not writable?); earlier snapshots are complete";
  }
  comm.broadcast(failure);
  if (failure.empty()) return;
  if (comm.parallel()) throw AgreedIoError(failure);
  throw std::runtime_error(failure);
}

namespace {

SnapshotHeader read_header(const std::string& path) {
  {
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open it as HDF5");
    SnapshotHeader h;
    h.time = h5::read_double_attribute(file.get(), "time");
    h.points = static_cast<std::size_t>(h5::read_int_attribute(file.get(), "particle_count"));
    h.grid = h5::has_link(file.get(), "grid");
    h.dimension = h5::has_attribute(file.get(), "dimension") ? static_cast<int>(h5::read_int_attribute(file.get(), "dimension")) : 2;
    return h;
  }
}

}  // namespace

SnapshotHeader read_snapshot_header(const std::string& path) {
  h5::prepare_library();
  try {
    if (check_seal(path) == Seal::absent) probe_in_child(path, [&] { (void)read_header(path); });
    return read_header(path);
  } catch (const std::exception& e) {
    throw std::runtime_error("snapshot " + path + ": " + e.what());
  }
}

namespace {

template <int D>
Restart<D> read_state(const std::string& path, const PointChooser& choose) {
  {
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open it as HDF5");
    const hid_t f = file.get();
    if (!h5::has_attribute(f, "format_version") || !h5::has_link(f, "restart"))
      throw std::runtime_error("not an mpmshock snapshot with restart data");
    const std::int64_t format = h5::read_int_attribute(f, "format_version");
    if (format < 1 || format > 2)
      throw std::runtime_error("format_version " + std::to_string(format) + " is not one this mpmshock reads (1, 2)");
    const int dimension = h5::has_attribute(f, "dimension") ? static_cast<int>(h5::read_int_attribute(f, "dimension")) : 2;
    if (dimension != D) throw std::runtime_error("a " + std::to_string(dimension) + "D snapshot read as " + std::to_string(D) + "D");
    Restart<D> r;
    RunState& run = r.run;
    run.scene_text = h5::read_string_attribute(f, "scene");
    // The scene it ran says the same (no dimension line: a 2D run of an mpmshock before 3D).
    const auto line = ("\n" + run.scene_text).find("\ndimension = ");
    const int scene_dimension = line == std::string::npos ? 2 : run.scene_text[line + 12] - '0';
    if (scene_dimension != D)
      throw std::runtime_error("a " + std::to_string(D) + "D snapshot by its dimension attribute, but its scene says " +
                               "dimension = " + std::to_string(scene_dimension));
    run.clock.time = h5::read_double_attribute(f, "time");
    run.clock.steps = h5::read_int_attribute(f, "step");
    const std::int64_t count = h5::read_int_attribute(f, "particle_count");
    if (count < 1) throw std::runtime_error("particle_count " + std::to_string(count) + " is not a number of points");
    const auto n = static_cast<std::size_t>(count);
    const hsize_t d = D, C = kDeviatorComponents<D>;

    Handle rg(H5Gopen2(f, "restart", H5P_DEFAULT), H5Gclose, "open /restart");
    const hid_t g = rg.get();
    run.clock.max_signal = h5::read_double_attribute(g, "max_signal");
    run.clock.work_mismatch = h5::has_attribute(g, "work_mismatch") ? h5::read_double_attribute(g, "work_mismatch") : 0.0;
    // Without the points' own sums (an older snapshot), its total is carried as what came before.
    const bool own_mismatch = h5::has_link(g, "work_mismatch");
    run.clock.work_mismatch_before =
        !own_mismatch ? run.clock.work_mismatch
                      : (h5::has_attribute(g, "work_mismatch_before") ? h5::read_double_attribute(g, "work_mismatch_before") : 0.0);
    if (h5::has_attribute(g, "unreached_tail")) {
      const std::int64_t head = h5::read_int_attribute(g, "unreached_head"), tail = h5::read_int_attribute(g, "unreached_tail");
      if (head < 0 || tail < head) throw std::runtime_error("/restart unreached_head and unreached_tail are not a range");
      run.clock.unreached_head = static_cast<std::size_t>(head);
      run.clock.unreached_tail = static_cast<std::size_t>(tail);
    }
    run.schedule.snapshot_index = static_cast<int>(h5::read_int_attribute(g, "snapshot_index"));
    run.schedule.last_dt = h5::read_double_attribute(g, "last_dt");
    const std::vector<double> t = h5::read_doubles_attribute(g, "initial_totals");
    if (t.size() != 4 + D) throw std::runtime_error("/restart initial_totals has the wrong length");
    run.initial.mass = t[0];
    for (int k = 0; k < D; ++k) run.initial.momentum[k] = t[1 + k];
    run.initial.momentum_magnitude = t[1 + D];
    run.initial.kinetic = t[2 + D];
    run.initial.internal = t[3 + D];
    for (BodySummary* b : {&run.target, &run.flyer}) {
      b->name = b == &run.target ? "target" : "flyer";
      const std::string prefix = b->name + "_";
      b->lattice_points = static_cast<std::size_t>(h5::read_int_attribute(g, (prefix + "lattice_points").c_str()));
      b->material_points = static_cast<std::size_t>(h5::read_int_attribute(g, (prefix + "material_points").c_str()));
      const std::vector<double> extent = h5::read_doubles_attribute(g, (prefix + "extent").c_str());
      if (extent.size() == 2) {
        b->y_bottom = extent[0];
        b->y_top = extent[1];
      }
      const std::vector<double> v = h5::read_doubles(g, (prefix + "voids").c_str(), 0, {D == 3 ? 4u : 3u});
      for (std::size_t k = 0; k + D < v.size(); k += D + 1)
        b->voids.push_back(D == 3 ? Void{v[k], v[k + 1], v[k + 3], v[k + 2]} : Void{v[k], v[k + 1], v[k + 2]});
    }

    // The rows to read, of the whole impact's n (the points are in id order).
    r.total_points = n;
    const auto [first, end] = choose ? choose(run, n) : std::pair<std::size_t, std::size_t>{0, n};
    if (!(first <= end && end <= n)) throw std::logic_error("read_snapshot: rows outside the snapshot's");
    r.first_point = first;
    const h5::Rows rows{first, end};
    const std::size_t m = end - first;
    Particles<D>& p = r.points;
    const bool strength = h5::has_link(g, "deviatoric_stress"), back = h5::has_link(g, "back_stress");
    p.id = h5::read_uint32(f, "/particles/id", n, rows);
    const std::vector<std::uint8_t> body = h5::read_uint8(f, "/particles/body", n, rows);
    p.body.resize(m);
    for (std::size_t q = 0; q < m; ++q) {
      if (body[q] >= kBodies)
        throw std::runtime_error("/particles/body holds " + std::to_string(body[q]) + ", not 0, 1 or 2");
      p.body[q] = static_cast<Body>(body[q]);
    }
    unflatten(h5::read_doubles(f, "/particles/position", n, {d}, rows), p.x);
    unflatten(h5::read_doubles(f, "/particles/velocity", n, {d}, rows), p.v);
    p.m = h5::read_doubles(f, "/particles/mass", n, {}, rows);
    p.V0 = h5::read_doubles(g, "volume0", n, {}, rows);
    unflatten(h5::read_doubles(f, "/particles/deformation_gradient", n, {d, d}, rows), p.F);
    unflatten(h5::read_doubles(f, "/particles/velocity_gradient", n, {d, d}, rows), p.L);
    p.E = h5::read_doubles(f, "/particles/internal_energy", n, {}, rows);
    p.P = h5::read_doubles(f, "/particles/pressure", n, {}, rows);
    // Format 1 named the viscous pressure after the effect.
    p.q = h5::read_doubles(f, h5::has_link(f, "/particles/viscous_pressure") ? "/particles/viscous_pressure"
                                                                               : "/particles/artificial_viscosity",
                           n, {}, rows);
    p.work.assign(m, 0.0);
    p.work_mismatch = own_mismatch ? h5::read_doubles(g, "work_mismatch", n, {}, rows) : std::vector<double>(m, 0.0);
    p.enable_strength(strength, back);
    if (strength) {
      unflatten(h5::read_doubles(g, "deviatoric_stress", n, {C}, rows), p.s);
      p.eps_p = h5::read_doubles(f, "/particles/plastic_strain", n, {}, rows);
    }
    if (back) unflatten(h5::read_doubles(g, "back_stress", n, {C}, rows), p.alpha);
    p.enable_cold_work(h5::has_link(g, "stored_energy"));
    if (p.stores_cold_work()) p.E_stored = h5::read_doubles(g, "stored_energy", n, {}, rows);
    p.enable_plastic_heat(h5::has_link(g, "plastic_heat"));
    if (p.tracks_plastic_heat()) p.plastic_heat = h5::read_doubles(g, "plastic_heat", n, {}, rows);
    p.enable_failure(h5::has_link(g, "failure_J"));
    if (p.has_failure()) {
      p.failure_J = h5::read_doubles(g, "failure_J", n, {}, rows);
      p.damage = h5::read_doubles(f, "/particles/damage", n, {}, rows);
    }
    return r;
  }
}

}  // namespace

template <int D>
Restart<D> read_snapshot(const std::string& path, const PointChooser& choose) {
  h5::prepare_library();
  try {
    if (check_seal(path) == Seal::absent) probe_in_child(path, [&] { (void)read_state<D>(path, choose); });
    return read_state<D>(path, choose);
  } catch (const std::exception& e) {
    // A snapshot that cannot be restarted is a bad request (exit 2), whatever is wrong with it.
    throw SceneError("snapshot " + path + ": " + e.what());
  }
}

#define MPMSHOCK_INSTANTIATE(D)                                                                                  \
  template void write_snapshot<D>(const std::string&, const Particles<D>&, const BodyTemperatures*,            \
                                  const RunState&, const SnapshotOptions<D>&);                                    \
  template Restart<D> read_snapshot<D>(const std::string&, const PointChooser&);
MPMSHOCK_INSTANTIATE(2)
MPMSHOCK_INSTANTIATE(3)
#undef MPMSHOCK_INSTANTIATE

}  // namespace mpmshock
