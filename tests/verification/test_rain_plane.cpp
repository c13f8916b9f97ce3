// Rain on a dry tilted plane (cases/rain-plane): the kinematic wave. Rain i falls on a plane
// of length L falling at S to an open edge; in kinematic flow, q = alpha h^(5/3) with
// alpha = S^(1/2) / n, the depth everywhere rises as i t until the wave from the top edge
// reaches the outlet at t_e = (i L / alpha)^(3/5) / i, so that the outflow per metre of width
// rises as alpha (i t)^(5/3) and then holds at i L (Singh, Kinematic Wave Modeling in Water
// Resources, 1996; docs/rain.md). The scene's kinematic-wave number S L / (h F^2) is about
// 150: the shallow-water equations are within a per cent of the kinematic solution.

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "swemps/hydrology/rain.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

using namespace swemps;

namespace {

constexpr double kRain = 100.0 * hydrology::kMetresPerSecondPerMmPerHour;  // i
constexpr double kLength = 100.0, kWidth = 10.0, kSlope = 0.01, kManningN = 0.02;

// The kinematic solution's outflow volume (m^3) by time t.
double kinematic_outflow_m3(double t) {
  const double alpha = std::sqrt(kSlope) / kManningN;
  const double t_e = std::pow(kRain * kLength / alpha, 0.6) / kRain;
  const double rising = kWidth * alpha * std::pow(kRain, 5.0 / 3.0) *
                        std::pow(std::min(t, t_e), 8.0 / 3.0) / (8.0 / 3.0);
  return rising + kWidth * kRain * kLength * std::max(0.0, t - t_e);
}

}  // namespace

TEST_CASE("rain on a dry plane: the outflow follows the kinematic wave to rain x area",
          "[verification][rain]") {
  const auto scene =
      scenario::load(std::string(SWEMPS_SOURCE_DIR) + "/cases/rain-plane/scenario.json");
  auto sim = scenario::make_simulation(scene);
  const hydrology::Rain* rain = nullptr;
  for (const auto& effect : sim.effects()) {
    if (!rain) rain = dynamic_cast<const hydrology::Rain*>(effect.get());
  }
  REQUIRE(rain != nullptr);
  REQUIRE(rain->rain_area_m2() == Approx(kLength * kWidth).epsilon(1e-14));

  std::vector<double> outflow_m3;  // every 10 s
  double worst_balance = 0.0;
  for (int k = 1; k <= 120; ++k) {
    sim.advance_to(10.0 * k);
    outflow_m3.push_back(sim.ledger().removed_m3);
    worst_balance = std::max(worst_balance, std::abs(sim.relative_volume_change()));
  }
  const auto at = [&](double t) { return outflow_m3[static_cast<std::size_t>(t / 10.0) - 1]; };

  // Every drop is booked: the water in the domain is the rain booked less the outflow, and
  // the rain that fell is the rain booked and the water pending in dry cells.
  CHECK(worst_balance < 1e-12);
  CHECK(rain->volume_fallen() == Approx(kRain * kLength * kWidth * 1200.0).epsilon(1e-12));
  CHECK(rain->volume_added() + rain->pending_volume() ==
        Approx(rain->volume_fallen()).epsilon(1e-12));
  CHECK(sim.ledger().rain_m3 == rain->volume_added());

  // The equilibrium: the outflow over the last 400 s is rain x area (measured -0.1 %). The
  // issue's bar is 2 %.
  const double equilibrium = (at(1200.0) - at(800.0)) / 400.0;
  INFO("equilibrium outflow " << equilibrium << " m3/s, rain x area " << kRain * kLength * kWidth);
  CHECK(equilibrium == Approx(kRain * kLength * kWidth).epsilon(0.02));

  // The rising limb, from the time the first particles have run off (the first rain waits in
  // dry cells until it holds 1 mm, 36 s at this rate): the volume out by each time within 5 %
  // of the kinematic solution's (measured: within 1.3 % from 220 s, -5 % at 140 s). A flow
  // slowed by its friction update, as the update once did in thin water, stored 12 % too
  // much and let out 43 % too little by 220 s.
  for (const double t : {200.0, 300.0, 400.0, 500.0, 700.0}) {
    INFO("t = " << t << " s: out " << at(t) << " m3, kinematic " << kinematic_outflow_m3(t));
    CHECK(at(t) == Approx(kinematic_outflow_m3(t)).epsilon(0.05));
  }
}
