#pragma once
// From a validated Scenario to the objects that run it: the rasters read and the domain
// settled (the terrain), the particles, the walls, the effects the scene asks for, the output
// grid. Files are read here, through io; the solver gets plain objects.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swemps/boundaries/wall_index.hpp"
#include "swemps/maps/cell_averages.hpp"
#include "swemps/ns/simulation.hpp"
#include "swemps/ns/tank.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/bed.hpp"
#include "swemps/swe/operators.hpp"
#include "swemps/swe/simulation.hpp"
#include "swemps/terrain/footprints.hpp"
#include "swemps/terrain/gridded_field.hpp"
#include "swemps/tsunami/okada.hpp"

namespace swemps::scenario {

// What the scene's files say about the ground, with the domain they settle.
struct Terrain {
  Rectangle domain;                                         // as given, or the bed raster's extent
  std::shared_ptr<const swe::BedSource> bed;                // null: flat at z = 0
  // With a fault source: `bed` is the floor after the rupture, and this the one before it
  // (null: flat at z = 0), over which the water's still depth is measured.
  std::shared_ptr<const swe::BedSource> bed_before_rupture;
  std::shared_ptr<const tsunami::FaultSource> fault_source;  // null: none
  std::shared_ptr<const terrain::GriddedField> bed_raster;  // raster beds only: the surface
  // A raster bed's natural cells: the file's own, or those its warp to the scene's CRS lands
  // on. bed_raster splits each of them bed_refinement x bed_refinement times.
  terrain::GridGeometry bed_cells;
  std::size_t bed_refinement = 1;
  std::shared_ptr<const terrain::GriddedField> roughness;  // Manning's n map only
  // Per water body, the depth raster it names; null for the other bodies.
  std::vector<std::shared_ptr<const terrain::GriddedField>> water_depth;
  // Per water body, the rasters of its surface's starting rise and of its starting velocity's
  // east and north components; null where it names none.
  std::vector<std::shared_ptr<const terrain::GriddedField>> displacement, velocity_u, velocity_v;
  std::string crs_wkt;  // the scene's CRS (the bed raster's, or another raster's); empty: none
  // Buildings that are walls: their footprints (null: none), under which no water is seeded
  // and no rain falls, and their rings as wall segments.
  std::shared_ptr<const terrain::Footprints> building_footprints;
  std::vector<boundaries::WallSegment> building_walls;
  // Per building file, what it held, for reports.
  struct BuildingsRead {
    std::string key_path, layer;
    std::size_t footprints = 0, not_polygons = 0, degenerate = 0;
  };
  std::vector<BuildingsRead> buildings;
  // The polygons output.pathlines chooses its particles in, in the scene's CRS; null: none.
  std::shared_ptr<const terrain::Footprints> pathline_area;
  // Per rain (scene.rain), the maps it names, in the scene's CRS and the scene's units (mm/h,
  // mm, ...): its rate, one map or a series of them with the start of each in seconds of the
  // run, the last until rate_end_s; and its loss parameters by their keys in the rain
  // ("initial_loss_mm", "green_ampt/suction_mm"). No rate maps: the rain's rate is a series.
  struct RainMaps {
    std::vector<double> rate_starts_s;
    std::vector<std::shared_ptr<const terrain::GriddedField>> rate_mm_h;
    double rate_end_s = 0.0;
    std::map<std::string, std::shared_ptr<const terrain::GriddedField>> parameters;
  };
  std::vector<RainMaps> rain;
};

// Reads the rasters the scene names, warped to the scene's CRS, and settles the domain:
// the bed raster's extent when the file gives none, which also completes the checks that
// need the domain (check_within_domain). Throws ScenarioError at the key that named the file
// for a raster that cannot be read, does not cover the domain, has nodata inside it, or (for
// Manning's n) holds a value that is not > 0 there.
Terrain read_terrain(const Scenario& scene);

// How the starting particles got their volumes.
struct StartingVolumes {
  // V = depth x lattice cell area, summed over all particles (the volume before balancing).
  double geometric_m3 = 0.0;
  // Whether some water's depth came from the terrain (a level surface or a depth raster).
  bool from_terrain = false;
  // When the scene balances its volumes: what balancing did, and the depth tolerance it had.
  std::optional<swe::VolumeBalanceReport> balance;
  double balance_tolerance_m = 0.0;
};

struct BuiltScene {
  Terrain terrain;
  swe::Simulation simulation;
  StartingVolumes volumes;
};

// The scene ready to run: terrain read, particles seeded (and balanced, if asked), effects in
// place. Throws ScenarioError for what only the files or the seeding can reveal.
BuiltScene build(const Scenario& scene);

// build(scene).simulation, for callers that need nothing else.
swe::Simulation make_simulation(const Scenario& scene);

// The output grid: the bed raster's natural cells (Terrain::bed_cells) that lie whole inside the
// grid bounds when the scene gives a raster bed and no grid spacing; otherwise cell centres
// covering the bounds at the requested spacing. Bounds default to the domain. Throws ScenarioError
// when no raster cell lies whole inside the bounds.
swe::RegularGrid output_grid(const Scenario& scene, const Terrain& terrain);

// The smallest spacing the scene creates particles at (water bodies, inflows and rain); 0 when it
// creates none.
double finest_spacing(const Scenario& scene);

// How the scene's maps read its particles on `grid`: cell averages of the particles' water
// over the scene's bed, within the domain, sampled finely enough for the finest spacing the
// scene creates particles at.
maps::CellAverages map_reader(const Scenario& scene, const Terrain& terrain,
                              const swe::RegularGrid& grid);

// How a gauge at `point` reads the particles: the cell averages of one cell centred on it, as
// wide as a cell of `grid` but at most kGaugeSpacings of the finest particle spacing, so that
// the water surface it reads is an average over several particles, as a grid model's gauge
// reads its cell. The depth at the gauge is the level of the water in that cell
// (CellAverages::level) less the bed at the point.
maps::CellAverages gauge_reader(const Scenario& scene, const Terrain& terrain,
                                const swe::RegularGrid& grid, const Point& point);
inline constexpr double kGaugeSpacings = 4.0;
inline constexpr double kGaugeLeastSpacings = 2.0;
inline constexpr double kGaugeSubPointsPerSpacing = 8.0;

// Model ns. The tank: the domain's plan (its x range; and y range in 3D) from the floor (the
// level bed's elevation, 0 without a bed) up to ns.tank_height; each water body a box from
// the floor up to its depth over the same ranges (in 2D only its x range); solid layers
// enough to fill either kernel's support, ceil(support / l_0). The scene must pass
// check_ns_scene (throws ScenarioError otherwise). Dim is the scene's dimension.
template <int Dim>
ns::TankSpec<Dim> ns_tank(const Scenario& scene);

// The Navier-Stokes run of the scene: the tank filled (ns::fill_tank) and the simulation
// built with the tank's box, solid layers included, as the bounds fluid may not leave.
// Throws ScenarioError at the key to blame for a tank the lattice cannot fill, water holding
// no lattice node, or settings the solver refuses; std::invalid_argument when Dim is not the
// scene's dimension.
template <int Dim>
ns::Simulation<Dim> make_ns_simulation(const Scenario& scene);

extern template ns::TankSpec<2> ns_tank<2>(const Scenario&);
extern template ns::TankSpec<3> ns_tank<3>(const Scenario&);
extern template ns::Simulation<2> make_ns_simulation<2>(const Scenario&);
extern template ns::Simulation<3> make_ns_simulation<3>(const Scenario&);

}  // namespace swemps::scenario
