// Studies measured by maps: a reference map averaged over the output cells, the figures of a
// maximum-depth comparison and of gauge peaks, the study file's map and finest-run
// references, and `swe-mps study` end to end against a reference that is one of its own runs
// (every figure must then be exactly that of a perfect match).

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "../support/csv_table.hpp"
#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/scenario/study_file.hpp"
#include "swemps/study/map_comparison.hpp"

namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using swemps::terrain::GriddedField;
using swemps::testing::grid_geometry;
using swemps::testing::number;
using swemps::testing::read_csv;
using namespace swemps::study;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

swemps::study::Study parse(const std::string& text) {
  return swemps::scenario::parse_study(text, "/studies", "/studies/default.csv");
}

}  // namespace

TEST_CASE("a reference map is averaged over the output cells by shared area", "[study][maps]") {
  // 10 m cells, value = column + 10 row, under 20 m cells: each is the mean of a 2 x 2 block.
  std::vector<double> values;
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) values.push_back(col + 10.0 * row);
  }
  const GriddedField fine(grid_geometry(4, 4, 0.0, 40.0, 10.0, 10.0), values);
  const auto blocks = area_average(fine, grid_geometry(2, 2, 0.0, 40.0, 20.0, 20.0));
  REQUIRE(blocks.size() == 4);
  CHECK(blocks[0] == Approx(0.25 * (0 + 1 + 10 + 11)));
  CHECK(blocks[1] == Approx(0.25 * (2 + 3 + 12 + 13)));
  CHECK(blocks[3] == Approx(0.25 * (22 + 23 + 32 + 33)));

  SECTION("cells offset from the reference's weigh each by the area it shares") {
    // One 10 m cell centred on the corner of four: a quarter of each.
    const auto offset = area_average(fine, grid_geometry(1, 1, 5.0, 35.0, 10.0, 10.0));
    CHECK(offset[0] == Approx(0.25 * (0 + 1 + 10 + 11)));
    // A 15 m cell: 10 x 10 of cell (0, 0), 5 x 10 of (1, 0), 10 x 5 of (0, 1), 5 x 5 of (1, 1).
    const auto wide = area_average(fine, grid_geometry(1, 1, 0.0, 40.0, 15.0, 15.0));
    CHECK(wide[0] == Approx((100.0 * 0 + 50.0 * 1 + 50.0 * 10 + 25.0 * 11) / 225.0));
  }
  SECTION("no data and negative values are dry; a cell mostly off the reference is not compared") {
    std::vector<double> holes = values;
    holes[0] = kNaN;  // a grid model writes no depth where no water came
    holes[1] = -1.0;
    const GriddedField with_holes(fine.geometry(), holes);
    CHECK(area_average(with_holes, grid_geometry(1, 1, 0.0, 40.0, 20.0, 20.0))[0] ==
          Approx(0.25 * (10 + 11)));
    // Half on the reference: the mean of its covered half. Less than half: NaN.
    const auto half = area_average(fine, grid_geometry(1, 1, 30.0, 40.0, 20.0, 10.0));
    CHECK(half[0] == Approx(3.0));
    const auto off = area_average(fine, grid_geometry(1, 1, 35.0, 40.0, 20.0, 10.0));
    CHECK(std::isnan(off[0]));
  }
}

TEST_CASE("maximum depths are compared over the cells wet in either map", "[study][maps]") {
  //                         both wet  run only  ref only  dry both  not on the ref
  const std::vector<double> run{1.0, 2.0, 0.5, 0.0, 0.01, 3.0};
  const std::vector<double> ref{1.2, 1.0, 0.0, 0.3, 0.02, kNaN};
  const MaxDepthComparison c = compare_max_depth(run, ref, 0.05);
  REQUIRE(c.compared_cells == 4);
  // Differences -0.2, +1.0, +0.5, -0.3.
  CHECK(c.mean_abs_difference_m == Approx((0.2 + 1.0 + 0.5 + 0.3) / 4));
  CHECK(c.bias_m == Approx((-0.2 + 1.0 + 0.5 - 0.3) / 4));
  CHECK(c.within_half_metre == Approx(3.0 / 4));
  CHECK(c.critical_success_index == Approx(2.0 / 4));
  // NaN in the run is dry.
  const MaxDepthComparison dry =
      compare_max_depth(std::vector<double>{kNaN}, std::vector<double>{1.0}, 0.05);
  CHECK(dry.bias_m == Approx(-1.0));
  CHECK(dry.critical_success_index == 0.0);
  // Nothing wet: nothing to say.
  const MaxDepthComparison none =
      compare_max_depth(std::vector<double>{0.0}, std::vector<double>{0.0}, 0.05);
  CHECK(none.compared_cells == 0);
  CHECK(std::isnan(none.mean_abs_difference_m));
}

TEST_CASE("a series' peak is its highest value at the first time reached", "[study][maps]") {
  const std::vector<double> t{0, 10, 20, 30, 40};
  const SeriesPeak p = series_peak(t, std::vector<double>{kNaN, 1.0, 2.0, 2.0, 1.5});
  CHECK(p.value == 2.0);
  CHECK(p.time_s == 20.0);
  CHECK(std::isnan(series_peak(t, std::vector<double>(5, kNaN)).value));
}

TEST_CASE("a study file names a reference map, gauge columns, or its finest run", "[study][maps]") {
  const auto map = parse(R"({"scene": "scene.json",
      "reference": {"max_depth": "ref/max.tif",
                    "gauges": {"table": "ref/gauges.csv", "columns": {"a": "a_depth_m"}}},
      "sweep": {"spacing": [30, 15]}, "wet_depth": 0.05})");
  const auto& m = std::get<MapReference>(map.reference);
  CHECK(m.max_depth == "/studies/ref/max.tif");
  CHECK(m.gauge_table == "/studies/ref/gauges.csv");
  REQUIRE(m.gauge_columns.size() == 1);
  CHECK(m.gauge_columns[0].gauge == "a");
  CHECK(m.gauge_columns[0].column == "a_depth_m");
  CHECK(map.wet_depth_m == 0.05);
  // A dataset name keeps its driver and variable; its file is taken from the study's folder.
  const auto wrapped = parse(R"({"scene": "s.json",
      "reference": {"max_depth": "NETCDF:\"run.nc\":max_depth"}, "sweep": {}})");
  CHECK(std::get<MapReference>(wrapped.reference).max_depth ==
        "NETCDF:\"/studies/run.nc\":max_depth");
  CHECK_FALSE(wrapped.wet_depth_m);  // the scene's own
  const auto finest = parse(
      R"({"scene": "s.json", "reference": {"finest_run": {}}, "sweep": {"spacing": [2, 1]}})");
  CHECK(std::holds_alternative<FinestRunReference>(finest.reference));

  struct Refused {
    std::string text, path;
  };
  const std::string sweep = R"(, "sweep": {}})";
  for (const Refused& c : std::vector<Refused>{
           {R"({"scene": "s.json", "reference": {})" + sweep, "/reference"},
           {R"({"scene": "s.json", "reference": {"finest_run": {}, "max_depth": "m.tif"})" + sweep,
            "/reference"},
           {R"({"scene": "s.json", "reference": {"finest_run": {}, "gauges": {}})" + sweep,
            "/reference/gauges"},
           {R"({"scene": "s.json", "reference": {"finest_run": {"x": 1}})" + sweep,
            "/reference/finest_run/x"},
           {R"({"scene": "s.json", "reference": {"max_depth": ""})" + sweep,
            "/reference/max_depth"},
           {R"({"scene": "s.json", "reference": {"max_depth": "m.tif",
                "gauges": {"table": "g.csv", "columns": {}}})" +
                sweep,
            "/reference/gauges/columns"},
           {R"({"scene": "s.json", "reference": {"max_depth": "m.tif",
                "gauges": {"table": "g.csv", "columns": {"a": 3}}})" +
                sweep,
            "/reference/gauges/columns/a"},
           {R"({"scene": "s.json", "reference": {"max_depth": "m.tif"},
                "profile_spacing_ratio": 4, "sweep": {}})",
            "/profile_spacing_ratio"},
           {R"({"scene": "s.json", "reference": {"ritter": {"dam_x": 1, "depth": 1}},
                "wet_depth": 0.05, "sweep": {}})",
            "/wet_depth"},
           {R"({"scene": "s.json", "reference": {"finest_run": {}}, "wet_depth": 0,
                "sweep": {}})",
            "/wet_depth"},
       }) {
    INFO(c.text);
    try {
      parse(c.text);
      FAIL("accepted");
    } catch (const swemps::scenario::ScenarioError& e) {
      CHECK(e.json_path() == c.path);
      CHECK_THAT(std::string(e.what()), Contains("study error at " + c.path));
    }
  }
}

TEST_CASE("swe-mps study measures its runs against a reference map and against its finest run",
          "[study][maps]") {
  const swemps::testing::TempDir scratch("study-maps");
  const fs::path& dir = scratch.path();
  // A tilted valley floor (10 m cells, UTM) with a lake released down it.
  std::vector<double> z;
  const auto g = grid_geometry(30, 12, 500000.0, 4000120.0, 10.0, 10.0);
  for (std::size_t row = 0; row < g.rows; ++row) {
    for (std::size_t col = 0; col < g.columns; ++col) {
      const double y = g.cell_centre_y(row) - 4000060.0;
      z.push_back(100.0 - 0.01 * g.cell_centre_x(col) + 500000.0 * 0.01 + 0.002 * y * y);
    }
  }
  swemps::io::write_geotiff(
      GriddedField(g, z, swemps::testing::wkt_of("EPSG:32616"), "bed elevation"), dir / "bed.tif");
  std::ofstream(dir / "scene.json") << R"({
    "end_time": 30,
    "bed": {"raster": "bed.tif"},
    "water": [{"fill": {"polygon": [[500010, 4000030], [500080, 4000030], [500080, 4000090],
                                    [500010, 4000090]]},
               "surface_elevation": 100.5, "spacing": 5}],
    "output": {"path": "scene.nc", "interval": 10, "series_interval": 1,
               "gauges": [{"name": "down", "x": 500150, "y": 4000060}]}
  })";
  const std::string cli = SWEMPS_CLI;
  // The reference: one run of the scene at 5 m, its maximum depth read by GDAL from its netCDF
  // file and its gauge from the table export writes.
  const auto reference_run = swemps::testing::run_command(
      cli + " run " + (dir / "scene.json").string() + " -q -o " + (dir / "ref.nc").string());
  INFO(reference_run.output);
  REQUIRE(reference_run.status == 0);
  REQUIRE(fs::exists(dir / "ref_gauges.csv"));

  std::ofstream(dir / "map.json") << R"({"scene": "scene.json",
      "reference": {"max_depth": "NETCDF:\"ref.nc\":max_depth",
                    "gauges": {"table": "ref_gauges.csv", "columns": {"down": "down_depth_m"}}},
      "sweep": {"spacing": [10, 5]}, "jobs": 1})";
  const auto map_study =
      swemps::testing::run_command(cli + " study " + (dir / "map.json").string() + " --threads 1");
  INFO(map_study.output);
  REQUIRE(map_study.status == 0);
  CHECK_THAT(map_study.output, Contains("Pareto front, wall time against max depth MAD"));
  const auto rows = read_csv(dir / "map.csv");
  REQUIRE(rows.size() == 2);
  for (const auto& row : rows) {
    REQUIRE(row.at("status") == "ok");
    CHECK(fs::exists(row.at("result")));
    CHECK(number(row, "compared_cells") > 10);
  }
  // The 5 m run is the reference run again, bit for bit: a perfect match, to the round-off
  // of averaging a map over its own cells.
  const auto& same = rows[1];
  CHECK(number(same, "spacing_m") == 5.0);
  CHECK(number(same, "max_depth_mad_m") < 1e-12);
  CHECK(std::abs(number(same, "max_depth_bias_m")) < 1e-12);
  CHECK(number(same, "within_0.5m") == 1.0);
  CHECK(number(same, "wet_csi") == 1.0);
  // The gauge table holds 12 digits.
  CHECK(std::abs(number(same, "down_peak_error_m")) < 1e-9);
  CHECK(number(same, "down_peak_time_error_s") == Approx(0.0).margin(1e-9));
  CHECK(number(same, "down_peak_m") > 0.05);
  // The 10 m run differs.
  const auto& coarse = rows[0];
  CHECK(number(coarse, "max_depth_mad_m") > 1e-3);
  CHECK(number(coarse, "wet_csi") <= 1.0);

  // The same runs with the finest as the reference: the same figures.
  std::ofstream(dir / "finest.json") << R"({"scene": "scene.json",
      "reference": {"finest_run": {}}, "sweep": {"spacing": [10, 5]}, "jobs": 1})";
  const auto finest_study = swemps::testing::run_command(
      cli + " study " + (dir / "finest.json").string() + " --threads 1");
  INFO(finest_study.output);
  REQUIRE(finest_study.status == 0);
  CHECK_THAT(finest_study.output, Contains("the reference is run 2 (spacing 5 m)"));
  const auto finest_rows = read_csv(dir / "finest.csv");
  REQUIRE(finest_rows.size() == 2);
  for (const char* column : {"max_depth_mad_m", "max_depth_bias_m", "within_0.5m", "wet_csi"}) {
    INFO(column);
    CHECK(number(finest_rows[0], column) == Approx(number(coarse, column)).margin(1e-12));
    CHECK(number(finest_rows[1], column) == Approx(number(same, column)).margin(1e-12));
  }
  CHECK(number(finest_rows[0], "down_peak_error_m") ==
        Approx(number(coarse, "down_peak_error_m")).margin(1e-9));

  // A reference that cannot be read stops the study before any run, at its key.
  std::ofstream(dir / "broken.json") << R"({"scene": "scene.json",
      "reference": {"max_depth": "nowhere.tif"}, "sweep": {"spacing": [10]}})";
  const auto broken =
      swemps::testing::run_command(cli + " study " + (dir / "broken.json").string());
  CHECK(broken.status == 2);
  CHECK_THAT(broken.output, Contains("study error at /reference/max_depth"));
  CHECK_THAT(broken.output, Contains("nowhere.tif"));
  CHECK_FALSE(fs::exists(dir / "broken-runs" / "run-0.nc"));
}
