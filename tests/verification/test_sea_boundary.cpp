// Sea boundaries against what they promise (docs/tsunami.md, "Sea boundaries"):
//  - an open boundary lets a long wave leave: what comes back from it is measured at a gauge
//    10 m inside, as the difference from the same run in a channel twice as long, over the
//    time the wave's reflection from the line would pass the gauge. The issue asks for under
//    5 % of the incident height; 0.7 % is measured. The same measure against a wall at the
//    line reads the whole wave, which shows that it sees reflections;
//  - a level boundary makes the water beside it follow its series, and every cubic metre it
//    lets in or out is booked.
// The window ends before the still water behind the wave grows its particle-scale ripples
// (docs/tsunami.md, "Limits"), which would swamp a reflection this small.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "swemps/boundaries/sea_boundary.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

using namespace swemps;

namespace {

constexpr double kDepth = 1.0, kHeight = 0.01, kSpacing = 0.2, kGauge = 90.0;

// The surface's rise at the gauge at every step to `end`, in a channel 1 m wide from x = 0 to
// `length`, walled but for what `east` puts at x = length, with a solitary wave starting at
// x = 25 and moving east.
std::vector<std::array<double, 2>> gauge_series(double length, const std::string& east,
                                                double end) {
  char text[2048];
  std::snprintf(text, sizeof text, R"({"name": "sea", "end_time": %g,
    "domain": {"x_min": 0, "x_max": %g, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": %g, "y_min": 0, "y_max": 1},
               "depth": %g, "spacing": %g,
               "solitary_wave": {"height": %g, "crest": [25, 0.5], "direction": [1, 0]}}],
    %s,
    "output": {"path": "sea.nc", "grid": {"spacing": %g}}})",
                end, length, length, kDepth, kSpacing, kHeight, east.c_str(), kSpacing);
  const auto scene = scenario::parse(text, std::filesystem::temp_directory_path(), "sea");
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  const auto grid = scenario::output_grid(scene, built.terrain);
  const auto gauge = scenario::gauge_reader(scene, built.terrain, grid, {kGauge, 0.5});
  std::vector<std::array<double, 2>> series;
  sim.advance_to(end, [&] {
    sim.refresh();
    const auto f = gauge.fields(sim.particles(), sim.kernel());
    series.push_back({sim.time(), gauge.level(0, f.depth.front()) - kDepth});
  });
  CHECK(std::abs(sim.relative_volume_change()) < 1e-12);
  return series;
}

// The series' value at t, linear between samples.
double at(const std::vector<std::array<double, 2>>& s, double t) {
  const auto after = std::lower_bound(s.begin(), s.end(), t,
                                      [](const auto& p, double time) { return p[0] < time; });
  if (after == s.begin()) return s.front()[1];
  if (after == s.end()) return s.back()[1];
  const auto& a = *(after - 1);
  const auto& b = *after;
  return a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
}

// The largest difference between a run and the reference at the run's samples.
double largest_difference(const std::vector<std::array<double, 2>>& run,
                          const std::vector<std::array<double, 2>>& reference) {
  double largest = 0.0;
  for (const auto& [t, rise] : run) largest = std::max(largest, std::abs(rise - at(reference, t)));
  return largest;
}

}  // namespace

TEST_CASE("an open sea boundary lets a long wave leave", "[verification][tsunami]") {
  // The crest reaches the line at 24 s and its reflection would pass the gauge by 28 s; in
  // the channel twice as long nothing comes back before 55 s.
  constexpr double kEnd = 28.0;
  // Walls along the sides and the west end, and across the east end when `closed`.
  const auto walled = [](double length, bool closed) {
    std::string w = R"("walls": [{"polyline": [[)" + std::to_string(length) +
                    R"(, 0], [0, 0], [0, 1], [)" + std::to_string(length) + R"(, 1])";
    if (closed) w += R"(, [)" + std::to_string(length) + R"(, 0])";
    return w + "]}]";
  };
  const auto reference = gauge_series(200.0, walled(200.0, true), kEnd);
  const auto open =
      gauge_series(100.0,
                   walled(100.0, false) +
                       R"(, "sea_boundaries": [{"line": [[100, 0], [100, 1]], "type": "open"}])",
                   kEnd);
  const auto wall = gauge_series(100.0, walled(100.0, true), kEnd);
  double incident = 0.0;
  for (const auto& [t, rise] : reference) incident = std::max(incident, rise);
  const double through_open = largest_difference(open, reference);
  const double off_wall = largest_difference(wall, reference);
  INFO("incident " << incident << " m; back from the open boundary " << through_open << " m ("
                   << 100.0 * through_open / incident << " %), from a wall " << off_wall << " m");
  CHECK(incident == Approx(kHeight).epsilon(0.05));
  CHECK(through_open < 0.05 * incident);
  CHECK(off_wall > 0.5 * incident);
}

TEST_CASE("a level boundary makes the water follow its series and books what it lets through",
          "[verification][tsunami]") {
  // A 20 m basin, its east end held at a level that rises 5 cm over 40 s, holds, and falls
  // back. A gauge 1 m inside follows the level within a tenth of the rise: the ramp's kinks
  // stir the basin's seiche (period 4 L / c = 25.5 s; amplitude about rate x period / 2 pi
  // = 5 mm at the far wall, a tenth of it 1 m from the held line), the gauge lags the line by
  // 1 m / c = 0.3 s (0.4 mm), and the water beside a line that takes particles in and out
  // moves by a few mm (measured: 4.2 mm at most). Every cubic metre is booked.
  const std::string text = R"({"name": "tide", "end_time": 100,
    "domain": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 1},
               "depth": 1, "spacing": 0.2}],
    "walls": [{"polyline": [[20, 0], [0, 0], [0, 1], [20, 1]]}],
    "sea_boundaries": [{"name": "tide", "line": [[20, 0], [20, 1]], "type": "level",
                        "series": [[0, 1], [40, 1.05], [60, 1.05], [100, 1]]}],
    "output": {"path": "tide.nc", "grid": {"spacing": 0.2}}})";
  const auto scene = scenario::parse(text, std::filesystem::temp_directory_path(), "tide");
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  const auto grid = scenario::output_grid(scene, built.terrain);
  const auto gauge = scenario::gauge_reader(scene, built.terrain, grid, {19.0, 0.5});
  const boundaries::LevelSeries level({{0, 1}, {40, 1.05}, {60, 1.05}, {100, 1}});
  double furthest = 0.0, volume_error = 0.0;
  sim.advance_to(100.0, [&] {
    sim.refresh();
    const auto f = gauge.fields(sim.particles(), sim.kernel());
    furthest =
        std::max(furthest, std::abs(gauge.level(0, f.depth.front()) - level.level(sim.time())));
    volume_error = std::max(volume_error, std::abs(sim.relative_volume_change()));
  });
  const boundaries::SeaBoundary* sea = nullptr;
  for (const auto& effect : sim.effects()) {
    if (const auto* s = dynamic_cast<const boundaries::SeaBoundary*>(effect.get())) sea = s;
  }
  REQUIRE(sea != nullptr);
  INFO("the gauge 1 m inside strayed " << furthest << " m from the level; in "
                                       << sea->volume_added() << " m3, out "
                                       << sea->volume_removed() << " m3");
  CHECK(furthest < 0.1 * 0.05);
  // The basin rose by 5 cm x 20 m^2 and drained again: water went both ways.
  CHECK(sea->volume_added() > 0.5);
  CHECK(sea->volume_removed() > 0.5);
  CHECK(sim.ledger().added_m3 == sea->volume_added());
  CHECK(sim.ledger().removed_m3 == sea->volume_removed());
  CHECK(volume_error < 1e-12);
}
