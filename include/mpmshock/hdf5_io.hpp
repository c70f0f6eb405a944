// Thin RAII and typed helpers over the HDF5 C API, shared by the snapshot writer and reader.
// Failures throw std::runtime_error with what was being done; callers add the file name.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace mpmshock::h5 {

// Owns one HDF5 handle and closes it with the matching call.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what);
  ~Handle();
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t status, const std::string& what);

// Call before any other HDF5 use: errors become exceptions with our own words (not HDF5's stack
// dump on stderr), and HDF5 registers no exit handler. Every file is closed by its Handle; after a
// write fails (a full disk), HDF5 1.10's exit handler would crash closing that file again.
void prepare_library();

struct Compression {
  int level = 0;  // gzip level with byte shuffle; 0: stored as is
};

void write_string_attribute(hid_t loc, const char* name, const std::string& value);
void write_double_attribute(hid_t loc, const char* name, double value);
void write_int_attribute(hid_t loc, const char* name, std::int64_t value);
void write_doubles_attribute(hid_t loc, const char* name, const std::vector<double>& values);

// A dataset of dims (rows first) with `units` and `description` attributes; chunked by rows when
// compressed.
void write_dataset(hid_t group, const char* name, hid_t mem_type, const void* data, const std::vector<hsize_t>& dims,
                   const char* units, const char* description, Compression compression = {});

// The same dataset written a slab of rows at a time (a snapshot streams its points in chunks).
class RowWriter {
 public:
  RowWriter(hid_t group, const char* name, hid_t mem_type, std::vector<hsize_t> dims, const char* units,
            const char* description, Compression compression = {});
  // Rows [first, first + rows) from `data`, rows first as in dims.
  void write(hsize_t first, hsize_t rows, const void* data);

 private:
  Handle set_;
  hid_t type_;
  std::vector<hsize_t> dims_;
  std::string name_;
};

std::string read_string_attribute(hid_t loc, const char* name);
double read_double_attribute(hid_t loc, const char* name);
std::int64_t read_int_attribute(hid_t loc, const char* name);
std::vector<double> read_doubles_attribute(hid_t loc, const char* name);
bool has_attribute(hid_t loc, const char* name);
bool has_link(hid_t loc, const char* path);

// Rows [first, end) of a dataset (cut to the rows it has; the default: all of them).
struct Rows {
  std::size_t first = 0, end = static_cast<std::size_t>(-1);
};

// Reads a dataset's rows, checking its shape: rows == expected_rows (if non-zero) and the
// trailing dimensions equal `tail`.
std::vector<double> read_doubles(hid_t loc, const char* path, std::size_t expected_rows,
                                 const std::vector<hsize_t>& tail, Rows rows = {});
std::vector<std::uint32_t> read_uint32(hid_t loc, const char* path, std::size_t expected_rows, Rows rows = {});

// A dataset's raw values in the machine's native form, and its dimensions: the bytes a writer
// handed to write_dataset with the same native type.
std::vector<unsigned char> read_raw(hid_t loc, const char* path, std::vector<hsize_t>& dims);
// The names of the datasets directly in a group, in name order (none if the group is absent).
std::vector<std::string> dataset_names(hid_t loc, const char* group);
std::vector<std::uint8_t> read_uint8(hid_t loc, const char* path, std::size_t expected_rows, Rows rows = {});

}  // namespace mpmshock::h5
