#include "swemps/scenario/build.hpp"

#include <cmath>
#include <memory>
#include <variant>

#include "swemps/boundaries/domain_outflow.hpp"
#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/particles/seeding.hpp"
#include "swemps/splitting/particle_splitting.hpp"
#include "swemps/swe/bed_slope.hpp"
#include "swemps/swe/manning_friction.hpp"

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

// The bed as a source of z_b, or none when the scene names no bed (flat at z = 0).
std::shared_ptr<const swe::BedSource> make_bed(const BedSpec& spec) {
  if (const auto* plane = std::get_if<PlaneBedSpec>(&spec)) {
    return std::make_shared<swe::PlaneBed>(plane->elevation_m, plane->slope, plane->origin_m);
  }
  if (const auto* profile = std::get_if<ProfileBedSpec>(&spec)) {
    return std::make_shared<swe::ProfileBed>(profile->points);
  }
  return nullptr;
}

}  // namespace

swe::Simulation make_simulation(const Scenario& scene) {
  auto walls = make_walls(scene.walls);
  // Effects in the order they act within their stage.
  std::vector<std::unique_ptr<swe::Effect>> effects;
  if (scene.splitting) {
    effects.push_back(std::make_unique<splitting::ParticleSplitting>(
        *scene.splitting,
        std::vector<boundaries::WallSegment>(walls.segments().begin(), walls.segments().end())));
  }
  const auto bed = make_bed(scene.bed);
  // A level bed exerts no force: its elevation is set once on the particles (and inherited
  // by daughters), and no effect runs.
  const auto* plane = std::get_if<PlaneBedSpec>(&scene.bed);
  const bool level = plane && plane->slope[0] == 0.0 && plane->slope[1] == 0.0;
  if (bed && !level)
    effects.push_back(std::make_unique<swe::BedSlope>(bed, scene.numerics.gradient));
  if (scene.manning_n) {
    effects.push_back(std::make_unique<swe::ManningFriction>(*scene.manning_n));
  }
  const auto& d = scene.domain;
  effects.push_back(std::make_unique<boundaries::DomainOutflow>(
      boundaries::Box{d.x_min, d.x_max, d.y_min, d.y_max}));
  auto particles = seed_water(scene.water);
  // The initial particles stand on the bed too (written with the first output).
  if (bed) {
    for (std::size_t i = 0; i < particles.fluid_count(); ++i) {
      particles.bed[i] = bed->elevation(particles.x[i], particles.y[i]);
    }
  }
  return swe::Simulation(std::move(particles), scene.numerics, std::move(walls),
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
