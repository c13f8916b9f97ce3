#include "swemps/boundaries/outflow_line.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "swemps/boundaries/particle_removal.hpp"
#include "swemps/neighbors/parallel.hpp"

namespace swemps::boundaries {

namespace {

using Vec = std::array<double, 2>;

// Which side of the line a -> b the point p lies on: +1 left, -1 right, 0 on it.
int side(Vec a, Vec b, Vec p) {
  const double c = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
  return (c > 0.0) - (c < 0.0);
}

// For p on the line through a and b: whether it lies between them (ends included).
bool within(Vec a, Vec b, Vec p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
         std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

bool finite(Vec p) { return std::isfinite(p[0]) && std::isfinite(p[1]); }

}  // namespace

OutflowLines::OutflowLines(std::vector<Polyline> polylines) {
  if (polylines.empty()) throw std::invalid_argument("outflow lines: none given");
  for (std::size_t k = 0; k < polylines.size(); ++k) {
    const Polyline& line = polylines[k];
    const std::string who = "outflow line " + std::to_string(k + 1) + ": ";
    if (line.size() < 2) throw std::invalid_argument(who + "needs at least two points");
    for (std::size_t j = 0; j < line.size(); ++j) {
      const std::string point = "point " + std::to_string(j + 1);
      if (!finite(line[j])) throw std::invalid_argument(who + point + " is not finite");
      if (j > 0 && line[j] == line[j - 1]) {
        throw std::invalid_argument(who + point + " repeats the one before (zero-length segment)");
      }
      if (j == 0) continue;
      const Vec a = line[j - 1], b = line[j];
      segments_.push_back({a, b, std::min(a[0], b[0]), std::max(a[0], b[0]), std::min(a[1], b[1]),
                           std::max(a[1], b[1])});
    }
  }
}

bool OutflowLines::touches(Vec a, Vec b, Vec p0, Vec p1) {
  const int s0 = side(a, b, p0), s1 = side(a, b, p1);
  const int sa = side(p0, p1, a), sb = side(p0, p1, b);
  if (s0 * s1 < 0 && sa * sb < 0) return true;  // a proper crossing
  // Otherwise they meet only where an end of one lies on the other.
  return (s0 == 0 && within(a, b, p0)) || (s1 == 0 && within(a, b, p1)) ||
         (sa == 0 && within(p0, p1, a)) || (sb == 0 && within(p0, p1, b));
}

bool OutflowLines::path_touches_any(Vec p0, Vec p1) const {
  const double x_min = std::min(p0[0], p1[0]), x_max = std::max(p0[0], p1[0]);
  const double y_min = std::min(p0[1], p1[1]), y_max = std::max(p0[1], p1[1]);
  for (const Segment& s : segments_) {
    if (x_max < s.x_min || x_min > s.x_max || y_max < s.y_min || y_min > s.y_max) continue;
    if (touches(s.a, s.b, p0, p1)) return true;
  }
  return false;
}

void OutflowLines::apply(swe::StepContext& context) {
  auto& p = context.particles;
  const std::size_t n = p.fluid_count();
  const auto old_x = context.previous_x, old_y = context.previous_y;
  if (old_x.size() != old_y.size() || old_x.size() > n) {
    throw std::logic_error(
        "outflow lines: the positions before the move do not match the particles; an effect "
        "that removes particles must come after this one");
  }
  leaving_.assign(n, 0);
  parallel_for(n, [&](std::size_t i) {
    const Vec now{p.x[i], p.y[i]};
    const Vec before = i < old_x.size() ? Vec{old_x[i], old_y[i]} : now;
    if (!finite(now) || !finite(before)) return;
    leaving_[i] = path_touches_any(before, now) ? 1 : 0;
  });
  const Removal removal = remove_flagged(p, leaving_, context.ledger);
  removed_ += removal.particles;
  removed_m3_ += removal.volume_m3;
}

std::string OutflowLines::report() const {
  std::ostringstream out;
  out << removed_ << " particles, " << removed_m3_ << " m3 left through outflow lines";
  return out.str();
}

void OutflowLines::save_state(swe::StateWriter& out) const {
  out.count(removed_);
  out.number(removed_m3_);
}

void OutflowLines::restore_state(swe::StateReader& in) {
  removed_ = in.count();
  removed_m3_ = in.number();
}

}  // namespace swemps::boundaries
