#include "swemps/io/geotiff_writer.hpp"

#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <climits>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "swemps/io/gdal_messages.hpp"

namespace swemps::io {

namespace {

// Tiles of 256 pixels: a map of a few hundred cells a side already gets overviews, and a
// reader over HTTP fetches small pieces.
constexpr int kBlockSize_px = 256;
constexpr std::uint8_t kClassNodata = 0;  // class numbers start at 1
constexpr std::size_t kMaxClasses = 255;  // Byte values 1..255

// Okabe and Ito's colour-blind-safe qualitative colours (without their black, which reads as
// "no data" on most maps), repeated for more classes.
constexpr std::array<std::array<std::uint8_t, 3>, 7> kDefaultColours{{
    {230, 159, 0},
    {86, 180, 233},
    {0, 158, 115},
    {240, 228, 66},
    {0, 114, 178},
    {213, 94, 0},
    {204, 121, 167},
}};

// A GDAL NAME=VALUE list, owned.
class OptionList {
 public:
  OptionList() = default;
  OptionList(const OptionList&) = delete;
  OptionList& operator=(const OptionList&) = delete;
  ~OptionList() { CSLDestroy(list_); }
  OptionList& set(const char* name, const std::string& value) {
    list_ = CSLSetNameValue(list_, name, value.c_str());
    return *this;
  }
  OptionList& add(const std::string& item) {
    list_ = CSLAddString(list_, item.c_str());
    return *this;
  }
  char** get() const { return list_; }

 private:
  char** list_ = nullptr;
};

[[noreturn]] void reject(const std::string& problem) {
  throw std::invalid_argument("GeoTIFF writer: " + problem);
}

bool is_class_map(const RasterBand& band) { return !band.class_names.empty(); }

void check_inputs(const Grid& grid, std::span<const double> values, const RasterBand& band,
                  const std::map<std::string, std::string>& metadata) {
  if (grid.nx == 0 || grid.ny == 0) reject("the grid has no cells");
  // GDAL counts pixels in int.
  if (grid.nx > static_cast<std::size_t>(INT_MAX) || grid.ny > static_cast<std::size_t>(INT_MAX)) {
    reject("the grid has too many cells along one axis for GDAL");
  }
  if (!(grid.dx > 0.0) || !(grid.dy > 0.0) || !std::isfinite(grid.dx) || !std::isfinite(grid.dy)) {
    reject("the cell size must be positive and finite");
  }
  if (!std::isfinite(grid.x0) || !std::isfinite(grid.y0)) {
    reject("the first cell centre must be finite");
  }
  if (values.size() != grid.nx * grid.ny) {
    reject(std::to_string(values.size()) + " values for a grid of " + std::to_string(grid.nx) +
           " x " + std::to_string(grid.ny) + " cells");
  }
  for (const auto& [key, value] : metadata) {
    // GDAL splits its metadata items at the first '=' or ':'.
    if (key.empty() || key.find_first_of("=:") != std::string::npos) {
      reject("metadata key '" + key + "' is empty or holds '=' or ':'");
    }
  }
  if (!is_class_map(band)) return;
  const std::size_t classes = band.class_names.size();
  if (classes > kMaxClasses) reject("more than 255 classes");
  if (!band.class_colours.empty() && band.class_colours.size() != classes) {
    reject(std::to_string(band.class_colours.size()) + " class colours for " +
           std::to_string(classes) + " classes");
  }
  for (std::size_t cell = 0; cell < values.size(); ++cell) {
    const double v = values[cell];
    if (std::isnan(v)) continue;
    if (!(v >= 1.0 && v <= static_cast<double>(classes) && v == std::floor(v))) {
      reject("value " + std::to_string(v) + " at cell " + std::to_string(cell) +
             " is not a class number 1.." + std::to_string(classes));
    }
  }
}

// The grid's CRS, or an empty one for local metres.
std::unique_ptr<OGRSpatialReference> crs_of(const Grid& grid) {
  if (grid.crs_wkt.empty()) return nullptr;
  auto crs = std::make_unique<OGRSpatialReference>();
  crs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (crs->importFromWkt(grid.crs_wkt.c_str()) != OGRERR_NONE) {
    reject("the grid's CRS is not WKT GDAL reads");
  }
  if (!crs->IsProjected() || std::abs(crs->GetLinearUnits() - 1.0) > 1e-12) {
    reject("the grid's CRS must be projected, in metres");
  }
  return crs;
}

// The map in memory, north-up, with everything the file is to carry; null if GDAL fails.
GDALDatasetUniquePtr in_memory(const Grid& grid, std::span<const double> values,
                               const RasterBand& band, const OGRSpatialReference* crs,
                               const std::map<std::string, std::string>& metadata) {
  const bool classes = is_class_map(band);
  const int columns = static_cast<int>(grid.nx);
  const int rows = static_cast<int>(grid.ny);
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("MEM");
  if (!driver) return nullptr;
  GDALDatasetUniquePtr memory(
      driver->Create("", columns, rows, 1, classes ? GDT_Byte : GDT_Float32, nullptr));
  if (!memory) return nullptr;

  // Pixel (0, 0) is the north-west corner, so the pixel centres are the grid's cell centres.
  double gt[6] = {grid.x0 - 0.5 * grid.dx,
                  grid.dx,
                  0.0,
                  grid.y0 + (static_cast<double>(grid.ny) - 0.5) * grid.dy,
                  0.0,
                  -grid.dy};
  memory->SetGeoTransform(gt);
  if (crs) memory->SetSpatialRef(crs);
  for (const auto& [key, value] : metadata) memory->SetMetadataItem(key.c_str(), value.c_str());

  GDALRasterBand* out = memory->GetRasterBand(1);
  out->SetDescription(band.description.c_str());
  out->SetUnitType(band.units.c_str());
  if (classes) {
    out->SetNoDataValue(kClassNodata);
    OptionList names;
    names.add("");  // the nodata value
    for (std::size_t c = 0; c < band.class_names.size(); ++c) {
      names.add(band.class_names[c]);
      // Also inside the TIFF, where a copy of the file without its sidecar still has them.
      const std::string key = "CLASS_" + std::to_string(c + 1);
      out->SetMetadataItem(key.c_str(), band.class_names[c].c_str());
    }
    out->SetCategoryNames(names.get());
    GDALColorTable colours;
    const GDALColorEntry transparent{0, 0, 0, 0};
    colours.SetColorEntry(kClassNodata, &transparent);
    for (std::size_t c = 0; c < band.class_names.size(); ++c) {
      const auto& rgb = band.class_colours.empty() ? kDefaultColours[c % kDefaultColours.size()]
                                                   : band.class_colours[c];
      const GDALColorEntry entry{rgb[0], rgb[1], rgb[2], 255};
      colours.SetColorEntry(static_cast<int>(c + 1), &entry);
    }
    out->SetColorTable(&colours);
  } else {
    out->SetNoDataValue(std::nan(""));
  }

  // Raster row r is grid row ny - 1 - r: GeoTIFF runs north to south, the grid south to north.
  std::vector<double> row(grid.nx);
  for (int r = 0; r < rows; ++r) {
    const std::size_t k = grid.ny - 1 - static_cast<std::size_t>(r);
    for (std::size_t i = 0; i < grid.nx; ++i) {
      const double v = values[k * grid.nx + i];
      row[i] = classes && std::isnan(v) ? kClassNodata : v;
    }
    // GDAL converts to the band's type (double to float rounds; NaN stays NaN).
    if (out->RasterIO(GF_Write, 0, r, columns, 1, row.data(), columns, 1, GDT_Float64, 0, 0,
                      nullptr) != CE_None) {
      return nullptr;
    }
  }
  return memory;
}

void set_creation_options(OptionList& options, TiffLayout layout, bool classes) {
  options.set("COMPRESS", "DEFLATE").set("BIGTIFF", "IF_SAFER");
  if (layout == TiffLayout::plain) {
    // Differences between neighbours deflate better than values: horizontal differencing
    // for integers, the floating-point predictor for floats.
    options.set("TILED", "YES").set("PREDICTOR", classes ? "2" : "3");
    options.set("BLOCKXSIZE", std::to_string(kBlockSize_px));
    options.set("BLOCKYSIZE", std::to_string(kBlockSize_px));
    return;
  }
  // YES picks the predictor by type, as above.
  options.set("PREDICTOR", "YES").set("OVERVIEW_COMPRESS", "DEFLATE");
  options.set("OVERVIEW_PREDICTOR", "YES").set("BLOCKSIZE", std::to_string(kBlockSize_px));
  // AUTO halves the raster until it fits one tile, so any map larger than a tile gets
  // overviews. Classes are not numbers to blend: a zoomed-out pixel takes its most common
  // class. A continuous map takes the mean of its valid cells (NaN skipped): unlike the
  // cubic default it never overshoots, so no negative depth appears beside a dry cell.
  options.set("OVERVIEWS", "AUTO").set("OVERVIEW_RESAMPLING", classes ? "MODE" : "AVERAGE");
}

}  // namespace

void write_geotiff(const std::filesystem::path& path, const Grid& grid,
                   std::span<const double> values, const RasterBand& band, TiffLayout layout,
                   const std::map<std::string, std::string>& metadata) {
  check_inputs(grid, values, band, metadata);
  const auto crs = crs_of(grid);
  register_gdal_drivers();
  const QuietGdalErrors quiet;

  // GeoTIFF has no place for category names: GDAL keeps them in a sidecar <file>.aux.xml,
  // which travels with the file under the same renames.
  auto with_suffix = [](std::filesystem::path p, const char* suffix) { return p += suffix; };
  const auto partial = with_suffix(path, ".partial");
  const auto partial_sidecar = with_suffix(partial, ".aux.xml");
  const auto sidecar = with_suffix(path, ".aux.xml");
  auto fail = [&](const std::string& problem) {
    const std::string detail = gdal_detail();
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    std::filesystem::remove(partial_sidecar, ignored);
    throw std::runtime_error("GeoTIFF '" + path.string() + "': " + problem + detail);
  };

  // A sidecar left by an earlier failed write would be merged into this one.
  std::error_code stale;
  std::filesystem::remove(partial_sidecar, stale);

  const GDALDatasetUniquePtr memory = in_memory(grid, values, band, crs.get(), metadata);
  if (!memory) fail("cannot hold the map in memory");
  const char* driver_name = layout == TiffLayout::cloud_optimised ? "COG" : "GTiff";
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  if (!driver) fail(std::string("GDAL's ") + driver_name + " driver is missing");
  OptionList options;
  set_creation_options(options, layout, is_class_map(band));
  GDALDatasetUniquePtr file(
      driver->CreateCopy(partial.c_str(), memory.get(), TRUE, options.get(), nullptr, nullptr));
  if (!file) fail("cannot be written");
  CPLErrorReset();
  file.reset();  // closing writes the rest of the file
  if (CPLGetLastErrorType() >= CE_Failure) fail("cannot be completed");
  CPLErrorReset();  // a warning from closing is no reason for a failed rename

  // The sidecar first, the raster last: <path> appears only when all of it is in place. A
  // sidecar of an earlier file at <path> would lend the new one its names and statistics.
  std::error_code ec;
  if (std::filesystem::exists(partial_sidecar, ec)) {
    std::filesystem::rename(partial_sidecar, sidecar, ec);
    if (ec) fail("cannot rename '" + partial_sidecar.string() + "': " + ec.message());
  } else {
    std::filesystem::remove(sidecar, ec);
    if (ec) fail("cannot remove the old '" + sidecar.string() + "': " + ec.message());
  }
  std::filesystem::rename(partial, path, ec);
  if (ec) {
    const std::string reason = ec.message();
    std::filesystem::remove(sidecar, ec);
    fail("cannot rename '" + partial.string() + "' to it: " + reason);
  }
}

}  // namespace swemps::io
