// The scene keys of the Navier-Stokes mode: "model", "dimension" and the "ns" block arrive as
// ns::Settings with that module's defaults; model ns refuses what its tank cannot hold, at
// the key to blame; the tank built from a scene has the particles its lattice predicts.

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/broken_scenes.hpp"
#include "swemps/kernels/any_kernel.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

namespace {

using swemps::testing::Broken;
using swemps::testing::check_broken;
using swemps::testing::parse_text;

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using nlohmann::json;
using swemps::kernels::KernelType;
using swemps::scenario::Model;
using swemps::scenario::ScenarioError;
namespace ns = swemps::ns;

// A 0.4 m x 0.1 m tank with 0.1 m of water in its first quarter, on a 1 cm lattice.
json ns_scene() {
  return json::parse(R"({
    "end_time": 0.1,
    "model": "ns",
    "ns": {"spacing": 0.01},
    "domain": {"x_min": 0, "x_max": 0.4, "y_min": 0, "y_max": 0.1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 0.1, "y_min": 0, "y_max": 0.1}, "depth": 0.1}]
  })");
}

std::string ns_edited(const std::function<void(json&)>& edit) {
  json scene = ns_scene();
  edit(scene);
  return scene.dump(2);
}

std::vector<Broken> broken_ns_scenes() {
  return {
      {"misspelt ns key", ns_edited([](json& s) { s["ns"]["spaccing"] = 0.01; }), "/ns/spaccing",
       "did you mean \"spacing\"?"},
      {"misspelt model", ns_edited([](json& s) { s["model"] = "nss"; }), "/model",
       "expected one of \"swe\", \"ns\" (did you mean \"ns\"?)"},
      {"model ns without an ns block", ns_edited([](json& s) { s.erase("ns"); }), "/ns",
       "found nothing (key missing), expected an \"ns\" block"},
      {"ns block without a spacing", ns_edited([](json& s) { s["ns"] = json::object(); }),
       "/ns/spacing", "found nothing (key missing), expected a number > 0 (metres)"},
      {"dimension 4", ns_edited([](json& s) { s["dimension"] = 4; }), "/dimension",
       "found 4, expected 2 (a vertical x-z section along x) or 3 (x, y, z)"},
      {"dimension as a string", ns_edited([](json& s) { s["dimension"] = "3"; }), "/dimension",
       "found a string \"3\""},
      {"dimension in a plain shallow-water scene", ns_edited([](json& s) {
         s.erase("model");
         s.erase("ns");
         s["water"][0]["spacing"] = 0.01;
         s["dimension"] = 2;
       }),
       "/dimension", "it goes with \"model\": \"ns\" or an \"ns\" block"},
      {"bad kernel name", ns_edited([](json& s) {
         s["ns"]["pressure_kernel"] = {{"type", "wendland"}};
       }),
       "/ns/pressure_kernel/type",
       "expected one of \"standard\", \"sheu-quartic\", \"logarithmic\", \"hyperbolic\", "
       "\"hyperbolic-sph\", \"spiky\""},
      {"misspelt kernel name", ns_edited([](json& s) {
         s["ns"]["velocity_kernel"] = {{"type", "spikey"}};
       }),
       "/ns/velocity_kernel/type", "(did you mean \"spiky\"?)"},
      {"kernel support within one spacing", ns_edited([](json& s) {
         s["ns"]["pressure_kernel"] = {{"type", "standard"}, {"support", 1.0}};
       }),
       "/ns/pressure_kernel/support", "found 1.0, expected a number in (1, 8]"},
      {"kappa on a kernel without one", ns_edited([](json& s) {
         s["ns"]["pressure_kernel"] = {{"type", "standard"}, {"kappa", 3}};
       }),
       "/ns/pressure_kernel/kappa", "no \"kappa\" here"},
      {"theta on the SPH hyperbolic kernel", ns_edited([](json& s) {
         s["ns"]["pressure_kernel"] = {{"type", "hyperbolic-sph"}, {"theta", 2}};
       }),
       "/ns/pressure_kernel/theta", "no \"theta\" here"},
      {"zero kappa", ns_edited([](json& s) {
         s["ns"]["pressure_kernel"] = {{"type", "hyperbolic"}, {"kappa", 0}};
       }),
       "/ns/pressure_kernel/kappa", "found 0, expected a number > 0"},
      {"misspelt kernel key", ns_edited([](json& s) {
         s["ns"]["pressure_kernel"] = {{"typ", "standard"}};
       }),
       "/ns/pressure_kernel/typ", "(did you mean \"type\"?)"},
      {"beta of 1", ns_edited([](json& s) { s["ns"]["free_surface_beta"] = 1; }),
       "/ns/free_surface_beta", "found 1, expected a number in (0, 1)"},
      {"extrapolated walls with the standard gradient", ns_edited([](json& s) {
         s["ns"]["pressure_gradient"] = "minimum-pressure";
         s["ns"]["boundary_pressure"] = "extrapolated";
       }),
       "/ns/boundary_pressure", "a corrected \"pressure_gradient\" alongside it"},
      {"asymmetry test with the standard gradient", ns_edited([](json& s) {
         s["ns"]["scheme"] = "standard";
         s["ns"]["free_surface_asymmetry"] = 0.2;
       }),
       "/ns/free_surface_asymmetry", "a corrected \"pressure_gradient\" alongside it"},
      {"asymmetry test with the number-density source", ns_edited([](json& s) {
         s["ns"]["source"] = "number-density";
         s["ns"]["free_surface_asymmetry"] = 0.2;
       }),
       "/ns/free_surface_asymmetry", "\"source\": \"mixed\" alongside it"},
      {"kernel-slope weights with the standard gradient", ns_edited([](json& s) {
         s["ns"]["scheme"] = "standard";
         s["ns"]["gradient_weights"] = "kernel-slope";
       }),
       "/ns/gradient_weights", "the kernel's slope weighs the corrected MPS gradient only"},
      {"unknown gradient weights",
       ns_edited([](json& s) { s["ns"]["gradient_weights"] = "slope"; }),
       "/ns/gradient_weights", "\"kernel-slope\""},
      {"unknown gradient",
       ns_edited([](json& s) { s["ns"]["pressure_gradient"] = "least-squares"; }),
       "/ns/pressure_gradient", "\"corrected\""},
      {"repulsion distance without its gradient", ns_edited([](json& s) {
         s["ns"]["pressure_gradient"] = "corrected";
         s["ns"]["repulsion_distance"] = 0.9;
       }),
       "/ns/repulsion_distance", "it goes with \"pressure_gradient\": \"corrected-repulsive\""},
      {"courant of 0", ns_edited([](json& s) { s["ns"]["courant"] = 0; }), "/ns/courant",
       "found 0, expected a number in (0, 1]"},
      {"negative viscosity", ns_edited([](json& s) { s["ns"]["viscosity"] = -1e-6; }),
       "/ns/viscosity", "expected a number >= 0 (m^2/s, kinematic)"},
      {"zero density", ns_edited([](json& s) { s["ns"]["density"] = 0; }), "/ns/density",
       "expected a number > 0 (kg/m^3)"},
      {"zero max time step", ns_edited([](json& s) { s["ns"]["max_time_step"] = 0; }),
       "/ns/max_time_step", "expected a number > 0 (seconds)"},
      {"misspelt source", ns_edited([](json& s) { s["ns"]["source"] = "mixd"; }), "/ns/source",
       "one of \"number-density\", \"mixed\" (did you mean \"mixed\"?)"},
      {"gamma without the mixed source", ns_edited([](json& s) {
         s["ns"]["source"] = "number-density";
         s["ns"]["source_gamma"] = 0.1;
       }),
       "/ns/source_gamma", "it goes with \"source\": \"mixed\""},
      {"gamma above 1", ns_edited([](json& s) {
         s["ns"]["source"] = "mixed";
         s["ns"]["source_gamma"] = 1.5;
       }),
       "/ns/source_gamma", "found 1.5, expected a number in [0, 1]"},
      {"misspelt preconditioner", ns_edited([](json& s) {
         s["ns"]["solver"] = {{"preconditioner", "incomplete-choleski"}};
       }),
       "/ns/solver/preconditioner", "(did you mean \"incomplete-cholesky\"?)"},
      {"tolerance of 1", ns_edited([](json& s) {
         s["ns"]["solver"] = {{"tolerance", 1}};
       }),
       "/ns/solver/tolerance", "found 1, expected a number in (0, 1)"},
      {"fractional iteration cap", ns_edited([](json& s) {
         s["ns"]["solver"] = {{"max_iterations", 2.5}};
       }),
       "/ns/solver/max_iterations", "found 2.5, expected a whole number from 1 to 1000000"},
      {"collision as a word", ns_edited([](json& s) { s["ns"]["collision"] = "off"; }),
       "/ns/collision", "expected false (no collisions), true (the defaults) or an object"},
      {"collision distance of a whole spacing", ns_edited([](json& s) {
         s["ns"]["collision"] = {{"distance", 1}};
       }),
       "/ns/collision/distance", "found 1, expected a number in (0, 1)"},
      {"tank height between lattice planes",
       ns_edited([](json& s) { s["ns"]["tank_height"] = 0.155; }), "/ns/tank_height",
       "found 0.155, which is 15.5 spacings of 0.01 m, expected a whole number"},
      {"tank lower than the water", ns_edited([](json& s) { s["ns"]["tank_height"] = 0.05; }),
       "/ns/tank_height", "0.05 m, below the 0.1 m deep /water/0"},
      {"spacing not dividing the domain", ns_edited([](json& s) { s["ns"]["spacing"] = 0.03; }),
       "/ns/spacing",
       "found 0.03, which divides the domain's x side of 0.4 m into 13.3333333333 spacings, "
       "expected a spacing that divides the domain's x side and y side into whole numbers"},
      {"spacing not dividing the width in 3D", ns_edited([](json& s) {
         s["domain"]["y_max"] = 0.105;
         s["water"][0]["rectangle"]["y_max"] = 0.105;
       }),
       "/ns/spacing", "the domain's y side of 0.105 m into 10.5 spacings"},
      {"non-rectangular water", ns_edited([](json& s) {
         s["water"][0].erase("rectangle");
         s["water"][0]["polygon"] = {{0, 0}, {0.1, 0}, {0.1, 0.1}, {0.05, 0.1}};
       }),
       "/water/0",
       "found a polygon of 4 vertices that is not an axis-aligned rectangle, expected a "
       "\"rectangle\" (any other shape is not supported with model ns"},
      {"a triangle of water", ns_edited([](json& s) {
         s["water"][0].erase("rectangle");
         s["water"][0]["polygon"] = {{0, 0}, {0.1, 0}, {0.1, 0.1}};
       }),
       "/water/0", "is not supported with model ns"},
      {"water already moving", ns_edited([](json& s) {
         s["water"][0]["velocity"] = {0.5, 0};
       }),
       "/water/0/velocity", "a starting velocity is not supported with model ns"},
      {"water filled to a level", ns_edited([](json& s) {
         s["bed"] = {{"plane", json::object()}};
         s["water"][0] = {{"fill", {{"rectangle", s["water"][0]["rectangle"]}}},
                          {"surface_elevation", 0.1}};
       }),
       "/water/0/fill", "a level fill is not supported with model ns"},
      {"Manning friction", ns_edited([](json& s) {
         s["friction"] = {{"manning_n", 0.01}};
       }),
       "/friction",
       "found bed friction, expected no \"friction\" (Manning friction is not "
       "supported with model ns"},
      {"splitting", ns_edited([](json& s) { s["splitting"] = json::object(); }), "/splitting",
       "splitting is not supported with model ns"},
      {"merging", ns_edited([](json& s) { s["merging"] = json::object(); }), "/merging",
       "merging is not supported with model ns"},
      {"inflow", ns_edited([](json& s) {
         s["inflow"] = json::parse(R"([{"line": [[0.2, 0], [0.2, 0.1]], "hydrograph": [[0, 1]]}])");
       }),
       "/inflow", "inflow is not supported with model ns"},
      {"outflow", ns_edited([](json& s) {
         s["outflow"] = json::parse(R"([{"line": [[0.3, 0], [0.3, 0.1]]}])");
       }),
       "/outflow", "outflow is not supported with model ns"},
      {"sloping bed", ns_edited([](json& s) {
         s["bed"] = {{"plane", {{"slope", {0.1, 0}}}}};
       }),
       "/bed/plane/slope", "a sloping bed is not supported with model ns"},
      {"bed profile", ns_edited([](json& s) {
         s["bed"] = {{"profile_x", {{0, 0}, {0.4, 0.1}}}};
       }),
       "/bed/profile_x", "a bed profile is not supported with model ns"},
  };
}

}  // namespace

TEST_CASE("broken Navier-Stokes scenes point at the exact key", "[scenario]") {
  check_broken(broken_ns_scenes(), true);
}

TEST_CASE("a bad kernel name lists every kernel the solver knows", "[scenario]") {
  try {
    parse_text(ns_edited([](json& s) { s["ns"]["pressure_kernel"] = {{"type", "gauss"}}; }));
    FAIL("no error");
  } catch (const ScenarioError& e) {
    for (const auto name : swemps::kernels::kernel_type_names()) {
      CHECK_THAT(e.expected(), Contains("\"" + std::string(name) + "\""));
    }
  }
}

namespace {

// What a scene without "scheme" gets (docs/scenario.md).
constexpr ns::Scheme kDefaultScheme = ns::Scheme::well_balanced;

// Every numerical setting of `got` is the one in `expected` (spacing and gravity aside).
void check_numerics(const ns::Settings& got, const ns::Settings& expected) {
  CHECK(got.density_kg_m3 == expected.density_kg_m3);
  CHECK(got.kinematic_viscosity_m2_s == expected.kinematic_viscosity_m2_s);
  CHECK(got.courant == expected.courant);
  CHECK(got.max_time_step_s == expected.max_time_step_s);
  CHECK(got.pressure_kernel.spec.type == expected.pressure_kernel.spec.type);
  CHECK(got.pressure_kernel.support_spacings == expected.pressure_kernel.support_spacings);
  CHECK(got.pressure_kernel.spec.kappa == expected.pressure_kernel.spec.kappa);
  CHECK(got.pressure_kernel.spec.theta == expected.pressure_kernel.spec.theta);
  CHECK(got.velocity_kernel.spec.type == expected.velocity_kernel.spec.type);
  CHECK(got.velocity_kernel.support_spacings == expected.velocity_kernel.support_spacings);
  CHECK(got.free_surface_beta == expected.free_surface_beta);
  CHECK(got.free_surface_asymmetry == expected.free_surface_asymmetry);
  CHECK(got.gradient == expected.gradient);
  CHECK(got.gradient_weights == expected.gradient_weights);
  CHECK(got.repulsion_distance_spacings == expected.repulsion_distance_spacings);
  CHECK(got.boundary == expected.boundary);
  CHECK(got.source == expected.source);
  CHECK(got.source_gamma == expected.source_gamma);
  CHECK(got.operators == expected.operators);
  CHECK(got.solver.preconditioner == expected.solver.preconditioner);
  CHECK(got.solver.relative_tolerance == expected.solver.relative_tolerance);
  CHECK(got.solver.max_iterations == expected.solver.max_iterations);
  CHECK(got.solver.multigrid_setup_solves == expected.solver.multigrid_setup_solves);
  REQUIRE(got.collision.has_value());
  CHECK(got.collision->distance_spacings == expected.collision->distance_spacings);
  CHECK(got.collision->restitution == expected.collision->restitution);
}

}  // namespace

TEST_CASE("the ns block takes the default scheme's settings", "[scenario]") {
  const auto s = parse_text(ns_edited([](json& j) { j["gravity"] = 9.8; }));
  CHECK(s.model == Model::ns);
  CHECK(s.dimension == 3);
  REQUIRE(s.ns.has_value());
  const ns::Settings& got = s.ns->settings;
  CHECK(got.spacing_m == 0.01);
  CHECK(got.gravity_m_s2 == 9.8);  // the scene's gravity
  check_numerics(got, ns::scheme_settings(kDefaultScheme, 3));
  // Twice the deepest water, on the lattice.
  REQUIRE(s.ns->tank_height_m.has_value());
  CHECK(*s.ns->tank_height_m == Approx(0.2));
  // Water needs no spacing of its own, and the grid's cells hold two particle columns.
  CHECK(s.water[0].spacing_m == 0.01);
  REQUIRE(s.output.grid.spacing_m.has_value());
  CHECK(*s.output.grid.spacing_m == Approx(0.02));
}

TEST_CASE("the least-squares ns scheme is the well-balanced one on least-squares operators",
          "[scenario]") {
  const auto got = parse_text(ns_edited([](json& j) { j["ns"]["scheme"] = "least-squares"; }));
  // The well-balanced scheme's 3D gradient weights and kept setup are its MPS gradient's and
  // its multigrid's, which the least-squares scheme has not: its choices are the 2D ones.
  ns::Settings expected = ns::scheme_settings(ns::Scheme::well_balanced, 2);
  expected.operators = ns::Operators::least_squares;
  expected.solver.preconditioner = ns::Preconditioner::incomplete_cholesky;  // its incomplete LU
  check_numerics(got.ns->settings, expected);
  check_numerics(got.ns->settings, ns::scheme_settings(ns::Scheme::least_squares, 3));
  // The fits replace the corrected gradient and need the walls' extrapolated pressures.
  CHECK(got.ns->settings.gradient_weights == ns::GradientWeights::mps);
  for (const auto& [key, value] : {std::pair{"pressure_gradient", "minimum-pressure"},
                                   std::pair{"boundary_pressure", "poisson"},
                                   std::pair{"gradient_weights", "kernel-slope"}}) {
    CAPTURE(key);
    try {
      parse_text(ns_edited([&](json& j) {
        j["ns"]["scheme"] = "least-squares";
        j["ns"][key] = value;
      }));
      FAIL("the least-squares scheme took " << key << " = " << value);
    } catch (const ScenarioError& e) {
      CHECK(e.json_path() == std::string("/ns/") + key);
      CHECK_THAT(std::string(e.what()), Contains("least-squares"));
    }
  }
}

TEST_CASE("the ns scheme sets every numerical default, and keys override one by one",
          "[scenario]") {
  const auto standard = parse_text(ns_edited([](json& j) { j["ns"]["scheme"] = "standard"; }));
  check_numerics(standard.ns->settings, ns::scheme_settings(ns::Scheme::standard, 3));
  CHECK(standard.ns->settings.gradient == ns::PressureGradient::minimum_pressure);

  const auto balanced = parse_text(ns_edited([](json& j) { j["ns"]["scheme"] = "well-balanced"; }));
  const ns::Settings expected = ns::scheme_settings(ns::Scheme::well_balanced, 3);
  check_numerics(balanced.ns->settings, expected);
  CHECK(expected.gradient == ns::PressureGradient::corrected_repulsive);
  CHECK(expected.boundary == ns::BoundaryPressure::extrapolated);
  CHECK(expected.pressure_kernel.spec.type == KernelType::sheu_quartic);
  // In 3D the gradient on the kernel's slope (w / r^2 amplifies a lattice wave there at
  // 2.1 l0) and the multigrid's setup kept longer; in 2D the MPS weights and 5 solves.
  CHECK(expected.gradient_weights == ns::GradientWeights::kernel_slope);
  CHECK(expected.solver.multigrid_setup_solves == 20);
  const auto section = parse_text(ns_edited([](json& j) { j["dimension"] = 2; }));
  check_numerics(section.ns->settings, ns::scheme_settings(ns::Scheme::well_balanced, 2));
  CHECK(section.ns->settings.gradient_weights == ns::GradientWeights::mps);
  CHECK(section.ns->settings.solver.multigrid_setup_solves == 5);
  // An explicit key still wins over the dimension's default.
  const auto asked = parse_text(ns_edited([](json& j) { j["ns"]["gradient_weights"] = "mps"; }));
  CHECK(asked.ns->settings.gradient_weights == ns::GradientWeights::mps);

  // One key changed, the rest of the scheme kept.
  const auto courant = parse_text(ns_edited([](json& j) {
    j["ns"]["scheme"] = "well-balanced";
    j["ns"]["courant"] = 0.3;
    j["ns"]["pressure_kernel"] = {{"support", 3.1}};
  }));
  ns::Settings changed = expected;
  changed.courant = 0.3;
  changed.pressure_kernel.support_spacings = 3.1;
  changed.velocity_kernel = changed.pressure_kernel;
  check_numerics(courant.ns->settings, changed);

  // A velocity kernel object is completed from the scheme's kernel, not the pressure one.
  const auto split = parse_text(ns_edited([](json& j) {
    j["ns"]["pressure_kernel"] = {{"type", "standard"}};
    j["ns"]["velocity_kernel"] = {{"support", 3.0}};
  }));
  CHECK(split.ns->settings.pressure_kernel.spec.type == KernelType::standard);
  CHECK(split.ns->settings.velocity_kernel.spec.type ==
        ns::scheme_settings(kDefaultScheme, 3).velocity_kernel.spec.type);
  CHECK(split.ns->settings.velocity_kernel.support_spacings == 3.0);

  // The standard gradient turns off what only the corrected one can carry, without an error
  // (it is the scheme's default, not the scene's request).
  const auto minimum = parse_text(ns_edited([](json& j) {
    j["ns"]["scheme"] = "well-balanced";
    j["ns"]["pressure_gradient"] = "minimum-pressure";
  }));
  CHECK(minimum.ns->settings.gradient == ns::PressureGradient::minimum_pressure);
  CHECK(minimum.ns->settings.boundary == ns::BoundaryPressure::poisson);
  CHECK(minimum.ns->settings.free_surface_asymmetry == 0.0);
  CHECK(minimum.ns->settings.source == ns::SourceTerm::mixed);  // the rest stays

  // The number-density source turns off the asymmetry test (it breaks down with it).
  const auto plain = parse_text(ns_edited([](json& j) {
    j["ns"]["scheme"] = "well-balanced";
    j["ns"]["source"] = "number-density";
  }));
  CHECK(plain.ns->settings.free_surface_asymmetry == 0.0);
  CHECK(plain.ns->settings.boundary == ns::BoundaryPressure::extrapolated);
  CHECK(plain.ns->settings.gradient == ns::PressureGradient::corrected_repulsive);

  try {
    parse_text(ns_edited([](json& j) { j["ns"]["scheme"] = "fast"; }));
    FAIL("an unknown scheme was accepted");
  } catch (const ScenarioError& e) {
    CHECK(e.json_path() == "/ns/scheme");
    CHECK_THAT(std::string(e.what()), Contains("\"well-balanced\""));
  }
}

TEST_CASE("the default tank height is rounded up to whole spacings", "[scenario]") {
  const auto s = parse_text(ns_edited([](json& j) { j["water"][0]["depth"] = 0.083; }));
  CHECK(*s.ns->tank_height_m == Approx(0.17));  // 2 x 0.083 = 0.166, up to 17 spacings
}

TEST_CASE("every ns key arrives as given", "[scenario]") {
  const auto s = parse_text(ns_edited([](json& j) {
    j["dimension"] = 2;
    j["ns"] = json::parse(R"({
      "spacing": 0.02, "tank_height": 0.3, "density": 998, "viscosity": 1.5e-6,
      "courant": 0.1, "max_time_step": 5e-4,
      "pressure_kernel": {"type": "hyperbolic", "support": 3.1, "kappa": 4, "theta": 2},
      "velocity_kernel": {"type": "hyperbolic-sph", "support": 2.5, "kappa": 3},
      "free_surface_beta": 0.95, "source": "mixed", "source_gamma": 0.1,
      "free_surface_asymmetry": 0.25, "pressure_gradient": "corrected-repulsive",
      "gradient_weights": "kernel-slope", "repulsion_distance": 0.8,
      "boundary_pressure": "extrapolated",
      "solver": {"preconditioner": "diagonal", "tolerance": 1e-8, "max_iterations": 300,
                 "setup_solves": 7},
      "collision": {"distance": 0.4, "restitution": 0.5}
    })");
  }));
  CHECK(s.dimension == 2);
  const ns::Settings& got = s.ns->settings;
  CHECK(got.spacing_m == 0.02);
  CHECK(*s.ns->tank_height_m == 0.3);
  CHECK(got.density_kg_m3 == 998);
  CHECK(got.kinematic_viscosity_m2_s == 1.5e-6);
  CHECK(got.courant == 0.1);
  CHECK(got.max_time_step_s == 5e-4);
  CHECK(got.pressure_kernel.spec.type == KernelType::hyperbolic_mps);
  CHECK(got.pressure_kernel.support_spacings == 3.1);
  CHECK(got.pressure_kernel.spec.kappa == 4);
  CHECK(got.pressure_kernel.spec.theta == 2);
  CHECK(got.velocity_kernel.spec.type == KernelType::hyperbolic_sph);
  CHECK(got.velocity_kernel.support_spacings == 2.5);
  CHECK(got.velocity_kernel.spec.kappa == 3);
  CHECK(got.free_surface_beta == 0.95);
  CHECK(got.source == ns::SourceTerm::mixed);
  CHECK(got.source_gamma == 0.1);
  CHECK(got.free_surface_asymmetry == 0.25);
  CHECK(got.gradient == ns::PressureGradient::corrected_repulsive);
  CHECK(got.gradient_weights == ns::GradientWeights::kernel_slope);
  CHECK(got.repulsion_distance_spacings == 0.8);
  CHECK(got.boundary == ns::BoundaryPressure::extrapolated);
  CHECK(got.solver.preconditioner == ns::Preconditioner::diagonal);
  CHECK(got.solver.relative_tolerance == 1e-8);
  CHECK(got.solver.max_iterations == 300);
  CHECK(got.solver.multigrid_setup_solves == 7);
  REQUIRE(got.collision.has_value());
  CHECK(got.collision->distance_spacings == 0.4);
  CHECK(got.collision->restitution == 0.5);
}

TEST_CASE("one kernel serves both sides unless the velocity side names its own", "[scenario]") {
  const auto s = parse_text(ns_edited([](json& j) {
    j["ns"]["pressure_kernel"] = {{"type", "spiky"}, {"support", 3}};
  }));
  CHECK(s.ns->settings.velocity_kernel.spec.type == KernelType::spiky);
  CHECK(s.ns->settings.velocity_kernel.support_spacings == 3.0);
  // A velocity kernel given in part takes the defaults, not the pressure kernel's values.
  const auto t = parse_text(ns_edited([](json& j) {
    j["ns"]["pressure_kernel"] = {{"type", "spiky"}, {"support", 3}};
    j["ns"]["velocity_kernel"] = {{"type", "logarithmic"}};
  }));
  CHECK(t.ns->settings.velocity_kernel.spec.type == KernelType::logarithmic);
  CHECK(t.ns->settings.velocity_kernel.support_spacings == 2.1);
}

TEST_CASE("collisions switch off with false and keep their defaults with true", "[scenario]") {
  CHECK_FALSE(parse_text(ns_edited([](json& j) {
                j["ns"]["collision"] = false;
              })).ns->settings.collision.has_value());
  const auto on = parse_text(ns_edited([](json& j) { j["ns"]["collision"] = true; }));
  REQUIRE(on.ns->settings.collision.has_value());
  CHECK(on.ns->settings.collision->distance_spacings == ns::Collision{}.distance_spacings);
}

TEST_CASE("a 2D section ignores the scene's y", "[scenario]") {
  // 0.105 m is no whole number of spacings; only a 3D tank has a width to fill.
  const auto s = parse_text(ns_edited([](json& j) {
    j["dimension"] = 2;
    j["domain"]["y_max"] = 0.105;
  }));
  CHECK(s.dimension == 2);
}

TEST_CASE("a shallow-water scene may carry an ns block without its restrictions", "[scenario]") {
  const auto s = parse_text(ns_edited([](json& j) {
    j.erase("model");
    j["dimension"] = 2;
    j["water"][0] = json::parse(
        R"({"polygon": [[0, 0], [0.1, 0], [0.05, 0.1]], "depth": 0.1, "spacing": 0.01})");
    j["friction"] = {{"manning_n", 0.01}};
  }));
  CHECK(s.model == Model::swe);
  CHECK(s.dimension == 2);
  REQUIRE(s.ns.has_value());
  // The grid follows the shallow-water rule: half the particle spacing.
  CHECK(*s.output.grid.spacing_m == Approx(0.005));
  // Run as model ns (what compare does), the scene is refused at the first key in the way.
  auto as_ns = s;
  as_ns.model = Model::ns;
  CHECK_THROWS_WITH(swemps::scenario::check_ns_scene(as_ns),
                    Contains("/friction") && Contains("not supported with model ns"));
  auto without_block = s;
  without_block.ns.reset();
  try {
    swemps::scenario::check_ns_scene(without_block);
    FAIL("no error");
  } catch (const ScenarioError& e) {
    CHECK(e.json_path() == "/ns");
  }
}

// ---------------------------------------------------------------------------------------------
// The tank built from a scene

TEST_CASE("a 2D scene fills its tank section with the lattice's particles", "[scenario]") {
  // 10 x 6 cells of 1 cm; water 4 cells long and 3 deep; a support of 2.1 spacings needs 3
  // solid layers. Layer k: two side columns from z = -k up to the top (6 + k nodes each)
  // and the floor row between them (10 + 2 (k - 1) nodes).
  const auto s = parse_text(ns_edited([](json& j) {
    j["dimension"] = 2;
    j["domain"] = {{"x_min", 0}, {"x_max", 0.1}, {"y_min", -5}, {"y_max", 5}};
    j["water"][0] = json::parse(
        R"({"rectangle": {"x_min": 0, "x_max": 0.04, "y_min": -1, "y_max": 1}, "depth": 0.03})");
    j["ns"]["tank_height"] = 0.06;
    j["bed"] = {{"plane", {{"elevation", 1.0}}}};
  }));
  const auto tank = swemps::scenario::ns_tank<2>(s);
  CHECK(tank.solid_layers == 3);
  CHECK(tank.interior.lower[1] == 1.0);  // the floor is the level bed
  CHECK(tank.interior.upper[1] == Approx(1.06));
  const auto sim = swemps::scenario::make_ns_simulation<2>(s);
  const auto& p = sim.particles();
  CHECK(p.fluid == 4 * 3);
  CHECK(p.wall == 2 * 7 + 10);
  CHECK(p.dummy == (2 * 8 + 12) + (2 * 9 + 14));
  CHECK(p.position[1][0] == Approx(1.005));  // half a spacing above the floor
  CHECK(sim.settings().spacing_m == 0.01);
  CHECK(sim.settings().gravity_m_s2 == 9.81);
  // The scene is 2D: a 3D tank of it is a programming error.
  CHECK_THROWS_AS(swemps::scenario::make_ns_simulation<3>(s), std::invalid_argument);
}

TEST_CASE("a 3D scene fills its tank with the lattice's particles", "[scenario]") {
  // 4 x 3 cells in plan, 5 high; water 2 cells deep over the whole floor; a support of 1.5
  // spacings needs 2 solid layers around the sides and under the floor.
  const auto s = parse_text(ns_edited([](json& j) {
    j["domain"] = {{"x_min", 0}, {"x_max", 0.04}, {"y_min", 0}, {"y_max", 0.03}};
    j["water"][0] = json::parse(
        R"({"rectangle": {"x_min": 0, "x_max": 0.04, "y_min": 0, "y_max": 0.03}, "depth": 0.02})");
    j["ns"]["tank_height"] = 0.05;
    j["ns"]["pressure_kernel"] = {{"support", 1.5}};
  }));
  const auto sim = swemps::scenario::make_ns_simulation<3>(s);
  const auto& p = sim.particles();
  const int nx = 4, ny = 3, nz = 5;
  CHECK(p.fluid == static_cast<std::size_t>(nx * ny * 2));
  // Layer 1 (wall): the box grown by one node on each side and one under the floor, minus
  // the interior; both layers likewise with two.
  const int wall = (nx + 2) * (ny + 2) * (nz + 1) - nx * ny * nz;
  const int solid = (nx + 4) * (ny + 4) * (nz + 2) - nx * ny * nz;
  CHECK(p.wall == static_cast<std::size_t>(wall));
  CHECK(p.dummy == static_cast<std::size_t>(solid - wall));
  CHECK(swemps::kernels::support<3>(sim.pressure_kernel()) == Approx(0.015));
}

TEST_CASE("water that holds no lattice node is a scene error", "[scenario]") {
  const auto s = parse_text(ns_edited([](json& j) {
    j["dimension"] = 2;
    j["water"][0]["rectangle"] = {{"x_min", 0.016}, {"x_max", 0.024}, {"y_min", 0}, {"y_max", 0.1}};
  }));
  try {
    swemps::scenario::make_ns_simulation<2>(s);
    FAIL("no error");
  } catch (const ScenarioError& e) {
    CHECK(e.json_path() == "/water");
    CHECK_THAT(std::string(e.what()), Contains("no lattice node"));
  }
}
