#include "swemps/terrain/footprints.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace swemps::terrain {

bool ring_contains(const Ring& ring, double x, double y) {
  // Even-odd: count the edges a ray to +x crosses.
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const auto& a = ring[i];
    const auto& b = ring[j];
    if ((a[1] > y) != (b[1] > y) && x < a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1])) {
      inside = !inside;
    }
  }
  return inside;
}

namespace {

bool footprint_contains(const Footprint& f, double x, double y) {
  if (!ring_contains(f.outer, x, y)) return false;
  return std::none_of(f.holes.begin(), f.holes.end(),
                      [&](const Ring& hole) { return ring_contains(hole, x, y); });
}

void check_ring(const Ring& ring) {
  if (ring.size() < 3) throw std::invalid_argument("footprint ring of fewer than 3 vertices");
  for (const auto& p : ring) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1])) {
      throw std::invalid_argument("footprint ring with a non-finite vertex");
    }
  }
}

}  // namespace

Footprints::Footprints(std::vector<Footprint> footprints) : footprints_(std::move(footprints)) {
  double total_side = 0.0;
  boxes_.reserve(footprints_.size());
  for (const auto& f : footprints_) {
    check_ring(f.outer);
    for (const auto& hole : f.holes) check_ring(hole);
    neighbors::BoxGrid::Box box{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const auto& p : f.outer) {
      box = {std::min(box[0], p[0]), std::min(box[1], p[1]), std::max(box[2], p[0]),
             std::max(box[3], p[1])};
    }
    boxes_.push_back(box);
    total_side += std::max(box[2] - box[0], box[3] - box[1]);
  }
  // Cells about a footprint's size: a point meets one or two polygons.
  if (!footprints_.empty()) {
    grid_ = neighbors::BoxGrid(boxes_, total_side / static_cast<double>(footprints_.size()));
  }
}

std::int64_t Footprints::footprint_at(double x, double y) const {
  std::int64_t found = -1;
  grid_.for_each_candidate(x, y, x, y, [&](std::uint32_t id) {
    if (found >= 0) return;
    const auto& b = boxes_[id];
    if (x < b[0] || x > b[2] || y < b[1] || y > b[3]) return;
    if (footprint_contains(footprints_[id], x, y)) found = id;
  });
  return found;
}

bool Footprints::contains(double x, double y) const { return footprint_at(x, y) >= 0; }

RaisedBed raise_footprints(const GriddedField& bed, const Footprints& footprints, double height_m) {
  const GridGeometry& g = bed.geometry();
  std::vector<double> values = bed.values();
  std::vector<std::uint8_t> hit(footprints.size(), 0);
  std::size_t raised = 0;
  for (std::size_t row = 0; row < g.rows; ++row) {
    const double y = g.cell_centre_y(row);
    for (std::size_t col = 0; col < g.columns; ++col) {
      const std::int64_t f = footprints.footprint_at(g.cell_centre_x(col), y);
      if (f < 0) continue;
      hit[static_cast<std::size_t>(f)] = 1;
      double& z = values[row * g.columns + col];
      if (std::isnan(z)) continue;
      z += height_m;
      ++raised;
    }
  }
  const auto missed = static_cast<std::size_t>(std::count(hit.begin(), hit.end(), 0));
  return {GriddedField(g, std::move(values), bed.crs_wkt(), bed.name()), raised, missed};
}

}  // namespace swemps::terrain
