#include "swemps/io/raster_reader.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "swemps/io/gdal_messages.hpp"

namespace swemps::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// GDAL's utilities take their options as a command line; this owns one.
class ArgumentList {
 public:
  ArgumentList& add(const std::string& argument) {
    list_ = CSLAddString(list_, argument.c_str());
    return *this;
  }
  char** get() const { return list_; }
  ~ArgumentList() { CSLDestroy(list_); }
  ArgumentList() = default;
  ArgumentList(const ArgumentList&) = delete;
  ArgumentList& operator=(const ArgumentList&) = delete;

 private:
  char** list_ = nullptr;
};

class RasterError {
 public:
  explicit RasterError(const RasterRequest& request)
      : prefix_(request.purpose + " '" + request.path.string() + "': ") {}
  [[noreturn]] void operator()(const std::string& problem) const {
    throw std::runtime_error(prefix_ + problem);
  }

 private:
  std::string prefix_;
};

std::string to_wkt2(const OGRSpatialReference& crs) {
  char* text = nullptr;
  const char* const options[] = {"FORMAT=WKT2_2019", nullptr};
  const OGRErr status = crs.exportToWkt(&text, options);
  std::string wkt = status == OGRERR_NONE && text ? text : "";
  CPLFree(text);
  return wkt;
}

bool in_metres(const OGRSpatialReference& crs) {
  return std::abs(crs.GetLinearUnits() - 1.0) < 1e-12;
}

std::string linear_unit_name(const OGRSpatialReference& crs) {
  const char* name = nullptr;
  crs.GetLinearUnits(&name);
  return name ? name : "unknown units";
}

// The UTM zone of a geographic raster's centre, for the message that asks for a target CRS.
std::string suggested_crs(GDALDataset& dataset, const OGRSpatialReference& geographic,
                          const std::array<double, 6>& gt) {
  const double x = gt[0] + 0.5 * gt[1] * dataset.GetRasterXSize();
  const double y = gt[3] + 0.5 * gt[5] * dataset.GetRasterYSize();
  // GDAL puts longitude on the raster's x axis; the angular unit may not be the degree.
  const double to_degrees = geographic.GetAngularUnits() * 180.0 / std::numbers::pi;
  return utm_crs_for(x * to_degrees, y * to_degrees);
}

// One band of a dataset, as stored, turned north-up, with nodata as NaN.
terrain::GriddedField read_band(GDALDataset& dataset, int band_index, std::string crs_wkt,
                                const RasterRequest& request) {
  const RasterError fail(request);
  std::array<double, 6> gt{};
  if (dataset.GetGeoTransform(gt.data()) != CE_None) {
    fail("has no georeferencing (no geotransform)");
  }
  if (gt[2] != 0.0 || gt[4] != 0.0) {
    fail("is rotated or sheared (geotransform terms " + std::to_string(gt[2]) + ", " +
         std::to_string(gt[4]) + "); warp it to a north-up grid first");
  }
  if (gt[1] == 0.0 || gt[5] == 0.0 || !std::isfinite(gt[1]) || !std::isfinite(gt[5])) {
    fail("has a zero or non-finite cell size");
  }
  const auto columns = static_cast<std::size_t>(dataset.GetRasterXSize());
  const auto rows = static_cast<std::size_t>(dataset.GetRasterYSize());
  GDALRasterBand* band = dataset.GetRasterBand(band_index);
  std::vector<double> stored(columns * rows);
  if (band->RasterIO(GF_Read, 0, 0, static_cast<int>(columns), static_cast<int>(rows),
                     stored.data(), static_cast<int>(columns), static_cast<int>(rows), GDT_Float64,
                     0, 0, nullptr) != CE_None) {
    fail("cannot read band " + std::to_string(band_index) + gdal_detail());
  }
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  // A Float32 band's nodata may be written with fewer digits than the stored value has;
  // compare as the band stores it.
  const bool single_precision = band->GetRasterDataType() == GDT_Float32;
  auto is_nodata = [&](double v) {
    if (!std::isfinite(v)) return true;
    if (!has_nodata) return false;
    return single_precision ? static_cast<float>(v) == static_cast<float>(nodata) : v == nodata;
  };

  // Rows run north to south and columns west to east in the field, whatever the file does.
  const bool south_up = gt[5] > 0.0;
  const bool east_to_west = gt[1] < 0.0;
  terrain::GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.cell_width = std::abs(gt[1]);
  geometry.cell_height = std::abs(gt[5]);
  geometry.x_left = east_to_west ? gt[0] + gt[1] * static_cast<double>(columns) : gt[0];
  geometry.y_top = south_up ? gt[3] + gt[5] * static_cast<double>(rows) : gt[3];
  std::vector<double> values(columns * rows);
  for (std::size_t row = 0; row < rows; ++row) {
    const std::size_t stored_row = south_up ? rows - 1 - row : row;
    for (std::size_t col = 0; col < columns; ++col) {
      const std::size_t stored_col = east_to_west ? columns - 1 - col : col;
      const double v = stored[stored_row * columns + stored_col];
      values[row * columns + col] = is_nodata(v) ? kNaN : v;
    }
  }
  return terrain::GriddedField(geometry, std::move(values), std::move(crs_wkt), request.purpose);
}

// The extent and size of a warp's output grid; none: GDAL's suggested grid.
struct WarpGrid {
  double x_min = 0.0, y_min = 0.0, x_max = 0.0, y_max = 0.0;
  std::size_t columns = 0, rows = 0;
};

// Warps one band to `target` (square cells, bilinear), into memory: on GDAL's suggested grid,
// or on `grid` when given. Cells whose centre falls outside the source's footprint, or on its
// nodata, become NaN.
GDALDatasetUniquePtr warp_band(GDALDataset& source, int band_index,
                               const OGRSpatialReference& target, const RasterRequest& request,
                               const std::optional<WarpGrid>& grid = std::nullopt) {
  const RasterError fail(request);
  const std::string target_description = request.crs_setting + " = \"" + request.target_crs + "\"";
  // The warper of this GDAL generation takes no band choice, so the band goes alone into a
  // virtual dataset first.
  GDALDatasetUniquePtr single_band;
  GDALDataset* input = &source;
  if (source.GetRasterCount() > 1) {
    ArgumentList arguments;
    arguments.add("-of").add("VRT").add("-b").add(std::to_string(band_index));
    GDALTranslateOptions* options = GDALTranslateOptionsNew(arguments.get(), nullptr);
    single_band.reset(GDALDataset::FromHandle(
        GDALTranslate("", GDALDataset::ToHandle(&source), options, nullptr)));
    GDALTranslateOptionsFree(options);
    if (!single_band) fail("cannot select band " + std::to_string(band_index) + gdal_detail());
    input = single_band.get();
  }

  ArgumentList arguments;
  arguments.add("-of").add("MEM").add("-t_srs").add(to_wkt2(target));
  arguments.add("-r")
      .add(request.resampling == RasterRequest::Resampling::nearest ? "near" : "bilinear")
      .add("-ot")
      .add("Float64");
  if (grid) {
    const auto text = [](double v) {
      std::ostringstream s;
      s.precision(17);
      s << v;
      return s.str();
    };
    arguments.add("-te").add(text(grid->x_min)).add(text(grid->y_min));
    arguments.add(text(grid->x_max)).add(text(grid->y_max));
    arguments.add("-ts").add(std::to_string(grid->columns)).add(std::to_string(grid->rows));
  }
  // GDAL's default approximation of the transform may misplace values by 1/8 of a source
  // cell; 1/100 keeps that well below the interpolation's own error at little cost.
  arguments.add("-et").add("0.01");
  // NaN marks the cells the source cannot fill; without it they would read as 0 m.
  arguments.add("-dstnodata").add("nan");
  GDALRasterBand* band = input->GetRasterBand(1);
  int has_nodata = 0;
  band->GetNoDataValue(&has_nodata);
  const GDALDataType type = band->GetRasterDataType();
  if (!has_nodata && (type == GDT_Float32 || type == GDT_Float64)) {
    // NaN in a float source without a declared nodata is still a hole, not a number to blend.
    arguments.add("-srcnodata").add("nan");
  }
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(arguments.get(), nullptr);
  if (!options) fail("cannot set up the warp to " + target_description + gdal_detail());
  GDALDatasetH input_handle = GDALDataset::ToHandle(input);
  GDALDatasetUniquePtr warped(
      GDALDataset::FromHandle(GDALWarp("", nullptr, 1, &input_handle, options, nullptr)));
  GDALWarpAppOptionsFree(options);
  if (!warped) fail("cannot be warped to " + target_description + gdal_detail());
  return warped;
}

// A raster read on its own cells: its own surface, unrefined.
RasterSurface as_read(terrain::GriddedField field) {
  const terrain::GridGeometry cells = field.geometry();
  return {std::move(field), cells, 1};
}

// Why GDAL could not open a dataset, in the user's terms. A name GDAL cannot open may still be
// a dataset name rather than a file, so the file is looked at only after GDAL has had its try.
std::string why_not_opened(const std::filesystem::path& name) {
  const auto wrapped = split_dataset_name(name.string());
  const std::filesystem::path file = wrapped ? std::filesystem::path(wrapped->file) : name;
  const std::string which = wrapped ? "the file '" + file.string() + "' it names " : "";
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) return wrapped ? which + "is not found" : "file not found";
  if (std::filesystem::is_directory(status)) {
    return wrapped ? which + "is a folder" : "is a folder, not a raster file";
  }
  errno = 0;  // so that a failure without a system reason is not blamed on an old one
  if (std::ifstream probe(file, std::ios::binary); !probe) {
    const int err = errno;
    return which + "cannot be read: " + (err != 0 ? std::strerror(err) : "cannot open it");
  }
  if (wrapped) {
    return "the file exists, but GDAL's " + wrapped->driver + " driver cannot open '" +
           wrapped->rest + "' in it" + gdal_detail();
  }
  return "is not a raster GDAL can read" + gdal_detail();
}

}  // namespace

std::optional<WrappedDataset> split_dataset_name(const std::string& name) {
  // DRIVER:"file"rest, scanned by hand: a regular expression recurses once per character
  // and overflows the stack on long names. The driver name needs two characters or more,
  // so a drive letter ("C:") is no driver.
  const auto is_letter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  const auto is_word = [&](char c) { return is_letter(c) || (c >= '0' && c <= '9') || c == '_'; };
  std::size_t colon = 0;
  while (colon < name.size() && is_word(name[colon])) ++colon;
  if (colon < 2 || !is_letter(name[0])) return std::nullopt;
  if (name.compare(colon, 2, ":\"") != 0) return std::nullopt;
  const std::size_t file_start = colon + 2;
  const std::size_t quote = name.find('"', file_start);
  if (quote == std::string::npos || quote == file_start) return std::nullopt;
  std::string rest = name.substr(quote + 1);
  if (rest.find_first_of("\n\r") != std::string::npos) return std::nullopt;
  return WrappedDataset{name.substr(0, colon), name.substr(file_start, quote - file_start),
                        std::move(rest)};
}

std::string utm_crs_for(double longitude_deg, double latitude_deg) {
  // Longitudes may come as 0..360; zone 1 starts at 180 W.
  double lon = std::fmod(longitude_deg + 180.0, 360.0);
  if (lon < 0.0) lon += 360.0;
  const int zone = std::min(60, static_cast<int>(std::floor(lon / 6.0)) + 1);
  return "EPSG:" + std::to_string((latitude_deg >= 0.0 ? 32600 : 32700) + zone);
}

terrain::GriddedField read_raster(const RasterRequest& request) {
  return read_raster_surface(request, 1).field;
}

RasterSurface read_raster_surface(const RasterRequest& request, std::size_t refinement) {
  register_gdal_drivers();
  const QuietGdalErrors quiet;
  const RasterError fail(request);

  // Verbose: a file no driver recognises leaves a message to pass on, not silence.
  GDALDatasetUniquePtr dataset(GDALDataset::Open(
      request.path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR));
  if (!dataset) fail(why_not_opened(request.path));
  const int band_count = dataset->GetRasterCount();
  if (band_count == 0) {
    fail(
        "holds no raster band (a file with several variables needs the variable named, e.g. "
        "NETCDF:\"file.nc\":elevation)");
  }
  if (request.band < 1 || request.band > band_count) {
    fail("has no band " + std::to_string(request.band) + " (it has " + std::to_string(band_count) +
         ")");
  }
  std::array<double, 6> gt{};
  if (dataset->GetGeoTransform(gt.data()) != CE_None) {
    fail("has no georeferencing (no geotransform)");
  }
  // A header can promise any number of cells; the allocator would fail on them, or the
  // kernel kill the process, after a long wait.
  const double cells = static_cast<double>(dataset->GetRasterXSize()) * dataset->GetRasterYSize();
  const double needed_bytes = cells * kRasterBytesPerCell;
  if (request.memory_limit_bytes > 0 &&
      needed_bytes > static_cast<double>(request.memory_limit_bytes)) {
    std::ostringstream s;
    s.precision(3);
    s << "holds " << dataset->GetRasterXSize() << " x " << dataset->GetRasterYSize()
      << " cells, which need about " << needed_bytes << " bytes to read (" << kRasterBytesPerCell
      << " per cell), more than the " << static_cast<double>(request.memory_limit_bytes)
      << " bytes of memory swe-mps may use here; crop it to the scene's area or coarsen it first "
         "(gdal_translate -projwin or -tr)";
    fail(s.str());
  }

  OGRSpatialReference target;
  target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const bool has_target = !request.target_crs.empty();
  if (has_target) {
    const std::string setting = request.crs_setting + " = \"" + request.target_crs + "\"";
    // A scene file must not make the reader fetch URLs or open other files.
    if (target.SetFromUserInput(request.target_crs.c_str(),
                                OGRSpatialReference::SET_FROM_USER_INPUT_LIMITATIONS_get()) !=
        OGRERR_NONE) {
      fail(setting + " is not a CRS GDAL understands" + gdal_detail());
    }
    if (!target.IsProjected() || !in_metres(target)) {
      fail(setting + " must be a projected CRS in metres (a UTM zone such as \"EPSG:32616\")");
    }
  }

  const OGRSpatialReference* source_crs = dataset->GetSpatialRef();
  if (!source_crs || source_crs->IsEmpty()) {
    if (has_target) {
      fail("has no CRS, so it cannot be placed in " + request.crs_setting + " = \"" +
           request.target_crs + "\"; give the file a CRS, or remove " + request.crs_setting +
           " to take its coordinates as metres");
    }
    return as_read(read_band(*dataset, request.band, "", request));
  }
  if (source_crs->IsGeographic()) {
    if (!has_target) {
      const std::string suggestion = suggested_crs(*dataset, *source_crs, gt);
      fail("is in longitude/latitude; set " + request.crs_setting +
           " to a projected CRS in metres to warp it to, e.g. \"" + suggestion +
           "\" (the UTM zone of the raster's centre)");
    }
  } else if (source_crs->IsProjected()) {
    if (!in_metres(*source_crs)) {
      fail("is in " + linear_unit_name(*source_crs) +
           "; the solver works in metres, so reproject it to a CRS in metres first");
    }
    if (!has_target || source_crs->IsSame(&target)) {
      return as_read(read_band(*dataset, request.band, to_wkt2(*source_crs), request));
    }
  } else {
    fail("has a CRS that is neither projected nor geographic");
  }
  auto warped = warp_band(*dataset, request.band, target, request);
  auto coarse = read_band(*warped, 1, to_wkt2(target), request);
  const terrain::GridGeometry natural = coarse.geometry();
  // The fine grid, as large as memory allows: the reader's own budget per cell, for every
  // fine cell.
  const auto coarse_cells = static_cast<double>(natural.columns * natural.rows);
  while (refinement > 1 && request.memory_limit_bytes > 0 &&
         coarse_cells * static_cast<double>(refinement * refinement) * kRasterBytesPerCell >
             static_cast<double>(request.memory_limit_bytes)) {
    --refinement;
  }
  if (refinement <= 1) return as_read(std::move(coarse));
  const WarpGrid fine_grid{natural.x_left, natural.y_bottom(),           natural.x_right(),
                           natural.y_top,  natural.columns * refinement, natural.rows * refinement};
  auto fine_warp = warp_band(*dataset, request.band, target, request, fine_grid);
  auto fine = read_band(*fine_warp, 1, to_wkt2(target), request);
  // At the footprint's edge a fine centre may fall outside the source where the coarse one
  // did not: keep the coarse surface there, so refining never adds nodata.
  std::vector<double> values = fine.values();
  const auto& g = fine.geometry();
  for (std::size_t row = 0; row < g.rows; ++row) {
    for (std::size_t col = 0; col < g.columns; ++col) {
      double& v = values[row * g.columns + col];
      if (std::isnan(v)) v = coarse.sample(g.cell_centre_x(col), g.cell_centre_y(row));
    }
  }
  return {terrain::GriddedField(g, std::move(values), fine.crs_wkt(), fine.name()), natural,
          refinement};
}

void write_geotiff(const terrain::GriddedField& field, const std::filesystem::path& path) {
  register_gdal_drivers();
  const QuietGdalErrors quiet;
  auto fail = [&](const std::string& problem) {
    throw std::runtime_error("GeoTIFF '" + path.string() + "': " + problem + gdal_detail());
  };
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!driver) fail("the GeoTIFF driver is missing");
  const auto& g = field.geometry();
  ArgumentList creation;
  // Floating-point prediction before deflate shrinks smooth terrain well.
  creation.add("COMPRESS=DEFLATE").add("PREDICTOR=3");
  GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), static_cast<int>(g.columns),
                                              static_cast<int>(g.rows), 1, GDT_Float64,
                                              creation.get()));
  if (!dataset) fail("cannot be created");
  auto gt = g.geotransform();
  if (dataset->SetGeoTransform(gt.data()) != CE_None) fail("cannot store the geotransform");
  if (!field.crs_wkt().empty()) {
    OGRSpatialReference crs;
    if (crs.importFromWkt(field.crs_wkt().c_str()) != OGRERR_NONE) fail("the CRS is not WKT");
    if (dataset->SetSpatialRef(&crs) != CE_None) fail("cannot store the CRS");
  }
  GDALRasterBand* band = dataset->GetRasterBand(1);
  band->SetNoDataValue(kNaN);
  if (!field.name().empty()) band->SetDescription(field.name().c_str());
  auto values = field.values();
  if (band->RasterIO(GF_Write, 0, 0, static_cast<int>(g.columns), static_cast<int>(g.rows),
                     values.data(), static_cast<int>(g.columns), static_cast<int>(g.rows),
                     GDT_Float64, 0, 0, nullptr) != CE_None) {
    fail("cannot write the values");
  }
  CPLErrorReset();
  dataset.reset();  // closing writes the file
  if (CPLGetLastErrorType() >= CE_Failure) fail("cannot be completed");
}

}  // namespace swemps::io
