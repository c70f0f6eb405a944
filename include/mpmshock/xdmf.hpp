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
};

std::string xdmf_document(const std::vector<XdmfSnapshot>& snapshots);

// Writes the document to PATH.tmp, then renames it over PATH.
void write_xdmf(const std::string& path, const std::vector<XdmfSnapshot>& snapshots);

}  // namespace mpmshock
