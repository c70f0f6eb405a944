// A program outside the project, built against the installed library: resolves a scene.
#include <cstdio>

#include "mpmshock/provenance.hpp"
#include "mpmshock/scene.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const mpmshock::Scene scene = mpmshock::load_scene(argv[1], {});
  std::printf("mpmshock %s\n%s", mpmshock::build_info().version, mpmshock::resolved_scene(scene).c_str());
  return 0;
}
