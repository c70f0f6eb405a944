// Continuing a run from one of its snapshots.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <map>
#include <set>
#include <sstream>

#include "mpmshock/outputs.hpp"
#include "mpmshock/probes.hpp"
#include "mpmshock/regions.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/run_log.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/snapshot.hpp"
#include "mpmshock/time_loop.hpp"

namespace mpmshock {

static bool scene_sets(const std::string& scene_text, const std::string& key) {
  return scene_text.rfind(key + " =", 0) == 0 || scene_text.find("\n" + key + " =") != std::string::npos;
}

// The value a scene's text gives a key on a line of its own ("" if none).
static std::string scene_value(const std::string& scene_text, const std::string& key) {
  std::istringstream in(scene_text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + " = ", 0) == 0) return line.substr(key.size() + 3);
  return "";
}

// A snapshot written before the symmetry key existed ran the whole domain: it goes on so (its
// scene would otherwise read symmetry = auto and drop its flyer). One written before
// spall_criterion existed judged spall point by point: it goes on so.
std::vector<std::string> with_old_defaults(const std::string& scene_text, std::vector<std::string> overrides) {
  if (!scene_sets(scene_text, "symmetry")) overrides.push_back("symmetry=off");
  if (!scene_sets(scene_text, "spall_criterion")) overrides.push_back("spall_criterion=point");
  // Written before the time step had a volume limit: go on without one (1e9 never binds).
  if (!scene_sets(scene_text, "max_volume_change")) overrides.push_back("max_volume_change=1e9");
  // Written before volumetric smoothing existed (2026-12-03) ran without it; its default is now
  // on for a porous scene (auto), so such a run goes on without it.
  if (!scene_sets(scene_text, "volumetric_smoothing")) overrides.push_back("volumetric_smoothing=off");
  // Written before the Steinberg-Guinan constants were each material's (2026-12-05): the bare keys
  // were every body's, so a named material a body used softened by them; it goes on so.
  std::vector<std::string> done;  // the named materials given them
  if (scene_value(scene_text, "thermal_softening") == "on" && scene_text.find(".melt_temperature = ") == std::string::npos)
    for (const char* body : {"flyer_material", "target_material", "window_material"}) {
      const std::string name = scene_value(scene_text, body);
      if (name.empty() || name == "scene" || std::count(done.begin(), done.end(), name)) continue;
      done.push_back(name);
      for (const char* key : {"softening_temperature", "melt_temperature", "lindemann_a", "pressure_hardening_scale",
                              "yield_stress_max", "latent_heat"})
        if (const std::string v = scene_value(scene_text, key); !v.empty())
          overrides.push_back("material." + name + "." + key + "=" + v);
    }
  return overrides;
}

namespace {

// Keys a restart may change: outputs and numerics. The bodies, grid and material are the state.
const std::set<std::string>& restart_changeable_keys() {
  static const std::set<std::string> keys = {
      "end_time",      "cfl",        "sample_interval", "snapshot_interval", "snapshot_compression",
      "snapshot_grid", "output_dir", "av_linear",       "av_quadratic",      "artificial_viscosity",
      "update_scheme", "thermal",  "flip_fraction", "probe_interval", "snapshot_times", "skip_unreached",
      "max_volume_change"};
  return keys;
}

// Rows appended to a CSV must have its columns: a run written by an mpmshock with other columns
// continues only in a new output_dir.
void check_csv_header(const fs::path& path, const std::string& expected, const std::string& snapshot) {
  std::ifstream in(path);
  std::string header;
  if (!in || !std::getline(in, header) || header == expected) return;
  throw SceneError(snapshot + ": " + path.string() +
                   " has the columns of another mpmshock version; continue in a new directory (--set output_dir=DIR)");
}


void check_restart_overrides(const std::string& snapshot, const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) {
    const std::string key = override_key(o);
    if (key.rfind("region.", 0) == 0 || key.rfind("probe.", 0) == 0 || restart_changeable_keys().count(key)) continue;
    std::string allowed;
    for (const std::string& k : restart_changeable_keys()) allowed += k + ", ";
    throw SceneError("--set " + o + ": key '" + key + "': cannot change on restart from " + snapshot +
                     " (the bodies, grid and material are part of the saved state); restart may change " + allowed +
                     "and region.* and probe.* keys");
  }
}

// The lines of a resolved scene that are the run's state (not changeable on restart).
std::vector<std::string> state_lines(const std::string& resolved) {
  std::vector<std::string> out;
  std::istringstream in(resolved);
  for (std::string line; std::getline(in, line);) {
    const std::string key = override_key(line);
    if (key.rfind("region.", 0) == 0 || key.rfind("probe.", 0) == 0 || restart_changeable_keys().count(key)) continue;
    out.push_back(line);
  }
  return out;
}

// A snapshot restarted in its own directory must belong to the run whose outputs are there:
// another run's snapshot copied in would mix two runs in one directory.
void check_same_run(const std::string& snapshot, const Scene& snapshot_scene, const fs::path& dir) {
  const fs::path scene_file = dir / "scene.txt";
  if (!fs::exists(scene_file)) {
    // Outputs that cannot be told from another run's are not continued.
    for (const char* csv : {"regions.csv", "conservation.csv", "probes.csv"})
      if (fs::exists(dir / csv))
        throw SceneError("snapshot " + snapshot + ": " + (dir / csv).string() + " is there but " + scene_file.string() +
                         " is not, so whether it belongs to the snapshot's run cannot be checked; restart into a " +
                         "new directory with --set output_dir=... (or put the run's scene.txt back)");
    return;
  }
  std::vector<std::string> there;
  try {
    there = state_lines(resolved_scene(load_scene(scene_file.string())));
  } catch (const SceneError&) {
    throw SceneError("snapshot " + snapshot + ": " + scene_file.string() + " does not parse, so the directory's run " +
                     "cannot be told from the snapshot's; restart into a new directory with --set output_dir=...");
  }
  const std::vector<std::string> mine = state_lines(resolved_scene(snapshot_scene));
  for (std::size_t k = 0; k < std::max(mine.size(), there.size()); ++k) {
    const std::string a = k < mine.size() ? mine[k] : "", b = k < there.size() ? there[k] : "";
    if (a == b) continue;
    throw SceneError("snapshot " + snapshot + " belongs to another run than the one in " + dir.string() +
                     ": the snapshot has '" + a + "', scene.txt has '" + b +
                     "'; restart it into a new directory with --set output_dir=...");
  }
}

// Everything read from a snapshot is checked before it is used: the clock, the schedule, the
// bodies against the scene, and every point (finite, J > 0, inside the grid). A snapshot that
// fails is refused (exit 2) naming what is wrong.
template <int D>
void validate_restart(const Restart<D>& r, const Scene& scene, const GridGeometry<D>& grid,
                      const std::string& snapshot) {
  auto bad = [&](const std::string& why) { throw SceneError("snapshot " + snapshot + ": " + why); };
  const RunState& run = r.run;
  if (!(std::isfinite(run.clock.time) && run.clock.time >= 0.0)) bad("its time is not a time");
  if (run.clock.steps < 0) bad("its step count is negative");
  if (!(std::isfinite(run.clock.max_signal) && run.clock.max_signal > 0.0)) bad("its signal speed is not positive");
  if (!std::isfinite(run.clock.work_mismatch) || !std::isfinite(run.clock.work_mismatch_before))
    bad("its work_mismatch is not finite");
  if (!(std::isfinite(run.schedule.last_dt) && run.schedule.last_dt >= 0.0)) bad("its last time step is not a time");
  const int index = run.schedule.snapshot_index;
  if (index < 0 || index > 99999) bad("its snapshot_index " + std::to_string(index) + " is out of range");
  const int own = snapshot_number(snapshot);
  if (own >= 0 && own != index)
    bad("it says it is snapshot " + std::to_string(index) + " but its file name says " + std::to_string(own));

  // The bodies as the scene builds them.
  const double a = scene.particle_spacing();
  const auto across = static_cast<std::size_t>(scene.points_across());
  const std::size_t lattice[2] = {across * static_cast<std::size_t>(std::lround(scene.target_height / a)),
                                  across * static_cast<std::size_t>(std::lround(scene.flyer_height / a))};
  const BodySummary* bodies[2] = {&run.target, &run.flyer};
  std::size_t material = 0;
  for (int b = 0; b < 2; ++b) {
    if (bodies[b]->lattice_points != lattice[b] || bodies[b]->material_points > lattice[b])
      bad("its " + bodies[b]->name + " (" + std::to_string(bodies[b]->lattice_points) +
          " lattice points) does not match its scene (" + std::to_string(lattice[b]) + ")");
    material += bodies[b]->material_points;
  }
  material += across * static_cast<std::size_t>(std::lround(scene.window_height / a));  // the window: solid
  if (r.total_points != material)
    bad("it holds " + std::to_string(r.total_points) + " points, its bodies " + std::to_string(material));

  // The points read (an MPI rank's share of them) from here on.
  const Particles<D>& p = r.points;
  const std::size_t n = p.size();
  for (std::size_t q = 0; q < n; ++q)  // snapshots hold points in id order, and restarts rely on it
    if (p.id[q] != r.first_point + q) bad("its point ids are not a numbering of its points in order");
  const Model model(scene);
  auto finite = [](const auto& values) {
    const auto* d = reinterpret_cast<const double*>(values.data());
    const std::size_t count = values.size() * sizeof(values[0]) / sizeof(double);
    return std::all_of(d, d + count, [](double v) { return std::isfinite(v); });
  };
  for (const auto* field : {&p.m, &p.V0, &p.E, &p.P, &p.q, &p.eps_p, &p.failure_J, &p.damage, &p.plastic_heat,
                            &p.work_mismatch})
    if (!finite(*field)) bad("it holds a value that is not a finite number (NaN or infinity)");
  if (p.has_failure() != scene.effects.spall)
    bad(std::string("its scene has spall = ") + (scene.effects.spall ? "on" : "off") + " but it holds " +
        (p.has_failure() ? "" : "no ") + "failure state");
  if (p.tracks_plastic_heat() != scene.tracks_plastic_heat())
    bad(std::string("its scene has temperature_model = ") +
        (scene.temperature_model == TemperatureModel::paper ? "paper" : "energy") + " and paper_temperature = " +
        (scene.paper_temperature ? "on" : "off") + " but it holds " + (p.tracks_plastic_heat() ? "" : "no ") +
        "plastic heat");
  if (std::any_of(p.plastic_heat.begin(), p.plastic_heat.end(), [](double w) { return w < 0.0; }))
    bad("it holds a negative plastic heat");
  if (std::any_of(p.failure_J.begin(), p.failure_J.end(), [](double j) { return j < 0.0; }))
    bad("it holds a negative failure_J");
  for (std::size_t q = 0; q < p.damage.size(); ++q)
    if (!(p.damage[q] >= 0.0 && p.damage[q] <= 1.0) || (p.damage[q] > 0.0 && p.failure_J[q] == 0.0))
      bad("it holds a damage outside [0, 1], or damage at a point that has not failed");
  if (!finite(p.x) || !finite(p.v) || !finite(p.F) || !finite(p.L) || !finite(p.s) || !finite(p.alpha))
    bad("it holds a value that is not a finite number (NaN or infinity)");
  std::visit(
      [&](auto shape) {
        using Shape = decltype(shape);
        for (std::size_t q = 0; q < n; ++q) {
          const std::string which = "point " + std::to_string(p.id[q]);
          if (!(p.m[q] > 0.0 && p.V0[q] > 0.0)) bad(which + " has no mass or volume");
          if (!(p.J(q) > model.limiting_compression(p.body[q]))) bad(which + " has J = det F = " + std::to_string(p.J(q)) + ", not a volume");
          const Vec<D>& x = p.x[q];
          if (!(x[0] >= 0.0 && x[0] < grid.width())) bad(which + " lies outside the column (x = " + std::to_string(x[0]) + " m)");
          if constexpr (D == 3)
            if (!(x[2] >= 0.0 && x[2] < grid.depth())) bad(which + " lies outside the column (z)");
          const int row = Shape::first_row(x[1], grid);
          if (!(row >= 0 && row <= grid.ny - Shape::support)) bad(which + " lies outside the grid (y = " + std::to_string(x[1]) + " m)");
        }
      },
      model.shape);
}

// The ids [first, end) of this rank's share of the points a restart simulates: with symmetry = on
// the target's, ids from flyer_points on in the snapshot's whole impact. Symmetry cannot change on
// restart, so the snapshot's own scene says.
std::pair<std::size_t, std::size_t> share_of_snapshot(const RunState& run, std::size_t n, const std::string& snapshot,
                                                      const Comm& comm) {
  const Scene own = parse_scene(run.scene_text, snapshot + " (scene)", with_old_defaults(run.scene_text, {}));
  const std::size_t from = own.symmetry == Symmetry::on ? std::min(run.flyer.material_points, n) : 0;
  const auto rank = static_cast<std::uint64_t>(comm.rank()), ranks = static_cast<std::uint64_t>(comm.size());
  const std::uint64_t simulated = n - from;
  return {from + rank * simulated / ranks, from + (rank + 1) * simulated / ranks};
}

// A restart may name new regions and probes, not give an existing name another meaning: one
// column of regions.csv or probes.csv would then hold two things under one name.
void check_same_names(const std::string& snapshot, const Scene& own, const Scene& scene) {
  std::map<std::string, std::string> before;
  std::istringstream in(resolved_scene(own));
  for (std::string line; std::getline(in, line);) {
    const std::string key = override_key(line);
    if (key.rfind("region.", 0) == 0 || key.rfind("probe.", 0) == 0) before[key] = line;
  }
  std::istringstream now(resolved_scene(scene));
  for (std::string line; std::getline(now, line);) {
    const std::string key = override_key(line);
    const auto it = before.find(key);
    if (it == before.end() || it->second == line) continue;
    throw SceneError(scene.where(key) + ": key '" + key + "': the run of " + snapshot + " already has '" +
                     it->second + "', whose series its " + (key[0] == 'r' ? "regions.csv" : "probes.csv") +
                     " holds; a restart may add a " + (key[0] == 'r' ? "region" : "probe") +
                     " under a new name but not redefine one");
  }
}

// Prepares the snapshot's own directory (locked) for the run to go on there: the run there must be the
// snapshot's, the outputs after the snapshot are dropped (with --force), and the CSVs that are
// there are continued. Returns which; `earlier` gets the snapshots the XDMF index keeps listing.
template <int D>
ContinuedFiles continue_in_place(const std::string& snapshot, const Scene& own, const Scene& scene,
                                 const fs::path& dir, int index, double t0, const GridGeometry<D>& grid, bool force,
                                 std::vector<XdmfSnapshot>& earlier) {
  check_same_run(snapshot, own, dir);
  const char* csvs[3] = {"regions.csv", "conservation.csv", "probes.csv"};
  check_csv_header(dir / csvs[0], regions_header(scene.paper_temperature), snapshot);
  check_csv_header(dir / csvs[1], conservation_header(D), snapshot);
  check_csv_header(dir / csvs[2], probes_header(scene.paper_temperature, D), snapshot);
  // Later snapshots and rows belong to the continuation this restart replaces.
  std::vector<fs::path> later;
  for (const auto& e : fs::directory_iterator(dir))
    if (snapshot_number(e.path()) > index) later.push_back(e.path());
  if (!force) {
    std::size_t later_rows = 0;
    for (const char* csv : csvs) later_rows += count_rows_after(dir / csv, t0);
    if (!later.empty() || later_rows > 0)
      throw SceneError(snapshot + ": restarting here discards " + std::to_string(later.size()) +
                       " later snapshot(s) and " + std::to_string(later_rows) +
                       " later row(s) of regions.csv, conservation.csv and probes.csv; pass --force to replace them");
  }
  // What a killed run left half-written goes too (the complete files it replaced are there).
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0 && is_run_output(e.path()))
      later.push_back(e.path());
  }
  for (const fs::path& p : later) fs::remove(p);
  for (const char* csv : csvs) truncate_rows_after(dir / csv, t0);
  for (int k = 0; k <= index; ++k) {
    const fs::path p = dir / snapshot_name(k);
    if (!fs::exists(p)) continue;
    try {
      const SnapshotHeader h = read_snapshot_header(p.string());
      earlier.push_back(
          {p.filename().string(), h.time, h.points, h.grid, grid.nx, grid.ny, grid.y_min, grid.h, D, grid.nz});
    } catch (const std::exception& e) {
      say(stderr, "mpmshock: warning: " + p.string() + " is left out of " + kXdmfName + ": " + e.what() + "\n");
    }
  }
  return {fs::exists(dir / csvs[0]), fs::exists(dir / csvs[1]), fs::exists(dir / csvs[2])};
}

template <int D>
RunResult restart_from(const std::string& snapshot, const std::vector<std::string>& overrides,
                       const RunOptions& options) {
  const Comm& comm = Comm::world();
  // Each rank reads its share of the points (one rank: all of them); they move to their slabs' ranks.
  // A damaged row is one rank's to find; every rank stops on it.
  Restart<D> r;
  on_every_rank(comm, [&] {
    r = read_snapshot<D>(snapshot, [&](const RunState& run, std::size_t n) {
      return share_of_snapshot(run, n, snapshot, comm);
    });
  });
  const Scene own = parse_scene(r.run.scene_text, snapshot + " (scene)", with_old_defaults(r.run.scene_text, {}));
  Scene scene = parse_scene(r.run.scene_text, snapshot + " (scene)", with_old_defaults(r.run.scene_text, overrides));
  check_same_names(snapshot, own, scene);
  on_every_rank(comm, [&] { check_fits<D>(scene, comm.size(), comm.node_ranks()); });
  const double t0 = r.run.clock.time;
  if (!(scene.end_time > t0))
    throw SceneError(scene.where("end_time") + ": key 'end_time': the snapshot is at t = " + std::to_string(t0 * 1e9) +
                     " ns; set a later end_time to go on (--set end_time=...)");

  // Outputs go on where the snapshot lies, unless the restart names a new output_dir; scene.txt
  // says where they are.
  const bool new_dir = std::any_of(overrides.begin(), overrides.end(),
                                   [](const std::string& o) { return override_key(o) == "output_dir"; });
  const fs::path dir = new_dir ? fs::path(scene.output_dir) : fs::absolute(snapshot).parent_path();
  std::error_code ec;  // the scene's own output_dir where that is the snapshot's directory, else this one
  if (!new_dir && !fs::equivalent(own.output_dir, dir, ec)) scene.output_dir = dir.string();
  const int index = r.run.schedule.snapshot_index;
  const GridGeometry<D> grid = build_grid_geometry<D>(scene);
  on_every_rank(comm, [&] { validate_restart(r, scene, grid, snapshot); });  // each rank its share

  // Probes and the mirror image come from the initial state, as the run made them (and only they
  // are kept of it; each rank makes a share of its rows). A snapshot holds the whole impact; with
  // symmetry = on the target's points go on. All of it before the directory is touched: a restart
  // refused writes nothing.
  MirrorImage<D> mirror;
  Probes<D> probes;
  if (!scene.probes.empty() || scene.symmetry == Symmetry::on) {
    const InitialState<D> initial = InitialBuilder<D>(scene).build_share(comm.rank(), comm.size());
    probes = probes_of(scene, initial, comm);
    mirror = initial.mirror;
  }
  if (mirror.on()) r.points = mirror.half(r.points, r.first_point);
  std::optional<Simulation<D>> simulation;
  try {  // the saved unreached material is checked against the points
    simulation.emplace(scene, grid, std::move(r.points), r.run.clock);
  } catch (const SceneError& e) {
    throw SceneError("snapshot " + snapshot + ": " + e.what());
  }
  Simulation<D>& sim = *simulation;
  if (comm.root()) print_scene_warnings(scene, sim.stable_time_step());

  std::vector<XdmfSnapshot> earlier;
  ContinuedFiles continued;
  DirectoryLock lock;
  on_root(comm, [&] {  // the directory is rank 0's
    if (new_dir) {
      lock = prepare_output_dir(scene, options.force);
    } else {
      lock = DirectoryLock(dir, snapshot + ": ");
      continued = continue_in_place(snapshot, own, scene, dir, index, t0, grid, options.force, earlier);
    }
    open_run_log(dir, !new_dir);
    write_text(dir / "scene.txt", resolved_scene(scene));
    if (!fs::exists(dir / "voids.csv")) write_voids(dir / "voids.csv", r.run.flyer, r.run.target, D);
  });
  r.run.scene_text = resolved_scene(scene);
  // Which CSVs go on is rank 0's finding; every rank's output schedule follows it (probes.csv's
  // next row time, the first rows' sums).
  std::string flags = comm.root() ? std::string{continued.regions ? '1' : '0', continued.conservation ? '1' : '0',
                                                continued.probes ? '1' : '0'}
                                  : "";
  comm.broadcast(flags);
  continued = {flags[0] == '1', flags[1] == '1', flags[2] == '1'};
  Outputs<D> out(scene, dir, continued, std::move(mirror));
  if (!probes.empty()) out.follow(std::move(probes), sim.time());
  out.keep_listing(std::move(earlier));
  // Resume the output schedule from the snapshot's time, by the rule the loop itself uses.
  resume_schedule(r.run.schedule, scene, t0, 1e-9 * r.run.schedule.last_dt);
  r.run.schedule.snapshot_index = index + 1;
  out.start_rows(sim, r.run.schedule.last_dt);  // a file that starts here starts at the restart time
  return advance(scene, sim, r.run, out, dir, options);
}

}  // namespace

// The dimension a snapshot says it holds; 2 where it cannot be read, so that the full read that
// follows reports what is wrong with the file as it always has.
int snapshot_dimension(const std::string& snapshot) {
  try {
    return read_snapshot_header(snapshot).dimension;
  } catch (const std::exception&) {
    return 2;
  }
}

RunResult restart_run(const std::string& snapshot, const std::vector<std::string>& overrides,
                      const RunOptions& options) {
  check_input_file(snapshot, "snapshot");
  check_restart_overrides(snapshot, overrides);
  return snapshot_dimension(snapshot) == 3 ? restart_from<3>(snapshot, overrides, options)
                                           : restart_from<2>(snapshot, overrides, options);
}

namespace {

template <int D>
std::string check_restart_in(const std::string& snapshot, const std::vector<std::string>& overrides) {
  Restart<D> r = read_snapshot<D>(snapshot);
  const Scene scene =
      parse_scene(r.run.scene_text, snapshot + " (scene)", with_old_defaults(r.run.scene_text, overrides));
  const Comm& comm = Comm::world();  // refuse on mpirun what the restart on as many ranks refuses
  check_fits<D>(scene, comm.size(), comm.node_ranks());
  validate_restart(r, scene, build_grid_geometry<D>(scene), snapshot);
  std::ostringstream out;
  out << "snapshot " << snapshot << ": t = " << r.run.clock.time * 1e9 << " ns, step " << r.run.clock.steps << ", "
      << r.points.size() << " material points; checksum and state valid\n";
  return out.str();
}

}  // namespace

std::string check_restart(const std::string& snapshot, const std::vector<std::string>& overrides) {
  check_input_file(snapshot, "snapshot");
  check_restart_overrides(snapshot, overrides);
  return snapshot_dimension(snapshot) == 3 ? check_restart_in<3>(snapshot, overrides)
                                           : check_restart_in<2>(snapshot, overrides);
}

}  // namespace mpmshock
