#include "mpmshock/particles.hpp"

namespace mpmshock {

namespace {

// Every per-point double field, for bulk operations that must not forget one.
template <class P, class F>
void for_each_double_field(P& p, F&& f) {
  for (auto* v : {&p.x, &p.y, &p.vx, &p.vy, &p.mass, &p.volume0, &p.Fxx, &p.Fxy, &p.Fyx, &p.Fyy, &p.Lxx, &p.Lxy,
                  &p.Lyx, &p.Lyy, &p.work, &p.energy, &p.pressure, &p.viscosity})
    f(*v);
}
template <class P, class F>
void for_each_strength_field(P& p, F&& f) {
  if (p.has_strength())
    for (auto* v : {&p.sxx, &p.syy, &p.sxy, &p.plastic_strain}) f(*v);
  if (p.has_back_stress())
    for (auto* v : {&p.axx, &p.ayy, &p.axy}) f(*v);
}

}  // namespace

void Particles::add(double px, double py, double pvx, double pvy, double m, double V0, Body b) {
  id.push_back(static_cast<std::uint32_t>(x.size()));
  x.push_back(px);
  y.push_back(py);
  vx.push_back(pvx);
  vy.push_back(pvy);
  mass.push_back(m);
  volume0.push_back(V0);
  Fxx.push_back(1.0);
  Fxy.push_back(0.0);
  Fyx.push_back(0.0);
  Fyy.push_back(1.0);
  for (auto* v : {&Lxx, &Lxy, &Lyx, &Lyy, &work, &energy, &pressure, &viscosity}) v->push_back(0.0);
  for_each_strength_field(*this, [](std::vector<double>& v) { v.push_back(0.0); });
  body.push_back(b);
}

void Particles::enable_strength(bool on, bool back_stress) {
  for (auto* v : {&sxx, &syy, &sxy, &plastic_strain, &axx, &ayy, &axy}) v->clear();
  strength_ = on;
  back_stress_ = on && back_stress;
  for_each_strength_field(*this, [&](std::vector<double>& v) { v.assign(size(), 0.0); });
}

void Particles::reserve(std::size_t n) {
  for_each_double_field(*this, [&](std::vector<double>& v) { v.reserve(n); });
  for_each_strength_field(*this, [&](std::vector<double>& v) { v.reserve(n); });
  id.reserve(n);
  body.reserve(n);
}

std::size_t Particles::bytes_per_point() const {
  const std::size_t doubles = 18 + (has_strength() ? 4 : 0) + (has_back_stress() ? 3 : 0);
  return doubles * sizeof(double) + sizeof(std::uint32_t) + sizeof(Body);
}

}  // namespace mpmshock
