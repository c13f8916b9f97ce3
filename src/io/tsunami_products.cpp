#include "swemps/io/tsunami_products.hpp"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "result_reader.hpp"
#include "swemps/io/gdal_messages.hpp"
#include "swemps/terrain/gridded_field.hpp"
#include "text_file.hpp"
#include "vector_files.hpp"

namespace swemps::io {

using namespace netcdf;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Cells without data in the raster the contours are traced on: far below any depth.
constexpr double kNoData = -1e30;

// A map of the result (south-up, cell (i, k) at k * nx + i, as the file stores it) as a
// north-up raster in memory, whose bilinear reading between cell centres is the terrain
// module's.
terrain::GriddedField as_field(const Grid& g, const std::vector<double>& south_up) {
  terrain::GridGeometry geometry{
      g.nx, g.ny, g.x0 - 0.5 * g.dx, g.y0 + (static_cast<double>(g.ny) - 0.5) * g.dy, g.dx, g.dy};
  std::vector<double> north_up(g.nx * g.ny);
  for (std::size_t k = 0; k < g.ny; ++k) {
    for (std::size_t i = 0; i < g.nx; ++i)
      north_up[(g.ny - 1 - k) * g.nx + i] = south_up[k * g.nx + i];
  }
  return terrain::GriddedField(geometry, std::move(north_up), g.crs_wkt);
}

// The lines where `depth` falls to `level`, traced by GDAL's contouring on the cell centres,
// into a layer of 2D line strings held in memory.
GDALDatasetUniquePtr trace_contours(const terrain::GriddedField& depth, double level,
                                    const std::filesystem::path& result) {
  const terrain::GridGeometry& g = depth.geometry();
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error("cannot trace the inundation line of " + quoted(result) + ": " + what +
                             gdal_detail());
  };
  GDALDriver* raster_driver = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* vector_driver = GetGDALDriverManager()->GetDriverByName("Memory");
  if (!raster_driver || !vector_driver) fail("GDAL has no in-memory driver");
  const GDALDatasetUniquePtr raster(raster_driver->Create(
      "", static_cast<int>(g.columns), static_cast<int>(g.rows), 1, GDT_Float64, nullptr));
  if (!raster) fail("no raster in memory");
  std::array<double, 6> gt = g.geotransform();
  raster->SetGeoTransform(gt.data());
  std::vector<double> values = depth.values();
  for (double& v : values) {
    if (std::isnan(v)) v = kNoData;
  }
  GDALRasterBand* band = raster->GetRasterBand(1);
  band->SetNoDataValue(kNoData);
  if (band->RasterIO(GF_Write, 0, 0, static_cast<int>(g.columns), static_cast<int>(g.rows),
                     values.data(), static_cast<int>(g.columns), static_cast<int>(g.rows),
                     GDT_Float64, 0, 0, nullptr) != CE_None) {
    fail("cannot fill the raster in memory");
  }
  GDALDatasetUniquePtr lines(vector_driver->Create("", 0, 0, 0, GDT_Unknown, nullptr));
  if (!lines) fail("no vector layer in memory");
  OGRLayer* layer = lines->CreateLayer("contours", nullptr, wkbLineString, nullptr);
  OGRFieldDefn id_field("id", OFTInteger), level_field("level", OFTReal);
  if (!layer || layer->CreateField(&id_field) != OGRERR_NONE ||
      layer->CreateField(&level_field) != OGRERR_NONE) {
    fail("no vector layer in memory");
  }
  char level_text[64], nodata_text[64];
  std::snprintf(level_text, sizeof level_text, "FIXED_LEVELS=%.17g", level);
  std::snprintf(nodata_text, sizeof nodata_text, "NODATA=%.17g", kNoData);
  const char* options[] = {level_text, nodata_text, "ID_FIELD=0", "ELEV_FIELD=1", nullptr};
  if (GDALContourGenerateEx(GDALRasterBand::ToHandle(band), OGRLayer::ToHandle(layer), options,
                            nullptr, nullptr) != CE_None) {
    fail("GDAL's contouring failed");
  }
  return lines;
}

// One inundation line with the ground under each vertex.
struct Line {
  OGRLineString points;  // Z: the bed elevation
  double length_m = 0.0;
  double max_ground_m = -std::numeric_limits<double>::infinity();
  double max_x = 0.0, max_y = 0.0;
};

// `bed`: the bed at the cell centres; none for a flat scene (z = 0).
std::vector<Line> lines_with_ground(OGRLayer& contours,
                                    const std::optional<terrain::GriddedField>& bed) {
  std::vector<Line> out;
  contours.ResetReading();
  for (auto& feature : contours) {
    const OGRGeometry* geometry = feature->GetGeometryRef();
    if (!geometry || wkbFlatten(geometry->getGeometryType()) != wkbLineString) continue;
    const OGRLineString* traced = geometry->toLineString();
    if (traced->getNumPoints() < 2) continue;
    Line line;
    for (int p = 0; p < traced->getNumPoints(); ++p) {
      const double x = traced->getX(p), y = traced->getY(p);
      const double z = bed ? bed->sample(x, y) : 0.0;
      line.points.addPoint(x, y, z);
      if (z > line.max_ground_m) {
        line.max_ground_m = z;
        line.max_x = x;
        line.max_y = y;
      }
    }
    line.length_m = traced->get_Length();
    out.push_back(std::move(line));
  }
  // The longest first: the coast before the puddles.
  std::sort(out.begin(), out.end(),
            [](const Line& a, const Line& b) { return a.length_m > b.length_m; });
  return out;
}

void write_lines(const std::vector<Line>& lines, const Grid& grid, std::optional<double> still_m,
                 const std::filesystem::path& file, VectorFile format) {
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error("cannot write the inundation line " + quoted(file) + ": " + what +
                             gdal_detail());
  };
  vector::NewLayer created;
  try {
    created = vector::create_layer(file, format, "inundation_line", grid.crs_wkt, wkbLineString25D);
  } catch (const std::runtime_error& e) {
    fail(e.what());
  }
  GDALDataset* out = created.file.get();
  OGRLayer* layer = created.layer;
  for (const char* name : {"max_ground_elevation_m", "max_runup_m", "length_m"}) {
    OGRFieldDefn field(name, OFTReal);
    if (layer->CreateField(&field) != OGRERR_NONE) fail(std::string("cannot add field ") + name);
  }
  if (out->StartTransaction() == OGRERR_FAILURE) fail("cannot start a transaction");
  for (const Line& line : lines) {
    OGRFeature feature(layer->GetLayerDefn());
    feature.SetField("max_ground_elevation_m", line.max_ground_m);
    if (still_m) feature.SetField("max_runup_m", line.max_ground_m - *still_m);
    feature.SetField("length_m", line.length_m);
    feature.SetGeometry(&line.points);
    if (layer->CreateFeature(&feature) != OGRERR_NONE) fail("cannot add a line");
  }
  if (out->CommitTransaction() == OGRERR_FAILURE) fail("cannot commit the lines");
  created.file.reset();  // closes, so that a failure to flush shows before the rename
  if (CPLGetLastErrorType() == CE_Failure) fail("cannot close it");
}

// The still level a result with tsunami maps measured from; none otherwise.
std::optional<double> still_level(const ResultReader& in) {
  if (!in.has("tsunami_arrival_time")) return std::nullopt;
  const double level = in.number(in.variable("tsunami_arrival_time"), "still_level_m");
  return std::isfinite(level) ? std::optional<double>(level) : std::nullopt;
}

// A CSV field: quoted, with its quotes doubled, when it holds a comma, a quote or a line end.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

bool has_tsunami_maps(const std::filesystem::path& result) {
  return ResultReader(result).has("tsunami_arrival_time");
}

std::optional<InundationSummary> export_inundation_line(const std::filesystem::path& result,
                                                        const std::filesystem::path& file,
                                                        VectorFile format) {
  Grid grid;
  std::vector<double> max_depth, bed_values;
  std::optional<double> still_m;
  double wet_depth_m = kNaN;
  {
    const ResultReader in(result);
    grid = in.grid();
    max_depth = in.values("max_depth");
    wet_depth_m = in.number(in.variable("max_depth"), "wet_depth_threshold_m");
    if (in.has("bed_elevation")) bed_values = in.values("bed_elevation");
    still_m = still_level(in);
  }
  if (!std::isfinite(wet_depth_m)) {
    throw std::runtime_error("the result " + quoted(result) +
                             " does not say its wet depth (max_depth has no "
                             "wet_depth_threshold_m): is it a finished swe-mps result?");
  }
  if (grid.nx < 2 || grid.ny < 2) return std::nullopt;
  const terrain::GriddedField depth = as_field(grid, max_depth);
  std::optional<terrain::GriddedField> bed;
  if (!bed_values.empty()) bed = as_field(grid, bed_values);

  register_gdal_drivers();
  const QuietGdalErrors quiet;
  const GDALDatasetUniquePtr contours = trace_contours(depth, wet_depth_m, result);
  const std::vector<Line> lines = lines_with_ground(*contours->GetLayer(0), bed);
  if (lines.empty()) return std::nullopt;

  vector::write_then_rename(file, [&](const std::filesystem::path& partial) {
    write_lines(lines, grid, still_m, partial, format);
  });

  InundationSummary summary;
  summary.lines = lines.size();
  const auto highest = std::max_element(
      lines.begin(), lines.end(),
      [](const auto& a, const auto& b) { return a.max_ground_m < b.max_ground_m; });
  summary.max_ground_elevation_m = highest->max_ground_m;
  if (still_m) summary.max_runup_m = highest->max_ground_m - *still_m;
  summary.x_m = highest->max_x;
  summary.y_m = highest->max_y;
  return summary;
}

bool export_gauge_arrivals(const std::filesystem::path& result, const std::filesystem::path& csv) {
  const ResultReader in(result);
  const std::optional<double> still_m = still_level(in);
  if (!still_m || !in.has("gauge_name")) return false;
  const double rise_m = in.number(in.variable("tsunami_arrival_time"), "arrival_rise_m");
  const std::vector<std::string> names = in.strings("gauge_name");
  const std::vector<double> x = in.values("gauge_x"), y = in.values("gauge_y");
  const std::vector<double> time = in.values("series_time");
  const std::vector<double> surface = in.values("gauge_surface_elevation");
  const std::size_t n = names.size();
  if (surface.size() != time.size() * n || x.size() != n || y.size() != n) {
    throw std::runtime_error("the result " + quoted(result) + " has " +
                             std::to_string(surface.size()) + " gauge surface elevations for " +
                             std::to_string(time.size()) + " times and " + std::to_string(n) +
                             " gauges");
  }

  std::string table = "gauge,x_m,y_m,arrival_time_s,max_surface_rise_m,time_of_max_rise_s\n";
  for (std::size_t g = 0; g < n; ++g) {
    // A dry sample has no surface (NaN): it neither arrives nor rises.
    double arrival = kNaN, max_rise = kNaN, time_of_max = kNaN;
    for (std::size_t t = 0; t < time.size(); ++t) {
      const double rise = surface[t * n + g] - *still_m;
      if (std::isnan(rise)) continue;
      if (std::isnan(arrival) && rise > rise_m) arrival = time[t];
      if (!(max_rise >= rise)) {
        max_rise = rise;
        time_of_max = time[t];
      }
    }
    table += csv_field(names[g]);
    for (const double v : {x[g], y[g], arrival, max_rise, time_of_max}) text::append_cell(table, v);
    table += '\n';
  }
  text::write_then_rename(csv, vector::partial_name(csv), table);
  return true;
}

}  // namespace swemps::io
