#include <cpl_conv.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "swemps/io/geotiff_writer.hpp"

namespace fs = std::filesystem;
using swemps::io::Grid;
using swemps::io::RasterBand;
using swemps::io::TiffLayout;
using swemps::io::write_geotiff;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string wkt_of_epsg(int code) {
  OGRSpatialReference crs;
  REQUIRE(crs.importFromEPSG(code) == OGRERR_NONE);
  char* text = nullptr;
  crs.exportToWkt(&text);
  std::string wkt = text;
  CPLFree(text);
  return wkt;
}

// 7 x 5 cells of 2.5 m x 4 m in UTM zone 14 N.
Grid small_grid() {
  Grid g;
  g.x0 = 500123.25;
  g.y0 = 3712345.5;
  g.dx = 2.5;
  g.dy = 4.0;
  g.nx = 7;
  g.ny = 5;
  g.crs_wkt = wkt_of_epsg(32614);
  return g;
}

GDALDatasetUniquePtr open(const fs::path& path) {
  GDALAllRegister();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  REQUIRE(ds);
  return ds;
}

// The band's values in the file's own order: row 0 is the northernmost.
std::vector<double> stored_values(GDALRasterBand& band) {
  const int columns = band.GetXSize(), rows = band.GetYSize();
  std::vector<double> out(static_cast<std::size_t>(columns) * rows);
  REQUIRE(band.RasterIO(GF_Read, 0, 0, columns, rows, out.data(), columns, rows, GDT_Float64, 0, 0,
                        nullptr) == CE_None);
  return out;
}

std::string structure(GDALDataset& ds, const char* key) {
  const char* value = ds.GetMetadataItem(key, "IMAGE_STRUCTURE");
  return value ? value : "";
}

// The command that runs GDAL's COG validator, if this machine's Python has it.
std::optional<std::string> cog_validator() {
  const std::string module = "osgeo_utils.samples.validate_cloud_optimized_geotiff";
  for (const std::string python : {"python3", "/usr/bin/python3"}) {
    if (swemps::testing::run_command(python + " -c 'import " + module + "'").status == 0) {
      return python + " -m " + module;
    }
  }
  return std::nullopt;
}

bool folder_is_empty(const fs::path& dir) {
  return fs::directory_iterator(dir) == fs::directory_iterator();
}

}  // namespace

TEST_CASE("a continuous map reads back north-up on the grid's cell centres, in its CRS",
          "[io][geotiff]") {
  const TiffLayout layout = GENERATE(TiffLayout::plain, TiffLayout::cloud_optimised);
  CAPTURE(layout == TiffLayout::plain ? "plain" : "cloud-optimised");
  swemps::testing::TempDir dir("geotiff");
  const fs::path path = dir.path() / "max_depth.tif";
  const Grid g = small_grid();
  std::vector<double> values(g.nx * g.ny);
  for (std::size_t k = 0; k < g.ny; ++k) {
    for (std::size_t i = 0; i < g.nx; ++i) values[k * g.nx + i] = 10.0 * k + i + 0.125;
  }
  values[0] = kNaN;                // south-west corner
  values[3 * g.nx + 5] = kNaN;     // an inner cell
  values[g.nx * g.ny - 1] = kNaN;  // north-east corner
  const RasterBand band{"maximum water depth", "m", {}, {}};
  write_geotiff(path, g, values, band, layout,
                {{"TIFFTAG_SOFTWARE", "swe-mps test"}, {"source", "cases/dam.json"}});

  REQUIRE(fs::exists(path));
  CHECK_FALSE(fs::exists(dir.path() / "max_depth.tif.partial"));
  CHECK_FALSE(fs::exists(dir.path() / "max_depth.tif.aux.xml"));
  auto ds = open(path);
  REQUIRE(ds->GetRasterXSize() == 7);
  REQUIRE(ds->GetRasterYSize() == 5);
  REQUIRE(ds->GetRasterCount() == 1);
  double gt[6];
  REQUIRE(ds->GetGeoTransform(gt) == CE_None);
  CHECK(gt[0] == Approx(g.x0 - 1.25).epsilon(1e-15));
  CHECK(gt[1] == 2.5);
  CHECK(gt[2] == 0.0);
  CHECK(gt[3] == Approx(g.y0 + 4.5 * 4.0).epsilon(1e-15));
  CHECK(gt[4] == 0.0);
  CHECK(gt[5] == -4.0);

  const OGRSpatialReference* crs = ds->GetSpatialRef();
  REQUIRE(crs);
  OGRSpatialReference expected;
  expected.importFromEPSG(32614);
  CHECK(crs->IsSame(&expected));

  GDALRasterBand* b = ds->GetRasterBand(1);
  CHECK(b->GetRasterDataType() == GDT_Float32);
  int has_nodata = 0;
  CHECK(std::isnan(b->GetNoDataValue(&has_nodata)));
  CHECK(has_nodata);
  CHECK(std::string(b->GetDescription()) == "maximum water depth");
  CHECK(std::string(b->GetUnitType()) == "m");
  const auto stored = stored_values(*b);
  for (std::size_t k = 0; k < g.ny; ++k) {
    for (std::size_t i = 0; i < g.nx; ++i) {
      CAPTURE(i, k);
      const double expected_value = values[k * g.nx + i];
      const double got = stored[(g.ny - 1 - k) * g.nx + i];
      if (std::isnan(expected_value)) {
        CHECK(std::isnan(got));
      } else {
        CHECK(got == static_cast<float>(expected_value));
      }
    }
  }
  CHECK(structure(*ds, "COMPRESSION") == "DEFLATE");
  CHECK(structure(*ds, "PREDICTOR") == "3");
  CHECK(structure(*ds, "LAYOUT") == (layout == TiffLayout::plain ? "" : "COG"));
  int block_x = 0, block_y = 0;
  b->GetBlockSize(&block_x, &block_y);
  CHECK(block_y > 1);  // tiled, not stripped
  CHECK(std::string(ds->GetMetadataItem("TIFFTAG_SOFTWARE")) == "swe-mps test");
  CHECK(std::string(ds->GetMetadataItem("source")) == "cases/dam.json");
}

TEST_CASE("a map without a CRS is written without one", "[io][geotiff]") {
  swemps::testing::TempDir dir("geotiff");
  Grid g = small_grid();
  g.crs_wkt.clear();
  write_geotiff(dir.path() / "local.tif", g, std::vector<double>(35, 1.0),
                RasterBand{"depth", "m", {}, {}}, TiffLayout::plain);
  auto ds = open(dir.path() / "local.tif");
  const OGRSpatialReference* crs = ds->GetSpatialRef();
  CHECK((crs == nullptr || crs->IsEmpty()));
}

TEST_CASE("a class map is Byte with nodata 0, category names and a colour table", "[io][geotiff]") {
  const TiffLayout layout = GENERATE(TiffLayout::plain, TiffLayout::cloud_optimised);
  swemps::testing::TempDir dir("geotiff");
  const fs::path path = dir.path() / "hazard.tif";
  const Grid g = small_grid();
  std::vector<double> values(g.nx * g.ny);
  for (std::size_t c = 0; c < values.size(); ++c) values[c] = c % 4 == 0 ? kNaN : double(c % 4);
  RasterBand band{"flood hazard class",
                  "1",
                  {"low", "medium", "high"},
                  {{{0, 200, 0}}, {{255, 200, 0}}, {{220, 0, 0}}}};
  write_geotiff(path, g, values, band, layout);

  auto ds = open(path);
  GDALRasterBand* b = ds->GetRasterBand(1);
  CHECK(b->GetRasterDataType() == GDT_Byte);
  int has_nodata = 0;
  CHECK(b->GetNoDataValue(&has_nodata) == 0.0);
  CHECK(has_nodata);
  CHECK(std::string(b->GetDescription()) == "flood hazard class");
  char** names = b->GetCategoryNames();
  REQUIRE(CSLCount(names) >= 4);
  CHECK(std::string(names[1]) == "low");
  CHECK(std::string(names[2]) == "medium");
  CHECK(std::string(names[3]) == "high");
  CHECK(std::string(b->GetMetadataItem("CLASS_3")) == "high");
  const GDALColorTable* colours = b->GetColorTable();
  REQUIRE(colours);
  REQUIRE(colours->GetColorEntryCount() >= 4);
  const GDALColorEntry* high = colours->GetColorEntry(3);
  CHECK((high->c1 == 220 && high->c2 == 0 && high->c3 == 0));
  const auto stored = stored_values(*b);
  for (std::size_t k = 0; k < g.ny; ++k) {
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double v = values[k * g.nx + i];
      CHECK(stored[(g.ny - 1 - k) * g.nx + i] == (std::isnan(v) ? 0.0 : v));
    }
  }
  CHECK(structure(*ds, "PREDICTOR") == "2");
}

TEST_CASE("a class map without colours gets one colour per class", "[io][geotiff]") {
  swemps::testing::TempDir dir("geotiff");
  write_geotiff(dir.path() / "c.tif", small_grid(), std::vector<double>(35, 2.0),
                RasterBand{"class", "1", {"a", "b"}, {}}, TiffLayout::plain);
  auto ds = open(dir.path() / "c.tif");
  const GDALColorTable* colours = ds->GetRasterBand(1)->GetColorTable();
  REQUIRE(colours);
  const GDALColorEntry* a = colours->GetColorEntry(1);
  const GDALColorEntry* b = colours->GetColorEntry(2);
  CHECK_FALSE((a->c1 == b->c1 && a->c2 == b->c2 && a->c3 == b->c3));
}

TEST_CASE("a map larger than one tile is a valid COG with overviews", "[io][geotiff]") {
  swemps::testing::TempDir dir("geotiff");
  Grid g = small_grid();
  g.nx = 600;
  g.ny = 400;
  // A dry half beside a 5 m deep half with holes: a zoomed-out view must neither lose the
  // holes' neighbours to NaN nor invent depths below 0 or above 5 at the edge.
  std::vector<double> depth(g.nx * g.ny);
  for (std::size_t c = 0; c < depth.size(); ++c) {
    const std::size_t i = c % g.nx;
    depth[c] = c % 13 == 0 ? kNaN : (i < 301 ? 0.0 : 5.0);
  }
  // Classes 1 and 3 as a chequerboard: a zoomed-out pixel must show one of them, never the
  // class 2 that lies between them in number only.
  std::vector<double> classes(depth.size());
  for (std::size_t c = 0; c < classes.size(); ++c) {
    classes[c] = std::isnan(depth[c]) ? kNaN : ((c % g.nx + c / g.nx) % 2 == 0 ? 1.0 : 3.0);
  }

  const fs::path depth_path = dir.path() / "depth.tif", class_path = dir.path() / "class.tif";
  write_geotiff(depth_path, g, depth, RasterBand{"maximum water depth", "m", {}, {}},
                TiffLayout::cloud_optimised);
  write_geotiff(class_path, g, classes, RasterBand{"class", "1", {"a", "b", "c"}, {}},
                TiffLayout::cloud_optimised);

  for (const auto& path : {depth_path, class_path}) {
    CAPTURE(path);
    auto ds = open(path);
    CHECK(structure(*ds, "LAYOUT") == "COG");
    GDALRasterBand* b = ds->GetRasterBand(1);
    REQUIRE(b->GetOverviewCount() > 0);
    const auto overview = stored_values(*b->GetOverview(0));
    for (double v : overview) {
      REQUIRE(std::isfinite(v));
      if (path == depth_path) REQUIRE((v >= 0.0 && v <= 5.0));
      if (path == class_path) REQUIRE((v == 1.0 || v == 3.0));
    }
  }

  // The validator comes with GDAL's Python bindings (python3-gdal, which tools/install-deps.sh
  // installs): without it this test cannot do its job, so it fails rather than passes.
  const auto validator = cog_validator();
  REQUIRE(validator.has_value());
  for (const auto& path : {depth_path, class_path}) {
    const auto result = swemps::testing::run_command(*validator + " '" + path.string() + "'");
    INFO(result.output);
    CHECK(result.status == 0);
  }
}

TEST_CASE("a failed GeoTIFF write names the file and leaves nothing behind", "[io][geotiff]") {
  swemps::testing::TempDir dir("geotiff");
  const std::vector<double> values(35, 1.0);
  const RasterBand band{"depth", "m", {}, {}};
  const TiffLayout layout = GENERATE(TiffLayout::plain, TiffLayout::cloud_optimised);

  SECTION("a folder that does not exist") {
    const fs::path path = dir.path() / "missing" / "depth.tif";
    CHECK_THROWS_AS(write_geotiff(path, small_grid(), values, band, layout), std::runtime_error);
    CHECK_THROWS_WITH(write_geotiff(path, small_grid(), values, band, layout),
                      Catch::Matchers::Contains(path.string()));
    CHECK(folder_is_empty(dir.path()));
  }
  SECTION("a folder in the way of the rename") {
    const fs::path path = dir.path() / "depth.tif";
    fs::create_directories(path / "occupied");
    CHECK_THROWS_AS(write_geotiff(path, small_grid(), values, band, layout), std::runtime_error);
    CHECK_THROWS_WITH(write_geotiff(path, small_grid(), values, band, layout),
                      Catch::Matchers::Contains(path.string()));
    CHECK_FALSE(fs::exists(dir.path() / "depth.tif.partial"));
    CHECK_FALSE(fs::exists(dir.path() / "depth.tif.aux.xml"));
  }
}

TEST_CASE("a sidecar of an earlier map at the same path is not left to the new one",
          "[io][geotiff]") {
  swemps::testing::TempDir dir("geotiff");
  const fs::path path = dir.path() / "map.tif";
  write_geotiff(path, small_grid(), std::vector<double>(35, 1.0),
                RasterBand{"class", "1", {"a"}, {}}, TiffLayout::plain);
  REQUIRE(fs::exists(dir.path() / "map.tif.aux.xml"));
  write_geotiff(path, small_grid(), std::vector<double>(35, 1.5), RasterBand{"depth", "m", {}, {}},
                TiffLayout::plain);
  CHECK_FALSE(fs::exists(dir.path() / "map.tif.aux.xml"));
  auto ds = open(path);
  CHECK(ds->GetRasterBand(1)->GetCategoryNames() == nullptr);
}

TEST_CASE("the GeoTIFF writer refuses inputs that make no map", "[io][geotiff]") {
  swemps::testing::TempDir dir("geotiff");
  const fs::path path = dir.path() / "bad.tif";
  const RasterBand depth{"depth", "m", {}, {}};
  const std::vector<double> values(35, 1.0);
  Grid g = small_grid();

  CHECK_THROWS_AS(write_geotiff(path, g, std::vector<double>(34, 1.0), depth, TiffLayout::plain),
                  std::invalid_argument);
  SECTION("empty grid") {
    g.nx = 0;
    CHECK_THROWS_AS(write_geotiff(path, g, {}, depth, TiffLayout::plain), std::invalid_argument);
  }
  SECTION("cell size not positive") {
    g.dy = -4.0;
    CHECK_THROWS_AS(write_geotiff(path, g, values, depth, TiffLayout::plain),
                    std::invalid_argument);
  }
  SECTION("a CRS in degrees") {
    g.crs_wkt = wkt_of_epsg(4326);
    CHECK_THROWS_AS(write_geotiff(path, g, values, depth, TiffLayout::plain),
                    std::invalid_argument);
  }
  SECTION("a metadata key that GDAL would split") {
    CHECK_THROWS_AS(write_geotiff(path, g, values, depth, TiffLayout::plain, {{"a=b", "c"}}),
                    std::invalid_argument);
  }
  SECTION("class values outside 1..n or not whole") {
    const RasterBand classes{"class", "1", {"a", "b"}, {}};
    const double bad = GENERATE(0.0, 3.0, 1.5, -1.0);
    std::vector<double> v(35, 1.0);
    v[17] = bad;
    CHECK_THROWS_AS(write_geotiff(path, g, v, classes, TiffLayout::plain), std::invalid_argument);
  }
  SECTION("class colours that do not match the classes") {
    const RasterBand classes{"class", "1", {"a", "b"}, {{{1, 2, 3}}}};
    CHECK_THROWS_AS(write_geotiff(path, g, values, classes, TiffLayout::plain),
                    std::invalid_argument);
  }
  CHECK(folder_is_empty(dir.path()));
}
