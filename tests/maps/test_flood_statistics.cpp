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
using swemps::maps::LandUse;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<double> copy(std::span<const double> s) { return {s.begin(), s.end()}; }

// Statistics of one cell recomputed from its full history, straight from the rules in the
// header: the slow reference for the running accumulator.
struct CellHistory {
  std::vector<double> t, h, u, v;
};
struct CellResult {
  double max_depth = kNaN, time_of_max = kNaN, max_surface = kNaN, max_speed = kNaN,
         max_depth_speed = kNaN, max_depth_speed2 = kNaN, max_rating = kNaN, max_class = kNaN;
  std::vector<double> arrival, duration;  // per threshold
};
// The maximum over the whole history first, then the first sample that reaches it.
CellResult reference(const CellHistory& c, const std::vector<double>& thresholds, double bed,
                     LandUse land) {
  const double wet = thresholds.front();
  CellResult r;
  r.arrival.assign(thresholds.size(), kNaN);
  r.duration.assign(thresholds.size(), kNaN);
  for (std::size_t k = 0; k < c.t.size(); ++k) {
    if (std::isnan(c.h[k])) continue;
    if (std::isnan(r.max_depth)) {
      r.max_depth = c.h[k];
      r.max_speed = r.max_depth_speed = r.max_depth_speed2 = r.max_rating = r.max_class = 0.0;
      r.duration.assign(thresholds.size(), 0.0);
    }
    r.max_depth = std::max(r.max_depth, c.h[k]);
    for (std::size_t j = 0; j < thresholds.size(); ++j) {
      if (!(c.h[k] > thresholds[j])) continue;
      if (std::isnan(r.arrival[j])) r.arrival[j] = c.t[k];
      if (k > 0) r.duration[j] += c.t[k] - c.t[k - 1];
    }
    if (c.h[k] <= wet) continue;
    r.max_surface =
        std::isnan(r.max_surface) ? c.h[k] + bed : std::max(r.max_surface, c.h[k] + bed);
    const double s = std::sqrt(c.u[k] * c.u[k] + c.v[k] * c.v[k]);
    if (std::isfinite(s)) {
      r.max_speed = std::max(r.max_speed, s);
      r.max_depth_speed = std::max(r.max_depth_speed, c.h[k] * s);
      r.max_depth_speed2 = std::max(r.max_depth_speed2, c.h[k] * s * s);
      r.max_rating = std::max(r.max_rating, swemps::maps::uk_hazard_rating(c.h[k], s, land));
      r.max_class =
          std::max(r.max_class, static_cast<double>(swemps::maps::aidr_hazard(c.h[k], s)));
    }
  }
  if (r.max_depth > wet) {
    for (std::size_t k = 0; k < c.t.size(); ++k) {
      if (c.h[k] == r.max_depth) {
        r.time_of_max = c.t[k];
        break;
      }
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
  FloodStatistics stats(4, {0.01, {0.15}}, {10.0, 20.0, 30.0, 40.0});
  CHECK(stats.thresholds() == std::vector<double>{0.01, 0.15});
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

  const auto max_depth_speed = copy(stats.max_depth_speed());
  CHECK(max_depth_speed[0] == Approx(1.0));  // 0.2 m * 5 m/s beats 0.1 m * 1 m/s
  CHECK(max_depth_speed[1] == 0.0);
  CHECK(max_depth_speed[2] == Approx(0.8));  // 0.4 m * 2 m/s
  CHECK(std::isnan(max_depth_speed[3]));
  CHECK(stats.max_depth_speed2()[0] == Approx(5.0));  // 0.2 m * 25 m2/s2
  CHECK(stats.max_depth_speed2()[2] == Approx(1.6));  // 0.4 m * 4 m2/s2

  const auto time_of_max = copy(stats.time_of_max_depth());
  CHECK(time_of_max[0] == 10.0);
  CHECK(std::isnan(time_of_max[1]));  // never wet
  CHECK(time_of_max[2] == 0.0);
  const auto surface = copy(stats.max_surface_elevation());
  CHECK(surface[0] == Approx(10.2));
  CHECK(std::isnan(surface[1]));
  CHECK(surface[2] == Approx(30.5));

  // Hazard of each sample from its own depth and speed (urban land): cell 0 at t = 10 s has
  // 0.2 m at 5 m/s: HR = 0.2 x 5.5 + 0 = 1.1, and v > 2 m/s makes DF 1 (the last row of the
  // debris table): 2.1, extreme; AIDR: 5 m/s > 4 m/s, H6. Cell 2 at t = 10 s: 0.4 m at
  // 2 m/s, HR = 0.4 x 2.5 + 1 = 2.0, d v = 0.8: H4.
  CHECK(stats.max_hazard_rating()[0] == Approx(2.1));
  CHECK(stats.max_hazard_class()[0] == 6.0);
  CHECK(stats.max_hazard_rating()[1] == 0.0);
  CHECK(stats.max_hazard_class()[1] == 0.0);
  CHECK(stats.max_hazard_rating()[2] == Approx(2.0));
  CHECK(stats.max_hazard_class()[2] == 4.0);

  const auto arrival = copy(stats.arrival_time());
  CHECK(arrival[0] == 10.0);
  CHECK(std::isnan(arrival[1]));
  CHECK(arrival[2] == 0.0);
  CHECK(std::isnan(arrival[3]));

  const auto duration = copy(stats.duration_above());
  CHECK(duration[0] == 20.0);  // wet at t = 10 and 20: (0, 10] and (10, 20]
  CHECK(duration[1] == 0.0);
  CHECK(duration[2] == 30.0);  // wet at all four samples; the first counts nothing
  CHECK(std::isnan(duration[3]));

  // Above 0.15 m: cell 0 only at t = 10 s, cell 2 at every sample, cell 1 never.
  CHECK(stats.arrival_time(1)[0] == 10.0);
  CHECK(stats.duration_above(1)[0] == 10.0);
  CHECK(std::isnan(stats.arrival_time(1)[1]));
  CHECK(stats.duration_above(1)[1] == 0.0);
  CHECK(stats.arrival_time(1)[2] == 0.0);
  CHECK(stats.duration_above(1)[2] == 30.0);
}

TEST_CASE("FloodStatistics skips missing velocities but keeps the depth", "[maps][statistics]") {
  FloodStatistics stats(1, {0.0});
  stats.update(1.0, std::vector{0.5}, std::vector{kNaN}, std::vector{0.0});
  stats.update(3.0, std::vector{0.25}, std::vector{1.0}, std::vector{0.0});
  CHECK(stats.max_depth()[0] == 0.5);
  CHECK(stats.max_speed()[0] == 1.0);
  CHECK(stats.max_depth_speed()[0] == 0.25);
  CHECK(stats.arrival_time()[0] == 1.0);
  CHECK(stats.duration_above()[0] == 2.0);
}

TEST_CASE("FloodStatistics rejects bad input and stays unchanged", "[maps][statistics]") {
  CHECK_THROWS_AS(FloodStatistics(3, {-0.01}), std::invalid_argument);
  CHECK_THROWS_AS(FloodStatistics(3, {kNaN}), std::invalid_argument);
  CHECK_THROWS_AS(FloodStatistics(3, {0.1, {0.1}}), std::invalid_argument);  // not above
  CHECK_THROWS_AS(FloodStatistics(3, {0.1, {0.3, kNaN}}), std::invalid_argument);
  CHECK_THROWS_AS(FloodStatistics(3, {0.1}, {1.0, 2.0}), std::invalid_argument);  // bed size

  FloodStatistics stats(2, {0.01});
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
  CHECK(stats.duration_above()[0] == 0.0);

  // An infinite depth is no data, as NaN is: nothing throws halfway through the cells.
  FloodStatistics other(2, {0.01});
  const std::vector<double> infinite{std::numeric_limits<double>::infinity(), 1.0};
  other.update(1.0, infinite, two, two);
  CHECK(std::isnan(other.max_depth()[0]));
  CHECK(other.max_depth()[1] == 1.0);
  CHECK(other.samples() == 1);
}

TEST_CASE("FloodStatistics matches a reference that keeps the whole history",
          "[maps][statistics]") {
  const std::size_t cells = 50, samples = 40;
  const double wet = 0.05;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> depth(-0.02, 0.3), vel(-2.0, 2.0), step(0.1, 5.0),
      unit(0.0, 1.0);

  const std::vector<double> further{0.2, 0.1};  // any order
  std::vector<double> bed(cells);
  for (std::size_t i = 0; i < cells; ++i) bed[i] = 0.5 * static_cast<double>(i);
  FloodStatistics stats(cells, {wet, further, LandUse::pasture_arable}, bed);
  const std::vector<double> thresholds{wet, 0.1, 0.2};
  REQUIRE(stats.thresholds() == thresholds);
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
    const CellResult r = reference(history[i], thresholds, bed[i], LandUse::pasture_arable);
    INFO("cell " << i);
    CHECK(same(stats.max_depth()[i], r.max_depth));
    CHECK(same(stats.time_of_max_depth()[i], r.time_of_max));
    CHECK(same(stats.max_surface_elevation()[i], r.max_surface));
    CHECK(same(stats.max_speed()[i], r.max_speed));
    CHECK(same(stats.max_depth_speed()[i], r.max_depth_speed));
    CHECK(same(stats.max_depth_speed2()[i], r.max_depth_speed2));
    CHECK(same(stats.max_hazard_rating()[i], r.max_rating));
    CHECK(same(stats.max_hazard_class()[i], r.max_class));
    for (std::size_t j = 0; j < thresholds.size(); ++j) {
      INFO("threshold " << thresholds[j]);
      CHECK(same(stats.arrival_time(j)[i], r.arrival[j]));
      CHECK(same(stats.duration_above(j)[i], r.duration[j]));
    }
  }
}

TEST_CASE("FloodStatistics rates each sample by its own depth and speed", "[maps][statistics]") {
  // docs/outputs.md, "Why the maximum hazard is not the hazard of the maximum depth and
  // speed": a pasture cell sees a fast shallow front (0.2 m at 1.4 m/s: HR 0.38, H1), then
  // deep slow ponding (1 m at 0.2 m/s: HR = 1 x 0.7 + 0.5 = 1.2, H3). The maxima combined
  // (1 m at 1.4 m/s) would give HR 2.4 and H5.
  FloodStatistics stats(1, {0.01, {}, LandUse::pasture_arable});
  stats.update(0.0, std::vector{0.2}, std::vector{1.4}, std::vector{0.0});
  stats.update(60.0, std::vector{1.0}, std::vector{0.2}, std::vector{0.0});
  CHECK(stats.max_depth()[0] == 1.0);
  CHECK(stats.max_speed()[0] == Approx(1.4));
  CHECK(stats.max_hazard_rating()[0] == Approx(1.2));
  CHECK(stats.max_hazard_class()[0] == 3.0);
  CHECK(swemps::maps::uk_hazard_rating(1.0, 1.4, LandUse::pasture_arable) == Approx(2.4));
}

TEST_CASE("FloodStatistics maps a tsunami's rise and arrival above the still level",
          "[maps][statistics][tsunami]") {
  using swemps::maps::TsunamiLevels;
  // Still level 0, arrival rise 0.05. Cell 0: sea floor at -2 m, the wave comes at t = 20.
  // Cell 1: beach at +0.5 m, wetted at t = 30 by 0.2 m. Cell 2: beach at 0.02 m, reached by
  // 0.02 m of water (wet, but only 0.04 above the still level: not arrived). Cell 3: dry.
  swemps::maps::StatisticsSettings settings{0.01, {}};
  settings.tsunami = TsunamiLevels{0.0, 0.05};
  FloodStatistics stats(4, settings, {-2.0, 0.5, 0.02, 3.0});
  const std::vector<double> zero(4, 0.0);
  stats.update(0.0, std::vector{2.0, 0.0, 0.0, 0.0}, zero, zero);
  stats.update(10.0, std::vector{2.04, 0.0, 0.0, 0.0}, zero, zero);  // 0.04: not yet
  stats.update(20.0, std::vector{2.3, 0.0, 0.02, 0.0}, zero, zero);
  stats.update(30.0, std::vector{1.9, 0.2, 0.005, 0.0}, zero, zero);
  const auto rise = stats.max_surface_rise();
  REQUIRE(rise.size() == 4);
  CHECK(rise[0] == Approx(0.3));
  CHECK(rise[1] == Approx(0.7));
  CHECK(rise[2] == Approx(0.04));
  CHECK(std::isnan(rise[3]));  // never wet
  const auto arrival = copy(stats.rise_arrival_time());
  CHECK(arrival[0] == 20.0);
  CHECK(arrival[1] == 30.0);
  CHECK(std::isnan(arrival[2]));
  CHECK(std::isnan(arrival[3]));

  // The arrival map is part of the state a checkpoint keeps; the rise is made from the
  // surface, so it needs no map of its own.
  const FloodStatistics plain(4, {0.01, {}});
  CHECK(stats.maps().size() == plain.maps().size() + 1);
  CHECK(plain.max_surface_rise().empty());
  CHECK(plain.rise_arrival_time().empty());
  std::vector<std::vector<double>> saved;
  for (const auto m : stats.maps()) saved.push_back(copy(m));
  FloodStatistics restored(4, settings, {-2.0, 0.5, 0.02, 3.0});
  restored.restore(stats.samples(), stats.last_time(), saved);
  CHECK(copy(restored.rise_arrival_time())[1] == 30.0);
  CHECK_THROWS_AS(FloodStatistics(4, {0.01, {}}).restore(4, 30.0, saved), std::invalid_argument);

  settings.tsunami = TsunamiLevels{0.0, 0.0};
  CHECK_THROWS_AS(FloodStatistics(4, settings), std::invalid_argument);
  settings.tsunami = TsunamiLevels{kNaN, 0.05};
  CHECK_THROWS_AS(FloodStatistics(4, settings), std::invalid_argument);
}
