#include "mpmshock/hdf5_io.hpp"

#include <algorithm>
#include <stdexcept>

namespace mpmshock::h5 {

Handle::Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
  if (id_ < 0) throw std::runtime_error("cannot " + what);
}

Handle::~Handle() {
  if (id_ >= 0) close_(id_);
}

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("cannot " + what);
}

void prepare_library() {
  static const bool once = [] {
    H5dont_atexit();  // must come before the library's first initialisation
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)once;
}

namespace {

Handle string_type() {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "make a string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), "size a string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "set UTF-8");
  return type;
}

template <class T>
void write_attribute(hid_t loc, const char* name, hid_t type, const T* values, hsize_t count) {
  Handle space(count == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr), H5Sclose,
               "make an attribute space");
  Handle attr(H5Acreate2(loc, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  check(H5Awrite(attr.get(), type, values), std::string("write attribute ") + name);
}

// A damaged header cannot make us allocate what the file does not hold: gzip compresses our most
// repetitive fields ~230x, so more than 1024x the stored bytes (plus 1 MiB) is damage.
void check_plausible_size(hid_t set, double bytes, const char* path) {
  const double stored = static_cast<double>(H5Dget_storage_size(set));
  if (bytes > 1024.0 * stored + 1048576.0)
    throw std::runtime_error(std::string("dataset ") + path + " claims more values than the file holds");
}

// Selects rows [first, first + rows) of a dataset's space `dims` in `file_space` (each with its trailing
// dimensions whole); returns the memory space of those rows.
Handle select_rows(hid_t file_space, const std::vector<hsize_t>& dims, hsize_t first, hsize_t rows,
                   const std::string& name) {
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = first;
  count[0] = rows;
  check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select rows of " + name);
  return Handle(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose,
                "make the memory space of " + name);
}

template <class T>
std::vector<T> read_rows(hid_t loc, const char* path, hid_t mem_type, std::size_t expected_rows,
                         const std::vector<hsize_t>& tail, Rows rows) {
  Handle set(H5Dopen2(loc, path, H5P_DEFAULT), H5Dclose, std::string("open dataset ") + path);
  Handle space(H5Dget_space(set.get()), H5Sclose, std::string("read the shape of ") + path);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank > 0 ? rank : 0));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  bool ok = rank == static_cast<int>(1 + tail.size()) && (expected_rows == 0 || dims[0] == expected_rows);
  for (std::size_t k = 0; ok && k < tail.size(); ++k) ok = dims[k + 1] == tail[k];
  if (!ok) throw std::runtime_error(std::string("dataset ") + path + " has an unexpected shape");
  double count_d = 1.0;
  for (hsize_t d : dims) count_d *= static_cast<double>(d);
  check_plausible_size(set.get(), count_d * sizeof(T), path);
  // Rows [first, end) of the dataset's (cut to those it has).
  const hsize_t first = std::min<hsize_t>(rows.first, dims[0]), end = std::clamp<hsize_t>(rows.end, first, dims[0]);
  std::size_t values = end - first;
  for (std::size_t k = 1; k < dims.size(); ++k) values *= static_cast<std::size_t>(dims[k]);
  std::vector<T> out(values);
  if (values == 0) return out;
  const Handle memory = select_rows(space.get(), dims, first, end - first, path);
  check(H5Dread(set.get(), mem_type, memory.get(), space.get(), H5P_DEFAULT, out.data()), std::string("read ") + path);
  return out;
}

}  // namespace

void write_string_attribute(hid_t loc, const char* name, const std::string& value) {
  const Handle type = string_type();
  const char* text = value.c_str();
  write_attribute(loc, name, type.get(), &text, 1);
}

void write_double_attribute(hid_t loc, const char* name, double value) {
  write_attribute(loc, name, H5T_NATIVE_DOUBLE, &value, 1);
}

void write_int_attribute(hid_t loc, const char* name, std::int64_t value) {
  write_attribute(loc, name, H5T_NATIVE_INT64, &value, 1);
}

void write_doubles_attribute(hid_t loc, const char* name, const std::vector<double>& values) {
  write_attribute(loc, name, H5T_NATIVE_DOUBLE, values.data(), values.size());
}

namespace {

Handle create_dataset(hid_t group, const char* name, hid_t mem_type, const std::vector<hsize_t>& dims,
                      Compression compression) {
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
               std::string("make the dataspace of ") + name);
  Handle create(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "make dataset properties");
  if (compression.level > 0 && dims[0] > 0) {
    // Chunks of up to 64 Ki rows: large enough for deflate, small enough to read a slice.
    std::vector<hsize_t> chunk = dims;
    chunk[0] = dims[0] < 65536 ? dims[0] : 65536;
    check(H5Pset_chunk(create.get(), static_cast<int>(chunk.size()), chunk.data()), "chunk a dataset");
    check(H5Pset_shuffle(create.get()), "set the shuffle filter");
    check(H5Pset_deflate(create.get(), static_cast<unsigned>(compression.level)), "set the deflate filter");
  }
  return Handle(H5Dcreate2(group, name, mem_type, space.get(), H5P_DEFAULT, create.get(), H5P_DEFAULT), H5Dclose,
                std::string("create dataset ") + name);
}

}  // namespace

RowWriter::RowWriter(hid_t group, const char* name, hid_t mem_type, std::vector<hsize_t> dims, const char* units,
                     const char* description, Compression compression)
    : set_(create_dataset(group, name, mem_type, dims, compression)), type_(mem_type), dims_(std::move(dims)),
      name_(name) {
  write_string_attribute(set_.get(), "units", units);
  write_string_attribute(set_.get(), "description", description);
}

void RowWriter::write(hsize_t first, hsize_t rows, const void* data) {
  if (rows == 0) return;
  Handle file_space(H5Dget_space(set_.get()), H5Sclose, "read the shape of " + name_);
  const Handle memory = select_rows(file_space.get(), dims_, first, rows, name_);
  check(H5Dwrite(set_.get(), type_, memory.get(), file_space.get(), H5P_DEFAULT, data), "write " + name_);
}

void write_dataset(hid_t group, const char* name, hid_t mem_type, const void* data, const std::vector<hsize_t>& dims,
                   const char* units, const char* description, Compression compression) {
  RowWriter writer(group, name, mem_type, dims, units, description, compression);
  writer.write(0, dims[0], data);
}

std::string read_string_attribute(hid_t loc, const char* name) {
  Handle attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  Handle type(H5Aget_type(attr.get()), H5Tclose, std::string("read the type of ") + name);
  if (H5Tget_class(type.get()) != H5T_STRING) throw std::runtime_error(std::string("attribute ") + name + " is not text");
  const Handle mem = string_type();
  char* text = nullptr;
  check(H5Aread(attr.get(), mem.get(), &text), std::string("read attribute ") + name);
  std::string out = text ? text : "";
  Handle space(H5Aget_space(attr.get()), H5Sclose, "read an attribute space");
#if H5_VERSION_GE(1, 12, 0)
  H5Treclaim(mem.get(), space.get(), H5P_DEFAULT, &text);
#else
  H5Dvlen_reclaim(mem.get(), space.get(), H5P_DEFAULT, &text);
#endif
  return out;
}

double read_double_attribute(hid_t loc, const char* name) {
  Handle attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  double v = 0;
  check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v), std::string("read attribute ") + name);
  return v;
}

std::int64_t read_int_attribute(hid_t loc, const char* name) {
  Handle attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  std::int64_t v = 0;
  check(H5Aread(attr.get(), H5T_NATIVE_INT64, &v), std::string("read attribute ") + name);
  return v;
}

std::vector<double> read_doubles_attribute(hid_t loc, const char* name) {
  Handle attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  Handle space(H5Aget_space(attr.get()), H5Sclose, "read an attribute space");
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<double> v(static_cast<std::size_t>(n > 0 ? n : 0));
  if (!v.empty()) check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, v.data()), std::string("read attribute ") + name);
  return v;
}

bool has_attribute(hid_t loc, const char* name) { return H5Aexists(loc, name) > 0; }

bool has_link(hid_t loc, const char* path) { return H5Lexists(loc, path, H5P_DEFAULT) > 0; }

std::vector<double> read_doubles(hid_t loc, const char* path, std::size_t expected_rows,
                                 const std::vector<hsize_t>& tail, Rows rows) {
  return read_rows<double>(loc, path, H5T_NATIVE_DOUBLE, expected_rows, tail, rows);
}

std::vector<std::uint32_t> read_uint32(hid_t loc, const char* path, std::size_t expected_rows, Rows rows) {
  return read_rows<std::uint32_t>(loc, path, H5T_NATIVE_UINT32, expected_rows, {}, rows);
}

std::vector<unsigned char> read_raw(hid_t loc, const char* path, std::vector<hsize_t>& dims) {
  Handle set(H5Dopen2(loc, path, H5P_DEFAULT), H5Dclose, std::string("open dataset ") + path);
  Handle space(H5Dget_space(set.get()), H5Sclose, std::string("read the shape of ") + path);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0 || rank > 8) throw std::runtime_error(std::string("dataset ") + path + " has an unexpected rank");
  dims.assign(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  Handle file_type(H5Dget_type(set.get()), H5Tclose, std::string("read the type of ") + path);
  Handle type(H5Tget_native_type(file_type.get(), H5T_DIR_ASCEND), H5Tclose, std::string("read the type of ") + path);
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > 64 || H5Tis_variable_str(type.get()) > 0)
    throw std::runtime_error(std::string("dataset ") + path + " has an unexpected type");
  // No larger than the file holds: a damaged header cannot make us allocate what is not there.
  const double count = [&] {
    double c = 1.0;
    for (hsize_t d : dims) c *= static_cast<double>(d);
    return c;
  }();
  check_plausible_size(set.get(), count * static_cast<double>(size), path);
  std::vector<unsigned char> out(static_cast<std::size_t>(count) * size);
  if (!out.empty())
    check(H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), std::string("read ") + path);
  return out;
}

std::vector<std::string> dataset_names(hid_t loc, const char* group) {
  std::vector<std::string> names;
  if (!has_link(loc, group)) return names;
  Handle g(H5Gopen2(loc, group, H5P_DEFAULT), H5Gclose, std::string("open group ") + group);
  hsize_t index = 0;
  auto visit = [](hid_t parent, const char* name, const H5L_info_t*, void* out) -> herr_t {
    H5O_info_t info;
#if H5_VERSION_GE(1, 12, 0)
    if (H5Oget_info_by_name3(parent, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) return -1;
#else
    if (H5Oget_info_by_name2(parent, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) return -1;
#endif
    if (info.type == H5O_TYPE_DATASET) static_cast<std::vector<std::string>*>(out)->push_back(name);
    return 0;
  };
  check(H5Literate(g.get(), H5_INDEX_NAME, H5_ITER_INC, &index, visit, &names), std::string("list group ") + group);
  return names;
}

std::vector<std::uint8_t> read_uint8(hid_t loc, const char* path, std::size_t expected_rows, Rows rows) {
  return read_rows<std::uint8_t>(loc, path, H5T_NATIVE_UINT8, expected_rows, {}, rows);
}

}  // namespace mpmshock::h5
