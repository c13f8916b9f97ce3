#include "swemps/cli/study_reference.hpp"

#include <limits>
#include <stdexcept>

#include "swemps/io/comparison_inputs.hpp"
#include "swemps/io/ensemble_products.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/build.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A result's map as a north-up field: the netCDF grid's rows may run south to north.
terrain::GriddedField north_up(const io::Grid& grid, const std::vector<double>& values,
                               const std::string& name) {
  terrain::GridGeometry g;
  g.columns = grid.nx;
  g.rows = grid.ny;
  g.cell_width = std::abs(grid.dx);
  g.cell_height = std::abs(grid.dy);
  g.x_left = grid.x0 - 0.5 * grid.dx;
  const double last_y = grid.y0 + static_cast<double>(grid.ny - 1) * grid.dy;
  g.y_top = std::max(grid.y0, last_y) + 0.5 * g.cell_height;
  std::vector<double> rows(values.size());
  for (std::size_t j = 0; j < grid.ny; ++j) {
    const std::size_t row = grid.dy > 0.0 ? grid.ny - 1 - j : j;
    for (std::size_t i = 0; i < grid.nx; ++i) rows[row * grid.nx + i] = values[j * grid.nx + i];
  }
  return terrain::GriddedField(g, std::move(rows), grid.crs_wkt, name);
}

scenario::ScenarioError reference_error(const std::string& key, const std::string& found,
                                        const std::string& expected) {
  return scenario::ScenarioError("/reference/" + key, found, expected, "study");
}

}  // namespace

ReferenceMaps read_reference_maps(const study::MapReference& reference,
                                  const scenario::Scenario& scene) {
  ReferenceMaps maps;
  // The scene's CRS is that of its rasters: read them as a run would.
  const scenario::Terrain terrain = scenario::read_terrain(scene);
  io::RasterRequest request;
  request.path = reference.max_depth;
  request.target_crs = terrain.crs_wkt;
  request.purpose = "reference maximum depth";
  request.crs_setting = "the scene's CRS";
  try {
    maps.max_depth = std::make_shared<const terrain::GriddedField>(io::read_raster(request));
  } catch (const std::exception& e) {
    throw reference_error("max_depth", e.what(), "a raster of the maximum depth GDAL can read");
  }
  if (reference.gauge_table.empty()) return maps;
  io::NumericTable table;
  try {
    table = io::read_numeric_csv(reference.gauge_table);
    const auto& time = table.column("time_s");
    for (const auto& [gauge, column] : reference.gauge_columns) {
      const bool known = std::any_of(scene.output.gauges.begin(), scene.output.gauges.end(),
                                     [&](const auto& g) { return g.name == gauge; });
      if (!known) {
        throw reference_error("gauges/columns/" + gauge, "a gauge the scene does not have",
                              "the name of one of the scene's gauges");
      }
      maps.gauges.push_back({gauge, time, table.column(column)});
    }
  } catch (const scenario::ScenarioError&) {
    throw;
  } catch (const std::exception& e) {
    throw reference_error("gauges/table", e.what(),
                          "a CSV table with a time_s column and the columns named");
  }
  return maps;
}

ReferenceMaps reference_from_result(const std::filesystem::path& result) {
  const io::MemberResult run = io::read_member_result(result);
  ReferenceMaps maps;
  maps.max_depth = std::make_shared<const terrain::GriddedField>(
      north_up(run.grid, run.max_depth, "maximum depth"));
  const io::GaugeSeries series = io::read_gauge_series(result);
  for (std::size_t g = 0; g < series.names.size(); ++g) {
    maps.gauges.push_back({series.names[g], series.time_s, series.depth_m[g]});
  }
  return maps;
}

MapMeasures measure_result(const std::filesystem::path& result, const ReferenceMaps& reference,
                           double wet_depth_m) {
  const io::MemberResult run = io::read_member_result(result);
  const terrain::GriddedField map = north_up(run.grid, run.max_depth, "maximum depth");
  MapMeasures m;
  const std::vector<double> on_cells = study::area_average(*reference.max_depth, map.geometry());
  m.max_depth = study::compare_max_depth(map.values(), on_cells, wet_depth_m);
  if (reference.gauges.empty()) return m;
  const io::GaugeSeries series = io::read_gauge_series(result);
  for (const auto& gauge : reference.gauges) {
    GaugePeakError e{gauge.name, kNaN, kNaN, kNaN};
    const study::SeriesPeak expected = study::series_peak(gauge.time_s, gauge.depth_m);
    for (std::size_t g = 0; g < series.names.size(); ++g) {
      if (series.names[g] != gauge.name) continue;
      const study::SeriesPeak peak = study::series_peak(series.time_s, series.depth_m[g]);
      e.peak_m = peak.value;
      e.depth_error_m = peak.value - expected.value;
      e.time_error_s = peak.time_s - expected.time_s;
    }
    m.gauges.push_back(e);
  }
  return m;
}

}  // namespace swemps::cli
