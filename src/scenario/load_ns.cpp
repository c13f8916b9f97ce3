// The Navier-Stokes parts of a scene file: "model", "dimension" and the "ns" block (tank,
// kernel, Poisson solve, collisions), and the checks a model ns scene must pass
// (check_ns_scene). The rest of the scene is load.cpp's; the strict JSON reading is
// json_reading.hpp's.

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/kernels/any_kernel.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

// ---------------------------------------------------------------------------------------------
// Navier-Stokes

Names kernel_names() {
  const auto names = kernels::kernel_type_names();
  return Names(names.begin(), names.end());
}

// `k` holds the scheme's kernel: what the scene leaves out.
ns::KernelChoice read_kernel(const json& v, const std::string& path, ns::KernelChoice k) {
  const Object o(v, path, {"type", "support", "kappa", "theta"},
                 "an object with a kernel \"type\" and optionally \"support\", \"kappa\" and "
                 "\"theta\"");
  const std::string_view name =
      choice(o, "type", kernel_names(), kernels::kernel_type_name(k.spec.type));
  k.spec.type = *kernels::kernel_type_from_name(name);
  // Within one spacing a lattice particle has no neighbour at all; beyond eight a 3D support
  // holds thousands, and the run would crawl for no gain in accuracy.
  k.support_spacings = in_range(o, "support", 1.0, true, 8.0, false,
                                "the cut-off distance in particle spacings", k.support_spacings);
  // kappa shapes both hyperbolic kernels and theta only the MPS one; elsewhere a value would
  // be silently ignored, so it is refused.
  const bool hyperbolic = k.spec.type == kernels::KernelType::hyperbolic_mps ||
                          k.spec.type == kernels::KernelType::hyperbolic_sph;
  if (o.find("kappa") != nullptr) {
    if (!hyperbolic) {
      throw ScenarioError(o.path("kappa"), "a \"kappa\" for the " + literal(name) + " kernel",
                          "no \"kappa\" here (it shapes the \"hyperbolic\" and "
                          "\"hyperbolic-sph\" kernels)");
    }
    k.spec.kappa = positive(o, "kappa", "the steepness of the hyperbolic bell");
  }
  if (o.find("theta") != nullptr) {
    if (k.spec.type != kernels::KernelType::hyperbolic_mps) {
      throw ScenarioError(o.path("theta"), "a \"theta\" for the " + literal(name) + " kernel",
                          "no \"theta\" here (it is the \"hyperbolic\" kernel's w(0))");
    }
    k.spec.theta = positive(o, "theta", "the hyperbolic kernel's value at r = 0");
  }
  return k;
}

// `s` holds the scheme's solver settings: what the scene leaves out.
ns::PoissonSettings read_solver(const json* v, const std::string& path, ns::PoissonSettings s) {
  const Object o(v ? *v : empty_object(), path,
                 {"preconditioner", "tolerance", "max_iterations", "setup_solves"}, "an object");
  const std::string_view preconditioner =
      choice(o, "preconditioner", {"incomplete-cholesky", "diagonal", "multigrid"},
             ns::preconditioner_name(s.preconditioner));
  s.preconditioner = *ns::preconditioner_from_name(preconditioner);  // choice() checked it
  s.relative_tolerance =
      in_range(o, "tolerance", 0.0, true, 1.0, true,
               "the relative residual |b - A p| / |b| the solve stops at", s.relative_tolerance);
  s.max_iterations = whole_number(o, "max_iterations", 1, 1000000,
                                  "conjugate-gradient iterations per solve", s.max_iterations);
  s.multigrid_setup_solves =
      whole_number(o, "setup_solves", 1, 1000000, "solves that one multigrid setup serves",
                   s.multigrid_setup_solves);
  return s;
}

std::optional<ns::Collision> read_collision(const json* v, const std::string& path) {
  if (v == nullptr) return ns::Collision{};
  if (v->is_boolean()) {
    return v->get<bool>() ? std::optional<ns::Collision>(ns::Collision{}) : std::nullopt;
  }
  const Object o(*v, path, {"distance", "restitution"},
                 "false (no collisions), true (the defaults) or an object with \"distance\" and "
                 "\"restitution\"");
  ns::Collision c;
  c.distance_spacings = in_range(o, "distance", 0.0, true, 1.0, true,
                                 "the closest approach in particle spacings", c.distance_spacings);
  c.restitution = in_range(o, "restitution", 0.0, false, 1.0, false,
                           "the share of the approach speed kept", c.restitution);
  return c;
}

// A length that must be a whole number of lattice spacings (to 1e-6 of one, as the tank's
// lattice takes it).
bool whole_spacings(double length, double spacing) {
  const double n = length / spacing;
  return n >= 1.0 - 1e-6 && std::abs(n - std::round(n)) <= 1e-6;
}

std::optional<NsSpec> read_ns(const json* v, double gravity, int dimensions) {
  if (v == nullptr) return std::nullopt;
  const Object o(*v, "/ns",
                 {"scheme", "spacing", "tank_height", "density", "viscosity", "courant",
                  "max_time_step", "pressure_kernel", "velocity_kernel", "free_surface_beta",
                  "free_surface_asymmetry", "source", "source_gamma", "pressure_gradient",
                  "gradient_weights", "repulsion_distance", "boundary_pressure", "solver",
                  "collision"},
                 "an object with at least the particle \"spacing\"");
  NsSpec spec;
  ns::Settings& s = spec.settings;
  // The scheme sets every numerical default; the keys below override them one by one.
  const std::string_view scheme =
      choice(o, "scheme", {"well-balanced", "standard", "least-squares"}, "well-balanced");
  s = ns::scheme_settings(scheme == "standard"        ? ns::Scheme::standard
                          : scheme == "least-squares" ? ns::Scheme::least_squares
                                                      : ns::Scheme::well_balanced,
                          dimensions);
  s.gravity_m_s2 = gravity;
  s.spacing_m = positive(o, "spacing", kMetres);
  if (o.find("tank_height") != nullptr) {
    const double height = positive(o, "tank_height", kMetres);
    if (!whole_spacings(height, s.spacing_m)) {
      throw ScenarioError(o.path("tank_height"),
                          describe(*o.find("tank_height")) + ", which is " +
                              fmt(height / s.spacing_m) + " spacings of " + fmt(s.spacing_m) + " m",
                          "a whole number of spacings (metres; the walls stand on the lattice)");
    }
    spec.tank_height_m = height;
  }
  s.density_kg_m3 = positive(o, "density", "kg/m^3", s.density_kg_m3);
  s.kinematic_viscosity_m2_s =
      non_negative(o, "viscosity", "m^2/s, kinematic", s.kinematic_viscosity_m2_s);
  s.courant =
      in_range(o, "courant", 0.0, true, 1.0, false, "the Courant number u dt / l_0", s.courant);
  s.max_time_step_s = positive(o, "max_time_step", kSeconds, s.max_time_step_s);
  const ns::KernelChoice scheme_kernel = s.pressure_kernel;
  if (const json* kernel = o.find("pressure_kernel")) {
    s.pressure_kernel = read_kernel(*kernel, o.path("pressure_kernel"), scheme_kernel);
  }
  // One kernel for both sides unless the scene splits them (Kakuda's choice); a velocity
  // kernel object is completed from the scheme's kernel, not from the pressure kernel.
  const json* velocity_kernel = o.find("velocity_kernel");
  s.velocity_kernel = velocity_kernel
                          ? read_kernel(*velocity_kernel, o.path("velocity_kernel"), scheme_kernel)
                          : s.pressure_kernel;
  s.free_surface_beta = in_range(o, "free_surface_beta", 0.0, true, 1.0, true,
                                 "the share of n0 below which a particle is on the free surface",
                                 s.free_surface_beta);
  const std::string_view gradient =
      choice(o, "pressure_gradient", {"minimum-pressure", "corrected", "corrected-repulsive"},
             ns::pressure_gradient_name(s.gradient));
  s.gradient = gradient == "corrected"             ? ns::PressureGradient::corrected
               : gradient == "corrected-repulsive" ? ns::PressureGradient::corrected_repulsive
                                                   : ns::PressureGradient::minimum_pressure;
  if (gradient == "corrected-repulsive") {
    s.repulsion_distance_spacings = in_range(o, "repulsion_distance", 0.0, true, 8.0, false,
                                             "the distance, in spacings, under which pairs repel",
                                             s.repulsion_distance_spacings);
  } else if (o.find("repulsion_distance") != nullptr) {
    throw ScenarioError(o.path("repulsion_distance"),
                        "a \"repulsion_distance\" without the \"corrected-repulsive\" gradient",
                        "no \"repulsion_distance\" here (it goes with \"pressure_gradient\": "
                        "\"corrected-repulsive\")");
  }
  const std::string_view source =
      choice(o, "source", {"number-density", "mixed"},
             s.source == ns::SourceTerm::mixed ? "mixed" : "number-density");
  s.source = source == "mixed" ? ns::SourceTerm::mixed : ns::SourceTerm::number_density;
  if (source == "mixed") {
    s.source_gamma = in_range(o, "source_gamma", 0.0, false, 1.0, false,
                              "the share of the compression relaxed per step", s.source_gamma);
  } else if (o.find("source_gamma") != nullptr) {
    throw ScenarioError(o.path("source_gamma"),
                        "a \"source_gamma\" with the \"number-density\" source",
                        "no \"source_gamma\" here (it goes with \"source\": \"mixed\")");
  }
  // The surface asymmetry test and extrapolated walls lean on the corrected gradient's
  // balance at the surface and beside walls; with the standard gradient the water breaks
  // down within a second. The asymmetry test also needs the mixed source: it keeps particles
  // with a number-density deficit in the Poisson equation, where the number-density source
  // turns the deficit into suction (a 2D dam break breaks down at T = 0.8;
  // docs/ns-dam-break.md). So where these do not hold their defaults are off whatever the
  // scheme, and asking for them is refused.
  const bool standard_gradient = s.gradient == ns::PressureGradient::minimum_pressure;
  const bool number_density = s.source == ns::SourceTerm::number_density;
  if (standard_gradient) s.boundary = ns::BoundaryPressure::poisson;
  if (standard_gradient || number_density) s.free_surface_asymmetry = 0.0;
  s.free_surface_asymmetry =
      in_range(o, "free_surface_asymmetry", 0.0, false, 1.0, true,
               "the neighbours' mean offset, in spacings, above which a particle under beta n0 "
               "is on the surface (0: number density alone)",
               s.free_surface_asymmetry);
  s.boundary =
      choice(o, "boundary_pressure", {"poisson", "extrapolated"},
             s.boundary == ns::BoundaryPressure::extrapolated ? "extrapolated" : "poisson") ==
              "extrapolated"
          ? ns::BoundaryPressure::extrapolated
          : ns::BoundaryPressure::poisson;
  for (const char* key : {"boundary_pressure", "free_surface_asymmetry"}) {
    const bool asks = key == std::string_view("boundary_pressure")
                          ? s.boundary == ns::BoundaryPressure::extrapolated
                          : s.free_surface_asymmetry > 0.0;
    if (asks && standard_gradient) {
      throw ScenarioError(o.path(key),
                          describe(*o.find(key)) + " with the \"minimum-pressure\" gradient",
                          "a corrected \"pressure_gradient\" alongside it");
    }
  }
  // The least-squares operators fit over the walls' extrapolated pressures and replace the
  // corrected gradient (least_squares_operators.hpp): they have neither Poisson walls nor the
  // minimum-pressure gradient.
  if (s.operators == ns::Operators::least_squares) {
    for (const char* key : {"pressure_gradient", "boundary_pressure"}) {
      const bool refused = key == std::string_view("pressure_gradient")
                               ? standard_gradient
                               : s.boundary == ns::BoundaryPressure::poisson;
      if (refused) {
        throw ScenarioError(o.path(key),
                            describe(*o.find(key)) + " with the \"least-squares\" scheme",
                            key == std::string_view("pressure_gradient")
                                ? "\"corrected\" or \"corrected-repulsive\""
                                : "\"extrapolated\" (or no key)");
      }
    }
  }
  // The gradient's pair weights belong to the corrected MPS gradient: the standard gradient
  // and the least-squares fits have their own, so there the default is the MPS weights and
  // asking for the kernel's slope is refused.
  const bool own_gradient = standard_gradient || s.operators == ns::Operators::least_squares;
  if (own_gradient) s.gradient_weights = ns::GradientWeights::mps;
  s.gradient_weights = *ns::gradient_weights_from_name(  // choice() checked the name
      choice(o, "gradient_weights", {"mps", "kernel-slope"},
             ns::gradient_weights_name(s.gradient_weights)));
  if (own_gradient && s.gradient_weights == ns::GradientWeights::kernel_slope) {
    throw ScenarioError(o.path("gradient_weights"),
                        describe(*o.find("gradient_weights")) +
                            (standard_gradient ? " with the \"minimum-pressure\" gradient"
                                               : " with the \"least-squares\" scheme"),
                        "\"mps\" (or no key): the kernel's slope weighs the corrected MPS "
                        "gradient only");
  }
  if (s.free_surface_asymmetry > 0.0 && number_density) {
    throw ScenarioError(
        o.path("free_surface_asymmetry"),
        describe(*o.find("free_surface_asymmetry")) + " with the \"number-density\" source",
        "\"source\": \"mixed\" alongside it");
  }
  s.solver = read_solver(o.find("solver"), o.path("solver"), s.solver);
  s.collision = read_collision(o.find("collision"), o.path("collision"));
  return spec;
}

// Twice the deepest water, rounded up to whole spacings: room for the splash of a dam break.
}  // namespace

void default_tank_height(Scenario& s) {
  if (!s.ns || s.ns->tank_height_m) return;
  double deepest = 0.0;
  for (const WaterBody& w : s.water) {
    if (const auto* uniform = std::get_if<UniformDepth>(&w.depth)) {
      deepest = std::max(deepest, uniform->depth_m);
    }
  }
  if (!(deepest > 0.0)) return;
  const double l0 = s.ns->settings.spacing_m;
  // The slack keeps a product such as 2 x 0.2 / 0.01 = 40.000000000000007 at 40 spacings.
  s.ns->tank_height_m = std::ceil(2.0 * deepest / l0 - 1e-9) * l0;
}

namespace {

std::string unsupported(const std::string& what) {
  return what + " is not supported with model ns";
}

// The tank is a box on the lattice: water boxes, each an axis-aligned rectangle of uniform
// depth standing on the floor, at rest.
void check_ns_water(const Scenario& s, double tank_height) {
  for (std::size_t i = 0; i < s.water.size(); ++i) {
    const WaterBody& w = s.water[i];
    const std::string path = element_path("/water", i);
    if (std::holds_alternative<LevelSurface>(w.depth)) {
      throw ScenarioError(member_path(path, "fill"), "water filled to a level",
                          "water given by \"depth\" (" + unsupported("a level fill") + ")");
    }
    if (std::holds_alternative<DepthRaster>(w.depth)) {
      throw ScenarioError(member_path(path, "depth_raster"), "water depth from a raster",
                          "water given by \"depth\" (" + unsupported("a depth raster") + ")");
    }
    // A rectangle is stored as its four corners; a polygon that is one passes too.
    const Rectangle bb = bounding_box(w.polygon);
    const bool rectangle =
        w.polygon.size() == 4 &&
        std::all_of(w.polygon.begin(), w.polygon.end(), [&](const Point& p) {
          return (p[0] == bb.x_min || p[0] == bb.x_max) && (p[1] == bb.y_min || p[1] == bb.y_max);
        });
    if (!rectangle) {
      throw ScenarioError(path,
                          "a polygon of " + std::to_string(w.polygon.size()) +
                              " vertices that is not an axis-aligned rectangle",
                          "a \"rectangle\" (" + unsupported("any other shape") +
                              ": the water starts as boxes in the tank)");
    }
    if (w.velocity_m_s[0] != 0.0 || w.velocity_m_s[1] != 0.0) {
      throw ScenarioError(
          member_path(path, "velocity"),
          "a starting velocity [" + fmt(w.velocity_m_s[0]) + ", " + fmt(w.velocity_m_s[1]) + "]",
          "water at rest, [0, 0] (" + unsupported("a starting velocity") + ")");
    }
    if (w.velocity_rasters) {
      throw ScenarioError(member_path(path, "velocity"), "a starting velocity from rasters",
                          "water at rest (" + unsupported("a starting velocity") + ")");
    }
    if (std::holds_alternative<SolitaryWaveStart>(w.displacement)) {
      throw ScenarioError(member_path(path, "solitary_wave"), "a solitary wave",
                          "water at rest (" + unsupported("a starting wave") + ")");
    }
    if (std::holds_alternative<DisplacementRaster>(w.displacement)) {
      throw ScenarioError(member_path(path, "surface_displacement"), "a displaced surface",
                          "water at rest (" + unsupported("a starting wave") + ")");
    }
    const double depth = std::get<UniformDepth>(w.depth).depth_m;
    if (depth > tank_height * (1.0 + 1e-12)) {
      throw ScenarioError("/ns/tank_height",
                          fmt(tank_height) + " m, below the " + fmt(depth) + " m deep " + path,
                          "a tank at least as high as the deepest water (metres)");
    }
  }
}

// The walls stand on the lattice, so the sides the tank takes from the domain must be whole
// numbers of spacings; y only in 3D, where the tank has a width.
void check_ns_domain(const Scenario& s) {
  const double l0 = s.ns->settings.spacing_m;
  const std::string expected =
      std::string("a spacing that divides the domain's x side") +
      (s.dimension == 3 ? " and y side" : "") +
      " into whole numbers (metres; the tank's walls stand on the lattice)";
  const std::array<std::pair<const char*, double>, 2> sides{
      {{"x", s.domain.x_max - s.domain.x_min}, {"y", s.domain.y_max - s.domain.y_min}}};
  for (int axis = 0; axis < (s.dimension == 3 ? 2 : 1); ++axis) {
    const auto& [name, length] = sides[static_cast<std::size_t>(axis)];
    if (whole_spacings(length, l0)) continue;
    throw ScenarioError("/ns/spacing",
                        fmt(l0) + ", which divides the domain's " + name + " side of " +
                            fmt(length) + " m into " + fmt(length / l0) + " spacings",
                        expected);
  }
}

}  // namespace

void check_ns_scene(const Scenario& s) {
  if (!s.ns) {
    throw ScenarioError("/ns", kMissing,
                        "an \"ns\" block with at least the particle \"spacing\" (model ns runs "
                        "on it)");
  }
  if (const auto* plane = std::get_if<PlaneBedSpec>(&s.bed)) {
    if (plane->slope[0] != 0.0 || plane->slope[1] != 0.0) {
      throw ScenarioError(
          "/bed/plane/slope",
          "a sloping plane [" + fmt(plane->slope[0]) + ", " + fmt(plane->slope[1]) + "]",
          "slope [0, 0] (" + unsupported("a sloping bed") +
              ": the tank's floor "
              "is flat)");
    }
  } else if (std::holds_alternative<ProfileBedSpec>(s.bed)) {
    throw ScenarioError("/bed/profile_x", "a bed profile",
                        "no bed or a level \"plane\" (" + unsupported("a bed profile") +
                            ": the tank's floor is flat)");
  } else if (std::holds_alternative<RasterBedSpec>(s.bed)) {
    throw ScenarioError("/bed/raster", "a raster bed",
                        "no bed or a level \"plane\" (" + unsupported("a raster bed") +
                            ": the tank's floor is flat)");
  }
  if (s.fault_source) {
    throw ScenarioError(
        "/fault_source", "a fault source",
        "no \"fault_source\" (" + unsupported("a fault source") + ": the tank's floor is flat)");
  }
  if (s.output.provenance.any()) {
    throw ScenarioError("/output/provenance", "provenance output",
                        "no \"provenance\" (" + unsupported("provenance") +
                            ": its particles carry no source or age)");
  }
  if (s.output.pathlines) {
    throw ScenarioError(
        "/output/pathlines", "pathlines",
        "no \"pathlines\" (" + unsupported("pathlines") + ": they follow shallow-water particles)");
  }
  if (s.manning_n) {
    throw ScenarioError("/friction", "bed friction",
                        "no \"friction\" (" + unsupported("Manning friction") +
                            "; the water's own viscosity is ns.viscosity)");
  }
  if (s.splitting) {
    throw ScenarioError("/splitting", "particle splitting",
                        "no \"splitting\" (" + unsupported("splitting") + ")");
  }
  if (s.merging) {
    throw ScenarioError("/merging", "particle merging",
                        "no \"merging\" (" + unsupported("merging") + ")");
  }
  if (!s.inflows.empty()) {
    throw ScenarioError("/inflow", std::to_string(s.inflows.size()) + " inflow lines",
                        "no \"inflow\" (" + unsupported("inflow") + ")");
  }
  if (!s.outflows.empty()) {
    throw ScenarioError("/outflow", std::to_string(s.outflows.size()) + " outflow lines",
                        "no \"outflow\" (" + unsupported("outflow") + ")");
  }
  if (!s.sea_boundaries.empty()) {
    throw ScenarioError("/sea_boundaries",
                        std::to_string(s.sea_boundaries.size()) + " sea boundaries",
                        "no \"sea_boundaries\" (" + unsupported("sea boundaries") + ")");
  }
  if (s.water.empty()) {
    throw ScenarioError("/water", "an empty array",
                        "at least one water body (model ns starts from water in the tank)");
  }
  // Every body has a uniform depth here or fails first, so the default height exists then.
  check_ns_water(s, s.ns->tank_height_m.value_or(std::numeric_limits<double>::infinity()));
  check_ns_domain(s);
}

// "model", "dimension" and the "ns" block. The dimension comes first: the scheme's defaults
// depend on it (ns::scheme_settings).
void read_model(const Object& o, double gravity, Scenario& s) {
  s.model = choice(o, "model", {"swe", "ns"}, "swe") == "ns" ? Model::ns : Model::swe;
  if (o.find("dimension") != nullptr) {
    if (s.model != Model::ns && o.find("ns") == nullptr) {
      throw ScenarioError(o.path("dimension"),
                          "a \"dimension\" in a shallow-water scene without an \"ns\" block",
                          "no \"dimension\" here (it goes with \"model\": \"ns\" or an \"ns\" "
                          "block)");
    }
    const std::string expected = "2 (a vertical x-z section along x) or 3 (x, y, z)";
    const double d = number(o, "dimension", expected);
    if (d != 2.0 && d != 3.0) {
      throw ScenarioError(o.path("dimension"), describe(*o.find("dimension")), expected);
    }
    s.dimension = static_cast<int>(d);
  }
  s.ns = read_ns(o.find("ns"), gravity, s.dimension);
  if (s.model == Model::ns && !s.ns) {
    throw ScenarioError(o.path("ns"), kMissing,
                        "an \"ns\" block with at least the particle \"spacing\" (model ns runs "
                        "on it)");
  }
}

}  // namespace swemps::scenario
