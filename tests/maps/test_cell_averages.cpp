// Tests of what a map cell reads (maps::CellAverages): the map holds the particles' volume
// whatever the ratio of cell to particle spacing, no cell reads water that no particle's
// surface reaches, uniform water reads its depth, results do not depend on the thread count,
// and a gauge reads the level of water at rest less the bed at its point.

#include <omp.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "../support/broken_scenes.hpp"
#include "swemps/maps/cell_averages.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

using namespace swemps;

namespace {

double mapped_volume(const maps::CellFields& f, const swe::RegularGrid& grid) {
  double sum = 0.0;
  for (double h : f.depth) sum += h;
  return sum * grid.dx * grid.dy;
}

// A grid of square cells of `cell` m covering the domain [0, width] x [0, height] (the last
// row and column may reach past it).
swe::RegularGrid covering(double width, double height, double cell) {
  const auto nx = static_cast<std::size_t>(std::ceil(width / cell));
  const auto ny = static_cast<std::size_t>(std::ceil(height / cell));
  return {0.5 * cell, 0.5 * cell, cell, cell, nx, ny};
}

// The lowest bed in a cell, sampled finely (the bowl is smooth at this scale).
double lowest_bed(const swe::BedSource& bed, const swe::RegularGrid& g, std::size_t i,
                  std::size_t k) {
  constexpr int kSamples = 24;
  double low = std::numeric_limits<double>::infinity();
  for (int a = 0; a <= kSamples; ++a) {
    for (int b = 0; b <= kSamples; ++b) {
      const double x = g.x0 + (static_cast<double>(i) - 0.5 + a / double(kSamples)) * g.dx;
      const double y = g.y0 + (static_cast<double>(k) - 0.5 + b / double(kSamples)) * g.dy;
      low = std::min(low, bed.elevation(x, y));
    }
  }
  return low;
}

// How closely a cell of uniform water reads its depth. Exact for the continuous kernel,
// mirrored at walls and edges; the shares are its quadrature at sub-points about a particle
// spacing apart (0.8 of it in these tests), whose aliasing was measured at up to 0.6 % inside
// and 1.2 % in a corner of the domain, where three mirror images meet.
double uniform_tolerance(const swe::RegularGrid& g, std::size_t i, std::size_t k) {
  const bool edge = i == 0 || k == 0 || i + 1 == g.nx || k + 1 == g.ny;
  return edge ? 0.02 : 0.01;
}

// The scene built and its depths summed, walls' ghosts included, as a run has them before its
// first step.
scenario::BuiltScene summed(const scenario::Scenario& scene) {
  auto built = scenario::build(scene);
  built.simulation.refresh();
  return built;
}

}  // namespace

TEST_CASE("a map holds the particles' volume at any cell size, and no water above their surface",
          "[maps]") {
  // Thacker's bowl a little after release: a moving shoreline on a curved hillside, particles
  // of 4 cm, radii differing from particle to particle.
  auto scene = scenario::load(std::string(SWEMPS_SOURCE_DIR) + "/cases/thacker/scenario.json");
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  sim.advance_to(0.6);
  sim.refresh();
  const auto& p = sim.particles();
  const double particle_volume = p.total_fluid_volume();
  const auto& bed = *built.terrain.bed;
  const auto& d = built.terrain.domain;
  const double width = d.x_max - d.x_min, height = d.y_max - d.y_min;
  // From half a spacing to 5.5 spacings: cells finer than the particles, and coarse cells
  // that several particles share, as 82.6 m cells over 15 m particles do.
  for (double cell : {0.02, 0.04, 0.11, 0.22}) {
    INFO("cell " << cell << " m");
    const auto grid = covering(width, height, cell);
    const maps::CellAverages averages(grid, built.terrain.bed, {d.x_min, d.x_max, d.y_min, d.y_max},
                                      0.04);
    const auto f = averages.fields(p, sim.kernel());
    CHECK(mapped_volume(f, grid) == Approx(particle_volume).epsilon(1e-12));
    // Reading the bed at each share instead of keeping it (a large map) changes nothing.
    const maps::CellAverages unstored(grid, built.terrain.bed, {d.x_min, d.x_max, d.y_min, d.y_max},
                                      0.04, 0);
    CHECK(unstored.fields(p, sim.kernel()).depth == f.depth);
    // Every wet cell holds ground below the surface of some particle whose kernel reaches it.
    std::size_t wet = 0;
    for (std::size_t k = 0; k < grid.ny; ++k) {
      for (std::size_t i = 0; i < grid.nx; ++i) {
        const std::size_t c = k * grid.nx + i;
        if (!(f.depth[c] > 0.0)) {
          CHECK(std::isnan(f.u[c]));
          continue;
        }
        ++wet;
        const double x = grid.x0 + static_cast<double>(i) * grid.dx;
        const double y = grid.y0 + static_cast<double>(k) * grid.dy;
        double highest_surface = -std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < p.fluid_count(); ++j) {
          const double reach = swe::ParticleKernel::support(p.smoothing_length[j]);
          const double dx = std::max(std::abs(p.x[j] - x) - 0.5 * grid.dx, 0.0);
          const double dy = std::max(std::abs(p.y[j] - y) - 0.5 * grid.dy, 0.0);
          if (dx * dx + dy * dy < reach * reach)
            highest_surface = std::max(highest_surface, p.bed[j] + p.depth[j]);
        }
        INFO("cell " << i << ", " << k);
        CHECK(highest_surface > lowest_bed(bed, grid, i, k));
        // The surface a cell reports is a mean of those surfaces.
        CHECK(f.surface[c] <= highest_surface + 1e-12);
      }
    }
    CHECK(wet > 10);
  }
}

TEST_CASE("a map's cells read uniform water's depth, the same on any number of threads", "[maps]") {
  const auto scene = testing::parse_text(R"({
    "end_time": 1,
    "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 6},
    "water": [{"rectangle": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 6},
               "depth": 0.5, "spacing": 0.2}]
  })");
  auto built = summed(scene);
  const auto& sim = built.simulation;
  const auto& p = sim.particles();
  // Cells covering the domain, not aligned with the lattice: 2.94 x 2.73 spacings.
  const swe::RegularGrid grid{10.0 / 34.0, 6.0 / 22.0, 10.0 / 17.0, 6.0 / 11.0, 17, 11};
  const auto averages = scenario::map_reader(scene, built.terrain, grid);
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = averages.fields(p, sim.kernel());
  omp_set_num_threads(2);
  const auto two = averages.fields(p, sim.kernel());
  omp_set_num_threads(before);
  CHECK(one.depth == two.depth);  // bitwise: the shares are added in particle order
  CHECK(one.u == two.u);
  for (std::size_t k = 0; k < grid.ny; ++k) {
    for (std::size_t i = 0; i < grid.nx; ++i) {
      INFO("cell " << i << ", " << k);
      CHECK(one.depth[k * grid.nx + i] == Approx(0.5).epsilon(uniform_tolerance(grid, i, k)));
      CHECK(one.u[k * grid.nx + i] == 0.0);
    }
  }
}

TEST_CASE("a gauge reads the level of water at rest less the bed at its point", "[maps]") {
  // A lake over a sloping plane, filled to 1 m: its shore crosses the domain.
  const auto scene = testing::parse_text(R"({
    "end_time": 1,
    "domain": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 10},
    "bed": {"plane": {"slope": [0.1, 0.02]}},
    "water": [{"fill": {"rectangle": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 10}},
               "surface_elevation": 1.0, "spacing": 0.25}],
    "output": {"grid": {"spacing": 1.0}}
  })");
  auto built = summed(scene);
  const auto& sim = built.simulation;
  const auto& p = sim.particles();
  const auto grid = scenario::output_grid(scene, built.terrain);
  for (const scenario::Point point :
       {scenario::Point{2.1, 5.3}, scenario::Point{5.0, 2.0}, scenario::Point{8.4, 6.6}}) {
    INFO("gauge at " << point[0] << ", " << point[1]);
    const auto gauge = scenario::gauge_reader(scene, built.terrain, grid, point);
    const auto f = gauge.fields(p, sim.kernel());
    REQUIRE(f.surface.size() == 1);
    // Balanced volumes put every particle's surface at the level within the balancing's
    // tolerance.
    const double bed = built.terrain.bed->elevation(point[0], point[1]);
    CHECK(f.surface.front() == Approx(1.0).margin(2e-3));
    // The level of the cell's water: its depth reads the uniform water's within the
    // quadrature's 1 % (uniform_tolerance), so the level is as near 1 m as 1 % of the depth;
    // in the shore cell at (8.4, 6.6), a third of it dry, 2.8 mm (measured) below.
    const double level = gauge.level(0, f.depth.front());
    CHECK(level == Approx(1.0).margin(std::max(0.01 * (1.0 - bed), 4e-3)));
  }
  // Far up the slope, where the ground stands above the lake: no water.
  const auto dry = scenario::gauge_reader(scene, built.terrain, grid, {18.0, 5.0});
  CHECK(dry.fields(p, sim.kernel()).depth.front() == 0.0);
}

TEST_CASE("a gauge reads the depth of water flowing down a slope, not the higher surfaces",
          "[maps]") {
  // Water 0.5 m deep over a plane falling 5 % in x, moving down it: uniform flow, as far as
  // the maps can tell. Particles up-slope send more of their water down-slope into a cell
  // than those down-slope send up, so the mean of the particles' surfaces in the cell leans
  // up-slope; the level of the cell's water does not.
  const auto scene = testing::parse_text(R"({
    "end_time": 1,
    "domain": {"x_min": 0, "x_max": 100, "y_min": 0, "y_max": 40},
    "bed": {"plane": {"slope": [-0.05, 0]}},
    "water": [{"rectangle": {"x_min": 0, "x_max": 100, "y_min": 0, "y_max": 40},
               "depth": 0.5, "spacing": 2.0, "velocity": [1, 0]}],
    "output": {"grid": {"spacing": 8.0}}
  })");
  auto built = summed(scene);
  const auto& sim = built.simulation;
  const auto grid = scenario::output_grid(scene, built.terrain);
  const scenario::Point point{50.0, 20.0};
  const auto gauge = scenario::gauge_reader(scene, built.terrain, grid, point);
  const auto f = gauge.fields(sim.particles(), sim.kernel());
  const double bed = built.terrain.bed->elevation(point[0], point[1]);
  const double depth = gauge.level(0, f.depth.front()) - bed;
  // Within the quadrature's 1 % of the depth (uniform_tolerance).
  CHECK(depth == Approx(0.5).epsilon(0.01));
  // The guard: the particles' mean surface reads deeper (measured +2.1 % here, on the
  // starting lattice; +20 % in a uniform flow down a 1.5 % slope at 20 m spacing).
  CHECK(f.surface.front() - bed > 0.5 * 1.015);
  INFO("level depth " << depth);
}

TEST_CASE("no share of a particle's water falls behind a wall", "[maps]") {
  // Water on the west side of a wall across the middle of the domain, dry land east of it.
  // The wall stands off the cell edges, so a column of cells astride it holds both sides.
  const auto scene = testing::parse_text(R"({
    "end_time": 1,
    "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 6},
    "walls": [{"polyline": [[5.2, -1], [5.2, 7]]}],
    "water": [{"rectangle": {"x_min": 0, "x_max": 5.2, "y_min": 0, "y_max": 6},
               "depth": 0.5, "spacing": 0.2}]
  })");
  auto built = summed(scene);
  const auto& sim = built.simulation;
  const auto& p = sim.particles();
  REQUIRE(p.size() > p.fluid_count());  // the wall's ghosts are in
  // Cells of 2.27 spacings; a sub-point row of the map (3 a cell) lies at a tenth of a
  // spacing from the wall: no sub-point stands on it, where its share would count on both
  // sides.
  const double dx = 10.0 / 22.0;
  const swe::RegularGrid grid{0.5 * dx, 0.25, dx, 0.5, 22, 12};
  const auto f = scenario::map_reader(scene, built.terrain, grid).fields(p, sim.kernel());
  CHECK(mapped_volume(f, grid) == Approx(p.total_fluid_volume()).epsilon(1e-12));
  // The wall lies in column 11. Within a sub-point spacing of it the quadrature moves some of
  // the water between column 11 and its western neighbour, so those two are checked together.
  const std::size_t astride = 11;
  for (std::size_t k = 0; k < grid.ny; ++k) {
    for (std::size_t i = 0; i < grid.nx; ++i) {
      INFO("cell " << i << ", " << k);
      const double depth = f.depth[k * grid.nx + i];
      if (i > astride) {
        CHECK(depth == 0.0);  // wholly behind the wall
      } else if (i + 1 < astride) {
        // In front, away from the wall: uniform.
        CHECK(depth == Approx(0.5).epsilon(uniform_tolerance(grid, i, k)));
      }
    }
    // The two columns at the wall hold the water in front of it.
    const double west_edge = static_cast<double>(astride - 1) * grid.dx;
    const double pair =
        (f.depth[k * grid.nx + astride - 1] + f.depth[k * grid.nx + astride]) * grid.dx;
    INFO("row " << k);
    CHECK(pair == Approx(0.5 * (5.2 - west_edge)).epsilon(uniform_tolerance(grid, 1, k)));
  }
}

TEST_CASE("a map resolves its cells, or its particles where cells are finer", "[maps]") {
  const maps::Bounds domain{0.0, 4.0, 0.0, 2.0};
  // Cells 0.1 by 0.2 m: the narrower side is what a cell resolves.
  const swe::RegularGrid grid{0.05, 0.1, 0.1, 0.2, 40, 10};
  CHECK(maps::CellAverages(grid, nullptr, domain, 0.04).resolved_length_m() == 0.1);
  CHECK(maps::CellAverages(grid, nullptr, domain, 0.25).resolved_length_m() == 0.25);
  CHECK(maps::CellAverages(grid, nullptr, domain, 0.0).resolved_length_m() == 0.1);
}
