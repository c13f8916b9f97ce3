// Tests of where and how hard rain falls: one rate for every cell, and maps of the rate, static
// or a series, each holding over its interval.

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "../support/effect_stepper.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/hydrology/rain_rate.hpp"

using namespace swemps;
using hydrology::MappedRainRate;

namespace {

constexpr double kMmH = hydrology::kMetresPerSecondPerMmPerHour;
constexpr double kForever = std::numeric_limits<double>::infinity();

// A 2 x 1 map of 10 m cells over [0, 20] x [0, 10], rates in m/s.
std::shared_ptr<const terrain::GriddedField> two_cells(double west, double east) {
  terrain::GridGeometry g{2, 1, 0.0, 10.0, 10.0, 10.0};
  return std::make_shared<const terrain::GriddedField>(g, std::vector<double>{west, east});
}

}  // namespace

TEST_CASE("a map of the rate gives each cell its map cell's rate; maps hold over their intervals",
          "[rain]") {
  MappedRainRate rate(
      {{0.0, two_cells(10.0 * kMmH, 30.0 * kMmH)}, {600.0, two_cells(0.0, 60.0 * kMmH)}}, 1200.0);
  // Cells on both sides, one on the edge between them (it belongs to the east).
  const std::vector<std::array<double, 2>> centres = {{2.0, 5.0}, {10.0, 5.0}, {19.0, 1.0}};
  rate.bind(centres);
  CHECK(rate.peak_m_s() == Approx(60.0 * kMmH));
  std::vector<double> depth(3);
  // 300 s of the first map, 300 s of the second.
  CHECK(rate.depth_over(300.0, 900.0, depth) == Approx((30.0 + 60.0) / 12.0 * 1e-3));
  CHECK(depth[0] == Approx(10.0 / 12.0 * 1e-3));
  CHECK(depth[1] == Approx((30.0 + 60.0) / 12.0 * 1e-3));
  // Nothing before the first map or after the last one's end.
  CHECK(rate.depth_over(-100.0, 0.0, depth) == 0.0);
  CHECK(rate.depth_over(1200.0, 1300.0, depth) == 0.0);
  CHECK(rate.depth_over(1100.0, 1300.0, depth) == Approx(60.0 / 36.0 * 1e-3));
}

TEST_CASE("rain from a coarse map brings the map's volume to finer cells", "[rain]") {
  // The map's west cell rains 36 mm/h, its east cell 72 mm/h; 1 m rain cells under it.
  hydrology::RainSettings s;
  s.domain = {0.0, 20.0, 0.0, 10.0};
  s.spacing_m = 1.0;
  s.creation_depth_m = 1.0;  // everything stays pending, to count it
  hydrology::Rain rain(
      s, std::make_unique<MappedRainRate>(
             std::vector<MappedRainRate::Frame>{{0.0, two_cells(36.0 * kMmH, 72.0 * kMmH)}},
             kForever));
  testing::EffectStepper st;
  st.step(rain, 0.0, 100.0);
  const double expected = (36.0 + 72.0) / 36.0 * 1e-3 * 100.0;  // m^3 over 100 m^2 a cell
  CHECK(rain.volume_fallen() == Approx(expected).epsilon(1e-12));
  CHECK(rain.pending_volume() == Approx(expected).epsilon(1e-12));
  CHECK(rain.volume_due(0.0, 100.0) == Approx(expected).epsilon(1e-12));
  CHECK(rain.time_step_limit(st.settings, 0.0) == Approx(1.0 / (72.0 * kMmH)));
}

TEST_CASE("rain maps refuse what they cannot give", "[rain]") {
  using Frames = std::vector<MappedRainRate::Frame>;
  CHECK_THROWS_AS(MappedRainRate(Frames{}, 10.0), std::invalid_argument);
  CHECK_THROWS_AS(MappedRainRate(Frames{{0.0, two_cells(1, 1)}, {0.0, two_cells(1, 1)}}, 10.0),
                  std::invalid_argument);
  CHECK_THROWS_AS(MappedRainRate(Frames{{0.0, two_cells(1, 1)}}, 0.0), std::invalid_argument);
  terrain::GridGeometry other{1, 1, 0.0, 10.0, 20.0, 10.0};
  CHECK_THROWS_AS(MappedRainRate(Frames{{0.0, two_cells(1, 1)},
                                        {5.0, std::make_shared<const terrain::GriddedField>(
                                                  other, std::vector<double>{1.0})}},
                                 10.0),
                  std::invalid_argument);

  const std::vector<std::array<double, 2>> off = {{25.0, 5.0}};
  MappedRainRate small(Frames{{0.0, two_cells(1e-6, 1e-6)}}, kForever);
  CHECK_THROWS_WITH(small.bind(off), Catch::Contains("does not cover the rain cell at (25, 5)"));
  const std::vector<std::array<double, 2>> on = {{15.0, 5.0}};
  MappedRainRate gap(Frames{{0.0, two_cells(1e-6, 1e-6)},
                            {60.0, two_cells(1e-6, std::numeric_limits<double>::quiet_NaN())}},
                     kForever);
  CHECK_THROWS_WITH(gap.bind(on), Catch::Contains("map of 60 s has no value (nodata)"));
  MappedRainRate negative(Frames{{0.0, two_cells(1e-6, -3.0 * kMmH)}}, kForever);
  CHECK_THROWS_WITH(negative.bind(on), Catch::Contains("-3.0") && Catch::Contains("mm/h"));
}
