// A material point colder than 0 K (its internal energy below the 0 K isotherm at its volume) is
// not physics but a numerical failure, typically a strong shock with too little artificial
// viscosity ringing. Checked at every sample, where the temperatures are computed anyway (it
// costs ~14 ns per point, too much for every step). On with thermal = on. It checks E itself, by the
// energy model whatever temperature_model says: the paper model's T_H + W_p/c_v cannot fall below 0 K.
#pragma once

#include "mpmshock/parallel.hpp"
#include "mpmshock/step_effect.hpp"
#include "mpmshock/temperature.hpp"

namespace mpmshock {

template <int D>
class ZeroKelvinCheck final : public StepEffect<D> {
 public:
  explicit ZeroKelvinCheck(const BodyTemperatures& thermal) : thermal_(thermal) {}
  const char* name() const override { return "0 K check"; }
  unsigned slots() const override { return slot_bit(StepSlot::at_sample); }

  StepStatus at_sample(const Particles<D>& pts) override {
    std::size_t first = ~std::size_t{0};
#pragma omp parallel for schedule(dynamic, kChunk) reduction(min : first)
    for (std::size_t p = 0; p < pts.size(); ++p)
      if (!(thermal_.energy_temperature(pts, p) > 0.0)) first = p < first ? p : first;
    if (first == ~std::size_t{0}) return {};
    return {StepStatus::Code::below_zero_kelvin, first};
  }

 private:
  const BodyTemperatures& thermal_;
};

}  // namespace mpmshock
