// A tiny porous impact run end to end through run_scene: every output file written, every column of
// regions.csv present and finite, the snapshots readable, conservation and porosity reported.
#include <unistd.h>

#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "check.hpp"
#include "mpmshock/regions.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/scene.hpp"

using namespace mpmshock;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const fs::path out = fs::temp_directory_path() / ("mpmshock_test_porous_run_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const Scene scene = load_scene(argv[1], {"output_dir=" + out.string()});
  const RunResult r = run_scene(scene, {true, false});
  CHECK(r.exit_code == kExitOk);
  CHECK_REL(r.porosity, 1.2, 0.005);
  CHECK(r.voids > 0);
  CHECK(r.mass_error == 0.0);
  CHECK(r.momentum_error < 1e-12);
  CHECK(r.energy_error < 1e-10);
  std::printf("%s", describe_result(r).c_str());

  // regions.csv: the exact header, six regions at t = 0, 10, ..., 60 ns, every field finite.
  std::ifstream csv(out / "regions.csv");
  std::string line;
  std::getline(csv, line);
  CHECK(line == kRegionsHeader);
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    std::istringstream fields(line);
    std::string field;
    int column = 0;
    while (std::getline(fields, field, ',')) {
      if (column != 1) {
        const double v = std::stod(field);
        if (!std::isfinite(v)) check::fail(__FILE__, __LINE__, "non-finite value in row: " + line);
      }
      ++column;
    }
    CHECK(column == 19);
  }
  CHECK(rows == 7 * 6);

  // conservation.csv, scene.txt, summary.json and snapshots 0 (t = 0), 1 (30 ns), 2 (60 ns).
  for (const char* f : {"conservation.csv", "scene.txt", "summary.json", "snapshot_00000.h5", "snapshot_00001.h5",
                        "snapshot_00002.h5"})
    CHECK(fs::exists(out / f));
  CHECK(!fs::exists(out / "snapshot_00003.h5"));
  const hid_t file = H5Fopen((out / "snapshot_00002.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  CHECK(file >= 0);
  if (file >= 0) {
    double t = 0;
    const hid_t attr = H5Aopen(file, "time", H5P_DEFAULT);
    H5Aread(attr, H5T_NATIVE_DOUBLE, &t);
    H5Aclose(attr);
    CHECK_REL(t, 60e-9, 1e-12);
    for (const char* name : {"position", "velocity", "mass", "volume", "density", "pressure", "temperature", "stress",
                             "plastic_strain", "internal_energy"}) {
      const hid_t set = H5Dopen2(file, (std::string("/particles/") + name).c_str(), H5P_DEFAULT);
      CHECK(set >= 0);
      if (set < 0) continue;
      const hid_t space = H5Dget_space(set);
      hsize_t dims[3] = {0, 0, 0};
      H5Sget_simple_extent_dims(space, dims, nullptr);
      CHECK(dims[0] == (r.symmetry ? 2 : 1) * r.points);  // snapshots show the whole impact
      H5Sclose(space);
      H5Dclose(set);
    }
    H5Fclose(file);
  }

  // A second run into the same directory is refused without --force, with the key named.
  CHECK_THROWS_WITH(run_scene(scene, {true, false}), "'output_dir'", "--force");
  CHECK(run_scene(scene, {true, true}).exit_code == kExitOk);
  fs::remove_all(out);
  return check::result();
}
