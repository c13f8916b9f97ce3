// Tests of the rain effect: the cells it falls on, the water it gives to particles over wet
// cells and the particles it creates on dry ones, its losses, and its books: the rain that
// fell is the rain booked, the losses and the water pending in dry cells, to round-off.

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

#include "../support/effect_stepper.hpp"
#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/swe/state_record.hpp"

using namespace swemps;
using boundaries::Hydrograph;
using hydrology::Rain;
using hydrology::RainSettings;

namespace {

constexpr double kMmH = hydrology::kMetresPerSecondPerMmPerHour;

std::unique_ptr<hydrology::RainLoss> initial_continuing(double initial_m, double continuing_m_s) {
  return std::make_unique<hydrology::InitialContinuingLoss>(
      hydrology::CellParameter{initial_m, nullptr, "initial loss"},
      hydrology::CellParameter{continuing_m_s, nullptr, "continuing loss"});
}

using Stepper = testing::EffectStepper;

// A 10 m x 4 m domain in cells of 1 m.
RainSettings ten_by_four() {
  RainSettings s;
  s.domain = {0.0, 10.0, 0.0, 4.0};
  s.spacing_m = 1.0;
  return s;
}

// fallen = booked + lost + pending, relative to what fell.
void check_books(const Rain& rain, const swe::VolumeLedger& ledger) {
  CHECK(ledger.rain_m3 == Approx(rain.volume_added()).epsilon(1e-14));
  const double accounted = rain.volume_added() + rain.volume_lost() + rain.pending_volume();
  CHECK(accounted == Approx(rain.volume_fallen()).epsilon(1e-12));
}

}  // namespace

TEST_CASE("rain cells tile the domain; a polygon keeps the cells whose centres it holds",
          "[rain]") {
  auto s = ten_by_four();
  s.spacing_m = 0.9;  // 10 / 0.9 rounds to 11 columns, 4 / 0.9 to 4 rows
  const Rain whole(s, Hydrograph({{0.0, 1.0}}));
  CHECK(whole.cell_count() == 44);
  CHECK(whole.rain_area_m2() == Approx(40.0).epsilon(1e-14));

  s.spacing_m = 1.0;
  s.polygon = {{0.0, 0.0}, {5.0, 0.0}, {5.0, 4.0}, {0.0, 4.0}};  // the western half
  const Rain half(s, Hydrograph({{0.0, 1.0}}));
  CHECK(half.cell_count() == 20);
  for (std::size_t k = 0; k < half.cell_count(); ++k) CHECK(half.cell_centre(k)[0] < 5.0);
}

TEST_CASE("rain on a dry domain makes one particle per cell once a cell holds the creation depth",
          "[rain]") {
  auto s = ten_by_four();
  s.creation_depth_m = 1e-3;
  Rain rain(s, Hydrograph({{0.0, 36.0 * kMmH}}));  // 36 mm/h: 1 mm in 100 s
  Stepper st;
  // 60 s: 0.6 mm in every cell, pending.
  st.step(rain, 0.0, 60.0);
  CHECK(st.particles.fluid_count() == 0);
  CHECK(rain.pending_volume() == Approx(0.6e-3 * 40.0));
  CHECK(st.ledger.rain_m3 == 0.0);
  // 60 s more: 1.2 mm, past the creation depth: a particle at rest at every cell's centre,
  // holding all that cell's water, its created area the cell's.
  st.step(rain, 60.0, 60.0);
  REQUIRE(st.particles.fluid_count() == 40);
  CHECK(rain.particles_created() == 40);
  for (std::size_t i = 0; i < 40; ++i) {
    CHECK(st.particles.volume[i] == Approx(1.2e-3));
    CHECK(st.particles.initial_area[i] == Approx(1.0));
    CHECK(st.particles.u[i] == 0.0);
    CHECK(std::abs(std::fmod(st.particles.x[i], 1.0) - 0.5) < 1e-12);
  }
  CHECK(rain.pending_volume() == 0.0);
  CHECK(st.ledger.rain_m3 == Approx(1.2e-3 * 40.0));
  check_books(rain, st.ledger);
}

TEST_CASE("rain over wet cells goes to the particles over them, which keep their momentum",
          "[rain]") {
  auto s = ten_by_four();
  Rain rain(s, Hydrograph({{0.0, 360.0 * kMmH}}));  // 0.1 mm/s
  Stepper st;
  // Two particles 4 m apart, each 1 m^2 in area: each covers the cells whose centres lie
  // within 1 m of it, and the rest of the domain stays dry.
  st.particles.add_fluid(2.5, 1.5, 1.0, 0.0, 0.1, 0.1, 1.0, 0.0);
  st.particles.add_fluid(6.5, 1.5, 0.0, -2.0, 0.3, 0.3, 1.0, 0.0);
  st.step(rain, 0.0, 1.0);
  // Each covers its own cell and the 4 beside it: 5 cells of 0.1 mm.
  CHECK(st.particles.volume[0] == Approx(0.1 + 5e-4));
  CHECK(st.particles.volume[1] == Approx(0.3 + 5e-4));
  CHECK(st.particles.u[0] == Approx(1.0 * 0.1 / (0.1 + 5e-4)));
  CHECK(st.particles.v[1] == Approx(-2.0 * 0.3 / (0.3 + 5e-4)));
  CHECK(rain.pending_volume() == Approx(1e-4 * 30.0));
  check_books(rain, st.ledger);

  // A cell under both shares its rain equally: particles 1 m apart both cover the cells
  // between them.
  Rain shared(s, Hydrograph({{0.0, 360.0 * kMmH}}));
  Stepper two;
  two.particles.add_fluid(4.5, 1.5, 0.0, 0.0, 0.1, 0.1, 1.0, 0.0);
  two.particles.add_fluid(5.5, 1.5, 0.0, 0.0, 0.1, 0.1, 1.0, 0.0);
  two.step(shared, 0.0, 1.0);
  // Cells (4.5, 1.5) and (5.5, 1.5) are under both; each particle has 3 of its own and half
  // of 2: 4 cells' rain.
  CHECK(two.particles.volume[0] == Approx(0.1 + 4e-4));
  CHECK(two.particles.volume[1] == Approx(0.1 + 4e-4));
  check_books(shared, two.ledger);
}

TEST_CASE("the rain gathered by a dry cell joins the water that reaches it", "[rain]") {
  auto s = ten_by_four();
  s.creation_depth_m = 1.0;  // no cell makes a particle here
  Rain rain(s, Hydrograph({{0.0, 360.0 * kMmH}}));
  Stepper st;
  st.step(rain, 0.0, 10.0);                                           // 1 mm pending everywhere
  st.particles.add_fluid(0.5, 0.5, 0.0, 0.0, 0.01, 0.01, 0.01, 0.0);  // covers its own cell only
  st.step(rain, 10.0, 1.0);
  CHECK(st.particles.volume[0] == Approx(0.01 + 1.1e-3));
  check_books(rain, st.ledger);
}

TEST_CASE("rain losses: the initial loss first, then the continuing loss of each step", "[rain]") {
  auto s = ten_by_four();
  Rain rain(s, Hydrograph({{0.0, 40.0 * kMmH}}), initial_continuing(2e-3, 10.0 * kMmH));
  Stepper st;
  st.particles.add_fluid(5.0, 2.0, 0.0, 0.0, 100.0, 2.5, 40.0, 0.0);  // covers every cell
  const double hour = 3600.0;
  // The first 3 minutes bring 2 mm: all taken by the initial loss.
  st.step(rain, 0.0, 0.05 * hour);
  CHECK(st.ledger.rain_m3 == 0.0);
  CHECK(rain.volume_lost() == Approx(2e-3 * 40.0));
  // Then 40 - 10 mm/h reaches the water.
  st.step(rain, 0.05 * hour, hour);
  CHECK(st.ledger.rain_m3 == Approx(30e-3 * 40.0));
  CHECK(st.particles.volume[0] == Approx(100.0 + 30e-3 * 40.0));
  check_books(rain, st.ledger);

  // Rain lighter than the continuing loss never reaches the ground's water.
  Rain soaked(ten_by_four(), Hydrograph({{0.0, 5.0 * kMmH}}), initial_continuing(0.0, 10.0 * kMmH));
  Stepper dry;
  dry.step(soaked, 0.0, hour);
  CHECK(dry.ledger.rain_m3 == 0.0);
  CHECK(soaked.pending_volume() == 0.0);
  CHECK(soaked.volume_lost() == Approx(5e-3 * 40.0));
}

TEST_CASE("a rain series is integrated exactly over each step", "[rain]") {
  auto s = ten_by_four();
  s.creation_depth_m = 1.0;
  // 0 -> 72 mm/h over an hour, then back to 0 over the next: 72 mm in all.
  Rain rain(s, Hydrograph({{0.0, 0.0}, {3600.0, 72.0 * kMmH}, {7200.0, 0.0}}));
  Stepper st;
  for (double t = 0.0; t < 7200.0; t += 450.0) st.step(rain, t, 450.0);
  CHECK(rain.volume_fallen() == Approx(72e-3 * 40.0).epsilon(1e-13));
  CHECK(rain.pending_volume() == Approx(72e-3 * 40.0).epsilon(1e-13));
  // While dry, the step lets the peak rate fill a dry cell to the creation depth once.
  CHECK(rain.time_step_limit(st.settings, 0.0) == Approx(1.0 / (72.0 * kMmH)));
}

TEST_CASE("rain's state carries what the cells have gathered and have still to lose", "[rain]") {
  auto s = ten_by_four();
  Rain rain(s, Hydrograph({{0.0, 3.6 * kMmH}}), initial_continuing(1e-3, 0.0));
  Stepper st;
  st.step(rain, 0.0, 1500.0);  // 1.5 mm: 1 lost, 0.5 pending
  swe::StateWriter out;
  rain.save_state(out);
  Rain restored(s, Hydrograph({{0.0, 3.6 * kMmH}}), initial_continuing(1e-3, 0.0));
  swe::StateReader in(out.bytes(), "a test record");
  restored.restore_state(in);
  CHECK(restored.pending_volume() == rain.pending_volume());
  CHECK(restored.volume_lost() == rain.volume_lost());
  Stepper b;
  st.step(rain, 1500.0, 1000.0);
  b.step(restored, 1500.0, 1000.0);
  CHECK(b.particles.fluid_count() == st.particles.fluid_count());
  CHECK(restored.particles_created() == rain.particles_created());

  // A record of another scene's cells is refused.
  auto other = ten_by_four();
  other.spacing_m = 2.0;
  Rain coarser(other, Hydrograph({{0.0, 1.0}}));
  swe::StateReader again(out.bytes(), "a test record");
  CHECK_THROWS_AS(coarser.restore_state(again), swe::StateError);
}

TEST_CASE("rain refuses settings that make no cells or no sense", "[rain]") {
  const Hydrograph rate({{0.0, 1.0}});
  auto bad = ten_by_four();
  bad.spacing_m = 0.0;
  CHECK_THROWS_AS(Rain(bad, rate), std::invalid_argument);
  bad = ten_by_four();
  bad.creation_depth_m = -1.0;
  CHECK_THROWS_AS(Rain(bad, rate), std::invalid_argument);
  CHECK_THROWS_AS(Rain(ten_by_four(), rate, initial_continuing(0.0, -1.0)), std::invalid_argument);
  bad = ten_by_four();
  bad.polygon = {{20.0, 20.0}, {30.0, 20.0}, {30.0, 30.0}};  // outside the domain
  CHECK_THROWS_AS(Rain(bad, rate), std::invalid_argument);
  bad = ten_by_four();
  bad.name.clear();
  CHECK_THROWS_AS(Rain(bad, rate), std::invalid_argument);
}
