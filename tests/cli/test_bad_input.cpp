// Bad input through the real swe-mps executable, one table row per mistake a user can make:
// broken JSON, wrong types, missing keys, bad spacings and times, crossing polygons, water
// outside the domain, rasters that are missing, unreadable, not rasters, too large, in
// longitude/latitude or with nodata where the water starts, output paths that cannot be
// written, and scenes too large for the machine's memory. Each must end the process normally
// (no signal, no core dump) with the status of its kind and exactly one line on stderr that
// names the problem and where it is (JSON path or file); the scene layer's own tests
// (tests/scenario) check the parsing in detail, these check what a user sees.
//
// With SWEMPS_BAD_INPUT_TABLE=FILE the test also writes the table of docs/robustness.md
// ("Bad input") there: each input with the message it printed, verbatim, and its status.

#include <fcntl.h>
#include <gdal_priv.h>
#include <grp.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace fs = std::filesystem;

namespace {

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;
using swemps::terrain::GriddedField;

constexpr int kInput = 2, kOutput = 4;  // swemps::cli::ExitStatus
constexpr uid_t kNobody = 65534;        // for the permission cases when the test runs as root
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Running the executable

struct Outcome {
  bool exited = false;  // ended by exit(), not by a signal
  int status = -1;      // its exit status
  int signal = 0;       // the signal that ended it, if one did
  bool core_dumped = false;
  std::string out, err;
};

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// How the child is started: with an address-space cap (bytes, 0: none), so that a scene that
// tried to allocate what it asks for would fail rather than be refused; as user nobody, so that
// a file without read permission is unreadable even when the tests run as root.
struct Launch {
  rlim_t address_space = 0;
  bool as_nobody = false;
};

// fork and exec rather than popen through a shell, so that the status says whether the
// process itself exited or was killed, and stdout and stderr are kept apart.
Outcome run_cli(const std::vector<std::string>& args, const fs::path& dir, const Launch& launch) {
  const fs::path out_file = dir / "stdout.txt", err_file = dir / "stderr.txt";
  std::vector<std::string> argv_text{SWEMPS_CLI};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec.
    const int out = open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0) _exit(125);
    if (launch.address_space > 0) {
      const rlimit cap{launch.address_space, launch.address_space};
      if (setrlimit(RLIMIT_AS, &cap) != 0) _exit(125);
    }
    if (launch.as_nobody &&
        (setgroups(0, nullptr) != 0 || setgid(kNobody) != 0 || setuid(kNobody) != 0)) {
      _exit(126);
    }
    execv(argv[0], argv.data());
    _exit(127);
  }
  int raw = 0;
  REQUIRE(waitpid(pid, &raw, 0) == pid);
  Outcome o;
  o.exited = WIFEXITED(raw);
  o.status = o.exited ? WEXITSTATUS(raw) : -1;
  o.signal = WIFSIGNALED(raw) ? WTERMSIG(raw) : 0;
  o.core_dumped = WIFSIGNALED(raw) && WCOREDUMP(raw);
  o.out = slurp(out_file);
  o.err = slurp(err_file);
  return o;
}

// A scene that runs: 0.5 m of water on [1, 4] x [1, 4] in a 10 m x 10 m domain. Each case
// breaks one thing in it, by a JSON merge patch (RFC 7386: null removes a key) or as text.
const json kGoodScene = json::parse(R"({
  "end_time": 0.05,
  "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 10},
  "water": [{"rectangle": {"x_min": 1, "x_max": 4, "y_min": 1, "y_max": 4}, "depth": 0.5,
             "spacing": 0.5}],
  "output": {"path": "out.nc", "grid": {"spacing": 1}}
})");

// ---------------------------------------------------------------------------------------------
// The files the broken scenes name, written into the test's folder

// 10 x 10 cells of 1 m over [0, 10] x [0, 10], in local metres (no CRS).
swemps::terrain::GridGeometry metre_grid() {
  return swemps::testing::grid_geometry(10, 10, 0.0, 10.0, 1.0, 1.0);
}

// A field of `value` with nodata (NaN) in the cells whose centres lie in [x0, x1] x [y0, y1].
GriddedField field_with_hole(double value, double x0, double x1, double y0, double y1) {
  const auto g = metre_grid();
  std::vector<double> v;
  for (std::size_t row = 0; row < g.rows; ++row) {
    for (std::size_t col = 0; col < g.columns; ++col) {
      const double x = g.cell_centre_x(col), y = g.cell_centre_y(row);
      v.push_back(x >= x0 && x <= x1 && y >= y0 && y <= y1 ? kNaN : value);
    }
  }
  return GriddedField(g, std::move(v));
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

// A GeoTIFF with values but no geotransform: GDAL opens it, but it lies nowhere.
void write_unplaced_geotiff(const fs::path& file) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  REQUIRE(driver != nullptr);
  GDALDatasetUniquePtr dataset(driver->Create(file.c_str(), 4, 4, 1, GDT_Float64, nullptr));
  REQUIRE(dataset);
  std::vector<double> zeros(16, 0.0);
  REQUIRE(dataset->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 4, 4, zeros.data(), 4, 4, GDT_Float64,
                                              0, 0, nullptr) == CE_None);
}

void write_fixtures(const fs::path& dir) {
  using swemps::io::write_geotiff;
  write_geotiff(GriddedField(metre_grid(), std::vector<double>(100, 0.0)), dir / "dem.tif");
  // Nodata under the water (which stands on [1, 4] x [1, 4]).
  write_geotiff(field_with_hole(0.0, 2.0, 3.0, 2.0, 3.0), dir / "dem_hole.tif");
  write_geotiff(field_with_hole(0.5, 0.0, 5.0, 0.0, 5.0), dir / "depth_hole.tif");
  write_geotiff(field_with_hole(0.03, 7.0, 8.0, 7.0, 8.0), dir / "manning_hole.tif");
  // Longitude/latitude: 0.001 degree cells west of Knoxville, in UTM zone 16.
  write_geotiff(GriddedField(swemps::testing::grid_geometry(10, 10, -90.0, 35.0, 1e-3, 1e-3),
                             std::vector<double>(100, 0.0), swemps::testing::wkt_of("EPSG:4326")),
                dir / "geographic.tif");
  write_unplaced_geotiff(dir / "unplaced.tif");
  // UTM zone 16N: 10 x 10 cells of 1 m; a building near it in longitude/latitude, as GeoJSON
  // without a "crs" member is.
  write_geotiff(GriddedField(swemps::testing::grid_geometry(10, 10, 500000.0, 4000010.0, 1.0, 1.0),
                             std::vector<double>(100, 0.0), swemps::testing::wkt_of("EPSG:32616")),
                dir / "utm.tif");
  write_text(dir / "lonlat.geojson",
             R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
                 "geometry": {"type": "Polygon", "coordinates": [[[-87.0, 36.13],
                 [-86.9999, 36.13], [-86.9999, 36.1301], [-87.0, 36.13]]]}}]})");
  // Land-use classes 1 and 2, and 3 in the easternmost column.
  std::string classes = "ncols 10\nnrows 10\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
  for (int row = 0; row < 10; ++row) classes += "1 1 1 1 1 2 2 2 2 3\n";
  write_text(dir / "land_use.asc", classes);
  fs::copy_file(dir / "dem.tif", dir / "truncated.tif");
  fs::resize_file(dir / "truncated.tif", fs::file_size(dir / "dem.tif") / 2);
  fs::copy_file(dir / "dem.tif", dir / "unreadable.tif");
  fs::permissions(dir / "unreadable.tif", fs::perms::none);
  write_text(dir / "unreadable.json", kGoodScene.dump());
  fs::permissions(dir / "unreadable.json", fs::perms::none);
  write_text(dir / "not_a_raster.tif", "elevation,0\n");
  fs::create_directory(dir / "a_folder.tif");
  // A header promising 9e10 cells: 2.9 TB to read, refused before a cell is read.
  write_text(dir / "huge.asc",
             "ncols 300000\nnrows 300000\nxllcorner 0\nyllcorner 0\ncellsize 1\n0 0 0\n");
  write_text(dir / "bad_hydrograph.csv", "time_s,discharge_m3_s\n0,10\n60,lots\n");
  json compare_scene = kGoodScene;
  compare_scene["ns"] = {{"spacing", 0.25}};
  write_text(dir / "compare.json", compare_scene.dump());
  write_text(dir / "study.json",
             R"({"scene": "scene.json", "sweep": {"spacing": [0.5, 0.25]}, "output": "s.csv",
                 "reference": {"ritter": {"dam_x": 4, "depth": 0.5, "reservoir_start_x": 1}}})");
  write_text(dir / "a_file", "not a folder\n");
  // Where user nobody may write: the permission cases run as nobody when the tests run as root.
  fs::create_directory(dir / "open");
  fs::permissions(dir / "open", fs::perms::all);
}

// ---------------------------------------------------------------------------------------------
// The table

std::string patched(const std::string& patch) {
  json scene = kGoodScene;
  scene.merge_patch(json::parse(patch));
  return scene.dump();
}

// The water body replaced by `water` (an object's JSON text).
std::string with_water(const std::string& water) {
  return patched(R"({"water": [)" + water + "]}");
}

std::string with_bed_raster(const std::string& raster, const std::string& extra = "") {
  return patched(R"({"bed": {"raster": ")" + raster + "\"" + extra + "}}");
}

enum class Needs { nothing, nobody, memory_cap };

struct BadInput {
  std::string input;  // what is wrong, as docs/robustness.md lists it
  std::string scene;  // the text of <dir>/scene.json
  int status;
  std::string where;              // the JSON path or file the message must name; {dir}: the folder
  std::string problem;            // words of the message that say what is wrong
  std::vector<std::string> args;  // after "<command> <dir>/<scene_file> -q"; {dir} as above
  std::string scene_file = "scene.json";  // what the command is given, in the folder
  Needs needs = Needs::nothing;
  std::string command = "run";

  BadInput& by(std::string other_command) {
    command = std::move(other_command);
    return *this;
  }

  BadInput& with(std::vector<std::string> more_args) {
    args = std::move(more_args);
    return *this;
  }
  BadInput& reading(std::string file) {
    scene_file = std::move(file);
    return *this;
  }
  BadInput& needing(Needs what) {
    needs = what;
    return *this;
  }
};

BadInput input_error(std::string input, std::string scene, std::string where, std::string problem) {
  return {std::move(input), std::move(scene), kInput, std::move(where), std::move(problem)};
}

// The good scene, written to a path the output check refuses.
BadInput output_error(std::string input, std::string path, std::string where, std::string problem) {
  BadInput c{std::move(input), kGoodScene.dump(), kOutput, std::move(where), std::move(problem)};
  return c.with({"-o", std::move(path)});
}

std::vector<BadInput> bad_inputs() {
  const std::string square = R"("rectangle": {"x_min": 1, "x_max": 4, "y_min": 1, "y_max": 4})";
  const std::string bow_tie = R"([[1, 1], [4, 4], [4, 1], [1, 4]])";
  return {
      // The scenario file itself
      input_error("scenario file missing", "", "{dir}/no_such_scene.json", "No such file")
          .reading("no_such_scene.json"),
      input_error("scenario file is a folder", "", "{dir}/open", "it is a folder").reading("open"),
      input_error("scenario file without read permission", "", "{dir}/unreadable.json",
                  "Permission denied")
          .reading("unreadable.json")
          .needing(Needs::nobody)
          .with({"-o", "{dir}/open/out.nc"}),
      input_error("empty scenario file", "", "at /:", "unexpected end of input"),
      // JSON syntax
      input_error("trailing comma", R"({"end_time": 1,})", "line 1, column 16",
                  "expected string literal"),
      input_error("comment", "{\"end_time\": 1 // seconds\n}", "line 1, column 16",
                  "invalid literal"),
      input_error("NaN as a number", R"({"end_time": NaN})", "line 1, column 14",
                  "invalid literal"),
      input_error("unclosed object", R"({"end_time": 1, "domain": {"x_min": 0)",
                  "line 1, column 37", "unexpected end of input"),
      input_error("a byte that is not UTF-8", "{\"name\": \"caf\xe9\"}",
                  "at /:", "invalid string: ill-formed UTF-8 byte"),
      input_error(
          "arrays nested 1,000 deep",
          R"({"end_time": 1, "x": )" + std::string(1000, '[') + std::string(1000, ']') + "}",
          "at /x/0/0/0", "nested more than 64 levels deep"),
      input_error("a line break inside a key (the message stays one line)",
                  with_water("{" + square + R"(, "depth": 0.5, "spacing": 0.5, "sp\nacing": 1})"),
                  "at /water/0/sp\\nacing:", "unknown key \"sp\\nacing\""),
      // Types and missing keys
      input_error("end_time as a string", patched(R"({"end_time": "60"})"),
                  "at /end_time:", "found a string \"60\""),
      input_error("water as an object", patched(R"({"water": {"depth": 1}})"),
                  "at /water:", "an array of water bodies"),
      input_error("point of three numbers",
                  with_water(R"({"polygon": [[1, 1], [4, 1], [4, 4, 0]], "depth": 0.5,
                                 "spacing": 0.5})"),
                  "at /water/0/polygon/2:", "an [x, y] pair of numbers"),
      input_error("end_time missing", patched(R"({"end_time": null})"),
                  "at /end_time:", "key missing"),
      input_error("spacing missing", with_water("{" + square + R"(, "depth": 0.5})"),
                  "at /water/0/spacing:", "key missing"),
      // Spacings
      input_error("negative spacing",
                  with_water("{" + square + R"(, "depth": 0.5, "spacing": -0.5})"),
                  "at /water/0/spacing:", "found -0.5, expected a number > 0"),
      input_error("zero spacing", with_water("{" + square + R"(, "depth": 0.5, "spacing": 0})"),
                  "at /water/0/spacing:", "found 0, expected a number > 0"),
      input_error("zero output grid spacing", patched(R"({"output": {"grid": {"spacing": 0}}})"),
                  "at /output/grid/spacing:", "expected a number > 0"),
      // Times (a run starts at t = 0)
      input_error("end_time zero", patched(R"({"end_time": 0})"),
                  "at /end_time:", "found 0, expected a number > 0"),
      input_error("end_time negative", patched(R"({"end_time": -10})"),
                  "at /end_time:", "found -10, expected a number > 0"),
      input_error("output time after end_time", patched(R"({"output": {"times": [0.01, 0.1]}})"),
                  "at /output/times/1:", "0.1"),
      input_error("output time before the start", patched(R"({"output": {"times": [-0.01]}})"),
                  "at /output/times/0:", "-0.01"),
      input_error("negative output interval", patched(R"({"output": {"interval": -1}})"),
                  "at /output/interval:", "expected a number > 0"),
      input_error("hydrograph going back in time",
                  patched(R"({"inflow": [{"line": [[0.5, 5], [0.5, 6]],
                                          "hydrograph": [[0, 1], [60, 2], [30, 0]]}]})"),
                  "at /inflow/0/hydrograph/2/0:", "a time greater than the previous point's 60"),
      // Shapes
      input_error("water polygon crossing itself (bow tie)",
                  with_water(R"({"polygon": )" + bow_tie + R"(, "depth": 0.5, "spacing": 0.5})"),
                  "at /water/0/polygon:", "intersecting"),
      input_error("lake outline crossing itself",
                  patched(R"({"bed": {"plane": {}}, "water": [{"fill": {"polygon": )" + bow_tie +
                          R"(}, "surface_elevation": 0.5, "spacing": 0.5}]})"),
                  "at /water/0/fill/polygon:", "intersecting"),
      input_error("polygon closed by repeating its first vertex",
                  with_water(R"({"polygon": [[1, 1], [4, 1], [4, 4], [1, 1]], "depth": 0.5,
                                 "spacing": 0.5})"),
                  "at /water/0/polygon/0:", "do not repeat the first vertex"),
      input_error("domain with x_min > x_max",
                  patched(R"({"domain": {"x_min": 10, "x_max": 0, "y_min": 0, "y_max": 10}})"),
                  "at /domain/x_max:", "a number > x_min"),
      input_error("water outside the domain",
                  with_water(R"({"rectangle": {"x_min": 8, "x_max": 12, "y_min": 1, "y_max": 4},
                                 "depth": 0.5, "spacing": 0.5})"),
                  "at /water/0/rectangle:", "outside the domain"),
      input_error("gauge outside the domain",
                  patched(R"({"output": {"gauges": [{"name": "bridge", "x": 20, "y": 5}]}})"),
                  "at /output/gauges/0:", "outside the domain"),
      // Rasters
      input_error("raster file missing", with_bed_raster("no_such_dem.tif"),
                  "at /bed/raster:", "'{dir}/no_such_dem.tif': file not found"),
      input_error("raster that is not a raster", with_bed_raster("not_a_raster.tif"),
                  "{dir}/not_a_raster.tif", "not recognized as a supported file format"),
      input_error("raster that is a folder", with_bed_raster("a_folder.tif"), "{dir}/a_folder.tif",
                  "is a folder, not a raster file"),
      input_error("raster without read permission", with_bed_raster("unreadable.tif"),
                  "{dir}/unreadable.tif", "cannot be read: Permission denied")
          .needing(Needs::nobody)
          .with({"-o", "{dir}/open/out.nc"}),
      input_error("raster cut short (truncated GeoTIFF)", with_bed_raster("truncated.tif"),
                  "{dir}/truncated.tif", "GDAL:"),
      input_error("raster without georeferencing", with_bed_raster("unplaced.tif"),
                  "{dir}/unplaced.tif", "has no georeferencing"),
      input_error("raster too large for memory (a header of 300000 x 300000 cells)",
                  with_bed_raster("huge.asc"), "{dir}/huge.asc", "holds 300000 x 300000 cells")
          .needing(Needs::memory_cap),
      input_error("longitude/latitude raster without a target CRS",
                  with_bed_raster("geographic.tif"), "at /bed/raster:",
                  "set bed.crs to a projected CRS in metres to warp it to, e.g. \"EPSG:32616\""),
      input_error("target CRS GDAL does not know",
                  with_bed_raster("dem.tif", R"(, "crs": "EPSG:99999")"),
                  "at /bed/raster:", "bed.crs = \"EPSG:99999\" is not a CRS GDAL understands"),
      input_error("building file in another CRS, without a transform",
                  patched(R"({"domain": {"x_min": 500000, "x_max": 500010, "y_min": 4000000,
                                         "y_max": 4000010},
                              "water": [{"rectangle": {"x_min": 500001, "x_max": 500004,
                                         "y_min": 4000001, "y_max": 4000004},
                                         "depth": 0.5, "spacing": 0.5}],
                              "bed": {"raster": "utm.tif"},
                              "buildings": {"file": "lonlat.geojson"}})"),
                  "at /buildings/file:", "set /buildings/reproject to true to transform it"),
      input_error("land-use class missing from the table",
                  patched(R"({"friction": {"land_use_raster": "land_use.asc",
                                           "land_use_manning_n": {"1": 0.03, "2": 0.02}}})"),
                  "at /friction/land_use_raster:", "the land-use class 3 in the cell centred at"),
      input_error("negative rain rate", patched(R"({"rain": {"rate_mm_h": -5}})"),
                  "at /rain/rate_mm_h:", "-5 mm/h"),
      input_error("rain series out of order",
                  patched(R"({"rain": {"rate_mm_h": [[0, 10], [600, 20], [300, 0]]}})"),
                  "at /rain/rate_mm_h/2/0:", "greater than the previous point's 600"),
      input_error("bed raster nodata under the water", with_bed_raster("dem_hole.tif"),
                  "at /domain:", "1 nodata cell of the bed raster inside the domain"),
      input_error("depth raster nodata where the water starts",
                  with_water("{" + square + R"(, "depth_raster": "depth_hole.tif",
                                               "spacing": 0.5})"),
                  "at /water/0:", "the depth raster is dry or nodata there"),
      input_error("Manning's n raster with nodata in the domain",
                  patched(R"({"friction": {"manning_n_raster": "manning_hole.tif"}})"),
                  "at /friction/manning_n_raster:", "1 nodata cell inside the domain"),
      input_error("hydrograph CSV with a word for a number",
                  patched(R"({"inflow": [{"line": [[0.5, 5], [0.5, 6]],
                                          "hydrograph_csv": "bad_hydrograph.csv"}]})"),
                  "at /inflow/0/hydrograph_csv:", "bad_hydrograph.csv:3"),
      // Output
      output_error("output under a regular file", "{dir}/a_file/out.nc", "'{dir}/a_file/out.nc'",
                   "'{dir}/a_file' is a file, not a folder"),
      output_error("output path that is a folder", "{dir}/open", "'{dir}/open'", "is a folder"),
      output_error("output in folders that do not exist", "{dir}/no/such/folder/out.nc",
                   "'{dir}/no/such/folder'", "does not exist"),
      output_error("output folder that refuses new files", "/proc/out.nc", "'/proc'",
                   "cannot create files in the folder"),
      output_error("empty output path", "", "''", "names no file"),
      output_error("compare output in a folder that does not exist", "{dir}/no/such/cmp",
                   "'{dir}/no/such/cmp.swe.nc'", "does not exist")
          .by("compare")
          .reading("compare.json"),
      output_error("empty compare output path", "", "''", "names no file")
          .by("compare")
          .reading("compare.json"),
      output_error("study table in a folder that does not exist", "{dir}/no/such/study.csv",
                   "'{dir}/no/such/study.csv'", "does not exist")
          .by("study")
          .reading("study.json"),
      // Memory
      input_error("water needing more memory than the machine has",
                  patched(R"({"domain": {"x_min": 0, "x_max": 1e6, "y_min": 0, "y_max": 1e6},
                              "water": [{"rectangle": {"x_min": 0, "x_max": 1e6,
                                                       "y_min": 0, "y_max": 1e6},
                                         "depth": 1, "spacing": 0.3}],
                              "output": {"grid": {"spacing": 1000}}})"),
                  "at /water/0/spacing:", "1.11e+13 particles")
          .needing(Needs::memory_cap),
      input_error("Navier-Stokes tank needing more memory than the machine has",
                  R"({"end_time": 0.1, "model": "ns", "ns": {"spacing": 0.001, "tank_height": 2},
                      "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 10},
                      "water": [{"rectangle": {"x_min": 0, "x_max": 5, "y_min": 0, "y_max": 10},
                                 "depth": 1}],
                      "output": {"path": "out.nc", "grid": {"spacing": 0.1}}})",
                  "at /ns/spacing:", "fluid and")
          .needing(Needs::memory_cap),
  };
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// A markdown table cell: pipes escaped, so that a message holding one keeps its column.
std::string cell(const std::string& text) { return replaced(text, "|", "\\|"); }

// Code in a table cell, verbatim. Double backticks, because GDAL quotes names `like this'.
std::string code(const std::string& text) { return "`` " + cell(text) + " ``"; }

}  // namespace

TEST_CASE("the scene the bad inputs break runs", "[cli][bad-input]") {
  const swemps::testing::TempDir dir("bad-input");
  write_text(dir.path() / "scene.json", kGoodScene.dump());
  const Outcome o = run_cli({"run", (dir.path() / "scene.json").string(), "-q"}, dir.path(), {});
  INFO(o.err);
  CHECK(o.status == 0);
  CHECK(o.err.empty());
}

TEST_CASE("every bad input is refused with one line naming it and the status of its kind",
          "[cli][bad-input]") {
  const swemps::testing::TempDir dir("bad-input");
  const std::string folder = dir.path().string();
  write_fixtures(dir.path());
  const auto cases = bad_inputs();
  REQUIRE(cases.size() >= 30);

  std::ostringstream table;
  table << "| Bad input | What swe-mps prints on stderr | Exit status |\n|---|---|---|\n";
  std::size_t skipped = 0;
  for (const BadInput& c : cases) {
    INFO("case: " << c.input);
    Launch launch;
    if (c.needs == Needs::memory_cap) {
      // Far below what either scene asks for, far above what refusing it takes.
      launch.address_space = rlim_t{2} << 30;
    }
    if (c.needs == Needs::nobody && geteuid() == 0) launch.as_nobody = true;
    write_text(dir.path() / "scene.json", c.scene);
    std::vector<std::string> args{c.command, folder + "/" + c.scene_file, "-q"};
    for (const auto& a : c.args) args.push_back(replaced(a, "{dir}", folder));
    const Outcome o = run_cli(args, dir.path(), launch);
    if (o.status == 126) {
      // Root that may not become nobody (a container without the capability): the permission
      // bits cannot be tested.
      WARN("skipped, cannot drop to user nobody: " << c.input);
      ++skipped;
      continue;
    }
    INFO("status " << o.status << ", stderr:\n" << o.err);
    CHECK(o.exited);
    CHECK(o.signal == 0);
    CHECK_FALSE(o.core_dumped);
    CHECK(o.status == c.status);
    CHECK(o.out.empty());
    // One line: "swe-mps: ..." and its newline, nothing else (no GDAL or HDF5 chatter).
    CHECK_THAT(o.err, StartsWith("swe-mps: "));
    CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
    CHECK(o.err.back() == '\n');
    CHECK_THAT(o.err, Contains(replaced(c.where, "{dir}", folder)));
    CHECK_THAT(o.err, Contains(replaced(c.problem, "{dir}", folder)));
    const std::string message = replaced(o.err.substr(0, o.err.size() - 1), folder, "<dir>");
    table << "| " << cell(c.input) << " | " << code(message) << " | " << o.status << " |\n";
  }
  if (const char* table_file = std::getenv("SWEMPS_BAD_INPUT_TABLE")) {
    REQUIRE(skipped == 0);
    std::ofstream(table_file) << table.str();
  }
}
