// Probes: material points followed through the run, written to probes.csv at their own interval
// (every step by default), the simulation's counterpart of a VISAR or PDV record. A probe names
// its points once, from the initial state (the target's top cell of points for `surface`, the
// point nearest to X Y for `point`), by id, so it follows the same material whatever happens.
// Each row is the mean over the probe's points; a row costs one pass over those points only.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "mpmshock/mirror_image.hpp"
#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

// probes.csv's header; 3D adds z and velocity_z, paper_temperature = on the column
// paper_temperature at the end.
std::string probes_header(bool paper_temperature, int dimension);

// A warning (empty if none) where the scene's probes would write more than kProbesWarnBytes to
// probes.csv, with every-step probes counted at `first_step`, the first time step (steps only get
// shorter, so that is a lower bound).
constexpr double kProbesWarnBytes = 50e6;
std::string probes_size_warning(const Scene& scene, double first_step);

template <int D>
class Probes {
 public:
  Probes() = default;
  // Resolves the scene's probes on the initial points (the state every run and restart of the
  // scene starts from) in the grid's periodic column: the points simulated, with the flyer as
  // their mirror image where that is on. On MPI ranks each rank passes a share of the points (any
  // split, every point on one rank) and every rank gets the same probes. Refuses (SceneError) a
  // point probe with no material point within a cell of it.
  Probes(const Scene& scene, const Particles<D>& initial, const GridGeometry<D>& grid, const MirrorImage<D>& mirror,
         const Comm& comm);

  bool empty() const { return probes_.empty(); }
  // The time of the first row after time t (probe_interval 0: every step).
  double next_after(double t) const;
  // One row per probe at the points' current state; with a mirror image on, a flyer point is read
  // as the mirror of the target point it is the image of.
  // On MPI ranks each rank passes its own points (in id order) and rank 0 the file; the means are
  // over every rank's.
  void write_rows(std::FILE* out, double time, const Particles<D>& p, const BodyTemperatures* thermal,
                  const MirrorImage<D>& mirror, const Comm& comm = Comm::world()) const;

 private:
  struct Probe {
    std::string name;
    std::vector<std::uint32_t> ids;
  };
  std::vector<Probe> probes_;
  double interval_ = 0.0;
};

// The scene's probes, resolved on the whole impact's initial points, of which `initial` holds this
// rank's share.
template <int D>
Probes<D> probes_of(const Scene& scene, const InitialState<D>& initial, const Comm& comm) {
  if (scene.probes.empty()) return {};
  return Probes<D>(scene, initial.particles, initial.grid, initial.mirror, comm);
}

extern template class Probes<2>;
extern template class Probes<3>;

}  // namespace mpmshock
