// Provenance (docs/provenance.md): every particle carries the share of its water that came from
// each source of the scene and when that water entered; splitting, merging, inflow, outflow,
// rain and restarts keep each source's volume to round-off, and the run writes it all.

#include <netcdf.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/netcdf_values.hpp"
#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "../support/two_lanes.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/state_record.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
using swemps::particles::Origin;
using swemps::particles::SweParticles;

using swemps::testing::two_lane_channel;

namespace {

swemps::scenario::Scenario scene_of(const json& j) {
  return swemps::scenario::parse(j.dump(), std::filesystem::temp_directory_path(), "provenance");
}

// Every source's water against its books, relative to what it brought.
double worst_label_balance(const swemps::swe::Simulation& sim) {
  double worst = 0.0;
  for (std::size_t k = 0; k < sim.particles().label_count(); ++k) {
    worst = std::max(worst, std::abs(sim.relative_label_volume_change(k)));
  }
  return worst;
}

}  // namespace

TEST_CASE("particles keep their sources' shares through reorder, removal, splits and merges",
          "[provenance]") {
  SweParticles p;
  p.track_provenance(3, true);
  p.add_fluid(0.0, 0.0, 0.0, 0.0, 2.0, 1.0, 2.0, 0.0, Origin{0, 0.0});
  p.add_fluid(1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, Origin{2, 5.0});
  p.add_fluid(2.0, 0.0, 0.0, 0.0, 3.0, 1.0, 3.0, 0.0, Origin{1, 1.0});
  REQUIRE(p.label_share.size() == 9);
  CHECK(p.label_volume(0) == 2.0);
  CHECK(p.label_volume(1) == 3.0);
  CHECK(p.label_volume(2) == 1.0);

  // Merging particle 1 into 0: each label's volume is kept, entry times mixed by volume.
  p.mix_provenance(0, 2.0, 1, 1.0);
  p.volume[0] = 3.0;
  p.volume[1] = 0.0;
  CHECK(p.label_volume(0) == Approx(2.0).epsilon(1e-15));
  CHECK(p.label_volume(2) == Approx(1.0).epsilon(1e-15));
  CHECK(p.entry_time[0] == Approx(5.0 / 3.0));
  // 1.5 m3 of label 1 water falling on particle 0 at t = 4 s.
  p.mix_in(0, 3.0, 1.5, Origin{1, 4.0});
  p.volume[0] = 4.5;
  CHECK(p.label_volume(1) == Approx(4.5).epsilon(1e-15));
  CHECK(p.entry_time[0] == Approx((3.0 * 5.0 / 3.0 + 1.5 * 4.0) / 4.5));
  double sum = 0.0;
  for (std::size_t k = 0; k < 3; ++k) sum += p.label_share[k];
  CHECK(sum == Approx(1.0).epsilon(1e-15));

  // A daughter takes its parent's shares; reordering and removal carry them with the particle.
  p.add_fluid(3.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0);
  p.copy_provenance(2, 3);
  const std::vector<std::uint32_t> order{3, 2, 1, 0};
  p.reorder(order);
  CHECK(p.label_share[0 * 3 + 1] == 1.0);  // the daughter, first now
  CHECK(p.entry_time[0] == 1.0);
  const std::vector<std::uint8_t> flagged{0, 0, 1, 0};  // the emptied particle 1, third now
  p.remove(flagged);
  REQUIRE(p.fluid_count() == 3);
  REQUIRE(p.label_share.size() == 9);
  REQUIRE(p.entry_time.size() == 3);
  CHECK(p.x[2] == 0.0);
  CHECK(p.entry_time[2] == Approx((3.0 * 5.0 / 3.0 + 1.5 * 4.0) / 4.5));
  CHECK(p.label_share[2 * 3 + 0] == Approx(2.0 / 4.5));
}

TEST_CASE("particles that track no provenance carry none", "[provenance]") {
  json j = two_lane_channel();
  j["output"].erase("provenance");
  const auto built = swemps::scenario::build(scene_of(j));
  const auto& p = built.simulation.particles();
  CHECK(p.label_count() == 0);
  CHECK_FALSE(p.tracks_ages());
  CHECK(p.label_share.empty());
  CHECK(p.entry_time.empty());
  CHECK(built.simulation.ledger().label_initial_m3.empty());
}

TEST_CASE("the sources of a scene are its names, shared names one label", "[provenance]") {
  json j = two_lane_channel();
  j["water"].push_back(j["water"][0]);
  j["water"][2]["rectangle"] = {{"x_min", 15}, {"x_max", 16}, {"y_min", 5}, {"y_max", 10}};
  j["water"].push_back(j["water"][1]);
  j["water"][3].erase("name");
  j["water"][3]["rectangle"] = {{"x_min", 15}, {"x_max", 16}, {"y_min", 0}, {"y_max", 5}};
  const auto labels = swemps::scenario::provenance_labels(scene_of(j));
  CHECK(labels == std::vector<std::string>{"north lake", "south lake", "water", "north river",
                                           "south river", "storm"});
  CHECK(swemps::scenario::provenance_label(scene_of(j), "storm") == 5);
}

TEST_CASE("two sources side by side in a channel keep apart, and every source's water balances",
          "[provenance]") {
  auto built = swemps::scenario::build(scene_of(two_lane_channel()));
  auto& sim = built.simulation;
  const std::size_t labels = sim.particles().label_count();
  REQUIRE(labels == 5);
  // North lake, south lake, north river, south river, storm.
  const std::vector<std::size_t> north{0, 2}, south{1, 3};
  constexpr std::size_t kStorm = 4;
  double worst = 0.0;
  while (!sim.reached(8.0)) {
    sim.step_towards(8.0);
    worst = std::max(worst, worst_label_balance(sim));
  }
  sim.refresh();
  const auto& p = sim.particles();
  const auto& ledger = sim.ledger();
  // Every way water comes and goes was taken: the numbers say the test saw them.
  for (const std::size_t k : {2, 3, 4}) CHECK(ledger.label_added_m3[k] > 0.0);
  CHECK(ledger.label_removed_m3[0] > 0.0);  // the lakes' water reached the outflow line
  CHECK(ledger.label_removed_m3[1] > 0.0);
  std::size_t resolution_changes = 0;
  for (const auto& e : sim.effect_times()) {
    if (e.name != "particle splitting" && e.name != "particle merging") continue;
    INFO(e.name << ": " << e.report);
    CHECK(e.report.rfind("0 ", 0) != 0);  // "N splits", "N merges" with N > 0
    ++resolution_changes;
  }
  CHECK(resolution_changes == 2);
  // A source's volume to round-off: 1e-12 of what it brought, at every step.
  CHECK(worst < 1e-12);

  std::size_t north_particles = 0, south_particles = 0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double* share = &p.label_share[i * labels];
    double sum = 0.0;
    for (std::size_t k = 0; k < labels; ++k) sum += share[k];
    CHECK(sum == Approx(1.0).epsilon(1e-12));
    // Not a drop of the other lane's water crosses the wall: the shares are exactly nought.
    const auto& other = p.y[i] > 5.0 ? south : north;
    for (const std::size_t k : other) CHECK(share[k] == 0.0);
    ++(p.y[i] > 5.0 ? north_particles : south_particles);
    // Age: entered between the start and now.
    CHECK(p.entry_time[i] >= 0.0);
    CHECK(p.entry_time[i] <= sim.time());
  }
  CHECK(north_particles > 100);
  CHECK(south_particles > 100);
  CHECK(p.label_volume(kStorm) > 0.0);
}

TEST_CASE("provenance survives a restart bit for bit", "[provenance]") {
  const auto scene = scene_of(two_lane_channel());
  auto first = swemps::scenario::build(scene);
  first.simulation.advance_to(3.0);
  swemps::swe::StateWriter record;
  first.simulation.save_state(record);
  auto second = swemps::scenario::build(scene);
  swemps::swe::StateReader in(record.bytes(), "the record");
  second.simulation.restore_state(in);
  first.simulation.advance_to(5.0);
  second.simulation.advance_to(5.0);
  first.simulation.refresh();
  second.simulation.refresh();
  const auto& a = first.simulation.particles();
  const auto& b = second.simulation.particles();
  REQUIRE(a.fluid_count() == b.fluid_count());
  CHECK(a.x == b.x);
  CHECK(a.label_share == b.label_share);
  CHECK(a.entry_time == b.entry_time);
  CHECK(first.simulation.ledger().label_removed_m3 == second.simulation.ledger().label_removed_m3);
  CHECK(worst_label_balance(second.simulation) < 1e-12);

  // A record of a scene without provenance does not fit one with it.
  json plain = two_lane_channel();
  plain["output"].erase("provenance");
  auto untracked = swemps::scenario::build(scene_of(plain));
  swemps::swe::StateWriter plain_record;
  untracked.simulation.save_state(plain_record);
  auto tracked = swemps::scenario::build(scene);
  swemps::swe::StateReader plain_in(plain_record.bytes(), "the plain record");
  CHECK_THROWS_AS(tracked.simulation.restore_state(plain_in), swemps::swe::StateError);
}

TEST_CASE("a run writes each source's maps, balance and gauge shares, and the water's age",
          "[provenance][cli]") {
  swemps::testing::TempDir dir("provenance");
  json scene = two_lane_channel();
  scene["output"]["rasters"] = {"max_source_share", "max_mean_age"};
  std::ofstream(dir.path() / "lanes.json") << scene.dump(2);
  const auto run = swemps::testing::run_command(std::string(SWEMPS_CLI) + " run -q " +
                                                (dir.path() / "lanes.json").string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  const auto file = dir.path() / "lanes.nc";
  int nc = -1;
  REQUIRE(nc_open(file.c_str(), NC_NOWRITE, &nc) == NC_NOERR);
  int dim = -1;
  std::size_t sources = 0, times = 0, cells_y = 0, cells_x = 0;
  REQUIRE(nc_inq_dimid(nc, "source", &dim) == NC_NOERR);
  REQUIRE(nc_inq_dimlen(nc, dim, &sources) == NC_NOERR);
  REQUIRE(sources == 5);
  REQUIRE(nc_inq_dimid(nc, "time", &dim) == NC_NOERR);
  REQUIRE(nc_inq_dimlen(nc, dim, &times) == NC_NOERR);
  REQUIRE(nc_inq_dimid(nc, "y", &dim) == NC_NOERR);
  REQUIRE(nc_inq_dimlen(nc, dim, &cells_y) == NC_NOERR);
  REQUIRE(nc_inq_dimid(nc, "x", &dim) == NC_NOERR);
  REQUIRE(nc_inq_dimlen(nc, dim, &cells_x) == NC_NOERR);
  int name_var = -1;
  REQUIRE(nc_inq_varid(nc, "source_name", &name_var) == NC_NOERR);
  std::vector<char*> names(sources);
  REQUIRE(nc_get_var_string(nc, name_var, names.data()) == NC_NOERR);
  CHECK(std::string(names[0]) == "north lake");
  CHECK(std::string(names[4]) == "storm");
  nc_free_string(sources, names.data());

  const auto depth = swemps::testing::whole_variable(nc, "depth");
  const auto source_depth = swemps::testing::whole_variable(nc, "source_depth");
  const auto source_share = swemps::testing::whole_variable(nc, "source_share");
  const auto mean_age = swemps::testing::whole_variable(nc, "mean_age");
  const std::size_t cells = cells_x * cells_y;
  REQUIRE(source_depth.size() == times * sources * cells);
  std::size_t wet = 0;
  for (std::size_t t = 0; t < times; ++t) {
    for (std::size_t c = 0; c < cells; ++c) {
      double depth_sum = 0.0, share_sum = 0.0;
      for (std::size_t k = 0; k < sources; ++k) {
        depth_sum += source_depth[(t * sources + k) * cells + c];
        share_sum += source_share[(t * sources + k) * cells + c];
      }
      // The sources' depths make up the depth (to the maps' single precision).
      CHECK(depth_sum == Approx(depth[t * cells + c]).epsilon(1e-5).margin(1e-7));
      if (depth[t * cells + c] > 0.011) {
        ++wet;
        CHECK(share_sum == Approx(1.0).epsilon(1e-5));
        CHECK(mean_age[t * cells + c] >= 0.0);
        CHECK(mean_age[t * cells + c] <= 4.0 * static_cast<double>(t) + 1e-6);
      }
    }
  }
  CHECK(wet > 100);
  // Every source's volume balances at every series sample.
  for (const double error : swemps::testing::whole_variable(nc, "source_volume_error")) {
    CHECK(std::abs(error) < 1e-12);
  }
  // The gauge in the north lake holds north water and rain only; the one on dry ground, none.
  const auto shares = swemps::testing::whole_variable(nc, "gauge_source_share");
  const std::size_t samples = shares.size() / (2 * sources);
  REQUIRE(samples > 10);
  const auto at = [&](std::size_t s, std::size_t gauge, std::size_t k) {
    return shares[(s * 2 + gauge) * sources + k];
  };
  CHECK(at(samples - 1, 0, 0) > 0.1);
  CHECK(at(samples - 1, 0, 1) == 0.0);
  CHECK(at(samples - 1, 0, 3) == 0.0);
  CHECK(at(samples - 1, 1, 0) == NC_FILL_DOUBLE);
  // The whole-run maxima: each source's deepest water holds every map's, and the largest age
  // is the run's at most.
  const auto max_source_depth = swemps::testing::whole_variable(nc, "max_source_depth");
  REQUIRE(max_source_depth.size() == sources * cells);
  for (std::size_t t = 0; t < times; ++t) {
    for (std::size_t i = 0; i < sources * cells; ++i) {
      CHECK(max_source_depth[i] >= source_depth[t * sources * cells + i]);
    }
  }
  const auto max_share = swemps::testing::whole_variable(nc, "max_source_share");
  CHECK(max_share[0 * cells + cells_x * 7 + 5] > 0.5);  // the north lake's own water
  CHECK(max_share[1 * cells + cells_x * 7 + 5] == 0.0);
  for (const double age : swemps::testing::whole_variable(nc, "max_mean_age")) {
    if (age != NC_FILL_FLOAT) CHECK(age <= 8.0 + 1e-5);
  }
  nc_close(nc);

  // GDAL reads each source's depth as bands (time x source).
  const auto info =
      swemps::testing::run_command("gdalinfo NETCDF:" + file.string() + ":source_depth");
  INFO(info.output);
  CHECK(info.status == 0);
  CHECK_THAT(info.output, Contains("NETCDF_DIM_source=4"));

  // The maxima as GeoTIFF, one per source; each source's share in the gauge table.
  for (const char* tif : {"lanes_max_source_share_north_lake.tif",
                          "lanes_max_source_share_storm.tif", "lanes_max_mean_age.tif"}) {
    INFO(tif);
    CHECK(std::filesystem::exists(dir.path() / tif));
  }
  CHECK_FALSE(std::filesystem::exists(dir.path() / "lanes_max_source_depth_storm.tif"));
  std::ifstream csv(dir.path() / "lanes_gauges.csv");
  std::string header;
  std::getline(csv, header);
  CHECK_THAT(header, Contains("north_v_m_s,north_share_north_lake,north_share_south_lake,"));
  CHECK_THAT(header, Contains("dry_share_storm"));
}

TEST_CASE("provenance is refused where it cannot be kept", "[provenance]") {
  const auto error_at = [](const json& j) {
    try {
      scene_of(j);
    } catch (const swemps::scenario::ScenarioError& e) {
      return e.json_path();
    }
    return std::string("no error");
  };
  json unknown = two_lane_channel();
  unknown["output"]["provenance"]["colour"] = true;
  CHECK(error_at(unknown) == "/output/provenance/colour");
  json unnamed = two_lane_channel();
  unnamed["water"][0]["name"] = "";
  CHECK(error_at(unnamed) == "/water/0/name");
  json tank = json::parse(R"({
    "name": "tank", "model": "ns", "dimension": 2, "end_time": 0.1,
    "domain": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 0.5, "y_min": 0, "y_max": 1},
               "depth": 0.2, "spacing": 0.05}],
    "ns": {"spacing": 0.05},
    "output": {"provenance": {"age": true}}
  })");
  CHECK(error_at(tank) == "/output/provenance");
}

TEST_CASE("a scene that starts dry writes its provenance from its first water on",
          "[provenance][cli]") {
  swemps::testing::TempDir dir("provenance");
  json scene = two_lane_channel();
  scene.erase("water");
  scene["end_time"] = 2;
  scene["output"]["interval"] = 1;
  std::ofstream(dir.path() / "dry.json") << scene.dump(2);
  const auto run = swemps::testing::run_command(std::string(SWEMPS_CLI) + " run -q " +
                                                (dir.path() / "dry.json").string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  int nc = -1;
  REQUIRE(nc_open((dir.path() / "lanes.nc").c_str(), NC_NOWRITE, &nc) == NC_NOERR);
  const auto age = swemps::testing::whole_variable(nc, "mean_age");
  const auto depth = swemps::testing::whole_variable(nc, "source_depth");
  nc_close(nc);
  // At t = 0 the map is dry: no age, no source's water anywhere.
  const std::size_t cells = 40 * 10;
  for (std::size_t c = 0; c < cells; ++c) CHECK(age[c] == NC_FILL_FLOAT);
  for (std::size_t k = 0; k < 3 * cells; ++k) CHECK(depth[k] == 0.0);
}
