#pragma once
// Buildings from vector files (docs/buildings.md): read into the scene's CRS, then either
// closed walls the water flows around, or the bed raised under their footprints. Internal to
// the scenario module: read_terrain raises the bed, build adds the walls.

#include <memory>
#include <string>
#include <vector>

#include "swemps/boundaries/wall_index.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/terrain/footprints.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace swemps::scenario {

// What the scene's building files hold, read.
struct BuildingSet {
  const BuildingsSpec* spec = nullptr;
  terrain::Footprints footprints;
  std::string layer;                             // the layer read
  std::size_t not_polygons = 0, degenerate = 0;  // features left out
};

// Reads every building file of the scene into `scene_crs_wkt` (empty: local metres);
// ScenarioError at the file's key for a file that cannot be read or placed.
std::vector<BuildingSet> read_buildings(const Scenario& scene, const std::string& scene_crs_wkt);

// The bed raised under the footprints of every set the scene raises into the bed; the bed as
// it is when there is none. ScenarioError when a set is to be raised into a bed that is not a
// raster (raster_key names the bed's key), or when not one of its footprints covers a cell.
terrain::GriddedField raise_buildings(const std::vector<BuildingSet>& sets,
                                      const terrain::GriddedField& bed);

// The footprints of the sets that are walls, all together (empty when there is none): no
// water is seeded and no rain falls under them.
std::shared_ptr<const terrain::Footprints> wall_footprints(const std::vector<BuildingSet>& sets);

// The polygons output.pathlines chooses its particles in (its own polygon, or those of its
// file read into `scene_crs_wkt`); null when it gives none. ScenarioError at the file's key
// for a file that cannot be read or placed.
std::shared_ptr<const terrain::Footprints> pathline_area(const PathlineOutput& pathlines,
                                                         const std::string& scene_crs_wkt);

// Every ring of the sets that are walls, closed, as wall segments.
std::vector<boundaries::WallSegment> building_walls(const std::vector<BuildingSet>& sets);

}  // namespace swemps::scenario
