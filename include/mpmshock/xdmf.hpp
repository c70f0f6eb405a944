// XDMF index of a run's snapshots, so that ParaView and VisIt open the run as a time series of
// point clouds (and, with snapshot_grid = on, of the grid) with every field. It only points into
// the HDF5 files; it holds no data.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace mpmshock {

struct XdmfSnapshot {
  std::string file;  // the snapshot's file name, relative to the XDMF file
  double time = 0.0;
  std::size_t points = 0;
  bool grid = false;
  int nx = 0, ny = 0;  // grid nodes when grid is true
  double y_min = 0.0, h = 0.0;
  int dimension = 2;   // 3: points in x, y, z and a grid of nz node layers
  int nz = 1;
};

std::string xdmf_document(const std::vector<XdmfSnapshot>& snapshots);

// The index file of a run, grown by one snapshot at a time. The first write (and the first after
// a restart, which lists the snapshots already there) writes the whole document to PATH.tmp and
// renames it; later ones overwrite only the document's tail in place, so a run of thousands of
// snapshots costs thousands of entries, not millions.
class XdmfIndex {
 public:
  explicit XdmfIndex(std::string path, std::vector<XdmfSnapshot> earlier = {});
  void add(const XdmfSnapshot& snapshot);

 private:
  void add_to_memory(const XdmfSnapshot& s);
  void rewrite();
  std::string path_;
  std::vector<XdmfSnapshot> snapshots_;
  std::size_t steps_bytes_ = 0;  // bytes of the point cloud's steps in the file
  std::string grid_steps_;       // the grid collection's steps, rewritten with the tail
};

}  // namespace mpmshock
