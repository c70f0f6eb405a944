#include "mpmshock/run.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "mpmshock/diagnostics.hpp"
#include "mpmshock/regions.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/snapshot.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string human_time(double seconds) {
  char buf[64];
  if (seconds < 60) std::snprintf(buf, sizeof buf, "%.0fs", seconds);
  else if (seconds < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(seconds) / 60, int(seconds) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", int(seconds) / 3600, (int(seconds) % 3600) / 60);
  return buf;
}

std::string bytes_text(double b) {
  char buf[64];
  if (b < 1024.0 * 1024.0) std::snprintf(buf, sizeof buf, "%.0f KiB", b / 1024.0);
  else if (b < 1024.0 * 1024.0 * 1024.0) std::snprintf(buf, sizeof buf, "%.1f MiB", b / (1024.0 * 1024.0));
  else std::snprintf(buf, sizeof buf, "%.2f GiB", b / (1024.0 * 1024.0 * 1024.0));
  return buf;
}

// The files a run writes; --force removes exactly these, never anything else in the directory.
bool is_run_output(const fs::path& p) {
  const std::string name = p.filename().string();
  if (name == "regions.csv" || name == "conservation.csv" || name == "summary.json" || name == "scene.txt" ||
      name == "voids.csv")
    return true;
  return name.rfind("snapshot_", 0) == 0 && (p.extension() == ".h5" || p.extension() == ".tmp");
}

// Refusals that the user fixes in the scene name the output_dir key; failures of the disk are
// runtime errors (exit code 4).
void prepare_output_dir(const Scene& scene, bool force) {
  const std::string& dir = scene.output_dir;
  const std::string key = scene.where("output_dir") + ": key 'output_dir': ";
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw SceneError(key + "'" + dir + "' exists and is not a directory");
    std::vector<fs::path> earlier;
    for (const auto& entry : fs::directory_iterator(dir, ec))
      if (is_run_output(entry.path())) earlier.push_back(entry.path());
    if (!earlier.empty() && !force)
      throw SceneError(key + "'" + dir + "' holds the outputs of an earlier run; pass --force to replace them, or " +
                       "choose another output_dir");
    for (const fs::path& p : earlier) fs::remove(p, ec);
  } else {
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error("cannot create output_dir '" + dir + "': " + ec.message());
  }
  // Fail now, not after an hour of computing, if the directory cannot be written.
  const fs::path probe = fs::path(dir) / ".mpmshock-write-test";
  std::FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) throw std::runtime_error("output_dir '" + dir + "' is not writable");
  std::fclose(f);
  fs::remove(probe, ec);
}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_output(const fs::path& path) {
  File f(std::fopen(path.c_str(), "w"));
  if (!f) throw std::runtime_error("cannot open " + path.string() + " for writing");
  return f;
}

void flush_or_throw(std::FILE* f, const std::string& what) {
  if (std::fflush(f) != 0 || std::ferror(f)) throw std::runtime_error("cannot write " + what + " (disk full?)");
}

// Time of the k-th event of a periodic output; interval 0 means never (before the end).
double event_time(std::int64_t k, double interval) {
  return interval > 0.0 ? static_cast<double>(k) * interval : std::numeric_limits<double>::infinity();
}

class Progress {
 public:
  Progress(bool enabled, double end_time)
      : enabled_(enabled), end_time_(end_time), tty_(isatty(fileno(stderr))), start_(Clock::now()), last_(start_) {}

  void update(double t, std::int64_t step, double dt) {
    if (!enabled_) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (since < (tty_ ? 1.0 : 10.0)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double frac = t / end_time_;
    const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
    std::fprintf(stderr, "%s[%5.1f%%] t = %.4g ns  step %lld  dt = %.4g ns  ETA %s%s", tty_ ? "\r" : "", 100.0 * frac,
                 t * 1e9, static_cast<long long>(step), dt * 1e9, human_time(eta).c_str(), tty_ ? "   " : "\n");
    std::fflush(stderr);
    shown_ = true;
  }
  void finish() {
    if (enabled_ && tty_ && shown_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  double end_time_;
  bool tty_;
  bool shown_ = false;
  Clock::time_point start_, last_;
};

void write_summary_json(const fs::path& path, const RunResult& r) {
  File f = open_output(path);
  std::fprintf(f.get(),
               "{\n  \"exit_code\": %d,\n  \"failure\": \"%s\",\n  \"steps\": %lld,\n  \"end_time\": %.10g,\n"
               "  \"wall_seconds\": %.6g,\n  \"material_points\": %zu,\n  \"point_steps_per_second\": %.6g,\n"
               "  \"threads\": %d,\n  \"mass_error\": %.6g,\n  \"momentum_error\": %.6g,\n  \"energy_error\": %.6g,\n"
               "  \"porosity\": %.10g,\n  \"voids\": %zu\n}\n",
               r.exit_code, r.exit_code == 0 ? "" : "see stderr", static_cast<long long>(r.steps), r.end_time,
               r.wall_seconds, r.points, r.point_steps_per_second, omp_get_max_threads(), r.mass_error,
               r.momentum_error, r.energy_error, r.porosity, r.voids);
  flush_or_throw(f.get(), path.string());
}

}  // namespace

std::string describe_setup(const Scene& s, const InitialState& st) {
  std::ostringstream out;
  const GridGeometry& g = st.grid;
  auto body = [&](const BodySummary& b) {
    out << "  " << b.name << ": y " << b.y_bottom * 1e3 << " .. " << b.y_top * 1e3 << " mm, " << b.material_points
        << " material points, " << b.voids.size() << " voids, porosity " << b.porosity << "\n";
  };
  out << "scene " << s.source << "\n";
  out << "bodies (width " << s.width * 1e3 << " mm, periodic in x, impact speed +-" << s.velocity << " m/s)\n";
  body(st.target);
  body(st.flyer);
  out << "  porosity requested " << s.porosity << ", achieved " << st.porosity() << " (relative error "
      << std::abs(st.porosity() - s.porosity) / s.porosity << ")\n";
  out << "grid: " << g.nx << " x " << g.ny - 1 << " cells of " << g.h * 1e6 << " um, y " << g.y_min * 1e3 << " .. "
      << g.y_max() * 1e3 << " mm, " << g.nodes() << " nodes\n";
  out << "material points: " << st.particles.size() << " (" << s.particles_per_cell << " x " << s.particles_per_cell
      << " per cell)\n";
  const Model model(s);
  const double signal = initial_signal_speed(st.particles, model);
  const double dt0 = s.cfl * s.cell_size / signal;
  // Shocked material carries sound faster than c0; dt shrinks as the run goes, so this is a floor.
  const auto steps = static_cast<long long>(std::ceil(s.end_time / dt0));
  out << "time step: " << dt0 * 1e9 << " ns at start (cfl " << s.cfl << ", fastest signal " << signal
      << " m/s); at least " << steps << " steps to " << s.end_time * 1e9 << " ns\n";
  out << "effects: plasticity " << (s.effects.plasticity ? "on" : "off") << ", thermal "
      << (s.effects.thermal ? "on" : "off") << ", artificial viscosity "
      << (s.effects.artificial_viscosity ? "on" : "off") << ", voids " << (s.porosity > 1.0 ? "on" : "off")
      << "; update scheme " << (s.update_scheme == UpdateScheme::musl ? "MUSL" : "USL") << "\n";
  const double bytes = static_cast<double>(st.particles.size()) * (st.particles.bytes_per_point() + 8) +
                       static_cast<double>(g.nodes()) * Grid::bytes_per_node();
  out << "memory: about " << bytes_text(bytes) << " (" << st.particles.bytes_per_point() + 8 << " bytes per point, "
      << Grid::bytes_per_node() << " per node)\n";
  return out.str();
}

std::string describe_result(const RunResult& r) {
  std::ostringstream out;
  out << "steps: " << r.steps << " to t = " << r.end_time * 1e9 << " ns\n";
  out << "wall time: " << r.wall_seconds << " s on " << omp_get_max_threads() << " threads\n";
  out << "material points: " << r.points << ", point-steps per second: " << r.point_steps_per_second << "\n";
  out << "relative error: mass " << r.mass_error << ", momentum " << r.momentum_error << ", energy " << r.energy_error
      << "\n";
  out << "porosity (from material points): " << r.porosity << " with " << r.voids << " voids\n";
  return out.str();
}

RunResult run_scene(const Scene& scene, const RunOptions& options) {
  InitialState initial = build_initial_state(scene);  // SceneError on voids that cannot fit
  const fs::path dir(scene.output_dir);
  prepare_output_dir(scene, options.force);

  RunResult result;
  result.porosity = initial.porosity();
  result.voids = initial.target.voids.size() + initial.flyer.voids.size();

  const std::string scene_text = resolved_scene(scene);
  {
    File f = open_output(dir / "scene.txt");
    std::fputs(scene_text.c_str(), f.get());
    flush_or_throw(f.get(), "scene.txt");
  }

  {
    File f = open_output(dir / "voids.csv");
    std::fprintf(f.get(), "body,x,y,radius\n");
    for (const BodySummary* b : {&initial.flyer, &initial.target})
      for (const Void& v : b->voids) std::fprintf(f.get(), "%s,%.17g,%.17g,%.17g\n", b->name.c_str(), v.x, v.y, v.r);
    flush_or_throw(f.get(), "voids.csv");
  }

  std::unique_ptr<HugoniotTemperature> thermal;
  if (scene.effects.thermal) thermal = std::make_unique<HugoniotTemperature>(scene.material);
  Simulation sim(scene, std::move(initial));
  const Particles& points = sim.particles();
  result.points = points.size();

  File regions = open_output(dir / "regions.csv");
  File conservation = open_output(dir / "conservation.csv");
  std::fprintf(regions.get(), "%s\n", kRegionsHeader);
  std::fprintf(conservation.get(),
               "time,step,dt,mass,momentum_x,momentum_y,kinetic_energy,internal_energy,total_energy\n");

  const Totals start = compute_totals(points);
  double last_dt = 0.0;
  auto sample = [&] {
    write_region_rows(regions.get(), sim.time(), sample_regions(points, scene.regions, thermal.get()));
    const Totals t = compute_totals(points);
    std::fprintf(conservation.get(), "%.10g,%lld,%.6g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", sim.time(),
                 static_cast<long long>(sim.steps()), last_dt, t.mass, t.momentum_x, t.momentum_y, t.kinetic,
                 t.internal, t.total_energy());
    flush_or_throw(regions.get(), "regions.csv");
    flush_or_throw(conservation.get(), "conservation.csv");
  };
  int snapshot_index = 0;
  auto snapshot = [&] {
    char name[64];
    std::snprintf(name, sizeof name, "snapshot_%05d.h5", snapshot_index);
    write_snapshot((dir / name).string(), points, sim.model(), thermal.get(),
                   {sim.time(), sim.steps(), snapshot_index, scene_text});
    ++snapshot_index;
  };

  sample();
  snapshot();
  std::int64_t next_sample = 1, next_snapshot = 1;
  Progress progress(!options.quiet, scene.end_time);
  const auto wall_start = Clock::now();
  StepStatus status;
  while (sim.time() < scene.end_time * (1.0 - 1e-12)) {
    // Land exactly on output times; split a step that would leave a sliver into two equal ones.
    const double t_event = std::min({scene.end_time, event_time(next_sample, scene.sample_interval),
                                     event_time(next_snapshot, scene.snapshot_interval)});
    const double remaining = t_event - sim.time();
    double dt = sim.stable_time_step();
    if (dt >= remaining) dt = remaining;
    else if (2.0 * dt > remaining) dt = 0.5 * remaining;
    status = sim.step(dt);
    last_dt = dt;
    if (!status.ok()) break;
    const double tol = 1e-9 * dt;
    if (sim.time() >= event_time(next_sample, scene.sample_interval) - tol) {
      sample();
      while (event_time(next_sample, scene.sample_interval) <= sim.time() + tol) ++next_sample;
    }
    if (sim.time() >= event_time(next_snapshot, scene.snapshot_interval) - tol) {
      snapshot();
      while (event_time(next_snapshot, scene.snapshot_interval) <= sim.time() + tol) ++next_snapshot;
    }
    progress.update(sim.time(), sim.steps(), dt);
  }
  progress.finish();
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - wall_start).count();

  if (!status.ok()) {
    result.exit_code = kExitNumerical;
    result.failure = sim.describe(status);
    sample();
    snapshot();  // the state that went wrong, for inspection
  } else {
    // The end time is an output time whatever the intervals.
    const double tol = 1e-9 * last_dt;
    if (event_time(next_sample - 1, scene.sample_interval) < sim.time() - tol) sample();
    if (scene.snapshot_interval == 0.0 || event_time(next_snapshot - 1, scene.snapshot_interval) < sim.time() - tol)
      snapshot();
  }

  const Totals end = compute_totals(points);
  result.steps = sim.steps();
  result.end_time = sim.time();
  result.point_steps_per_second =
      result.wall_seconds > 0 ? static_cast<double>(points.size()) * result.steps / result.wall_seconds : 0.0;
  result.mass_error = std::abs(end.mass - start.mass) / start.mass;
  result.momentum_error = std::hypot(end.momentum_x - start.momentum_x, end.momentum_y - start.momentum_y) /
                          start.momentum_magnitude;
  result.energy_error = std::abs(end.total_energy() - start.total_energy()) / start.total_energy();
  write_summary_json(dir / "summary.json", result);
  return result;
}

}  // namespace mpmshock
