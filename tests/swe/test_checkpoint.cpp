// Failing well at the level of the simulation: a saved state restored into a simulation built
// from the same scene continues bit for bit (every effect's state included), a record that
// does not fit is refused, and a non-finite value stops the run at the last good state with a
// message naming the step, the particle and the quantity.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "swemps/io/checkpoint.hpp"
#include "swemps/particles/seeding.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/simulation.hpp"
#include "swemps/swe/state_record.hpp"

using namespace swemps;
using Catch::Contains;

namespace {

// A dam break down a sloping, rough channel with every effect that carries state from step to
// step: an inflow (its strip), splitting, eddy viscosity (its time-step limit), an outflow line
// and the open end of the domain (their counts).
constexpr const char* kEffectsScene = R"({
  "name": "restart", "end_time": 10,
  "numerics": {"eddy_viscosity": 0.01},
  "domain": {"x_min": 0, "x_max": 3, "y_min": 0, "y_max": 1},
  "water": [{"rectangle": {"x_min": 0.2, "x_max": 1.2, "y_min": 0, "y_max": 1},
             "depth": 0.2, "spacing": 0.1}],
  "walls": [{"polyline": [[3, 0], [0, 0], [0, 1], [3, 1]]}],
  "bed": {"plane": {"slope": [-0.05, 0]}},
  "friction": {"manning_n": 0.02},
  "splitting": {"threshold": 1.5},
  "inflow": [{"line": [[0.05, 0.05], [0.05, 0.95]], "hydrograph": [[0, 0.05], [2, 0.1]],
              "direction": [1, 0], "depth": 0.1}],
  "outflow": [{"line": [[2.0, 0], [2.0, 1]]}],
  "output": {"path": "restart.nc", "interval": 1}
})";

scenario::Scenario effects_scene() {
  return scenario::parse(kEffectsScene, std::filesystem::temp_directory_path(), "test");
}

void steps(swe::Simulation& sim, int n) {
  for (int k = 0; k < n; ++k) sim.advance(sim.stable_time_step());
}

// Every field of every fluid particle, and what the run has counted, bit for bit.
void require_same_state(swe::Simulation& a, swe::Simulation& b, bool same_effects = true) {
  a.refresh();
  b.refresh();
  REQUIRE(a.time() == b.time());
  REQUIRE(a.steps() == b.steps());
  REQUIRE(a.particle_steps() == b.particle_steps());
  REQUIRE(a.ledger().added_m3 == b.ledger().added_m3);
  REQUIRE(a.ledger().removed_m3 == b.ledger().removed_m3);
  const auto& p = a.particles();
  const auto& q = b.particles();
  const std::size_t n = p.fluid_count();
  REQUIRE(q.fluid_count() == n);
  const auto same = [n](const std::vector<double>& f, const std::vector<double>& g) {
    return std::equal(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(n), g.begin());
  };
  CHECK(same(p.x, q.x));
  CHECK(same(p.y, q.y));
  CHECK(same(p.u, q.u));
  CHECK(same(p.v, q.v));
  CHECK(same(p.volume, q.volume));
  CHECK(same(p.depth, q.depth));
  CHECK(same(p.area, q.area));
  CHECK(same(p.initial_area, q.initial_area));
  CHECK(same(p.bed, q.bed));
  if (!same_effects) return;
  const auto ea = a.effect_times(), eb = b.effect_times();
  REQUIRE(ea.size() == eb.size());
  for (std::size_t k = 0; k < ea.size(); ++k) CHECK(ea[k].report == eb[k].report);
}

// A scene run straight for 70 steps, and stopped after 29, saved, restored into a simulation
// built anew and run the 41 steps left: what require_same_state compares.
struct StraightAndRestarted {
  swe::Simulation straight, restarted;
};
StraightAndRestarted run_with_a_restart(const scenario::Scenario& scene) {
  auto straight = scenario::make_simulation(scene);
  auto stopped = scenario::make_simulation(scene);
  steps(stopped, 29);
  swe::StateWriter saved;
  stopped.save_state(saved);
  auto restarted = scenario::make_simulation(scene);
  swe::StateReader in(saved.bytes(), "test state");
  restarted.restore_state(in);
  steps(straight, 70);
  steps(restarted, 41);
  return {std::move(straight), std::move(restarted)};
}

// Writes NaN or infinity into one field of one particle, or adds a particle at a NaN position,
// in every step that starts at or after a given time: stateless, so that the rollback's replay
// of earlier steps is untouched by it.
class Poison final : public swe::Effect {
 public:
  enum class Field { acceleration, velocity, volume, added_position };
  Poison(swe::Stage stage, Field field, std::size_t particle, double from_s)
      : stage_(stage), field_(field), particle_(particle), from_s_(from_s) {}
  std::string_view name() const override { return "poison"; }
  swe::Stage stage() const override { return stage_; }
  void apply(swe::StepContext& c) override {
    if (c.time_s < from_s_) return;
    switch (field_) {
      case Field::acceleration: c.accel_x[particle_] = std::nan(""); break;
      case Field::velocity: c.particles.v[particle_] = INFINITY; break;
      case Field::volume: c.particles.volume[particle_] = std::nan(""); break;
      case Field::added_position:
        c.particles.add_fluid(std::nan(""), 0.1, 0.0, 0.0, 2.5e-4, 0.1, 2.5e-3, 0.0);
        break;
    }
  }

 private:
  swe::Stage stage_;
  Field field_;
  std::size_t particle_;
  double from_s_;
};

// Still water over the left half of a closed box, with a bump that sets it moving.
swe::Simulation basin(std::unique_ptr<swe::Effect> effect, swe::Settings settings = {}) {
  const auto lattice = particles::fill_polygon({{0, 0}, {1, 0}, {1, 0.5}, {0, 0.5}}, 0.05);
  particles::SweParticles p;
  for (const auto& pt : lattice.points) {
    const double depth = pt[0] < 0.3 ? 0.3 : 0.1;
    p.add_fluid(pt[0], pt[1], 0.0, 0.0, depth * lattice.cell_area_m2, depth, lattice.cell_area_m2,
                0.0);
  }
  const std::array<double, 2> a{0, 0}, b{2, 0}, c{2, 0.5}, d{0, 0.5};
  boundaries::GhostWalls walls({{a, b}, {b, c}, {c, d}, {d, a}});
  std::vector<std::unique_ptr<swe::Effect>> effects;
  if (effect) effects.push_back(std::move(effect));
  return swe::Simulation(std::move(p), settings, std::move(walls), std::move(effects));
}

// The time each step of the basin starts at, from a run without poison.
std::vector<double> step_start_times(int n) {
  auto sim = basin(nullptr);
  std::vector<double> times;
  for (int k = 0; k < n; ++k) {
    times.push_back(sim.time());
    sim.advance(sim.stable_time_step());
  }
  return times;
}

}  // namespace

TEST_CASE("a simulation restored from its saved state continues bit for bit", "[swe][checkpoint]") {
  const auto scene = effects_scene();
  auto straight = scenario::make_simulation(scene);
  auto stopped = scenario::make_simulation(scene);
  // 29 steps: between two sorts (every 8), so the restored run must take the schedule over.
  steps(stopped, 29);
  swe::StateWriter saved;
  stopped.save_state(saved);

  // Through a checkpoint file, as a run would.
  testing::TempDir dir("checkpoint");
  io::Checkpoint c;
  c.scenario_hash = 42;
  c.program = "test";
  c.time_s = stopped.time();
  c.steps = stopped.steps();
  c.simulation.assign(saved.bytes().begin(), saved.bytes().end());
  io::write_checkpoint(dir.path() / "run.checkpoint", c);
  const auto read = io::read_checkpoint(dir.path() / "run.checkpoint");
  CHECK(read.scenario_hash == 42);
  CHECK(read.steps == 29);
  CHECK(read.simulation == c.simulation);

  auto restarted = scenario::make_simulation(scene);
  swe::StateReader in(read.simulation, "test checkpoint");
  restarted.restore_state(in);
  in.expect_end();

  steps(straight, 70);
  steps(restarted, 41);
  // Every effect has acted, or the test would not cover its state.
  REQUIRE(straight.ledger().added_m3 > 0.0);
  REQUIRE(straight.ledger().removed_m3 > 0.0);
  bool split = false;
  for (const auto& e : straight.effect_times()) {
    if (e.name == "particle splitting") split = e.report.rfind("0 splits", 0) != 0;
  }
  CHECK(split);
  require_same_state(straight, restarted);
}

TEST_CASE("a run that repairs its neighbour rows continues bit for bit after a restart",
          "[swe][checkpoint]") {
  // Without walls the rows around split particles and widened kernels are repaired, not searched
  // anew (neighbors/row_repair.hpp); a restored state searches every row anew, and must find
  // the same rows.
  auto scene = effects_scene();
  scene.walls.clear();
  auto [straight, restarted] = run_with_a_restart(scene);
  REQUIRE(restarted.search_counts().repairs > 0);
  require_same_state(straight, restarted);
}

TEST_CASE("a run with a sea boundary continues bit for bit after a restart",
          "[swe][checkpoint][sea_boundary]") {
  // The level rises while the run is stopped and falls after: the restored buffer must let
  // water in and take it out as the straight run does, and hold the same states.
  const auto scene = scenario::parse(R"({"name": "sea", "end_time": 2,
    "domain": {"x_min": 0, "x_max": 3, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 3, "y_min": 0, "y_max": 1},
               "depth": 0.5, "spacing": 0.1}],
    "walls": [{"polyline": [[3, 0], [0, 0], [0, 1], [3, 1]]}],
    "sea_boundaries": [{"line": [[3, 0], [3, 1]], "type": "level",
                        "series": [[0, 0.5], [0.4, 0.55], [0.8, 0.45]]}],
    "output": {"path": "sea.nc"}})",
                                     std::filesystem::temp_directory_path(), "test");
  auto [straight, restarted] = run_with_a_restart(scene);
  REQUIRE(straight.ledger().added_m3 > 0.0);
  REQUIRE(straight.ledger().removed_m3 > 0.0);
  require_same_state(straight, restarted);
}

TEST_CASE("a saved state that does not fit is refused", "[swe][checkpoint]") {
  auto scene = effects_scene();
  auto sim = scenario::make_simulation(scene);
  steps(sim, 3);
  swe::StateWriter saved;
  sim.save_state(saved);

  SECTION("a scene with other effects") {
    scene.splitting.reset();
    auto other = scenario::make_simulation(scene);
    swe::StateReader in(saved.bytes(), "the record");
    CHECK_THROWS_WITH(other.restore_state(in), Contains("effect"));
  }
  SECTION("a record cut short") {
    auto other = scenario::make_simulation(scene);
    swe::StateReader in(saved.bytes().first(saved.size() / 2), "the record");
    CHECK_THROWS_WITH(other.restore_state(in),
                      Contains("the record ends early") || Contains("the record is damaged"));
  }
  SECTION("checkpoint files: damaged, cut short, of another kind") {
    testing::TempDir dir("checkpoint");
    const auto path = dir.path() / "run.checkpoint";
    io::Checkpoint c;
    c.simulation.assign(saved.bytes().begin(), saved.bytes().end());
    io::write_checkpoint(path, c);
    std::string bytes;
    {
      std::ifstream in(path, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const auto rewrite = [&](const std::string& text) {
      std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    };
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x10;
    rewrite(flipped);
    CHECK_THROWS_WITH(io::read_checkpoint(path), Contains("damaged"));
    rewrite(bytes.substr(0, bytes.size() - 100));
    CHECK_THROWS_WITH(io::read_checkpoint(path), Contains("cut short"));
    rewrite("{\"name\": \"a scene, not a checkpoint\"}\n");
    CHECK_THROWS_WITH(io::read_checkpoint(path), Contains("not a swe-mps checkpoint"));
    CHECK_THROWS_WITH(io::read_checkpoint(dir.path() / "nope"), Contains("no such file"));
  }
}

TEST_CASE("a non-finite value stops the run at the last good state", "[swe][breakdown]") {
  // Step 37 breaks: after the snapshot of step 32, so the rollback replays steps 33 to 36.
  constexpr int kBrokenStep = 37;
  const auto times = step_start_times(kBrokenStep);
  const double from_s = times[kBrokenStep - 1];
  struct Case {
    swe::Stage stage;
    Poison::Field field;
    const char* quantity;
  };
  for (const Case& k :
       {Case{swe::Stage::forces, Poison::Field::acceleration, "non-finite acceleration (nan, "},
        Case{swe::Stage::velocity, Poison::Field::velocity, "non-finite velocity (u, v) = ("},
        Case{swe::Stage::topology, Poison::Field::volume, "non-finite volume nan"},
        Case{swe::Stage::topology, Poison::Field::added_position,
             "non-finite position (nan, 0.1) m of particle "}}) {
    INFO(k.quantity);
    auto sim = basin(std::make_unique<Poison>(k.stage, k.field, 5, from_s));
    std::string message;
    bool at_last_good_state = false;
    try {
      for (int s = 0; s < 100; ++s) sim.advance(sim.stable_time_step());
      FAIL("no breakdown");
    } catch (const swe::SimulationError& e) {
      message = e.what();
      at_last_good_state = e.at_last_good_state();
    }
    CHECK(at_last_good_state);
    CHECK_THAT(message, Contains(k.quantity));
    CHECK_THAT(message, Contains("in step " + std::to_string(kBrokenStep) + " (t = "));
    CHECK_THAT(message, Contains("the last good state"));
    CHECK_THAT(message, Contains("(step " + std::to_string(kBrokenStep - 1) + ")"));
    // The volume is only found in the summed depth, after the sort renumbered the particles;
    // the others name particle 5 and where it was when the step began.
    // A new particle is found by the cell lists, which refuse its position.
    if (k.field == Poison::Field::volume) {
      CHECK_THAT(message, Contains(" of particle "));
      CHECK_THAT(message, Contains("after the depth summation"));
    } else if (k.field == Poison::Field::added_position) {
      CHECK_THAT(message, Contains("(added by an effect in this step)"));
    } else {
      CHECK_THAT(message, Contains("of particle 5 (at ("));
      CHECK_THAT(message, Contains("when the step began"));
    }

    // The simulation holds the state the broken step started from, bit for bit.
    auto reference = basin(nullptr);
    steps(reference, kBrokenStep - 1);
    CHECK(sim.time() == from_s);
    require_same_state(sim, reference, false);
    // Going on breaks down the same way: the step's state is checked as the next refresh.
    CHECK_THROWS_AS(steps(sim, 2), swe::SimulationError);
    CHECK(sim.steps() == kBrokenStep - 1);
  }
}

TEST_CASE("a time step below the floor stops the run where it is", "[swe][breakdown]") {
  swe::Settings settings;
  settings.min_time_step_s = 1.0;  // s: far above what eq 13 allows the basin
  auto sim = basin(nullptr, settings);
  try {
    (void)sim.stable_time_step();
    FAIL("no breakdown");
  } catch (const swe::SimulationError& e) {
    CHECK(e.at_last_good_state());
    CHECK_THAT(std::string(e.what()), Contains("the time step collapsed to"));
    CHECK_THAT(std::string(e.what()), Contains("for step 1 at t = 0 s, limited by particle"));
  }
  CHECK(sim.steps() == 0);
}
