#include "mpmshock/snapshot.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "mpmshock/hdf5_io.hpp"
#include "mpmshock/version.hpp"

namespace mpmshock {
namespace {

using h5::Compression;
using h5::Handle;

// Interleaves per-point fields into rows: rows[k * n + j] = fields[j][k].
std::vector<double> rows_of(std::size_t count, std::initializer_list<const std::vector<double>*> fields) {
  std::vector<double> out(count * fields.size());
  std::size_t j = 0;
  for (const std::vector<double>* f : fields) {
    for (std::size_t k = 0; k < count; ++k) out[k * fields.size() + j] = (*f)[k];
    ++j;
  }
  return out;
}

// The inverse of rows_of.
void split_rows(const std::vector<double>& rows, std::initializer_list<std::vector<double>*> fields) {
  const std::size_t n = fields.size(), count = rows.size() / n;
  std::size_t j = 0;
  for (std::vector<double>* f : fields) {
    f->resize(count);
    for (std::size_t k = 0; k < count; ++k) (*f)[k] = rows[k * n + j];
    ++j;
  }
}

void write_particles(hid_t file, const Particles& p, const HugoniotTemperature* thermal, int level) {
  Handle group(H5Gcreate2(file, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /particles");
  const hid_t g = group.get();
  const std::size_t n = p.size();
  const hsize_t N = n;
  const Compression always{level > 0 ? level : 1};  // fields that compress >100x: worth it at any setting
  const Compression chosen{level};
  auto doubles = [&](const char* name, const std::vector<double>& v, std::vector<hsize_t> dims, const char* units,
                     const char* what, Compression c) {
    h5::write_dataset(g, name, H5T_NATIVE_DOUBLE, v.data(), dims, units, what, c);
  };

  h5::write_dataset(g, "id", H5T_NATIVE_UINT32, p.id.data(), {N}, "", "stable material-point number", always);
  h5::write_dataset(g, "body", H5T_NATIVE_UINT8, p.body.data(), {N}, "", "0 flyer, 1 target", always);
  doubles("position", rows_of(n, {&p.x, &p.y}), {N, 2}, "m", "x, y", chosen);
  doubles("velocity", rows_of(n, {&p.vx, &p.vy}), {N, 2}, "m/s", "v_x, v_y", chosen);
  doubles("mass", p.mass, {N}, "kg/m", "mass per metre of depth (plane strain)", always);

  std::vector<double> scalar(n);
  for (std::size_t q = 0; q < n; ++q) scalar[q] = p.volume(q);
  doubles("volume", scalar, {N}, "m2", "volume per metre of depth (plane strain)", chosen);
  for (std::size_t q = 0; q < n; ++q) scalar[q] = p.density(q);
  doubles("density", scalar, {N}, "kg/m3", "density of the material point", chosen);
  doubles("pressure", p.pressure, {N}, "Pa", "Mie-Grueneisen pressure (without artificial viscosity)", chosen);
  doubles("artificial_viscosity", p.viscosity, {N}, "Pa", "artificial viscous pressure q", chosen);
  for (std::size_t q = 0; q < n; ++q) scalar[q] = thermal ? thermal->temperature(p.J(q), p.energy[q]) : std::nan("");
  doubles("temperature", scalar, {N}, "K", "T = T_H(V) + (E - E_H(V)) / c_v; NaN when thermal = off", chosen);
  doubles("internal_energy", p.energy, {N}, "J/kg", "specific internal energy, 0 at the reference state", chosen);

  std::vector<double> tensor(9 * n, 0.0);
  for (std::size_t q = 0; q < n; ++q) {
    const double pq = p.pressure[q] + p.viscosity[q];
    const double sxx = p.has_strength() ? p.sxx[q] : 0.0, syy = p.has_strength() ? p.syy[q] : 0.0;
    const double sxy = p.has_strength() ? p.sxy[q] : 0.0;
    double* t = &tensor[9 * q];
    t[0] = sxx - pq;
    t[1] = t[3] = sxy;
    t[4] = syy - pq;
    t[8] = -(sxx + syy) - pq;
  }
  doubles("stress", tensor, {N, 3, 3}, "Pa", "Cauchy stress s - (P + q) I, plane strain (zz non-zero)", chosen);
  for (std::size_t q = 0; q < n; ++q) scalar[q] = p.has_strength() ? p.plastic_strain[q] : 0.0;
  doubles("plastic_strain", scalar, {N}, "", "effective plastic strain", chosen);
  doubles("deformation_gradient", rows_of(n, {&p.Fxx, &p.Fxy, &p.Fyx, &p.Fyy}), {N, 2, 2}, "",
          "F, in-plane (F_zz = 1), F[i][j] = dx_i/dX_j", chosen);
  doubles("velocity_gradient", rows_of(n, {&p.Lxx, &p.Lxy, &p.Lyx, &p.Lyy}), {N, 2, 2}, "1/s",
          "L = grad v of the last step, L[i][j] = dv_i/dx_j", chosen);
}

void write_bodies(hid_t g, const RunState& run) {
  for (const BodySummary* b : {&run.target, &run.flyer}) {
    const std::string prefix = b->name + "_";
    h5::write_int_attribute(g, (prefix + "lattice_points").c_str(), static_cast<std::int64_t>(b->lattice_points));
    h5::write_int_attribute(g, (prefix + "material_points").c_str(), static_cast<std::int64_t>(b->material_points));
    h5::write_doubles_attribute(g, (prefix + "extent").c_str(), {b->y_bottom, b->y_top});
    std::vector<double> voids;
    for (const Void& v : b->voids) voids.insert(voids.end(), {v.x, v.y, v.r});
    const hsize_t M = b->voids.size();
    h5::write_dataset(g, (prefix + "voids").c_str(), H5T_NATIVE_DOUBLE, voids.data(), {M, 3}, "m",
                      "void centres x, y and radii", {1});
  }
}

void write_restart(hid_t file, const Particles& p, const RunState& run) {
  Handle group(H5Gcreate2(file, "restart", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /restart");
  const hid_t g = group.get();
  const std::size_t n = p.size();
  const hsize_t N = n;
  h5::write_double_attribute(g, "max_signal", run.clock.max_signal);
  h5::write_int_attribute(g, "next_sample", run.schedule.next_sample);
  h5::write_int_attribute(g, "next_snapshot", run.schedule.next_snapshot);
  h5::write_int_attribute(g, "snapshot_index", run.schedule.snapshot_index);
  h5::write_double_attribute(g, "last_dt", run.schedule.last_dt);
  const Totals& t = run.initial;
  h5::write_doubles_attribute(g, "initial_totals",
                              {t.mass, t.momentum_x, t.momentum_y, t.momentum_magnitude, t.kinetic, t.internal});
  h5::write_string_attribute(g, "random_state",
                             "none: random numbers are drawn only at set-up (the void layout, stored here)");
  write_bodies(g, run);
  h5::write_dataset(g, "volume0", H5T_NATIVE_DOUBLE, p.volume0.data(), {N}, "m2", "reference volume V0", {1});
  if (p.has_strength())
    h5::write_dataset(g, "deviatoric_stress", H5T_NATIVE_DOUBLE, rows_of(n, {&p.sxx, &p.syy, &p.sxy}).data(),
                      {N, 3}, "Pa", "s_xx, s_yy, s_xy (s_zz = -(s_xx + s_yy))");
  if (p.has_back_stress())
    h5::write_dataset(g, "back_stress", H5T_NATIVE_DOUBLE, rows_of(n, {&p.axx, &p.ayy, &p.axy}).data(), {N, 3}, "Pa",
                      "alpha_xx, alpha_yy, alpha_xy (kinematic hardening)");
}

void write_grid(hid_t file, const SnapshotOptions& o) {
  const Grid& grid = *o.grid;
  const GridGeometry& geo = grid.geo;
  Handle group(H5Gcreate2(file, "grid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /grid");
  const hid_t g = group.get();
  h5::write_doubles_attribute(g, "origin", {0.0, geo.y_min});
  h5::write_double_attribute(g, "spacing", geo.h);
  h5::write_doubles_attribute(g, "nodes", {static_cast<double>(geo.nx), static_cast<double>(geo.ny)});
  const std::size_t nodes = geo.nodes();
  std::vector<double> mass(nodes, 0.0), vx(nodes, 0.0), vy(nodes, 0.0);
  const std::size_t b = geo.node(0, o.grid_row_begin), e = geo.node(0, o.grid_row_end);
  for (std::size_t i = b; i < e; ++i) {
    if (!(grid.m[i] > 0.0)) continue;
    mass[i] = grid.m[i];
    vx[i] = grid.vx[i];
    vy[i] = grid.vy[i];
  }
  // Row j, column i is the node at (i h, y_min + j h).
  const hsize_t rows = static_cast<hsize_t>(geo.ny), cols = static_cast<hsize_t>(geo.nx);
  h5::write_dataset(g, "mass", H5T_NATIVE_DOUBLE, mass.data(), {rows, cols}, "kg/m", "nodal mass m_i", {1});
  h5::write_dataset(g, "velocity_x", H5T_NATIVE_DOUBLE, vx.data(), {rows, cols}, "m/s",
                    "nodal v_x after the last step's momentum update", {1});
  h5::write_dataset(g, "velocity_y", H5T_NATIVE_DOUBLE, vy.data(), {rows, cols}, "m/s",
                    "nodal v_y after the last step's momentum update", {1});
}

}  // namespace

void write_snapshot(const std::string& path, const Particles& p, const HugoniotTemperature* thermal,
                    const RunState& run, const SnapshotOptions& options) {
  h5::prepare_library();
  const std::string tmp = path + ".tmp";
  try {
    {
      Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create " + tmp);
      const hid_t f = file.get();
      h5::write_double_attribute(f, "time", run.clock.time);
      h5::write_int_attribute(f, "step", run.clock.steps);
      h5::write_int_attribute(f, "snapshot", run.schedule.snapshot_index);
      h5::write_int_attribute(f, "particle_count", static_cast<std::int64_t>(p.size()));
      h5::write_string_attribute(f, "units",
                                 "SI: m, s, kg, Pa, K, J/kg; 2D plane strain, extensive quantities per metre of depth");
      h5::write_string_attribute(f, "scene", run.scene_text);
      h5::write_string_attribute(f, "mpmshock_version", kVersion);
      h5::write_int_attribute(f, "format_version", 1);
      write_particles(f, p, thermal, options.compression);
      write_restart(f, p, run);
      if (options.grid) write_grid(f, options);
      h5::check(H5Fflush(f, H5F_SCOPE_GLOBAL), "flush " + tmp);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + ec.message());
  } catch (const std::runtime_error& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("writing snapshot " + path + ": " + e.what() +
                             " (is the disk full or the directory not writable?); earlier snapshots are complete");
  }
}

SnapshotHeader read_snapshot_header(const std::string& path) {
  h5::prepare_library();
  try {
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open it as HDF5");
    SnapshotHeader h;
    h.time = h5::read_double_attribute(file.get(), "time");
    h.points = static_cast<std::size_t>(h5::read_int_attribute(file.get(), "particle_count"));
    h.grid = h5::has_link(file.get(), "grid");
    return h;
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("snapshot " + path + ": " + e.what());
  }
}

Restart read_snapshot(const std::string& path) {
  h5::prepare_library();
  try {
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open it as HDF5");
    const hid_t f = file.get();
    if (!h5::has_attribute(f, "format_version") || !h5::has_link(f, "restart"))
      throw std::runtime_error("not an mpmshock snapshot with restart data");
    Restart r;
    RunState& run = r.run;
    run.scene_text = h5::read_string_attribute(f, "scene");
    run.clock.time = h5::read_double_attribute(f, "time");
    run.clock.steps = h5::read_int_attribute(f, "step");
    const auto n = static_cast<std::size_t>(h5::read_int_attribute(f, "particle_count"));

    Handle rg(H5Gopen2(f, "restart", H5P_DEFAULT), H5Gclose, "open /restart");
    const hid_t g = rg.get();
    run.clock.max_signal = h5::read_double_attribute(g, "max_signal");
    run.schedule.snapshot_index = static_cast<int>(h5::read_int_attribute(g, "snapshot_index"));
    run.schedule.last_dt = h5::read_double_attribute(g, "last_dt");
    const std::vector<double> t = h5::read_doubles_attribute(g, "initial_totals");
    if (t.size() != 6) throw std::runtime_error("/restart initial_totals has the wrong length");
    run.initial = {t[0], t[1], t[2], t[3], t[4], t[5]};
    for (BodySummary* b : {&run.target, &run.flyer}) {
      b->name = b == &run.target ? "target" : "flyer";
      const std::string prefix = b->name + "_";
      b->lattice_points = static_cast<std::size_t>(h5::read_int_attribute(g, (prefix + "lattice_points").c_str()));
      b->material_points = static_cast<std::size_t>(h5::read_int_attribute(g, (prefix + "material_points").c_str()));
      const std::vector<double> extent = h5::read_doubles_attribute(g, (prefix + "extent").c_str());
      if (extent.size() == 2) {
        b->y_bottom = extent[0];
        b->y_top = extent[1];
      }
      b->porosity = static_cast<double>(b->lattice_points) / static_cast<double>(b->material_points);
      const std::vector<double> v = h5::read_doubles(g, (prefix + "voids").c_str(), 0, {3});
      for (std::size_t k = 0; k + 2 < v.size(); k += 3) b->voids.push_back({v[k], v[k + 1], v[k + 2]});
    }

    Particles& p = r.points;
    const bool strength = h5::has_link(g, "deviatoric_stress"), back = h5::has_link(g, "back_stress");
    p.id = h5::read_uint32(f, "/particles/id", n);
    const std::vector<std::uint8_t> body = h5::read_uint8(f, "/particles/body", n);
    p.body.resize(n);
    for (std::size_t q = 0; q < n; ++q) p.body[q] = body[q] ? Body::target : Body::flyer;
    split_rows(h5::read_doubles(f, "/particles/position", n, {2}), {&p.x, &p.y});
    split_rows(h5::read_doubles(f, "/particles/velocity", n, {2}), {&p.vx, &p.vy});
    p.mass = h5::read_doubles(f, "/particles/mass", n, {});
    p.volume0 = h5::read_doubles(g, "volume0", n, {});
    split_rows(h5::read_doubles(f, "/particles/deformation_gradient", n, {2, 2}), {&p.Fxx, &p.Fxy, &p.Fyx, &p.Fyy});
    split_rows(h5::read_doubles(f, "/particles/velocity_gradient", n, {2, 2}), {&p.Lxx, &p.Lxy, &p.Lyx, &p.Lyy});
    p.energy = h5::read_doubles(f, "/particles/internal_energy", n, {});
    p.pressure = h5::read_doubles(f, "/particles/pressure", n, {});
    p.viscosity = h5::read_doubles(f, "/particles/artificial_viscosity", n, {});
    p.enable_strength(strength, back);
    if (strength) {
      split_rows(h5::read_doubles(g, "deviatoric_stress", n, {3}), {&p.sxx, &p.syy, &p.sxy});
      p.plastic_strain = h5::read_doubles(f, "/particles/plastic_strain", n, {});
    }
    if (back) split_rows(h5::read_doubles(g, "back_stress", n, {3}), {&p.axx, &p.ayy, &p.axy});
    return r;
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("snapshot " + path + ": " + e.what());
  }
}

}  // namespace mpmshock
