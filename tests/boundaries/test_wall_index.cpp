// Tests of the wall index: it finds every wall a brute-force test finds, for points, boxes
// and paths, over walls short and long, and ghosts come out as they would without it.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "../support/particle_rows.hpp"
#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/boundaries/wall_index.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"

using namespace swemps;
using boundaries::GhostWalls;
using boundaries::WallIndex;
using boundaries::WallSegment;

namespace {

// A town's walls (short, turned rectangles) and two long walls across it.
std::vector<WallSegment> town_walls(std::mt19937& random) {
  std::uniform_real_distribution<double> at(0.0, 200.0), size(2.0, 10.0), turn(0.0, 3.0);
  std::vector<WallSegment> walls;
  for (int k = 0; k < 60; ++k) {
    const double cx = at(random), cy = at(random), a = size(random), b = size(random);
    const double t = turn(random), c = std::cos(t), s = std::sin(t);
    const double corners[4][2] = {{-a, -b}, {a, -b}, {a, b}, {-a, b}};
    for (int v = 0; v < 4; ++v) {
      const auto& p = corners[v];
      const auto& q = corners[(v + 1) % 4];
      walls.push_back({{cx + c * p[0] - s * p[1], cy + s * p[0] + c * p[1]},
                       {cx + c * q[0] - s * q[1], cy + s * q[0] + c * q[1]}});
    }
  }
  walls.push_back({{-50.0, -20.0}, {260.0, 230.0}});
  walls.push_back({{0.0, 100.0}, {200.0, 100.0}});
  return walls;
}

// Where the path p0 -> p1 meets wall w, as a fraction of the path, or -1.
double meets_at(const WallSegment& w, std::array<double, 2> p0, std::array<double, 2> p1) {
  const double dx = p1[0] - p0[0], dy = p1[1] - p0[1];
  const double ex = w.to[0] - w.from[0], ey = w.to[1] - w.from[1];
  const double denom = dx * ey - dy * ex;
  if (denom == 0.0) return -1.0;
  const double wx = w.from[0] - p0[0], wy = w.from[1] - p0[1];
  const double t = (wx * ey - wy * ex) / denom, s = (wx * dy - wy * dx) / denom;
  return t > 0.0 && t <= 1.0 && s >= 0.0 && s <= 1.0 ? t : -1.0;
}

bool boxes_meet(const WallSegment& w, double x0, double y0, double x1, double y1) {
  return std::max(w.from[0], w.to[0]) >= x0 && std::min(w.from[0], w.to[0]) <= x1 &&
         std::max(w.from[1], w.to[1]) >= y0 && std::min(w.from[1], w.to[1]) <= y1;
}

}  // namespace

TEST_CASE("the wall index offers every wall whose box meets the query box", "[boundaries]") {
  std::mt19937 random(7);
  const auto walls = town_walls(random);
  const WallIndex index(walls);
  REQUIRE(index.segments().size() == walls.size());
  CHECK(index.cell_size() > 0.0);
  std::uniform_real_distribution<double> at(-30.0, 230.0), half(0.0, 8.0);
  int met = 0;
  for (int q = 0; q < 2000; ++q) {
    const double x = at(random), y = at(random), r = half(random);
    std::set<std::uint32_t> offered;
    index.for_each_candidate(x - r, y - r, x + r, y + r,
                             [&](std::uint32_t k) { offered.insert(k); });
    for (std::uint32_t k = 0; k < walls.size(); ++k) {
      if (boxes_meet(walls[k], x - r, y - r, x + r, y + r)) {
        ++met;
        INFO("query " << q << " wall " << k);
        CHECK(offered.count(k) == 1);
      }
    }
  }
  CHECK(met > 2000);  // the queries do meet walls
}

TEST_CASE("the wall index finds a crossing path exactly when a test of every wall does",
          "[boundaries]") {
  std::mt19937 random(11);
  const auto walls = town_walls(random);
  const WallIndex index(walls);
  std::uniform_real_distribution<double> at(-30.0, 230.0), step(-6.0, 6.0);
  int crossing = 0;
  for (int q = 0; q < 5000; ++q) {
    const std::array<double, 2> p0{at(random), at(random)};
    const std::array<double, 2> p1{p0[0] + step(random), p0[1] + step(random)};
    const bool brute = GhostWalls::crosses_any(walls, p0, p1);
    crossing += brute ? 1 : 0;
    CHECK(index.crosses_any(p0, p1) == brute);
  }
  CHECK(crossing > 100);
  // A path ending exactly on a wall crosses it, as for one wall alone.
  CHECK(index.crosses_any({100.0, 99.0}, {100.0, 100.0}));
  // Far outside the walls' box, below and above: nothing.
  CHECK_FALSE(index.crosses_any({-500.0, -500.0}, {-499.0, -499.0}));
  CHECK_FALSE(index.crosses_any({900.0, 900.0}, {901.0, 901.0}));
}

TEST_CASE("ghosts from the index are those a test of every wall gives, in order", "[boundaries]") {
  std::mt19937 random(3);
  const auto walls = town_walls(random);
  GhostWalls indexed(walls);
  std::uniform_real_distribution<double> at(0.0, 200.0);
  particles::SweParticles p;
  for (int k = 0; k < 3000; ++k)
    p.add_fluid(at(random), at(random), 0.1, -0.2, 0.01, 0.3, 1.0, 0.0);
  const double reach = 1.5;
  indexed.add_ghosts(p, reach);
  // By brute force: each particle's walls within reach (half-open along the wall), in index
  // order, one ghost mirrored across each, then one per pair that is not parallel.
  std::size_t expected = 0, checked = 0;
  std::size_t g = p.fluid_count();
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    std::vector<std::size_t> near;
    for (std::size_t k = 0; k < walls.size(); ++k) {
      const auto& w = walls[k];
      const double dx = w.to[0] - w.from[0], dy = w.to[1] - w.from[1];
      const double length = std::hypot(dx, dy);
      const double rx = p.x[i] - w.from[0], ry = p.y[i] - w.from[1];
      const double along = (rx * dx + ry * dy) / length;
      const double across = (rx * dy - ry * dx) / length;
      if (along >= 0.0 && along < length && std::abs(across) < reach) near.push_back(k);
    }
    const auto mirror = [&](std::size_t k, double x, double y) {
      const auto& w = walls[k];
      const double dx = w.to[0] - w.from[0], dy = w.to[1] - w.from[1];
      const double length = std::hypot(dx, dy);
      const double nx = -dy / length, ny = dx / length;
      const double d = (x - w.from[0]) * nx + (y - w.from[1]) * ny;
      return std::array<double, 2>{x - 2.0 * d * nx, y - 2.0 * d * ny};
    };
    std::vector<std::array<double, 2>> ghosts;
    for (const std::size_t k : near) {
      ghosts.push_back(mirror(k, p.x[i], p.y[i]));
    }
    for (std::size_t a = 0; a < near.size(); ++a) {
      for (std::size_t b = a + 1; b < near.size(); ++b) {
        const auto& wa = walls[near[a]];
        const auto& wb = walls[near[b]];
        const double cross = (wa.to[0] - wa.from[0]) * (wb.to[1] - wb.from[1]) -
                             (wa.to[1] - wa.from[1]) * (wb.to[0] - wb.from[0]);
        if (std::abs(cross) <= 1e-9 * std::hypot(wa.to[0] - wa.from[0], wa.to[1] - wa.from[1]) *
                                   std::hypot(wb.to[0] - wb.from[0], wb.to[1] - wb.from[1]))
          continue;
        const auto once = mirror(near[a], p.x[i], p.y[i]);
        const auto twice = mirror(near[b], once[0], once[1]);
        ghosts.push_back(twice);
      }
    }
    expected += ghosts.size();
    // Every ghost of the particle where the brute force puts it, in the same order.
    for (const auto& m : ghosts) {
      REQUIRE(g < p.size());
      CHECK(p.source[g] == i);
      CHECK(p.x[g] == Approx(m[0]).margin(1e-9));
      CHECK(p.y[g] == Approx(m[1]).margin(1e-9));
      ++checked;
      ++g;
    }
  }
  CHECK(p.ghost_count() == expected);
  CHECK(checked > 100);
}

TEST_CASE("the pairs hidden across walls are those a test of every wall hides", "[boundaries]") {
  std::mt19937 random(5);
  const auto walls = town_walls(random);
  GhostWalls indexed(walls);
  std::uniform_real_distribution<double> at(0.0, 200.0);
  particles::SweParticles p;
  for (int k = 0; k < 4000; ++k) p.add_fluid(at(random), at(random), 0.0, 0.0, 0.01, 0.3, 1.0, 0.0);
  const double reach = 4.0;
  indexed.add_ghosts(p, reach);
  neighbors::NeighborList rows = testing::rows_within(p, reach);
  const neighbors::NeighborList searched = rows;
  const std::size_t hidden = indexed.hide_pairs_across_walls(p, rows);
  // By brute force: j stays in row i when it is one of i's ghosts, or when the path from the
  // lower-numbered of i and j's particle to the higher meets no wall.
  std::size_t expected_hidden = 0, ghosts_hidden = 0;
  for (std::uint32_t i = 0; i < p.fluid_count(); ++i) {
    std::vector<std::uint32_t> expected;
    for (const std::uint32_t j : searched.row(i)) {
      const std::uint32_t k = p.source[j];
      const std::array<double, 2> xi{p.x[i], p.y[i]}, xk{p.x[k], p.y[k]};
      const bool seen = k == i || std::none_of(walls.begin(), walls.end(), [&](const auto& w) {
                          return i < k ? meets_at(w, xi, xk) >= 0.0 : meets_at(w, xk, xi) >= 0.0;
                        });
      if (seen) {
        expected.push_back(j);
      } else {
        ++expected_hidden;
        if (j >= p.fluid_count()) ++ghosts_hidden;
      }
    }
    const auto row = rows.row(i);
    INFO("row " << i);
    CHECK(std::vector<std::uint32_t>(row.begin(), row.end()) == expected);
  }
  CHECK(hidden == expected_hidden);
  CHECK(ghosts_hidden > 100);  // the test sees ghosts hidden as well as particles
  CHECK(expected_hidden > ghosts_hidden);
}

TEST_CASE("a wall index refuses a wall with a non-finite end", "[boundaries]") {
  CHECK_THROWS_AS(WallIndex(std::vector<WallSegment>{{{0.0, 0.0}, {NAN, 1.0}}}),
                  std::invalid_argument);
  CHECK(WallIndex{}.empty());
  CHECK_FALSE(WallIndex{}.crosses_any({0.0, 0.0}, {1.0, 1.0}));
}
