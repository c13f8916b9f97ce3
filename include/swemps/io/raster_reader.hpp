#pragma once
// Rasters in: any grid GDAL can open (GeoTIFF, ESRI ASCII grid, netCDF, ...) becomes a
// terrain::GriddedField in a projected CRS in metres, the only coordinates the solver knows.
// Rasters in longitude/latitude are warped (bilinear) to the scene's CRS here, once, so that
// nothing downstream ever meets degrees.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "swemps/terrain/gridded_field.hpp"

namespace swemps::io {

struct RasterRequest {
  std::filesystem::path path;  // a file, or a GDAL dataset name such as NETCDF:"f.nc":z
  // The scene's CRS: empty, or anything OGRSpatialReference::SetFromUserInput accepts without
  // reading files or the network ("EPSG:32616", WKT, a PROJ string). Must be projected, in
  // metres.
  std::string target_crs;
  std::string purpose = "raster";       // what the raster is for ("bed raster"), in messages
  std::string crs_setting = "bed.crs";  // the scene key that sets target_crs, in messages
  int band = 1;                         // 1-based, as in GDAL
  // How a warp resamples: bilinear for surfaces (elevation, depth, n), nearest for classes
  // (land use), whose codes must not be averaged into codes that mean nothing.
  enum class Resampling { bilinear, nearest };
  Resampling resampling = Resampling::bilinear;
  // The memory reading may take, in bytes (the machine's); 0: no limit. A raster whose cells
  // would need more (kRasterBytesPerCell each) is refused before any of them is read.
  std::uint64_t memory_limit_bytes = 0;
};

// What reading costs per cell of the raster: the values as stored and as returned, and a
// warped copy when the raster is warped, with room to spare.
inline constexpr double kRasterBytesPerCell = 32.0;

// Reads one band into a north-up GriddedField named after the request's purpose:
//  - a raster too large for request.memory_limit_bytes is an error, before it is read;
//  - a projected CRS in metres is used as it is, or warped when target_crs names another;
//  - a geographic CRS (longitude/latitude) is warped to target_crs on GDAL's suggested grid
//    (square cells, bilinear); cells outside the source's footprint become nodata. Without a
//    target_crs this is an error that names the scene key and suggests a UTM zone;
//  - no CRS at all is taken as local metres, allowed only when target_crs is empty;
//  - a projected CRS in other units (feet, ...) and a rotated or sheared raster are errors;
//  - a south-up (or east-to-west) raster is flipped to north-up;
//  - the band's nodata value and any non-finite value become NaN.
// The field's crs_wkt() is WKT2 (ISO 19162:2019), which GDAL and PROJ read back; it is empty
// for local metres. Throws std::runtime_error, one line naming the purpose, the file and the
// problem.
terrain::GriddedField read_raster(const RasterRequest& request);

// A raster as a surface to sample, with the cells it came on. A raster already in the target
// CRS is its own surface (refinement 1). A warped one is warped twice from the source: once
// onto the grid GDAL suggests (`cells`: the raster's natural cells in the scene's CRS, which
// the output maps use), and once onto that grid with every cell split into refinement x
// refinement (`field`), so that bilinear interpolation between the fine centres follows the
// source's own surface rather than a coarse resampling of it: interpolating between the
// centres of coarse warped cells lowers rims, saddles and channel banks (docs/method.md, "The
// bed"). The refinement is reduced, down to 1, while the fine cells would need more memory
// than request.memory_limit_bytes allows. Fine cells that the warp leaves nodata while the
// coarse surface has a value there (at the footprint's edge) take the coarse surface's value.
struct RasterSurface {
  terrain::GriddedField field;
  terrain::GridGeometry cells;
  std::size_t refinement = 1;
};
RasterSurface read_raster_surface(const RasterRequest& request, std::size_t refinement);

// Writes a field as a single-band, deflate-compressed Float64 GeoTIFF with NaN as nodata (for
// fixtures and tools). Throws std::runtime_error naming the file if it cannot.
void write_geotiff(const terrain::GriddedField& field, const std::filesystem::path& path);

// A GDAL dataset name that wraps a file, DRIVER:"file"[:rest] such as NETCDF:"dem.nc":elevation,
// in its parts (rest ":elevation"); nullopt for a plain file name.
struct WrappedDataset {
  std::string driver, file, rest;
};
std::optional<WrappedDataset> split_dataset_name(const std::string& name);

// The WGS 84 / UTM zone holding a point, as "EPSG:326zz" (north) or "EPSG:327zz" (south):
// standard 6-degree zones, without the Norway and Svalbard exceptions.
std::string utm_crs_for(double longitude_deg, double latitude_deg);

}  // namespace swemps::io
