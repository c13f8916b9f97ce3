#include "buildings.hpp"

#include <memory>
#include <stdexcept>
#include <utility>

#include "swemps/io/vector_reader.hpp"

namespace swemps::scenario {

namespace {

// The polygons of a file the scene names at `key_path`, into `scene_crs_wkt`; ScenarioError at
// its "file" key when it cannot be read or placed.
io::PolygonLayer read_polygon_file(const PolygonFileSpec& spec, const std::string& purpose,
                                   const std::string& scene_crs_wkt) {
  io::VectorRequest request;
  request.path = spec.file;
  request.layer = spec.layer;
  request.purpose = purpose;
  request.scene_crs = scene_crs_wkt;
  request.scene_crs_name = "the scene's CRS";
  request.file_crs = spec.crs;
  request.file_crs_setting = spec.key_path + "/crs";
  request.reproject = spec.reproject;
  request.reproject_setting = spec.key_path + "/reproject";
  try {
    return io::read_polygons(request);
  } catch (const std::exception& e) {
    throw ScenarioError(spec.key_path + "/file", e.what(),
                        "a vector file of polygons GDAL can read, in the scene's CRS (or with "
                        "\"reproject\": true)");
  }
}

}  // namespace

std::vector<BuildingSet> read_buildings(const Scenario& scene, const std::string& scene_crs_wkt) {
  std::vector<BuildingSet> sets;
  for (const BuildingsSpec& spec : scene.buildings) {
    const PolygonFileSpec file{spec.key_path, spec.file, spec.layer, spec.crs, spec.reproject};
    io::PolygonLayer layer = read_polygon_file(file, "building file", scene_crs_wkt);
    sets.push_back({&spec, terrain::Footprints(std::move(layer.polygons)), layer.layer,
                    layer.not_polygons, layer.degenerate});
  }
  return sets;
}

std::shared_ptr<const terrain::Footprints> pathline_area(const PathlineOutput& pathlines,
                                                         const std::string& scene_crs_wkt) {
  if (pathlines.polygon_file) {
    io::PolygonLayer layer =
        read_polygon_file(*pathlines.polygon_file, "pathline polygon file", scene_crs_wkt);
    return std::make_shared<const terrain::Footprints>(std::move(layer.polygons));
  }
  if (pathlines.polygon.empty()) return nullptr;
  terrain::Footprint footprint;
  for (const Point& vertex : pathlines.polygon) footprint.outer.push_back({vertex[0], vertex[1]});
  return std::make_shared<const terrain::Footprints>(std::vector<terrain::Footprint>{footprint});
}

terrain::GriddedField raise_buildings(const std::vector<BuildingSet>& sets,
                                      const terrain::GriddedField& bed) {
  terrain::GriddedField raised = bed;
  for (const BuildingSet& set : sets) {
    if (set.spec->as != BuildingsSpec::As::bed) continue;
    auto result = terrain::raise_footprints(raised, set.footprints, set.spec->height_m);
    if (result.cells_raised == 0) {
      throw ScenarioError(set.spec->key_path + "/as",
                          "\"bed\", but not one of the " + std::to_string(set.footprints.size()) +
                              " footprints covers a cell centre of the bed raster",
                          "footprints over the bed raster and larger than its cells (or \"as\": "
                          "\"walls\", which any footprint makes)");
    }
    raised = std::move(result.field);
  }
  return raised;
}

std::shared_ptr<const terrain::Footprints> wall_footprints(const std::vector<BuildingSet>& sets) {
  std::vector<terrain::Footprint> all;
  for (const BuildingSet& set : sets) {
    if (set.spec->as != BuildingsSpec::As::walls) continue;
    const auto& f = set.footprints.footprints();
    all.insert(all.end(), f.begin(), f.end());
  }
  if (all.empty()) return nullptr;
  return std::make_shared<const terrain::Footprints>(std::move(all));
}

std::vector<boundaries::WallSegment> building_walls(const std::vector<BuildingSet>& sets) {
  std::vector<boundaries::WallSegment> segments;
  const auto add_ring = [&](const terrain::Ring& ring, boundaries::WallCondition condition) {
    for (std::size_t k = 0; k < ring.size(); ++k) {
      segments.push_back({ring[k], ring[(k + 1) % ring.size()], condition});
    }
  };
  for (const BuildingSet& set : sets) {
    if (set.spec->as != BuildingsSpec::As::walls) continue;
    const auto condition = set.spec->condition == WallCondition::slip
                               ? boundaries::WallCondition::slip
                               : boundaries::WallCondition::no_slip;
    for (const auto& f : set.footprints.footprints()) {
      add_ring(f.outer, condition);
      for (const auto& hole : f.holes) add_ring(hole, condition);
    }
  }
  return segments;
}

}  // namespace swemps::scenario
