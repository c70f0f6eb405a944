#include "mpmshock/run.hpp"

#include <cstdio>
#include <sstream>

#include "mpmshock/diagnostics.hpp"
#include "mpmshock/probes.hpp"
#include "mpmshock/run_log.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/time_loop.hpp"

namespace mpmshock {

namespace {

// Everything that can fail for the scene's sake (its size, its voids) and every allocation comes
// before the output directory is touched: a refused or impossible run deletes and writes nothing.
template <int D>
RunResult run_new(const Scene& scene, const RunOptions& options) {
  const Comm& comm = Comm::world();
  on_every_rank(comm, [&] { check_fits<D>(scene, comm.size(), comm.node_ranks()); });  // each its machine
  // Each rank makes the points of its share of the rows only (on one rank: all of them).
  InitialState<D> initial = InitialBuilder<D>(scene).build_share(comm.rank(), comm.size());  // SceneError on voids that cannot fit
  RunState run;
  run.scene_text = resolved_scene(scene);
  run.target = initial.target;
  run.flyer = initial.flyer;
  run.initial = initial.mirror.whole(compute_totals(initial.particles, comm));  // summed as every later total is
  Probes<D> probes = probes_of(scene, initial, comm);
  Simulation<D> sim(scene, initial.grid, std::move(initial.particles));
  if (comm.root()) print_scene_warnings(scene, sim.stable_time_step());

  const fs::path dir(scene.output_dir);
  DirectoryLock lock;  // rank 0 writes the directory
  on_root(comm, [&] {
    lock = prepare_output_dir(scene, options.force);
    open_run_log(dir, false);
    write_text(dir / "scene.txt", run.scene_text);
    write_voids(dir / "voids.csv", run.flyer, run.target, D);
  });
  Outputs<D> out(scene, dir, {}, std::move(initial.mirror));
  out.follow(std::move(probes), sim.time());
  out.start_rows(sim, 0.0);
  run.clock = sim.clock();
  out.snapshot(sim, run);
  run.schedule.snapshot_index = 1;
  return advance(scene, sim, run, out, dir, options);
}

}  // namespace

void print_scene_warnings(const Scene& scene, double first_step) {
  std::vector<std::string> warnings = scene_warnings(scene);
  if (const std::string probes = probes_size_warning(scene, first_step); !probes.empty()) warnings.push_back(probes);
  for (const std::string& w : warnings) say(stderr, "mpmshock: warning: " + w + "\n");
}

RunResult run_scene(const Scene& scene, const RunOptions& options) {
  return scene.dimension == 3 ? run_new<3>(scene, options) : run_new<2>(scene, options);
}

std::string describe_result(const RunResult& r) {
  std::ostringstream out;
  out << "steps: " << r.steps << " to t = " << r.end_time * 1e9 << " ns";
  if (r.start_time > 0) out << " (restarted at " << r.start_time * 1e9 << " ns)";
  out << "\nwall time: " << r.wall_seconds << " s on ";
  if (r.ranks > 1) out << r.ranks << " MPI ranks x ";
  out << r.threads << (r.threads == 1 ? " thread" : " threads");
  if (r.steps_with_fewer_threads > 0)
    out << " (fewer for " << r.steps_with_fewer_threads << " steps, where that measured faster: a busy machine)";
  if (r.ranks > 1) out << "; the largest rank's work is " << r.imbalance << " x the mean";
  if (r.step_share < 0.9)
    out << "\nsteps: on average " << r.step_share << " of the step cfl allows, cut to land on sample or snapshot times"
        << " (an output interval shorter than the step sets it)";
  out << "\n";
  out << "material points: " << r.points;
  if (r.symmetry) out << " simulated (the target; symmetry = on: the flyer is its mirror image, " << 2 * r.points
                      << " points in the outputs)";
  out << ", point-steps per second: " << r.point_steps_per_second << "\n";
  out << "relative error: mass " << r.mass_error << ", momentum " << r.momentum_error << ", energy " << r.energy_error
      << "\n";
  out << "porosity (from material points): " << r.porosity << " with " << r.voids << " voids\n";
  if (r.beyond_eos_fit > 0)
    out << "warning: up to " << r.beyond_eos_fit << " material points were compressed past the equation of state's fit "
        << "(J < " << r.beyond_eos_fit_J << ", fit_particle_velocity): their states are extrapolated\n";
  out << "outputs: " << r.output_dir << "\n";
  return out.str();
}

}  // namespace mpmshock
