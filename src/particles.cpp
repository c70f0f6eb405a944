#include "mpmshock/particles.hpp"

namespace mpmshock {

template <int D>
void Particles<D>::add(const Vec<D>& position, const Vec<D>& velocity, double mass, double volume0, Body b) {
  id.push_back(static_cast<std::uint32_t>(x.size()));
  x.push_back(position);
  v.push_back(velocity);
  m.push_back(mass);
  V0.push_back(volume0);
  F.push_back(Mat<D>::identity());
  L.push_back(Mat<D>{});
  for (auto* f : {&work, &E, &P, &q, &work_mismatch}) f->push_back(0.0);
  if (strength_) {
    s.push_back({});
    eps_p.push_back(0.0);
  }
  if (back_stress_) alpha.push_back({});
  if (failure_) {
    failure_J.push_back(0.0);
    damage.push_back(0.0);
  }
  if (stored_) E_stored.push_back(0.0);
  if (plastic_heat_) plastic_heat.push_back(0.0);
  body.push_back(b);
}

template <int D>
void Particles<D>::enable_strength(bool on, bool back_stress) {
  strength_ = on;
  back_stress_ = on && back_stress;
  s.assign(strength_ ? size() : 0, {});
  eps_p.assign(strength_ ? size() : 0, 0.0);
  alpha.assign(back_stress_ ? size() : 0, {});
}

template <int D>
void Particles<D>::enable_failure(bool on) {
  failure_ = on;
  failure_J.assign(on ? size() : 0, 0.0);
  damage.assign(on ? size() : 0, 0.0);
}

template <int D>
void Particles<D>::enable_cold_work(bool on) {
  stored_ = on;
  E_stored.assign(on ? size() : 0, 0.0);
}

template <int D>
void Particles<D>::enable_plastic_heat(bool on) {
  plastic_heat_ = on;
  plastic_heat.assign(on ? size() : 0, 0.0);
}

template <int D>
void Particles<D>::reserve(std::size_t n) {
  for_each_member([&](auto field) { (this->*field).reserve(n); });
}

template <int D>
void Particles<D>::enable_fields_of(const Particles& other) {
  enable_strength(other.strength_, other.back_stress_);
  enable_failure(other.failure_);
  enable_cold_work(other.stored_);
  enable_plastic_heat(other.plastic_heat_);
}

template <int D>
void Particles<D>::append_copy(const Particles& from, std::size_t p) {
  for_each_member([&](auto field) { (this->*field).push_back((from.*field)[p]); });
}

template <int D>
std::size_t Particles<D>::bytes_per_point() const {
  std::size_t bytes = 0;
  for_each_member([&](auto field) { bytes += sizeof((this->*field)[0]); });
  return bytes;
}

template struct Particles<2>;
template struct Particles<3>;

}  // namespace mpmshock
