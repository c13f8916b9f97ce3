#pragma once
// How a body of water starts besides its still depth: the rise of its surface above the still
// level (a solitary wave or a displacement raster) and its velocity (uniform, from rasters,
// plus a solitary wave's own). Internal to the scenario module: build.cpp asks it at each
// lattice point it seeds.

#include <array>
#include <cstddef>
#include <memory>
#include <optional>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/tsunami/solitary_wave.hpp"

namespace swemps::scenario {

class StartingSurface {
 public:
  // Body `index` of the scene, with the rasters read_terrain() read for it. Throws
  // ScenarioError at /water/<index>/solitary_wave when the still water under a solitary wave's
  // crest is no deeper than the wave is high (or dry).
  StartingSurface(const Scenario& scene, const Terrain& terrain, std::size_t index);

  // The surface's rise at (x, y) above the body's still level, m; 0 off a raster or on its
  // nodata.
  double rise(double x_m, double y_m) const;
  // The starting velocity (u, v) at (x, y), m/s.
  std::array<double, 2> velocity(double x_m, double y_m) const;

 private:
  std::optional<tsunami::SolitaryWave> wave_;
  std::shared_ptr<const terrain::GriddedField> displacement_, u_, v_;
  std::array<double, 2> uniform_velocity_m_s_{0.0, 0.0};
};

}  // namespace swemps::scenario
