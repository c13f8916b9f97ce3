#pragma once
// Building footprints (and any other obstacle drawn as a polygon): polygons with holes in the
// scene's CRS, filed by the cells of a grid so that "is this point under a building?" reads a
// cell's few polygons rather than every one of a town's thousands. Reading them from a
// vector file is the io module's job (io/vector_reader.hpp); what they become (walls, or a
// raised bed) is the scene's choice (docs/buildings.md).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "swemps/neighbors/box_grid.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace swemps::terrain {

using Ring = std::vector<std::array<double, 2>>;  // open: the last vertex is not the first

struct Footprint {
  Ring outer;               // >= 3 vertices
  std::vector<Ring> holes;  // courtyards: not under the building
};

class Footprints {
 public:
  Footprints() = default;
  // Throws std::invalid_argument for a ring of fewer than 3 vertices or a non-finite one.
  explicit Footprints(std::vector<Footprint> footprints);

  bool empty() const { return footprints_.empty(); }
  std::size_t size() const { return footprints_.size(); }
  const std::vector<Footprint>& footprints() const { return footprints_; }

  // True if (x, y) lies inside a footprint's outer ring and outside its holes (even-odd; a
  // point exactly on an edge may fall either way).
  bool contains(double x, double y) const;
  // The index of the footprint holding (x, y), or -1.
  std::int64_t footprint_at(double x, double y) const;

 private:
  std::vector<Footprint> footprints_;
  std::vector<neighbors::BoxGrid::Box> boxes_;  // per footprint
  neighbors::BoxGrid grid_;
};

// True if (x, y) lies inside the ring (even-odd rule).
bool ring_contains(const Ring& ring, double x, double y);

// A field with every cell whose centre lies under a footprint raised by height_m (nodata
// stays nodata). `cells_raised` counts the cells; `footprints_missed` the footprints that
// hold no cell centre, too small for the raster to show them.
struct RaisedBed {
  GriddedField field;
  std::size_t cells_raised = 0, footprints_missed = 0;
};
RaisedBed raise_footprints(const GriddedField& bed, const Footprints& footprints, double height_m);

}  // namespace swemps::terrain
