#pragma once
// The effects a scene's boundary lines ask for: inflow lines with their hydrographs, outflow
// lines, and sea boundaries. Internal to the scenario module: build.cpp adds them to the
// simulation in their order within the topology stage.

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "swemps/particles/swe_particles.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::scenario {

// Relative slack for comparing map coordinates: coordinates in the millions (projected maps)
// must not fail a comparison by a rounding error; at least 1e-9 m elsewhere.
double slack_for(const Rectangle& r);

// The points of a series the scene gives in the file or names as a CSV file, the file read now
// by `read_csv`; a file it cannot read is a ScenarioError at `csv_path`, expecting `expected`.
using SeriesPoints = std::vector<std::array<double, 2>>;
SeriesPoints series_points(const std::variant<SeriesPoints, std::filesystem::path>& source,
                           SeriesPoints (*read_csv)(const std::filesystem::path&),
                           const std::string& csv_path, const std::string& expected);

// Inflow `index` of the scene (its hydrograph file read now); ScenarioError at its key.
// `label`: the provenance label of the water it lets in (provenance_label()).
std::unique_ptr<swe::Effect> make_inflow(const Inflow& in, std::size_t index,
                                         const Terrain& terrain, std::uint32_t label);
std::unique_ptr<swe::Effect> make_outflow(const std::vector<Outflow>& outflows);
// Sea boundary `index`, facing away from the domain's centre, its buffer mirrored at an end
// that lies on one of `walls`. An open boundary
// without a given level takes the mean surface of the starting water within two spacings of its
// line (`seeded`, before any balancing); ScenarioError at its key when there is none.
std::unique_ptr<swe::Effect> make_sea_boundary(const SeaBoundarySpec& spec, std::size_t index,
                                               const Terrain& terrain,
                                               const std::vector<Wall>& walls,
                                               const particles::SweParticles& seeded,
                                               std::uint32_t label);

}  // namespace swemps::scenario
