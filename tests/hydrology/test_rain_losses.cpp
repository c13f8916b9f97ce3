// Tests of the losses rain meets on the ground: the initial and continuing loss per cell from
// maps, and Green-Ampt infiltration against its closed-form solution for steady rain.

#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "swemps/hydrology/rain.hpp"
#include "swemps/hydrology/rain_losses.hpp"
#include "swemps/swe/state_record.hpp"

using namespace swemps;
using hydrology::CellParameter;

namespace {

constexpr double kMmH = hydrology::kMetresPerSecondPerMmPerHour;

// A 2 x 1 map of 10 m cells over [0, 20] x [0, 10].
std::shared_ptr<const terrain::GriddedField> two_cells(double west, double east) {
  terrain::GridGeometry g{2, 1, 0.0, 10.0, 10.0, 10.0};
  return std::make_shared<const terrain::GriddedField>(g, std::vector<double>{west, east});
}

// F at time t under steady rain i on soil (K, S), from F = 0 at t = 0, solved by bisection on
// the closed form: all the rain soaks in until ponding at F_p = K S / (i - K), t_p = F_p / i;
// then F - F_p - S ln((F + S) / (F_p + S)) = K (t - t_p).
double green_ampt_closed_form(double i, double k, double s, double t) {
  if (i <= k) return i * t;
  const double fp = k * s / (i - k), tp = fp / i;
  if (t <= tp) return i * t;
  double lo = fp, hi = fp + i * (t - tp);
  for (int n = 0; n < 200; ++n) {
    const double mid = 0.5 * (lo + hi);
    const double g = mid - fp - s * std::log((mid + s) / (fp + s)) - k * (t - tp);
    (g > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("initial and continuing losses per cell from maps", "[rain][losses]") {
  hydrology::InitialContinuingLoss loss(CellParameter{0.0, two_cells(1e-3, 4e-3), "initial loss"},
                                        CellParameter{2.0 * kMmH, nullptr, "continuing loss"});
  const std::vector<std::array<double, 2>> centres = {{5.0, 5.0}, {15.0, 5.0}};
  loss.bind(centres);
  // 3 mm over an hour on each: the west keeps 1 mm then 2 mm/h; the east keeps all 3 mm.
  std::vector<double> rain = {3e-3, 3e-3};
  const double lost = loss.take(3600.0, rain);
  CHECK(rain[0] == Approx(0.0).margin(1e-15));
  CHECK(rain[1] == Approx(0.0).margin(1e-15));
  CHECK(lost == Approx(6e-3));
  // The next hour: the west has no initial loss left (2 mm/h taken of 3 mm), the east 1 mm.
  rain = {3e-3, 3e-3};
  loss.take(3600.0, rain);
  CHECK(rain[0] == Approx(1e-3));
  CHECK(rain[1] == Approx(0.0).margin(1e-15));

  // A cell off the map, or a negative value, is refused at binding.
  hydrology::InitialContinuingLoss off(CellParameter{0.0, two_cells(1e-3, 1e-3), "initial loss"},
                                       CellParameter{});
  const std::vector<std::array<double, 2>> outside = {{25.0, 5.0}};
  CHECK_THROWS_WITH(off.bind(outside), Catch::Contains("does not cover"));
  hydrology::InitialContinuingLoss negative(
      CellParameter{0.0, two_cells(1e-3, -1e-3), "initial loss"}, CellParameter{});
  CHECK_THROWS_WITH(negative.bind(centres), Catch::Contains("initial loss is -0.001"));
  // A map in other units is scaled; a value above the most allowed is refused.
  CellParameter deficit{0.0, two_cells(0.5, 1.5), "moisture deficit"};
  deficit.most = 1.0;
  CHECK_THROWS_WITH(deficit.at(centres), Catch::Contains("moisture deficit is 1.5"));
  CellParameter millimetres{0.0, two_cells(1.0, 4.0), "initial loss", 1e-3};
  CHECK(millimetres.at(centres)[1] == Approx(4e-3));
}

TEST_CASE("Green-Ampt infiltration under steady rain follows the closed form at any step",
          "[rain][losses]") {
  // A loam: K = 10 mm/h, psi = 110 mm, dtheta = 0.3; rain 40 mm/h. Ponding at F_p = 11 mm,
  // t_p = 990 s.
  const double k = 10.0 * kMmH, s = 0.110 * 0.3, i = 40.0 * kMmH;
  for (const double dt : {1.0, 9.0, 600.0, 3600.0}) {  // each divides the 2 h
    double f = 0.0, taken = 0.0;
    for (double t = 0.0; t < 7200.0 - 1e-9; t += dt) {
      taken += hydrology::green_ampt_infiltration(k, s, i * dt, dt, f);
    }
    INFO("step " << dt << " s");
    CHECK(f == Approx(green_ampt_closed_form(i, k, s, 7200.0)).epsilon(1e-9));
    CHECK(taken == Approx(f).epsilon(1e-12));
  }
  // Before ponding every drop soaks in.
  double f = 0.0;
  CHECK(hydrology::green_ampt_infiltration(k, s, i * 900.0, 900.0, f) == Approx(i * 900.0));
  // Rain lighter than K never ponds; no conductivity takes nothing; no suction takes K.
  f = 0.0;
  CHECK(hydrology::green_ampt_infiltration(k, s, 0.5 * k * 3600.0, 3600.0, f) ==
        Approx(0.5 * k * 3600.0));
  f = 0.0;
  CHECK(hydrology::green_ampt_infiltration(0.0, s, i * 60.0, 60.0, f) == 0.0);
  f = 0.0;
  CHECK(hydrology::green_ampt_infiltration(k, 0.0, i * 60.0, 60.0, f) == Approx(k * 60.0));
  // Late in a long storm the capacity falls toward K.
  f = 0.0;
  for (int hour = 0; hour < 48; ++hour) hydrology::green_ampt_infiltration(k, s, i * 3600, 3600, f);
  const double last = hydrology::green_ampt_infiltration(k, s, i * 3600, 3600, f) / 3600.0;
  CHECK(last > k);
  CHECK(last < 1.1 * k);
}

TEST_CASE("Green-Ampt losses: an initial loss first, then the soil; the state carries F",
          "[rain][losses]") {
  const auto soil = [] {
    return hydrology::GreenAmptSoil{CellParameter{10.0 * kMmH, nullptr, "hydraulic conductivity"},
                                    CellParameter{0.110, nullptr, "suction head"},
                                    CellParameter{0.3, nullptr, "moisture deficit"}};
  };
  hydrology::GreenAmptLoss loss(soil(), CellParameter{5e-3, nullptr, "initial loss"});
  const std::vector<std::array<double, 2>> centre = {{5.0, 5.0}};
  loss.bind(centre);
  std::vector<double> rain = {4e-3};
  CHECK(loss.take(360.0, rain) == Approx(4e-3));  // all to the initial loss
  CHECK(loss.infiltrated_m()[0] == 0.0);
  rain = {40.0 * kMmH * 3600.0};
  loss.take(3600.0, rain);
  // 1 mm of initial loss, then the soil takes 39 mm of rain over a 40 mm/h hour: it ponds at
  // F = 11 mm; past that it takes less than the rain.
  CHECK(loss.infiltrated_m()[0] > 0.011);
  CHECK(rain[0] > 0.0);
  CHECK(loss.infiltrated_m()[0] + rain[0] == Approx(0.039));

  swe::StateWriter out;
  loss.save_state(out);
  hydrology::GreenAmptLoss restored(soil(), CellParameter{5e-3, nullptr, "initial loss"});
  restored.bind(centre);
  swe::StateReader in(out.bytes(), "a test record");
  restored.restore_state(in);
  CHECK(restored.infiltrated_m()[0] == loss.infiltrated_m()[0]);
}
