// Artificial viscosity: zero in expansion and at rest, the linear + quadratic form in compression.
#include "check.hpp"
#include "mpmshock/artificial_viscosity.hpp"

using namespace mpmshock;

int main() {
  const ArtificialViscosity av{0.2, 2.0};
  const double rho = 3000, c = 6000, h = 1e-5;
  CHECK(av.pressure(rho, c, h, 0.0) == 0.0);
  CHECK(av.pressure(rho, c, h, 1e8) == 0.0);
  CHECK(av.signal(c, h, 1e8) == 0.0);
  for (double trD : {-1e5, -1e7, -1e9}) {
    const double expect = rho * (0.2 * c * h * -trD + 2.0 * h * h * trD * trD);
    CHECK_REL(av.pressure(rho, c, h, trD), expect, 1e-14);
    CHECK(av.pressure(rho, c, h, trD) > 0.0);
    CHECK_REL(av.signal(c, h, trD), 0.2 * c + 2.0 * h * -trD, 1e-14);
  }
  // Zero coefficients give no viscous pressure either; artificial_viscosity = off is its own law
  // type, which the point update compiles out.
  const ArtificialViscosity off{0.0, 0.0};
  CHECK(off.pressure(rho, c, h, -1e9) == 0.0);
  static_assert(!NoViscosity::active && ArtificialViscosity::active, "the off law must compile out");
  return check::result();
}
