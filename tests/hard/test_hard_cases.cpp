// The hard-case suite (docs/robustness.md): scenes chosen to break particle shallow-water
// codes, each run from its scene file in cases/hard/ and checked after every step for the
// invariants of verification/invariants.hpp: every value finite, depth positive, volume
// conserved to 1e-12 net of inflow and outflow, no particle behind a wall, no water leaving
// a closed scene, no time step below the floor (stable_time_step() throws), and in closed
// frictionless scenes total energy never above its start.
//
// The energy bound is E(t) <= E_0 (1 + 1e-9): such a scene has no source of energy, so any
// growth beyond round-off (1e-9 leaves room for the summation order of some 1e4 terms) is
// made by the scheme. The scenes that check it run the default scheme, whose force is the
// exact gradient of the potential energy (verification/invariants.hpp) and whose pairwise
// dissipation takes what the time integration would otherwise put back: over a level bed, and
// over a sloping one under the point bed term. The default balanced bed term is an external
// force, exact at rest but not such a gradient: a sheet spreading over a dry slope gains
// energy under it, and its scenes are held to the bound measured for them (kBalancedEnergy).
// The seed scheme's eq 6 is not such a gradient either, and gains energy in a strong shock
// (measured below and in docs/robustness.md).

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/verification/invariants.hpp"
#include "swemps/verification/stoker.hpp"

using namespace swemps;

namespace {

const std::filesystem::path kCases = std::filesystem::path(SWEMPS_SOURCE_DIR) / "cases" / "hard";

constexpr double kEnergyRoundOff = 1e-9;
// The thin film under the balanced bed term: measured max (E - E0) / E0 = +2.8e-3 over its
// 10 s (+6.4e-3 to +6.7e-3 before the planes' arrangement error was taken out; docs/method.md,
// "Where the sheet gains its energy"); 1e-2 leaves room for round-off in the film's shoreline
// and fails on a gain that keeps growing (the same correction with the kernel's values as the
// levels' weights: +2.1e-2).
constexpr double kBalancedEnergy = 1e-2;

std::vector<std::array<double, 2>> domain_box(const scenario::Scenario& scene) {
  const auto& d = scene.domain;
  return {{d.x_min, d.y_min}, {d.x_max, d.y_min}, {d.x_max, d.y_max}, {d.x_min, d.y_max}};
}

struct HardRun {
  verification::InvariantRecord record;
  std::size_t steps = 0;
  std::optional<verification::StokerErrors> stoker;
};

struct RunOptions {
  bool closed = true;                                    // no water enters or leaves
  bool check_energy = true;                              // closed and frictionless
  double energy_growth = kEnergyRoundOff;                // the bound when checked
  std::function<void(scenario::Scenario&)> adjust = {};  // changes to the scene as loaded
  // Stoker comparison at this time (s), for the wet dam breaks.
  std::optional<double> stoker_time_s = {};
};

// Runs the scene to its end time, checking the invariants after every step.
HardRun run_hard_case(const std::string& file, const RunOptions& options) {
  auto scene = scenario::load(kCases / file);
  if (options.adjust) options.adjust(scene);
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  verification::InvariantBounds bounds;
  bounds.bed = built.terrain.bed;
  bounds.closed = options.closed;
  bounds.energy_growth = options.check_energy ? options.energy_growth : -1.0;
  bounds.inside_polygon = domain_box(scene);
  verification::InvariantMonitor monitor(sim, bounds);
  HardRun run;
  const auto check = [&] { monitor.check(sim); };
  if (options.stoker_time_s) {
    sim.advance_to(*options.stoker_time_s, check);
    sim.refresh();
    const auto& d = scene.domain;
    // The two water bodies: upstream and downstream of the dam.
    const verification::StokerProblem problem{
        scene.water[0].polygon[1][0],
        std::get<scenario::UniformDepth>(scene.water[0].depth).depth_m,
        std::get<scenario::UniformDepth>(scene.water[1].depth).depth_m,
        scene.numerics.gravity_m_s2};
    const auto profile = verification::channel_profile(sim.particles(), sim.kernel(),
                                                       {d.x_min, d.x_max, d.y_min, d.y_max},
                                                       scene.water[0].spacing_m / 4.0);
    run.stoker = verification::compare_with_stoker(problem, profile, *options.stoker_time_s);
  }
  sim.advance_to(scene.end_time_s, check);
  run.record = monitor.record();
  run.steps = sim.steps();
  const auto& r = run.record;
  std::printf(
      "%s: %zu steps, particles %zu..%zu, min depth %.3e m, max |dV/V| %.2e, max (E-E0)/E0 "
      "%.3e, max energy rise %.3e, max speed %.3g m/s, min dt %.3e s\n",
      file.c_str(), run.steps, r.min_particles, r.max_particles, r.min_depth_m, r.max_volume_change,
      r.max_energy_growth, r.max_energy_rise, r.max_speed_m_s, r.min_time_step_s);
  return run;
}

void require_invariants(const HardRun& run) {
  INFO(run.record.first_violation);
  CHECK(run.record.first_violation.empty());
  CHECK(run.record.non_finite == 0);
  CHECK(run.record.outside == 0);
  CHECK(run.record.min_depth_m > 0.0);
  CHECK(run.record.max_volume_change <= 1e-12);
}

void print_stoker(const char* label, const verification::StokerErrors& e) {
  std::printf(
      "%s: Stoker L1 %.4f, Linf %.4f, plateau overshoot %.4f, shock at %.3f m (exact %.3f)\n",
      label, e.l1, e.linf, e.plateau_overshoot, e.shock_x_m, e.exact_shock_x_m);
}

}  // namespace

TEST_CASE("Wet dam break 10:1: the shock stays sane, with and without dissipation", "[hard]") {
  RunOptions plain;
  plain.stoker_time_s = 1.5;
  const auto with = run_hard_case("dam-break-wet-10.json", plain);
  require_invariants(with);

  // Without dissipation the shock's energy comes back as noise: measured over the whole 8 s,
  // E rises 12 % above E0, particles reach 18 m/s and the step falls to 1e-4 s (7,922 steps
  // against 1,456), so that run stops at the Stoker time and its energy is not bounded.
  RunOptions inviscid = plain;
  inviscid.check_energy = false;
  inviscid.adjust = [](scenario::Scenario& s) {
    s.numerics.dissipation = 0.0;
    s.end_time_s = 1.5;
  };
  const auto without = run_hard_case("dam-break-wet-10.json", inviscid);
  require_invariants(without);

  print_stoker("conservative scheme, dissipation 1 (default)", *with.stoker);
  print_stoker("conservative scheme, no dissipation", *without.stoker);
  // What the pairwise dissipation is for (measured at 1.5 s, with particle shifting): with it
  // the shock runs at Stoker's speed (0.02 m behind, against 0.77 m behind without), the
  // depth L1 is 0.77 % of h_l against 3.2 %, the fastest particle 2.7 m/s against 5.7 m/s,
  // and E never rises above its lowest value, over all 8 s and the reflections from both
  // ends. The overshoot just behind the shock (11 % with, 17 % without) moves by several per
  // cent with round-off, so it is not compared.
  const auto shock_miss = [](const verification::StokerErrors& e) {
    return std::abs(e.shock_x_m - e.exact_shock_x_m);
  };
  CHECK(shock_miss(*with.stoker) < shock_miss(*without.stoker));
  CHECK(with.stoker->l1 < without.stoker->l1);
  CHECK(with.record.max_speed_m_s < without.record.max_speed_m_s);
  CHECK(with.record.max_energy_rise == 0.0);
  CHECK(without.record.max_energy_rise > 0.0);
  // Near Stoker's solution (measured L1 0.77 % of h_l with dissipation, 3.2 % without; the
  // seed scheme's bound below is 10 %: a particle shock is spread over a few support radii).
  CHECK(with.stoker->l1 < 0.03);
  CHECK(without.stoker->l1 < 0.1);
}

TEST_CASE("Wet dam break 10:1 under the seed scheme, with and without shock viscosity", "[hard]") {
  const auto seed = [](double shock_viscosity) {
    return [shock_viscosity](scenario::Scenario& s) {
      s.numerics.scheme = swe::SchemeKind::seed;
      s.numerics.gradient = swe::GradientVariant::summation;
      if (shock_viscosity > 0.0) s.shock_viscosity = shock_viscosity;
    };
  };
  RunOptions plain;
  plain.stoker_time_s = 1.5;
  plain.adjust = seed(0.0);
  const auto without = run_hard_case("dam-break-wet-10.json", plain);
  require_invariants(without);

  RunOptions viscous = plain;
  viscous.adjust = seed(0.5);
  const auto with = run_hard_case("dam-break-wet-10.json", viscous);
  require_invariants(with);

  print_stoker("seed scheme without shock viscosity", *without.stoker);
  print_stoker("seed scheme with shock viscosity 0.5", *with.stoker);
  // What the viscosity is for: the particle shock rings, overshooting the middle state, and
  // the energy the shock should take comes partly back as noise. Dissipation only between
  // approaching particles damps both (measured: overshoot 16 % -> 11 %, energy rise 2.1 % ->
  // 0.15 % of E_0). Both runs keep every invariant; these say the effect does its job.
  CHECK(with.stoker->plateau_overshoot < without.stoker->plateau_overshoot);
  CHECK(with.record.max_energy_rise < without.record.max_energy_rise);
  // Both stay near Stoker's solution (10 % of h_l: the particle shock is spread over a few
  // support radii).
  CHECK(without.stoker->l1 < 0.1);
  CHECK(with.stoker->l1 < 0.1);
}

TEST_CASE("Wet dam break 10:1 under the seed scheme's eq 6 stays finite and inside", "[hard]") {
  // eq 6 is not the gradient of an energy: in this shock it gains energy (docs/robustness.md),
  // so only the other invariants are checked.
  RunOptions options;
  options.check_energy = false;
  options.adjust = [](scenario::Scenario& s) {
    s.numerics.scheme = swe::SchemeKind::seed;
    s.numerics.gradient = swe::GradientVariant::mps;
  };
  require_invariants(run_hard_case("dam-break-wet-10.json", options));
}

TEST_CASE("Wet dam break 1000:1: millimetre water under a metre-deep bore", "[hard]") {
  require_invariants(run_hard_case("dam-break-wet-1000.json", {}));
}

TEST_CASE("Thin film: depths of 1e-5 m and below", "[hard]") {
  // The film piles against the wall, squeezed to 1/1000 of its seeded area, and the sheet's toe
  // runs over micrometres of water: the balanced term's plane is fitted through finer points of
  // the bed where a kernel reaches no neighbouring node, and cut back where only a sliver of the
  // support is wet (swe/balanced_bed_slope.cpp). Before either, the run broke down at 4-7 s with
  // particles at 20-120 m/s; with the sliver's plane uncut its fastest particle reached 6 m/s.
  //
  // Energy is held to kBalancedEnergy: the balanced term is an external force, not the gradient
  // of the particles' potential, and a sheet spreading over a dry or micrometre-wet bed gains
  // energy under it (docs/robustness.md).
  RunOptions options;
  options.energy_growth = kBalancedEnergy;
  const auto run = run_hard_case("thin-film.json", options);
  require_invariants(run);
  CHECK(run.record.min_depth_m < 1e-5);
  // Measured 0.26 m/s (0.21 stepped to the scene's outputs); the point bed term's run 0.19 m/s.
  // Particles flung by steep planes went past 1 m/s (6 m/s uncut).
  CHECK(run.record.max_speed_m_s < 0.5);
}

TEST_CASE("Thin film under the point bed term: no energy gained", "[hard]") {
  // The point bed's force is the gradient of the particles' potential energy: the closed box
  // never gains energy beyond round-off.
  RunOptions options;
  options.adjust = [](scenario::Scenario& scene) { scene.numerics.bed_term = swe::BedTerm::point; };
  const auto run = run_hard_case("thin-film.json", options);
  require_invariants(run);
  CHECK(run.record.min_depth_m < 1e-5);  // the case reaches the depths it is about
}

TEST_CASE("Run-up and run-down on a 1:2 slope", "[hard]") {
  require_invariants(run_hard_case("runup-steep.json", {}));
}

TEST_CASE("Splitting cascade: the water's area grows a hundredfold", "[hard]") {
  // Energy is not checked: a split changes the summed depth around it, and so the potential
  // energy, by a small amount of either sign, and under the conservative scheme those changes
  // add up to a gain (measured: max (E - E0) / E0 = +0.13 over the 6 s; without splitting, at
  // cfl 0.1, E fell by 0.3 % over the first 0.35 s; docs/robustness.md). The steps of the
  // other closed cases never add energy; what splitting adds is an open item there.
  RunOptions options;
  options.check_energy = false;
  const auto run = run_hard_case("splitting-cascade.json", options);
  require_invariants(run);
  // Daughters split again: the particle count follows the area.
  CHECK(run.record.max_particles >= 100 * run.record.min_particles);
}

TEST_CASE("Supercritical jet hitting a wall", "[hard]") {
  RunOptions options;
  options.closed = false;  // water enters through the inflow line
  options.check_energy = false;
  require_invariants(run_hard_case("jet-wall.json", options));
}

TEST_CASE("Still water over rough terrain for 1e5 steps", "[hard]") {
  const auto run = run_hard_case("still-water-rough-bed.json", {});
  require_invariants(run);
  CHECK(run.steps >= 100000);
  // Water at rest stays at rest: the balanced start has no force but round-off, and the
  // eddy viscosity damps what round-off stirs (1e-6 m/s would still be invisible in a map,
  // but a growing mode passes it within seconds: docs/robustness.md).
  CHECK(run.record.max_speed_m_s < 1e-6);
}

namespace {

// The bed seen through the particles' kernels: a level surface gives no force at any
// particle, with no eddy viscosity and nothing balanced (measured under 3e-14 m/s at every
// hourly sample through the six hours, docs/method.md). 1e-9 m/s leaves room for round-off
// on other compilers; an imbalance shows up as mm/s within a minute. Every particle kept:
// nothing balanced away at the beach.
void require_still_over_rough_bed(const HardRun& run) {
  require_invariants(run);
  CHECK(run.record.min_particles == run.record.max_particles);
  CHECK(run.record.max_speed_m_s < 1e-9);
}

}  // namespace

TEST_CASE("Still water over rough terrain for 15 minutes with the default balanced bed term",
          "[hard]") {
  // The first quarter hour of the six below, fifteen times the minute an imbalance takes to
  // show as mm/s; the six hours are a long study (-DSWEMPS_LONG_TESTS=ON).
  RunOptions options;
  options.adjust = [](scenario::Scenario& scene) { scene.end_time_s = 900.0; };
  require_still_over_rough_bed(run_hard_case("still-water-rough-bed-balanced.json", options));
}

TEST_CASE("Still water over rough terrain for six hours with the default balanced bed term",
          "[hard][long]") {
  require_still_over_rough_bed(run_hard_case("still-water-rough-bed-balanced.json", {}));
}

namespace {

void require_sea_still(const HardRun& run) {
  require_invariants(run);
  // Every particle kept: nothing balanced away at the shore, where the 1:33 beach at 50 m
  // spacing leaves a last row of particles 1.3 m deep.
  CHECK(run.record.min_particles == run.record.max_particles);
  // Measured 1.9e-12 m/s over the six hours (38,269 steps); the point bed term reaches
  // 0.36 m/s within the first hour on the same scene (docs/method.md). 1e-9 m/s leaves room
  // for round-off on other compilers.
  CHECK(run.record.max_speed_m_s < 1e-9);
}

}  // namespace

TEST_CASE("A sea at rest over a shelf, slope and beach for an hour with the balanced bed term",
          "[hard]") {
  // The first of the six hours below, the hour in which the point bed term reaches 0.36 m/s;
  // the six are a long study (-DSWEMPS_LONG_TESTS=ON).
  RunOptions options;
  options.adjust = [](scenario::Scenario& scene) { scene.end_time_s = 3600.0; };
  require_sea_still(run_hard_case("still-sea-shelf-beach.json", options));
}

TEST_CASE("A sea at rest over a shelf, slope and beach for six hours with the balanced bed term",
          "[hard][long]") {
  require_sea_still(run_hard_case("still-sea-shelf-beach.json", {}));
}
