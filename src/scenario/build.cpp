#include "swemps/scenario/build.hpp"

#include <cmath>

#include "swemps/boundaries/domain_outflow.hpp"
#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/particles/seeding.hpp"

namespace swemps::scenario {

namespace {

particles::SweParticles seed_water(const std::vector<WaterBody>& water) {
  particles::SweParticles p;
  for (const auto& body : water) {
    const auto lattice = particles::fill_polygon(body.polygon, body.spacing_m);
    // Each particle carries the water of its lattice cell: the scene's volume exactly.
    const double volume = body.depth_m * lattice.cell_area_m2;
    for (const auto& point : lattice.points) {
      p.add_fluid(point[0], point[1], body.velocity_m_s[0], body.velocity_m_s[1], volume,
                  body.depth_m, lattice.cell_area_m2, 0.0);
    }
  }
  return p;
}

boundaries::GhostWalls make_walls(const std::vector<Wall>& walls) {
  std::vector<boundaries::WallSegment> segments;
  for (const auto& wall : walls) {
    const auto condition = wall.condition == WallCondition::slip
                               ? boundaries::WallCondition::slip
                               : boundaries::WallCondition::no_slip;
    for (std::size_t k = 0; k + 1 < wall.polyline.size(); ++k) {
      segments.push_back({wall.polyline[k], wall.polyline[k + 1], condition});
    }
  }
  return boundaries::GhostWalls(std::move(segments));
}

}  // namespace

swe::Simulation make_simulation(const Scenario& scene) {
  std::vector<std::unique_ptr<swe::Effect>> effects;
  const auto& d = scene.domain;
  effects.push_back(std::make_unique<boundaries::DomainOutflow>(
      boundaries::Box{d.x_min, d.x_max, d.y_min, d.y_max}));
  return swe::Simulation(seed_water(scene.water), scene.numerics, make_walls(scene.walls),
                         std::move(effects));
}

swe::RegularGrid output_grid(const Scenario& scene) {
  const auto& g = scene.output.grid;
  const double width = g.bounds.x_max - g.bounds.x_min;
  const double height = g.bounds.y_max - g.bounds.y_min;
  const auto nx = static_cast<std::size_t>(std::max(1.0, std::round(width / g.spacing_m)));
  const auto ny = static_cast<std::size_t>(std::max(1.0, std::round(height / g.spacing_m)));
  const double dx = width / static_cast<double>(nx);
  const double dy = height / static_cast<double>(ny);
  return {g.bounds.x_min + 0.5 * dx, g.bounds.y_min + 0.5 * dy, dx, dy, nx, ny};
}

}  // namespace swemps::scenario
