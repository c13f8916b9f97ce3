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
  if (footprints_.empty()) return;
  double x_min = INFINITY, y_min = INFINITY, x_max = -INFINITY, y_max = -INFINITY;
  double total_side = 0.0;
  boxes_.reserve(footprints_.size());
  for (const auto& f : footprints_) {
    check_ring(f.outer);
    for (const auto& hole : f.holes) check_ring(hole);
    std::array<double, 4> box{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const auto& p : f.outer) {
      box = {std::min(box[0], p[0]), std::min(box[1], p[1]), std::max(box[2], p[0]),
             std::max(box[3], p[1])};
    }
    boxes_.push_back(box);
    total_side += std::max(box[2] - box[0], box[3] - box[1]);
    x_min = std::min(x_min, box[0]);
    y_min = std::min(y_min, box[1]);
    x_max = std::max(x_max, box[2]);
    y_max = std::max(y_max, box[3]);
  }
  // Cells about a footprint's size: a point meets one or two polygons. At most 16 cells per
  // footprint (and 4096 in all), so that a few footprints far apart make no huge grid.
  const double width = x_max - x_min, height = y_max - y_min;
  const double max_cells =
      static_cast<double>(std::max<std::size_t>(4096, 16 * footprints_.size()));
  cell_ = total_side / static_cast<double>(footprints_.size());
  cell_ = std::max({cell_, std::sqrt(std::max(width, 1e-9) * std::max(height, 1e-9) / max_cells),
                    width / max_cells, height / max_cells, 1e-9});
  x0_ = x_min;
  y0_ = y_min;
  nx_ = static_cast<std::size_t>(std::floor(width / cell_)) + 1;
  ny_ = static_cast<std::size_t>(std::floor(height / cell_)) + 1;
  const auto index = [&](double v, double origin, std::size_t count) {
    const double k = std::floor((v - origin) / cell_);
    return std::min(count - 1, static_cast<std::size_t>(std::max(k, 0.0)));
  };
  const auto for_each_cell = [&](const std::array<double, 4>& box, auto&& f) {
    for (std::size_t j = index(box[1], y0_, ny_); j <= index(box[3], y0_, ny_); ++j) {
      for (std::size_t i = index(box[0], x0_, nx_); i <= index(box[2], x0_, nx_); ++i) {
        f(j * nx_ + i);
      }
    }
  };
  start_.assign(nx_ * ny_ + 1, 0);
  for (const auto& box : boxes_) for_each_cell(box, [&](std::size_t c) { ++start_[c + 1]; });
  for (std::size_t c = 0; c < nx_ * ny_; ++c) start_[c + 1] += start_[c];
  ids_.resize(start_.back());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (std::uint32_t k = 0; k < boxes_.size(); ++k) {
    for_each_cell(boxes_[k], [&](std::size_t c) { ids_[next[c]++] = k; });
  }
}

std::int64_t Footprints::footprint_at(double x, double y) const {
  if (footprints_.empty() || !(x >= x0_) || !(y >= y0_)) return -1;
  const double i = std::floor((x - x0_) / cell_), j = std::floor((y - y0_) / cell_);
  if (i >= static_cast<double>(nx_) || j >= static_cast<double>(ny_)) return -1;
  const std::size_t c = static_cast<std::size_t>(j) * nx_ + static_cast<std::size_t>(i);
  for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
    const std::uint32_t id = ids_[k];
    const auto& b = boxes_[id];
    if (x < b[0] || x > b[2] || y < b[1] || y > b[3]) continue;
    if (footprint_contains(footprints_[id], x, y)) return id;
  }
  return -1;
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
