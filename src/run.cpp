#include "mpmshock/run.hpp"

#include <omp.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "mpmshock/diagnostics.hpp"
#include "mpmshock/parallel.hpp"
#include "mpmshock/regions.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/snapshot.hpp"
#include "mpmshock/temperature.hpp"
#include "mpmshock/thread_tuner.hpp"
#include "mpmshock/xdmf.hpp"

namespace mpmshock {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int sig) {
  g_stop_signal = sig;
  std::signal(sig, SIG_DFL);  // a second signal ends the program at once
}

namespace fs = std::filesystem;
using WallClock = std::chrono::steady_clock;

constexpr const char* kConservationHeader =
    "time,step,dt,mass,momentum_x,momentum_y,kinetic_energy,internal_energy,total_energy";
constexpr const char* kXdmfName = "snapshots.xdmf";

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

std::string snapshot_name(int index) {
  char name[64];
  std::snprintf(name, sizeof name, "snapshot_%05d.h5", index);
  return name;
}

// The number of a snapshot file name, or -1.
int snapshot_number(const fs::path& p) {
  const std::string name = p.filename().string();
  int k = -1;
  char tail[8] = {0};
  if (std::sscanf(name.c_str(), "snapshot_%d.%7s", &k, tail) == 2 && std::string(tail) == "h5") return k;
  return -1;
}

// The files a run writes; --force removes exactly these, never anything else in the directory.
bool is_run_output(const fs::path& p) {
  const std::string name = p.filename().string();
  for (const char* own : {"regions.csv", "conservation.csv", "summary.json", "scene.txt", "voids.csv", kXdmfName})
    if (name == own) return true;
  return name.rfind("snapshot_", 0) == 0 && (p.extension() == ".h5" || p.extension() == ".tmp");
}

// Refusals the user fixes in the scene name the output_dir key; failures of the disk are runtime
// errors (exit code 4).
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

File open_output(const fs::path& path, const char* mode = "w") {
  File f(std::fopen(path.c_str(), mode));
  if (!f) throw std::runtime_error("cannot open " + path.string() + " for writing");
  return f;
}

void flush_or_throw(std::FILE* f, const std::string& what) {
  if (std::fflush(f) != 0 || std::ferror(f)) throw std::runtime_error("cannot write " + what + " (disk full?)");
}

void write_text(const fs::path& path, const std::string& text) {
  File f = open_output(path);
  std::fputs(text.c_str(), f.get());
  flush_or_throw(f.get(), path.string());
}

void write_voids(const fs::path& path, const BodySummary& flyer, const BodySummary& target) {
  File f = open_output(path);
  std::fprintf(f.get(), "body,x,y,radius\n");
  for (const BodySummary* b : {&flyer, &target})
    for (const Void& v : b->voids) std::fprintf(f.get(), "%s,%.17g,%.17g,%.17g\n", b->name.c_str(), v.x, v.y, v.r);
  flush_or_throw(f.get(), path.string());
}

// Time of the k-th event of a periodic output; interval 0 means never (before the end).
double event_time(std::int64_t k, double interval) {
  return interval > 0.0 ? static_cast<double>(k) * interval : std::numeric_limits<double>::infinity();
}

// The end time, moved onto a sample or snapshot time that it equals up to round-off (3e-8 and
// 3 * 1e-8 differ in the last bit): a run that ends at T/2 then lands exactly where a longer run
// passes T/2, so the two step identically and a restart from there reproduces the longer run.
double landing_end_time(const Scene& s) {
  for (double interval : {s.sample_interval, s.snapshot_interval}) {
    if (!(interval > 0.0)) continue;
    const double k = std::round(s.end_time / interval);
    if (k >= 1 && std::abs(k * interval - s.end_time) <= 1e-9 * s.end_time) return k * interval;
  }
  return s.end_time;
}

// The first k with event_time(k) after t: the same rule whether the loop just wrote an event at t
// or a restart resumes at t, so both continue identically.
std::int64_t next_event_after(double t, double interval, double tol) {
  if (!(interval > 0.0)) return 1;
  auto k = static_cast<std::int64_t>(std::floor(t / interval));
  while (event_time(k, interval) <= t + tol) ++k;
  while (k > 1 && event_time(k - 1, interval) > t + tol) --k;
  return std::max<std::int64_t>(k, 1);
}

class Progress {
 public:
  Progress(bool enabled, double start, double end_time)
      : enabled_(enabled), start_(start), end_time_(end_time), tty_(isatty(fileno(stderr))),
        wall_start_(WallClock::now()), last_(wall_start_) {}

  void update(double t, std::int64_t step, double dt) {
    if (!enabled_) return;
    const auto now = WallClock::now();
    if (std::chrono::duration<double>(now - last_).count() < (tty_ ? 1.0 : 10.0)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - wall_start_).count();
    const double done = (t - start_) / (end_time_ - start_);
    const double eta = done > 0 ? elapsed * (1.0 - done) / done : 0.0;
    std::fprintf(stderr, "%s[%5.1f%%] t = %.4g ns  step %lld  dt = %.4g ns  ETA %s%s", tty_ ? "\r" : "",
                 100.0 * t / end_time_, t * 1e9, static_cast<long long>(step), dt * 1e9, human_time(eta).c_str(),
                 tty_ ? "   " : "\n");
    std::fflush(stderr);
    shown_ = true;
  }
  void finish() {
    if (enabled_ && tty_ && shown_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  double start_, end_time_;
  bool tty_;
  bool shown_ = false;
  WallClock::time_point wall_start_, last_;
};

// A material point colder than 0 K (its energy below the 0 K isotherm at its volume) is not
// physics; checked at every sample, where the temperatures are computed anyway. Returns the
// lowest index of such a point, or kNoPoint.
std::size_t first_point_below_zero_kelvin(const Particles& p, const HugoniotTemperature& thermal) {
  std::size_t first = std::numeric_limits<std::size_t>::max();
#pragma omp parallel for schedule(dynamic, kChunk) reduction(min : first)
  for (std::size_t q = 0; q < p.size(); ++q)
    if (!(thermal.temperature(p.J(q), p.energy[q]) > 0.0)) first = q < first ? q : first;
  return first;
}

// The output files of a run directory, appended to as the run goes.
class Outputs {
 public:
  Outputs(const Scene& scene, const fs::path& dir, bool append)
      : scene_(scene), dir_(dir), regions_(open_output(dir / "regions.csv", append ? "a" : "w")),
        conservation_(open_output(dir / "conservation.csv", append ? "a" : "w")) {
    if (!append) {
      std::fprintf(regions_.get(), "%s\n", kRegionsHeader);
      std::fprintf(conservation_.get(), "%s\n", kConservationHeader);
    }
    if (scene.effects.thermal) thermal_ = std::make_unique<HugoniotTemperature>(scene.material);
  }

  // Snapshots already in the directory that the XDMF index must keep listing (restart).
  void keep_listing(std::vector<XdmfSnapshot> earlier) { xdmf_ = std::move(earlier); }

  const HugoniotTemperature* thermal() const { return thermal_.get(); }

  void sample(const Simulation& sim, double dt) {
    write_region_rows(regions_.get(), sim.time(), sample_regions(sim.particles(), scene_.regions, thermal_.get()));
    const Totals t = compute_totals(sim.particles());
    std::fprintf(conservation_.get(), "%.10g,%lld,%.6g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", sim.time(),
                 static_cast<long long>(sim.steps()), dt, t.mass, t.momentum_x, t.momentum_y, t.kinetic, t.internal,
                 t.total_energy());
    flush_or_throw(regions_.get(), "regions.csv");
    flush_or_throw(conservation_.get(), "conservation.csv");
  }

  void snapshot(const Simulation& sim, const RunState& run) {
    const std::string name = snapshot_name(run.schedule.snapshot_index);
    SnapshotOptions options;
    options.compression = scene_.snapshot_compression;
    if (scene_.snapshot_grid) {
      options.grid = &sim.grid();
      options.grid_row_begin = sim.active_row_begin();
      options.grid_row_end = sim.active_row_end();
    }
    write_snapshot((dir_ / name).string(), sim.particles(), thermal_.get(), run, options);
    const GridGeometry& g = sim.grid().geo;
    xdmf_.push_back({name, sim.time(), sim.particles().size(), scene_.snapshot_grid, g.nx, g.ny, g.y_min, g.h});
    write_xdmf((dir_ / kXdmfName).string(), xdmf_);
  }

 private:
  const Scene& scene_;
  fs::path dir_;
  File regions_, conservation_;
  std::unique_ptr<HugoniotTemperature> thermal_;
  std::vector<XdmfSnapshot> xdmf_;
};

void write_summary_json(const fs::path& path, const RunResult& r) {
  const fs::path tmp = path.string() + ".tmp";
  File f = open_output(tmp);
  std::fprintf(f.get(),
               "{\n  \"exit_code\": %d,\n  \"failure\": \"%s\",\n  \"steps\": %lld,\n  \"start_time\": %.10g,\n"
               "  \"end_time\": %.10g,\n  \"wall_seconds\": %.6g,\n  \"material_points\": %zu,\n"
               "  \"point_steps_per_second\": %.6g,\n  \"threads\": %d,\n  \"steps_with_fewer_threads\": %lld,\n  \"mass_error\": %.6g,\n"
               "  \"momentum_error\": %.6g,\n  \"energy_error\": %.6g,\n  \"porosity\": %.10g,\n  \"voids\": %zu\n}\n",
               r.exit_code, r.exit_code == 0 ? "" : "see stderr", static_cast<long long>(r.steps), r.start_time,
               r.end_time, r.wall_seconds, r.points, r.point_steps_per_second, r.threads,
               static_cast<long long>(r.steps_with_fewer_threads), r.mass_error,
               r.momentum_error, r.energy_error, r.porosity, r.voids);
  flush_or_throw(f.get(), path.string());
  f.reset();
  fs::rename(tmp, path);
}

// The time loop, shared by new and restarted runs: steps that land exactly on output times,
// samples, snapshots, progress; then the closing sample and snapshot and the summary.
RunResult advance(const Scene& scene, Simulation& sim, RunState& run, Outputs& out, const fs::path& dir,
                  const RunOptions& options) {
  RunResult result;
  result.output_dir = dir.string();
  result.start_time = sim.time();
  const std::int64_t start_steps = sim.steps();
  result.porosity = static_cast<double>(run.target.lattice_points + run.flyer.lattice_points) /
                    static_cast<double>(run.target.material_points + run.flyer.material_points);
  result.voids = run.target.voids.size() + run.flyer.voids.size();
  result.points = sim.particles().size();
  OutputSchedule& sch = run.schedule;
  auto take_snapshot = [&] {
    run.clock = sim.clock();
    out.snapshot(sim, run);
    ++sch.snapshot_index;
  };

  const double end_time = landing_end_time(scene);
  Progress progress(!options.quiet, sim.time(), end_time);
  const auto wall_start = WallClock::now();
  ThreadTuner threads(options.fixed_threads ? 1 : omp_get_max_threads());
  const int all_threads = omp_get_max_threads();
  StepStatus status;
  std::size_t cold_point = std::numeric_limits<std::size_t>::max();
  while (sim.time() < end_time * (1.0 - 1e-12)) {
    // Land exactly on output times; split a step that would leave a sliver into two equal ones.
    const double t_event = std::min({end_time, event_time(sch.next_sample, scene.sample_interval),
                                     event_time(sch.next_snapshot, scene.snapshot_interval)});
    const double remaining = t_event - sim.time();
    double dt = sim.stable_time_step();
    if (dt >= remaining) dt = remaining;
    else if (2.0 * dt > remaining) dt = 0.5 * remaining;
    if (!options.fixed_threads) omp_set_num_threads(threads.threads());
    const auto step_start = WallClock::now();
    status = sim.step(dt);
    threads.record(std::chrono::duration<double>(WallClock::now() - step_start).count());
    sch.last_dt = dt;
    if (!status.ok()) break;
    if (g_stop_signal != 0) break;  // after a whole step, so the state is consistent
    const double tol = 1e-9 * dt;
    if (sim.time() >= event_time(sch.next_sample, scene.sample_interval) - tol) {
      out.sample(sim, dt);
      sch.next_sample = next_event_after(sim.time(), scene.sample_interval, tol);
      if (out.thermal()) {
        const std::size_t cold = first_point_below_zero_kelvin(sim.particles(), *out.thermal());
        if (cold != std::numeric_limits<std::size_t>::max()) {
          cold_point = cold;
          break;
        }
      }
    }
    if (sim.time() >= event_time(sch.next_snapshot, scene.snapshot_interval) - tol) {
      sch.next_snapshot = next_event_after(sim.time(), scene.snapshot_interval, tol);
      take_snapshot();
    }
    progress.update(sim.time(), sim.steps(), dt);
  }
  progress.finish();
  result.threads = all_threads;
  result.steps_with_fewer_threads = threads.steps_below_max();
  result.wall_seconds = std::chrono::duration<double>(WallClock::now() - wall_start).count();

  if (!status.ok()) {
    result.exit_code = kExitNumerical;
    result.failure = sim.describe(status);
    out.sample(sim, sch.last_dt);
    take_snapshot();  // the state that went wrong, for inspection
  } else if (cold_point != std::numeric_limits<std::size_t>::max()) {
    const Particles& p = sim.particles();
    const std::size_t q = cold_point;
    std::ostringstream why;
    why << "step " << sim.steps() << ", t = " << sim.time() << " s: material point " << p.id[q]
        << " reached a non-physical state (temperature " << out.thermal()->temperature(p.J(q), p.energy[q])
        << " K: its internal energy " << p.energy[q] << " J/kg is below the 0 K isotherm at J = " << p.J(q)
        << "); at (" << p.x[q] << ", " << p.y[q] << ") m with pressure " << p.pressure[q]
        << " Pa. Typical cause: a shock without enough artificial viscosity";
    result.exit_code = kExitNumerical;
    result.failure = why.str();
    take_snapshot();  // the state that went wrong, for inspection (its sample is written)
  } else if (g_stop_signal != 0 && sim.time() < end_time * (1.0 - 1e-12)) {
    const int sig = g_stop_signal;
    result.exit_code = 128 + sig;
    const std::string name = snapshot_name(sch.snapshot_index);
    out.sample(sim, sch.last_dt);
    take_snapshot();  // a state to restart from
    std::ostringstream why;
    why << "stopped by " << (sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal") << " at t = "
        << sim.time() * 1e9 << " ns, step " << sim.steps() << "; continue with: mpmshock --restart "
        << (dir / name).string();
    result.failure = why.str();
  } else {
    // The end time is an output time whatever the intervals.
    const double tol = 1e-9 * sch.last_dt;
    if (event_time(sch.next_sample - 1, scene.sample_interval) < sim.time() - tol) out.sample(sim, sch.last_dt);
    if (scene.snapshot_interval == 0.0 || event_time(sch.next_snapshot - 1, scene.snapshot_interval) < sim.time() - tol)
      take_snapshot();
  }

  const Totals end = compute_totals(sim.particles());
  const Totals& start = run.initial;
  result.steps = sim.steps();
  result.end_time = sim.time();
  result.point_steps_per_second =
      result.wall_seconds > 0
          ? static_cast<double>(sim.particles().size()) * static_cast<double>(sim.steps() - start_steps) /
                result.wall_seconds
          : 0.0;
  result.mass_error = std::abs(end.mass - start.mass) / start.mass;
  result.momentum_error = std::hypot(end.momentum_x - start.momentum_x, end.momentum_y - start.momentum_y) /
                          start.momentum_magnitude;
  result.energy_error = std::abs(end.total_energy() - start.total_energy()) / start.total_energy();
  omp_set_num_threads(all_threads);
  write_summary_json(dir / "summary.json", result);
  return result;
}

// A CSV row whose time (first column) is after t; rows carry 10 significant digits of time.
bool row_after(const std::string& line, double t) { return std::strtod(line.c_str(), nullptr) > t * (1.0 + 1e-9); }

// The rows of a CSV after t (the header is not a row).
std::size_t count_rows_after(const fs::path& path, double t) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::size_t n = 0;
  while (std::getline(in, line)) n += row_after(line, t);
  return n;
}

// Keeps the header and the rows of a CSV that are not after t; rewrites the file atomically.
// Returns the number of rows dropped.
std::size_t truncate_rows_after(const fs::path& path, double t) {
  std::ifstream in(path);
  if (!in) return 0;
  std::string line, kept;
  std::size_t dropped = 0;
  bool header = true;
  while (std::getline(in, line)) {
    if (header) {
      kept += line + "\n";
      header = false;
      continue;
    }
    if (!row_after(line, t)) kept += line + "\n";
    else ++dropped;
  }
  in.close();
  if (dropped > 0) {
    const fs::path tmp = path.string() + ".tmp";
    write_text(tmp, kept);
    fs::rename(tmp, path);
  }
  return dropped;
}

// Keys a restart may change: outputs and numerics. The bodies, grid and material are the state.
const std::set<std::string>& restart_changeable_keys() {
  static const std::set<std::string> keys = {
      "end_time",   "cfl",          "sample_interval", "snapshot_interval",    "snapshot_compression",
      "snapshot_grid", "output_dir", "av_linear",      "av_quadratic",         "artificial_viscosity",
      "update_scheme", "thermal"};
  return keys;
}

void check_restart_overrides(const std::string& snapshot, const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) {
    const std::string key = o.substr(0, o.find('='));
    std::string trimmed = key;
    trimmed.erase(0, trimmed.find_first_not_of(" \t"));
    trimmed.erase(trimmed.find_last_not_of(" \t") + 1);
    if (trimmed.rfind("region.", 0) == 0 || restart_changeable_keys().count(trimmed)) continue;
    throw SceneError("--set " + o + ": key '" + trimmed + "': cannot change on restart from " + snapshot +
                     " (the bodies, grid and material are part of the saved state); restart may change end_time, "
                     "cfl, sample_interval, snapshot_interval, snapshot_compression, snapshot_grid, output_dir, "
                     "av_linear, av_quadratic, artificial_viscosity, update_scheme, thermal and region.* keys");
  }
}

}  // namespace

void install_stop_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

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
  if (s.cfl > 0.5)
    out << "warning: cfl " << s.cfl << " > 0.5 was measured unstable in jetting cases (docs/stability.md)\n";
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
  out << "steps: " << r.steps << " to t = " << r.end_time * 1e9 << " ns";
  if (r.start_time > 0) out << " (restarted at " << r.start_time * 1e9 << " ns)";
  out << "\nwall time: " << r.wall_seconds << " s on " << r.threads << (r.threads == 1 ? " thread" : " threads");
  if (r.steps_with_fewer_threads > 0)
    out << " (fewer for " << r.steps_with_fewer_threads << " steps, where that measured faster: a busy machine)";
  out << "\n";
  out << "material points: " << r.points << ", point-steps per second: " << r.point_steps_per_second << "\n";
  out << "relative error: mass " << r.mass_error << ", momentum " << r.momentum_error << ", energy " << r.energy_error
      << "\n";
  out << "porosity (from material points): " << r.porosity << " with " << r.voids << " voids\n";
  out << "outputs: " << r.output_dir << "\n";
  return out.str();
}

RunResult run_scene(const Scene& scene, const RunOptions& options) {
  InitialState initial = build_initial_state(scene);  // SceneError on voids that cannot fit
  if (scene.cfl > 0.5 && !options.quiet)
    std::fprintf(stderr, "mpmshock: warning: cfl %g > 0.5 was measured unstable in jetting cases "
                 "(docs/stability.md); the run stops with a diagnostic if it goes wrong\n", scene.cfl);
  const fs::path dir(scene.output_dir);
  prepare_output_dir(scene, options.force);

  RunState run;
  run.scene_text = resolved_scene(scene);
  run.target = initial.target;
  run.flyer = initial.flyer;
  run.initial = compute_totals(initial.particles);
  write_text(dir / "scene.txt", run.scene_text);
  write_voids(dir / "voids.csv", run.flyer, run.target);

  Simulation sim(scene, initial.grid, std::move(initial.particles));
  Outputs out(scene, dir, false);
  out.sample(sim, 0.0);
  run.clock = sim.clock();
  out.snapshot(sim, run);
  run.schedule.snapshot_index = 1;
  return advance(scene, sim, run, out, dir, options);
}

RunResult restart_run(const std::string& snapshot, const std::vector<std::string>& overrides,
                      const RunOptions& options) {
  check_restart_overrides(snapshot, overrides);
  Restart r = read_snapshot(snapshot);
  const Scene scene = parse_scene(r.run.scene_text, snapshot + " (scene)", overrides);
  const double t0 = r.run.clock.time;
  if (!(scene.end_time > t0))
    throw SceneError(scene.where("end_time") + ": key 'end_time': the snapshot is at t = " + std::to_string(t0 * 1e9) +
                     " ns; set a later end_time to go on (--set end_time=...)");

  // Outputs go on where the snapshot lies, unless the restart names a new output_dir.
  const bool new_dir = std::any_of(overrides.begin(), overrides.end(),
                                   [](const std::string& o) { return o.rfind("output_dir", 0) == 0; });
  const fs::path dir = new_dir ? fs::path(scene.output_dir) : fs::absolute(snapshot).parent_path();
  const int index = r.run.schedule.snapshot_index;
  const GridGeometry grid = build_grid_geometry(scene);
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
      const std::size_t later_rows = count_rows_after(dir / "regions.csv", t0) + count_rows_after(dir / "conservation.csv", t0);
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

  Simulation sim(scene, grid, std::move(r.points), r.run.clock);
  Outputs out(scene, dir, append);
  out.keep_listing(std::move(earlier));
  // Resume the output schedule from the snapshot's time, by the rule the loop itself uses.
  const double tol = 1e-9 * r.run.schedule.last_dt;
  r.run.schedule.next_sample = next_event_after(t0, scene.sample_interval, tol);
  r.run.schedule.next_snapshot = next_event_after(t0, scene.snapshot_interval, tol);
  r.run.schedule.snapshot_index = index + 1;
  if (new_dir) {
    out.sample(sim, r.run.schedule.last_dt);  // the new directory starts at the restart time
  }
  return advance(scene, sim, r.run, out, dir, options);
}

}  // namespace mpmshock
