// Probes: material points followed through the run, written to probes.csv at their own interval
// (every step by default), the simulation's counterpart of a VISAR or PDV record. A probe names
// its points once, from the initial state (the target's top cell of points for `surface`, the
// point nearest to X Y for `point`), by id, so it follows the same material whatever happens.
// Each row is the mean over the probe's points; a row costs one pass over those points only.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "mpmshock/particles.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

extern const char* const kProbesHeader;

template <int D>
class Probes {
 public:
  Probes() = default;
  // Resolves the scene's probes on the initial points (the state every run and restart of the
  // scene starts from); `width` is the periodic column's.
  Probes(const Scene& scene, const Particles<D>& initial, double width);

  bool empty() const { return probes_.empty(); }
  // The time of the first row after time t (probe_interval 0: every step).
  double next_after(double t) const;
  // One row per probe at the points' current state.
  void write_rows(std::FILE* out, double time, const Particles<D>& p, const HugoniotTemperature* thermal) const;

 private:
  struct Probe {
    std::string name;
    std::vector<std::uint32_t> ids;
  };
  std::vector<Probe> probes_;
  double interval_ = 0.0;
};

extern template class Probes<2>;
extern template class Probes<3>;

}  // namespace mpmshock
