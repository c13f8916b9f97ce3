#pragma once
// Single-band maps out as GeoTIFF, for GIS users who want one file per map rather than the
// netCDF of a whole run (a maximum-depth map, a hazard-class map). The raster is the grid's
// own: north-up, one pixel per grid cell, pixel centres exactly on the grid's cell centres,
// the grid's CRS attached. A cloud-optimised layout (tiles, overviews, header first) lets web
// maps and QGIS read a large map over HTTP a piece and a zoom level at a time.
// The file is written under <path>.partial and renamed to <path> only once complete, so a
// failed write never leaves a file that looks complete.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "swemps/io/netcdf_writer.hpp"

namespace swemps::io {

struct RasterBand {
  std::string description;  // band description, e.g. "maximum water depth"
  std::string units;        // e.g. "m", "s", "m2 s-1", "1" for classes
  // A class map when not empty: the names of the class values 1..n (at most 255); the
  // raster is then Byte with 0 as nodata, with a colour table and the names as category
  // names, so that GIS software shows classes rather than a colour ramp. GeoTIFF has no place
  // for category names: GDAL keeps them in a sidecar <path>.aux.xml; the file itself holds
  // them too, as band metadata CLASS_1 .. CLASS_n.
  std::vector<std::string> class_names;
  // RGB of the classes 1..n, in order; empty for a default colour-blind-safe palette.
  std::vector<std::array<std::uint8_t, 3>> class_colours;
};

enum class TiffLayout {
  plain,            // tiled, deflate-compressed GeoTIFF
  cloud_optimised,  // the same as a COG: 256-pixel tiles, overviews, header first
};

// Writes ny * nx values (row-major, x fastest, rows by ascending y: index k * nx + i, as in
// MapFields) as one band; NaN is nodata.
//  - A continuous map is Float32 with NaN as nodata; other values, infinities included, are
//    stored as they round to single precision.
//  - A class map (band.class_names not empty) is Byte, nodata 0; each value must be NaN or a
//    whole class number 1..n.
//  - `metadata` becomes the dataset's metadata (key = value); TIFFTAG_SOFTWARE,
//    TIFFTAG_DATETIME and TIFFTAG_IMAGEDESCRIPTION go into the TIFF tags of those names.
// Throws std::invalid_argument for an empty grid, a cell size that is not positive and
// finite, a value count other than nx * ny, a CRS that is not projected in metres, a bad
// class value or colour count, or a metadata key that is empty or holds '=' or ':'.
// Throws std::runtime_error naming the file and GDAL's message if the file cannot be written.
void write_geotiff(const std::filesystem::path& path, const Grid& grid,
                   std::span<const double> values, const RasterBand& band, TiffLayout layout,
                   const std::map<std::string, std::string>& metadata = {});

}  // namespace swemps::io
