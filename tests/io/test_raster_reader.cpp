#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <array>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace fs = std::filesystem;
using swemps::io::RasterRequest;
using swemps::io::read_raster;
using swemps::io::split_dataset_name;
using swemps::io::utm_crs_for;
using swemps::io::write_geotiff;
using swemps::terrain::GriddedField;
using swemps::terrain::GridGeometry;

using TempDir = swemps::testing::TempDir;
using swemps::testing::grid_geometry;
using swemps::testing::wkt_of;

namespace {

bool same_crs(const std::string& wkt, const std::string& user_input) {
  OGRSpatialReference a, b;
  if (a.importFromWkt(wkt.c_str()) != OGRERR_NONE) return false;
  REQUIRE(b.SetFromUserInput(user_input.c_str()) == OGRERR_NONE);
  return a.IsSame(&b);
}

std::string error_of(const RasterRequest& request) {
  try {
    read_raster(request);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  FAIL("read_raster did not throw for " << request.path);
  return {};
}

// A UTM zone 16N field of 6 x 4 cells of 30 m, one of them nodata.
GriddedField utm_field() {
  const GridGeometry g = grid_geometry(6, 4, 740000.0, 4060000.0, 30.0, 30.0);
  std::vector<double> values;
  for (std::size_t k = 0; k < g.columns * g.rows; ++k) values.push_back(300.0 + 1.25 * k);
  values[9] = std::nan("");
  return GriddedField(g, values, wkt_of("EPSG:32616"), "bed elevation");
}

// Longitude/latitude degrees of a field's geotransform, value linear in both: bilinear
// interpolation, in the source or after warping, reproduces it up to the map's curvature.
double lon_lat_value(double lon, double lat) {
  return 1000.0 * (lon + 86.0) + 2000.0 * (lat - 35.0);
}

GriddedField lon_lat_field(double lon_west, double lat_north, double step_deg, std::size_t columns,
                           std::size_t rows) {
  const GridGeometry g = grid_geometry(columns, rows, lon_west, lat_north, step_deg, step_deg);
  std::vector<double> values;
  for (std::size_t row = 0; row < rows; ++row) {
    for (std::size_t col = 0; col < columns; ++col) {
      values.push_back(lon_lat_value(g.cell_centre_x(col), g.cell_centre_y(row)));
    }
  }
  return GriddedField(g, values, wkt_of("EPSG:4326"), "elevation");
}

// A coordinate transformation between two EPSG codes, x first (longitude, easting).
std::unique_ptr<OGRCoordinateTransformation> transformation(int from_epsg, int to_epsg) {
  OGRSpatialReference from, to;
  from.importFromEPSG(from_epsg);
  to.importFromEPSG(to_epsg);
  from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&from, &to));
  REQUIRE(t);
  return t;
}

}  // namespace

TEST_CASE("a GeoTIFF written and read back is the same field", "[raster]") {
  TempDir dir;
  const auto field = utm_field();
  const auto path = dir.path() / "bed.tif";
  write_geotiff(field, path);
  for (const std::string target : {"", "EPSG:32616"}) {
    const auto back = read_raster({path, target, "bed raster"});
    const auto& g = back.geometry();
    CHECK(g.columns == 6);
    CHECK(g.rows == 4);
    CHECK(g.x_left == 740000.0);
    CHECK(g.y_top == 4060000.0);
    CHECK(g.cell_width == 30.0);
    CHECK(g.cell_height == 30.0);
    CHECK(back.name() == "bed raster");
    CHECK(same_crs(back.crs_wkt(), "EPSG:32616"));
    for (std::size_t k = 0; k < field.values().size(); ++k) {
      if (std::isnan(field.values()[k])) {
        CHECK(std::isnan(back.values()[k]));
      } else {
        CHECK(back.values()[k] == field.values()[k]);
      }
    }
  }
}

TEST_CASE("an ESRI ASCII grid reads as local metres with nodata as NaN", "[raster]") {
  TempDir dir;
  const auto path = dir.path() / "dem.asc";
  {
    std::ofstream out(path);
    out << "ncols 4\nnrows 3\nxllcorner 100\nyllcorner 200\ncellsize 5\nNODATA_value -9999\n"
        << "1 2 3 4\n"
        << "5 -9999 7 8\n"
        << "9 10 11 12.5\n";
  }
  const auto field = read_raster({path, "", "bed raster"});
  const auto& g = field.geometry();
  CHECK(g.columns == 4);
  CHECK(g.rows == 3);
  CHECK(g.x_left == 100.0);
  CHECK(g.y_top == 215.0);  // the lower-left corner plus three rows
  CHECK(g.cell_width == 5.0);
  CHECK(field.at(0, 0) == 1.0);  // the first line of the file is the northern row
  CHECK(std::isnan(field.at(1, 1)));
  CHECK(field.at(3, 2) == 12.5);
  CHECK(field.crs_wkt().empty());
  CHECK(field.sample(g.cell_centre_x(3), g.cell_centre_y(2)) == 12.5);

  // Without a CRS it cannot be placed in a named one.
  const auto message = error_of({path, "EPSG:32616", "bed raster"});
  CHECK_THAT(message, Catch::Contains("dem.asc"));
  CHECK_THAT(message, Catch::Contains("has no CRS"));
  CHECK_THAT(message, Catch::Contains("bed.crs"));
}

TEST_CASE("unreadable rasters fail with one line naming the file", "[raster]") {
  TempDir dir;
  const auto missing = error_of({dir.path() / "nowhere.tif", "", "bed raster"});
  CHECK_THAT(missing, Catch::StartsWith("bed raster '"));
  CHECK_THAT(missing, Catch::Contains("nowhere.tif"));
  CHECK_THAT(missing, Catch::Contains("file not found"));

  const auto text = dir.path() / "notes.tif";
  std::ofstream(text) << "not a raster\n";
  CHECK_THAT(error_of({text, "", "manning raster"}), Catch::Contains("is not a raster"));

  const auto bed = dir.path() / "bed.tif";
  write_geotiff(utm_field(), bed);
  RasterRequest second_band{bed, "", "bed raster"};
  second_band.band = 2;
  CHECK_THAT(error_of(second_band), Catch::Contains("has no band 2"));

  for (const std::string target : {"EPSG:4326", "no such crs", "EPSG:2277"}) {
    CHECK_THAT(error_of({bed, target, "bed raster"}),
               Catch::Contains("bed.crs = \"" + target + "\""));
  }
  CHECK(error_of({text, "", "manning raster"}).find('\n') == std::string::npos);
}

TEST_CASE("a projected raster not in metres is refused", "[raster]") {
  TempDir dir;
  auto feet = utm_field();
  const auto path = dir.path() / "feet.tif";
  write_geotiff(GriddedField(feet.geometry(), feet.values(), wkt_of("EPSG:2277")), path);
  CHECK_THAT(error_of({path, "", "bed raster"}), Catch::Contains("foot"));
}

TEST_CASE("a longitude/latitude raster needs a target CRS, and the message says which",
          "[raster]") {
  TempDir dir;
  const auto path = dir.path() / "geographic.tif";
  // Centred near 84.2 W, 36.6 N: UTM zone 16N.
  write_geotiff(lon_lat_field(-84.4, 36.75, 0.01, 30, 30), path);
  const auto message = error_of({path, "", "bed raster"});
  CHECK_THAT(message, Catch::Contains("geographic.tif"));
  CHECK_THAT(message, Catch::Contains("longitude/latitude"));
  CHECK_THAT(message, Catch::Contains("bed.crs"));
  CHECK_THAT(message, Catch::Contains("EPSG:32616"));
}

TEST_CASE("a longitude/latitude raster is warped to UTM", "[raster]") {
  TempDir dir;
  const auto path = dir.path() / "geographic.tif";
  // 1.6 x 1 degrees, 1.2 to 2.8 degrees east of zone 16's central meridian (87 W): grid north
  // turns away from true north there, so the footprint does not fill its bounding box.
  const double west = -85.8, north = 36.0, step = 0.01;
  write_geotiff(lon_lat_field(west, north, step, 160, 100), path);
  const auto field = read_raster({path, "EPSG:32616", "bed raster"});
  const auto& g = field.geometry();
  CHECK(same_crs(field.crs_wkt(), "EPSG:32616"));
  CHECK(g.cell_width == Approx(g.cell_height));  // square cells
  CHECK(g.cell_width > 700.0);                   // 0.01 degree is 0.9 to 1.1 km here
  CHECK(g.cell_width < 1200.0);
  CHECK(g.columns > 100);
  CHECK(g.rows > 80);

  const auto to_utm = transformation(4326, 32616);
  const auto to_lon_lat = transformation(32616, 4326);

  // Known points well inside the footprint: the value there is the source's, up to the
  // bilinear error of a surface linear in degrees seen on a grid in metres (0.1 is 1/100 of
  // the change across a source cell).
  for (const auto& [lon, lat] : std::vector<std::array<double, 2>>{
           {-85.0, 35.5}, {-85.63, 35.17}, {-84.41, 35.86}, {-85.2468, 35.3012}}) {
    double x = lon, y = lat;
    REQUIRE(to_utm->Transform(1, &x, &y));
    CHECK(field.covers(x, y));
    CHECK(field.sample(x, y) == Approx(lon_lat_value(lon, lat)).margin(0.1));
  }

  // Corner cells: NaN where the cell centre lies outside the source raster, a value where it
  // lies well inside. At least one corner must be outside for the check to mean anything.
  int outside = 0;
  for (std::size_t col : {std::size_t{0}, g.columns - 1}) {
    for (std::size_t row : {std::size_t{0}, g.rows - 1}) {
      double lon = g.cell_centre_x(col), lat = g.cell_centre_y(row);
      REQUIRE(to_lon_lat->Transform(1, &lon, &lat));
      const double east = west + 160 * step, south = north - 100 * step;
      const double margin = step;  // the warp's own edge handling is not under test
      if (lon < west - margin || lon > east + margin || lat < south - margin ||
          lat > north + margin) {
        ++outside;
        CHECK(std::isnan(field.at(col, row)));
      } else if (lon > west + margin && lon < east - margin && lat > south + margin &&
                 lat < north - margin) {
        CHECK(std::isfinite(field.at(col, row)));
      }
    }
  }
  CHECK(outside > 0);
}

TEST_CASE("a south-up raster is turned north-up", "[raster]") {
  TempDir dir;
  const auto path = dir.path() / "south_up.tif";
  GDALAllRegister();
  {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    REQUIRE(driver);
    GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 3, 2, 1, GDT_Float32, nullptr));
    REQUIRE(dataset);
    // The first stored row is the southern one, at y in [1000, 1010].
    std::array<double, 6> gt = {500.0, 10.0, 0.0, 1000.0, 0.0, 10.0};
    dataset->SetGeoTransform(gt.data());
    std::array<float, 6> stored = {1, 2, 3, 4, 5, 6};
    REQUIRE(dataset->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 3, 2, stored.data(), 3, 2,
                                                GDT_Float32, 0, 0, nullptr) == CE_None);
  }
  const auto field = read_raster({path, "", "bed raster"});
  const auto& g = field.geometry();
  CHECK(g.y_top == 1020.0);
  CHECK(g.cell_height == 10.0);
  CHECK(field.at(0, 0) == 4.0);  // the northern row was stored last
  CHECK(field.at(2, 1) == 3.0);
  // The point (505, 1005) is in the first stored cell, whatever the order.
  CHECK(field.sample(505.0, 1005.0) == 1.0);
}

TEST_CASE("the UTM zone of a point", "[raster]") {
  CHECK(utm_crs_for(-84.25, 36.6) == "EPSG:32616");
  CHECK(utm_crs_for(151.2, -33.9) == "EPSG:32756");
  CHECK(utm_crs_for(-180.0, 0.0) == "EPSG:32601");
  CHECK(utm_crs_for(180.0, 1.0) == "EPSG:32601");   // the same meridian as 180 W
  CHECK(utm_crs_for(359.0, 10.0) == "EPSG:32630");  // 1 W
  CHECK(utm_crs_for(3.0, 60.0) == "EPSG:32631");
}

TEST_CASE("a wrapped dataset name splits into driver, file and the rest", "[raster]") {
  const auto nc = split_dataset_name(R"(NETCDF:"bed.nc":elevation)");
  REQUIRE(nc);
  CHECK(nc->driver == "NETCDF");
  CHECK(nc->file == "bed.nc");
  CHECK(nc->rest == ":elevation");
  const auto gpkg = split_dataset_name(R"(GPKG:"dir/my bed.gpkg")");
  REQUIRE(gpkg);
  CHECK(gpkg->file == "dir/my bed.gpkg");
  CHECK(gpkg->rest.empty());
  CHECK_FALSE(split_dataset_name(R"(C:"bed.tif")"));  // a drive letter, not a driver
  CHECK_FALSE(split_dataset_name(R"(1X:"bed.tif")"));
  CHECK_FALSE(split_dataset_name(R"(NETCDF:"":x)"));
  CHECK_FALSE(split_dataset_name(R"(NETCDF:"bed.nc)"));
  CHECK_FALSE(split_dataset_name("NETCDF:\"bed.nc\":a\nb"));
  CHECK_FALSE(split_dataset_name("bed.tif"));
  // Long names once overflowed the stack of the pattern matcher.
  CHECK_FALSE(split_dataset_name(std::string(300000, 'a')));
  const auto long_file = split_dataset_name("GTiff:\"" + std::string(300000, 'b') + "\"");
  REQUIRE(long_file);
  CHECK(long_file->file.size() == 300000);
}

TEST_CASE("the shipped Jacksboro DEM reads in UTM zone 16N", "[raster]") {
  const fs::path path = fs::path(SWEMPS_SOURCE_DIR) / "data" / "jacksboro_fault_dem.tif";
  CHECK_THAT(error_of({path, "", "bed raster"}), Catch::Contains("EPSG:32616"));

  const auto field = read_raster({path, "EPSG:32616", "bed raster"});
  const auto& g = field.geometry();
  // GDAL's suggested grid for 403 x 344 cells of 3 arc-seconds at 36.6 N.
  CHECK(g.columns == 375);
  CHECK(g.rows == 395);
  CHECK(g.cell_width == Approx(82.622).margin(1e-3));
  CHECK(g.cell_height == Approx(g.cell_width));
  CHECK(g.x_left == Approx(730939.2).margin(0.1));
  CHECK(g.y_top == Approx(4069226.2).margin(0.1));
  // The footprint is turned by grid convergence: the bounding box's corners are outside it.
  CHECK(std::isnan(field.at(0, 0)));
  CHECK(std::isnan(field.at(g.columns - 1, 0)));
  CHECK(std::isnan(field.at(0, g.rows - 1)));
  CHECK(std::isnan(field.at(g.columns - 1, g.rows - 1)));
  // The largest box inside the footprint (731796..760934 x 4037415..4068363), less two
  // cells, is free of nodata.
  const auto inside = field.nodata_in(731966.0, 760764.0, 4037585.0, 4068193.0);
  CHECK(inside.count == 0);
  double low = 1e9, high = -1e9;
  for (double v : field.values()) {
    if (std::isnan(v)) continue;
    low = std::min(low, v);
    high = std::max(high, v);
  }
  CHECK(low >= 236.0);  // the source's range, which bilinear resampling cannot leave
  CHECK(high <= 1076.0);
  CHECK(low < 300.0);
  CHECK(high > 1000.0);
}

TEST_CASE("the requested band is read, warped or not", "[raster]") {
  TempDir dir;
  const auto path = dir.path() / "two_bands.tif";
  GDALAllRegister();
  {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    REQUIRE(driver);
    GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 20, 20, 2, GDT_Float64, nullptr));
    REQUIRE(dataset);
    std::array<double, 6> gt = {-84.3, 0.01, 0.0, 36.7, 0.0, -0.01};
    dataset->SetGeoTransform(gt.data());
    OGRSpatialReference lon_lat;
    lon_lat.importFromEPSG(4326);
    dataset->SetSpatialRef(&lon_lat);
    for (int band : {1, 2}) {
      std::vector<double> values(400, 100.0 * band);
      REQUIRE(dataset->GetRasterBand(band)->RasterIO(GF_Write, 0, 0, 20, 20, values.data(), 20, 20,
                                                     GDT_Float64, 0, 0, nullptr) == CE_None);
    }
  }
  RasterRequest request{path, "EPSG:32616", "manning raster"};
  request.band = 2;
  const auto field = read_raster(request);
  const auto& g = field.geometry();
  CHECK(field.sample(0.5 * (g.x_left + g.x_right()), 0.5 * (g.y_top + g.y_bottom())) ==
        Approx(200.0));
  CHECK(field.name() == "manning raster");
}

TEST_CASE("a warped raster is refined before it is interpolated, so that a rim keeps its height",
          "[raster]") {
  TempDir dir;
  const auto path = dir.path() / "rim.tif";
  // 3 arc-second cells (about 92 x 75 m here) on flat ground at 100 m, with one row of cells
  // at 110 m running east-west: a rim one source cell wide, as a basin's edge in a DEM.
  const double step = 1.0 / 1200.0;
  const std::size_t columns = 60, rows = 60, rim_row = 31;
  const GridGeometry g = grid_geometry(columns, rows, -84.40, 36.70, step, step);
  std::vector<double> values(columns * rows, 100.0);
  for (std::size_t col = 0; col < columns; ++col) values[rim_row * columns + col] = 110.0;
  write_geotiff(GriddedField(g, values, wkt_of("EPSG:4326"), "elevation"), path);
  const RasterRequest request{path, "EPSG:32616", "bed raster"};

  const auto coarse = swemps::io::read_raster_surface(request, 1);
  const auto fine = swemps::io::read_raster_surface(request, 4);
  CHECK(coarse.refinement == 1);
  REQUIRE(fine.refinement == 4);
  // The natural cells are the unrefined warp's, and the fine cells tile them 4 x 4.
  const auto& n = fine.cells;
  CHECK(n.columns == coarse.cells.columns);
  CHECK(n.rows == coarse.cells.rows);
  CHECK(n.x_left == coarse.cells.x_left);
  CHECK(n.y_top == coarse.cells.y_top);
  const auto& f = fine.field.geometry();
  CHECK(f.columns == 4 * n.columns);
  CHECK(f.rows == 4 * n.rows);
  CHECK(f.x_left == Approx(n.x_left).margin(1e-6));
  CHECK(f.y_top == Approx(n.y_top).margin(1e-6));
  CHECK(f.cell_width == Approx(n.cell_width / 4.0).epsilon(1e-12));

  // Across the rim, well inside the footprint: the source's surface (bilinear between its
  // centres) peaks at 110 m on the rim row's centre line. The fine surface has a centre
  // within 1/8 of a natural cell (about 10 m) of any line, where the source's tent, a cell
  // of about 92 m wide on each side, is within 1.2 m of its peak; the coarse surface may
  // miss the peak by half a natural cell and then interpolates across it once more.
  const auto to_utm = transformation(4326, 32616);
  double fine_lowest_peak = 1e9, coarse_lowest_peak = 1e9;
  for (int k = 10; k <= 50; k += 4) {
    const double lon = g.cell_centre_x(static_cast<std::size_t>(k));
    double fine_peak = 0.0, coarse_peak = 0.0;
    for (int s = -200; s <= 200; ++s) {
      double x = lon, y = g.cell_centre_y(rim_row) + s * step / 100.0;
      REQUIRE(to_utm->Transform(1, &x, &y));
      fine_peak = std::max(fine_peak, fine.field.sample(x, y));
      coarse_peak = std::max(coarse_peak, coarse.field.sample(x, y));
    }
    fine_lowest_peak = std::min(fine_lowest_peak, fine_peak);
    coarse_lowest_peak = std::min(coarse_lowest_peak, coarse_peak);
  }
  CHECK(fine_lowest_peak > 108.5);
  CHECK(fine_lowest_peak > coarse_lowest_peak);
  INFO("lowest rim crest: coarse " << coarse_lowest_peak << " m, fine " << fine_lowest_peak);

  // Memory that cannot hold the fine cells takes the refinement down, never the read.
  RasterRequest tight = request;
  const double natural_cells = static_cast<double>(n.columns * n.rows);
  tight.memory_limit_bytes =
      static_cast<std::uint64_t>(natural_cells * 5.0 * swemps::io::kRasterBytesPerCell);
  const auto limited = swemps::io::read_raster_surface(tight, 4);
  CHECK(limited.refinement == 2);
  CHECK(limited.field.geometry().columns == 2 * n.columns);
}

TEST_CASE("a raster in the scene's own CRS is its own surface, unrefined", "[raster]") {
  TempDir dir;
  const auto path = dir.path() / "bed.tif";
  write_geotiff(utm_field(), path);
  const auto surface = swemps::io::read_raster_surface({path, "EPSG:32616", "bed raster"}, 4);
  CHECK(surface.refinement == 1);
  CHECK(surface.field.geometry().columns == surface.cells.columns);
  const auto expected = utm_field().values();
  REQUIRE(surface.field.values().size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const double v = surface.field.values()[k];
    CHECK((v == expected[k] || (std::isnan(v) && std::isnan(expected[k]))));
  }
}
