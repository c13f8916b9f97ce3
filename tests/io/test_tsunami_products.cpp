// Tests of the tsunami products made from a result file: the inundation line on a beach and
// around an island whose positions and ground are known, and the arrivals at gauges.

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/gdal_messages.hpp"
#include "swemps/io/netcdf_writer.hpp"
#include "swemps/io/tsunami_products.hpp"
#include "swemps/maps/flood_statistics.hpp"

namespace fs = std::filesystem;
using swemps::io::GaugeSample;
using swemps::io::Grid;
using swemps::io::NetcdfWriter;
using swemps::io::VectorFile;
using swemps::maps::FloodStatistics;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kWet = 0.01;

// A beach rising along x, z = 0.1 (x - 5), under a sea still at 0 that a wave lifted to
// 0.3 m everywhere it reached, with a cone of ground rising to 0.6 m at (2, 5) that the wave
// did not cover. The line where the largest depth 0.3 - z falls to the wet depth is x = 7.9
// (ground 0.29 m) on the beach, and a ring of ground 0.29 m round the cone.
struct Scene {
  Grid grid;
  std::vector<double> bed;
};

double beach(double x, double y) {
  const double cone = 0.6 - 0.3 * std::hypot(x - 2.0, y - 5.0);
  return std::max(0.1 * (x - 5.0), cone);
}

Scene beach_scene(const std::string& crs_wkt) {
  Scene s;
  s.grid = Grid{0.05, 0.05, 0.1, 0.1, 100, 100, crs_wkt};
  for (std::size_t k = 0; k < s.grid.ny; ++k) {
    for (std::size_t i = 0; i < s.grid.nx; ++i) {
      s.bed.push_back(beach(s.grid.x0 + static_cast<double>(i) * s.grid.dx,
                            s.grid.y0 + static_cast<double>(k) * s.grid.dy));
    }
  }
  return s;
}

// Writes the result of a run that starts at rest and is lifted 0.3 m at t = 10 s; gauge
// "sea" stands on the beach's toe, gauge "hill" on the cone's top.
fs::path write_result(const fs::path& folder, const Scene& s, bool tsunami) {
  const fs::path file = folder / "beach.nc";
  const std::size_t cells = s.bed.size();
  swemps::maps::StatisticsSettings settings{kWet, {}};
  if (tsunami) settings.tsunami = swemps::maps::TsunamiLevels{0.0, 0.02};
  FloodStatistics stats(cells, settings, s.bed);
  const std::vector<double> zero(cells, 0.0);
  std::vector<double> rest(cells), lifted(cells);
  for (std::size_t c = 0; c < cells; ++c) {
    rest[c] = std::max(0.0, -s.bed[c]);
    lifted[c] = std::max(0.0, 0.3 - s.bed[c]);
  }
  stats.update(0.0, rest, zero, zero);
  stats.update(10.0, lifted, zero, zero);
  stats.update(20.0, rest, zero, zero);
  swemps::io::RunMetadata meta;
  meta.title = "beach";
  NetcdfWriter w(file, {s.grid, false, {{"sea", 1.0, 1.0}, {"hill", 2.0, 5.0}}}, meta);
  w.write_bed(s.bed);
  const double sea_bed = beach(1.0, 1.0);
  for (const double t : {0.0, 10.0, 20.0}) {
    const double surface = t == 10.0 ? 0.3 : 0.0;
    const std::vector<GaugeSample> gauges{{surface - sea_bed, 0.0, 0.0, surface},
                                          {0.0, kNaN, kNaN, kNaN}};
    w.write_series(t, gauges, {});
  }
  w.write(0.0, {rest, rest, zero, zero});
  w.write_summary(stats);
  w.finish();
  return file;
}

struct ReadLine {
  std::vector<double> x, y, z;
  double max_ground = kNaN, max_runup = kNaN, length = kNaN;
};

std::vector<ReadLine> read_lines(const fs::path& file, std::string* crs_name = nullptr) {
  swemps::io::register_gdal_drivers();
  const GDALDatasetUniquePtr ds(GDALDataset::Open(file.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  REQUIRE(ds);
  REQUIRE(ds->GetLayerCount() == 1);
  OGRLayer* layer = ds->GetLayer(0);
  CHECK(std::string(layer->GetName()) == "inundation_line");
  CHECK(wkbHasZ(layer->GetGeomType()));
  if (crs_name && layer->GetSpatialRef()) *crs_name = layer->GetSpatialRef()->GetName();
  std::vector<ReadLine> out;
  for (auto& f : *layer) {
    const OGRLineString* g = f->GetGeometryRef()->toLineString();
    ReadLine line;
    for (int p = 0; p < g->getNumPoints(); ++p) {
      line.x.push_back(g->getX(p));
      line.y.push_back(g->getY(p));
      line.z.push_back(g->getZ(p));
    }
    line.max_ground = f->GetFieldAsDouble("max_ground_elevation_m");
    if (f->IsFieldSetAndNotNull(f->GetFieldIndex("max_runup_m"))) {
      line.max_runup = f->GetFieldAsDouble("max_runup_m");
    }
    line.length = f->GetFieldAsDouble("length_m");
    out.push_back(line);
  }
  return out;
}

}  // namespace

TEST_CASE("the inundation line bounds the water's reach and carries the ground it reached",
          "[io][tsunami]") {
  swemps::testing::TempDir tmp;
  const Scene scene = beach_scene(swemps::testing::wkt_of("EPSG:32616"));
  const fs::path result = write_result(tmp.path(), scene, true);
  const auto format = GENERATE(VectorFile::gpkg, VectorFile::geojson);
  const fs::path file = tmp.path() / (format == VectorFile::gpkg ? "line.gpkg" : "line.geojson");
  const auto summary = swemps::io::export_inundation_line(result, file, format);
  REQUIRE(summary.has_value());
  CHECK(summary->lines == 2);
  CHECK_FALSE(fs::exists(
      tmp.path() / (format == VectorFile::gpkg ? "line.partial.gpkg" : "line.partial.geojson")));

  std::string crs;
  const auto lines = read_lines(file, &crs);
  CHECK(crs == "WGS 84 / UTM zone 16N");
  REQUIRE(lines.size() == 2);
  // The longest first: the beach's line runs the grid's whole height (the tracing carries it
  // from the outer centres to the outer cells' edges). Linear between centres of a linear
  // depth, it stands at x = 7.9 exactly, and the bilinear ground of a linear bed is the bed.
  const ReadLine& coast = lines[0];
  CHECK(coast.length == Approx(10.0).margin(1e-6));
  for (std::size_t p = 0; p < coast.x.size(); ++p) {
    CHECK(coast.x[p] == Approx(7.9).margin(1e-9));
    CHECK(coast.z[p] == Approx(0.29).margin(1e-9));
  }
  CHECK(coast.max_ground == Approx(0.29).margin(1e-9));
  CHECK(coast.max_runup == Approx(0.29).margin(1e-9));
  // The island: a closed ring round the cone where its ground is 0.29 m, radius 1.033 m.
  // There the depth falls to 0 inside a cell (at r = 1, a kink), which the linear reading
  // between centres cannot see: it puts the line on the dry side's way by up to a fifth of a
  // cell (0.017 m here), and never beyond the true line.
  const ReadLine& island = lines[1];
  REQUIRE(island.x.size() > 8);
  CHECK(island.x.front() == Approx(island.x.back()));
  CHECK(island.y.front() == Approx(island.y.back()));
  const double radius = (0.6 - 0.29) / 0.3;
  for (std::size_t p = 0; p < island.x.size(); ++p) {
    const double r = std::hypot(island.x[p] - 2.0, island.y[p] - 5.0);
    CHECK(r == Approx(radius - 0.01).margin(0.01));
    CHECK(island.z[p] == Approx(0.6 - 0.3 * r).margin(0.003));  // the bilinear ground
  }
  CHECK(island.length == Approx(2.0 * M_PI * (radius - 0.01)).epsilon(0.02));

  // The summary is the highest vertex of all the lines: here on the island's ring.
  REQUIRE(summary->max_runup_m.has_value());
  CHECK(summary->max_ground_elevation_m == Approx(island.max_ground).margin(1e-12));
  CHECK(*summary->max_runup_m == Approx(island.max_runup).margin(1e-12));
  CHECK(island.max_ground > coast.max_ground);
  CHECK(std::hypot(summary->x_m - 2.0, summary->y_m - 5.0) == Approx(radius - 0.01).margin(0.01));
}

TEST_CASE("a result without tsunami maps has a line but no run-up or arrivals", "[io][tsunami]") {
  swemps::testing::TempDir tmp;
  const fs::path result = write_result(tmp.path(), beach_scene(""), false);
  CHECK_FALSE(swemps::io::has_tsunami_maps(result));
  const auto summary =
      swemps::io::export_inundation_line(result, tmp.path() / "line.gpkg", VectorFile::gpkg);
  REQUIRE(summary.has_value());
  CHECK_FALSE(summary->max_runup_m.has_value());
  const auto lines = read_lines(tmp.path() / "line.gpkg");
  REQUIRE(lines.size() == 2);
  CHECK(std::isnan(lines[0].max_runup));
  CHECK(lines[0].max_ground == Approx(0.29).margin(1e-9));
  CHECK_FALSE(swemps::io::export_gauge_arrivals(result, tmp.path() / "arrivals.csv"));
  CHECK_FALSE(fs::exists(tmp.path() / "arrivals.csv"));
}

TEST_CASE("gauge arrivals: the first sample the arrival rise above the still level",
          "[io][tsunami]") {
  swemps::testing::TempDir tmp;
  const fs::path result = write_result(tmp.path(), beach_scene(""), true);
  CHECK(swemps::io::has_tsunami_maps(result));
  const fs::path csv = tmp.path() / "arrivals.csv";
  REQUIRE(swemps::io::export_gauge_arrivals(result, csv));
  std::ifstream in(csv);
  std::stringstream text;
  text << in.rdbuf();
  CHECK(text.str() ==
        "gauge,x_m,y_m,arrival_time_s,max_surface_rise_m,time_of_max_rise_s\n"
        "sea,1,1,10,0.3,10\n"
        "hill,2,5,,,\n");
}

TEST_CASE("the tsunami products name a file they cannot read or write", "[io][tsunami]") {
  swemps::testing::TempDir tmp;
  CHECK_THROWS_WITH(swemps::io::export_inundation_line(tmp.path() / "missing.nc",
                                                       tmp.path() / "l.gpkg", VectorFile::gpkg),
                    Catch::Contains("missing.nc"));
  const fs::path result = write_result(tmp.path(), beach_scene(""), true);
  CHECK_THROWS_WITH(swemps::io::export_inundation_line(
                        result, tmp.path() / "no-such-folder" / "l.gpkg", VectorFile::gpkg),
                    Catch::Contains("l.partial.gpkg"));
  CHECK_THROWS_WITH(
      swemps::io::export_gauge_arrivals(result, tmp.path() / "no-such-folder" / "a.csv"),
      Catch::Contains("a.partial.csv"));
}
