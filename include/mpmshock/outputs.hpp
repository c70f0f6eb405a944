// The output files of a run directory that grow as the run goes: regions.csv and
// conservation.csv (one row per sample), the snapshots and their XDMF index. On MPI ranks every
// rank computes its share of each row (sums across ranks: comm.hpp) and rank 0 writes the files; a
// snapshot gathers every rank's points at rank 0, which writes the one file.
#pragma once

#include <string>
#include <vector>

#include "mpmshock/mirror_image.hpp"
#include "mpmshock/probes.hpp"
#include "mpmshock/run_directory.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/snapshot.hpp"
#include "mpmshock/xdmf.hpp"

namespace mpmshock {

// conservation.csv's header for a D-dimensional run.
std::string conservation_header(int dimension);

// The CSV files a restart continues: each is appended to where it is (and belongs to the run);
// the others start anew, with a row at the restart time.
struct ContinuedFiles {
  bool regions = false, conservation = false, probes = false;
};

template <int D>
class Outputs {
 public:
  // Opens regions.csv and conservation.csv in `dir`: new (with headers), or appended to where
  // `continued` says so (restart). With a mirror image on, the outputs show the whole impact, the
  // flyer as the target's mirror image (mirror_image.hpp). On MPI ranks every rank passes rank 0's
  // `continued`.
  Outputs(const Scene& scene, const fs::path& dir, ContinuedFiles continued = {}, MirrorImage<D> mirror = {});

  // Probes to follow (probes.csv, new or appended to like the other CSVs); none: no file.
  void follow(Probes<D> probes, double start_time);
  // The first row, at the simulation's time, of every CSV file that is new (all of them in a new
  // run; in a restart those it does not continue).
  void start_rows(Simulation<D>& sim, double dt);
  // probes.csv rows when due (every step, or every probe_interval).
  void probe(const Simulation<D>& sim) {
    if (probes_.empty() || sim.time() < next_probe_ * (1.0 - 1e-12)) return;
    write_probe_rows(sim);
  }

  // Snapshots already in the directory that the XDMF index must keep listing (restart).
  void keep_listing(std::vector<XdmfSnapshot> earlier) {
    if (writes_) xdmf_ = XdmfIndex(xdmf_path(), std::move(earlier));
  }

  // One row per region in regions.csv and one in conservation.csv, at the simulation's time.
  void sample(Simulation<D>& sim, double dt);
  // snapshot_NNNNN.h5 (NNNNN = run.schedule.snapshot_index) and the XDMF index; `fast`: without
  // the scene's compression (the snapshot of a stop, which mpirun may kill a second later).
  void snapshot(const Simulation<D>& sim, const RunState& run, bool fast = false);
  // The conserved totals of the whole impact.
  Totals totals(const Simulation<D>& sim) const { return mirror_.whole(compute_totals(sim.particles(), comm_)); }

 private:
  const Scene& scene_;
  const Comm& comm_ = Comm::world();
  bool writes_ = comm_.root();  // this rank writes the files
  fs::path dir_;
  MirrorImage<D> mirror_;
  bool regions_need_whole_ = false;  // a band region counts flyer points too
  std::string xdmf_path() const { return (dir_ / kXdmfName).string(); }
  void write_probe_rows(const Simulation<D>& sim);
  void write_samples(Simulation<D>& sim, double dt, bool regions, bool conservation);
  File regions_, conservation_, probes_file_;
  Probes<D> probes_;
  double next_probe_ = 0.0;
  ContinuedFiles continued_;
  XdmfIndex xdmf_;
};

extern template class Outputs<2>;
extern template class Outputs<3>;

}  // namespace mpmshock
