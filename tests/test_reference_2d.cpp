// The 2D results stay what they were: five tiny impacts (the default model, and before its volumetric smoothing; bspline2 at cfl 0.3, the
// default until 2026-12-05; every optional effect with gimp and USL; the paper's bilinear cells and
// temperature) run to their end, and every per-point
// field of the final state is compared with tests/data/reference_2d.txt, written before 3D was added
// and rewritten once since, when P2G began keeping its stencils for the later passes (the weights are
// the same numbers, but FMA contraction differs when they are loaded rather than computed inline:
// field sums moved by 1e-16 to 3e-14 relative in the gimp and bilinear cases, the default case not at all),
// and when the work mismatch in the clock became an exact sum (only the clock changed), and when the
// equation of state began to carry its reference energy and the point update its volume rate
// (issue 28: the same arithmetic regrouped, FMA contraction moved field sums by 1e-16 to 4e-13),
// and when thermal softening became Steinberg-Guinan's with its pressure term, Y_max and the latent
// heat, with 6061-T6's conductivity (the every-effect case only: its deviatoric stress sum nearly
// doubled, as SG's factor near 2 at 18 GPa says; the other two cases bitwise unchanged), and when
// spall began to judge the neighbourhood's tension (spall_neighbourhood.hpp; the every-effect case
// only: 31 % fewer opened points by their failure_J sum, the other two cases bitwise unchanged), and
// when max_volume_change began to bound the step (the paper_cells case only: the point noise of
// bilinear cells makes |tr D| dt reach 0.03, 324 steps to 60 ns; the other two cases' field sums
// unchanged to 1e-9; written on a build without AVX-512), and when the default became bspline2_domain
// at cfl 0.6 with max_volume_change 0.02 (2026-12-05: a new "default" case; the old default's state
// kept bitwise as the case "bspline2", the other two bitwise unchanged), and when a porous scene's
// volumetric smoothing became automatic (2026-12-05: the new "default" case; the old default's state
// kept bitwise as "no_smoothing", the other three bitwise unchanged), and when the passes of the
// four-column stencils began to take a stencil row's nodes in vector lanes (2026-12-06, issue 32:
// node_rows.hpp; the gathers' sums grouped by lanes moved the "default" and "no_smoothing" cases'
// field sums by at most 1.2e-12 relative, the other three bitwise unchanged; written on a build
// with AVX-512, where the file before was written without it), and when every pass began to read
// the stencils of one pass before P2G (2026-12-06, issue 32: compute_stencils, the domain B-spline's
// weights four points at a time, and P2G reading its weights instead of computing them inline):
// the "default", "no_smoothing" and "paper_cells" cases moved (point fields by at most 7e-15
// relative in their sums, the step's scratch `work` by 2.4e-12, the clock's time by 4.8e-13), the
// "bspline2" and "every_effect" cases bitwise unchanged, and when the point update began to take
// four points at a time (2026-12-06, issue 32: constitutive.hpp's step_lanes, the same formulas
// with FMA contraction chosen apart): the "default", "bspline2" and "paper_cells" cases moved (field
// sums by at most 3e-15 relative, the step's scratch `work` by 6e-13, the clock's time by 1e-12),
// "no_smoothing" in its clock alone, "every_effect" (spall and softening, still point by point)
// bitwise unchanged, and when the heat flux began to compute its points' temperatures and rates
// four at a time (2026-12-06, issue 32: number.hpp's exp and expm1, within 1 and 4 ulp of libm's):
// the four cases without spall moved (field sums by at most 5e-15 relative, the step's scratch
// `work` by 2.3e-12, the clock's time by 3.5e-13), "every_effect" (melting: still point by point)
// bitwise unchanged, and when the vector loads and stores of lanes.hpp stopped being memcpy
// (2026-12-06, issue 32: the transfers no longer reload pointers after each store, and GCC
// contracted their FMAs differently): "default" and "no_smoothing" moved (field sums by at most
// 2.5e-15 relative, `work` by 2.3e-12, the clock by 9e-13), the other three bitwise unchanged, and
// when the four-column passes began to weigh by columns once and by rows after (node_rows.hpp's
// Columns and RowFactors, 2026-12-06, issue 32: the same products in another order): "default" and
// "no_smoothing" moved (field sums by at most 5.3e-15 relative, `work` by 1.2e-12, the clock by
// 1.4e-12), the other three bitwise unchanged, and when those passes began to choose once per point
// whether a stencil wraps, the row loops compiled for each case, and to run their point kernels
// inline (2026-12-06, issue 32: the same formulas, FMAs contracted anew): "default" and
// "no_smoothing" moved (field sums by at most 2.8e-15 relative, `work` by 7.8e-13, the clock by
// 3.4e-13), the other three bitwise unchanged, and when a row wrapped round the periodic seam began
// to load and store its two runs of memory as whole vectors and halves, its row loop compiled for
// each of the three ways it can wrap (2026-12-07, issue 32: node_rows.hpp's RowRuns, FMAs
// contracted anew in the new copies): "default" and "no_smoothing" moved (field sums by at most
// 5e-15 relative, `work` by 7.7e-13, the clock by 1.9e-13), the other three bitwise unchanged, and
// when the artificial heat flux's scatter began to ride on P2G's sweep (2026-12-07, issue 32:
// heat_flux_rider.hpp; written on a build without AVX-512, where the file before was written with
// it). Built with -ffp-contract=off before and after, the four cases without heat conduction are
// bitwise the same; with contraction, on this build against the old code's states on the same
// build, they moved (field sums by at most 7e-15 relative, `work` by 1.8e-12, the clock by 3.1e-13). "every_effect" moved by its physics: the flux now takes its
// temperatures from the step's start, before conduction acts in the step, not after it (field sums
// by at most 3.2e-5 relative, the clock by 2.0e-5, `work` by 1.2e-3). And when each point began to
// keep its own running sum of the work mismatch (Particles::work_mismatch, a new field here), which
// the clock sums exactly at samples instead of summing every step's points exactly (2026-12-07,
// issue 32): every other field of the five cases bitwise unchanged on this build; the clock moved
// by at most 2.7e-14 relative (one rounding per point and step instead of one per step).
//
// Bitwise where that is meaningful: floating-point results depend on the compiler and on the
// instructions it may use (FMA contraction under -march=native), so the reference records the build
// it was made with. A build with the same fingerprint must match every field's bytes (a 64-bit hash);
// another build compares each field's sum of magnitudes to 1e-9 instead, and says so.
//
//   test_reference_2d SCENE            compare
//   test_reference_2d SCENE --write F  (re)write the reference file F
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "check.hpp"
#include "compare_outputs.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"

using namespace mpmshock;

namespace {

std::string build_fingerprint() {
  std::string f = MPMSHOCK_BUILD_FINGERPRINT;
  f += " | gcc " __VERSION__;
#ifdef __FMA__
  f += " fma";
#endif
#ifdef __AVX2__
  f += " avx2";
#endif
#ifdef __AVX512F__
  f += " avx512f";
#endif
  return f;
}

struct Case {
  std::string name;
  std::vector<std::string> overrides;
};

// Short runs that still see the shock cross voids, the free surfaces and every effect's code path.
// The cases other than "default" keep max_volume_change at 0.03 (its default until 2026-12-05) and
// the automatic cfl of their shape (0.3), so their states are the ones recorded before that day.
// Every case but "default" keeps volumetric smoothing off (the default of a porous scene until
// 2026-12-05), and "no_smoothing" is the default of that day before it.
const std::vector<Case> kCases = {
    {"default", {}},
    {"no_smoothing", {"volumetric_smoothing=off"}},  // the default until volumetric_smoothing = auto
    {"bspline2", {"shape_function=bspline2", "max_volume_change=0.03", "volumetric_smoothing=off"}},  // the default until 2026-12-05
    {"every_effect",
     {"symmetry=off", "shape_function=gimp", "spall=on", "heat_conduction=on",
      "thermal_softening=on", "hardening_beta=0.5", "taylor_quinney=0.9", "flip_fraction=0.98", "update_scheme=usl",
      "max_volume_change=0.03", "volumetric_smoothing=off"}},
    {"paper_cells",
     {"shape_function=bilinear",
      "temperature_model=paper", "skip_unreached=off", "flyer_mirror=off", "max_volume_change=0.03",
      "volumetric_smoothing=off"}},
};

struct FieldSum {
  std::uint64_t hash = 0;
  double magnitude = 0.0;  // sum of |component| over the field
};

std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t h = 1469598103934665603ull) {
  const auto* b = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

template <class T>
FieldSum sum_of(const std::vector<T>& v) {
  FieldSum s;
  s.hash = fnv1a(v.data(), v.size() * sizeof(T));
  if constexpr (std::is_same_v<T, double>) {
    for (double x : v) s.magnitude += std::abs(x);
  } else if constexpr (sizeof(T) % sizeof(double) == 0) {
    for (const T& x : v) {
      double c[sizeof(T) / sizeof(double)];
      std::memcpy(c, &x, sizeof c);
      for (double y : c) s.magnitude += std::abs(y);
    }
  } else {
    for (const T& x : v) s.magnitude += static_cast<double>(x);
  }
  return s;
}

// The name of a per-point field, from its member pointer.
template <class Member>
std::string field_name(Member member) {
  using P = Particles<2>;
#define NAME_OF(f)                                                         \
  if constexpr (std::is_same_v<Member, decltype(&P::f)>) {                 \
    if (member == &P::f) return #f;                                        \
  }
  NAME_OF(x) NAME_OF(v) NAME_OF(m) NAME_OF(V0) NAME_OF(F) NAME_OF(L) NAME_OF(work) NAME_OF(work_mismatch) NAME_OF(E) NAME_OF(P) NAME_OF(q)
  NAME_OF(s) NAME_OF(alpha) NAME_OF(eps_p) NAME_OF(failure_J) NAME_OF(damage) NAME_OF(E_stored) NAME_OF(plastic_heat)
  NAME_OF(id) NAME_OF(body)
#undef NAME_OF
  return "unnamed";
}

// "case field" -> sums of the final state of each case.
std::map<std::string, FieldSum> run_cases(const std::string& scene_path) {
  std::map<std::string, FieldSum> out;
  for (const Case& c : kCases) {
    const Scene scene = load_scene(scene_path, c.overrides);
    InitialState<2> initial = build_initial_state<2>(scene);
    Simulation<2> sim(scene, initial.grid, std::move(initial.particles));
    if (!compare::march(sim, scene.end_time, c.name)) continue;
    const Particles<2>& p = sim.particles();
    p.for_each_member([&](auto member) { out[c.name + " " + field_name(member)] = sum_of(p.*member); });
    std::printf("%s: %zu points, %" PRId64 " steps to %.3g ns\n", c.name.c_str(), p.size(), sim.steps(),
                sim.time() * 1e9);
    sim.settle();
    FieldSum clock;
    const double clock_values[] = {sim.time(), sim.clock().work_mismatch, sim.clock().max_signal};
    clock.hash = fnv1a(clock_values, sizeof clock_values);
    clock.magnitude = std::abs(sim.clock().work_mismatch);
    out[c.name + " clock"] = clock;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const std::map<std::string, FieldSum> now = run_cases(argv[1]);
  const std::string fingerprint = build_fingerprint();

  if (argc == 4 && std::string(argv[2]) == "--write") {
    std::ofstream f(argv[3]);
    f << "# test_reference_2d: the final state of its five cases, per field: 64-bit hash of the bytes, sum of |x|\n";
    f << "build " << fingerprint << "\n";
    for (const auto& [key, s] : now) {
      char line[200];
      std::snprintf(line, sizeof line, "%s %016" PRIx64 " %.17g\n", key.c_str(), s.hash, s.magnitude);
      f << line;
    }
    std::printf("wrote %s\n", argv[3]);
    return check::result();
  }

  std::ifstream f(MPMSHOCK_REFERENCE_2D);
  CHECK(f.good());
  std::string line, made_with;
  std::map<std::string, FieldSum> ref;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("build ", 0) == 0) {
      made_with = line.substr(6);
      continue;
    }
    std::istringstream in(line);
    std::string name, index, hash;
    FieldSum s;
    in >> name >> index >> hash >> s.magnitude;
    s.hash = std::stoull(hash, nullptr, 16);
    ref[name + " " + index] = s;
  }
  const bool bitwise = made_with == fingerprint;
  if (bitwise)
    std::printf("this build is the reference's: every field must match bit for bit\n");
  else
    std::printf("this build (%s)\ndiffers from the reference's (%s):\nbitwise not checked, each field's sum to 1e-9\n",
                fingerprint.c_str(), made_with.c_str());
  CHECK(ref.size() == now.size());
  int differ = 0;
  for (const auto& [key, r] : ref) {
    const auto it = now.find(key);
    CHECK(it != now.end());
    if (it == now.end()) continue;
    const FieldSum& s = it->second;
    const double rel = std::abs(s.magnitude - r.magnitude) / std::max(std::abs(r.magnitude), 1e-300);
    const bool same = bitwise ? s.hash == r.hash : rel <= 1e-9 || (r.magnitude == 0.0 && s.magnitude == 0.0);
    if (!same) {
      ++differ;
      std::printf("  %s differs: sum %.17g against %.17g (relative %.2e)\n", key.c_str(), s.magnitude, r.magnitude, rel);
    }
  }
  std::printf("%zu fields compared, %d differ\n", ref.size(), differ);
  CHECK(differ == 0);
  return check::result();
}
