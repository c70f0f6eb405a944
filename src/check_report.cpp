// The --check report: what a scene builds, what it will cost, before anything runs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "mpmshock/material_law.hpp"
#include "mpmshock/probes.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/setup.hpp"
#include "mpmshock/simulation.hpp"
#include "mpmshock/strip_bins.hpp"

namespace mpmshock {
namespace {

std::string bytes_text(double b) {
  char buf[64];
  if (b < 1024.0 * 1024.0) std::snprintf(buf, sizeof buf, "%.0f KiB", b / 1024.0);
  else if (b < 1024.0 * 1024.0 * 1024.0) std::snprintf(buf, sizeof buf, "%.1f MiB", b / (1024.0 * 1024.0));
  else std::snprintf(buf, sizeof buf, "%.2f GiB", b / (1024.0 * 1024.0 * 1024.0));
  return buf;
}

namespace {

// A body's shock state at particle velocity up (rankine_hugoniot.hpp).
ShockState shocked(const Model& model, Body b, double up) {
  return std::visit([&](const auto& eos) { return shock_from_rest(eos, up); }, model.eos[index_of(b)]);
}

// The shocked state of solid bodies at impact, where their Hugoniots cross (hydrodynamic, the
// impedance match; tests/test_impedance.cpp checks runs against it): the particle velocity u
// taken up by the target solves P_t(u) = P_f(V - u), V the closing speed, each P the
// Rankine-Hugoniot pressure of the body's equation of state (rankine_hugoniot.hpp; with
// Mie-Grüneisen rho0 (c0 + s u) u).
// The particle velocity the target takes up at impact.
double impact_particle_velocity(const Scene& s, const Model& model) {
  const double V = s.flyer_velocity + s.target_velocity;
  double lo = 0.0, hi = V;
  for (int k = 0; k < 200; ++k) {
    const double u = 0.5 * (lo + hi);
    (shocked(model, Body::target, u).pressure < shocked(model, Body::flyer, V - u).pressure ? lo : hi) = u;
  }
  return 0.5 * (lo + hi);
}

// u: impact_particle_velocity.
std::string impact_state(const Scene& s, const Model& model, double u) {
  std::ostringstream out;
  out << "impact (solid Hugoniots, hydrodynamic): " << shocked(model, Body::target, u).pressure * 1e-9
      << " GPa, the interface moving at " << u - s.target_velocity << " m/s\n";
  return out.str();
}

// The fastest signal of solid bodies once shocked: in each body's shocked state its longitudinal
// sound speed c_L (bulk plus shear), the viscous speed A1 c of material still compressing
// (artificial_viscosity.hpp) and the interface's speed, as the time step counts them. The run's
// step is shorter still where the quadratic term and the points' noise add to it. u:
// impact_particle_velocity.
double shocked_signal(const Scene& s, const Model& model, double u) {
  const double V = s.flyer_velocity + s.target_velocity;
  const double A1 = s.effects.artificial_viscosity ? s.av_linear : 0.0;
  double fastest = 0.0;
  for (const Body b : {Body::flyer, Body::target}) {
    const ShockState st = shocked(model, b, b == Body::target ? u : V - u);
    const double c2 = std::visit([&](const auto& eos) { return std::max(eos.state(st.J, st.energy).sound_speed_squared, 0.0); },
                                 model.eos[index_of(b)]);
    const double rho0 = std::visit([](const auto& eos) { return eos.rho0(); }, model.eos[index_of(b)]);
    const double cL2 = c2 + (4.0 / 3.0) * model.shear_modulus(b) * st.J / rho0;
    const double Q = A1 * std::sqrt(c2);
    fastest = std::max(fastest, std::abs(u - s.target_velocity) + Q + std::sqrt(Q * Q + cL2));
  }
  return fastest;
}

}  // namespace

template <int D>
std::string describe_setup(const Scene& s, const InitialState<D>& st) {
  std::ostringstream out;
  const GridGeometry<D>& g = st.grid;
  auto body = [&](const BodySummary& b) {
    out << "  " << b.name << ": y " << b.y_bottom * 1e3 << " .. " << b.y_top * 1e3 << " mm, " << b.material_points
        << " material points, " << b.voids.size() << (D == 3 ? " spherical" : "") << " voids, porosity " << b.porosity() << "\n";
  };
  const double porosity = porosity_of(st.target, st.flyer);
  out << "scene " << s.source << "\n";
  std::ostringstream speeds;
  if (s.flyer_velocity == s.target_velocity) speeds << "impact speed +-" << s.flyer_velocity << " m/s";
  else speeds << "flyer at " << s.flyer_velocity << " m/s, target at " << s.velocity_of(Body::target) << " m/s";
  if (D == 2)
    out << "bodies (width " << s.width * 1e3 << " mm, periodic in x, 2D plane strain, " << speeds.str() << ")\n";
  else
    out << "bodies (3D, width " << s.width * 1e3 << " mm x depth " << s.derived_depth() * 1e3
        << " mm, periodic in x and z, " << speeds.str() << ")\n";
  body(st.target);
  body(st.flyer);
  if (s.has_window())
    out << "  window: y " << s.target_height * 1e3 << " .. " << (s.target_height + s.window_height) * 1e3 << " mm, "
        << st.window_points << " material points of " << s.window_material << " (" << s.material_of(Body::window).density
        << " kg/m3) on the target's free surface\n";
  if (s.flyer_material != "scene" || s.target_material != "scene") {
    auto named = [](const std::string& n) { return n == "scene" ? std::string("the scene's material keys") : n; };
    out << "  materials: target " << named(s.target_material) << " (" << s.material_of(Body::target).density
        << " kg/m3), flyer " << named(s.flyer_material) << " (" << s.material_of(Body::flyer).density << " kg/m3)\n";
  }
  if (s.flyer_porosity == s.porosity)
    out << "  porosity requested " << s.porosity << ", achieved " << porosity << " (relative error "
        << std::abs(porosity - s.porosity) / s.porosity << ")\n";
  else
    out << "  porosity requested " << s.porosity << " (target), " << s.flyer_porosity << " (flyer); achieved "
        << st.target.porosity() << ", " << st.flyer.porosity() << "\n";
  out << "grid: " << g.nx << (D == 3 ? " x " + std::to_string(g.nz) : std::string()) << " x " << g.ny - 1 << " cells of " << g.h * 1e6 << " um, y " << g.y_min * 1e3 << " .. "
      << g.y_max() * 1e3 << " mm, " << g.nodes() << " nodes\n";
  const std::size_t whole = st.target.material_points + st.flyer.material_points + st.window_points,
                    simulated = st.particles.size();
  out << "material points: " << whole << " (" << s.particles_per_cell << " x " << s.particles_per_cell;
  if (D == 3) out << " x " << s.particles_per_cell;
  out << " per cell)\n";
  const bool mirrored = st.mirror.on();
  const std::string asymmetry = asymmetry_of(s);
  const std::string why_off = asymmetry.empty() ? "as the scene sets it" : asymmetry;
  out << "symmetry: "
      << (mirrored ? "on: the target's " + std::to_string(simulated) +
                         " points are simulated, the flyer is their mirror image about y = 0"
                   : "off (" + why_off + ")")
      << "\n";
  const Model model(s);
  const double signal = initial_signal_speed(st.particles, model);
  const double dt0 = model.time_step(signal), mechanical = s.cfl * s.cell_size / signal;
  // Shocked material carries sound faster than c0; dt shrinks as the run goes, so this is a floor.
  const auto steps = static_cast<long long>(std::ceil(s.end_time / dt0));
  out << "time step: " << dt0 * 1e9 << " ns at start, ";
  if (dt0 < mechanical)
    out << "set by heat conduction (" << model.diffusion_number << " h^2 / diffusivity, diffusivity " << model.max_diffusivity()
        << " m2/s; the sound limit, cfl " << s.cfl << " at " << signal << " m/s, allows " << mechanical * 1e9
        << " ns)";
  else
    out << "set by sound (cfl " << s.cfl << ", fastest signal " << signal << " m/s)";
  out << "; at least " << steps << " steps to " << s.end_time * 1e9 << " ns";
  const double impact_u = s.every_body_solid() ? impact_particle_velocity(s, model) : 0.0;
  if (s.every_body_solid() && !(dt0 < mechanical)) {
    const double shocked_dt = model.time_step(std::max(signal, shocked_signal(s, model, impact_u)));
    out << ", about " << static_cast<long long>(std::ceil(s.end_time / shocked_dt))
        << " at the step of the shocked state (its sound and viscous speeds)";
  }
  out << "\n";
  if (s.every_body_solid()) out << impact_state(s, model, impact_u);
  for (const std::string& w : scene_warnings(s)) out << "warning: " << w << "\n";
  if (const std::string w = probes_size_warning(s, dt0); !w.empty()) out << "warning: " << w << "\n";
  // Every effect the run simulates, and none that it does not.
  std::vector<std::string> on;
  if (s.effects.plasticity) {
    // Each body's law is its material's; where they differ, each material's is named.
    auto law_of = [&](const Material& m) -> std::string {
      const MaterialLaw& law = mpmshock::law_of(LawSlot::strength, m);
      if (!law.plasticity.empty()) return law.plasticity;
      return s.effects.thermal_softening ? "with Steinberg-Guinan softening" : "";
    };
    const std::vector<std::string> names = s.materials_in_use();
    bool one_law = true;
    for (const std::string& name : names)
      one_law = one_law && s.material_by_name(name).strength_model == s.material_by_name(names.front()).strength_model;
    if (one_law) {
      const std::string law = law_of(s.material_by_name(names.front()));
      on.push_back(law.empty() ? "plasticity" : "plasticity (" + law + ")");
    } else {
      std::string each;
      for (const std::string& name : names) {
        const Material& m = s.material_by_name(name);
        const std::string law = law_of(m);
        const bool own_flow_stress = !mpmshock::law_of(LawSlot::strength, m).plasticity.empty();
        each += (each.empty() ? "" : "; ") + name + ": " +
                (own_flow_stress ? law : m.strength_model + (law.empty() ? "" : ", " + law));
      }
      on.push_back("plasticity (" + each + ")");
    }
  }
  if (s.effects.thermal) {
    std::string thermal = s.temperature_model == TemperatureModel::paper ? "thermal (the paper's temperature model"
                                                                         : "thermal (energy temperature model";
    if (s.paper_temperature) thermal += ", the paper's reported beside it";
    on.push_back(thermal + ")");
  }
  if (s.effects.thermal_softening) {
    // Each body's material's melt curve (the target's first; a body of the same material adds none).
    std::ostringstream melt;
    melt << "melting (";
    const std::vector<std::string> names = s.materials_in_use();
    for (const std::string& name : names) {
      const Material& m = s.material_by_name(name);
      melt << (name == names.front() ? "" : "; ") << (name == "scene" ? "" : name + ": ");
      if (const MaterialLaw& law = law_of(LawSlot::strength, m); law.melt)  // its own law's melt
        melt << law.melt(m);
      else
        melt << "T_m0 " << m.melt_temperature << " K, Lindemann a " << m.lindemann_a << ", latent heat " << m.latent_heat
             << " J/kg";
    }
    melt << ")";
    on.push_back(melt.str());
  }
  if (s.material_of(Body::flyer).bound_expansion || s.material_of(Body::target).bound_expansion ||
      (s.has_window() && s.material_of(Body::window).bound_expansion))
    on.push_back("bounded expansion (Rose binding curve)");
  // The laws that name themselves (the registry's, src/laws/), each once if any body takes it.
  const std::vector<std::string> names = s.materials_in_use();
  for (const MaterialLaw& law : material_laws()) {
    if (!law.effect.empty() && std::any_of(names.begin(), names.end(), [&](const std::string& name) {
          return takes(law, s, s.material_by_name(name));
        }))
      on.push_back(law.effect);
  }
  if (s.effects.artificial_viscosity) {
    std::ostringstream av;
    av << "artificial viscosity (A1 " << s.av_linear << ", A2 " << s.av_quadratic << ")";
    on.push_back(av.str());
    if (model.heat_flux_beta > 0.0) {
      std::ostringstream hf;
      hf << "artificial heat flux (beta " << model.heat_flux_beta << ")";
      on.push_back(hf.str());
    }
  }
  if (s.volumetric_smoothing == Smoothing::on) on.push_back("volumetric smoothing");
  if (s.effects.spall)
    on.push_back(std::string("spall (") +
                 (s.spall_criterion == SpallCriterion::neighbourhood ? "the neighbourhood's" : "each point's own") +
                 " tension against " + std::to_string(s.spall_strength / 1e9).substr(0, 4) + " GPa)");
  if (model.conducts_heat()) on.push_back("heat conduction");
  if (s.porosity > 1.0) on.push_back("voids");
  out << "effects:";
  for (std::size_t k = 0; k < on.size(); ++k) out << (k ? ", " : " ") << on[k];
  if (on.empty()) out << " none";
  out << "; update scheme " << (s.update_scheme == UpdateScheme::musl ? "MUSL" : "USL") << "\n";
  const std::size_t per_point = st.particles.bytes_per_point() + step_scratch_bytes<D>(s);
  const double bytes = static_cast<double>(simulated) * static_cast<double>(per_point) +
                       static_cast<double>(g.nodes()) * static_cast<double>(Grid<D>::bytes_per_node());
  out << "memory: about " << bytes_text(bytes) << " (" << per_point << " bytes per simulated point, "
      << Grid<D>::bytes_per_node() << " per node)\n";
  return out.str();
}

template <int D>
std::string check_in(const Scene& scene) {
  const Comm& comm = Comm::world();  // refuse on mpirun what the run on as many ranks refuses
  check_fits<D>(scene, comm.size(), comm.node_ranks());
  const InitialState<D> whole = build_initial_state<D>(scene);
  // The probes are resolved as the run resolves them (a point probe in a void is refused): on
  // several ranks from each rank's share, as the run makes them.
  if (comm.parallel()) probes_of(scene, InitialBuilder<D>(scene).build_share(comm.rank(), comm.size()), comm);
  else probes_of(scene, whole, comm);
  return describe_setup(scene, whole);
}

}  // namespace

std::string check_report(const Scene& scene) {
  return scene.dimension == 3 ? check_in<3>(scene) : check_in<2>(scene);
}

}  // namespace mpmshock
