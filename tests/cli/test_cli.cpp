// End-to-end tests of the swe-mps executable: exit statuses, messages, and that its output
// opens in the netCDF and GDAL command-line tools.

#include <gdal_priv.h>
#include <netcdf.h>
#include <ogr_spatialref.h>
#include <sys/wait.h>

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/netcdf_values.hpp"
#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace fs = std::filesystem;

namespace {

using Result = swemps::testing::CommandResult;

Result run(const std::string& command) { return swemps::testing::run_command(command); }

bool have(const std::string& tool) {
  return std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) == 0;
}

const std::string cli = SWEMPS_CLI;
const std::string ritter = std::string(SWEMPS_SOURCE_DIR) + "/cases/ritter/scenario.json";

}  // namespace

TEST_CASE("--help and --version", "[cli]") {
  const auto help = run(cli + " --help");
  CHECK(help.status == 0);
  CHECK_THAT(help.output, Catch::Contains("swe-mps run SCENARIO.json"));
  CHECK_THAT(help.output, Catch::Contains("swe-mps compare SCENARIO.json"));
  const auto version = run(cli + " --version");
  CHECK(version.status == 0);
  CHECK_THAT(version.output, Catch::StartsWith("swe-mps "));
}

TEST_CASE("bad command lines exit 2 with one clear message", "[cli]") {
  for (const std::string args :
       {"", "fly x.json", "run", "compare", "run a.json --threads zero", "run a.json --bogus"}) {
    const auto r = run(cli + " " + args);
    INFO(args << " -> " << r.output);
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::StartsWith("swe-mps: "));
  }
}

TEST_CASE("a broken scenario exits 2 naming the JSON path", "[cli]") {
  const swemps::testing::TempDir scratch("cli-bad");
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "scenario.json")
      << R"({"end_time": 1, "domain": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1}, "dpeth": 0.1, "spacing": 0.1}]})";
  const auto r = run(cli + " run " + (dir / "scenario.json").string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("/water/0/dpeth"));
  CHECK_THAT(r.output, Catch::Contains("did you mean \"depth\""));
  CHECK_THAT(r.output, !Catch::Contains("terminate"));
  const auto missing = run(cli + " run " + (dir / "nope.json").string());
  CHECK(missing.status == 2);
  CHECK_THAT(missing.output, Catch::Contains("cannot read file"));
  fs::remove_all(dir);
}

TEST_CASE("an output folder that does not exist exits 4 and leaves nothing behind", "[cli]") {
  const swemps::testing::TempDir scratch("cli-noout");
  const fs::path& dir = scratch.path();
  const auto r = run(cli + " run " + ritter + " -q -o " + (dir / "missing" / "out.nc").string());
  CHECK(r.status == 4);
  CHECK_THAT(r.output, Catch::Contains("out.nc"));
  CHECK_FALSE(fs::exists(dir / "missing"));
  fs::remove_all(dir);
}

TEST_CASE("the Ritter case runs end to end and its file opens in ncdump and gdalinfo", "[cli]") {
  const swemps::testing::TempDir scratch("cli-ritter");
  const fs::path& dir = scratch.path();
  const auto out = dir / "ritter.nc";
  const auto r = run(cli + " run " + ritter + " --threads 2 -o " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(fs::exists(out));
  CHECK_FALSE(fs::exists(out.string() + ".partial"));
  // Not a terminal: plain progress lines, then the closing summary.
  CHECK_THAT(r.output, Catch::Contains("progress: 100.0%"));
  CHECK_THAT(r.output, Catch::Contains("particle-steps/s"));
  CHECK_THAT(r.output, Catch::Contains("relative change"));
  CHECK_THAT(r.output, Catch::Contains("effect 'domain outflow'"));
  if (have("ncdump")) {
    const auto dump = run("ncdump -h " + out.string());
    CHECK(dump.status == 0);
    CHECK_THAT(dump.output, Catch::Contains(":Conventions = \"CF-1.8\""));
    CHECK_THAT(dump.output, Catch::Contains("time = UNLIMITED ; // (6 currently)"));
  } else {
    WARN("ncdump not installed: skipped");
  }
  if (have("gdalinfo")) {
    const auto info = run("gdalinfo NETCDF:\"" + out.string() + "\":depth");
    CHECK(info.status == 0);
    CHECK_THAT(info.output, Catch::Contains("Size is 500, 50"));
  } else {
    WARN("gdalinfo not installed: skipped");
  }
  fs::remove_all(dir);
}

namespace {

// A whole variable of a netCDF file, as doubles.
std::vector<double> read_variable(const fs::path& file, const std::string& name) {
  int ncid = -1;
  REQUIRE(nc_open(file.c_str(), NC_NOWRITE, &ncid) == NC_NOERR);
  std::vector<double> values = swemps::testing::whole_variable(ncid, name.c_str());
  nc_close(ncid);
  return values;
}

// A tilted bowl of 40 x 30 cells of 10 m in UTM zone 16N, lowest (300 m) near its middle.
void write_bowl(const fs::path& path) {
  swemps::terrain::GridGeometry g;
  g.columns = 40;
  g.rows = 30;
  g.x_left = 500000.0;
  g.y_top = 4000300.0;
  g.cell_width = 10.0;
  g.cell_height = 10.0;
  std::vector<double> z;
  for (std::size_t row = 0; row < g.rows; ++row) {
    for (std::size_t col = 0; col < g.columns; ++col) {
      const double x = g.cell_centre_x(col), y = g.cell_centre_y(row);
      const double dx = x - 500200.0, dy = y - 4000150.0;
      z.push_back(300.0 + 0.002 * (dx * dx + dy * dy) + 0.01 * (x - 500000.0));
    }
  }
  OGRSpatialReference utm;
  REQUIRE(utm.importFromEPSG(32616) == OGRERR_NONE);
  char* wkt = nullptr;
  utm.exportToWkt(&wkt);
  const std::string crs = wkt;
  CPLFree(wkt);
  swemps::io::write_geotiff(swemps::terrain::GriddedField(g, z, crs, "bed elevation"), path);
}

std::unique_ptr<GDALDataset> open_raster(const std::string& name) {
  GDALAllRegister();
  return std::unique_ptr<GDALDataset>(GDALDataset::FromHandle(GDALOpen(name.c_str(), GA_ReadOnly)));
}

}  // namespace

TEST_CASE("export writes a finished result's maps as GeoTIFF, and refuses what it cannot",
          "[cli][export]") {
  const swemps::testing::TempDir scratch("cli-export");
  const fs::path& dir = scratch.path();
  const auto out = dir / "ritter.nc";
  REQUIRE(run(cli + " run " + ritter + " -q -o " + out.string()).status == 0);
  // A flat scene without gauges: no bed map, no gauge table.
  CHECK_FALSE(fs::exists(dir / "ritter_gauges.csv"));

  const auto r =
      run(cli + " export " + out.string() + " --maps max_depth,arrival_time --format geotiff -o " +
          (dir / "maps").string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  for (const char* file :
       {"maps_max_depth.tif", "maps_arrival_time_0.01m.tif", "maps_arrival_time_0.1m.tif",
        "maps_arrival_time_0.3m.tif", "maps_arrival_time_0.5m.tif", "maps_arrival_time_1m.tif"}) {
    INFO(file);
    CHECK(fs::exists(dir / file));
  }
  CHECK_FALSE(fs::exists(dir / "maps_max_speed.tif"));
  const auto tif = open_raster((dir / "maps_max_depth.tif").string());
  REQUIRE(tif != nullptr);
  CHECK(tif->GetRasterXSize() == 500);
  CHECK(tif->GetRasterYSize() == 50);
  // Plain GeoTIFF: no COG layout.
  const char* layout = tif->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE");
  CHECK((layout == nullptr || std::string(layout) != "COG"));

  const auto all = run(cli + " export " + out.string() + " -q");
  CHECK(all.status == 0);
  CHECK(fs::exists(dir / "ritter_hazard_class_uk.tif"));
  CHECK(fs::exists(dir / "ritter_max_depth_speed2.tif"));
  // "all", as the help offers it, is every map too.
  const auto named_all =
      run(cli + " export " + out.string() + " -q --maps all -o " + (dir / "every").string());
  INFO(named_all.output);
  CHECK(named_all.status == 0);
  CHECK(fs::exists(dir / "every_hazard_class_aidr.tif"));
  CHECK(fs::exists(dir / "every_inundation_duration_1m.tif"));

  const auto unknown = run(cli + " export " + out.string() + " --maps max_dept");
  CHECK(unknown.status == 2);
  CHECK_THAT(unknown.output, Catch::Contains("'max_dept' is not a map that can be exported"));
  const auto missing = run(cli + " export " + (dir / "nope.nc").string());
  CHECK(missing.status == 4);
  CHECK_THAT(missing.output, Catch::Contains("nope.nc"));
  const auto not_export = run(cli + " run " + ritter + " --maps max_depth");
  CHECK(not_export.status == 2);
}

TEST_CASE("a raster scene writes flood maps on the DEM's grid and closes its volume balance",
          "[cli]") {
  const swemps::testing::TempDir scratch("cli-raster");
  const fs::path& dir = scratch.path();
  write_bowl(dir / "bed.tif");
  // A lake moving east across an outflow line, and a flood entering from the west edge.
  std::ofstream(dir / "scenario.json") << R"({
    "end_time": 20,
    "bed": {"raster": "bed.tif", "crs": "EPSG:32616"},
    "water": [{"fill": {"polygon": [[500120, 4000080], [500280, 4000080], [500280, 4000220],
                                    [500120, 4000220]]},
               "surface_elevation": 312, "spacing": 10, "velocity": [2, 0]}],
    "inflow": [{"name": "west", "line": [[500005, 4000130], [500005, 4000170]],
                "hydrograph": [[0, 0], [5, 3], [20, 3]]}],
    "outflow": [{"line": [[500240, 4000100], [500240, 4000200]]}],
    "output": {"path": "lake.nc", "interval": 5, "series_interval": 0.5,
               "gauges": [{"name": "centre", "x": 500200, "y": 4000150},
                          {"name": "bank", "x": 500350, "y": 4000050}],
               "start_time": "2024-06-01T12:00:00Z",
               "rasters": ["max_depth", "hazard_class_aidr"]}
  })";
  const auto out = dir / "lake.nc";
  const auto r = run(cli + " run " + (dir / "scenario.json").string() + " --threads 2");
  INFO(r.output);
  REQUIRE(r.status == 0);
  // The conservative scheme keeps the terrain's volume: nothing is balanced.
  CHECK_THAT(r.output, Catch::Contains("water from terrain: geometric volume"));
  CHECK_THAT(r.output, !Catch::Contains("balanced particle volume"));
  CHECK_THAT(r.output, Catch::Contains("effect 'outflow lines'"));
  CHECK_THAT(r.output, Catch::Contains("effect 'west'"));
  // 10 m cells under 10 m particles, rough from cell to cell within one kernel support: the
  // default bed term sees the bed through the kernel and draws no warning.
  CHECK_THAT(r.output, Catch::Contains("effect 'bed slope (balanced)'"));
  CHECK_THAT(r.output, !Catch::Contains("narrower than 3 particle spacings"));
  REQUIRE(fs::exists(out));

  SECTION("GDAL reads the DEM's geotransform and CRS back from the maps") {
    const auto dem = open_raster((dir / "bed.tif").string());
    const auto maps = open_raster("NETCDF:\"" + out.string() + "\":max_depth");
    REQUIRE(dem != nullptr);
    REQUIRE(maps != nullptr);
    CHECK(maps->GetRasterXSize() == 40);
    CHECK(maps->GetRasterYSize() == 30);
    std::array<double, 6> expected{}, found{};
    REQUIRE(dem->GetGeoTransform(expected.data()) == CE_None);
    REQUIRE(maps->GetGeoTransform(found.data()) == CE_None);
    for (std::size_t k = 0; k < 6; ++k) {
      INFO("geotransform term " << k);
      CHECK(found[k] == Approx(expected[k]).epsilon(1e-9).margin(1e-12));
    }
    REQUIRE(maps->GetSpatialRef() != nullptr);
    CHECK(maps->GetSpatialRef()->IsSame(dem->GetSpatialRef()));
  }

  SECTION("the file holds the summary maps, the gauges and a closed volume balance") {
    const auto max_depth = read_variable(out, "max_depth");
    CHECK(max_depth.size() == 40 * 30);
    CHECK(*std::max_element(max_depth.begin(), max_depth.end()) > 1.0);
    const auto bed = read_variable(out, "bed_elevation");
    // The first cell is the south-west corner: the DEM's value at its centre.
    CHECK(bed.front() == Approx(300.0 + 0.002 * (195.0 * 195.0 + 145.0 * 145.0) + 0.05));
    for (const char* name : {"max_speed", "max_depth_speed", "max_hazard_rating", "hazard_class_uk",
                             "hazard_class_aidr"}) {
      INFO(name);
      CHECK(read_variable(out, name).size() == 40 * 30);
    }
    // The wet depth and the four default thresholds above it.
    CHECK(read_variable(out, "depth_threshold") == std::vector<double>{0.01, 0.1, 0.3, 0.5, 1.0});
    for (const char* name : {"arrival_time", "inundation_duration"}) {
      INFO(name);
      CHECK(read_variable(out, name).size() == 5 * 40 * 30);
    }

    const auto error = read_variable(out, "volume_error");
    const auto inflow = read_variable(out, "volume_inflow");
    const auto outflow = read_variable(out, "volume_outflow");
    const auto time = read_variable(out, "series_time");
    REQUIRE(error.size() >= 40);  // every 0.5 s of 20 s, and the output times
    CHECK(time.front() == 0.0);
    CHECK(time.back() == 20.0);
    for (std::size_t k = 0; k < error.size(); ++k) {
      INFO("sample " << k << " at t = " << time[k]);
      CHECK(std::abs(error[k]) < 1e-10);
    }
    CHECK(inflow.back() > 0.0);
    CHECK(outflow.back() > 0.0);

    const auto gauge_depth = read_variable(out, "gauge_depth");  // (series_time, gauge)
    REQUIRE(gauge_depth.size() == 2 * time.size());
    CHECK(gauge_depth[0] > 5.0);   // the lake's middle
    CHECK(gauge_depth[1] == 0.0);  // high on the bank
  }

  SECTION("xarray opens it, with the scene's date of t = 0") {
    const auto python = run(
        "/usr/bin/python3 -c 'import sys, numpy, xarray; ds = xarray.open_dataset(sys.argv[1]); "
        "assert ds[\"max_depth\"].dims == (\"y\", \"x\"); "
        "assert list(ds[\"gauge_name\"].values) == [\"centre\", \"bank\"]; "
        "assert ds[\"time\"].values[1] == numpy.datetime64(\"2024-06-01T12:00:05\"), "
        "ds[\"time\"].values' " +
        out.string());
    INFO(python.output);
    CHECK(python.status == 0);
  }

  SECTION("the file records where it came from") {
    int ncid = -1;
    REQUIRE(nc_open(out.c_str(), NC_NOWRITE, &ncid) == NC_NOERR);
    const auto text = [&](const char* name) {
      std::size_t n = 0;
      if (nc_inq_attlen(ncid, NC_GLOBAL, name, &n) != NC_NOERR) return std::string("(absent)");
      std::string value(n, '\0');
      REQUIRE(nc_get_att_text(ncid, NC_GLOBAL, name, value.data()) == NC_NOERR);
      return value;
    };
    CHECK(text("program") == std::string("swe-mps ") + SWEMPS_VERSION);
    CHECK_THAT(text("command_line"), Catch::StartsWith("swe-mps run "));
    CHECK(text("run_started").size() == 20);  // 2026-11-26T15:01:20Z
    CHECK_THAT(text("history"), Catch::EndsWith(text("command_line")));
    CHECK(text("time_coverage_start") == "2024-06-01T12:00:00Z");
    // The scene as read, with the defaults it took filled in.
    const auto scene = nlohmann::json::parse(text("scenario"));
    CHECK(scene["end_time"] == 20);
    CHECK(scene["numerics"]["scheme"] == "conservative");
    CHECK(scene["output"]["wet_depth"] == 0.01);
    CHECK(scene["output"]["land_use"] == "urban");
    CHECK(scene["water"][0]["spacing"] == 10);
    nc_close(ncid);
  }

  SECTION("the gauges as CSV hold the netCDF series") {
    const fs::path csv = dir / "lake_gauges.csv";
    REQUIRE(fs::exists(csv));
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    CHECK(header ==
          "time_s,centre_depth_m,centre_surface_elevation_m,centre_u_m_s,centre_v_m_s,"
          "bank_depth_m,bank_surface_elevation_m,bank_u_m_s,bank_v_m_s");
    const auto time = read_variable(out, "series_time");
    const std::vector<std::vector<double>> series{
        read_variable(out, "gauge_depth"), read_variable(out, "gauge_surface_elevation"),
        read_variable(out, "gauge_u"), read_variable(out, "gauge_v")};
    std::string line;
    std::size_t t = 0;
    for (; std::getline(in, line); ++t) {
      REQUIRE(t < time.size());
      std::vector<std::string> cells;
      std::stringstream row(line);
      for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
      if (!line.empty() && line.back() == ',') cells.emplace_back();
      REQUIRE(cells.size() == 9);
      INFO("row " << t << ": " << line);
      CHECK(std::stod(cells[0]) == Approx(time[t]).epsilon(1e-11));
      for (std::size_t g = 0; g < 2; ++g) {
        for (std::size_t k = 0; k < 4; ++k) {
          const double v = series[k][t * 2 + g];
          const std::string& cell = cells[1 + g * 4 + k];
          // Missing values (a dry gauge's surface and velocity) are empty cells.
          if (v == NC_FILL_DOUBLE) {
            CHECK(cell.empty());
          } else {
            REQUIRE_FALSE(cell.empty());
            CHECK(std::stod(cell) == Approx(v).epsilon(1e-11).margin(1e-300));
          }
        }
      }
    }
    CHECK(t == time.size());
    // The lake's centre is wet: its surface is bed plus depth, the bed there 302 m and the
    // bowl's curvature over the half cell to the nearest cell centres (0.002 x 25 m, twice).
    CHECK(series[1][0] - series[0][0] == Approx(302.05).margin(0.06));
  }

  SECTION("the scene's GeoTIFF maps are the netCDF maps") {
    const auto depth_tif = open_raster((dir / "lake_max_depth.tif").string());
    const auto class_tif = open_raster((dir / "lake_hazard_class_aidr.tif").string());
    REQUIRE(depth_tif != nullptr);
    REQUIRE(class_tif != nullptr);
    CHECK_FALSE(fs::exists(dir / "lake_max_speed.tif"));  // not asked for
    CHECK(std::string(depth_tif->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE")) == "COG");
    const auto dem = open_raster((dir / "bed.tif").string());
    std::array<double, 6> expected{}, found{};
    REQUIRE(dem->GetGeoTransform(expected.data()) == CE_None);
    REQUIRE(depth_tif->GetGeoTransform(found.data()) == CE_None);
    for (std::size_t k = 0; k < 6; ++k) CHECK(found[k] == Approx(expected[k]).margin(1e-6));
    CHECK(depth_tif->GetSpatialRef()->IsSame(dem->GetSpatialRef()));
    const auto nc_depth = read_variable(out, "max_depth");
    const auto nc_class = read_variable(out, "hazard_class_aidr");
    std::vector<float> tif_depth(40 * 30);
    std::vector<unsigned char> tif_class(40 * 30);
    REQUIRE(depth_tif->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 40, 30, tif_depth.data(), 40, 30,
                                                  GDT_Float32, 0, 0) == CE_None);
    REQUIRE(class_tif->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 40, 30, tif_class.data(), 40, 30,
                                                  GDT_Byte, 0, 0) == CE_None);
    std::size_t flooded = 0;
    for (std::size_t row = 0; row < 30; ++row) {
      for (std::size_t col = 0; col < 40; ++col) {
        // GeoTIFF rows run north to south, the netCDF grid's south to north.
        const std::size_t c = (29 - row) * 40 + col, p = row * 40 + col;
        CHECK(tif_depth[p] == static_cast<float>(nc_depth[c]));
        // Never wet (class 0) is nodata (0) in the raster too.
        CHECK(static_cast<double>(tif_class[p]) == nc_class[c]);
        if (nc_class[c] > 0.0) ++flooded;
      }
    }
    CHECK(flooded > 100);
  }

  SECTION("the log beside the result keeps the debug messages the terminal did not show") {
    std::ifstream in(dir / "lake.log");
    REQUIRE(in.good());
    const std::string log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK_THAT(log, Catch::Contains("[info] wrote " + out.string()));
    CHECK_THAT(log, Catch::Contains("[debug] wrote output at t = 20 s"));
    CHECK_THAT(r.output, !Catch::Contains("wrote output at t = 20 s"));
  }
  fs::remove_all(dir);
}

namespace {

// A CSV file of numbers under one header line; "nan" reads as NaN.
struct Table {
  std::string header;
  std::vector<std::vector<double>> rows;
};

Table read_csv(const fs::path& file) {
  std::ifstream in(file);
  REQUIRE(in.good());
  Table t;
  std::getline(in, t.header);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    t.rows.push_back(row);
  }
  return t;
}

// A tank 0.4 m long with 0.1 m of water in its first 0.1 m, as a vertical section on a 1 cm
// lattice: 100 fluid particles, 100 steps of 1 ms (the time step's cap).
const char* kTinyNsScene = R"({
  "end_time": 0.1,
  "model": "ns",
  "dimension": 2,
  "ns": {"spacing": 0.01},
  "domain": {"x_min": 0, "x_max": 0.4, "y_min": 0, "y_max": 0.1},
  "water": [{"rectangle": {"x_min": 0, "x_max": 0.1, "y_min": 0, "y_max": 0.1}, "depth": 0.1}],
  "walls": [{"polyline": [[0, 0], [0.4, 0]]}],
  "output": {"path": "tank.nc", "interval": 0.05, "series_interval": 0.01,
             "gauges": [{"name": "wall foot", "x": 0.02, "y": 0.05}]}
})";

}  // namespace

TEST_CASE("the point bed term warns of a bed finer than the particles", "[cli]") {
  const swemps::testing::TempDir scratch("cli-rough-bed-point");
  const fs::path& dir = scratch.path();
  write_bowl(dir / "bed.tif");
  std::ofstream(dir / "scenario.json") << R"({
    "end_time": 0.5,
    "numerics": {"bed_term": "point"},
    "bed": {"raster": "bed.tif", "crs": "EPSG:32616"},
    "water": [{"fill": {"rectangle": {"x_min": 500150, "x_max": 500250,
                                      "y_min": 4000100, "y_max": 4000200}},
               "surface_elevation": 306, "spacing": 10}],
    "output": {"path": "lake.nc"}
  })";
  const auto r = run(cli + " run " + (dir / "scenario.json").string() + " --threads 2");
  INFO(r.output);
  REQUIRE(r.status == 0);
  // 10 m cells under 10 m particles: rough from cell to cell within one kernel support.
  CHECK_THAT(r.output, Catch::Contains("the bed raster's cells (10 m) are narrower than 3 "
                                       "particle spacings (3 x 10 m)"));
  CHECK_THAT(r.output, Catch::Contains("effect 'bed slope'"));
}

TEST_CASE(
    "under the point bed term a raster three particle spacings fine or coarser draws no warning",
    "[cli]") {
  const swemps::testing::TempDir scratch("cli-smooth-bed");
  const fs::path& dir = scratch.path();
  write_bowl(dir / "bed.tif");
  std::ofstream(dir / "scenario.json") << R"({
    "end_time": 0.5,
    "numerics": {"bed_term": "point"},
    "bed": {"raster": "bed.tif", "crs": "EPSG:32616"},
    "water": [{"fill": {"rectangle": {"x_min": 500150, "x_max": 500250,
                                      "y_min": 4000100, "y_max": 4000200}},
               "surface_elevation": 306, "spacing": 3.3}],
    "output": {"path": "lake.nc"}
  })";
  const auto r = run(cli + " run " + (dir / "scenario.json").string() + " --threads 2");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("558 particles"));  // the scene it meant to run
  CHECK_THAT(r.output, !Catch::Contains("narrower than 3 particle spacings"));
}

TEST_CASE("a model ns scene writes column depths that hold its water, and a series table",
          "[cli]") {
  const swemps::testing::TempDir scratch("cli-ns");
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "scenario.json") << kTinyNsScene;
  const auto r = run(cli + " run " + (dir / "scenario.json").string() + " --threads 2");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("model ns (2D x-z section), 100 fluid"));
  CHECK_THAT(r.output, Catch::Contains("the scene's 1 walls are not used"));
  // The log names the numerics: the default (well-balanced) scheme's.
  CHECK_THAT(r.output, Catch::Contains("model ns numerics: kernel sheu-quartic at 2.1 l0, "
                                       "source mixed (gamma 0.05), gradient corrected-repulsive "
                                       "(repulsion under 0.9 l0)"));
  CHECK_THAT(r.output, Catch::Contains("wall pressures extrapolated, Courant 0.4"));
  CHECK_THAT(r.output, Catch::Contains("Poisson: conjugate gradients, multigrid "
                                       "preconditioner, tolerance 0.001"));
  CHECK_THAT(r.output, Catch::Contains("0 unconverged solves"));
  CHECK_THAT(r.output, Catch::Contains("time per phase: sort"));
  const auto nc = dir / "tank.nc";
  const auto csv = dir / "tank.series.csv";
  REQUIRE(fs::exists(nc));
  REQUIRE(fs::exists(csv));
  CHECK_FALSE(fs::exists(dir / "tank.nc.partial"));
  CHECK_FALSE(fs::exists(dir / "tank.series.csv.partial"));

  SECTION("the depth maps hold the particles' volume at every output time") {
    const auto depth = read_variable(nc, "depth");  // (time, y, x)
    const auto x = read_variable(nc, "x");
    const auto y = read_variable(nc, "y");
    const auto time = read_variable(nc, "time");
    REQUIRE(time == std::vector<double>{0.0, 0.05, 0.1});
    const std::size_t cells = x.size() * y.size();
    REQUIRE(depth.size() == time.size() * cells);
    const double dx = x[1] - x[0], dy = y[1] - y[0];
    // 100 particles of 1 cm x 1 cm in a section standing for the domain's 0.1 m width.
    const double volume0 = 100 * 0.01 * 0.01 * 0.1;
    for (std::size_t k = 0; k < time.size(); ++k) {
      double volume = 0.0;
      for (std::size_t c = 0; c < cells; ++c) {
        const double h = depth[k * cells + c];
        INFO("record " << k << ", cell " << c);
        REQUIRE(std::isfinite(h));
        REQUIRE(h >= 0.0);
        REQUIRE(h < 0.2);  // no fill values: the tank's water is 0.1 m deep
        volume += h * dx * dy;
      }
      // Every particle is counted in the cell it stands over, so only the maps' 32-bit
      // storage (7 significant digits) separates the two.
      INFO("t = " << time[k]);
      CHECK(volume == Approx(volume0).epsilon(1e-6));
    }
    // The water has left its box: depth downstream of it at the end, none at the start.
    CHECK(depth[10] == 0.0);            // x = 0.21 m, t = 0
    CHECK(depth[2 * cells + 5] > 0.0);  // x = 0.11 m, t = 0.1 s
    CHECK(read_variable(nc, "volume_in_domain").back() == Approx(volume0).epsilon(1e-12));
    int ncid = -1, varid = -1;
    REQUIRE(nc_open(nc.c_str(), NC_NOWRITE, &ncid) == NC_NOERR);
    CHECK(nc_inq_varid(ncid, "particle_count", &varid) != NC_NOERR);  // no SWE particles
    nc_close(ncid);
  }

  SECTION("the series table samples the run at the series interval") {
    const Table t = read_csv(csv);
    CHECK(t.header ==
          "time_s,time_step_s,front_m,fluid_particles,poisson_iterations,poisson_residual,"
          "unknowns,wall_foot_floor_pressure_pa");
    REQUIRE(t.rows.size() == 11);  // t = 0, 0.01, ..., 0.1
    double pressure_sum = 0.0;
    for (std::size_t k = 0; k < t.rows.size(); ++k) {
      const auto& row = t.rows[k];
      INFO("row " << k);
      REQUIRE(row.size() == 8);
      CHECK(row[0] == Approx(0.01 * static_cast<double>(k)).margin(1e-12));
      CHECK(row[1] > 0.0);
      CHECK(row[1] <= 1e-3);
      CHECK(row[3] == 100.0);
      if (k == 0) {
        CHECK(row[2] == Approx(0.1));  // the column's face: 10 particles from the wall
        CHECK(std::isnan(row[4]));     // no step yet
        CHECK(row[7] == 0.0);
        continue;
      }
      // The surge advances; a tip particle that loses its company (a droplet) may take the
      // front back by a fraction of a spacing.
      CHECK(row[2] >= t.rows[k - 1][2] - 0.005);
      CHECK(row[2] < 0.4);
      // A number: the step solved. Its count may be 0: with 100 unknowns the multigrid is one
      // level factorised whole, so its first update converges, which Eigen's conjugate
      // gradients count as no iteration.
      CHECK(row[4] >= 0.0);
      CHECK(row[5] <= 1e-3);
      // The submerged fluid particles: the walls' pressures are extrapolated, not unknowns.
      CHECK(row[6] >= 70.0);
      CHECK(row[6] <= 100.0);
      CHECK(row[7] >= 0.0);
      pressure_sum += row[7];
    }
    CHECK(t.rows.back()[2] > 0.15);  // the front ran out of the 0.1 m box
    // Near the back wall the column stands nearly full height until the rarefaction arrives
    // (at 0.1 m / sqrt(g h0) = 0.1 s), so the floor there carries about its weight: each
    // sample is noisy (MPS pressure, measured 0.3 to 1.8 times rho g h0), their mean is not.
    const double hydrostatic = 1000.0 * 9.81 * 0.1;
    CHECK(pressure_sum / 10.0 > 0.7 * hydrostatic);
    CHECK(pressure_sum / 10.0 < 1.2 * hydrostatic);
  }
  fs::remove_all(dir);
}

TEST_CASE("model ns refuses what its tank cannot hold, exiting 2", "[cli]") {
  const swemps::testing::TempDir scratch("cli-ns-bad");
  const fs::path& dir = scratch.path();
  std::string scene = kTinyNsScene;
  scene.insert(scene.rfind('}'), R"(, "friction": {"manning_n": 0.01})");
  std::ofstream(dir / "scenario.json") << scene;
  const auto r = run(cli + " run " + (dir / "scenario.json").string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("scenario error at /friction"));
  CHECK_THAT(r.output, Catch::Contains("not supported with model ns"));
  CHECK_FALSE(fs::exists(dir / "tank.nc.partial"));
  fs::remove_all(dir);
}

namespace {

// A 0.3 m x 0.04 m channel with a 0.06 m long, 0.04 m deep column at its upstream end: 24
// shallow-water particles, 96 Navier-Stokes particles.
const char* kTinyCompareScene = R"({
  "end_time": 0.1,
  "domain": {"x_min": 0, "x_max": 0.3, "y_min": 0, "y_max": 0.04},
  "water": [{"rectangle": {"x_min": 0, "x_max": 0.06, "y_min": 0, "y_max": 0.04},
             "depth": 0.04, "spacing": 0.01}],
  "walls": [{"polyline": [[0.3, 0], [0, 0], [0, 0.04], [0.3, 0.04]]}],
  "ns": {"spacing": 0.01},
  "output": {"path": "channel.nc", "interval": 0.05, "series_interval": 0.01,
             "grid": {"spacing": 0.02}}
})";

}  // namespace

TEST_CASE("compare runs both models and tabulates their fronts beside Ritter's", "[cli]") {
  const swemps::testing::TempDir scratch("cli-compare");
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "scenario.json") << kTinyCompareScene;
  const auto stem = dir / "out" / "dam";
  fs::create_directories(dir / "out");
  const auto r = run(cli + " compare " + (dir / "scenario.json").string() + " --threads 2 -o " +
                     stem.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("compare: Navier-Stokes 96 fluid"));
  CHECK_THAT(r.output, Catch::Contains("compare: shallow water 24 particles"));
  for (const char* suffix : {".swe.nc", ".ns.nc", ".ns.series.csv", ".fronts.csv"}) {
    INFO(suffix);
    CHECK(fs::exists(stem.string() + suffix));
  }
  CHECK_FALSE(fs::exists(dir / "channel.nc"));  // -o sets the stem of every file
  // Both maps on the scene's grid and times, so their depths can be set side by side.
  CHECK(read_variable(stem.string() + ".swe.nc", "time") ==
        read_variable(stem.string() + ".ns.nc", "time"));
  CHECK(read_variable(stem.string() + ".swe.nc", "x").size() == 15);
  CHECK(read_variable(stem.string() + ".ns.nc", "x").size() == 15);

  const Table t = read_csv(stem.string() + ".fronts.csv");
  CHECK(t.header == "time_s,swe_front_m,ns_front_m,ritter_front_m");
  REQUIRE(t.rows.size() == 11);
  const double c0 = std::sqrt(9.81 * 0.04);
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const auto& row = t.rows[k];
    INFO("row " << k);
    REQUIRE(row.size() == 4);
    CHECK(row[0] == Approx(0.01 * static_cast<double>(k)).margin(1e-12));
    CHECK(row[3] == Approx(0.06 + 2.0 * c0 * row[0]));
    // Neither model outruns the dry-bed front, and neither falls behind the dam.
    CHECK(row[1] <= row[3] + 1e-9);
    CHECK(row[2] <= row[3] + 1e-9);
    CHECK(row[1] >= 0.05);
    CHECK(row[2] >= 0.06 - 1e-9);
    if (k == 0) continue;
    // Fronts advance; half a spacing allows a tip particle's jitter.
    CHECK(row[1] >= t.rows[k - 1][1] - 0.005);
    CHECK(row[2] >= t.rows[k - 1][2] - 0.005);
  }
  // Both moved on by more than a spacing (the shallow-water front is the last particle deeper
  // than the 1 cm wet depth, a quarter of this column's depth, so it moves least).
  CHECK(t.rows.back()[1] > 0.065);
  CHECK(t.rows.back()[2] > 0.08);
  fs::remove_all(dir);
}

TEST_CASE("compare refuses a scene model ns cannot run, before running either", "[cli]") {
  const swemps::testing::TempDir scratch("cli-compare-bad");
  const fs::path& dir = scratch.path();
  std::string scene = kTinyCompareScene;
  scene.insert(scene.rfind('}'), R"(, "friction": {"manning_n": 0.01})");
  std::ofstream(dir / "scenario.json") << scene;
  const auto r = run(cli + " compare " + (dir / "scenario.json").string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("scenario error at /friction"));
  CHECK_FALSE(fs::exists(dir / "channel.swe.nc"));

  std::string no_block = kTinyCompareScene;
  no_block.erase(no_block.find(R"("ns": {"spacing": 0.01},)"), 25);
  std::ofstream(dir / "scenario.json") << no_block;
  const auto missing = run(cli + " compare " + (dir / "scenario.json").string());
  CHECK(missing.status == 2);
  CHECK_THAT(missing.output, Catch::Contains("scenario error at /ns: found nothing"));

  // The 3D run would take the numerics read for the scene's 2D section.
  std::string section = kTinyCompareScene;
  section.insert(section.rfind('}'), R"(, "dimension": 2)");
  std::ofstream(dir / "scenario.json") << section;
  const auto flat = run(cli + " compare " + (dir / "scenario.json").string());
  CHECK(flat.status == 2);
  CHECK_THAT(flat.output, Catch::Contains("scenario error at /dimension"));
  CHECK_FALSE(fs::exists(dir / "channel.swe.nc"));
  fs::remove_all(dir);
}
