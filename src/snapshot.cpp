#include "mpmshock/snapshot.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "mpmshock/version.hpp"

namespace mpmshock {
namespace {

// Owns one HDF5 handle; closes it with the matching call.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("HDF5: cannot " + what);
  }
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: cannot " + what);
}

void write_string_attribute(hid_t loc, const char* name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "make a string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), "size a string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "set UTF-8");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "make a scalar space");
  Handle attr(H5Acreate2(loc, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  const char* text = value.c_str();
  check(H5Awrite(attr.get(), type.get(), &text), std::string("write attribute ") + name);
}

template <class T>
void write_scalar_attribute(hid_t loc, const char* name, hid_t type, T value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "make a scalar space");
  Handle attr(H5Acreate2(loc, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  check(H5Awrite(attr.get(), type, &value), std::string("write attribute ") + name);
}

void write_dataset(hid_t group, const char* name, hid_t mem_type, const void* data, std::vector<hsize_t> dims,
                   const char* units, const char* description) {
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
               std::string("make the dataspace of ") + name);
  Handle set(H5Dcreate2(group, name, mem_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
             std::string("create dataset ") + name);
  if (dims[0] > 0) check(H5Dwrite(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), std::string("write ") + name);
  write_string_attribute(set.get(), "units", units);
  write_string_attribute(set.get(), "description", description);
}

void write_doubles(hid_t group, const char* name, const std::vector<double>& v, std::vector<hsize_t> dims,
                   const char* units, const char* description) {
  write_dataset(group, name, H5T_NATIVE_DOUBLE, v.data(), std::move(dims), units, description);
}

void write_particles(hid_t file, const Particles& p, const Model& model, const HugoniotTemperature* thermal) {
  Handle group(H5Gcreate2(file, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
               "create group /particles");
  const hid_t g = group.get();
  const std::size_t n = p.size();
  const hsize_t N = n;

  write_dataset(g, "id", H5T_NATIVE_UINT32, p.id.data(), {N}, "", "stable material-point number");
  write_dataset(g, "body", H5T_NATIVE_UINT8, p.body.data(), {N}, "", "0 flyer, 1 target");

  std::vector<double> buf(2 * n);
  for (std::size_t q = 0; q < n; ++q) {
    buf[2 * q] = p.x[q];
    buf[2 * q + 1] = p.y[q];
  }
  write_doubles(g, "position", buf, {N, 2}, "m", "x, y");
  for (std::size_t q = 0; q < n; ++q) {
    buf[2 * q] = p.vx[q];
    buf[2 * q + 1] = p.vy[q];
  }
  write_doubles(g, "velocity", buf, {N, 2}, "m/s", "v_x, v_y");

  write_doubles(g, "mass", p.mass, {N}, "kg/m", "mass per metre of depth (plane strain)");
  std::vector<double> scalar(n);
  for (std::size_t q = 0; q < n; ++q) scalar[q] = p.volume(q);
  write_doubles(g, "volume", scalar, {N}, "m2", "volume per metre of depth (plane strain)");
  for (std::size_t q = 0; q < n; ++q) scalar[q] = p.density(q);
  write_doubles(g, "density", scalar, {N}, "kg/m3", "density of the material point");
  write_doubles(g, "pressure", p.pressure, {N}, "Pa", "Mie-Grueneisen pressure (without artificial viscosity)");
  write_doubles(g, "artificial_viscosity", p.viscosity, {N}, "Pa", "artificial viscous pressure q");
  for (std::size_t q = 0; q < n; ++q) scalar[q] = thermal ? thermal->temperature(p.J(q), p.energy[q]) : std::nan("");
  write_doubles(g, "temperature", scalar, {N}, "K", "T = T_H(V) + (E - E_H(V)) / c_v; NaN when thermal = off");
  write_doubles(g, "internal_energy", p.energy, {N}, "J/kg", "specific internal energy, 0 at the reference state");

  std::vector<double> tensor(9 * n, 0.0);
  for (std::size_t q = 0; q < n; ++q) {
    const double pq = p.pressure[q] + p.viscosity[q];
    double sxx = 0.0, syy = 0.0, sxy = 0.0;
    if (p.has_strength()) {
      sxx = p.sxx[q];
      syy = p.syy[q];
      sxy = p.sxy[q];
    }
    double* t = &tensor[9 * q];
    t[0] = sxx - pq;
    t[1] = t[3] = sxy;
    t[4] = syy - pq;
    t[8] = -(sxx + syy) - pq;
  }
  write_doubles(g, "stress", tensor, {N, 3, 3}, "Pa", "Cauchy stress s - (P + q) I, plane strain (zz non-zero)");

  for (std::size_t q = 0; q < n; ++q) scalar[q] = p.has_strength() ? p.plastic_strain[q] : 0.0;
  write_doubles(g, "plastic_strain", scalar, {N}, "", "effective plastic strain");

  std::vector<double> mat(4 * n);
  for (std::size_t q = 0; q < n; ++q) {
    mat[4 * q] = p.Fxx[q];
    mat[4 * q + 1] = p.Fxy[q];
    mat[4 * q + 2] = p.Fyx[q];
    mat[4 * q + 3] = p.Fyy[q];
  }
  write_doubles(g, "deformation_gradient", mat, {N, 2, 2}, "", "F, in-plane (F_zz = 1)");
  for (std::size_t q = 0; q < n; ++q) {
    mat[4 * q] = p.Lxx[q];
    mat[4 * q + 1] = p.Lxy[q];
    mat[4 * q + 2] = p.Lyx[q];
    mat[4 * q + 3] = p.Lyy[q];
  }
  write_doubles(g, "velocity_gradient", mat, {N, 2, 2}, "1/s", "L = grad v of the last step, L[i][j] = dv_i/dx_j");
  (void)model;
}

}  // namespace

void write_snapshot(const std::string& path, const Particles& p, const Model& model,
                    const HugoniotTemperature* thermal, const SnapshotMeta& meta) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions with our own words
  const std::string tmp = path + ".tmp";
  try {
    {
      Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create " + tmp);
      const hid_t f = file.get();
      write_scalar_attribute(f, "time", H5T_NATIVE_DOUBLE, meta.time);
      write_scalar_attribute(f, "step", H5T_NATIVE_INT64, meta.step);
      write_scalar_attribute(f, "snapshot", H5T_NATIVE_INT32, meta.index);
      write_scalar_attribute(f, "particle_count", H5T_NATIVE_UINT64, static_cast<std::uint64_t>(p.size()));
      write_string_attribute(f, "units", "SI: m, s, kg, Pa, K, J/kg; 2D plane strain, extensive quantities per metre of depth");
      write_string_attribute(f, "scene", meta.scene);
      write_string_attribute(f, "mpmshock_version", kVersion);
      write_particles(f, p, model, thermal);
      check(H5Fflush(f, H5F_SCOPE_GLOBAL), "flush " + tmp);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + ec.message());
  } catch (const std::runtime_error& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("writing snapshot " + path + ": " + e.what());
  }
}

}  // namespace mpmshock
