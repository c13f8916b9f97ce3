// Rain from maps in a scene: a static map of the rate, a netCDF series of maps (its times in
// seconds of the run, its units converted), loss parameters as rasters, Green-Ampt soil, and
// the one-line errors for maps that cannot be used.

#include <netcdf.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/effect.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
using swemps::scenario::ScenarioError;

namespace {

constexpr double kMmH = swemps::hydrology::kMetresPerSecondPerMmPerHour;

// A 20 m x 10 m domain without water; the rain makes its own particles.
json rain_scene(const json& rain) {
  json s = json::parse(R"({
    "name": "rain-maps-test", "end_time": 10,
    "domain": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 10},
    "output": {"path": "out.nc"}
  })");
  s["rain"] = rain;
  return s;
}

swemps::scenario::Scenario parse(const json& scene, const std::filesystem::path& base) {
  return swemps::scenario::parse(scene.dump(), base, "rain-maps-test");
}

swemps::scenario::BuiltScene build(const json& scene, const std::filesystem::path& base) {
  return swemps::scenario::build(parse(scene, base));
}

std::string refusal(const json& scene, const std::filesystem::path& base) {
  try {
    build(scene, base);
  } catch (const ScenarioError& e) {
    return e.json_path() + " | " + e.what();
  }
  return "accepted";
}

const swemps::hydrology::Rain& rain_of(const swemps::scenario::BuiltScene& built) {
  for (const auto& effect : built.simulation.effects()) {
    if (const auto* rain = dynamic_cast<const swemps::hydrology::Rain*>(effect.get())) {
      return *rain;
    }
  }
  throw std::logic_error("no rain");
}

// Two 10 m cells side by side over the domain, no CRS.
void write_two_cells(const std::filesystem::path& file, double west, double east) {
  swemps::terrain::GridGeometry g{2, 1, 0.0, 10.0, 10.0, 10.0};
  swemps::io::write_geotiff(swemps::terrain::GriddedField(g, {west, east}), file);
}

// A netCDF series over (time, y, x) of the same two columns, in two rows of 5 m (GDAL needs two
// coordinates on an axis to know its spacing): `values` per time, west then east.
void write_series(const std::filesystem::path& file, const std::string& time_units,
                  const std::vector<double>& times, const std::string& value_units,
                  const std::vector<std::array<double, 2>>& values) {
  int nc = 0, t_dim = 0, y_dim = 0, x_dim = 0, t_var = 0, y_var = 0, x_var = 0, v_var = 0;
  REQUIRE(nc_create(file.c_str(), NC_CLOBBER | NC_NETCDF4, &nc) == NC_NOERR);
  nc_def_dim(nc, "time", times.size(), &t_dim);
  nc_def_dim(nc, "y", 2, &y_dim);
  nc_def_dim(nc, "x", 2, &x_dim);
  nc_def_var(nc, "time", NC_DOUBLE, 1, &t_dim, &t_var);
  nc_put_att_text(nc, t_var, "units", time_units.size(), time_units.c_str());
  nc_def_var(nc, "y", NC_DOUBLE, 1, &y_dim, &y_var);
  nc_def_var(nc, "x", NC_DOUBLE, 1, &x_dim, &x_var);
  for (const int var : {x_var, y_var}) nc_put_att_text(nc, var, "units", 1, "m");
  nc_put_att_text(nc, x_var, "standard_name", 23, "projection_x_coordinate");
  nc_put_att_text(nc, y_var, "standard_name", 23, "projection_y_coordinate");
  const int dims[3] = {t_dim, y_dim, x_dim};
  nc_def_var(nc, "rainfall_rate", NC_DOUBLE, 3, dims, &v_var);
  if (!value_units.empty()) {
    nc_put_att_text(nc, v_var, "units", value_units.size(), value_units.c_str());
  }
  nc_enddef(nc);
  nc_put_var_double(nc, t_var, times.data());
  const double y[2] = {2.5, 7.5}, x[2] = {5.0, 15.0};
  nc_put_var_double(nc, y_var, y);
  nc_put_var_double(nc, x_var, x);
  std::vector<double> flat;
  for (const auto& v : values) {
    for (int row = 0; row < 2; ++row) flat.insert(flat.end(), v.begin(), v.end());
  }
  nc_put_var_double(nc, v_var, flat.data());
  REQUIRE(nc_close(nc) == NC_NOERR);
}

}  // namespace

TEST_CASE("rain from a static map of the rate", "[scenario][rain]") {
  swemps::testing::TempDir dir("rain-map");
  write_two_cells(dir.path() / "rate.tif", 36.0, 72.0);
  const auto built =
      build(rain_scene(json::parse(R"({"rate_raster": "rate.tif", "spacing": 1})")), dir.path());
  const auto& rain = rain_of(built);
  // 100 m^2 at 36 mm/h and 100 at 72 over 100 s.
  CHECK(rain.volume_due(0.0, 100.0) == Approx((36.0 + 72.0) / 36.0 * 0.1).epsilon(1e-12));
  CHECK(rain.rate().peak_m_s() == Approx(72.0 * kMmH));

  write_two_cells(dir.path() / "holed.tif", 36.0, -5.0);
  CHECK_THAT(
      refusal(rain_scene(json::parse(R"({"rate_raster": "holed.tif", "spacing": 1})")), dir.path()),
      Contains("/rain | ") && Contains("-5") && Contains("mm/h"));
  CHECK_THAT(
      refusal(rain_scene(json::parse(R"({"rate_raster": "none.tif", "spacing": 1})")), dir.path()),
      Contains("/rain/rate_raster | ") && Contains("file not found"));
  CHECK_THAT(
      refusal(
          rain_scene(json::parse(R"({"rate_raster": "rate.tif", "rate_mm_h": 3, "spacing": 1})")),
          dir.path()),
      Contains("/rain | ") && Contains("exactly one of"));
}

TEST_CASE("rain from a netCDF series of maps: times of the run, units converted",
          "[scenario][rain]") {
  swemps::testing::TempDir dir("rain-series");
  // Three 10-minute maps, starting 10 minutes after the scene's t = 0.
  write_series(dir.path() / "radar.nc", "minutes since 2024-06-01 12:00:00", {10, 20, 30}, "mm/h",
               {{6, 12}, {60, 0}, {0, 30}});
  json scene = rain_scene(json::parse(R"({"rate_netcdf": "radar.nc", "spacing": 1})"));
  scene["end_time"] = 3600;
  scene["output"]["start_time"] = "2024-06-01T11:50:00Z";
  const auto built = build(scene, dir.path());
  const auto& rain = rain_of(built);
  const auto* maps = dynamic_cast<const swemps::hydrology::MappedRainRate*>(&rain.rate());
  REQUIRE(maps != nullptr);
  CHECK(maps->frame_count() == 3);
  CHECK(maps->end_s() == Approx(3000.0));  // the last map holds for the interval before it
  // Nothing in the first 20 minutes of the run; then 10 minutes of the first map.
  CHECK(rain.volume_due(0.0, 1200.0) == 0.0);
  CHECK(rain.volume_due(1200.0, 1800.0) == Approx((6 + 12) * 100.0 / 6.0 * 1e-3));
  CHECK(rain.volume_due(0.0, 3600.0) ==
        Approx((6 + 12 + 60 + 0 + 0 + 30) * 100.0 / 6.0 * 1e-3).epsilon(1e-12));

  // Without a start_time the file's reference date is t = 0; kg m-2 s-1 is mm/s.
  write_series(dir.path() / "flux.nc", "hours since 2024-06-01", {0, 1}, "kg m-2 s-1",
               {{0.01, 0.01}, {0, 0}});
  json flux = rain_scene(json::parse(R"({"rate_netcdf": "flux.nc", "spacing": 1})"));
  const auto flux_built = build(flux, dir.path());
  CHECK(rain_of(flux_built).volume_due(0.0, 7200.0) == Approx(0.01 * 3600.0 * 200.0 * 1e-3));
  // Depths per interval (mm): 5 mm in each 15-minute interval is 20 mm/h.
  write_series(dir.path() / "depths.nc", "seconds since 2024-06-01", {0, 900}, "mm",
               {{5, 5}, {5, 5}});
  const auto depths =
      build(rain_scene(json::parse(R"({"rate_netcdf": "depths.nc", "spacing": 1})")), dir.path());
  CHECK(rain_of(depths).rate().peak_m_s() == Approx(20.0 * kMmH));

  write_series(dir.path() / "inches.nc", "minutes since 2024-06-01", {0, 10}, "in/h",
               {{1, 1}, {1, 1}});
  CHECK_THAT(
      refusal(rain_scene(json::parse(R"({"rate_netcdf": "inches.nc", "spacing": 1})")), dir.path()),
      Contains("/rain/rate_netcdf | ") && Contains("rain in 'in/h'"));
  write_series(dir.path() / "backwards.nc", "minutes since 2024-06-01", {10, 0}, "mm/h",
               {{1, 1}, {1, 1}});
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"rate_netcdf": "backwards.nc", "spacing": 1})")),
                     dir.path()),
             Contains("/rain/rate_netcdf | ") && Contains("not after map 1"));
  write_two_cells(dir.path() / "flat.tif", 1, 1);
  CHECK_THAT(
      refusal(rain_scene(json::parse(R"({"rate_netcdf": "flat.tif", "spacing": 1})")), dir.path()),
      Contains("/rain/rate_netcdf | ") && Contains("has no time axis"));
}

TEST_CASE("losses from rasters, and Green-Ampt soil", "[scenario][rain]") {
  swemps::testing::TempDir dir("rain-losses");
  write_two_cells(dir.path() / "initial.tif", 2.0, 8.0);
  json scene = rain_scene(json::parse(
      R"({"rate_mm_h": 36, "spacing": 1, "initial_loss_mm": "initial.tif",
          "continuing_loss_mm_h": 1})"));
  REQUIRE(std::holds_alternative<swemps::scenario::RasterSpec>(
      parse(scene, dir.path()).rain[0].initial_loss_mm));
  CHECK(rain_of(build(scene, dir.path())).cell_count() == 200);

  json soil = rain_scene(json::parse(
      R"({"rate_mm_h": 36, "spacing": 1,
          "green_ampt": {"conductivity_mm_h": "initial.tif", "suction_mm": 110,
                         "moisture_deficit": 0.3}})"));
  REQUIRE(parse(soil, dir.path()).rain[0].green_ampt);
  CHECK(rain_of(build(soil, dir.path())).cell_count() == 200);

  CHECK_THAT(refusal(rain_scene(json::parse(
                         R"({"rate_mm_h": 36, "spacing": 1, "continuing_loss_mm_h": 1,
                             "green_ampt": {"conductivity_mm_h": 1, "suction_mm": 110,
                                            "moisture_deficit": 0.3}})")),
                     dir.path()),
             Contains("/rain | ") && Contains("at most one of"));
  CHECK_THAT(refusal(rain_scene(json::parse(
                         R"({"rate_mm_h": 36, "spacing": 1,
                             "green_ampt": {"conductivity_mm_h": 1, "suction_mm": 110}})")),
                     dir.path()),
             Contains("/rain/green_ampt/moisture_deficit | "));
  CHECK_THAT(refusal(rain_scene(json::parse(
                         R"({"rate_mm_h": 36, "spacing": 1,
                             "green_ampt": {"conductivity_mm_h": 1, "suction_mm": 110,
                                            "moisture_deficit": 1.5}})")),
                     dir.path()),
             Contains("/rain/green_ampt/moisture_deficit | ") && Contains("0 to 1"));
  write_two_cells(dir.path() / "negative.tif", 2.0, -1.0);
  CHECK_THAT(refusal(rain_scene(json::parse(
                         R"({"rate_mm_h": 36, "spacing": 1, "initial_loss_mm": "negative.tif"})")),
                     dir.path()),
             Contains("/rain | ") && Contains("initial loss is -0.001"));
}
