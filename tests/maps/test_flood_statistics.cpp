// Tests of the whole-run flood statistics: a hand-worked history, the edge cases of the
// rules, and a random history against a reference that keeps every sample.

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "swemps/maps/flood_statistics.hpp"

using swemps::maps::FloodStatistics;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<double> copy(std::span<const double> s) { return {s.begin(), s.end()}; }

// Statistics of one cell recomputed from its full history, straight from the rules in the
// header: the slow reference for the running accumulator.
struct CellHistory {
  std::vector<double> t, h, u, v;
};
struct CellResult {
  double max_depth = kNaN, max_speed = kNaN, max_hazard = kNaN, arrival = kNaN, duration = kNaN;
};
CellResult reference(const CellHistory& c, double wet) {
  CellResult r;
  for (std::size_t k = 0; k < c.t.size(); ++k) {
    if (std::isnan(c.h[k])) continue;
    if (std::isnan(r.max_depth)) r = {c.h[k], 0.0, 0.0, kNaN, 0.0};
    r.max_depth = std::max(r.max_depth, c.h[k]);
    if (c.h[k] <= wet) continue;
    if (std::isnan(r.arrival)) r.arrival = c.t[k];
    if (k > 0) r.duration += c.t[k] - c.t[k - 1];
    const double s = std::sqrt(c.u[k] * c.u[k] + c.v[k] * c.v[k]);
    if (std::isfinite(s)) {
      r.max_speed = std::max(r.max_speed, s);
      r.max_hazard = std::max(r.max_hazard, c.h[k] * s);
    }
  }
  return r;
}

bool same(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return a == Approx(b).epsilon(1e-12).margin(1e-14);
}

}  // namespace

TEST_CASE("FloodStatistics on a hand-worked history", "[maps][statistics]") {
  // Cell 0 floods at t = 10 and drains at t = 30; cell 1 stays below the threshold; cell 2
  // is wet from the start; cell 3 never has data.
  FloodStatistics stats(4, 0.01);
  CHECK(stats.samples() == 0);
  CHECK(std::isnan(stats.last_time()));
  CHECK(stats.wet_depth() == 0.01);
  stats.update(0.0, std::vector{0.0, 0.005, 0.5, kNaN}, std::vector{0.0, 9.0, 1.0, 0.0},
               std::vector{0.0, 0.0, 0.0, 0.0});
  stats.update(10.0, std::vector{0.2, 0.01, 0.4, kNaN}, std::vector{3.0, 9.0, 0.0, 0.0},
               std::vector{4.0, 0.0, 2.0, 0.0});
  stats.update(20.0, std::vector{0.1, 0.002, 0.3, kNaN}, std::vector{0.0, 9.0, 0.0, 0.0},
               std::vector{1.0, 0.0, 1.0, 0.0});
  stats.update(30.0, std::vector{0.0, 0.0, 0.2, kNaN}, std::vector{0.0, 9.0, 0.0, 0.0},
               std::vector{0.0, 0.0, 1.0, 0.0});
  CHECK(stats.samples() == 4);
  CHECK(stats.last_time() == 30.0);

  const auto max_depth = copy(stats.max_depth());
  CHECK(max_depth[0] == 0.2);
  CHECK(max_depth[1] == 0.01);  // recorded even though never wet
  CHECK(max_depth[2] == 0.5);
  CHECK(std::isnan(max_depth[3]));

  const auto max_speed = copy(stats.max_speed());
  CHECK(max_speed[0] == Approx(5.0));
  CHECK(max_speed[1] == 0.0);  // 9 m/s on a film at the threshold does not count
  CHECK(max_speed[2] == Approx(2.0));
  CHECK(std::isnan(max_speed[3]));

  const auto max_hazard = copy(stats.max_hazard());
  CHECK(max_hazard[0] == Approx(1.0));  // 0.2 m * 5 m/s beats 0.1 m * 1 m/s
  CHECK(max_hazard[1] == 0.0);
  CHECK(max_hazard[2] == Approx(0.8));  // 0.4 m * 2 m/s
  CHECK(std::isnan(max_hazard[3]));

  const auto arrival = copy(stats.arrival_time());
  CHECK(arrival[0] == 10.0);
  CHECK(std::isnan(arrival[1]));
  CHECK(arrival[2] == 0.0);
  CHECK(std::isnan(arrival[3]));

  const auto duration = copy(stats.inundation_duration());
  CHECK(duration[0] == 20.0);  // wet at t = 10 and 20: (0, 10] and (10, 20]
  CHECK(duration[1] == 0.0);
  CHECK(duration[2] == 30.0);  // wet at all four samples; the first counts nothing
  CHECK(std::isnan(duration[3]));
}

TEST_CASE("FloodStatistics skips missing velocities but keeps the depth", "[maps][statistics]") {
  FloodStatistics stats(1, 0.0);
  stats.update(1.0, std::vector{0.5}, std::vector{kNaN}, std::vector{0.0});
  stats.update(3.0, std::vector{0.25}, std::vector{1.0}, std::vector{0.0});
  CHECK(stats.max_depth()[0] == 0.5);
  CHECK(stats.max_speed()[0] == 1.0);
  CHECK(stats.max_hazard()[0] == 0.25);
  CHECK(stats.arrival_time()[0] == 1.0);
  CHECK(stats.inundation_duration()[0] == 2.0);
}

TEST_CASE("FloodStatistics rejects bad input and stays unchanged", "[maps][statistics]") {
  CHECK_THROWS_AS(FloodStatistics(3, -0.01), std::invalid_argument);
  CHECK_THROWS_AS(FloodStatistics(3, kNaN), std::invalid_argument);

  FloodStatistics stats(2, 0.01);
  const std::vector<double> two{1.0, 1.0}, one{1.0};
  CHECK_THROWS_AS(stats.update(0.0, one, two, two), std::invalid_argument);
  CHECK_THROWS_AS(stats.update(0.0, two, one, two), std::invalid_argument);
  CHECK_THROWS_AS(stats.update(0.0, two, two, one), std::invalid_argument);
  CHECK_THROWS_AS(stats.update(kNaN, two, two, two), std::invalid_argument);
  CHECK(stats.samples() == 0);

  stats.update(5.0, two, two, two);
  CHECK_THROWS_AS(stats.update(5.0, two, two, two), std::invalid_argument);
  CHECK_THROWS_AS(stats.update(4.0, two, two, two), std::invalid_argument);
  CHECK(stats.samples() == 1);
  CHECK(stats.last_time() == 5.0);
  CHECK(stats.inundation_duration()[0] == 0.0);
}

TEST_CASE("FloodStatistics matches a reference that keeps the whole history",
          "[maps][statistics]") {
  const std::size_t cells = 50, samples = 40;
  const double wet = 0.05;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> depth(-0.02, 0.3), vel(-2.0, 2.0), step(0.1, 5.0),
      unit(0.0, 1.0);

  FloodStatistics stats(cells, wet);
  std::vector<CellHistory> history(cells);
  double t = -3.0;  // times need not start at 0
  for (std::size_t k = 0; k < samples; ++k) {
    t += step(rng);
    std::vector<double> h(cells), u(cells), v(cells);
    for (std::size_t i = 0; i < cells; ++i) {
      // Some gaps in the data, some missing velocities, and a few depths exactly at the
      // threshold so that the strict comparison is exercised.
      h[i] = unit(rng) < 0.1 ? kNaN : (unit(rng) < 0.05 ? wet : depth(rng));
      u[i] = unit(rng) < 0.05 ? kNaN : vel(rng);
      v[i] = vel(rng);
      history[i].t.push_back(t);
      history[i].h.push_back(h[i]);
      history[i].u.push_back(u[i]);
      history[i].v.push_back(v[i]);
    }
    stats.update(t, h, u, v);
  }
  for (std::size_t i = 0; i < cells; ++i) {
    const CellResult r = reference(history[i], wet);
    INFO("cell " << i);
    CHECK(same(stats.max_depth()[i], r.max_depth));
    CHECK(same(stats.max_speed()[i], r.max_speed));
    CHECK(same(stats.max_hazard()[i], r.max_hazard));
    CHECK(same(stats.arrival_time()[i], r.arrival));
    CHECK(same(stats.inundation_duration()[i], r.duration));
  }
}
