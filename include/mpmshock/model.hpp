// The physics of a run, resolved once from the scene: constants and closed-form laws, no flags
// that hot loops would test.
#pragma once

#include "mpmshock/artificial_viscosity.hpp"
#include "mpmshock/eos.hpp"
#include "mpmshock/material.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/von_mises.hpp"

namespace mpmshock {

struct Model {
  Material material;
  MieGruneisen eos;
  VonMises von_mises;
  ArtificialViscosity viscosity;
  double cell_size;
  double speed_limit;  // |v| above this is a numerical runaway, not physics

  explicit Model(const Scene& s)
      : material(s.material), eos(s.material), von_mises(s.material),
        viscosity{s.effects.artificial_viscosity ? s.av_linear : 0.0,
                  s.effects.artificial_viscosity ? s.av_quadratic : 0.0},
        cell_size(s.cell_size),
        // No material point outruns several times the impact speed plus the sound speed; a
        // point that does is a blow-up.
        speed_limit(10.0 * (2.0 * s.velocity + s.material.sound_speed)) {}
};

}  // namespace mpmshock
