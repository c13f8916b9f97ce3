// A solitary wave over water of constant depth travels at the long-wave speed. The issue's
// measure: over ten depths, within 2 % of sqrt(g (d + H)), with its volume to round-off.
//
// The shallow-water equations have no wave of permanent form: each level of the wave moves at
// its own characteristic speed, about sqrt(g d) (1 + 3 eta / 2d) for a wave moving one way, so
// the crest outruns the flanks and the wave steepens. What is timed is therefore the passage
// of the whole wave, the time-centroid of its surface at a gauge (t_c = int t eta dt /
// int eta dt), which a peak's time would make hostage to a few tenths of a millimetre of
// noise on a crest this flat. A second-order finite-volume solution of the same equations on
// 1 cm cells (HLL fluxes, MUSCL, Heun) times it, between the same gauges over the same 22 s,
// at 0.30 % above sqrt(g (d + H)); this scheme at 0.2 m spacing at 1.38 % (measured), its
// wave a little broader and lower than the grid's (the kernel's smoothing). At 0.1 m the
// still water behind the wave grows particle-scale noise within 15 s (docs/tsunami.md), which
// the centroid's long window would read: this test keeps the coarser spacing that resolves the
// wave (its half-length is 18 depths, 90 spacings).

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

using namespace swemps;

namespace {

constexpr double kDepth = 1.0, kHeight = 0.019, kGravity = 9.81;
constexpr double kCrest = 30.0, kGaugeA = 60.0, kGaugeB = 70.0;  // ten depths apart
constexpr double kLength = 110.0, kWidth = 1.0, kSpacing = 0.2, kEnd = 22.0;

// The time-centroid of the surface's rise at a gauge, from samples at every step.
struct Passage {
  double weighted_time = 0.0, weight = 0.0;
  void add(double t, double rise, double dt) {
    weighted_time += t * rise * dt;
    weight += rise * dt;
  }
  double centroid() const { return weighted_time / weight; }
};

}  // namespace

TEST_CASE("a solitary wave over constant depth travels at the long-wave speed",
          "[verification][tsunami]") {
  char text[1024];
  std::snprintf(text, sizeof text, R"({"name": "solitary", "end_time": %g,
    "domain": {"x_min": 0, "x_max": %g, "y_min": 0, "y_max": %g},
    "water": [{"rectangle": {"x_min": 0, "x_max": %g, "y_min": 0, "y_max": %g},
               "depth": %g, "spacing": %g,
               "solitary_wave": {"height": %g, "crest": [%g, %g], "direction": [1, 0]}}],
    "walls": [{"polyline": [[0, 0], [%g, 0], [%g, %g], [0, %g], [0, 0]]}],
    "output": {"path": "solitary.nc", "grid": {"spacing": %g}}})",
                kEnd, kLength, kWidth, kLength, kWidth, kDepth, kSpacing, kHeight, kCrest,
                0.5 * kWidth, kLength, kLength, kWidth, kWidth, kSpacing);
  const auto scene = scenario::parse(text, std::filesystem::temp_directory_path(), "solitary");
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  const auto grid = scenario::output_grid(scene, built.terrain);
  const auto gauge_a = scenario::gauge_reader(scene, built.terrain, grid, {kGaugeA, 0.5 * kWidth});
  const auto gauge_b = scenario::gauge_reader(scene, built.terrain, grid, {kGaugeB, 0.5 * kWidth});
  Passage a, b;
  double largest_a = 0.0;
  const auto read = [&](Passage& passage, const maps::CellAverages& gauge, double dt) {
    const auto f = gauge.fields(sim.particles(), sim.kernel());
    const double rise = gauge.level(0, f.depth.front()) - kDepth;
    passage.add(sim.time(), rise, dt);
    return rise;
  };
  double last = 0.0;
  sim.advance_to(kEnd, [&] {
    sim.refresh();
    const double dt = sim.time() - last;
    last = sim.time();
    largest_a = std::max(largest_a, read(a, gauge_a, dt));
    read(b, gauge_b, dt);
  });
  const double speed = (kGaugeB - kGaugeA) / (b.centroid() - a.centroid());
  const double long_wave = std::sqrt(kGravity * (kDepth + kHeight));
  INFO("centroid passages " << a.centroid() << " s and " << b.centroid() << " s: " << speed
                            << " m/s against sqrt(g (d + H)) = " << long_wave << " m/s, "
                            << 100.0 * (speed / long_wave - 1.0) << " %; largest rise at A "
                            << largest_a << " m");
  CHECK(speed == Approx(long_wave).epsilon(0.02));
  // The wave arrives whole: its crest at the first gauge is still near its height (it has
  // travelled 30 depths; the steepening has not yet broken it).
  CHECK(largest_a == Approx(kHeight).epsilon(0.1));
  // Closed walls, no sources: the volume only moves between particles.
  CHECK(std::abs(sim.relative_volume_change()) < 1e-12);
}
