#pragma once
// CF-1.8 netCDF output of a run: the depth interpolated on a regular grid and, optionally,
// the particles themselves, one record per output time. The file is written under a
// temporary name (<path>.partial) and renamed to <path> only by finish(), so a run that
// crashes never leaves a file that looks complete.

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

#include "swemps/particles/swe_particles.hpp"

namespace swemps::io {

// Regular grid of cell centres: x_i = x0 + i dx (i < nx), y_k = y0 + k dy (k < ny).
struct Grid {
  double x0 = 0.0, y0 = 0.0;  // m, first cell centre
  double dx = 0.0, dy = 0.0;  // m
  std::size_t nx = 0, ny = 0;
};

struct RunMetadata {
  std::string title;          // global attribute "title"
  std::string scenario_file;  // global attribute "source"
  std::string history;        // global attribute "history" (command line)
  double gravity_m_s2 = 9.81;
};

class NetcdfWriter {
 public:
  // Creates <path>.partial (netCDF-4), defines dimensions and variables. Throws
  // std::runtime_error naming the file and netCDF's message if it cannot.
  NetcdfWriter(std::filesystem::path path, const Grid& grid, const RunMetadata& meta,
               bool write_particles);
  ~NetcdfWriter();  // closes the file if still open; leaves .partial in place
  NetcdfWriter(const NetcdfWriter&) = delete;
  NetcdfWriter& operator=(const NetcdfWriter&) = delete;

  // Appends one output time. `grid_depth` holds ny * nx values, row-major with x fastest
  // (index k * nx + i). Only the fluid particles of `p` are written.
  void write(double time_s, const particles::SweParticles& p, std::span<const double> grid_depth);

  // Closes the file and renames <path>.partial to <path>.
  void finish();

  const std::filesystem::path& path() const { return path_; }
  std::size_t records() const { return records_; }

 private:
  std::filesystem::path path_, partial_path_;
  int ncid_ = -1;
  bool write_particles_;
  std::size_t records_ = 0;
  std::size_t particle_samples_ = 0;
  Grid grid_;
  // variable ids
  int time_var_ = -1, depth_var_ = -1, count_var_ = -1;
  int px_var_ = -1, py_var_ = -1, pu_var_ = -1, pv_var_ = -1, ph_var_ = -1, pvol_var_ = -1,
      parea_var_ = -1;
};

}  // namespace swemps::io
