// Okada (1985)'s vertical surface displacement against the paper's own check values (Table 2,
// the finite rectangular source: x = 2, y = 3, d = 4, dip 70 degrees, L = 3, W = 2, a Poisson
// solid), and the fault planes placed on the map as catalogues give them.

#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "swemps/tsunami/okada.hpp"

using namespace swemps::tsunami;

namespace {
constexpr double kDip = 70.0 * std::numbers::pi / 180.0;
}

TEST_CASE("Okada's vertical displacement matches the paper's check values", "[tsunami]") {
  // Table 2, case 2: u_z = -2.747e-3 (strike slip), -3.564e-2 (dip slip), 3.214e-3 (tensile),
  // per unit dislocation, to the table's four digits.
  CHECK(okada_vertical(2, 3, 4, kDip, 3, 2, 1, 0, 0, 0.5) == Approx(-2.747e-3).epsilon(2e-4));
  CHECK(okada_vertical(2, 3, 4, kDip, 3, 2, 0, 1, 0, 0.5) == Approx(-3.564e-2).epsilon(2e-4));
  CHECK(okada_vertical(2, 3, 4, kDip, 3, 2, 0, 0, 1, 0.5) == Approx(3.214e-3).epsilon(2e-4));
  // Linear in the dislocation.
  CHECK(okada_vertical(2, 3, 4, kDip, 3, 2, 2, -1, 0.5, 0.5) ==
        Approx(2 * -2.747e-3 + 3.564e-2 + 0.5 * 3.214e-3).epsilon(1e-3));
}

TEST_CASE("a vertical fault's displacement is the limit of steep ones", "[tsunami]") {
  // Eq 29 replaces I4 and I5 where cos(dip) = 0; at 89.9999 degrees eq 28 must agree.
  const double steep = (90.0 - 1e-4) * std::numbers::pi / 180.0;
  for (const double u2 : {0.0, 1.0}) {
    const double u1 = 1.0 - u2;
    const double vertical = okada_vertical(2, 3, 4, std::numbers::pi / 2, 3, 2, u1, u2, 0, 0.5);
    const double near = okada_vertical(2, 3, 4, steep, 3, 2, u1, u2, 0, 0.5);
    CHECK(vertical == Approx(near).epsilon(1e-4));
  }
}

TEST_CASE("a fault plane on the map: a thrust lifts its hanging wall", "[tsunami]") {
  // A thrust striking north (+y), dipping 20 degrees east, its top edge 5 km deep, centred at
  // the origin, 100 km x 50 km, 5 m of slip.
  const FaultPlane thrust{{0.0, 0.0}, 5000.0, 0.0, 20.0, 90.0, 5.0, 100000.0, 50000.0};
  const FaultSource source({thrust});
  // Over the plane, east of its top edge: uplift of the order of the slip's vertical part
  // (1.25 m); beyond its lower edge (47 km east), the trough a thrust leaves (-0.61 m at 60 km,
  // measured); on the footwall, a little uplift fading west (0.06 m at 20 km).
  const double over = source.vertical_displacement(20000.0, 0.0);
  CHECK(over > 0.5);
  CHECK(over < 5.0 * std::sin(20.0 * std::numbers::pi / 180.0) + 1.0);
  CHECK(source.vertical_displacement(60000.0, 0.0) < -0.3);
  CHECK(std::abs(source.vertical_displacement(-20000.0, 0.0)) < 0.1 * over);
  // Symmetric about the plane's midline, and fading far away.
  CHECK(source.vertical_displacement(20000.0, 30000.0) ==
        Approx(source.vertical_displacement(20000.0, -30000.0)).epsilon(1e-9));
  CHECK(std::abs(source.vertical_displacement(500000.0, 0.0)) < 1e-2);
  // Struck south from the same point, the plane dips west (to the right of its strike): the
  // same plane turned half round, its uplift in the west.
  const FaultPlane turned{{0.0, 0.0}, 5000.0, 180.0, 20.0, 90.0, 5.0, 100000.0, 50000.0};
  CHECK(FaultSource({turned}).vertical_displacement(-20000.0, 0.0) == Approx(over).epsilon(1e-9));
  // Two planes add up.
  const FaultSource both({thrust, turned});
  CHECK(both.vertical_displacement(7000.0, 3000.0) ==
        Approx(source.vertical_displacement(7000.0, 3000.0) +
               FaultSource({turned}).vertical_displacement(7000.0, 3000.0))
            .epsilon(1e-12));
}

TEST_CASE("the floor after a rupture reads the displacement sampled once", "[tsunami]") {
  const FaultPlane thrust{{0.0, 0.0}, 5000.0, 0.0, 20.0, 90.0, 5.0, 100000.0, 50000.0};
  const FaultSource source({thrust});
  // 1 km cells over 200 km x 200 km; the displacement varies over the 5 km of the plane's top
  // depth and more, so bilinear reads between centres stay within 2 cm of Okada's (1.5 cm
  // measured).
  const auto grid = sample_displacement(source, -100000.0, 100000.0, -100000.0, 100000.0, 1000.0);
  const RupturedBed bed(
      std::make_shared<swemps::swe::PlaneBed>(-3000.0, std::array{0.0, 0.0}, std::array{0.0, 0.0}),
      grid);
  double worst = 0.0;
  for (double x = -95000.0; x <= 95000.0; x += 3700.0) {
    for (double y = -95000.0; y <= 95000.0; y += 4100.0) {
      worst = std::max(
          worst, std::abs(bed.elevation(x, y) - (-3000.0 + source.vertical_displacement(x, y))));
    }
  }
  CHECK(worst < 0.02);
  // The floor's slope is the flat bed's (none) plus the sampled displacement's own.
  const auto slope = bed.gradient(20300.0, 10700.0);
  const auto lift = grid.gradient(20300.0, 10700.0);
  CHECK(slope[0] == lift[0]);
  CHECK(slope[1] == lift[1]);
  // At a cell centre the read is Okada's own value.
  const double cx = grid.geometry().cell_centre_x(57), cy = grid.geometry().cell_centre_y(88);
  CHECK(bed.elevation(cx, cy) ==
        Approx(-3000.0 + source.vertical_displacement(cx, cy)).epsilon(1e-14));
  INFO("largest bilinear error " << worst << " m");
}

TEST_CASE("a fault source refuses planes that cannot be", "[tsunami]") {
  const FaultPlane good{{0.0, 0.0}, 5000.0, 0.0, 20.0, 90.0, 5.0, 1e5, 5e4};
  auto with = [&](auto change) {
    FaultPlane f = good;
    change(f);
    return std::vector<FaultPlane>{f};
  };
  CHECK_THROWS_AS(FaultSource(with([](FaultPlane& f) { f.dip_deg = 0.0; })), std::invalid_argument);
  CHECK_THROWS_AS(FaultSource(with([](FaultPlane& f) { f.dip_deg = 91.0; })),
                  std::invalid_argument);
  CHECK_THROWS_AS(FaultSource(with([](FaultPlane& f) { f.width_m = 0.0; })), std::invalid_argument);
  CHECK_THROWS_AS(FaultSource(with([](FaultPlane& f) { f.top_depth_m = -1.0; })),
                  std::invalid_argument);
  CHECK_THROWS_AS(FaultSource(with([](FaultPlane& f) { f.slip_m = NAN; })), std::invalid_argument);
  CHECK_THROWS_AS(FaultSource({good}, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(FaultSource({}), std::invalid_argument);
}
