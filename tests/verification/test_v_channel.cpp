// Uniform flow down a V-shaped channel: the exact steady solution of the 2D shallow-water
// equations with Manning friction, on a bed whose water is thin at both shores. The bed
// falls at S along x and rises at 1/Z each side of the thalweg, z_b = -S x + |y - y_c| / Z.
// In uniform flow the surface is level across the channel and every strip along it is in
// its own balance of gravity and friction, so the unit discharge is q(y) = h(y)^(5/3) S^(1/2) / n
// with h(y) = H - |y - y_c| / Z, and the discharge Q = 2 Z (3/8) H^(8/3) S^(1/2) / n sets the
// depth H on the thalweg. Per metre of channel the water fills A = Z H^2.
//
// This is the middle reach of the valley flood in miniature (docs/valley-flood.md, "Where the
// middle reach's shortfall sits"): a channel a few particles wide whose shores are thin sheets
// on a side slope. The particles must carry the discharge at the right depth there; too little
// water per metre of channel is what a too fast flow looks like.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/terrain/gridded_field.hpp"

using namespace swemps;

namespace {

constexpr double kSlope = 0.01;    // S
constexpr double kSideRun = 10.0;  // Z: the banks rise 1 m in 10 m
constexpr double kManningN = 0.035;
constexpr double kDischarge = 20.0;  // m^3/s
constexpr double kLength = 400.0;    // m along x
constexpr double kWidth = 62.0;      // m across: the banks stand 3.1 m over the thalweg
constexpr double kThalwegY = 31.0;   // on a bed cell's centre, so the kink is read exactly
constexpr double kBedCell = 2.0;

double normal_depth() {
  return std::pow(kDischarge * kManningN / (std::sqrt(kSlope) * 0.75 * kSideRun), 3.0 / 8.0);
}

// The bed as a GeoTIFF in local metres (no CRS), cell centres sampling the exact surface.
void write_bed(const std::filesystem::path& path) {
  io::write_geotiff(
      testing::sampled_field(
          static_cast<std::size_t>(kLength / kBedCell), static_cast<std::size_t>(kWidth / kBedCell),
          kBedCell,
          [](double x, double y) { return -kSlope * x + std::abs(y - kThalwegY) / kSideRun; }),
      path);
}

// The water per metre of channel over x in [150, 300] m, averaged over the last 150 s of
// 400 s: the inflow's discharge reaches the outflow line after about 200 s.
double water_per_metre(double spacing_m) {
  testing::TempDir dir("v-channel");
  write_bed(dir.path() / "bed.tif");
  const double top_half_width = kSideRun * normal_depth();
  const double inflow_x = spacing_m / 2;
  const nlohmann::json scene_json = {
      {"name", "v-channel"},
      {"end_time", 400},
      {"domain", {{"x_min", 0}, {"x_max", kLength}, {"y_min", 0}, {"y_max", kWidth}}},
      {"bed", {{"raster", "bed.tif"}}},
      {"friction", {{"manning_n", kManningN}}},
      {"splitting", nlohmann::json::object()},
      {"merging", nlohmann::json::object()},
      {"walls", {{{"polyline", {{0, 0}, {0, kWidth}}}}}},
      {"inflow",
       {{{"line", {{inflow_x, kThalwegY - top_half_width}, {inflow_x, kThalwegY + top_half_width}}},
         {"hydrograph", {{0, kDischarge}}},
         {"depth", 0.65},
         {"spacing", spacing_m},
         {"direction", {1, 0}}}}},
      {"outflow", {{{"line", {{350, 0}, {350, kWidth}}}}}},
      {"output", {{"path", "v-channel.nc"}}}};
  const auto scene = scenario::parse(scene_json.dump(), dir.path(), "v-channel");
  auto sim = scenario::make_simulation(scene);
  double sum = 0.0;
  int samples = 0;
  for (double t = 250.0; t <= 400.0 + 1e-9; t += 10.0) {
    sim.advance_to(t);
    sim.refresh();
    const auto& p = sim.particles();
    double volume = 0.0;
    for (std::size_t i = 0; i < p.fluid_count(); ++i)
      if (p.x[i] >= 150.0 && p.x[i] < 300.0) volume += p.volume[i];
    sum += volume / 150.0;
    ++samples;
  }
  return sum / samples;
}

}  // namespace

TEST_CASE("uniform flow down a V channel carries its discharge at the normal depth",
          "[verification]") {
  const double depth = normal_depth();            // 0.974 m
  const double exact = kSideRun * depth * depth;  // 9.50 m^2
  const double coarse = water_per_metre(4.0);     // some 5 particles across the water
  const double fine = water_per_metre(2.0);       // some 10
  INFO("water per metre: exact " << exact << " m2, 4 m spacing " << coarse << ", 2 m " << fine);
  // Measured (docs/verification.md): +7.0 % at 4 m, +3.2 % at 2 m (+8.2 and +4.0-4.3 % before
  // the planes' arrangement error was taken out, as on a channel of the valley's size then:
  // +7.6 % and +4.2 % at 4 and 9 particles across): first order in the particles across the
  // water, and too deep, not too fast. The bar is about half as much again as the 2 m error
  // was; a method that ran the water off too fast or not at all would fail it.
  CHECK(std::abs(fine / exact - 1.0) < 0.06);
  CHECK(std::abs(fine / exact - 1.0) < std::abs(coarse / exact - 1.0));
}
