// Continuing a run from one of its snapshots.
#include <algorithm>
#include <set>
#include <sstream>

#include "mpmshock/run.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/snapshot.hpp"
#include "mpmshock/time_loop.hpp"

namespace mpmshock {
namespace {

// Keys a restart may change: outputs and numerics. The bodies, grid and material are the state.
const std::set<std::string>& restart_changeable_keys() {
  static const std::set<std::string> keys = {
      "end_time",      "cfl",        "sample_interval", "snapshot_interval", "snapshot_compression",
      "snapshot_grid", "output_dir", "av_linear",       "av_quadratic",      "artificial_viscosity",
      "update_scheme", "thermal"};
  return keys;
}

void check_restart_overrides(const std::string& snapshot, const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) {
    const std::string key = override_key(o);
    if (key.rfind("region.", 0) == 0 || restart_changeable_keys().count(key)) continue;
    std::string allowed;
    for (const std::string& k : restart_changeable_keys()) allowed += k + ", ";
    throw SceneError("--set " + o + ": key '" + key + "': cannot change on restart from " + snapshot +
                     " (the bodies, grid and material are part of the saved state); restart may change " + allowed +
                     "and region.* keys");
  }
}

template <int D>
RunResult restart_from(const std::string& snapshot, const std::vector<std::string>& overrides,
                       const RunOptions& options) {
  Restart<D> r = read_snapshot<D>(snapshot);
  const Scene scene = parse_scene(r.run.scene_text, snapshot + " (scene)", overrides);
  const double t0 = r.run.clock.time;
  if (!(scene.end_time > t0))
    throw SceneError(scene.where("end_time") + ": key 'end_time': the snapshot is at t = " + std::to_string(t0 * 1e9) +
                     " ns; set a later end_time to go on (--set end_time=...)");

  // Outputs go on where the snapshot lies, unless the restart names a new output_dir.
  const bool new_dir = std::any_of(overrides.begin(), overrides.end(),
                                   [](const std::string& o) { return override_key(o) == "output_dir"; });
  const fs::path dir = new_dir ? fs::path(scene.output_dir) : fs::absolute(snapshot).parent_path();
  const int index = r.run.schedule.snapshot_index;
  const GridGeometry<D> grid = build_grid_geometry<D>(scene);
  std::vector<XdmfSnapshot> earlier;
  bool append = false;
  if (new_dir) {
    prepare_output_dir(scene, options.force);
  } else {
    // Later snapshots and rows belong to the continuation this restart replaces.
    std::vector<fs::path> later;
    for (const auto& e : fs::directory_iterator(dir))
      if (snapshot_number(e.path()) > index) later.push_back(e.path());
    if (!options.force) {
      const std::size_t later_rows =
          count_rows_after(dir / "regions.csv", t0) + count_rows_after(dir / "conservation.csv", t0);
      if (!later.empty() || later_rows > 0)
        throw SceneError(snapshot + ": restarting here discards " + std::to_string(later.size()) +
                         " later snapshot(s) and " + std::to_string(later_rows) +
                         " later row(s) of regions.csv and conservation.csv; pass --force to replace them");
    }
    for (const fs::path& p : later) fs::remove(p);
    truncate_rows_after(dir / "regions.csv", t0);
    truncate_rows_after(dir / "conservation.csv", t0);
    append = fs::exists(dir / "regions.csv") && fs::exists(dir / "conservation.csv");
    for (int k = 0; k <= index; ++k) {
      const fs::path p = dir / snapshot_name(k);
      if (!fs::exists(p)) continue;
      const SnapshotHeader h = read_snapshot_header(p.string());
      earlier.push_back({p.filename().string(), h.time, h.points, h.grid, grid.nx, grid.ny, grid.y_min, grid.h});
    }
  }
  r.run.scene_text = resolved_scene(scene);
  write_text(dir / "scene.txt", r.run.scene_text);
  if (!fs::exists(dir / "voids.csv")) write_voids(dir / "voids.csv", r.run.flyer, r.run.target);

  Simulation<D> sim(scene, grid, std::move(r.points), r.run.clock);
  Outputs<D> out(scene, dir, append);
  out.keep_listing(std::move(earlier));
  // Resume the output schedule from the snapshot's time, by the rule the loop itself uses.
  resume_schedule(r.run.schedule, scene, t0, 1e-9 * r.run.schedule.last_dt);
  r.run.schedule.snapshot_index = index + 1;
  if (new_dir) out.sample(sim, r.run.schedule.last_dt);  // the new directory starts at the restart time
  return advance(scene, sim, r.run, out, dir, options);
}

}  // namespace

RunResult restart_run(const std::string& snapshot, const std::vector<std::string>& overrides,
                      const RunOptions& options) {
  check_restart_overrides(snapshot, overrides);
  return restart_from<2>(snapshot, overrides, options);
}

}  // namespace mpmshock
