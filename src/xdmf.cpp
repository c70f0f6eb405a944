#include "mpmshock/xdmf.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace mpmshock {
namespace {

std::string dims(std::size_t n, const std::string& tail) {
  return std::to_string(n) + (tail.empty() ? "" : " " + tail);
}

void data_item(std::ostringstream& x, const std::string& dimensions, const std::string& source, const char* indent) {
  x << indent << "<DataItem Dimensions=\"" << dimensions << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
    << source << "</DataItem>\n";
}

// A point field straight from the file: AttributeType Scalar or Tensor (3 x 3).
void attribute(std::ostringstream& x, const XdmfSnapshot& s, const char* name, const char* type, const char* tail) {
  x << "        <Attribute Name=\"" << name << "\" AttributeType=\"" << type << "\" Center=\"Node\">\n";
  data_item(x, dims(s.points, tail), s.file + ":/particles/" + name, "          ");
  x << "        </Attribute>\n";
}

// What follows works around ParaView's XDMF2 reader, checked against ParaView 5.11 (docs/
// output-format.md): it takes only the last dimension as components, it reads an HDF5 dataset
// only with its own rank, and functions of rank-3 inputs fail. A JOIN function reshapes without
// copying the file's layout.

// A D x D matrix per point (N x D x D in the file) presented as D^2 components: a Matrix in 2D, a
// Tensor in 3D.
void matrix(std::ostringstream& x, const XdmfSnapshot& s, const char* name) {
  const int d = s.dimension;
  x << "        <Attribute Name=\"" << name << "\" AttributeType=\"" << (d == 2 ? "Matrix" : "Tensor")
    << "\" Center=\"Node\">\n"
    << "          <DataItem ItemType=\"Function\" Function=\"JOIN($0)\" Dimensions=\"" << s.points << " " << d * d
    << "\">\n";
  data_item(x, dims(s.points, std::to_string(d) + " " + std::to_string(d)), s.file + ":/particles/" + name,
            "            ");
  x << "          </DataItem>\n        </Attribute>\n";
}

// The points' velocity: in 3D straight from the file (N x 3); in 2D (N x 2 in the file) presented
// as 3-vectors (v_x, v_y, 0), since ParaView's glyphs want three components: each column is cut
// out with a hyperslab, and the two and a zero are joined.
void point_velocity(std::ostringstream& x, const XdmfSnapshot& s) {
  if (s.dimension == 3) {
    attribute(x, s, "velocity", "Vector", "3");
    return;
  }
  const std::string n = std::to_string(s.points);
  x << "        <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n"
    << "          <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, 0 * $0)\" Dimensions=\"" << n << " 3\">\n";
  for (int column = 0; column < 2; ++column) {
    x << "            <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << n << " 1\" Type=\"HyperSlab\">\n"
      << "              <DataItem Dimensions=\"3 2\" Format=\"XML\">0 " << column << " 1 1 " << n << " 1</DataItem>\n";
    data_item(x, n + " 2", s.file + ":/particles/velocity", "              ");
    x << "            </DataItem>\n";
  }
  x << "          </DataItem>\n        </Attribute>\n";
}

// A grid field (ny x nx in the file; nz x ny x nx in 3D) on the grid's 3D mesh (one node thick in
// 2D), as a scalar or, joined with a zero z component in 2D, a vector.
void grid_field(std::ostringstream& x, const XdmfSnapshot& s, const char* name, std::initializer_list<const char*> parts) {
  const std::string nodes = std::to_string(s.ny) + " " + std::to_string(s.nx);
  const std::string in_file = s.dimension == 3 ? std::to_string(s.nz) + " " + nodes : nodes;
  const bool vector = parts.size() > 1;
  const char* join = !vector ? "JOIN($0)" : parts.size() == 2 ? "JOIN($0, $1, 0 * $0)" : "JOIN($0, $1, $2)";
  x << "        <Attribute Name=\"" << name << "\" AttributeType=\"" << (vector ? "Vector" : "Scalar")
    << "\" Center=\"Node\">\n"
    << "          <DataItem ItemType=\"Function\" Function=\"" << join << "\" Dimensions=\""
    << (s.dimension == 3 ? std::to_string(s.nz) : std::string("1")) << " " << nodes << (vector ? " 3" : "") << "\">\n";
  for (const char* part : parts) data_item(x, in_file, s.file + ":/grid/" + part, "            ");
  x << "          </DataItem>\n        </Attribute>\n";
}

}  // namespace

namespace {

constexpr const char* kHead =
    "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n  <Domain>\n"
    "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
constexpr const char* kFoot = "  </Domain>\n</Xdmf>\n";

// One time step of the point cloud.
std::string particle_step(const XdmfSnapshot& s) {
  std::ostringstream x;
  x.precision(17);
  x << "      <Grid Name=\"" << s.file << "\" GridType=\"Uniform\">\n";
  x << "        <Time Value=\"" << s.time << "\" />\n";
  x << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << s.points << "\" NodesPerElement=\"1\" />\n";
  x << "        <Geometry GeometryType=\"" << (s.dimension == 3 ? "XYZ" : "XY") << "\">\n";
  data_item(x, dims(s.points, std::to_string(s.dimension)), s.file + ":/particles/position", "          ");
  x << "        </Geometry>\n";
  for (const char* name : {"density", "pressure", "temperature", "internal_energy", "plastic_strain", "damage", "melted",
                           "viscous_pressure", "mass", "volume"})
    attribute(x, s, name, "Scalar", "");
  point_velocity(x, s);
  attribute(x, s, "stress", "Tensor", "3 3");
  matrix(x, s, "deformation_gradient");
  matrix(x, s, "velocity_gradient");
  x << "        <Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\">\n          <DataItem Dimensions=\""
    << s.points << "\" NumberType=\"UInt\" Precision=\"4\" Format=\"HDF\">" << s.file
    << ":/particles/id</DataItem>\n        </Attribute>\n";
  x << "        <Attribute Name=\"body\" AttributeType=\"Scalar\" Center=\"Node\">\n          <DataItem Dimensions=\""
    << s.points << "\" NumberType=\"UChar\" Precision=\"1\" Format=\"HDF\">" << s.file
    << ":/particles/body</DataItem>\n        </Attribute>\n";
  x << "      </Grid>\n";
  return x.str();
}

// One time step of the grid (snapshot_grid = on).
std::string grid_step(const XdmfSnapshot& s) {
  std::ostringstream x;
  x.precision(17);
  x << "      <Grid Name=\"" << s.file << " grid\" GridType=\"Uniform\">\n";
  x << "        <Time Value=\"" << s.time << "\" />\n";
  // A 3D co-rectilinear mesh (one node thick in 2D): dimensions, origin and spacing in z, y, x
  // order. (ParaView lays a 2DCoRectMesh in its y-z plane.)
  x << "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << (s.dimension == 3 ? s.nz : 1) << " " << s.ny
    << " " << s.nx << "\" />\n";
  x << "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n";
  x << "          <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">0 " << s.y_min
    << " 0</DataItem>\n";
  x << "          <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
    << (s.dimension == 3 ? s.h : 1.0) << " " << s.h << " " << s.h << "</DataItem>\n";
  x << "        </Geometry>\n";
  grid_field(x, s, "mass", {"mass"});
  if (s.dimension == 3) grid_field(x, s, "velocity", {"velocity_x", "velocity_y", "velocity_z"});
  else grid_field(x, s, "velocity", {"velocity_x", "velocity_y"});
  x << "      </Grid>\n";
  return x.str();
}

// What follows the point cloud's steps: its closing tag, the grid collection, the end.
std::string tail(const std::string& grid_steps) {
  std::string t = "    </Grid>\n";
  if (!grid_steps.empty())
    t += "    <Grid Name=\"grid\" GridType=\"Collection\" CollectionType=\"Temporal\">\n" + grid_steps + "    </Grid>\n";
  return t + kFoot;
}

}  // namespace

std::string xdmf_document(const std::vector<XdmfSnapshot>& snapshots) {
  std::string steps, grid_steps;
  for (const XdmfSnapshot& s : snapshots) {
    steps += particle_step(s);
    if (s.grid) grid_steps += grid_step(s);
  }
  return kHead + steps + tail(grid_steps);
}

XdmfIndex::XdmfIndex(std::string path, std::vector<XdmfSnapshot> earlier) : path_(std::move(path)) {
  if (earlier.empty()) return;
  for (const XdmfSnapshot& s : earlier) add_to_memory(s);
  rewrite();
}

void XdmfIndex::add_to_memory(const XdmfSnapshot& s) {
  steps_bytes_ += particle_step(s).size();
  if (s.grid) grid_steps_ += grid_step(s);
  snapshots_.push_back(s);
}

void XdmfIndex::rewrite() {
  const std::string tmp = path_ + ".tmp";
  const std::string text = xdmf_document(snapshots_);
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f) throw std::runtime_error("cannot open " + tmp + " for writing");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  std::fclose(f);
  std::error_code ec;
  if (ok) std::filesystem::rename(tmp, path_, ec);
  if (!ok || ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path_ + " (disk full?)");
  }
}

void XdmfIndex::add(const XdmfSnapshot& s) {
  const bool first = snapshots_.empty();
  const std::size_t offset = std::strlen(kHead) + steps_bytes_;  // where the tail starts now
  const std::string step = particle_step(s);
  add_to_memory(s);
  if (first) {
    rewrite();
    return;
  }
  // Overwrite the tail with the new step and the (grown) tail: each snapshot costs its own entry
  // (and the grid collection's), not the whole index. A crash in between leaves an index that
  // stops early; a restart writes it whole again.
  std::FILE* f = std::fopen(path_.c_str(), "r+");
  if (!f) throw std::runtime_error("cannot open " + path_ + " for writing");
  const std::string text = step + tail(grid_steps_);
  const bool ok = std::fseek(f, static_cast<long>(offset), SEEK_SET) == 0 &&
                  std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  std::fclose(f);
  if (!ok) throw std::runtime_error("cannot write " + path_ + " (disk full?)");
}

}  // namespace mpmshock
