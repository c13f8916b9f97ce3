#pragma once
// The files of an ensemble: what is read of each member's result, and the products of the
// whole ensemble (ensemble::combine) written as one CF netCDF file and as GeoTIFFs on the
// members' grid and CRS.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "swemps/ensemble/ensemble.hpp"
#include "swemps/io/geotiff_writer.hpp"
#include "swemps/io/netcdf_writer.hpp"

namespace swemps::io {

// What the ensemble takes from one member's result file.
struct MemberResult {
  Grid grid;
  std::vector<double> max_depth;    // the whole-run maximum depth, NaN where no data (m)
  double wet_depth_m = 0.0;         // the run's wet depth (its flood statistics')
  double final_volume_error = 0.0;  // the last volume-balance sample; NaN without one
};

// Reads a member's result. Throws std::runtime_error naming the file when it cannot be read
// or is not a swe-mps result.
MemberResult read_member_result(const std::filesystem::path& result);

// Whether two grids are the same cells in the same CRS, so that their maps combine cell by
// cell.
bool same_grid(const Grid& a, const Grid& b);

// Where the products come from, for the files' metadata. Nothing here depends on when or
// where the products were made, so that the same members give the same files, byte for byte.
struct EnsembleSource {
  std::string title;          // "ensemble valley-peaks-roughness of scene valley-flood"
  std::string ensemble_file;  // its file name
  std::string program;        // "swe-mps 0.x"
  std::size_t members_total = 0;
  std::vector<std::size_t> members_used;  // the indices combined
};

// Writes the products as CF netCDF (under <path>.partial, renamed when complete):
// depth_threshold, exceedance_count and exceedance_probability per threshold, mean_max_depth
// and max_depth_envelope, on the grid's x, y and CRS. Throws std::runtime_error naming the file.
void write_ensemble_netcdf(const std::filesystem::path& path, const Grid& grid,
                           const ensemble::Products& products, const EnsembleSource& source);

// Writes the same maps as GeoTIFFs, <prefix>_<map>.tif and <prefix>_<map>_<threshold>m.tif,
// and returns the files written. Throws std::runtime_error naming the file.
std::vector<std::filesystem::path> write_ensemble_rasters(const std::filesystem::path& prefix,
                                                          const Grid& grid,
                                                          const ensemble::Products& products,
                                                          const EnsembleSource& source,
                                                          TiffLayout layout);

}  // namespace swemps::io
