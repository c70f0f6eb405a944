// When numbers go bad the step says so at once, naming the point: a NaN, J <= 0, compression past
// the Hugoniot's limit, a runaway speed. Each fault is planted in one point of a healthy run.
#include <cmath>
#include <functional>
#include <limits>

#include "check.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"

using namespace mpmshock;

namespace {

void expect_stop(const char* what, const std::function<void(Particles<2>&)>& plant, const char* reason) {
  const Scene scene = parse_scene(
      "velocity = 1000 m/s\nporosity = 1\nwidth = 40 um\ntarget_height = 100 um\nflyer_height = 100 um\n"
      "cell_size = 10 um\nend_time = 50 ns\n",
      "faults");
  InitialState<2> initial = build_initial_state<2>(scene);
  constexpr std::size_t victim = 123;
  // The id the outputs give it: with symmetry = on (this scene) the mirrored flyer's points come first.
  const std::string named = "material point " + std::to_string(victim + initial.mirror.flyer_points()) + " ";
  plant(initial.particles);
  Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
  const StepStatus s = sim.step(sim.stable_time_step());
  const std::string text = sim.describe(s);
  std::printf("%s: %s\n", what, text.c_str());
  CHECK(s.code == StepStatus::Code::bad_state);
  CHECK(s.point == victim);
  CHECK(initial.mirror.on());
  CHECK(text.find(named) != std::string::npos);
  CHECK(text.find(reason) != std::string::npos);
  CHECK(text.find("position (") != std::string::npos);
}

}  // namespace

int main() {
  expect_stop("NaN energy", [](Particles<2>& p) { p.E[123] = std::numeric_limits<double>::quiet_NaN(); },
              "non-finite pressure or energy");
  expect_stop("inverted point", [](Particles<2>& p) { p.F[123](1, 1) = -0.5; }, "J = det F <= 0");
  expect_stop("over-compressed point", [](Particles<2>& p) { p.F[123](1, 1) = 0.2; }, "compressed past its equation of state's limit J = 0.268657");
  expect_stop("runaway speed", [](Particles<2>& p) { p.v[123][1] = 1e6; }, "runaway speed");
  return check::result();
}
