#include "mpmshock/outputs.hpp"

#include <optional>

#include "mpmshock/diagnostics.hpp"
#include "mpmshock/regions.hpp"

namespace mpmshock {

std::string conservation_header(int dimension) {
  return std::string("time,step,dt,mass,momentum_x,momentum_y,") + (dimension == 3 ? "momentum_z," : "") +
         "kinetic_energy,internal_energy,total_energy,work_mismatch";
}

template <int D>
Outputs<D>::Outputs(const Scene& scene, const fs::path& dir, ContinuedFiles continued, MirrorImage<D> mirror)
    : scene_(scene), dir_(dir), mirror_(std::move(mirror)),
      regions_(writes_ ? open_output(dir / "regions.csv", continued.regions ? "a" : "w") : File{}),
      conservation_(writes_ ? open_output(dir / "conservation.csv", continued.conservation ? "a" : "w") : File{}),
      continued_(continued), xdmf_(xdmf_path()) {
  // A band that reaches within a cell of the plane counts flyer points (their extents reach across).
  for (const RegionSpec& r : scene.regions)
    regions_need_whole_ |= mirror_.on() && r.kind == RegionSpec::Kind::band && r.a < scene.cell_size;
  if (writes_ && !continued.regions) std::fprintf(regions_.get(), "%s\n", regions_header(scene.paper_temperature).c_str());
  if (writes_ && !continued.conservation) std::fprintf(conservation_.get(), "%s\n", conservation_header(D).c_str());
}

template <int D>
void Outputs<D>::follow(Probes<D> probes, double start_time) {
  probes_ = std::move(probes);
  if (probes_.empty()) return;
  const bool append = continued_.probes;
  if (writes_) {
    probes_file_ = open_output(dir_ / "probes.csv", append ? "a" : "w");
    if (!append) std::fprintf(probes_file_.get(), "%s\n", probes_header(scene_.paper_temperature, D).c_str());
  }
  next_probe_ = append ? probes_.next_after(start_time) : start_time;
}

template <int D>
void Outputs<D>::start_rows(Simulation<D>& sim, double dt) {
  if (!probes_.empty() && !continued_.probes) write_probe_rows(sim);
  if (!continued_.regions || !continued_.conservation)
    write_samples(sim, dt, !continued_.regions, !continued_.conservation);
}

template <int D>
void Outputs<D>::write_probe_rows(const Simulation<D>& sim) {
  const BodyTemperatures* thermal = sim.model().thermal ? &*sim.model().thermal : nullptr;
  probes_.write_rows(probes_file_.get(), sim.time(), sim.particles(), thermal, mirror_, comm_);
  next_probe_ = probes_.next_after(sim.time());
}

template <int D>
void Outputs<D>::sample(Simulation<D>& sim, double dt) {
  write_samples(sim, dt, true, true);
}

template <int D>
void Outputs<D>::write_samples(Simulation<D>& sim, double dt, bool regions, bool conservation) {
  sim.settle();
  const BodyTemperatures* thermal = sim.model().thermal ? &*sim.model().thermal : nullptr;
  // Regions of the target alone see the same points either way; a band may reach into the flyer.
  std::optional<Particles<D>> whole;
  if (regions_need_whole_) whole = mirror_.with_images(sim.particles());
  const Particles<D>& points = whole ? *whole : sim.particles();
  const std::vector<RegionStats> stats =
      sample_regions(points, scene_.regions, thermal, sim.whole_grid().cross_section(), comm_);
  const Totals t = totals(sim);
  if (!writes_) return;
  if (regions) write_region_rows(regions_.get(), sim.time(), stats);
  if (conservation) {
    std::fprintf(conservation_.get(), "%.10g,%lld,%.6g,%.12g,", sim.time(), static_cast<long long>(sim.steps()), dt,
                 t.mass);
    for (int d = 0; d < D; ++d) std::fprintf(conservation_.get(), "%.12g,", t.momentum[d]);
    std::fprintf(conservation_.get(), "%.12g,%.12g,%.12g,%.12g\n", t.kinetic, t.internal, t.total_energy(),
                 mirror_.whole_sum(sim.clock().work_mismatch));
  }
  if (probes_file_) flush_or_throw(probes_file_.get(), "probes.csv");
  flush_or_throw(regions_.get(), "regions.csv");
  flush_or_throw(conservation_.get(), "conservation.csv");
}

template <int D>
void Outputs<D>::snapshot(const Simulation<D>& sim, const RunState& run, bool fast) {
  const std::string name = snapshot_name(run.schedule.snapshot_index);
  SnapshotOptions<D> options;
  options.compression = fast ? 0 : static_cast<int>(scene_.snapshot_compression);
  for (const Body b : {Body::flyer, Body::target, Body::window}) options.melt[index_of(b)] = melt_curve_of(scene_.material_of(b));
  // A body of Johnson-Cook strength melts at its law's T_m (the model's laws, resolved per body).
  for (std::size_t b = 0; b < kBodies; ++b)
    if (const JohnsonCook* jc = johnson_cook_of(sim.model().strength[b])) options.melt_temperature[b] = jc->T_m;
  std::optional<Grid<D>> gathered;  // every rank's active rows in the whole grid
  if (scene_.snapshot_grid) {
    gathered.emplace(sim.gathered_grid(options.grid_rows));
    options.grid = &*gathered;
  }
  const BodyTemperatures* thermal = sim.model().thermal ? &*sim.model().thermal : nullptr;
  options.mirror = &mirror_;
  options.comm = &comm_;
  write_snapshot((dir_ / name).string(), sim.particles(), thermal, run, options);  // every rank: its points
  if (!writes_) return;
  const GridGeometry<D>& g = sim.whole_grid();
  const std::size_t points = sim.total_points() + (mirror_.on() ? mirror_.flyer_points() : 0);
  xdmf_.add({name, sim.time(), points, scene_.snapshot_grid, g.nx, g.ny, g.y_min, g.h, D, g.nz});
}

template class Outputs<2>;
template class Outputs<3>;

}  // namespace mpmshock
