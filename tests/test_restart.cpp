// Restart: a run to T and a run to T/2 restarted to T end in the same state, bit for bit, with one
// thread and with two, in 2D and in 3D; and the results do not depend on the thread count at all. Every sum in the
// step runs in a fixed order (strip-coloured scatter, block-ordered totals), so there is no
// round-off that the thread count could reorder.
#include <unistd.h>

#include <omp.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "check.hpp"
#include "mpmshock/hdf5_io.hpp"
#include "mpmshock/run.hpp"
#include "mpmshock/scene.hpp"
#include "mpmshock/snapshot.hpp"

using namespace mpmshock;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every /particles dataset of two snapshots, compared bit for bit.
void check_same_snapshot(const fs::path& a, const fs::path& b) {
  h5::Handle fa(H5Fopen(a.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + a.string());
  h5::Handle fb(H5Fopen(b.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + b.string());
  CHECK(h5::read_double_attribute(fa.get(), "time") == h5::read_double_attribute(fb.get(), "time"));
  CHECK(h5::read_int_attribute(fa.get(), "step") == h5::read_int_attribute(fb.get(), "step"));
  const std::size_t n = static_cast<std::size_t>(h5::read_int_attribute(fa.get(), "particle_count"));
  const auto d = static_cast<hsize_t>(h5::read_int_attribute(fa.get(), "dimension"));
  CHECK(h5::read_int_attribute(fb.get(), "dimension") == static_cast<std::int64_t>(d));
  const std::pair<const char*, std::vector<hsize_t>> fields[] = {
      {"position", {d}},  {"velocity", {d}},       {"mass", {}},   {"volume", {}},
      {"density", {}},    {"pressure", {}},        {"temperature", {}}, {"internal_energy", {}},
      {"stress", {3, 3}}, {"plastic_strain", {}},  {"deformation_gradient", {d, d}},
      {"velocity_gradient", {d, d}}, {"viscous_pressure", {}}};
  for (const auto& [name, tail] : fields) {
    const std::string path = std::string("/particles/") + name;
    const std::vector<double> va = h5::read_doubles(fa.get(), path.c_str(), n, tail);
    const std::vector<double> vb = h5::read_doubles(fb.get(), path.c_str(), n, tail);
    std::size_t differ = 0;
    for (std::size_t k = 0; k < va.size(); ++k)
      differ += std::memcmp(&va[k], &vb[k], sizeof(double)) != 0;
    if (differ) check::fail(__FILE__, __LINE__, std::string(name) + ": " + std::to_string(differ) + " values differ");
  }
  const hsize_t components = d == 2 ? 3 : 5;
  const std::vector<double> sa = h5::read_doubles(fa.get(), "/restart/deviatoric_stress", n, {components});
  const std::vector<double> sb = h5::read_doubles(fb.get(), "/restart/deviatoric_stress", n, {components});
  CHECK(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(double)) == 0);
}

RunResult run(const std::string& scene_file, const fs::path& out, const std::vector<std::string>& extra) {
  // The automatic grid margin grows with end_time; a run to T/2 is the same run as one to T only
  // on the same grid (a restart keeps its run's grid whatever end_time it is given).
  std::vector<std::string> overrides = {"output_dir=" + out.string(), "snapshot_interval=30ns", "grid_margin=100um"};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return run_scene(load_scene(scene_file, overrides), {true, true, true});  // fixed threads: test what was asked
}

// The restart and thread-count checks on one scene, both ways of running it: the target alone with
// its mirror image, and the whole.
void restart_checks(const std::string& scene, const fs::path& root) {
  for (const std::string symmetry : {"symmetry=on", "symmetry=off"}) {
    const std::string tag = symmetry.substr(9) + "_";
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      const fs::path whole = root / (tag + "whole" + std::to_string(threads));
      const fs::path half = root / (tag + "half" + std::to_string(threads));
      CHECK(run(scene, whole, {"end_time=60ns", symmetry}).exit_code == kExitOk);
      CHECK(run(scene, half, {"end_time=30ns", symmetry}).exit_code == kExitOk);
      const RunResult r = restart_run((half / "snapshot_00001.h5").string(), {"end_time=60ns"}, {true, false, true});
      CHECK(r.exit_code == kExitOk);
      CHECK(std::abs(r.start_time - 30e-9) < 1e-20 && std::abs(r.end_time - 60e-9) < 1e-20);
      check_same_snapshot(whole / "snapshot_00002.h5", half / "snapshot_00002.h5");
      CHECK(slurp(whole / "regions.csv") == slurp(half / "regions.csv"));
      CHECK(slurp(whole / "conservation.csv") == slurp(half / "conservation.csv"));
      CHECK(slurp(whole / "snapshots.xdmf") == slurp(half / "snapshots.xdmf"));
      // A restart into a new directory continues the same way.
      const fs::path other = root / (tag + "other" + std::to_string(threads));
      CHECK(restart_run((half / "snapshot_00001.h5").string(), {"end_time=60ns", "output_dir=" + other.string()},
                        {true, false})
                .exit_code == kExitOk);
      check_same_snapshot(whole / "snapshot_00002.h5", other / "snapshot_00002.h5");
    }
    // The thread count changes nothing.
    check_same_snapshot(root / (tag + "whole1") / "snapshot_00002.h5", root / (tag + "whole2") / "snapshot_00002.h5");
    CHECK(slurp(root / (tag + "whole1") / "regions.csv") == slurp(root / (tag + "whole2") / "regions.csv"));
  }
}

// The last value of a CSV file's last column.
double last_column(const fs::path& csv) {
  const std::string text = slurp(csv);
  const std::size_t end = text.find_last_not_of('\n'), comma = text.rfind(',', end);
  return std::stod(text.substr(comma + 1, end - comma));
}

// A snapshot of an mpmshock before the points kept their own work-mismatch sums (format 1, no
// /restart/work_mismatch): the run goes on from its total, to within the rounding of the sums.
void older_snapshot_check(const fs::path& root) {
  const fs::path src = root / "older_src", out = root / "older";
  fs::create_directories(src);
  const fs::path snapshot = src / "snapshot_00001.h5";
  fs::copy_file(root / "off_half1" / "snapshot_00001.h5", snapshot);
  {
    h5::Handle f(H5Fopen(snapshot.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "open " + snapshot.string());
    CHECK(H5Ldelete(f.get(), "/restart/work_mismatch", H5P_DEFAULT) >= 0);
    CHECK(H5Adelete_by_name(f.get(), "restart", "work_mismatch_before", H5P_DEFAULT) >= 0);
    const std::int64_t one = 1;
    h5::Handle a(H5Aopen(f.get(), "format_version", H5P_DEFAULT), H5Aclose, "open format_version");
    CHECK(H5Awrite(a.get(), H5T_NATIVE_INT64, &one) >= 0);
  }
  {  // format 1 has no checksum in its user block
    std::fstream block(snapshot, std::ios::in | std::ios::out | std::ios::binary);
    const std::string zeros(64, '\0');
    block.write(zeros.data(), 64);
  }
  omp_set_num_threads(1);
  CHECK(restart_run(snapshot.string(), {"end_time=60ns", "output_dir=" + out.string()}, {true, false}).exit_code ==
        kExitOk);
  check_same_snapshot(root / "off_whole1" / "snapshot_00002.h5", out / "snapshot_00002.h5");
  const double whole = last_column(root / "off_whole1" / "conservation.csv"), older = last_column(out / "conservation.csv");
  CHECK(whole != 0.0 && std::abs(older - whole) <= 1e-9 * std::abs(whole));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return 2;
  const std::string scene = argv[1], scene_3d = argv[2];
  const fs::path root = fs::temp_directory_path() / ("mpmshock_test_restart_" + std::to_string(::getpid()));
  fs::remove_all(root);
  restart_checks(scene_3d, root / "3d");
  restart_checks(scene, root);
  older_snapshot_check(root);

  // Restarting mid-run would discard later outputs: refused without --force, allowed with it.
  CHECK_THROWS_WITH(restart_run((root / "on_whole1" / "snapshot_00001.h5").string(), {}, {true, false}), "--force",
                    "1 later snapshot");
  // Keys that are the saved state cannot change.
  CHECK_THROWS_WITH(restart_run((root / "on_whole1" / "snapshot_00002.h5").string(), {"cell_size=5um"}, {true, false}),
                    "'cell_size'", "cannot change on restart");
  CHECK_THROWS_WITH(restart_run((root / "on_whole1" / "snapshot_00002.h5").string(), {"symmetry=off"}, {true, false}),
                    "'symmetry'", "cannot change on restart");
  CHECK_THROWS_WITH(restart_run((root / "on_whole1" / "snapshot_00002.h5").string(), {}, {true, false}), "'end_time'",
                    "later end_time");
  CHECK_THROWS_WITH(read_snapshot<2>((root / "on_whole1" / "regions.csv").string()), "regions.csv");
  fs::remove_all(root);
  return check::result();
}
