// What accuracy and each physical effect cost: point-steps per second of one porous impact under
// every variant, measured in one process and reported as ratios to the default model, plus bytes
// per material point. Wall-clock numbers are noisy on a shared machine: each variant runs
// `repeats` times, interleaved, and the best run counts.
//
// usage: mpmshock_bench [--points N] [--steps N] [--repeats N] [--threads N]
//        mpmshock_bench threads [--repeats N]
//
// The `threads` mode measures the default scene and a 640 k-point solid scene on 1 thread, on all
// threads, and on all threads with the thread tuner (how mpmshock runs), each on an idle machine
// and with a busy process beside it (a loop on one core, started and stopped by the benchmark).
#include <omp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mpmshock/regions.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/temperature.hpp"
#include "mpmshock/thread_tuner.hpp"

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

// Runs `steps` steps after a 100 ns warm-up (so the shock and void collapse are under way).
double point_steps_per_second(const Scene& scene, int steps, std::size_t& points, std::size_t& bytes) {
  InitialState<2> initial = build_initial_state<2>(scene);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  points = sim.particles().size();
  bytes = sim.particles().bytes_per_point();
  while (sim.time() < 100e-9) sim.step(sim.stable_time_step());
  const auto t0 = WallClock::now();
  for (int k = 0; k < steps; ++k) {
    const StepStatus s = sim.step(sim.stable_time_step());
    if (!s.ok()) {
      std::fprintf(stderr, "bench run stopped: %s\n", sim.describe(s).c_str());
      std::exit(1);
    }
  }
  const double seconds = std::chrono::duration<double>(WallClock::now() - t0).count();
  return static_cast<double>(points) * steps / seconds;
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
  std::printf("mpmshock_bench threads: point-steps per second (millions), best of %d, %d threads at most\n\n",
              repeats, all);
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

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && !std::strcmp(argv[1], "threads")) {
    const int repeats = (argc >= 4 && !std::strcmp(argv[2], "--repeats")) ? std::atoi(argv[3]) : 2;
    return threads_mode(std::max(1, repeats));
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
      {"default (bspline2, MUSL, all effects)", {}},
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
  const HugoniotTemperature thermal(scene.material);
  auto time_samples = [&](const HugoniotTemperature* t) {
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
