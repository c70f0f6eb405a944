// What accuracy and each physical effect cost: point-steps per second of one porous impact under
// every variant, measured in one process and reported as ratios to the default model, plus bytes
// per material point. Wall-clock numbers are noisy on a shared machine: each variant runs
// `repeats` times, interleaved, and the best run counts.
//
// usage: mpmshock_bench [--points N] [--steps N] [--repeats N] [--threads N]
//        mpmshock_bench threads [--repeats N]
//        mpmshock_bench speed [--repeats N] [--max-points N] [--dimension 2|3]
//
// The `threads` mode measures the default scene and a 640 k-point solid scene on 1 thread, on all
// threads, and on all threads with the thread tuner (how mpmshock runs), each on an idle machine
// and with a busy process beside it (a loop on one core, started and stopped by the benchmark).
// Like mpmshock, the benchmark starts itself again with a short OpenMP spin unless the user set a
// wait policy (src/openmp_wait.hpp), and prints which setting it ran with.
//
// The `speed` mode (issue 11) measures the speed scene, configs/speed.scene (solid plates, 5 um
// cells, 2 x 2 points per cell, +-1000 m/s), at 50 k, 640 k, 2.5 M and 10 M points (the width
// scaled) on 1 thread and on all threads: point-steps per second, bytes per point (the peak
// resident memory of a process that ran only that case, over its points), the machine's memory
// bandwidth (a STREAM triad in the same run) and the share of that bound the step reaches under a
// model of the bytes each step must move, all with every point computed; the time to solution of
// the whole speed scene with every point computed, with symmetry, and with symmetry and
// skip_unreached; the share of point-steps spent on material that nothing has reached yet
// (ahead of the elastic precursor) when it is computed; and the same plates in 3D (a square
// column, 2 x 2 x 2 points per cell) at 58 k, 640 k and 2.6 M points, beside 2D at as many points.
#include <omp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mpmshock/regions.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/temperature.hpp"
#include "mpmshock/thread_tuner.hpp"
#include "openmp_wait.hpp"

using namespace mpmshock;
using WallClock = std::chrono::steady_clock;

namespace {

struct Variant {
  const char* name;
  std::vector<std::string> settings;  // key=value overrides of the base scene
};

struct Measure {
  double best = 0.0;  // point-steps per second
  std::size_t points = 0, bytes_per_point = 0;
};

std::string base_scene(double width) {
  char text[512];
  std::snprintf(text, sizeof text,
                "velocity = 1000 m/s\nporosity = 1.1\nvoid_radius = 25 um\nwidth = %g um\ntarget_height = 1 mm\n"
                "flyer_height = 1 mm\ncell_size = 10 um\nend_time = 1 us\n",
                width * 1e6);
  return text;
}

// Point-steps per second of `steps` steps of `sim`; a step that fails ends the benchmark.
template <int D>
double timed_steps(Simulation<D>& sim, int steps) {
  const auto t0 = WallClock::now();
  for (int k = 0; k < steps; ++k) {
    const StepStatus s = sim.step(sim.stable_time_step());
    if (!s.ok()) {
      std::fprintf(stderr, "bench run stopped: %s\n", sim.describe(s).c_str());
      std::exit(1);
    }
  }
  const double seconds = std::chrono::duration<double>(WallClock::now() - t0).count();
  return static_cast<double>(sim.particles().size()) * steps / seconds;
}

// Runs `steps` steps after a 100 ns warm-up (so the shock and void collapse are under way).
double point_steps_per_second(const Scene& scene, int steps, std::size_t& points, std::size_t& bytes) {
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  points = sim.particles().size();
  bytes = sim.particles().bytes_per_point() + step_scratch_bytes<2>(scene);
  while (sim.time() < 100e-9) sim.step(sim.stable_time_step());
  return timed_steps(sim, steps);
}

// A process that keeps one core busy until it is killed: the competing load of `threads`.
pid_t start_busy_process() {
  const pid_t pid = fork();
  if (pid == 0) {
    volatile unsigned long spin = 0;
    for (;;) spin = spin + 1;
  }
  return pid;
}
void stop_busy_process(pid_t pid) {
  if (pid <= 0) return;
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
}

// Point-steps per second of `steps` steps after `warmup` steps, with `threads` threads, or with the
// thread tuner choosing up to `threads` (as mpmshock runs).
double rate_with_threads(const Scene& scene, int warmup, int steps, int threads, bool tuned) {
  omp_set_num_threads(threads);
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  for (int k = 0; k < warmup; ++k) sim.step(sim.stable_time_step());
  ThreadTuner tuner(tuned ? threads : 1);
  const auto t0 = WallClock::now();
  for (int k = 0; k < steps; ++k) {
    if (tuned) omp_set_num_threads(tuner.threads());
    const auto s0 = WallClock::now();
    sim.step(sim.stable_time_step());
    tuner.record(std::chrono::duration<double>(WallClock::now() - s0).count());
  }
  const double seconds = std::chrono::duration<double>(WallClock::now() - t0).count();
  omp_set_num_threads(threads);
  return static_cast<double>(sim.particles().size()) * steps / seconds;
}

int threads_mode(int repeats) {
  const int all = omp_get_max_threads();
  struct Case {
    const char* name;
    std::string text;
    int warmup, steps;
  };
  const std::vector<Case> cases = {
      {"default scene (36 k points)",
       "velocity = 1000 m/s\nporosity = 1.1\nvoid_radius = 25 um\nwidth = 0.5 mm\ntarget_height = 1 mm\n"
       "flyer_height = 1 mm\ncell_size = 10 um\nend_time = 300 ns\n",
       20, 400},
      {"solid plates (640 k points)",
       "porosity = 1\nwidth = 1 mm\ntarget_height = 2 mm\nflyer_height = 2 mm\ncell_size = 5 um\n"
       "end_time = 250 ns\n",
       5, 120},
  };
  std::printf("mpmshock_bench threads: point-steps per second (millions), best of %d, %d threads at most\n"
              "OpenMP waits: %s\n\n",
              repeats, all, mpmshock::openmp_wait().c_str());
  std::printf("| scene | machine | 1 thread | %d threads, fixed | %d threads, tuned (mpmshock) |\n", all, all);
  std::printf("|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    const Scene scene = parse_scene(c.text, "bench");
    for (bool busy : {false, true}) {
      const pid_t load = busy ? start_busy_process() : 0;
      double one = 0.0, fixed = 0.0, tuned = 0.0;
      for (int r = 0; r < repeats; ++r) {
        one = std::max(one, rate_with_threads(scene, c.warmup, c.steps, 1, false));
        fixed = std::max(fixed, rate_with_threads(scene, c.warmup, c.steps, all, false));
        tuned = std::max(tuned, rate_with_threads(scene, c.warmup, c.steps, all, true));
      }
      stop_busy_process(load);
      std::printf("| %s | %s | %.2f | %.2f | %.2f |\n", c.name, busy ? "one core busy" : "idle", one / 1e6,
                  fixed / 1e6, tuned / 1e6);
      std::fflush(stdout);
    }
  }
  return 0;
}

// --- speed mode -------------------------------------------------------------------------------

// configs/speed.scene with its width set to `width`, by default every point computed (symmetry and
// skip_unreached off: the cost per point-step of the method itself).
Scene speed_scene(double width, std::vector<std::string> settings = {"symmetry=off", "skip_unreached=off"}) {
  std::ifstream in(MPMSHOCK_SOURCE_DIR "/configs/speed.scene");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.empty()) {
    std::fprintf(stderr, "cannot read %s\n", MPMSHOCK_SOURCE_DIR "/configs/speed.scene");
    std::exit(1);
  }
  char w[64];
  std::snprintf(w, sizeof w, "width=%.9g", width);
  settings.push_back(w);
  return parse_scene(text, "configs/speed.scene", settings);
}

struct SpeedResult {
  double rate = 0.0;             // point-steps per second
  double peak_bytes = 0.0;       // peak resident memory of the process [bytes]
  double layout_bytes = 0.0;     // bytes per point of the particle layout and the step's scratch
  double modelled_traffic = 0.0; // bytes a step must move per point, by the model below
  std::size_t points = 0;
};

struct SolutionTime {
  std::size_t points = 0;
  std::int64_t steps = 0;
  double seconds = 0.0;
};

double peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) * 1024.0;
  return 0.0;
}

// The bytes one step must move per point if each pass over the points reads and writes only the
// fields it needs, once, and the grid stays in cache (STREAM's convention: a written byte counts
// once). Passes (transfer.hpp, constitutive.hpp): bin (x), P2G (x, F, m, V0, v, s, P, q; writes the
// stencil), G2P with the MUSL re-map (the stencil, m, v; writes v and v_pic, the grid velocity that
// moves the point), gradient, work and move (the stencil, v_pic, x, F, V0, m, P, q, s; writes L,
// work, x), point update (L, work, F, E, P, q, s, eps_p; writes F, E, P, q, s, eps_p). The stencil is the default bspline2_domain's (4 nodes per axis).
template <int D>
double modelled_traffic(const Particles<D>& p) {
  const double x = sizeof(Vec<D>), v = sizeof(Vec<D>), F = sizeof(Mat<D>), L = sizeof(Mat<D>), d = sizeof(double);
  const double st = sizeof(Stencil<support_of(ShapeFunction::bspline2_domain), D>);
  const double s = p.has_strength() ? sizeof(Deviator<D>) + d : 0.0;  // s and eps_p
  const double bin = x + 4.0;                                           // + the point's bin index
  const double p2g = x + F + 2 * d + v + s + 2 * d + st;
  const double g2p = st + d + v + v + v;
  const double move = st + v + x + F + 2 * d + 2 * d + s + (L + d + x);
  const double update = (L + d + F + 3 * d + s) + (F + 3 * d + s);
  return bin + p2g + g2p + move + update;
}

// Runs `measure` in a child process and returns what it wrote. The parent must not have started
// an OpenMP thread team before (libgomp's pool does not survive fork).
template <class Result, class Measure>
Result in_child(Measure&& measure) {
  int fd[2];
  if (pipe(fd) != 0) std::exit(1);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    const Result r = measure();
    if (write(fd[1], &r, sizeof r) != static_cast<ssize_t>(sizeof r)) _exit(1);
    _exit(0);
  }
  close(fd[1]);
  Result r{};
  const bool got = read(fd[0], &r, sizeof r) == static_cast<ssize_t>(sizeof r);
  close(fd[0]);
  waitpid(pid, nullptr, 0);
  if (!got) {
    std::fprintf(stderr, "mpmshock_bench speed: a measurement failed\n");
    std::exit(1);
  }
  return r;
}

// Runs the speed scene at `width` with `threads` threads in a child process (so its peak memory
// is its own) and returns what it measured. In 3D the column is `width` deep as well.
template <int D>
SpeedResult measure_speed(double width, int threads, int steps) {
  return in_child<SpeedResult>([&] {
    omp_set_num_threads(threads);
    char depth[64];
    std::snprintf(depth, sizeof depth, "depth=%.9g", width);
    const Scene scene = D == 2 ? speed_scene(width)
                               : speed_scene(width, {"symmetry=off", "skip_unreached=off", "dimension=3", depth});
    SpeedResult r;
    {
      InitialState<D> initial = build_initial_state<D>(scene);
      Simulation<D> sim(scene, initial.grid, std::move(initial.particles));
      r.points = sim.particles().size();
      r.layout_bytes = static_cast<double>(sim.particles().bytes_per_point() + step_scratch_bytes<D>(scene));
      r.modelled_traffic = modelled_traffic(sim.particles());
      for (int k = 0; k < 3; ++k) sim.step(sim.stable_time_step());  // first touch, shock formed
      r.rate = timed_steps(sim, steps);
      r.peak_bytes = peak_resident_bytes();
    }
    return r;
  });
}

// STREAM triad a = b + s c over arrays far larger than the caches, all threads, best of `repeats`:
// the memory bandwidth [bytes/s] in STREAM's convention (3 x 8 bytes per element).
double triad_bandwidth(int repeats) {
  const std::size_t n = std::size_t{1} << 26;  // 512 MiB per array, beyond any cache
  std::vector<double> a(n), b(n), c(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;
  double best = 0.0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = WallClock::now();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + 3.0 * c[i];
    const double seconds = std::chrono::duration<double>(WallClock::now() - t0).count();
    best = std::max(best, 3.0 * sizeof(double) * n / seconds);
  }
  if (a[n / 2] != 7.0) std::exit(1);  // keeps the loop
  return best;
}

// The share of point-steps of a run of `scene` (every point computed) spent on points that nothing
// has reached yet: still in their initial state by UnreachedMaterial's test (to round-off).
double unreached_share(const Scene& scene) {
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  const UnreachedMaterial<2> test(scene, sim.model(), sim.particles());
  double unreached = 0.0, total = 0.0;
  while (sim.time() < scene.end_time * (1 - 1e-12)) {
    sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time()));
    const Particles<2>& p = sim.particles();
    std::size_t n = 0;
    for (std::size_t q = 0; q < p.size(); ++q) n += test.reached(p, q) ? 0 : 1;
    unreached += static_cast<double>(n);
    total += static_cast<double>(p.size());
  }
  return unreached / total;
}

int speed_mode(int repeats, double max_points, int only_dimension) {
  const int all = omp_get_max_threads();
  // Widths (5 um cells, 4 mm of material, 4 points per cell: 3200 points per cell column).
  struct Size {
    const char* name;
    double width;
    int steps;
  };
  std::vector<Size> sizes = {{"50 k", 80e-6, 300}, {"640 k", 1e-3, 40}, {"2.5 M", 3.9e-3, 12}, {"10 M", 15.6e-3, 4}};
  sizes.erase(std::remove_if(sizes.begin(), sizes.end(),
                             [&](const Size& s) { return s.width / 5e-6 * 3200 > max_points * 1.01; }),
              sizes.end());
  if (only_dimension == 3) sizes.clear();
  const double bandwidth = in_child<double>([] { return triad_bandwidth(5); });
  std::printf("mpmshock_bench speed: configs/speed.scene (solid plates, 5 um cells, 2 x 2 points per cell, "
              "+-1000 m/s; every point computed: symmetry and skip_unreached off), width scaled; best of %d; %d threads "
              "at most\n",
              repeats, all);
  std::printf("memory bandwidth (STREAM triad, %d threads): %.2f GB/s\n\n", all, bandwidth / 1e9);
  std::printf("| points | threads | point-steps/s (M) | ns per point-step | bytes/point (peak RSS) | "
              "bytes/point (layout and step scratch) | modelled bytes moved per point-step | share of the bandwidth bound |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const Size& size : sizes)
    for (int threads : {1, all}) {
      SpeedResult best;
      for (int r = 0; r < repeats; ++r) {
        const SpeedResult m = measure_speed<2>(size.width, threads, size.steps);
        if (m.rate > best.rate) best = m;
      }
      const double bound = bandwidth / best.modelled_traffic;  // point-steps/s if only bandwidth counted
      std::printf("| %zu | %d | %.2f | %.1f | %.0f | %.0f | %.0f | %.1f %% |\n", best.points, threads,
                  best.rate / 1e6, 1e9 / best.rate, best.peak_bytes / best.points, best.layout_bytes,
                  best.modelled_traffic, 100.0 * best.rate / bound);
      std::fflush(stdout);
      if (all == 1) break;
    }
  // 3D: the same plates in a square column (width = depth), 2 x 2 x 2 points per cell: 1600 points
  // per (2.5 um)^2 of cross-section; at least 4 cells wide (the default shape's stencil).
  std::vector<Size> sizes_3d = {{"102 k", 20e-6, 60}, {"640 k", 50e-6, 10}, {"2.6 M", 100e-6, 3}};
  sizes_3d.erase(std::remove_if(sizes_3d.begin(), sizes_3d.end(),
                                [&](const Size& s) { return std::pow(s.width / 2.5e-6, 2) * 1600 > max_points * 1.01; }),
                 sizes_3d.end());
  if (only_dimension == 2) sizes_3d.clear();
  std::printf("\n3D: the speed scene in a column as deep as it is wide, 2 x 2 x 2 points per cell (64-node stencils), "
              "every point computed\n\n");
  std::printf("| points | threads | point-steps/s (M) | ns per point-step | bytes/point (peak RSS) | "
              "bytes/point (layout and step scratch) | cost per point-step vs 2D at the nearest size |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Size& size : sizes_3d)
    for (int threads : {1, all}) {
      SpeedResult best, best_2d;
      for (int r = 0; r < repeats; ++r) {  // 2D beside it at the same number of points, interleaved
        const SpeedResult m = measure_speed<3>(size.width, threads, size.steps);
        if (m.rate > best.rate) best = m;
        const double width_2d = std::round(static_cast<double>(m.points) / 3200.0) * 5e-6;
        const SpeedResult m2 = measure_speed<2>(std::max(width_2d, 20e-6), threads, size.steps * 3);
        if (m2.rate > best_2d.rate) best_2d = m2;
      }
      std::printf("| %zu | %d | %.2f | %.1f | %.0f | %.0f | %.2f |\n", best.points, threads, best.rate / 1e6,
                  1e9 / best.rate, best.peak_bytes / best.points, best.layout_bytes, best_2d.rate / best.rate);
      std::fflush(stdout);
      if (all == 1) break;
    }
  if (only_dimension == 3) return 0;
  // Time to solution: the whole speed scene to 250 ns, every point computed, then with each shortcut.
  std::printf("\ntime to solution: configs/speed.scene (640 k points) to 250 ns, %d threads\n\n", all);
  std::printf("| settings | points simulated | steps | wall time (s) | speed-up |\n|---|---|---|---|---|\n");
  const std::vector<std::vector<std::string>> shortcuts = {
      {"symmetry=off", "skip_unreached=off"}, {"symmetry=on", "skip_unreached=off"}, {"symmetry=on", "skip_unreached=on"}};
  double first = 0.0;
  for (const auto& settings : shortcuts) {
    const SolutionTime t = in_child<SolutionTime>([&] {
      omp_set_num_threads(all);
      const Scene scene = speed_scene(1e-3, settings);
      InitialState<2> initial = build_initial_state<2>(scene);
      Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
      const auto t0 = WallClock::now();
      while (sim.time() < scene.end_time * (1 - 1e-12))
        if (!sim.step(std::min(sim.stable_time_step(), scene.end_time - sim.time())).ok()) std::exit(1);
      return SolutionTime{sim.particles().size(), sim.steps(),
                          std::chrono::duration<double>(WallClock::now() - t0).count()};
    });
    if (first == 0.0) first = t.seconds;
    std::printf("| %s, %s | %zu | %lld | %.1f | %.2f |\n", settings[0].c_str(), settings[1].c_str(), t.points,
                static_cast<long long>(t.steps), t.seconds, first / t.seconds);
    std::fflush(stdout);
  }
  // The share ahead of the elastic precursor does not depend on the width: a narrow column of the
  // same plates, run to the end.
  const double share = unreached_share(speed_scene(50e-6));
  std::printf("\nshare of point-steps on material nothing has reached yet (F = I, v = v0), speed scene to "
              "250 ns: %.1f %%\n",
              100.0 * share);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mpmshock::prefer_short_waits(argv);  // may start the benchmark again: src/openmp_wait.hpp
  if (argc >= 2 && !std::strcmp(argv[1], "threads")) {
    const int repeats = (argc >= 4 && !std::strcmp(argv[2], "--repeats")) ? std::atoi(argv[3]) : 2;
    return threads_mode(std::max(1, repeats));
  }
  if (argc >= 2 && !std::strcmp(argv[1], "speed")) {
    int repeats = 2;
    double max_points = 1e7;
    int only_dimension = 0;
    for (int i = 2; i + 1 < argc; i += 2) {
      if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
      else if (!std::strcmp(argv[i], "--max-points")) max_points = std::atof(argv[i + 1]);
      else if (!std::strcmp(argv[i], "--dimension")) only_dimension = std::atoi(argv[i + 1]);
    }
    return speed_mode(repeats, max_points, only_dimension);
  }
  double width = 500e-6;
  int steps = 200, repeats = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--points")) width = 500e-6 * std::atof(argv[i + 1]) / 36000.0;
    else if (!std::strcmp(argv[i], "--steps")) steps = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repeats")) repeats = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads")) omp_set_num_threads(std::atoi(argv[i + 1]));
  }
  width = std::max(1, static_cast<int>(width / 10e-6 + 0.5)) * 10e-6;  // whole cells

  const std::vector<Variant> variants = {
      {"default (bspline2_domain, MUSL, all effects)", {}},
      {"shape bspline2 (the default until 2026-12-05)", {"shape_function=bspline2"}},
      {"plasticity off", {"plasticity=off"}},
      {"artificial viscosity off", {"artificial_viscosity=off"}},
      {"plasticity and viscosity off", {"plasticity=off", "artificial_viscosity=off"}},
      {"no voids (porosity 1)", {"porosity=1"}},
      {"shape bilinear", {"shape_function=bilinear"}},
      {"shape gimp", {"shape_function=gimp"}},
      {"update scheme USL", {"update_scheme=usl"}},
      {"3 x 3 points per cell", {"particles_per_cell=3"}},
      {"spall on", {"spall=on"}},
      {"heat conduction on", {"heat_conduction=on"}},
      {"thermal softening on", {"thermal_softening=on"}},
      {"taylor_quinney 0.9", {"taylor_quinney=0.9"}},
      {"flip_fraction 0.95", {"flip_fraction=0.95"}},
  };
  std::vector<Measure> m(variants.size());
  for (int r = 0; r < repeats; ++r)
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const Scene scene = parse_scene(base_scene(width), "bench", variants[v].settings);
      const double rate = point_steps_per_second(scene, steps, m[v].points, m[v].bytes_per_point);
      m[v].best = std::max(m[v].best, rate);
    }

  std::printf("mpmshock_bench: porous impact (delta 1.1, r 25 um, 1000 m/s, 10 um cells), %d steps after "
              "100 ns, best of %d, %d threads\n\n",
              steps, repeats, omp_get_max_threads());
  std::printf("| variant | points | point-steps/s | ns per point-step | time vs default | bytes/point |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (std::size_t v = 0; v < variants.size(); ++v)
    std::printf("| %s | %zu | %.3g | %.1f | %.2f | %zu |\n", variants[v].name, m[v].points, m[v].best,
                1e9 / m[v].best, m[0].best / m[v].best, m[v].bytes_per_point);

  // The thermal model costs nothing per step: temperature is a function of (J, E), evaluated only
  // when a sample or snapshot is written. Its cost is per sample.
  const Scene scene = parse_scene(base_scene(width), "bench");
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  while (sim.time() < 100e-9) sim.step(sim.stable_time_step());
  const BodyTemperatures thermal(scene.material, scene.material, scene.material);
  auto time_samples = [&](const BodyTemperatures* t) {
    double best = 1e9;
    for (int r = 0; r < 5; ++r) {
      const auto t0 = WallClock::now();
      for (int k = 0; k < 20; ++k) (void)sample_regions(sim.particles(), scene.regions, t, sim.grid().geo.cross_section());
      best = std::min(best, std::chrono::duration<double>(WallClock::now() - t0).count() / 20);
    }
    return best;
  };
  const double with = time_samples(&thermal), without = time_samples(nullptr);
  std::printf("\nthermal model: 0 per step; one regions.csv sample of %zu points takes %.2f ms with it, %.2f ms "
              "without (%.1f ns per point and sample)\n",
              sim.particles().size(), with * 1e3, without * 1e3, (with - without) * 1e9 / sim.particles().size());
  return 0;
}
